/* compensate.h — the compensated estimate (Hey & Purgathofer 2001, §3):
 * pm_estimate_compensated for renderers, which finds the photons and then
 * does what pm_comp_weights does; the inside of it (weights, statistics) for
 * tests, benchmarks and inspection tools.
 *
 * The model (the README's section on the compensated estimate says why):
 * a photon's target area A_p is the area, projected along its direction
 * Psi_p, of the surface in the cube where a photon arriving along Psi_p
 * could have landed and would have been used, and a photon is used exactly
 * when its own spot passes the same test. A point y on polygon g passes for
 * direction Psi when
 *  - g faces Psi: solids on their front; sheets on the side facing x only;
 *  - x' = x + (1e-3 of the cube) n sees y: the segment crosses no polygon of
 *    the cube (faces of x's own solid across a convex edge excepted);
 *  - y's backward ray along Psi meets what x's does within the cube: nothing
 *    (or the front of a wall across an edge), or the same object from the
 *    same side, where only layers (within 60 degrees of parallel to g) and
 *    the backs of solids are looked for. A layer on g's plane facing it (a
 *    block resting on a rug) covers y for every direction.
 *  - The facets of one smooth patch of a mesh in the cube whose sides that
 *    count lie within 45 degrees of their mean are one sheet: they hide none
 *    of each other from x', and a backward ray leaving the sheet does not
 *    meet it again (exact for rays steeper than its slopes). A patch that
 *    bends more within the cube is peeled into several such sheets; facets
 *    that count on their fronts and those that count on their backs (the
 *    near and far side of a thin tube) are never one sheet.
 * Other choices:
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
 *  - A polygon parallel to the shading normal n uses Psi_p . n in place of
 *    Psi_p . N_g, so that for the surface holding x the factor cancels
 *    between (Psi_p . N) and A_p and grazing photons stay exact.
 *  - A_p is never less than the photon's own polygon's share of one sample
 *    cell; a photon whose A_p is (almost) nothing is skipped and counted.
 *  - Nor less than FLOOR_REL of the cube's face as x's plane sees it,
 *    (2h)^2 (Psi_p . n) FLOOR_REL: about k FLOOR_REL photons land on such
 *    an area, under one, so the estimate rests there on a photon or none,
 *    and the one (a photon grazing a facet in a crevice of a rough mesh)
 *    read 400 times the pixel. The floor bounds a photon's weight at
 *    1 / FLOOR_REL times that of one on a wall filling the cube; it
 *    darkens what x sees of less than that area, by the share missing.
 *  - Photons all at one point (cube of size 0): the cube gets a minimum
 *    half-size of HMIN_REL times the size of the photon-surface geometry. */
#ifndef PM_COMPENSATE_H
#define PM_COMPENSATE_H

#include "estimators/estimate.h"
#include "scene/polyindex.h"

#define PM_COMP_TAU_REL 1e-3   /* boundary shell width, relative to h */
#define PM_COMP_HMIN_REL 1e-6  /* minimum h, relative to the geometry's size */
#define PM_COMP_SKIP_REL 1e-9  /* A_p below this * (2h)^2 * (Psi.n): skipped */
#define PM_COMP_FLOOR_REL (1.0 / 256) /* ... else at least this * (2h)^2 * (Psi.n) */

typedef struct pm_comp_scratch pm_comp_scratch;

/* Per-thread working memory for up to k photons. */
pm_comp_scratch *pm_comp_scratch_new(int k);
void pm_comp_scratch_free(pm_comp_scratch *sc);

/* Compensated (paper §3, eq. 1-4): the smallest cube centred at x holding k
 * photons (L-infinity nearest neighbours); the photon-surface polygons
 * clipped into it; per photon the target area A_p = sum over front-facing
 * clipped polygons g of A_g (Psi_p . N_g); L = sum Phi_p / A_p (Psi_p . N)
 * f_r(x, Psi_p, wo). Arguments as in estimate.h; pi indexes the scene at
 * the map's time. */
