/* estimate.c — the classical photon-map radiance estimate (Jensen 1996,
 * "Global Illumination using Photon Maps", eq. 6): the k nearest photons in
 * a sphere of radius r around x, their flux spread over the disc pi r^2;
 * optionally with the (k-1) normalisation below. */
#include "estimators/estimate.h"

#include <math.h>
#include <string.h>

#include "optics/bsdf.h"

/* Why (k-1). Where the photons land on a flat surface as a homogeneous
 * Poisson process of density lambda (evenly lit, flat), the disc out to the
 * k-th nearest photon, A = pi r_k^2, has lambda A ~ Gamma(k, 1), and for
 * k >= 2 E[1 / (lambda A)] = 1 / (k-1). Hence
 *   E[(k-1) / (pi r_k^2)] = lambda exactly, while
 *   E[k / (pi r_k^2)]     = lambda k / (k-1):
 * Jensen's form reads bright by 1/(k-1) (11% at k = 10, 2% at k = 50, 0.5%
 * at k = 200). The k-th photon lies on the sphere: it sets r but is no
 * sample of the disc's inside, which holds k-1 photons.
 *
 * Two ways give the flux sum that count: leave the k-th photon out, or scale
 * the sum of all k by (k-1)/k. When the photons' fluxes and directions do
 * not depend on where they landed (the case in which the Poisson argument
 * holds) both have expectation lambda E[f_r Phi]: given r_k, the k-1 inner
 * photons are uniform in the disc, and the k-th photon's f_r Phi is a draw
 * from the same distribution as theirs. We scale: it keeps the k-th photon's
 * flux in the mean (slightly less variance than dropping it), and needs no
 * choice of which photon is "the k-th", which the unordered neighbour list
 * does not give and which ties at distance r would make arbitrary. With
 * fewer than k photons in the whole map got replaces k (one photon: 0). */
static double
norm_factor(int norm, int got)
{
	return norm == PM_NORM_K1 ? (double)(got - 1) / got : 1.0;
}

pm_vec3
pm_estimate_classical_norm(const pm_photons *map, pm_vec3 x, pm_vec3 n, pm_vec3 wo,
                           const pm_material *m, int k, int norm, pm_nn *nn,
                           pm_estimate_info *info)
{
	return pm_estimate_classical_shrink(map, x, n, n, wo, m, k, norm, 1, nn, info);
}

/* The shrunk disc (shrink < 1) leaves the k-th photon outside: what it holds
 * is the k-1 inner photons' share, and the (k-1) argument above makes it
 * unbiased on a flat, evenly lit surface with no normalisation factor. */
pm_vec3
pm_estimate_classical_shrink(const pm_photons *map, pm_vec3 x, pm_vec3 n, pm_vec3 ns, pm_vec3 wo,
                             const pm_material *m, int k, int norm, double shrink,
                             pm_nn *nn, pm_estimate_info *info)
{
	float q[3] = {x.x, x.y, x.z}, r2 = 0;
	pm_vec3 sum = pm_v3(0, 0, 0);
	int got;

	info->size = info->disc = 0;
	info->nphotons = 0;
	if (map->h.count == 0 || map->h.emitted == 0 || k <= 0)
		return sum;
	got = pm_kd_knn(map->p, map->h.count, q, k, PM_L2, INFINITY, nn, &r2);
	info->nphotons = got;
	info->size = info->disc = sqrtf(r2);
	if (got == 0 || !(r2 > 0))
		return sum;
	if (shrink > 0 && shrink < 1) {
		r2 = (float)((double)r2 * shrink * shrink);
		info->size = info->disc = sqrtf(r2);
		if (!(r2 > 0))
			return sum;
	}
	int shading = ns.x != n.x || ns.y != n.y || ns.z != n.z;
	for (int i = 0; i < got; i++) {
		const pm_photon *p = &map->p[nn[i].idx];
		if (shrink > 0 && shrink < 1 && !(nn[i].d < r2))
			continue;
		pm_vec3 psi = pm_photon_dir(p);
		/* Photons arriving from behind the surface carry no light to this side. */
		if (pm_dot(psi, n) <= 0)
			continue;
		pm_vec3 f = pm_bsdf_eval(m, ns, psi, wo);
		if (shading)
			f = pm_scale(f, pm_shading_photon_weight(n, ns, psi));
		sum = pm_add(sum, pm_mul(f, pm_photon_power(p)));
	}
	return pm_scale(sum, (float)((shrink > 0 && shrink < 1 ? 1.0 : norm_factor(norm, got)) /
	                             ((double)map->h.emitted * PM_PI * r2)));
}

pm_vec3
pm_estimate_classical(const pm_photons *map, pm_vec3 x, pm_vec3 n, pm_vec3 wo,
                      const pm_material *m, int k, pm_nn *nn, pm_estimate_info *info)
{
	return pm_estimate_classical_norm(map, x, n, wo, m, k, PM_NORM_K, nn, info);
}

const char *
pm_classical_norm_name(int norm)
{
	return norm == PM_NORM_K1 ? "k-1" : norm == PM_NORM_K ? "k" : "?";
}

int
pm_classical_norm_parse(const char *name)
{
	if (strcmp(name, "k") == 0)
		return PM_NORM_K;
	if (strcmp(name, "k-1") == 0)
		return PM_NORM_K1;
	return -1;
}
