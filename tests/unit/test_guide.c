/* test_guide.c — photon-map importance sampling (lib/estimators/guide.h): the
 * histogram's density integrates to one over the hemisphere and is what its
 * sampler draws from, and the mixture's weight f cos / p keeps the expected
 * value of BSDF sampling (for a diffuse surface, its albedo) whatever the
 * photons say. */
#include <math.h>
#include <stdlib.h>

#include "optics/bsdf.h"
#include "check.h"
#include "estimators/guide.h"
#include "formats/kdtree.h"

/* A built map of photons around the origin on the plane y = 0, arriving
 * from two directions of the upper hemisphere with different powers. */
static void
two_beams(pm_photons *m, pm_photon *p, int n)
{
	pm_vec3 up = pm_v3(0, 1, 0);
	pm_vec3 a = pm_norm(pm_v3(0.9f, 0.3f, 0.1f)), b = pm_norm(pm_v3(-0.2f, 0.8f, -0.5f));
	pm_error err;

	for (int i = 0; i < n; i++) {
		pm_vec3 pos = pm_v3(0.01f * (float)(i % 7), 0, 0.01f * (float)(i / 7));
		pm_photon_pack(&p[i], pos, i % 3 ? a : b, up, i % 3 ? pm_v3(1, 1, 1) : pm_v3(3, 3, 3));
	}
	CHECK(pm_kd_build(p, (size_t)n, &err) == 0);
	m->p = p;
	m->h.count = (uint64_t)n;
	m->h.emitted = 1;
	m->h.kdtree = 1;
}

TEST(density_integrates_to_one)
{
	pm_photon p[100];
	pm_photons m = {0};
	pm_guide gd;
	pm_rng r = pm_rng_seed(1, 2);
	double sum = 0;
	int n = 400000;

	two_beams(&m, p, 100);
	pm_guide_build(&gd, &m, pm_v3(0.03f, 0, 0.03f), pm_v3(0, 1, 0));
	CHECK(!gd.empty);
	/* Uniform over the sphere: E[p / (1 / 4 pi)] = integral of p. */
	for (int i = 0; i < n; i++) {
		float u1 = pm_rng_f(&r), u2 = pm_rng_f(&r);
		sum += pm_guide_pdf(&gd, pm_sample_sphere(u1, u2)) * 4.0 * PM_PI;
	}
	CHECKF(fabs(sum / n - 1) < 0.02, "integral %g", sum / n);
}

TEST(mixture_weight_is_unbiased)
{
	pm_photon p[100];
	pm_photons m = {0};
	pm_material mat = {.kind = PM_MAT_DIFFUSE, .kd = {0.6f, 0.3f, 0.1f}};
	pm_vec3 up = pm_v3(0, 1, 0), wo = pm_norm(pm_v3(0.3f, 1, 0.2f));
	pm_guide gd;
	pm_rng r = pm_rng_seed(3, 4);
	double sum[3] = {0, 0, 0}, sq = 0, sqb = 0, sumb = 0, sumg = 0;
	int n = 400000, guided = 0;

	two_beams(&m, p, 100);
	pm_guide_build(&gd, &m, pm_v3(0.03f, 0, 0.03f), up);
	for (int i = 0; i < n; i++) {
		pm_scatter s;
		if (pm_guide_mix(&gd, &mat, up, up, wo, &r, &s) != 0)
			continue;
		sum[0] += s.weight.x;
		sum[1] += s.weight.y;
		sum[2] += s.weight.z;
		/* The beams' directions came out of the histogram's own sampler. */
		if (pm_dot(s.wi, pm_norm(pm_v3(0.9f, 0.3f, 0.1f))) > 0.95f)
			guided++;
		/* An integrand that lives where the photons come from: light
		 * from the cells they arrived through. */
		float g = pm_guide_pdf(&gd, s.wi) > 0;
		sq += (double)(g * s.weight.x) * (g * s.weight.x);
		sumg += g * s.weight.x;
		if (pm_bsdf_sample(&mat, up, wo, &r, &s) == 0) {
			float gb = pm_guide_pdf(&gd, s.wi) > 0;
			sqb += (double)(gb * s.weight.x) * (gb * s.weight.x);
			sumb += gb * s.weight.x;
		}
	}
	for (int c = 0; c < 3; c++)
		CHECKF(fabs(sum[c] / n - pm_vget(mat.kd, c)) < 0.01 * pm_vget(mat.kd, c) + 0.002,
		       "channel %d: mean weight %g, albedo %g", c, sum[c] / n, pm_vget(mat.kd, c));
	/* A third of the samples or more head into the strong beam's cell. */
	CHECKF(guided > n / 5, "%d of %d", guided, n);
	/* For that light the mixture's second moment is far below BSDF
	 * sampling's: less variance for the same mean. */
	CHECKF(sq < 0.5 * sqb, "second moments %g (guided) vs %g (BSDF)", sq / n, sqb / n);
	CHECKF(fabs(sumg - sumb) / n < 0.01 * mat.kd.x, "means %g (guided) vs %g (BSDF)", sumg / n, sumb / n);
}

TEST(no_photons_means_bsdf_sampling)
{
	pm_photons m = {0};
	pm_guide gd;

	pm_guide_build(&gd, &m, pm_v3(0, 0, 0), pm_v3(0, 0, 1));
	CHECK(gd.empty);
	CHECK(pm_guide_pdf(&gd, pm_v3(0, 0, 1)) == 0);
	/* The directions behind n carry nothing either way. */
	pm_photon p[100];
	two_beams(&m, p, 100);
	pm_guide_build(&gd, &m, pm_v3(0.03f, 0, 0.03f), pm_v3(0, 1, 0));
	CHECK(pm_guide_pdf(&gd, pm_v3(0, -1, 0)) == 0);
}

int
main(void)
{
	RUN(density_integrates_to_one);
	RUN(mixture_weight_is_unbiased);
	RUN(no_photons_means_bsdf_sampling);
	return check_done();
}
