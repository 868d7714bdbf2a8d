/* test_bsdf.c — BSDFs: reciprocity, energy, and that sampling matches eval. */
#include <math.h>
#include <string.h>

#include "optics/bsdf.h"
#include "check.h"

static pm_material
mat(int kind, float kd, float ks, float e)
{
	pm_material m;
	memset(&m, 0, sizeof m);
	m.kind = kind;
	m.kd = pm_v3(kd, kd * 0.5f, kd * 0.25f);
	m.ks = pm_v3(ks, ks, ks);
	m.exponent = e;
	m.ior = 1.5f;
	return m;
}

static pm_vec3
rnd_hemi(pm_rng *r, pm_vec3 n)
{
	return pm_sample_cosine(n, pm_rng_f(r), pm_rng_f(r));
}

TEST(reciprocity)
{
	pm_rng r = pm_rng_seed(1, 2);
	pm_vec3 n = pm_norm(pm_v3(0.3f, 1, -0.2f));
	pm_material ms[3] = {mat(PM_MAT_DIFFUSE, 0.8f, 0, 0), mat(PM_MAT_GLOSSY, 0.3f, 0.6f, 20),
	                     mat(PM_MAT_GLOSSY, 0.1f, 0.8f, 500)};
	for (int k = 0; k < 3; k++)
		for (int i = 0; i < 2000; i++) {
			pm_vec3 a = rnd_hemi(&r, n), b = rnd_hemi(&r, n);
			pm_vec3 f1 = pm_bsdf_eval(&ms[k], n, a, b), f2 = pm_bsdf_eval(&ms[k], n, b, a);
			CHECKF(fabsf(f1.x - f2.x) <= 1e-5f * fmaxf(1, f1.x), "mat %d: %g vs %g", k, f1.x, f2.x);
		}
}

TEST(below_surface_is_zero)
{
	pm_material m = mat(PM_MAT_GLOSSY, 0.3f, 0.6f, 20);
	pm_vec3 n = pm_v3(0, 0, 1);
	pm_vec3 f = pm_bsdf_eval(&m, n, pm_v3(0, 0.6f, -0.8f), pm_v3(0, 0, 1));
	CHECK(f.x == 0 && f.y == 0 && f.z == 0);
}

/* The mean sampled weight is the directional albedo; it must match the
 * integral of f cos computed independently by uniform hemisphere sampling,
 * and stay <= 1 for kd + ks <= 1. */
TEST(sampling_matches_eval)
{
	pm_material ms[3] = {mat(PM_MAT_DIFFUSE, 0.8f, 0, 0), mat(PM_MAT_GLOSSY, 0.3f, 0.6f, 10),
	                     mat(PM_MAT_GLOSSY, 0.2f, 0.7f, 60)};
	pm_vec3 n = pm_v3(0, 0, 1);
	float cosines[3] = {0.95f, 0.6f, 0.3f};
	for (int k = 0; k < 3; k++)
		for (int c = 0; c < 3; c++) {
			pm_vec3 wo = pm_v3(sqrtf(1 - cosines[c] * cosines[c]), 0, cosines[c]);
			pm_rng r = pm_rng_seed(7, (uint64_t)(k * 10 + c));
			double is = 0, us = 0;
			int N = 400000;
			for (int i = 0; i < N; i++) {
				pm_scatter s;
				if (pm_bsdf_sample(&ms[k], n, wo, &r, &s) == 0)
					is += s.weight.x;
				pm_vec3 wi = pm_sample_sphere(pm_rng_f(&r), pm_rng_f(&r));
				wi.z = fabsf(wi.z);
				us += pm_bsdf_eval(&ms[k], n, wi, wo).x * wi.z * 2 * PM_PI;
			}
			is /= N;
			us /= N;
			CHECKF(fabs(is - us) < 0.02 * us + 2e-3, "mat %d cos %g: sampled %g, integral %g", k, cosines[c], is, us);
			CHECKF(is <= 1.0 + 1e-3, "albedo %g > 1", is);
		}
}

TEST(diffuse_albedo_exact)
{
	pm_material m = mat(PM_MAT_DIFFUSE, 0.6f, 0, 0);
	pm_rng r = pm_rng_seed(3, 3);
	for (int i = 0; i < 100; i++) {
		pm_scatter s;
		CHECK(pm_bsdf_sample(&m, pm_v3(0, 1, 0), pm_norm(pm_v3(0.2f, 1, 0.1f)), &r, &s) == 0);
		CHECKF(s.weight.x == 0.6f && s.wi.y > 0, "%g", s.weight.x);
	}
}

