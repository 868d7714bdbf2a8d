/* test_overlap.c — polygon clipping to the cube (against the independent
 * streaming clipper of clip.c) and hidden areas between parallel polygons
 * (against hand-computed rectangles). */
#include <math.h>

#include "check.h"
#include "estimators/clip.h"
#include "estimators/overlap.h"
#include "base/rng.h"

static double
area(const pm_dvec3 *v, int n, pm_dvec3 N)
{
	pm_dvec3 s = pm_dv3(0, 0, 0);
	for (int i = 1; i + 1 < n; i++)
		s = pm_dadd(s, pm_dcross(pm_dsub(v[i], v[0]), pm_dsub(v[i + 1], v[0])));
	return 0.5 * fabs(pm_ddot(s, N));
}

TEST(clip_matches_streaming_clipper)
{
	pm_rng r = pm_rng_seed(11, 1);
	for (int t = 0; t < 20000; t++) {
		pm_dvec3 v[8], out[PM_OVERLAP_MAXV(8)], c = pm_dv3(pm_rng_f(&r) - 0.5, pm_rng_f(&r) - 0.5, pm_rng_f(&r) - 0.5);
		pm_dvec3 u = pm_dv3(pm_rng_f(&r) - 0.5, pm_rng_f(&r) - 0.5, pm_rng_f(&r) - 0.5), w;
		pm_dvec3 N;
		int n = 3 + (int)(pm_rng_f(&r) * 5);
		double h = 0.05 + pm_rng_f(&r);
		/* A convex polygon: points on an ellipse in a random plane. */
		u = pm_dscale(u, 1 / pm_dlen(u));
		w = pm_dcross(u, pm_dv3(0.3, 0.5, 0.8));
		w = pm_dscale(w, 1 / pm_dlen(w));
		N = pm_dcross(u, w);
		for (int i = 0; i < n; i++) {
			double a = 2 * PM_PI * i / n;
			v[i] = pm_dadd(c, pm_dadd(pm_dscale(u, 1.3 * cos(a)), pm_dscale(w, 0.7 * sin(a))));
		}
		int m = pm_clip_poly(v, n, h, out);
		double a1 = m ? area(out, m, N) : 0, a2 = pm_clip_area(v, (size_t)n, N, h);
		CHECKF(fabs(a1 - a2) <= 1e-9 * (1 + a2), "trial %d: %g vs %g", t, a1, a2);
		for (int i = 0; i < m; i++)
			CHECKF(fabs(out[i].x) <= h * (1 + 1e-12) && fabs(out[i].y) <= h * (1 + 1e-12) &&
			       fabs(out[i].z) <= h * (1 + 1e-12), "vertex outside the cube");
		if (check_cur_failed)
			return;
	}
}

TEST(convexity)
{
	pm_dvec3 sq[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
	pm_dvec3 L[6] = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
	CHECK(pm_poly_convex(sq, 4, pm_dv3(0, 0, 1)));
	CHECK(!pm_poly_convex(L, 6, pm_dv3(0, 0, 1)));
}

/* Unit square b at z = 0; square a of side 0.5 at z = 0.1, its corner at
 * (0.75, 0.75): straight down it hides 0.25 x 0.25 of b; along a direction
 * tilted 45 degrees toward -x it lands 0.1 further left: 0.35 x 0.25. */
TEST(parallel_overlap)
{
	pm_dvec3 b[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
	pm_dvec3 a[4] = {{0.75, 0.75, 0.1}, {1.25, 0.75, 0.1}, {1.25, 1.25, 0.1}, {0.75, 1.25, 0.1}};
	pm_dvec3 bcw[4] = {b[3], b[2], b[1], b[0]};
	pm_dvec3 scratch[2 * 8 + 8], N = pm_dv3(0, 0, 1);
	double s = sqrt(0.5);
	double o1 = pm_overlap_area(a, 4, b, 4, N, pm_dv3(0, 0, 1), scratch);
	double o2 = pm_overlap_area(a, 4, b, 4, N, pm_dv3(s, 0, s), scratch);
	double o3 = pm_overlap_area(a, 4, bcw, 4, N, pm_dv3(s, 0, s), scratch);
	double o4 = pm_overlap_area(a, 4, b, 4, pm_dv3(0, 0, -1), pm_dv3(0, 0, 1), scratch);
	CHECKF(fabs(o1 - 0.0625) < 1e-12, "%g", o1);
	CHECKF(fabs(o2 - 0.35 * 0.25) < 1e-12, "%g", o2);
	CHECKF(fabs(o3 - 0.35 * 0.25) < 1e-12, "clockwise b: %g", o3);
	CHECKF(fabs(o4 - 0.0625) < 1e-12, "normal flipped: %g", o4);
	CHECK(pm_overlap_area(a, 4, b, 4, N, pm_dv3(1, 0, 0), scratch) == 0);
	/* A triangle inside the square hides exactly its own area. */
	pm_dvec3 t[3] = {{0.2, 0.2, 0.3}, {0.6, 0.2, 0.3}, {0.2, 0.7, 0.3}};
	double o5 = pm_overlap_area(t, 3, b, 4, N, pm_dv3(0, 0, 1), scratch);
	CHECKF(fabs(o5 - 0.1) < 1e-12, "%g", o5);
}

int
main(void)
{
	RUN(clip_matches_streaming_clipper);
	RUN(convexity);
	RUN(parallel_overlap);
	return check_done();
}
