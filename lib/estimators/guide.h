/* guide.h — importance sampling by the photon map (Jensen 1995, "Importance
 * Driven Path Tracing using the Photon Map", EGWR): the incoming directions
 * of the photons nearest x, binned by power into a hemisphere histogram
 * around n whose cells are equal in solid angle, give a density over
 * directions that follows where x's indirect light comes from.
 *
 * Callers mix it with BSDF sampling (pm_guide_mix, one to one unless they
 * set share): a one-sample mixture whose weight
 * f cos / ((1 - share) p_bsdf + share p_guide) is exact whatever
 * the histogram holds and wherever f cos > 0, so the expected value is that
 * of BSDF sampling and only the variance changes. */
#ifndef PM_GUIDE_H
#define PM_GUIDE_H

#include "optics/bsdf.h"
#include "formats/photonfile.h"
#include "base/rng.h"

#define PM_GUIDE_THETA 8    /* cells in cos(theta): equal solid angle */
#define PM_GUIDE_PHI 16     /* cells in phi */
#define PM_GUIDE_CELLS (PM_GUIDE_THETA * PM_GUIDE_PHI)
#define PM_GUIDE_K 64       /* photons read */

typedef struct pm_guide {
	pm_vec3 n, t, b;                 /* the hemisphere's frame */
	float cdf[PM_GUIDE_CELLS + 1];   /* cumulative power over the cells */
	int empty;                       /* no photon arrives in front of n */
	float share;                     /* of the directions drawn from the
	                                  * histogram, the rest from the BSDF */
} pm_guide;

/* Builds the histogram at x, n (unit) from the PM_GUIDE_K photons of map
 * nearest x (a built photon map); share is set to 1/2. */
void pm_guide_build(pm_guide *gd, const pm_photons *map, pm_vec3 x, pm_vec3 n);

/* Solid-angle density of w under the histogram (0 below n or if empty). */
float pm_guide_pdf(const pm_guide *gd, pm_vec3 w);

/* Samples a direction of x's BSDF lobe: with probability 1 - share
 * from the BSDF, else from the histogram (BSDF alone if gd is NULL or
 * empty). Fills s as pm_bsdf_sample does, weight = f cos / mixture density.
 * m is diffuse or glossy; ng the geometric front normal, n on wo's side.
 * Used for gather rays (gather.h) and for view paths that go on from a
 * strong glossy surface (render.h, with a guide map).
 * Returns -1 for a direction that carries nothing. */
int pm_guide_mix(const pm_guide *gd, const pm_material *m, pm_vec3 ng, pm_vec3 n,
                 pm_vec3 wo, pm_rng *r, pm_scatter *s);

/* The density with which pm_guide_mix(gd, m, ...) draws wi: the BSDF's if
 * gd is NULL or empty, else the mixture's. n on wo's side. */
float pm_guide_mix_pdf(const pm_guide *gd, const pm_material *m, pm_vec3 n, pm_vec3 wi,
                       pm_vec3 wo);

#endif
