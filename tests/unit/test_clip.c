/* test_clip.c — the area of a polygon inside a cube (lib/estimators/clip.c) against
 * areas worked out by hand: through the centre, in and beside a face,
 * through an edge and a corner, a concave L and U, far from the origin,
 * degenerate input. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "estimators/clip.h"

#define NEAR(a, b, rel) (fabs((a) - (b)) <= (rel) * fmax(fabs(b), 1e-300))

/* A polygon in the plane through `o` spanned by unit u, v (normal u x v),
 * given by 2-D coordinates (s, t) scaled by `scale`, minus the cube centre c. */
static double
area2d(const double (*st)[2], int n, pm_dvec3 o, pm_dvec3 u, pm_dvec3 v,
       double scale, pm_dvec3 c, double h)
{
	pm_dvec3 p[16];
	for (int i = 0; i < n; i++)
		p[i] = pm_dsub(pm_dadd(o, pm_dadd(pm_dscale(u, st[i][0] * scale),
		                                  pm_dscale(v, st[i][1] * scale))), c);
	return pm_clip_area(p, (size_t)n, pm_dcross(u, v), h);
}

static const pm_dvec3 X = {1, 0, 0}, Y = {0, 1, 0}, Z = {0, 0, 1}, O = {0, 0, 0};

TEST(big_quad_through_centre)
{
	const double q[4][2] = {{-10, -10}, {10, -10}, {10, 10}, {-10, 10}};
	double h = 0.25;
	double a = area2d(q, 4, O, X, Y, 1, O, h);
	CHECKF(NEAR(a, 4 * h * h, 1e-12), "a=%.17g", a);
	/* clockwise gives the same (unsigned) area */
	const double r[4][2] = {{-10, 10}, {10, 10}, {10, -10}, {-10, -10}};
	a = area2d(r, 4, O, X, Y, 1, O, h);
	CHECKF(NEAR(a, 4 * h * h, 1e-12), "a=%.17g", a);
	/* a tilted plane z = x/2 cuts the cube in a rectangle 2h x 2h*sqrt(1.25) */
	pm_dvec3 u = {2 / sqrt(5.0), 0, 1 / sqrt(5.0)};
	a = area2d(q, 4, O, u, Y, 1, O, h);
	CHECKF(NEAR(a, 4 * h * h * sqrt(1.25), 1e-12), "a=%.17g", a);
}

TEST(quad_in_face_plane_counts)
{
	const double q[4][2] = {{-3, -3}, {3, -3}, {3, 3}, {-3, 3}};
	double h = 0.5;
	/* z = +h and z = -h: inside the closed cube */
	double a = area2d(q, 4, pm_dv3(0, 0, h), X, Y, 1, O, h);
	CHECKF(a == 4 * h * h, "a=%.17g", a);
	a = area2d(q, 4, pm_dv3(0, 0, -h), Y, X, 1, O, h);
	CHECKF(a == 4 * h * h, "a=%.17g", a);
	/* x = +h (a face with another axis) */
	a = area2d(q, 4, pm_dv3(h, 0, 0), Y, Z, 1, O, h);
	CHECKF(a == 4 * h * h, "a=%.17g", a);
	/* a hair outside: nothing */
	a = area2d(q, 4, pm_dv3(0, 0, nextafter(h, 1)), X, Y, 1, O, h);
	CHECKF(a == 0, "a=%.17g", a);
	a = area2d(q, 4, pm_dv3(0, 0, -h - 1e-12), X, Y, 1, O, h);
	CHECKF(a == 0, "a=%.17g", a);
	/* a hair inside: all of it */
	a = area2d(q, 4, pm_dv3(0, 0, nextafter(h, 0)), X, Y, 1, O, h);
	CHECKF(NEAR(a, 4 * h * h, 1e-15), "a=%.17g", a);
}

TEST(triangle_with_vertex_in_cube)
{
	/* right triangle (0,0) (1.5h,0) (0,1.5h): area 1.125 h^2 less the two
	 * corners beyond x = h and y = h, 0.125 h^2 each */
	double h = 2;
	const double t[3][2] = {{0, 0}, {1.5, 0}, {0, 1.5}};
	double a = area2d(t, 3, O, X, Y, h, O, h);
	CHECKF(NEAR(a, 0.875 * h * h, 1e-12), "a=%.17g", a);
	/* vertex inside, the other two far away on both sides: a triangle
	 * (0,0) (10,-10) (10,10) covers x in [0,h], |y| <= x: h^2 */
	const double w[3][2] = {{0, 0}, {10, -10}, {10, 10}};
	a = area2d(w, 3, O, X, Y, h, O, h);
	CHECKF(NEAR(a, h * h, 1e-12), "a=%.17g", a);
	/* the same triangle held in the plane x = 0.3h, spanning y, z */
	a = area2d(w, 3, pm_dv3(0.3 * h, 0, 0), Y, Z, h, O, h);
	CHECKF(NEAR(a, h * h, 1e-12), "a=%.17g", a);
}