TEST(mirror_reflects)
{
	pm_material m = mat(PM_MAT_MIRROR, 0, 0.9f, 0);
	pm_rng r = pm_rng_seed(3, 4);
	pm_scatter s;
	pm_vec3 wo = pm_norm(pm_v3(1, 1, 0));
	CHECK(pm_bsdf_sample(&m, pm_v3(0, 1, 0), wo, &r, &s) == 0);
	CHECKF(fabsf(s.wi.x + wo.x) < 1e-6f && fabsf(s.wi.y - wo.y) < 1e-6f && s.delta, "%g %g", s.wi.x, s.wi.y);
}

/* Glass at normal incidence reflects (n-1)^2/(n+1)^2 = 4% for n = 1.5; from
 * inside beyond the critical angle it always reflects; refraction obeys
 * Snell's law. */
TEST(glass_fresnel_snell)
{
	pm_material m = mat(PM_MAT_GLASS, 0, 1, 0);
	pm_rng r = pm_rng_seed(5, 5);
	pm_vec3 ng = pm_v3(0, 0, 1);
	int refl = 0, N = 200000;
	for (int i = 0; i < N; i++) {
		pm_scatter s;
		pm_bsdf_sample(&m, ng, ng, &r, &s);
		refl += s.wi.z > 0;
	}
	CHECKF(fabs(refl / (double)N - 0.04) < 0.003, "reflected %g", refl / (double)N);
	pm_vec3 wo = pm_norm(pm_v3(0.9f, 0, -0.3f));  /* inside, grazing: TIR */
	for (int i = 0; i < 1000; i++) {
		pm_scatter s;
		pm_bsdf_sample(&m, ng, wo, &r, &s);
		CHECK(s.wi.z < 0);
	}
	wo = pm_norm(pm_v3(0.5f, 0, 1));
	for (int i = 0; i < 1000; i++) {
		pm_scatter s;
		pm_bsdf_sample(&m, ng, wo, &r, &s);
		if (s.wi.z < 0) {
			float sin_i = sqrtf(1 - wo.z * wo.z), sin_t = sqrtf(1 - s.wi.z * s.wi.z);
			CHECKF(fabsf(sin_i - 1.5f * sin_t) < 1e-5f, "%g vs %g", sin_i, 1.5f * sin_t);
			CHECK(s.wi.x < 0);
		}
	}
}

/* Refraction's weight carries radiance: (eta on wo's side / eta on wi's
 * side)^2, so a camera in glass looking out sees radiance 2.25 times
 * brighter (for 1.5) and one outside looking in 1/2.25 of it; the adjoint
 * factor turns it back into power's (photons), which has no eta^2. The
 * reflection has neither. */
TEST(glass_radiance_scaling)
{
	pm_material m = mat(PM_MAT_GLASS, 0, 0.8f, 0);
	pm_vec3 ng = pm_v3(0, 0, 1);
	struct { pm_vec3 wo; float w; } c[] = {
		{ pm_v3(0, 0, -1), 0.8f * 2.25f },                /* wo inside */
		{ pm_v3(0, 0, 1), 0.8f / 2.25f },                 /* wo outside */
		{ pm_norm(pm_v3(0.3f, 0, 1)), 0.8f / 2.25f },     /* oblique, outside */
		{ pm_norm(pm_v3(0.3f, 0, -1)), 0.8f * 2.25f },    /* oblique, inside */
	};
	for (size_t k = 0; k < sizeof c / sizeof c[0]; k++) {
		pm_scatter s;
		/* u1 = 0.99 > F: refraction */
		CHECK(pm_bsdf_sample_u(&m, ng, c[k].wo, 0.99f, 0.5f, 0.5f, &s) == 0);
		CHECK(s.wi.z * c[k].wo.z < 0);
		CHECKF(fabsf(s.weight.x - c[k].w) < 1e-5f && s.weight.x == s.weight.z,
		       "case %zu: weight %g, want %g", k, s.weight.x, c[k].w);
		CHECKF(fabsf(s.weight.x * s.adjoint - 0.8f) < 1e-6f, "case %zu: power weight %g",
		       k, s.weight.x * s.adjoint);
		/* u1 = 0.001 < F: reflection, no factor either way */
		CHECK(pm_bsdf_sample_u(&m, ng, c[k].wo, 0.001f, 0.5f, 0.5f, &s) == 0);
		CHECK(s.wi.z * c[k].wo.z > 0 && s.weight.x == 1 && s.adjoint == 1);
	}
}

int
main(void)
{
	RUN(reciprocity);
	RUN(below_surface_is_zero);
	RUN(sampling_matches_eval);
	RUN(diffuse_albedo_exact);
	RUN(mirror_reflects);
	RUN(glass_fresnel_snell);
	RUN(glass_radiance_scaling);
	return check_done();
}