pm_vec3 pm_estimate_compensated(const pm_polyindex *pi, const pm_photons *map,
                                pm_vec3 x, pm_vec3 n, pm_vec3 wo,
                                const pm_material *m, int k,
                                pm_comp_scratch *sc, pm_estimate_info *info);

/* The same in the consistent mode (pm-render --consistent): the cube of
 * the k nearest photons, of half-size h_k, shrunk to shrink * h_k with
 * 0 < shrink < 1 and taken as open there (pm_comp_weights_cube): only the
 * photons strictly inside count, and the target areas are those in the
 * smaller cube. The k-th photon lies on the larger cube's boundary, so every
 * photon inside the smaller one is in the set, and given h_k the others are
 * spread over the larger cube as the surfaces' photons are: on a flat,
 * evenly lit surface the estimate is unbiased for any shrink. shrink >= 1
 * (or <= 0) is pm_estimate_compensated. ns is the shading normal on n's
 * side (pm_shading_side): the BSDF and the cosine at x take it (each photon
 * weighted by pm_shading_photon_weight), while the clipping, the target
 * areas and the weights stay on the facet's n. ns equal to n: the estimate
 * on the facets alone. */
pm_vec3 pm_estimate_compensated_shrink(const pm_polyindex *pi, const pm_photons *map,
                                       pm_vec3 x, pm_vec3 n, pm_vec3 ns, pm_vec3 wo,
                                       const pm_material *m, int k, double shrink,
                                       pm_comp_scratch *sc, pm_estimate_info *info);

