/* render.h — the view pass (paper §2): jittered camera paths per pixel that
 * continue through mirrors, glass and strong-glossy surfaces and end at the
 * first diffuse or soft-glossy surface with direct light (shadow rays) plus
 * a photon-map estimate; or, with an estimator without one (path), an
 * unbiased path tracer of the same scene for reference images; or, with one
 * that makes whole images (photons), that image. The estimators are rows of
 * estimators.h's table.
 *
 * Pixel i draws its random numbers from pm_rng_seed(seed', i) only, so the
 * image does not depend on the thread count. */
#ifndef PM_RENDER_H
#define PM_RENDER_H

#include <stdint.h>

#include "base/err.h"
#include "estimators/estimators.h"
#include "optics/frame.h"
#include "passes/gather.h"
#include "formats/image.h"
#include "formats/photonfile.h"
#include "base/progress.h"

typedef struct pm_render_opts {
	const pm_estimator *estimator;  /* a row of pm_estimators */
	int k;              /* nearest photons per estimate */
	int classical_norm; /* enum pm_classical_norm, for rows that take it; 0 is
	                     * Jensen's k / (pi r^2) */
	double shrink;      /* the estimates' support scale, pm_pass_shrink; 0: none */
	int spp;            /* camera samples per pixel */
	int light_samples;  /* shadow rays at a path's first hit and at its end
	                     * (the photon-surface hit); 0 means 1 */
	int estimate_once;  /* 1: a pixel's first-hit photon estimate is taken
	                     * once per polygon it sees, not per camera sample */
	int past_glossy;    /* with estimate_once, past a bounce that shares
	                     * nothing (a strong glossy lobe, a textured
	                     * mirror) the estimate is taken at a pixel's camera
	                     * samples 0, N, 2N, ... only, weighted spp over
	                     * their number; 0 or 1: at every one */
	uint64_t seed;
	int max_depth;      /* longest camera path; 0 means 64 */
	const pm_gather_opts *gather;  /* if set, final gathering at the photon
	                                * surface instead of the estimate there */
	const pm_photons *guide;  /* if set, a built guide map (photonfile.h):
	                           * paths go on from strong glossy surfaces in
	                           * directions drawn half from its photons'
	                           * (guide.h), half from the BSDF */
	pm_progress_fn *progress;  /* if set, called with (rows done, rows) */
	void *progress_arg;
} pm_render_opts;

/* The channels pm_render writes, in this order; see formats/image.md. */
#define PM_RENDER_NCHAN 15
extern const char *const pm_render_chans[PM_RENDER_NCHAN];

/* Renders f into img, which pm_render initializes (width and height from
 * the scene's camera). map may be NULL, and f's polygon index absent, when
 * the estimator does not need them; without an index the edge layer is 0.
 * See photonview.h for the photons estimator's image. */
int pm_render(const pm_frame *f, const pm_photons *map, const pm_render_opts *o,
              pm_image *img, pm_error *err);

#endif
