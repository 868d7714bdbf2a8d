/* estimators.h — the estimators a view pass can use (pm-render -e), as rows
 * of one table: each row says what the estimator needs and how to call it,
 * and the renderer does nothing but dispatch through the row. Adding an
 * estimator is one row in estimators.c and one file for its estimate. */
#ifndef PM_ESTIMATORS_H
#define PM_ESTIMATORS_H

#include "scene/accel.h"
#include "scene/camera.h"
#include "base/err.h"
#include "estimators/estimate.h"
#include "optics/frame.h"
#include "formats/image.h"
#include "formats/photon.h"

/* Bits of pm_estimator.needs besides frame.h's PM_NEEDS_POLYINDEX. */
#define PM_NEEDS_MAP 2     /* a photon map (pm-build's output) */
#define PM_TAKES_NORM 4    /* reads pm_est_in.classical_norm */

/* What an estimate reads besides the point: the same for every pixel. */
typedef struct pm_est_in {
	const pm_scene *s;
	const pm_accel *a;
	const pm_photons *map;     /* NULL unless the row needs it */
	const pm_polyindex *pi;    /* NULL unless the row needs it */
	int k;                     /* nearest photons per estimate */
	int classical_norm;        /* enum pm_classical_norm */
	double shrink;             /* the support's scale in the consistent mode
	                            * (pass.h, pm_pass_shrink); 0 or 1: none */
} pm_est_in;

typedef struct pm_estimator {
	const char *name;
	const char *help;          /* one line for pm-render -h */
	int needs;                 /* PM_NEEDS_* and PM_TAKES_NORM bits */
	/* Per-thread working memory for k photons; NULL if the row needs none. */
	void *(*scratch_new)(int k);
	void (*scratch_free)(void *sc);
	/* The radiance estimate at a photon-surface point x (estimate.h's
	 * arguments: n the facet's normal, ns the shading normal, both on wo's
	 * side); NULL: the camera path goes on there, a path tracer. */
	pm_vec3 (*estimate)(const pm_est_in *in, void *sc, pm_vec3 x, pm_vec3 n,
	                    pm_vec3 ns, pm_vec3 wo, const pm_material *m, pm_estimate_info *info);
	/* If set, the whole image comes from this and not from camera paths:
	 * img is initialized to zeros; no random numbers may be used. */
	int (*image)(const pm_est_in *in, const pm_camera *cam, pm_image *img, pm_error *err);
} pm_estimator;

/* The rows, ended by one whose name is NULL. */
extern const pm_estimator pm_estimators[];

/* Returns the row of that name, or NULL. */
const pm_estimator *pm_estimator_find(const char *name);

#endif
