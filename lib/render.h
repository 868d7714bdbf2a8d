/* render.h — the view pass (paper §2): jittered camera paths per pixel that
 * continue through mirrors, glass and strong-glossy surfaces and end at the
 * first diffuse or soft-glossy surface with direct light (shadow rays) plus
 * a photon-map estimate; or, with PM_EST_PATH, an unbiased path tracer of the
 * same scene for reference images; or, with PM_EST_PHOTONS, the photon map
 * itself as seen from the camera (paper figure 3c).
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
#include "photonfile.h"
#include "progress.h"
#include "scene.h"

enum pm_estimator { PM_EST_CLASSICAL, PM_EST_COMPENSATED, PM_EST_PATH, PM_EST_PHOTONS };

typedef struct pm_render_opts {
	int estimator;      /* enum pm_estimator */
	int k;              /* nearest photons per estimate */
	int classical_norm; /* enum pm_classical_norm, for PM_EST_CLASSICAL; 0 is
	                     * Jensen's k / (pi r^2) */
	int spp;            /* camera samples per pixel */
	uint64_t seed;
	int max_depth;      /* longest camera path; 0 means 64 */
	pm_progress_fn *progress;  /* if set, called with (rows done, rows) */
	void *progress_arg;
} pm_render_opts;

/* The channels pm_render writes, in this order; see formats/image.md. */
#define PM_RENDER_NCHAN 15
extern const char *const pm_render_chans[PM_RENDER_NCHAN];

/* Renders into img, which pm_render initializes (width and height from the
 * scene's camera). map and pi may be NULL for PM_EST_PATH; pi may be NULL for
 * PM_EST_CLASSICAL and PM_EST_PHOTONS, and then the edge layer is 0.
 *
 * PM_EST_PHOTONS splats every photon of the map that projects into the image
 * and that the camera sees (the first hit along the ray to it lies at its
 * distance) into its pixel: R, G, B and indirect.* get
 *   f_r(x_p, psi_p, w_o) * (power_p / emitted) / A_pix(x_p),
 * A_pix the pixel's footprint on the surface at the photon, so a pixel's
 * expected value is the photon-carried (indirect) radiance over the pixel;
 * count gets the number of photons splatted. Other channels are 0. No
 * random numbers are used: the image depends on the map only. */
int pm_render(const pm_scene *s, const pm_accel *a, const pm_lights *L,
              const pm_photons *map, const pm_polyindex *pi,
              const pm_render_opts *o, pm_image *img, pm_error *err);

const char *pm_estimator_name(int e);
/* Returns the estimator for a name, or -1. */
int pm_estimator_parse(const char *name);

#endif
