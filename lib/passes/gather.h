/* gather.h — final gathering (Jensen 1996, "Global Illumination using Photon
 * Maps", §3.2; the option of the paper's §2): at the first diffuse or soft
 * glossy surface x a camera path reaches, the photon estimate is not shown
 * there; gather rays sample x's BSDF and read, where they land, what that
 * surface reflects: its direct light (a shadow ray) plus the global map's
 * estimate. Light that reached x from the lights through mirrors, glass and
 * strong glossy surfaces alone (L S+ D) comes from the caustic map, shown
 * directly at x; without one, gather rays that pass such surfaces count the
 * emitters they reach instead (unbiased, but noisy where caustics are
 * sharp). Direct light at x stays with the camera path's shadow rays, so a
 * gather ray never counts an emitter it reaches directly.
 *
 * Everything drawn comes from the caller's pm_rng, so images stay a function
 * of the seed, not of the thread count. */
#ifndef PM_GATHER_H
#define PM_GATHER_H

#include "estimators/estimators.h"
#include "optics/frame.h"
#include "estimators/guide.h"
#include "estimators/irradiance.h"
#include "base/rng.h"

typedef struct pm_gather_opts {
	int rays;                    /* gather rays per camera sample, >= 1 */
	const pm_photons *caustic;   /* the caustic map (photonfile.h), or NULL */
	const pm_irradiance *irr;    /* precomputed irradiance, or NULL: the
	                              * full estimate at every gather hit */
	int guided;                  /* 1: directions drawn from the photons'
	                              * too (guide.h), 0: from the BSDF alone */
} pm_gather_opts;

/* What pm_gather reads: the same for every pixel. */
typedef struct pm_gather {
	const pm_scene *s;
	const pm_accel *a;
	const pm_lights *L;
	const pm_estimator *est;    /* a row with an estimate */
	pm_est_in global, caustic;  /* the estimator's inputs with either map */
	const pm_gather_opts *o;
} pm_gather;

/* Fills g from the frame, the estimator row and its inputs for the global
 * map (in->map), and o, which must outlive g. */
void pm_gather_init(pm_gather *g, const pm_frame *f, const pm_estimator *est,
                    const pm_est_in *in, const pm_gather_opts *o);

/* The radiance x reflects toward wo that did not come straight from an
 * emitter: the caustic estimate plus the mean of o->rays gather rays.
 * x, ng (the unit geometric front normal), n (the facet's normal on wo's
 * side), ns (the shading normal there, pm_shading_side: for the BSDF, the
 * gather rays and the estimate's cosine), m as in render.c; sc is the estimator's scratch for this thread. info gets the
 * caustic estimate's size and photon count (0 without a caustic map). */
pm_vec3 pm_gather_radiance(const pm_gather *g, void *sc, pm_rng *r, pm_vec3 x, pm_vec3 ng,
                           pm_vec3 n, pm_vec3 ns, pm_vec3 wo, const pm_material *m,
                           pm_estimate_info *info);

#endif
