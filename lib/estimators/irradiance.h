/* irradiance.h — precomputed irradiance (Christensen 1999, "Faster Photon
 * Map Global Illumination", JGT 4(3)): the estimate at a subset of the
 * photon positions, each with its surface normal, computed once per pass,
 * so that a gather ray's lookup costs one nearest-neighbour query instead of
 * an estimate.
 *
 * Stored per unit albedo: the radiance a white Lambertian surface at the
 * point would reflect (irradiance / pi), from the chosen estimator (classical
 * or compensated); a diffuse surface of albedo kd reflects kd times it. The
 * points are kept as photon records (photon.h) in a kd-tree: position, the
 * normal as the direction, the value as the power. */
#ifndef PM_IRRADIANCE_H
#define PM_IRRADIANCE_H

#include "base/err.h"
#include "estimators/estimators.h"
#include "formats/photonfile.h"
#include "base/progress.h"

typedef struct pm_irradiance {
	pm_photons pts;      /* h.count points in kd order; h.emitted = 1 */
} pm_irradiance;

/* Computes the estimate of est (a row with an estimate; its inputs in, with
 * the global map in->map) at every every-th photon of in->map (every >= 1),
 * in parallel; the result does not depend on the thread count. A photon
 * whose surface cannot be found again (a ray back along its direction meets
 * nothing within the accel's offset) is left out. */
int pm_irradiance_build(pm_irradiance *irr, const pm_estimator *est, const pm_est_in *in,
                        int every, pm_error *err);

/* The stored value nearest x among the PM_IRR_NEAR nearest points whose
 * normal is within PM_IRR_COS of n: returns 1 and sets *L, or 0 if none is. */
#define PM_IRR_NEAR 8
#define PM_IRR_COS 0.9f
int pm_irradiance_lookup(const pm_irradiance *irr, pm_vec3 x, pm_vec3 n, pm_vec3 *L);

void pm_irradiance_free(pm_irradiance *irr);

#endif
