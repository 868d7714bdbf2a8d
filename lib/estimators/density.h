/* density.h — density control for photon maps (Suykens & Willems 2000,
 * "Density Control for Photon Maps"), as pm-build --density: a filter on a
 * built map, so the light pass is unchanged and passes still compose.
 *
 * Importance is the camera's: one ray through each pixel centre of the
 * scene's camera finds the first surfaces seen (x_j, at distance t_j) and
 * the footprint of a pixel there, a_j = t_j 2 tan(fov/2) / height. A
 * photon's target radius is r = max(C a_j, |p - x_j|) for its nearest seen
 * point x_j: no estimate of k photons needs a support smaller than C pixels,
 * and away from what the camera sees the target density falls off with
 * the distance. The map's own density there is k / (pi r_k^2), r_k the
 * distance to its k-th nearest photon; a photon is stored with probability
 * f = min(1, (r_k / r)^2), which brings the density down to k / (pi r^2)
 * where it was above. The choice is a hash of the photon's index, so it is
 * a function of the map alone. A photon not stored hands its power, in
 * equal shares, to the stored photons among its k nearest, or if there are
 * none among its 4k or 16k nearest (if none is, it is stored): the total power is unchanged but for rounding and the
 * records' power encoding (formats/photons.md: 2^-10 of each photon's
 * largest channel). Surfaces seen only through mirrors or glass get the
 * falloff of the nearest surface seen directly. */
#ifndef PM_DENSITY_H
#define PM_DENSITY_H

#include <stdint.h>

#include "base/err.h"
#include "optics/frame.h"
#include "formats/photonfile.h"

typedef struct pm_density_opts {
	int k;              /* photons per estimate (pm-render -k) */
	double pixels;      /* C: the smallest support needed, in pixel footprints */
} pm_density_opts;

/* Filters map (a built map: kd order) in place as above and rebuilds its
 * kd-tree; f is the scene posed at the map's time, whose camera gives the
 * importance. Returns 0, or -1 (out of memory, bad camera) with map
 * unchanged. */
int pm_density_control(const pm_frame *f, pm_photons *map, const pm_density_opts *o,
                       pm_error *err);

#endif
