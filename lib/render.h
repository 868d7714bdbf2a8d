/* render.h — the view pass (paper §2): jittered camera paths per pixel that
 * continue through mirrors, glass and strong-glossy surfaces and end at the
 * first diffuse or soft-glossy surface with direct light (shadow rays) plus
 * a photon-map estimate; or, with PM_EST_PATH, an unbiased path tracer of the
 * same scene for reference images.
 *
 * Pixel i draws its random numbers from pm_rng_seed(seed', i) only, so the
 * image does not depend on the thread count. */
#ifndef PM_RENDER_H
#define PM_RENDER_H

#include <stdint.h>

#include "accel.h"
#include "err.h"
#include "estimate.h"
#include "image.h"
#include "light.h"
#include "photon.h"
#include "scene.h"

enum pm_estimator { PM_EST_CLASSICAL, PM_EST_COMPENSATED, PM_EST_PATH };

typedef struct pm_render_opts {
	int estimator;      /* enum pm_estimator */
	int k;              /* nearest photons per estimate */
	int spp;            /* camera samples per pixel */
	uint64_t seed;
	int max_depth;      /* longest camera path; 0 means 64 */
} pm_render_opts;

/* The channels pm_render writes, in this order; see formats/image.md. */
#define PM_RENDER_NCHAN 15
extern const char *const pm_render_chans[PM_RENDER_NCHAN];

/* Renders into img, which pm_render initializes (width and height from the
 * scene's camera). map and pi may be NULL for PM_EST_PATH; pi may be NULL for
 * PM_EST_CLASSICAL, and then the edge layer is 0. */
int pm_render(const pm_scene *s, const pm_accel *a, const pm_lights *L,
              const pm_photons *map, const pm_polyindex *pi,
              const pm_render_opts *o, pm_image *img, pm_error *err);

const char *pm_estimator_name(int e);
/* Returns the estimator for a name, or -1. */
int pm_estimator_parse(const char *name);

#endif
