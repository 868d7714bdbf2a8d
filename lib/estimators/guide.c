/* guide.c — photon-map importance sampling (see guide.h). */
#include "estimators/guide.h"

#include <math.h>

#include "formats/kdtree.h"

/* Cell of direction w, or -1 below the hemisphere. */
static int
cell(const pm_guide *gd, pm_vec3 w)
{
	float c = pm_dot(w, gd->n), phi;
	int i, j;

	if (!(c > 0))
		return -1;
	phi = atan2f(pm_dot(w, gd->b), pm_dot(w, gd->t));
	if (phi < 0)
		phi += 2.0f * (float)PM_PI;
	i = (int)(c * PM_GUIDE_THETA);
	j = (int)(phi * (float)(PM_GUIDE_PHI / (2.0 * PM_PI)));
	i = i < PM_GUIDE_THETA ? i : PM_GUIDE_THETA - 1;
	j = j < PM_GUIDE_PHI ? (j >= 0 ? j : 0) : PM_GUIDE_PHI - 1;
	return i * PM_GUIDE_PHI + j;
}

void
pm_guide_build(pm_guide *gd, const pm_photons *map, pm_vec3 x, pm_vec3 n)
{
	float w[PM_GUIDE_CELLS] = {0}, q[3] = {x.x, x.y, x.z}, r2;
	pm_nn nn[PM_GUIDE_K];
	int got = 0;

	gd->n = n;
	pm_basis(n, &gd->t, &gd->b);
	if (map && map->h.count > 0)
		got = pm_kd_knn(map->p, (size_t)map->h.count, q, PM_GUIDE_K, PM_L2, INFINITY, nn, &r2);
	/* Sorted by index first: the sums below then do not depend on the
	 * order in which the search returned the neighbours. */
	for (int i = 1; i < got; i++)
		for (int j = i; j > 0 && nn[j - 1].idx > nn[j].idx; j--) {
			pm_nn t = nn[j];
			nn[j] = nn[j - 1];
			nn[j - 1] = t;
		}
	for (int i = 0; i < got; i++) {
		const pm_photon *p = &map->p[nn[i].idx];
		int c = cell(gd, pm_photon_dir(p));
		if (c >= 0)
			w[c] += pm_lum(pm_photon_power(p));
	}
	gd->cdf[0] = 0;
	for (int c = 0; c < PM_GUIDE_CELLS; c++)
		gd->cdf[c + 1] = gd->cdf[c] + w[c];
	gd->empty = !(gd->cdf[PM_GUIDE_CELLS] > 0);
	gd->share = 0.5f;
}

float
pm_guide_pdf(const pm_guide *gd, pm_vec3 w)
{
	int c;

	if (gd->empty || (c = cell(gd, w)) < 0)
		return 0;
	/* Each cell spans 1/THETA in cos(theta) and 2 pi / PHI in phi. */
	return (gd->cdf[c + 1] - gd->cdf[c]) / gd->cdf[PM_GUIDE_CELLS] *
	       (float)(PM_GUIDE_CELLS / (2.0 * PM_PI));
}

static pm_vec3
guide_sample(const pm_guide *gd, float u1, float u2, float u3)
{
	float target = u1 * gd->cdf[PM_GUIDE_CELLS], c, s, phi;
	int lo = 0, hi = PM_GUIDE_CELLS - 1;

	/* The first cell whose upper bound exceeds target (empty cells never). */
	while (lo < hi) {
		int mid = (lo + hi) / 2;
		if (gd->cdf[mid + 1] > target)
			hi = mid;
		else
			lo = mid + 1;
	}
	c = ((float)(lo / PM_GUIDE_PHI) + u2) / PM_GUIDE_THETA;
	phi = ((float)(lo % PM_GUIDE_PHI) + u3) * (float)(2.0 * PM_PI / PM_GUIDE_PHI);
	s = sqrtf(fmaxf(0.0f, 1.0f - c * c));
	return pm_norm(pm_add(pm_add(pm_scale(gd->t, s * cosf(phi)), pm_scale(gd->b, s * sinf(phi))),
	                      pm_scale(gd->n, c)));
}

int
pm_guide_mix(const pm_guide *gd, const pm_material *m, pm_vec3 ng, pm_vec3 n,
             pm_vec3 wo, pm_rng *r, pm_scatter *s)
{
	float pick = pm_rng_f(r), ci, pdf;

	if (!gd || gd->empty)
		return pm_bsdf_sample(m, ng, wo, r, s);
	if (pick < 1.0f - gd->share) {
		if (pm_bsdf_sample(m, ng, wo, r, s) != 0)
			return -1;
	} else {
		float u1 = pm_rng_f(r), u2 = pm_rng_f(r), u3 = pm_rng_f(r);
		s->wi = guide_sample(gd, u1, u2, u3);
	}
	ci = pm_dot(s->wi, n);
	if (!(ci > 0))
		return -1;
	pdf = pm_guide_mix_pdf(gd, m, n, s->wi, wo);
	if (!(pdf > 0))
		return -1;
	s->weight = pm_scale(pm_bsdf_eval(m, n, s->wi, wo), ci / pdf);
	s->pdf = pdf;
	s->delta = 0;
	s->adjoint = 1;
	return pm_vfinite(s->weight) ? 0 : -1;
}

float
pm_guide_mix_pdf(const pm_guide *gd, const pm_material *m, pm_vec3 n, pm_vec3 wi, pm_vec3 wo)
{
	if (!gd || gd->empty)
		return pm_bsdf_pdf(m, n, wi, wo);
	return (1.0f - gd->share) * pm_bsdf_pdf(m, n, wi, wo) + gd->share * pm_guide_pdf(gd, wi);
}
