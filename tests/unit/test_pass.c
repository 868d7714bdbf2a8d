/* test_pass.c — pass I of N (lib/base/pass.h): the documented seed formula
 * against splitmix64 written out here from Vigna's reference, times that
 * stratify [0, 1) one per stratum, distinct seeds, and "I/N" parsing. */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "check.h"
#include "base/pass.h"

/* splitmix64 as in Vigna's splitmix64.c: state += golden gamma, then mix. */
static uint64_t
splitmix64(uint64_t x)
{
	uint64_t z = x + 0x9e3779b97f4a7c15ull;
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
	return z ^ (z >> 31);
}

TEST(splitmix64_reference_value)
{
	/* The first output of splitmix64 seeded with 0 (Vigna's test value). */
	CHECK(splitmix64(0) == 0xe220a8397b1dcdafull);
}

TEST(seed_and_time_follow_the_documented_formula)
{
	for (uint32_t n = 1; n <= 64; n *= 2)
		for (uint32_t i = 1; i <= n; i++) {
			uint64_t seed, want = splitmix64(((uint64_t)n << 32) | i);
			float t;
			double u = (double)(splitmix64(want) >> 40) / 16777216.0;
			pm_pass_derive(i, n, &seed, &t);
			CHECKF(seed == want, "pass %u/%u", i, n);
			CHECKF(t == (float)((i - 1 + u) / n), "pass %u/%u: %.9g", i, n, t);
		}
}

TEST(times_stratify_the_shutter)
{
	uint32_t n = 1000;
	uint64_t seeds[1000];

	for (uint32_t i = 1; i <= n; i++) {
		float t;
		pm_pass_derive(i, n, &seeds[i - 1], &t);
		CHECKF(t >= (float)(i - 1) / n && t <= (float)i / n && t <= 1.0f, "pass %u: t=%.9g", i, t);
		for (uint32_t j = 1; j < i; j++)
			CHECKF(seeds[j - 1] != seeds[i - 1], "passes %u and %u share a seed", j, i);
	}
	/* Same index, another set: another seed. */
	{
		uint64_t a, b;
		float t;
		pm_pass_derive(1, 8, &a, &t);
		pm_pass_derive(1, 16, &b, &t);
		CHECK(a != b);
	}
}

/* The consistent mode's support scale: pass 1 is unshrunk, the area
 * (scale^2) of pass I is I^(alpha - 1), and the average of the areas over
 * passes 1..N falls toward 0 (the bias with it), as N^(alpha - 1) / alpha. */
TEST(shrink_follows_the_pass_index)
{
	CHECK(pm_pass_shrink(1, 0.5) == 1.0);
	CHECKF(fabs(pm_pass_shrink(8, 0.5) - pow(8, -0.25)) < 1e-15, "%.17g", pm_pass_shrink(8, 0.5));
	CHECKF(fabs(pm_pass_shrink(1000, 2.0 / 3) * pm_pass_shrink(1000, 2.0 / 3) - 0.1) < 1e-12,
	       "%.17g", pm_pass_shrink(1000, 2.0 / 3));
	double a = 0;
	uint32_t n = 100000;
	for (uint32_t i = 1; i <= n; i++)
		a += pm_pass_shrink(i, 2.0 / 3) * pm_pass_shrink(i, 2.0 / 3);
	a /= n;
	CHECKF(fabs(a / (pow(n, -1.0 / 3) * 1.5) - 1) < 0.01, "mean area %g", a);
}

TEST(parse)
{
	uint32_t i = 0, n = 0;
	pm_error err;
	const char *bad[] = {"3", "0/8", "9/8", "3/0", "/8", "3/", "a/8", "3/8x", "-1/8", "+3/8",
	                     " 3/8", "3/4294967296", "3//8", ""};

	CHECK(pm_pass_parse("3/8", &i, &n, &err) == 0 && i == 3 && n == 8);
	CHECK(pm_pass_parse("1/1", &i, &n, &err) == 0 && i == 1 && n == 1);
	CHECK(pm_pass_parse("4294967295/4294967295", &i, &n, &err) == 0 && i == 4294967295u);
	for (size_t k = 0; k < sizeof bad / sizeof *bad; k++)
		CHECKF(pm_pass_parse(bad[k], &i, &n, &err) == -1 && strchr(err.msg, '\'') != NULL,
		       "'%s' accepted", bad[k]);
}

int
main(void)
{
	RUN(splitmix64_reference_value);
	RUN(seed_and_time_follow_the_documented_formula);
	RUN(times_stratify_the_shutter);
	RUN(parse);
	RUN(shrink_follows_the_pass_index);
	return check_done();
}