TEST(centre_on_polygon_edge_and_corner)
{
	/* x on the polygon's edge: half of the cube's cross-section */
	double h = 0.1;
	const double half[4][2] = {{0, -5}, {5, -5}, {5, 5}, {0, 5}};
	double a = area2d(half, 4, O, X, Y, 1, O, h);
	CHECKF(NEAR(a, 2 * h * h, 1e-12), "a=%.17g", a);
	/* x on the polygon's corner: a quarter */
	const double quarter[4][2] = {{0, 0}, {5, 0}, {5, 5}, {0, 5}};
	a = area2d(quarter, 4, O, X, Y, 1, O, h);
	CHECKF(NEAR(a, h * h, 1e-12), "a=%.17g", a);
	/* the polygon's corner at a corner of the cube and its edges along the
	 * cube's edges: the whole face-sized square */
	a = area2d(quarter, 4, pm_dv3(-h, -h, h), X, Y, 2 * h, O, h);
	CHECKF(NEAR(a, 4 * h * h, 1e-12), "a=%.17g", a);
	/* the polygon touching the cube only in a corner: nothing */
	a = area2d(quarter, 4, pm_dv3(h, h, h), X, Y, 1, O, h);
	CHECKF(a == 0, "a=%.17g", a);
}

TEST(plane_through_cube_edges_and_corners)
{
	double h = 0.5;
	const double q[4][2] = {{-9, -9}, {9, -9}, {9, 9}, {-9, 9}};
	/* the diagonal plane x = y contains two opposite edges of the cube: a
	 * 2 sqrt(2) h by 2h rectangle */
	pm_dvec3 d = {1 / sqrt(2.0), 1 / sqrt(2.0), 0};
	double a = area2d(q, 4, O, d, Z, 1, O, h);
	CHECKF(NEAR(a, 2 * sqrt(2.0) * h * 2 * h, 1e-12), "a=%.17g", a);
	/* x + y + z = 0 cuts a regular hexagon of side sqrt(2) h: 3 sqrt(3) h^2 */
	pm_dvec3 u = {1 / sqrt(2.0), -1 / sqrt(2.0), 0};
	pm_dvec3 v = {1 / sqrt(6.0), 1 / sqrt(6.0), -2 / sqrt(6.0)};
	a = area2d(q, 4, O, u, v, 1, O, h);
	CHECKF(NEAR(a, 3 * sqrt(3.0) * h * h, 1e-12), "a=%.17g", a);
	/* x + y + z = 3h touches only the corner (h, h, h) */
	pm_dvec3 c = {h, h, h};
	a = area2d(q, 4, c, u, v, 1, O, h);
	CHECKF(a < 1e-14, "a=%.17g", a);
	/* x + y + z = 2h: the corner triangle with vertices (h,h,0) (h,0,h)
	 * (0,h,h), side sqrt(2) h: sqrt(3)/4 * 2 h^2 */
	a = area2d(q, 4, pm_dv3(2 * h / 3, 2 * h / 3, 2 * h / 3), u, v, 1, O, h);
	CHECKF(NEAR(a, sqrt(3.0) / 2 * h * h, 1e-12), "a=%.17g", a);
}

TEST(concave_polygons)
{
	double h = 1;
	/* L: arms leave the cube through x = h and y = h; inside it is
	 * [-0.5,1]x[-0.5,0.5] united with [-0.5,0.5]x[-0.5,1]: 1.5 + 1.5 - 1 = 2 */
	const double L[6][2] = {{-0.5, -0.5}, {3, -0.5}, {3, 0.5}, {0.5, 0.5}, {0.5, 3}, {-0.5, 3}};
	double a = area2d(L, 6, O, X, Y, h, O, h);
	CHECKF(NEAR(a, 2 * h * h, 1e-12), "a=%.17g", a);
	/* U whose two arms leave through y = h: clipping bridges them along the
	 * face; base 1.6 x 0.4 plus two arms 0.4 x 1.4 */
	const double U[8][2] = {{-0.8, -0.8}, {0.8, -0.8}, {0.8, 3}, {0.4, 3},
	                        {0.4, -0.4}, {-0.4, -0.4}, {-0.4, 3}, {-0.8, 3}};
	a = area2d(U, 8, O, X, Y, h, O, h);
	CHECKF(NEAR(a, 0.64 + 2 * 0.56, 1e-12), "a=%.17g", a);
	/* the same U tilted out of the axis planes keeps its area ratio */
	pm_dvec3 u = {0.6, 0, 0.8}, v = {0, 1, 0};
	a = area2d(U, 8, O, u, v, 0.5, O, h);
	/* at scale 0.5 the arms reach y = 1.5 and are cut at y = 1 (t = 2): in
	 * plane units base 0.64 plus arms 0.4 x 2.4, times 0.5^2 */
	CHECKF(NEAR(a, 0.25 * (0.64 + 2 * 0.4 * 2.4), 1e-12), "a=%.17g", a);
}

