/* test_ldseq.c — the scrambled Sobol' pairs of lib/base/ldseq.h: every prefix of
 * 2^m points is a (0, m, 2)-net (each elementary box of area 2^-m holds
 * exactly one point) for any seed and pair, which pseudo-random points are
 * not; different seeds and pairs give different points; a pass's block
 * beyond 2^32 is scrambled anew. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "base/ldseq.h"

/* 1 if points [0, 2^m) of (seed, pair) put one point in every box of
 * 2^a x 2^(m-a) cells, for every a. */
static int
is_net(uint64_t seed, uint32_t pair, uint64_t start, int m)
{
	static unsigned char hit[1 << 12];
	uint32_t n = 1u << m;

	for (int a = 0; a <= m; a++) {
		memset(hit, 0, n);
		for (uint32_t i = 0; i < n; i++) {
			float u, v;
			pm_ld_pair(seed, pair, start + i, &u, &v);
			if (!(u >= 0 && u < 1 && v >= 0 && v < 1))
				return 0;
			uint32_t cx = (uint32_t)(u * (float)(1u << a)), cy = (uint32_t)(v * (float)(1u << (m - a)));
			if (hit[(cx << (m - a)) | cy]++)
				return 0;
		}
	}
	return 1;
}

TEST(prefixes_are_nets)
{
	for (uint64_t seed = 0; seed < 4; seed++)
		for (uint32_t pair = 0; pair < 5; pair++)
			for (int m = 1; m <= 12; m++)
				CHECKF(is_net(seed * 0x9e3779b97f4a7c15ull, pair, 0, m),
				       "seed %llu pair %u m %d", (unsigned long long)seed, pair, m);
	/* The block after 2^32 points is a net of its own, too. */
	CHECK(is_net(5, 1, (uint64_t)1 << 32, 10));
}

/* The mean of u, v and u v over 4096 points: 1/2, 1/2 and 1/4 far closer
 * than pseudo-random points' 1/sqrt(12 * 4096) = 0.0045. */
TEST(moments)
{
	double su = 0, sv = 0, suv = 0;
	for (uint32_t i = 0; i < 4096; i++) {
		float u, v;
		pm_ld_pair(11, 3, i, &u, &v);
		su += u;
		sv += v;
		suv += (double)u * v;
	}
	CHECKF(fabs(su / 4096 - 0.5) < 1e-3 && fabs(sv / 4096 - 0.5) < 1e-3, "%g %g", su / 4096, sv / 4096);
	CHECKF(fabs(suv / 4096 - 0.25) < 1e-3, "%g", suv / 4096);
}

/* Seeds and pairs scramble independently: no two of these streams share
 * their first point, and none is another's. */
TEST(streams_differ)
{
	float u[8], v[8];
	for (int s = 0; s < 8; s++)
		pm_ld_pair(s < 4 ? (uint64_t)s : 0, s < 4 ? 0 : (uint32_t)(s - 3), 0, &u[s], &v[s]);
	for (int a = 0; a < 8; a++)
		for (int b = a + 1; b < 8; b++)
			CHECKF(u[a] != u[b] || v[a] != v[b], "streams %d and %d", a, b);
	float x, y;
	pm_ld_pair(1, 0, (uint64_t)1 << 32, &x, &y);
	CHECK(x != u[1] || y != v[1]);
}

int
main(void)
{
	RUN(prefixes_are_nets);
	RUN(moments);
	RUN(streams_differ);
	return check_done();
}