typedef struct pm_comp_stats {
	double h;        /* half-size of the cube used (the clipping cube) */
	int found;       /* photons found by the search */
	int shell;       /* of those, set aside on the cube's boundary */
	int front;       /* used photons arriving in front of n */
	int skipped;     /* of those, without target area (A_p ~ 0) */
	int hidden;      /* of those, failing the model's test (not on a facing
	                    polygon of the cube, unseen from x', another fate) */
	int floored;     /* of those counted, whose A_p was raised to the floor
	                    (PM_COMP_FLOOR_REL) */
	int polys;       /* polygons with area in the cube */
	int groups;      /* sheets and lone polygons they make (compensate.c, groups()) */
	int sampled;     /* of the polygons, given sample points (something can hide part of it) */
	int whole;       /* of the polygons, found hidden from x' whole by one
	                    polygon (x's own or one on their list), with no
	                    samples (pm_comp_hidden_whole) */
	int cells;       /* their sample cells: of G x G over a polygon's box, those
	                    inside it (one, its vertices' mean, where none is) */
	int cast;        /* of those, with so many that may hide them that what x'
	                    sees of them is found through a tree (pm_comp_cast_at) */
	int fcast;       /* of the sampled, whose fates were found by rays
	                    (pm_comp_fate_cast_from) */
	int shared;      /* of the polygons, small facets of a sheet whose fates
	                    went by rays and that took another facet's rays
	                    (pm_comp_share_cells) */
	int nodes;       /* index nodes taken whole as parts of one sheet
	                    (pm_comp_sheet_nodes); 0 where polygons were taken one by one */
	int closed;      /* 1 if the cube was closed (see above) */
	long shadowed;   /* sample points a photon's fate test passed over
	                    (outside a polygon's shadow; pm_comp_shadow_from) */
	long waited;     /* fronts of solids a photon's fate test asked only of
	                    the points something else met (pm_comp_fronts_wait) */
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

/* pm_comp_weights for the open cube of half-size h > 0 around x, whatever
 * the photons' distances: those strictly inside count, the others (and
 * polygons in the cube's face planes) do not. The caller must know that
 * every photon strictly inside is among the m. */
void pm_comp_weights_cube(const pm_polyindex *pi, pm_vec3 x, pm_vec3 n,
                          const pm_vec3 *pos, const pm_vec3 *dir, int m, double h,
                          pm_comp_scratch *sc, double *w, pm_comp_stats *st);

/* In a cube of 32 polygons or more, a polygon that this many others may
 * hide from x' keeps no list of them: what x' sees of it is found by
 * segments through a tree of the cube's polygons, with the same answer
 * (compensate.c, CAST_AT). 16 unless changed; values below 9 count as 9
 * (the sampling asks whether there are more than 8); INT_MAX keeps every
 * list. For tests and benchmarks, set before any estimate runs. */
extern int pm_comp_cast_at;

/* From this many polygons in a cube of two groups or more (sheets and
 * lone polygons), the fates of its polygons' points are found by rays
 * through a tree of the cube's polygons, each polygon met asked what the
 * polygon's list would have said of it, in place of the lists
 * (compensate.c, FATE_CAST_POLYS): the same model for work that grows with
 * the points, not the pairs. 64 unless changed; 0 casts in every cube of
 * several groups, INT_MAX never (lists only). For tests and benchmarks,
 * set before any estimate runs. */
extern int pm_comp_fate_cast_from;

/* 1: where a photon's backward rays from a polygon wholly seen from x' can
 * meet one other polygon only, one wholly in front of it, the area they
 * meet it from is an exact overlap of the two along the photon's
 * direction; 0 counts it by the polygon's sample points, as everywhere
 * else (and as fates by rays always do). For tests, set before any
 * estimate runs. */
extern int pm_comp_exact_overlap;

/* From this many sample points of a polygon whose fate depends on the
 * direction, each photon's test of them against a polygon B passes over the
 * points outside B's shadow along the photon's direction (a box on the
 * polygon's plane), where the test would fail: the same answer for less
 * work (compensate.c, fates_hit()). 6 unless changed; INT_MAX tests every
 * point. For tests and benchmarks, set before any estimate runs. */
extern int pm_comp_shadow_from;

/* 1: each photon's test of a polygon's sample points leaves the fronts of
 * solids met from behind (fate -1, as if the ray left the cube) to the
 * points something else met, the only ones whose fate they can change:
 * the same answer for less work (compensate.c, opens_later()). 0 tests
 * them with the rest. For tests and benchmarks, set before any estimate
 * runs. */
extern int pm_comp_fronts_wait;

/* 1: a polygon that one convex polygon hides whole from x' (x's own, where
 * the model lets that hide it, or one on its list of what may hide it),
 * with a margin of a few eps, is taken as unseen at once: no lists of what
 * its points' backward rays may meet, no samples; the same weights
 * (compensate.c, hides_all()). 0 samples it and finds every cell hidden.
 * For tests and benchmarks, set before any estimate runs. */
extern int pm_comp_hidden_whole;

/* 1: a cube that holds one sheet which x lies on and x' sees whole takes
 * the polygon index's nodes that lie wholly inside it as one piece each
 * (their facets' sum of area times normal), clipping only the facets its
 * faces cut and those near x; the same weights up to rounding
 * (compensate.c, sheet_nodes()). 0 takes every polygon one by one. For
 * tests and benchmarks, set before any estimate runs. */
extern int pm_comp_sheet_nodes;

/* 1: where fates go by rays, the facets of a sheet smaller than a sample
 * cell (one point each) whose fate depends on the direction take, by the
 * cube's cells (GRID^3 of them), the backward rays of the first such
 * facet in their cell if they face within 10 degrees of it; each keeps
 * its own point for what x' sees of it, and its own area and facing
 * (compensate.c, share_cells()). The rays
 * then follow the cube's resolution, not the mesh's; the weights change
 * by that. 0 casts each facet's own. For tests and benchmarks, set before
 * any estimate runs. */
extern int pm_comp_share_cells;

/* 1: in a cube of many polygons, a photon's polygon is looked for among
 * those whose boxes meet its cell of a grid over the cube; the same
 * weights (compensate.c, poly_grid()). 0 tests every plane of the groups
 * that may hold it. For tests and benchmarks, set before any estimate
 * runs. */
extern int pm_comp_photon_grid;

/* The statistics of the last pm_estimate_compensated call with sc. */
const pm_comp_stats *pm_comp_last(const pm_comp_scratch *sc);

#endif