TEST(far_from_origin)
{
	/* a quad through the centre at (1e4, 1e4, 1e4) with h = 1e-3, held in a
	 * tilted plane: clipped relative to the centre, it must match the same
	 * quad at the origin */
	const double q[4][2] = {{-0.01, -0.007}, {0.013, -0.006}, {0.011, 0.009}, {-0.008, 0.012}};
	pm_dvec3 c = {1e4, 1e4, 1e4};
	pm_dvec3 u = {0.36, 0.48, 0.8}, v = {0.8, -0.6, 0};
	double h = 1e-3;
	double near = area2d(q, 4, O, u, v, 1, O, h);
	double far = area2d(q, 4, c, u, v, 1, c, h);
	CHECKF(near > 0 && NEAR(far, near, 1e-9), "near=%.17g far=%.17g", near, far);
	/* a tiny triangle partly inside: same */
	const double t[3][2] = {{-0.0005, -0.0004}, {0.003, 0.0001}, {0.0002, 0.0025}};
	near = area2d(t, 3, O, u, v, 1, O, h);
	far = area2d(t, 3, c, u, v, 1, c, h);
	CHECKF(near > 0 && NEAR(far, near, 1e-9), "near=%.17g far=%.17g", near, far);
}

TEST(degenerate_inputs)
{
	pm_dvec3 seg[4] = {{-1, 0, 0}, {1, 0, 0}, {0.5, 0, 0}, {-0.5, 0, 0}};
	double a = pm_clip_area(seg, 4, Z, 0.5);
	CHECKF(a == 0, "collinear a=%.17g", a);
	pm_dvec3 pt[3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
	a = pm_clip_area(pt, 3, Z, 0.5);
	CHECKF(a == 0, "point a=%.17g", a);
	a = pm_clip_area(pt, 0, Z, 0.5);
	CHECKF(a == 0, "empty a=%.17g", a);
	pm_dvec3 sq[4] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
	a = pm_clip_area(sq, 4, Z, 0);
	CHECKF(a == 0, "h=0 a=%.17g", a);
	a = pm_clip_area(sq, 4, Z, -1);
	CHECKF(a == 0, "h<0 a=%.17g", a);
	a = pm_clip_area(sq, 4, Z, NAN);
	CHECKF(a == 0, "h=nan a=%.17g", a);
	pm_dvec3 bad[4] = {{-1, -1, 0}, {NAN, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
	a = pm_clip_area(bad, 4, Z, 0.5);
	CHECKF(isfinite(a) && a >= 0, "nan vertex a=%.17g", a);
	/* a zero normal measures the vector area */
	a = pm_clip_area(sq, 4, pm_dv3(0, 0, 0), 0.5);
	CHECKF(NEAR(a, 1.0, 1e-15), "a=%.17g", a);
	/* many vertices: a 1000-gon approximating a circle of radius 2h */
	enum { N = 1000 };
	pm_dvec3 *circ = malloc(N * sizeof *circ);
	double h = 0.5, r = 2 * h;
	for (int i = 0; i < N; i++) {
		double t = 2 * PM_PI * i / N;
		circ[i] = pm_dv3(r * cos(t), r * sin(t), 0.2);
	}
	a = pm_clip_area(circ, N, Z, h);
	CHECKF(NEAR(a, 4 * h * h, 1e-12), "a=%.17g", a);
	/* radius 1.2h (short of the corners, 1.41h): the disc less the four
	 * circular segments beyond the faces */
	r = 1.2 * h;
	for (int i = 0; i < N; i++) {
		double t = 2 * PM_PI * (i + 0.5) / N;
		circ[i] = pm_dv3(r * cos(t), r * sin(t), 0);
	}
	double th = acos(h / r), seg_area = r * r * (th - sin(th) * cos(th));
	a = pm_clip_area(circ, N, Z, h);
	double want = PM_PI * r * r - 4 * seg_area;
	CHECKF(NEAR(a, want, 1e-4), "a=%.17g want %.17g", a, want);
	free(circ);
}

/* The array clipper against the streaming one, bit for bit, on random
 * triangles, quads and star-shaped (concave) polygons around and across a
 * cube, with and without bounds; and its -1 where out is too small. */
static double
urand(unsigned *st)
{
	*st = *st * 1664525u + 1013904223u;
	return (*st >> 8) * (1.0 / 16777216.0);
}

static pm_dvec3
unit(pm_dvec3 a)
{
	return pm_dscale(a, 1 / pm_dlen(a));
}

static int
same_bits(double a, double b)
{
	return memcmp(&a, &b, sizeof a) == 0;
}

TEST(array_matches_streaming)
{
	unsigned st = 7;
	int cut = 0, compared = 0;
	for (int trial = 0; trial < 4000; trial++) {
		int n = trial % 3 == 0 ? 3 : trial % 3 == 1 ? 4 : 5 + trial % 9;
		double h = 0.25 + urand(&st), lo[3] = {INFINITY, INFINITY, INFINITY},
		       hi[3] = {-INFINITY, -INFINITY, -INFINITY};
		pm_dvec3 c = pm_dv3(urand(&st) - 0.5, urand(&st) - 0.5, urand(&st) - 0.5), v[16], out[64];
		pm_dvec3 u = unit(pm_dv3(urand(&st) - 0.5, urand(&st) - 0.5, urand(&st) - 0.5));
		pm_dvec3 w = unit(pm_dcross(u, pm_dv3(0.3, 0.5, 0.8)));
		pm_dvec3 N = pm_dcross(u, w);
		double size = 0.2 + 3 * urand(&st);
		for (int i = 0; i < n; i++) {
			/* Star-shaped: every other vertex pulled in past 5 vertices. */
			double t = 2 * PM_PI * (i + 0.3 * urand(&st)) / n,
			       r = size * (n > 4 && i % 2 ? 0.3 : 1);
			v[i] = pm_dadd(c, pm_dadd(pm_dscale(u, r * cos(t)), pm_dscale(w, r * sin(t))));
			lo[0] = fmin(lo[0], v[i].x), lo[1] = fmin(lo[1], v[i].y), lo[2] = fmin(lo[2], v[i].z);
			hi[0] = fmax(hi[0], v[i].x), hi[1] = fmax(hi[1], v[i].y), hi[2] = fmax(hi[2], v[i].z);
		}
		for (int b = 0; b < 2; b++) {
			pm_clipper cl;
			pm_dvec3 keep[64], mid;
			double a;
			pm_clip_begin(&cl, h);
			if (b)
				pm_clip_bounds(&cl, lo, hi);
			pm_clip_keep(&cl, keep, 64);
			for (int i = 0; i < n; i++)
				pm_clip_vertex(&cl, v[i]);
			double want = pm_clip_end(&cl, N);
			int m = pm_clip_array(v, n, h, b ? lo : NULL, b ? hi : NULL, N, out, 64, &a, &mid);
			CHECKF(m == pm_clip_kept(&cl), "trial %d: %d vertices against %d", trial, m, pm_clip_kept(&cl));
			CHECKF(same_bits(a, want), "trial %d: area %.17g against %.17g", trial, a, want);
			pm_dvec3 wm = pm_clip_middle(&cl);
			CHECK(same_bits(mid.x, wm.x) && same_bits(mid.y, wm.y) && same_bits(mid.z, wm.z));
			for (int i = 0; i < m && i < 64; i++)
				CHECK(same_bits(out[i].x, keep[i].x) && same_bits(out[i].y, keep[i].y) &&
				      same_bits(out[i].z, keep[i].z));
			cut += m != n;
			compared++;
			/* Too small an out: -1 as pm_clip_kept gives it, never a
			 * write past it, and still the area. */
			if (m > 1) {
				pm_dvec3 small[64];
				small[m - 1] = pm_dv3(42, 42, 42);
				CHECK(pm_clip_array(v, n, h, NULL, NULL, N, small, m - 1, &a, &mid) == -1);
				CHECK(small[m - 1].x == 42);
				CHECK(same_bits(a, want));
			}
		}
	}
	/* The trials must have cut polygons, not only passed them through. */
	CHECKF(cut > compared / 4, "%d of %d cut", cut, compared);
	double a;
	pm_dvec3 mid, out[8], sq[4] = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
	CHECK(pm_clip_array(sq, 4, 0, NULL, NULL, Z, out, 8, &a, &mid) == 0 && a == 0);
	CHECK(pm_clip_array(sq, 4, NAN, NULL, NULL, Z, out, 8, &a, &mid) == 0 && a == 0);
}

int
main(void)
{
	RUN(big_quad_through_centre);
	RUN(quad_in_face_plane_counts);
	RUN(triangle_with_vertex_in_cube);
	RUN(centre_on_polygon_edge_and_corner);
	RUN(plane_through_cube_edges_and_corners);
	RUN(concave_polygons);
	RUN(far_from_origin);
	RUN(degenerate_inputs);
	RUN(array_matches_streaming);
	return check_done();
}
