/* test_sight.c — a polygon's box on the cube of directions holds every
 * point within e of it, and the grid finds every box a box meets. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "check.h"
#include "estimators/sight.h"

static uint64_t rng = 0x9e3779b97f4a7c15u;

static double
uni(void)
{
	rng ^= rng << 13;
	rng ^= rng >> 7;
	rng ^= rng << 17;
	return (double)(rng >> 11) / 9007199254740992.0;
}

static double
at(pm_dvec3 v, int a)
{
	return a == 0 ? v.x : a == 1 ? v.y : v.z;
}

/* A random convex triangle or quad (flat, as the estimate's polygons are)
 * of size about s centred near c. */
static int
poly(pm_dvec3 c, double s, pm_dvec3 *v)
{
	int n = uni() < 0.5 ? 3 : 4;
	pm_dvec3 a, b, w;
	do
		a = pm_dv3(uni() - 0.5, uni() - 0.5, uni() - 0.5);
	while (pm_dlen(a) < 0.1);
	a = pm_dscale(a, 1 / pm_dlen(a));
	do
		w = pm_dv3(uni() - 0.5, uni() - 0.5, uni() - 0.5);
	while (pm_dlen(pm_dcross(a, w)) < 0.05);
	b = pm_dcross(a, w);
	b = pm_dscale(b, 1 / pm_dlen(b));
	/* Corners at increasing angles round an ellipse: convex. */
	double t0 = 6.283185307179586 * uni(), ra = 0.5 * s * (0.3 + uni()), rb = 0.5 * s * (0.3 + uni());
	for (int k = 0; k < n; k++) {
		double t = t0 + 6.283185307179586 * (k + 0.8 * uni()) / n;
		v[k] = pm_dadd(c, pm_dadd(pm_dscale(a, ra * cos(t)), pm_dscale(b, rb * sin(t))));
	}
	return n;
}

static int
faces(const pm_sight *b)
{
	int k = 0;
	for (int f = 0; f < 6; f++)
		k += b->mask >> f & 1;
	return k;
}

/* 1 if point p (relative to the eye) lies in b's box on every face of the
 * cube of directions its direction lies on (two or three along the cube's
 * edges). */
static int
in_box(const pm_sight *b, pm_dvec3 p)
{
	double big = fmax(fabs(p.x), fmax(fabs(p.y), fabs(p.z)));
	if (!(big > 0))
		return 0;
	for (int f = 0; f < 6; f++) {
		int a = f / 2;
		double m = (f & 1 ? -1 : 1) * at(p, a);
		if (m != big)
			continue;
		if (!(b->mask >> f & 1))
			return 0;
		for (int i = 0; i < 2; i++) {
			double u = at(p, (a + 1 + i) % 3) / m;
			if (u < b->lo[f][i] || u > b->hi[f][i])
				return 0;
		}
	}
	return 1;
}

TEST(box_holds_the_polygon_and_its_neighbourhood)
{
	pm_dvec3 eye = pm_dv3(0.1, -0.2, 0.3), v[4];
	int bad = 0, boxed = 0, tried = 0, multi = 0;
	for (int t = 0; t < 4000; t++) {
		/* Every other one with a wide neighbourhood, which reaches
		 * faces the polygon itself stops short of. */
		double e = (t & 1 ? 3e-2 : 1e-3) * uni();
		pm_dvec3 c = pm_dv3(4 * uni() - 2, 4 * uni() - 2, 4 * uni() - 2);
		int n = poly(c, 0.5 * uni(), v);
		pm_sight b;
		pm_sight_box(v, n, eye, e, 1, &b);
		if (b.face < 0)
			continue;
		boxed++;
		multi += faces(&b) > 1;
		for (int s = 0; s < 50; s++) {
			/* A point of the polygon (a convex combination of its
			 * vertices), moved by up to e. */
			double w[4], sum = 0;
			pm_dvec3 p = pm_dv3(0, 0, 0), d;
			for (int k = 0; k < n; k++)
				sum += w[k] = uni();
			for (int k = 0; k < n; k++)
				p = pm_dadd(p, pm_dscale(v[k], w[k] / sum));
			do
				d = pm_dv3(2 * uni() - 1, 2 * uni() - 1, 2 * uni() - 1);
			while (pm_ddot(d, d) > 1);
			p = pm_dadd(p, pm_dscale(d, e));
			tried++;
			bad += !in_box(&b, pm_dsub(p, eye));
		}
	}
	CHECKF(bad == 0, "%d of %d points outside their polygon's box", bad, tried);
	CHECKF(boxed > 3900 && multi > 200, "only %d of 4000 polygons boxed, %d on several faces", boxed, multi);
}

