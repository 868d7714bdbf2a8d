/* estimate.c — the classical photon-map radiance estimate (Jensen 1996,
 * "Global Illumination using Photon Maps", eq. 6): the k nearest photons in
 * a sphere of radius r around x, their flux spread over the disc pi r^2. */
#include "estimate.h"

#include <math.h>

#include "bsdf.h"

pm_vec3
pm_estimate_classical(const pm_photons *map, pm_vec3 x, pm_vec3 n, pm_vec3 wo,
                      const pm_material *m, int k, pm_nn *nn, pm_estimate_info *info)
{
	float q[3] = {x.x, x.y, x.z}, r2 = 0;
	pm_vec3 sum = pm_v3(0, 0, 0);
	int got;

	info->size = 0;
	info->nphotons = 0;
	if (map->h.count == 0 || map->h.emitted == 0 || k <= 0)
		return sum;
	got = pm_kd_knn(map->p, map->h.count, q, k, PM_L2, INFINITY, nn, &r2);
	info->nphotons = got;
	info->size = sqrtf(r2);
	if (got == 0 || !(r2 > 0))
		return sum;
	for (int i = 0; i < got; i++) {
		const pm_photon *p = &map->p[nn[i].idx];
		pm_vec3 psi = pm_photon_dir(p);
		/* Photons arriving from behind the surface carry no light to this side. */
		if (pm_dot(psi, n) <= 0)
			continue;
		sum = pm_add(sum, pm_mul(pm_bsdf_eval(m, n, psi, wo), pm_photon_power(p)));
	}
	return pm_scale(sum, (float)(1.0 / ((double)map->h.emitted * PM_PI * r2)));
}
