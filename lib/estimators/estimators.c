/* estimators.c — the table of estimators (see estimators.h). The adapters
 * give each estimate the row's one signature. */
#include "estimators/estimators.h"

#include <stdlib.h>
#include <string.h>

#include "estimators/compensate.h"
#include "estimators/photonview.h"

static void *
nn_new(int k)
{
	return malloc((size_t)(k > 0 ? k : 1) * sizeof(pm_nn));
}

static pm_vec3
classical(const pm_est_in *in, void *sc, pm_vec3 x, pm_vec3 n, pm_vec3 ns, pm_vec3 wo,
          const pm_material *m, pm_estimate_info *info)
{
	return pm_estimate_classical_shrink(in->map, x, n, ns, wo, m, in->k, in->classical_norm,
	                                    in->shrink, sc, info);
}

static void *
comp_new(int k)
{
	return pm_comp_scratch_new(k);
}

static void
comp_free(void *sc)
{
	pm_comp_scratch_free(sc);
}

static pm_vec3
compensated(const pm_est_in *in, void *sc, pm_vec3 x, pm_vec3 n, pm_vec3 ns, pm_vec3 wo,
            const pm_material *m, pm_estimate_info *info)
{
	return pm_estimate_compensated_shrink(in->pi, in->map, x, n, ns, wo, m, in->k, in->shrink,
	                                      sc, info);
}

/* The polygon index of classical serves the edge layer only. */
const pm_estimator pm_estimators[] = {
	{"classical", "Jensen's: the k nearest photons' flux over pi r^2",
	 PM_NEEDS_MAP | PM_NEEDS_POLYINDEX | PM_TAKES_NORM, nn_new, free, classical, NULL},
	{"compensated", "Hey & Purgathofer's: k photons in a cube over the area they landed on",
	 PM_NEEDS_MAP | PM_NEEDS_POLYINDEX, comp_new, comp_free, compensated, NULL},
	{"path", "an unbiased path tracer; needs no MAP",
	 0, NULL, NULL, NULL, NULL},
	{"photons", "MAP's photons as seen from the camera",
	 PM_NEEDS_MAP, NULL, NULL, NULL, pm_photonview_image},
	{NULL, NULL, 0, NULL, NULL, NULL, NULL},
};

const pm_estimator *
pm_estimator_find(const char *name)
{
	for (const pm_estimator *e = pm_estimators; e->name; e++)
		if (strcmp(name, e->name) == 0)
			return e;
	return NULL;
}
