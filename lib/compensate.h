/* compensate.h — the inside of the compensated estimate (Hey & Purgathofer
 * 2001, §3), for tests, benchmarks and inspection tools. Renderers call
 * pm_estimate_compensated (estimate.h), which finds the photons and then
 * does what pm_comp_weights does.
 *
 * The rules where the paper is silent (see the README's section on the
 * compensated estimate):
 *  - The cube is the smallest L-infinity cube around x holding k photons. The
 *    search may have found only some of the photons on that cube's boundary
 *    (ties), most visibly when a wall parallel to a cube face enters it:
 *    then the photons at the boundary distance (within TAU_REL of it, chained)
 *    are set aside and the cube is taken as open at that distance: its inner
 *    photons, and the polygons' area inside it, polygons lying in a face plane
 *    excluded. Every photon inside is then known to be in the set.
 *  - If the search found every photon there is (fewer than k in the map), or
 *    all of those it found are on the boundary, the cube is closed and a hair
 *    larger: every photon found counts, polygons in a face plane count.
 *  - Solid objects are one-sided: a polygon adds A_g (Psi_p . N_g) to a
 *    photon's target area only if it faces the photon. Open sheets are
 *    two-sided: A_g |Psi_p . N_g|.
 *  - A polygon parallel to the shading normal n uses Psi_p . n in place of
 *    Psi_p . N_g, so that for the surface holding x the factor cancels
 *    between (Psi_p . N) and A_p and grazing photons stay exact.
 *  - A photon arriving in front of n whose target area is (almost) nothing
 *    cannot be spread over any surface: it is skipped and counted.
 *  - Parallel layers hide each other: the part of a polygon behind a
 *    parallel polygon, seen along the photon's direction, is not target
 *    area (a picture on a wall, a rug, a box resting on a table); see
 *    overlap.h. Photons behind a polygon as seen from x (the segment from x
 *    crosses it in the cube) are left out: no light through thin walls.
 *  - Photons all at one point (cube of size 0): the cube gets a minimum
 *    half-size of HMIN_REL times the size of the photon-surface geometry. */
#ifndef PM_COMPENSATE_H
#define PM_COMPENSATE_H

#include "estimate.h"
#include "polyindex.h"

#define PM_COMP_TAU_REL 1e-3   /* boundary shell width, relative to h */
#define PM_COMP_HMIN_REL 1e-6  /* minimum h, relative to the geometry's size */
#define PM_COMP_SKIP_REL 1e-9  /* A_p below this * (2h)^2 * (Psi.n): skipped */

typedef struct pm_comp_stats {
	double h;        /* half-size of the cube used (the clipping cube) */
	int found;       /* photons found by the search */
	int shell;       /* of those, set aside on the cube's boundary */
	int front;       /* used photons arriving in front of n */
	int skipped;     /* of those, without target area (A_p ~ 0) */
	int hidden;      /* of those, behind another polygon as seen from x */
	int polys;       /* polygons with area in the cube */
	int sampled;     /* of those, given sample points (something can hide part of it) */
	int closed;      /* 1 if the cube was closed (see above) */
} pm_comp_stats;

/* The per-photon weights of eq. 3 for m photons already found around x:
 * w[i] = (Psi_i . n) / A_i for photons that contribute, 0 for the others, so
 * that L = sum_i w[i] Phi_i f_r(x, Psi_i, wo). pos and dir are the photons'
 * positions and unit incoming directions; complete says that these are all
 * the photons there are (the search asked for more than it found). sc must
 * have room for m photons (pm_comp_scratch_new(k >= m)). st may be NULL. */
void pm_comp_weights(const pm_polyindex *pi, pm_vec3 x, pm_vec3 n,
                     const pm_vec3 *pos, const pm_vec3 *dir, int m,
                     int complete, pm_comp_scratch *sc, double *w,
                     pm_comp_stats *st);

/* The statistics of the last pm_estimate_compensated call with sc. */
const pm_comp_stats *pm_comp_last(const pm_comp_scratch *sc);

#endif
