/* estimate.h — the classical radiance estimate from a photon map at a
 * diffuse or soft glossy point x (Jensen 1996), and what every estimate
 * shares: its arguments and pm_estimate_info. The compensated estimate (Hey &
 * Purgathofer 2001, §3) is in compensate.h.
 *
 * Common arguments: map is a built photon map (kd order); x the point; n the
 * unit shading normal on the viewer's side; wo the unit direction toward the
 * viewer (the paper's Psi_i); m the material at x; k the number of nearest
 * photons. Photon flux is power / map->h.emitted. Results are RGB radiance,
 * finite and >= 0 always. The estimates are thread-safe given a scratch per
 * thread. */
#ifndef PM_ESTIMATE_H
#define PM_ESTIMATE_H

#include "formats/kdtree.h"
#include "formats/photonfile.h"
#include "scene/scene.h"
#include "base/vec.h"

typedef struct pm_estimate_info {
	float size;         /* sphere radius (classical) or cube half-size (compensated) */
	float disc;         /* the radius of a disc of the support's cross-section:
	                       size (classical), 2 size / sqrt(pi) (compensated) */
	int nphotons;       /* photons found */
} pm_estimate_info;

/* Normalisation of the classical estimate (see pm_estimate_classical_norm). */
enum pm_classical_norm {
	PM_NORM_K,          /* Jensen's: the k photons' flux over pi r^2 */
	PM_NORM_K1,         /* the same times (k-1)/k: unbiased for a flat, uniform density */
};

/* Classical: the k nearest in a sphere (L2) of radius r; L = sum over photons
 * arriving in front of n of f_r * flux / (pi r^2). nn holds >= k entries.
 * This is pm_estimate_classical_norm with PM_NORM_K. */
pm_vec3 pm_estimate_classical(const pm_photons *map, pm_vec3 x, pm_vec3 n,
                              pm_vec3 wo, const pm_material *m, int k,
                              pm_nn *nn, pm_estimate_info *info);

/* The classical estimate with a choice of normalisation (enum
 * pm_classical_norm). With PM_NORM_K1 the sum is scaled by (got-1)/got, got
 * the photons found (k unless the map holds fewer), so one photon gives 0. */
pm_vec3 pm_estimate_classical_norm(const pm_photons *map, pm_vec3 x, pm_vec3 n,
                                   pm_vec3 wo, const pm_material *m, int k,
                                   int norm, pm_nn *nn, pm_estimate_info *info);

/* The consistent mode (pm-render --consistent): with 0 < shrink < 1 the
 * disc of the k nearest photons, radius r, shrunk to shrink * r; the photons
 * strictly inside it over pi (shrink r)^2, norm unused. shrink >= 1 (or
 * <= 0) is pm_estimate_classical_norm. ns is the shading normal on n's side
 * (pm_shading_side): the BSDF and the cosine at x take it, each photon
 * weighted by pm_shading_photon_weight; which photons count (in front of the
 * facet) stays n's. ns equal to n is the estimate above. */
pm_vec3 pm_estimate_classical_shrink(const pm_photons *map, pm_vec3 x, pm_vec3 n,
                                     pm_vec3 ns, pm_vec3 wo, const pm_material *m, int k,
                                     int norm, double shrink, pm_nn *nn,
                                     pm_estimate_info *info);

const char *pm_classical_norm_name(int norm);
/* Returns the normalisation for a name ("k" or "k-1"), or -1. */
int pm_classical_norm_parse(const char *name);

#endif