TEST(box_refuses_what_it_cannot_hold)
{
	pm_dvec3 v[3] = {{1, 0, 0}, {0, 1, 0}, {1, 1, 0.1}};
	pm_sight b;
	/* Across two faces of the cube of directions: any direction, unless
	 * asked for a box on each, the one on +x reaching from the x axis
	 * (u = 0) to the seam (u = 1). */
	pm_sight_box(v, 3, pm_dv3(0, 0, 0), 1e-6, 0, &b);
	CHECK(b.face == -1 && b.mask == 0);
	pm_sight_box(v, 3, pm_dv3(0, 0, 0), 1e-6, 1, &b);
	CHECK(b.face == 0 && b.mask == (1u << 0 | 1u << 2));
	CHECK(b.lo[0][0] <= 0 && b.lo[0][0] > -1e-3 && b.hi[0][0] >= 1 && b.hi[0][0] < 1.01);
	/* Within 2 e of the eye. */
	pm_dvec3 w[3] = {{1, 0.1, 0}, {1, 0.2, 0}, {1.1, 0.1, 0}};
	pm_sight_box(w, 3, pm_dv3(0.9995, 0.15, 0), 1e-3, 1, &b);
	CHECK(b.face == -1);
	pm_sight_box(w, 3, pm_dv3(0, 0.15, 0), 1e-3, 0, &b);
	CHECK(b.face == 0 && b.mask == 1u);
	pm_sight_box(w, 3, pm_dv3(2, 0.15, 0), 1e-3, 1, &b);
	CHECK(b.face == 1 && b.mask == 2u);
	pm_dvec3 nan[3] = {{NAN, 0, 0}, {1, 0, 0}, {1, 1, 0}};
	pm_sight_box(nan, 3, pm_dv3(0, 0, 0), 1e-3, 1, &b);
	CHECK(b.face == -1);
}

TEST(grid_finds_every_box_that_meets)
{
	enum { N = 600 };
	static pm_sight s[N];
	static int out[N], mark[N];
	pm_sight_grid g = {0};
	pm_dvec3 eye = pm_dv3(0, 0, 0), v[4];
	int missed = 0, extra = 0, multi = 0, total = 0, stamp = 0;

	for (int round = 0; round < 3; round++) {
		for (int p = 0; p < N; p++) {
			pm_dvec3 c = pm_dv3(6 * uni() - 3, 6 * uni() - 3, 6 * uni() - 3);
			int n = poly(c, round == 2 ? 3 * uni() : 0.4 * uni(), v);
			pm_sight_box(v, n, eye, 1e-4, 1, &s[p]);
			multi += faces(&s[p]) > 1;
		}
		CHECK(pm_sight_grid_build(&g, s, N));
		for (int p = 0; p < N; p++)
			mark[p] = 0;
		for (int q = 0; q < N; q++) {
			int k = pm_sight_grid_query(&g, N, &s[q], NULL, 0, out, mark, ++stamp), found = 0;
			total += round < 2 ? k : 0;
			for (int i = 0; i < k; i++) {
				extra += mark[out[i]] != stamp;
				found += pm_sight_meet(&s[q], &s[out[i]]);
			}
			int want = 0;
			for (int p = 0; p < N; p++)
				want += pm_sight_meet(&s[q], &s[p]);
			missed += want != found;
		}
	}
	pm_sight_grid_free(&g);
	CHECKF(missed == 0 && extra == 0, "%d queries missed a box, %d results unmarked", missed, extra);
	CHECKF(multi > 0 && multi < 3 * N / 2, "%d of %d boxes on several faces", multi, 3 * N);
	/* Small polygons scattered around the eye: most pairs apart. */
	CHECKF(total < 2 * N * N / 4, "%d candidates for %d queries: the grid culls little", total, 2 * N);
}

/* A query told to leave out one group returns what the plain query does
 * but that group's polygons, for boxes on faces, wide ones and an asking
 * box of face -1 alike. */
TEST(grid_query_leaves_out_one_group)
{
	enum { N = 400, NG = 5 };
	static pm_sight s[N];
	static int out[N], out2[N], mark[N], mark2[N], grp[N];
	pm_sight_grid g = {0};
	pm_dvec3 eye = pm_dv3(0, 0, 0), v[4];
	int wrong = 0, left = 0, faceless = 0, stamp = 0;

	for (int p = 0; p < N; p++) {
		pm_dvec3 c = pm_dv3(6 * uni() - 3, 6 * uni() - 3, 6 * uni() - 3);
		/* Every 50th round the eye: it may meet any direction. */
		int n = poly(p % 50 == 0 ? eye : c, p % 7 == 0 ? 3 * uni() : 0.4 * uni(), v);
		pm_sight_box(v, n, eye, 1e-4, 1, &s[p]);
		grp[p] = p % NG;
		faceless += s[p].face < 0;
	}
	CHECK(pm_sight_grid_build(&g, s, N));
	for (int p = 0; p < N; p++)
		mark[p] = mark2[p] = 0;
	for (int q = 0; q < N; q++) {
		int skip = q % NG, st = ++stamp;
		int k = pm_sight_grid_query(&g, N, &s[q], NULL, skip, out, mark, st);
		int k2 = pm_sight_grid_query(&g, N, &s[q], grp, skip, out2, mark2, st);
		int j = 0;
		/* The same order, the skipped group's polygons taken out. */
		for (int i = 0; i < k; i++) {
			if (grp[out[i]] == skip) {
				left++;
				continue;
			}
			wrong += j >= k2 || out2[j] != out[i];
			j++;
		}
		wrong += j != k2;
		for (int i = 0; i < k2; i++)
			wrong += mark2[out2[i]] != st || grp[out2[i]] == skip;
	}
	pm_sight_grid_free(&g);
	CHECKF(wrong == 0, "%d differences from the plain query", wrong);
	CHECKF(left > 0 && faceless > 0, "%d left out, %d boxes of face -1: nothing tested", left, faceless);
}

int
main(void)
{
	RUN(box_holds_the_polygon_and_its_neighbourhood);
	RUN(box_refuses_what_it_cannot_hold);
	RUN(grid_finds_every_box_that_meets);
	RUN(grid_query_leaves_out_one_group);
	return check_done();
}
