/* test_compensate.c — the compensated radiance estimate (lib/estimators/compensate.c,
 * lib/scene/polyindex.c) on hand-built scenes and photon sets whose irradiance is
 * known: parallel beams lighting planar rectangles without occlusion, so
 * each rectangle's irradiance is (photons on it) * flux / area, and a
 * Lambertian surface's radiance is rho E / pi.
 *
 * Most tests drive pm_comp_weights with a brute-force L-infinity search
 * written here, so they test this module alone; the last one runs the whole
 * pm_estimate_compensated (kd-tree, packed photons, BSDF) against it. */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "optics/bsdf.h"
#include "check.h"
#include "estimators/compensate.h"
#include "formats/kdtree.h"
#include "base/rng.h"

#define RHO 0.7
#define K 50

/* ---- scenes ---- */

enum { MAXV = 1024, MAXP = 256 };

typedef struct tscene {
	pm_scene s;
	pm_material mats[2];       /* 0: diffuse (photon surface), 1: mirror */
	pm_object objs[16];
	pm_vec3 verts[MAXV];
	uint32_t start[MAXP + 1], vidx[MAXV], obj[MAXP];
	pm_vec3 normal[MAXP];
	/* rectangles, for placing photons: corner, edges, unit normal */
	pm_vec3 ro[MAXP], ru[MAXP], rv[MAXP];
	int nrect;
} tscene;

static void
ts_init(tscene *t)
{
	memset(t, 0, sizeof *t);
	t->mats[0].kind = PM_MAT_DIFFUSE;
	t->mats[0].kd = pm_v3(RHO, RHO, RHO);
	t->mats[1].kind = PM_MAT_MIRROR;
	t->mats[1].strong = 1;
	t->s.mats = t->mats;
	t->s.nmats = 2;
	t->s.objs = t->objs;
	t->s.verts = t->verts;
	t->s.poly_start = t->start;
	t->s.poly_vert = t->vidx;
	t->s.poly_obj = t->obj;
	t->s.poly_normal = t->normal;
}

static int
ts_object(tscene *t, int solid, int mat)
{
	pm_object *o = &t->objs[t->s.nobjs];
	o->solid = solid;
	o->material = mat;
	return t->s.nobjs++;
}

static void
ts_poly(tscene *t, int obj, int n, const pm_vec3 *v)
{
	uint32_t i = t->s.npolys, b = t->start[i];
	pm_dvec3 s = {0, 0, 0};
	for (int j = 0; j < n; j++) {
		t->verts[t->s.nverts] = v[j];
		t->vidx[b + j] = t->s.nverts++;
		s = pm_dadd(s, pm_dcross(pm_dfromf(v[j]), pm_dfromf(v[(j + 1) % n])));
	}
	double l = pm_dlen(s);
	t->normal[i] = pm_v3((float)(s.x / l), (float)(s.y / l), (float)(s.z / l));
	t->obj[i] = (uint32_t)obj;
	t->start[i + 1] = b + (uint32_t)n;
	t->s.npolys++;
}

/* The quad o, o+u, o+u+v, o+v; front normal u x v. */
static int
ts_rect(tscene *t, int obj, pm_vec3 o, pm_vec3 u, pm_vec3 v)
{
	pm_vec3 q[4] = {o, pm_add(o, u), pm_add(pm_add(o, u), v), pm_add(o, v)};
	ts_poly(t, obj, 4, q);
	t->ro[t->nrect] = o;
	t->ru[t->nrect] = u;
	t->rv[t->nrect] = v;
	return t->nrect++;
}

/* A new scene of one floor, the open quad z = 0, |x|, |y| <= 1, facing up;
 * returns its rectangle. */
static int
ts_floor(tscene *t)
{
	ts_init(t);
	return ts_rect(t, ts_object(t, 0, 0), pm_v3(-1, -1, 0), pm_v3(2, 0, 0), pm_v3(0, 2, 0));
}

/* ---- photons ---- */

typedef struct tphotons {
	pm_vec3 *pos, *dir;
	int n, cap;
	int *on;          /* rectangle each photon lies on */
	double flux;      /* per photon */
} tphotons;

static void
tp_add(tphotons *p, pm_vec3 pos, pm_vec3 dir, int rect)
{
	if (p->n == p->cap) {
		p->cap = p->cap ? 2 * p->cap : 1024;
		p->pos = realloc(p->pos, p->cap * sizeof *p->pos);
		p->dir = realloc(p->dir, p->cap * sizeof *p->dir);
		p->on = realloc(p->on, p->cap * sizeof *p->on);
	}
	p->pos[p->n] = pos;
	p->dir[p->n] = dir;
	p->on[p->n] = rect;
	p->n++;
}

static void
tp_free(tphotons *p)
{
	free(p->pos);
	free(p->dir);
	free(p->on);
	memset(p, 0, sizeof *p);
}

static double
rnd(pm_rng *r)
{
	return (pm_rng_u32(r) + 0.5) / 4294967296.0;
}

/* `count` photons uniform on rectangle i, all arriving from dir. q > 0
 * rounds positions to multiples of q (so translating them is exact). */
static void
tp_rect(tphotons *p, const tscene *t, int i, int count, pm_vec3 dir, pm_rng *r, double q)
{
	for (int j = 0; j < count; j++) {
		double a = rnd(r), b = rnd(r);
		double c[3];
		for (int k = 0; k < 3; k++) {
			c[k] = pm_vget(t->ro[i], k) + a * pm_vget(t->ru[i], k) + b * pm_vget(t->rv[i], k);
			if (q > 0)
				c[k] = q * nearbyint(c[k] / q);
		}
		tp_add(p, pm_v3((float)c[0], (float)c[1], (float)c[2]), dir, i);
	}
}

static double
rect_area(const tscene *t, int i)
{
	return pm_len(pm_cross(t->ru[i], t->rv[i]));
}

/* A parallel beam from direction dir, `dens` photons per unit area across
 * it, on every rectangle in mask that faces it (either side for sheets):
 * each gets dens * area * |cos| photons. */
static void
tp_beam(tphotons *p, const tscene *t, unsigned mask, pm_vec3 dir, double dens, pm_rng *r, double q)
{
	for (int i = 0; i < t->nrect; i++) {
		if (!(mask >> i & 1))
			continue;
		pm_vec3 N = pm_norm(pm_cross(t->ru[i], t->rv[i]));
		double c = fabs(pm_dot(N, dir));
		tp_rect(p, t, i, (int)lround(dens * rect_area(t, i) * c), dir, r, q);
	}
}

/* Irradiance on rectangle i from photons arriving on the side of N. */
static double
irradiance(const tphotons *p, const tscene *t, int i, pm_vec3 N)
{
	int c = 0;
	for (int j = 0; j < p->n; j++)
		c += p->on[j] == i && pm_dot(p->dir[j], N) > 0;
	return c * p->flux / rect_area(t, i);
}

/* ---- reference searches ---- */

static double
linf(pm_vec3 a, pm_vec3 x)
{
	return fmax(fabs((double)a.x - x.x), fmax(fabs((double)a.y - x.y), fabs((double)a.z - x.z)));
}

static double
l2sq(pm_vec3 a, pm_vec3 x)
{
	double dx = (double)a.x - x.x, dy = (double)a.y - x.y, dz = (double)a.z - x.z;
	return dx * dx + dy * dy + dz * dz;
}

/* The k nearest (ties by index), brute force; returns how many. */
static int
knn(const tphotons *p, pm_vec3 x, int k, double (*dist)(pm_vec3, pm_vec3), int *out, double *dfar)
{
	static double bd[4096];
	int m = 0;
	for (int i = 0; i < p->n; i++) {
		double d = dist(p->pos[i], x);
		if (m == k && !(d < bd[m - 1]))
			continue;
		int j = m < k ? m++ : m - 1;
		while (j > 0 && bd[j - 1] > d) {
			bd[j] = bd[j - 1];
			out[j] = out[j - 1];
			j--;
		}
		bd[j] = d;
		out[j] = i;
	}
	*dfar = m ? bd[m - 1] : 0;
	return m;
}

typedef struct est {
	double L;            /* one channel of radiance */
	pm_comp_stats st;
} est;

/* The compensated estimate for Lambertian rho: rho/pi * flux * sum w. */
static est
comp(const pm_polyindex *pi, const tphotons *p, pm_vec3 x, pm_vec3 n, int k)
{
	static int idx[4096];
	static pm_vec3 pos[4096], dir[4096];
	static double w[4096];
	pm_comp_scratch *sc = pm_comp_scratch_new(k);
	est e = {0};
	double dfar;
	int m = knn(p, x, k, linf, idx, &dfar);
	for (int i = 0; i < m; i++) {
		pos[i] = p->pos[idx[i]];
		dir[i] = p->dir[idx[i]];
	}
	pm_comp_weights(pi, x, n, pos, dir, m, m < k, sc, w, &e.st);
	double s = 0;
	for (int i = 0; i < m; i++) {
		CHECKF(isfinite(w[i]) && w[i] >= 0, "w[%d]=%g", i, w[i]);
		s += w[i];
	}
	e.L = RHO / PM_PI * p->flux * s;
	pm_comp_scratch_free(sc);
	return e;
}

/* Jensen's classical estimate: k nearest in a sphere, photons in front of n. */
static double
classical(const tphotons *p, pm_vec3 x, pm_vec3 n, int k)
{
	static int idx[4096];
	double r2, s = 0;
	int m = knn(p, x, k, l2sq, idx, &r2);
	for (int i = 0; i < m; i++)
		if (pm_dot(p->dir[idx[i]], n) > 0)
			s += p->flux;
	return r2 > 0 ? RHO / PM_PI * s / (PM_PI * r2) : 0;
}

static pm_polyindex *
index_of(const tscene *t)
{
	pm_polyindex *pi;
	pm_error err;
	if (pm_polyindex_build(&pi, &t->s, t->verts, &err) != 0) {
		printf("# polyindex: %s\n", err.msg);
		exit(1);
	}
	return pi;
}

#define GOOD(L) (isfinite(L) && (L) >= 0)

static pm_vec3
unit(double x, double y, double z)
{
	double l = sqrt(x * x + y * y + z * z);
	return pm_v3((float)(x / l), (float)(y / l), (float)(z / l));
}

static const pm_vec3 UP = {0, 0, 1};

/* ---- flat floor ---- */

/* 20000 photons on a 2 x 2 floor, one direction or cosine-distributed ones:
 * the mean over 100 well separated query points is within 5% of rho E / pi
 * (one estimate's spread is about 1/sqrt(k) = 14%, the mean's 1.4%). */
static void
floor_case(int solid, int random_dirs)
{
	tscene t;
	tphotons p = {0};
	pm_rng r = pm_rng_seed(1, (uint64_t)(solid * 2 + random_dirs));
	ts_init(&t);
	int f = ts_rect(&t, ts_object(&t, solid, 0), pm_v3(-1, -1, 0), pm_v3(2, 0, 0), pm_v3(0, 2, 0));
	p.flux = 1e-3;
	if (!random_dirs)
		tp_rect(&p, &t, f, 20000, unit(0.3, 0.2, 0.9), &r, 0);
	else
		for (int i = 0; i < 20000; i++) {
			pm_vec3 d = pm_sample_cosine(UP, pm_rng_f(&r), pm_rng_f(&r));
			tp_rect(&p, &t, f, 1, d, &r, 0);
		}
	pm_polyindex *pi = index_of(&t);
	double want = RHO / PM_PI * irradiance(&p, &t, f, UP), sum = 0;
	int n = 0, opened = 0;
	for (int i = 0; i < 10; i++)
		for (int j = 0; j < 10; j++) {
			pm_vec3 x = pm_v3(-0.45f + 0.1f * i, -0.45f + 0.1f * j, 0);
			est e = comp(pi, &p, x, UP, K);
			CHECKF(GOOD(e.L), "L=%g", e.L);
			CHECKF(e.st.polys == 1 && e.st.skipped == 0, "polys=%d skipped=%d", e.st.polys, e.st.skipped);
			opened += !e.st.closed && e.st.shell >= 1;
			sum += e.L;
			n++;
		}
	CHECKF(fabs(sum / n / want - 1) < 0.05, "mean/want=%g", sum / n / want);
	CHECKF(opened == n, "open cubes %d of %d", opened, n);
	pm_polyindex_free(pi);
	tp_free(&p);
}

TEST(floor_one_direction) { floor_case(0, 0); floor_case(1, 0); }

/* The consistent mode's cube (pm_comp_weights_cube at half the k-photon
 * cube): it holds the k-1 inner photons' share, so on the flat floor its
 * mean over 361 query points (about 12 photons each, a spread of 29%, the
 * mean's 1.5%) is within 5% of rho E / pi, and it counts exactly the
 * photons strictly inside it. */
TEST(floor_shrunk_cube)
{
	static int idx[4096];
	static pm_vec3 pos[4096], dir[4096];
	static double w[4096];
	tscene t;
	tphotons p = {0};
	pm_rng r = pm_rng_seed(1, 7);
	int f = ts_floor(&t);
	p.flux = 1e-3;
	tp_rect(&p, &t, f, 20000, unit(0.3, 0.2, 0.9), &r, 0);
	pm_polyindex *pi = index_of(&t);
	pm_comp_scratch *sc = pm_comp_scratch_new(K);
	double want = RHO / PM_PI * irradiance(&p, &t, f, UP), sum = 0;
	int n = 0;
	for (int i = 0; i < 19; i++)
		for (int j = 0; j < 19; j++) {
			pm_vec3 x = pm_v3(-0.45f + 0.05f * i, -0.45f + 0.05f * j, 0);
			double dfar, s = 0;
			int m = knn(&p, x, K, linf, idx, &dfar), inside = 0, used = 0;
			pm_comp_stats st;
			for (int a = 0; a < m; a++) {
				pos[a] = p.pos[idx[a]];
				dir[a] = p.dir[idx[a]];
				inside += linf(pos[a], x) < 0.5 * dfar;
			}
			pm_comp_weights_cube(pi, x, UP, pos, dir, m, 0.5 * dfar, sc, w, &st);
			for (int a = 0; a < m; a++) {
				CHECKF(isfinite(w[a]) && w[a] >= 0, "w[%d]=%g", a, w[a]);
				s += w[a];
				used += w[a] > 0;
			}
			CHECKF(st.h == 0.5 * dfar && !st.closed, "h %g of %g, closed %d", st.h, dfar, st.closed);
			CHECKF(used == inside, "used %d of %d inside", used, inside);
			sum += RHO / PM_PI * p.flux * s;
			n++;
		}
	CHECKF(fabs(sum / n / want - 1) < 0.05, "mean/want=%g", sum / n / want);
	pm_comp_scratch_free(sc);
	pm_polyindex_free(pi);
	tp_free(&p);
}
TEST(floor_random_directions) { floor_case(0, 1); floor_case(1, 1); }

/* ---- concave edge: floor and wall ---- */

/* A beam 5 degrees off vertical lights a floor (z = 0, x > 0) and a wall
 * (x = 0): at x on the edge line the floor's radiance is rho E_f / pi. The
 * compensated mean is within 10%; the classical one, which spreads the
 * floor's photons over a whole disc of which half is wall, is about
 * (E_f + E_w) / (2 E_f) = 0.54 of it. */
TEST(concave_edge)
{
	double sc = 0, cl = 0, want = 0;
	int n = 0;
	for (int seed = 0; seed < 4; seed++) {
		tscene t;
		tphotons p = {0};
		pm_rng r = pm_rng_seed(2, (uint64_t)seed);
		ts_init(&t);
		int o = ts_object(&t, 0, 0);
		int f = ts_rect(&t, o, pm_v3(0, -2, 0), pm_v3(2, 0, 0), pm_v3(0, 4, 0));
		int w = ts_rect(&t, o, pm_v3(0, -2, 0), pm_v3(0, 4, 0), pm_v3(0, 0, 2));
		double a = 5 * PM_PI / 180;
		p.flux = 1e-3;
		tp_beam(&p, &t, 3u, unit(sin(a), 0, cos(a)), 5000, &r, 0);
		pm_polyindex *pi = index_of(&t);
		want = RHO / PM_PI * irradiance(&p, &t, f, UP);
		CHECK(irradiance(&p, &t, w, pm_v3(1, 0, 0)) > 0);
		for (int i = 0; i <= 20; i++) {
			pm_vec3 x = pm_v3(0, -1.5f + 0.15f * i, 0);
			est e = comp(pi, &p, x, UP, K);
			double c = classical(&p, x, UP, K);
			CHECKF(GOOD(e.L) && GOOD(c), "L=%g classical=%g", e.L, c);
			CHECKF(e.st.polys == 2, "polys=%d", e.st.polys);
			sc += e.L / want;
			cl += c / want;
			n++;
		}
		pm_polyindex_free(pi);
		tp_free(&p);
	}
	CHECKF(fabs(sc / n - 1) < 0.10, "compensated mean/want=%g", sc / n);
	CHECKF(cl / n > 0.4 && cl / n < 0.7, "classical mean/want=%g", cl / n);
}

/* The same edge lit from 8 random directions in the quarter-space in front
 * of both surfaces; x on the edge and also on the wall (n = +x). */
TEST(concave_edge_random_directions)
{
	double sf = 0, sw = 0;
	int n = 0;
	for (int seed = 0; seed < 4; seed++) {
		tscene t;
		tphotons p = {0};
		pm_rng r = pm_rng_seed(3, (uint64_t)seed);
		ts_init(&t);
		int o = ts_object(&t, 0, 0);
		int f = ts_rect(&t, o, pm_v3(0, -2, 0), pm_v3(2, 0, 0), pm_v3(0, 4, 0));
		int w = ts_rect(&t, o, pm_v3(0, -2, 0), pm_v3(0, 4, 0), pm_v3(0, 0, 2));
		p.flux = 1e-3;
		for (int d = 0; d < 8; d++)
			tp_beam(&p, &t, 3u, unit(0.05 + rnd(&r), rnd(&r) - 0.5, 0.05 + rnd(&r)), 700, &r, 0);
		pm_polyindex *pi = index_of(&t);
		pm_vec3 X = {1, 0, 0};
		double wf = RHO / PM_PI * irradiance(&p, &t, f, UP);
		double ww = RHO / PM_PI * irradiance(&p, &t, w, X);
		for (int i = 0; i <= 20; i++) {
			pm_vec3 x = pm_v3(0, -1.5f + 0.15f * i, 0);
			est ef = comp(pi, &p, x, UP, K), ew = comp(pi, &p, x, X, K);
			CHECKF(GOOD(ef.L) && GOOD(ew.L), "L=%g %g", ef.L, ew.L);
			sf += ef.L / wf;
			sw += ew.L / ww;
			n++;
		}
		pm_polyindex_free(pi);
		tp_free(&p);
	}
	CHECKF(fabs(sf / n - 1) < 0.08, "floor mean/want=%g", sf / n);
	CHECKF(fabs(sw / n - 1) < 0.08, "wall mean/want=%g", sw / n);
}

/* ---- room corner ---- */

/* Three walls meeting at the origin, lit by three beams from the octant in
 * front of all of them; x exactly in the corner. One estimate per photon
 * set, averaged over 60 sets. The classical estimate sees a quarter disc of
 * each surface: about (E_f + E_x + E_y) / (4 E_f). */
TEST(room_corner)
{
	double sc = 0, cl = 0;
	int n = 0;
	for (int seed = 0; seed < 60; seed++) {
		tscene t;
		tphotons p = {0};
		pm_rng r = pm_rng_seed(4, (uint64_t)seed);
		ts_init(&t);
		int o = ts_object(&t, 0, 0);
		int f = ts_rect(&t, o, pm_v3(0, 0, 0), pm_v3(0.5f, 0, 0), pm_v3(0, 0.5f, 0));
		ts_rect(&t, o, pm_v3(0, 0, 0), pm_v3(0, 0.5f, 0), pm_v3(0, 0, 0.5f));
		ts_rect(&t, o, pm_v3(0, 0, 0), pm_v3(0, 0, 0.5f), pm_v3(0.5f, 0, 0));
		p.flux = 1e-3;
		tp_beam(&p, &t, 7u, unit(0.2, 0.3, 1), 3000, &r, 0);
		tp_beam(&p, &t, 7u, unit(1, 0.5, 1), 3000, &r, 0);
		tp_beam(&p, &t, 7u, unit(0.4, 1, 0.3), 3000, &r, 0);
		pm_polyindex *pi = index_of(&t);
		double want = RHO / PM_PI * irradiance(&p, &t, f, UP);
		est e = comp(pi, &p, pm_v3(0, 0, 0), UP, K);
		double c = classical(&p, pm_v3(0, 0, 0), UP, K);
		CHECKF(GOOD(e.L), "L=%g", e.L);
		CHECKF(e.st.polys == 3, "polys=%d", e.st.polys);
		sc += e.L / want;
		cl += c / want;
		n++;
		pm_polyindex_free(pi);
		tp_free(&p);
	}
	CHECKF(fabs(sc / n - 1) < 0.08, "compensated mean/want=%g", sc / n);
	CHECKF(cl / n < 0.75, "classical mean/want=%g", cl / n);
}

/* ---- convex edge: the edge of a solid table ---- */

/* Top z = 0 (x < 0) and side x = 0 (z < 0) of one object. Beams: one facing
 * both faces, one facing only the top (its side-facing cosine is negative:
 * the solid's side must not count), one facing only the side. x on the edge,
 * n = +z: rho E_top / pi. As open sheets the faces count on the side facing
 * x only, so the second beam's photons stay on the top there too. */
static double
table_edge(int solid)
{
	double s = 0;
	int n = 0;
	for (int seed = 0; seed < 4; seed++) {
		tscene t;
		tphotons p = {0};
		pm_rng r = pm_rng_seed(5, (uint64_t)seed);
		ts_init(&t);
		int o = ts_object(&t, solid, 0);
		int top = ts_rect(&t, o, pm_v3(-2, -2, 0), pm_v3(2, 0, 0), pm_v3(0, 4, 0));
		ts_rect(&t, o, pm_v3(0, -2, -2), pm_v3(0, 4, 0), pm_v3(0, 0, 2));
		p.flux = 1e-3;
		tp_beam(&p, &t, 3u, unit(1, 0, 1), 2500, &r, 0);
		tp_beam(&p, &t, 1u, unit(-1.5, 0.3, 1), 2500, &r, 0);
		tp_beam(&p, &t, 2u, unit(1, -0.2, -0.3), 2500, &r, 0);
		pm_polyindex *pi = index_of(&t);
		double want = RHO / PM_PI * irradiance(&p, &t, top, UP);
		for (int i = 0; i <= 20; i++) {
			est e = comp(pi, &p, pm_v3(0, -1.5f + 0.15f * i, 0), UP, K);
			CHECKF(GOOD(e.L), "L=%g", e.L);
			s += e.L / want;
			n++;
		}
		pm_polyindex_free(pi);
		tp_free(&p);
	}
	return s / n;
}

TEST(convex_edge_solid)
{
	double a = table_edge(1), b = table_edge(0);
	CHECKF(fabs(a - 1) < 0.08, "solid mean/want=%g", a);
	CHECKF(fabs(b - 1) < 0.08, "as sheets mean/want=%g", b);
}

/* ---- objects standing on a floor or on a rug ---- */

/* Photon placement only (no polygon): where a beam's photons land. */
static int
ts_region(tscene *t, pm_vec3 o, pm_vec3 u, pm_vec3 v)
{
	t->ro[t->nrect] = o;
	t->ru[t->nrect] = u;
	t->rv[t->nrect] = v;
	return t->nrect++;
}

/* n photons per unit area on region i, from directions spread by cos
 * about N: the photons of a uniform radiance field (a furnace). */
static void
tp_cos(tphotons *p, const tscene *t, int i, pm_vec3 N, double dens, pm_rng *r)
{
	int count = (int)lround(dens * rect_area(t, i));
	for (int j = 0; j < count; j++)
		tp_rect(p, t, i, 1, pm_sample_cosine(N, pm_rng_f(r), pm_rng_f(r)), r, 0);
}

/* A block of half-width b and height H standing (or floating by lift) on a
 * floor at z = 0 (solid, running on under the block), or on a rug (a sheet
 * at z0 > 0 over x < 0.5); the block a closed solid (bottom face on what it
 * stands on) or an open mesh (four walls and a top, two-sided). In a
 * uniform radiance field photons arrive on every surface from its whole
 * hemisphere, except where surfaces touch (under a block standing on
 * something). Every estimate is then rho E / pi: on the floor and rug next
 * to the block, up its side from the contact line, and on its top. None
 * may blow up (the fireflies on blocks standing on rugs) or read
 * dark (open blocks' contact edges). */
static void
standing_case(int solid, double z0, double lift, int rug, double *worst_hi, double *mean)
{
	const double b = 0.1, H = 0.3, dens = 40000;
	tscene t;
	tphotons p = {0};
	pm_rng r = pm_rng_seed(21, (uint64_t)(solid * 4 + rug * 2) + (uint64_t)((z0 + lift) * 1e6));
	pm_vec3 down = pm_v3(0, 0, -1);
	ts_init(&t);
	float zr = (float)z0, zb = (float)(z0 + lift), zs = rug ? zr : 0;
	float lo = (float)-b, hi = (float)b, top = (float)(z0 + lift + H);
	int fl = ts_rect(&t, ts_object(&t, 1, 0), pm_v3(-1, -1, 0), pm_v3(2, 0, 0), pm_v3(0, 2, 0));
	int rg = -1;
	if (rug)
		rg = ts_rect(&t, ts_object(&t, 0, 0), pm_v3(-1, -1, zr), pm_v3(1.5f, 0, 0), pm_v3(0, 2, 0));
	int o = ts_object(&t, solid, 0), side[4], tp;
	tp = ts_rect(&t, o, pm_v3(lo, lo, top), pm_v3(2 * hi, 0, 0), pm_v3(0, 2 * hi, 0));
	side[0] = ts_rect(&t, o, pm_v3(lo, lo, zb), pm_v3(2 * hi, 0, 0), pm_v3(0, 0, (float)H));
	side[1] = ts_rect(&t, o, pm_v3(hi, lo, zb), pm_v3(0, 2 * hi, 0), pm_v3(0, 0, (float)H));
	side[2] = ts_rect(&t, o, pm_v3(hi, hi, zb), pm_v3(2 * lo, 0, 0), pm_v3(0, 0, (float)H));
	side[3] = ts_rect(&t, o, pm_v3(lo, hi, zb), pm_v3(0, 2 * lo, 0), pm_v3(0, 0, (float)H));
	int bot = solid ? ts_rect(&t, o, pm_v3(lo, lo, zb), pm_v3(0, 2 * hi, 0), pm_v3(2 * hi, 0, 0)) : -1;
	p.flux = 1e-3;
	/* Outside faces of the block; its inside too when it is open. */
	tp_cos(&p, &t, tp, UP, dens, &r);
	for (int i = 0; i < 4; i++) {
		pm_vec3 N = pm_norm(pm_cross(t.ru[side[i]], t.rv[side[i]]));
		tp_cos(&p, &t, side[i], N, dens, &r);
		if (!solid)
			tp_cos(&p, &t, side[i], pm_neg(N), dens, &r);
	}
	if (!solid)
		tp_cos(&p, &t, tp, down, dens, &r);
	if (bot >= 0 && lift > 0)
		tp_cos(&p, &t, bot, down, dens, &r);
	/* What the block stands on: around it, and under it unless it stands
	 * on it (solid, no lift) or closes it off (open block on it). */
	float zc = rug ? zr : 0;
	int around[4];
	around[0] = ts_region(&t, pm_v3(-1, -1, zc), pm_v3(1 + lo, 0, 0), pm_v3(0, 2, 0));
	around[1] = ts_region(&t, pm_v3(hi, -1, zc), pm_v3((rug ? 0.5f : 1) - hi, 0, 0), pm_v3(0, 2, 0));
	around[2] = ts_region(&t, pm_v3(lo, -1, zc), pm_v3(2 * hi, 0, 0), pm_v3(0, 1 + lo, 0));
	around[3] = ts_region(&t, pm_v3(lo, hi, zc), pm_v3(2 * hi, 0, 0), pm_v3(0, 1 - hi, 0));
	for (int i = 0; i < 4; i++)
		tp_cos(&p, &t, around[i], UP, dens, &r);
	int under = ts_region(&t, pm_v3(lo, lo, zc), pm_v3(2 * hi, 0, 0), pm_v3(0, 2 * hi, 0));
	if (lift > 0)
		tp_cos(&p, &t, under, UP, dens, &r);
	if (rug) {
		/* the floor beyond the rug, the floor under it, the rug's underside */
		tp_cos(&p, &t, ts_region(&t, pm_v3(0.5f, -1, 0), pm_v3(0.5f, 0, 0), pm_v3(0, 2, 0)), UP, dens, &r);
		tp_cos(&p, &t, ts_region(&t, pm_v3(-1, -1, 0), pm_v3(1.5f, 0, 0), pm_v3(0, 2, 0)), UP, dens, &r);
		tp_cos(&p, &t, rg, down, dens, &r);
	}
	(void)fl;
	pm_polyindex *pi = index_of(&t);
	double want = RHO / PM_PI * p.flux * dens, sum = 0;
	int n = 0;
	for (int j = 0; j < 5; j++) {
		float y = (float)(-0.08 + 0.04 * j);
		/* toward the block on the floor or rug, then across its top */
		for (int i = 0; i < 40; i++) {
			double xx = -0.2 + 0.00501 * i;
			pm_vec3 x = xx < -b ? pm_v3((float)xx, y, zs) : pm_v3((float)xx, y, top);
			est e = comp(pi, &p, x, UP, K);
			CHECKF(GOOD(e.L), "L=%g", e.L);
			*worst_hi = fmax(*worst_hi, e.L / want);
			sum += e.L / want;
			n++;
		}
		/* up the block's -x side from the contact line */
		for (int i = 0; i < 20; i++) {
			pm_vec3 x = pm_v3(lo, y, zb + (float)(0.0005 + 0.003 * i));
			est e = comp(pi, &p, x, pm_v3(-1, 0, 0), K);
			CHECKF(GOOD(e.L), "L=%g", e.L);
			*worst_hi = fmax(*worst_hi, e.L / want);
			sum += e.L / want;
			n++;
		}
	}
	*mean = sum / n;
	pm_polyindex_free(pi);
	tp_free(&p);
}

TEST(standing_on_floor_and_rug)
{
	static const struct { int solid, rug; double z0, lift; } c[] = {
		{1, 0, 0, 0}, {0, 0, 0, 0},         /* closed and open block on the floor */
		{1, 1, 1e-3, 0}, {0, 1, 1e-3, 0},   /* on a rug 1 mm up */
		{1, 1, 5e-3, 0},                    /* on a rug 5 mm up */
		{1, 1, 1e-3, 1e-4},                 /* 0.1 mm above a rug */
		{1, 0, 0, 1e-4},                    /* 0.1 mm above the floor */
	};
	for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
		double hi = 0, mean = 0;
		standing_case(c[i].solid, c[i].z0, c[i].lift, c[i].rug, &hi, &mean);
		CHECKF(fabs(mean - 1) < 0.06, "case %zu (solid %d rug %d z0 %g): mean/want=%g",
		       i, c[i].solid, c[i].rug, c[i].z0, mean);
		/* Poisson noise alone reaches about 1.8 somewhere along these
		 * lines; the fireflies this guards against were 6 to 50. */
		CHECKF(hi < 2.5, "case %zu (solid %d rug %d z0 %g): worst/want=%g", i, c[i].solid,
		       c[i].rug, c[i].z0, hi);
	}
}

/* One closed solid of several parts, as a chair mesh is (seat, legs, back):
 * a thin fin standing on a slab's top, both faces of the same object. A
 * point on the slab beside the fin lies behind the plane of the fin's far
 * face while outside the fin; its estimate must not take it for a point
 * inside the solid, which hid every photon (chairs' seats and legs read
 * black in the room). In a uniform radiance field every estimate on the
 * slab beside the fin and up the fin's side is rho E / pi. */
TEST(solid_of_several_parts)
{
	const double b = 0.01, H = 0.3, L = 0.5, dens = 10000;
	tscene t;
	tphotons p = {0};
	pm_rng r = pm_rng_seed(27, 0);
	ts_init(&t);
	int o = ts_object(&t, 1, 0), side[4];
	float lo = (float)-b, hi = (float)b, yl = (float)-L, yh = (float)L;
	ts_rect(&t, o, pm_v3(-1, -1, 0), pm_v3(2, 0, 0), pm_v3(0, 2, 0));
	int cap = ts_rect(&t, o, pm_v3(lo, yl, (float)H), pm_v3(2 * hi, 0, 0), pm_v3(0, 2 * yh, 0));
	side[0] = ts_rect(&t, o, pm_v3(lo, yl, 0), pm_v3(2 * hi, 0, 0), pm_v3(0, 0, (float)H));
	side[1] = ts_rect(&t, o, pm_v3(hi, yl, 0), pm_v3(0, 2 * yh, 0), pm_v3(0, 0, (float)H));
	side[2] = ts_rect(&t, o, pm_v3(hi, yh, 0), pm_v3(2 * lo, 0, 0), pm_v3(0, 0, (float)H));
	side[3] = ts_rect(&t, o, pm_v3(lo, yh, 0), pm_v3(0, 2 * yl, 0), pm_v3(0, 0, (float)H));
	p.flux = 1e-3;
	tp_cos(&p, &t, cap, UP, dens, &r);
	for (int i = 0; i < 4; i++)
		tp_cos(&p, &t, side[i], pm_norm(pm_cross(t.ru[side[i]], t.rv[side[i]])), dens, &r);
	/* the slab's top around the fin, not under it */
	tp_cos(&p, &t, ts_region(&t, pm_v3(-1, -1, 0), pm_v3(1 + lo, 0, 0), pm_v3(0, 2, 0)), UP, dens, &r);
	tp_cos(&p, &t, ts_region(&t, pm_v3(hi, -1, 0), pm_v3(1 - hi, 0, 0), pm_v3(0, 2, 0)), UP, dens, &r);
	tp_cos(&p, &t, ts_region(&t, pm_v3(lo, -1, 0), pm_v3(2 * hi, 0, 0), pm_v3(0, 1 + yl, 0)), UP, dens, &r);
	tp_cos(&p, &t, ts_region(&t, pm_v3(lo, yh, 0), pm_v3(2 * hi, 0, 0), pm_v3(0, 1 - yh, 0)), UP, dens, &r);
	pm_polyindex *pi = index_of(&t);
	double want = RHO / PM_PI * p.flux * dens, sum = 0, worst_lo = INFINITY;
	int n = 0;
	/* Rows along the fin, each farther apart than the cubes are wide. */
	for (int j = 0; j < 13; j++) {
		float y = (float)(-0.45 + 0.075 * j);
		static const float at[3] = {0.001f, 0.008f, 0.02f};
		for (int i = 0; i < 6; i++) {
			/* on the slab beside the fin, then up its -x side */
			pm_vec3 x = pm_v3(lo - at[i % 3], y, 0), nx = UP;
			if (i >= 3) {
				x = pm_v3(lo, y, at[i % 3]);
				nx = pm_v3(-1, 0, 0);
			}
			est e = comp(pi, &p, x, nx, K);
			CHECKF(GOOD(e.L), "L=%g", e.L);
			worst_lo = fmin(worst_lo, e.L / want);
			sum += e.L / want;
			n++;
		}
	}
	CHECKF(fabs(sum / n - 1) < 0.06, "mean/want=%g", sum / n);
	/* Poisson noise of k = 50 photons stays above about 0.5. */
	CHECKF(worst_lo > 0.4, "darkest/want=%g", worst_lo);
	pm_polyindex_free(pi);
	tp_free(&p);
}

/* ---- thin walls: no light through ---- */

/* A two-sided sheet with four times as many photons under it as on it; a
 * thin solid slab (faces 2e-4 apart, far thinner than the cube) the same.
 * Each side's estimate is that side's rho E / pi: no leak. */
TEST(thin_walls)
{
	for (int solid = 0; solid <= 1; solid++) {
		double st = 0, sb = 0, wt = 0, wb = 0;
		int n = 0;
		for (int seed = 0; seed < 6; seed++) {
			tscene t;
			tphotons p = {0};
			pm_rng r = pm_rng_seed(6, (uint64_t)(seed + 10 * solid));
			float e = solid ? 1e-4f : 0;
			ts_init(&t);
			int o = ts_object(&t, solid, 0);
			int top = ts_rect(&t, o, pm_v3(-1, -1, e), pm_v3(2, 0, 0), pm_v3(0, 2, 0));
			int bot = top;
			if (solid)
				bot = ts_rect(&t, o, pm_v3(-1, -1, -e), pm_v3(0, 2, 0), pm_v3(2, 0, 0));
			p.flux = 1e-3;
			tp_rect(&p, &t, top, 4000, unit(0.2, 0.1, 1), &r, 0);
			tp_rect(&p, &t, bot, 16000, unit(-0.3, 0, -1), &r, 0);
			pm_polyindex *pi = index_of(&t);
			wt = RHO / PM_PI * irradiance(&p, &t, top, UP);
			wb = RHO / PM_PI * irradiance(&p, &t, bot, pm_v3(0, 0, -1));
			for (int i = 0; i < 7; i++)
				for (int j = 0; j < 7; j++) {
					float x = -0.6f + 0.2f * i, y = -0.6f + 0.2f * j;
					est a = comp(pi, &p, pm_v3(x, y, e), UP, K);
					est b = comp(pi, &p, pm_v3(x, y, -e), pm_v3(0, 0, -1), K);
					CHECKF(GOOD(a.L) && GOOD(b.L), "L=%g %g", a.L, b.L);
					st += a.L;
					sb += b.L;
					n++;
				}
			pm_polyindex_free(pi);
			tp_free(&p);
		}
		CHECKF(fabs(st / n / wt - 1) < 0.06, "solid=%d top mean/want=%g", solid, st / n / wt);
		CHECKF(fabs(sb / n / wb - 1) < 0.06, "solid=%d bottom mean/want=%g", solid, sb / n / wb);
	}
}

/* ---- photons on the cube's boundary ---- */

/* x on the floor 0.1 from a wall at x = 0.1, photon density such that the
 * cube reaches the wall's plane before it holds k floor photons (about 35
 * floor photons within 0.1, 35 on the wall's square): all the wall photons
 * near x are then at exactly distance 0.1 and the search keeps only some of
 * them. The estimate sets them aside and takes the open
 * cube: exactly rho/pi * flux * (floor photons nearer than 0.1) / (0.2)^2.
 * Averaged over those queries it is rho E_f / pi (a closed cube, counting the
 * wall's area with only part of its photons, reads over a quarter low). */
TEST(boundary_shell)
{
	double s = 0;
	int n = 0, shells = 0, reach = 0;
	static int idx[K];
	for (int seed = 0; seed < 12; seed++) {
		tscene t;
		tphotons p = {0};
		pm_rng r = pm_rng_seed(7, (uint64_t)seed);
		ts_init(&t);
		int o = ts_object(&t, 0, 0);
		int f = ts_rect(&t, o, pm_v3(-1, -1, 0), pm_v3(1.1f, 0, 0), pm_v3(0, 2, 0));
		ts_rect(&t, o, pm_v3(0.1f, 1, 0), pm_v3(0, -2, 0), pm_v3(0, 0, 1));
		p.flux = 1e-3;
		tp_beam(&p, &t, 3u, unit(-2, 0, 1), 875 * sqrt(5.0), &r, 0);
		pm_polyindex *pi = index_of(&t);
		double want = RHO / PM_PI * irradiance(&p, &t, f, UP);
		for (int i = 0; i < 30; i++) {
			pm_vec3 x = pm_v3(0, -0.87f + 0.06f * i, 0);
			est e = comp(pi, &p, x, UP, K);
			double dfar;
			CHECKF(GOOD(e.L), "L=%g", e.L);
			knn(&p, x, K, linf, idx, &dfar);
			reach += dfar == (double)0.1f;
			s += e.L / want;
			n++;
			/* the wall's shell (a floor photon within the shell's width
			 * of 0.1 would join it and shrink the cube a little) */
			if (e.st.shell < 2 || e.st.h != (double)0.1f)
				continue;
			shells++;
			int in = 0;
			for (int j = 0; j < p.n; j++)
				in += p.on[j] == f && linf(p.pos[j], x) < 0.1f;
			double h = 0.1f, exact = RHO / PM_PI * p.flux * in / (4 * h * h);
			CHECKF(e.st.h == h && !e.st.closed, "h=%.9g closed=%d", e.st.h, e.st.closed);
			CHECKF(fabs(e.L / exact - 1) < 1e-9, "L=%.12g exact=%.12g", e.L, exact);
		}
		pm_polyindex_free(pi);
		tp_free(&p);
	}
	CHECKF(reach >= n * 9 / 10 && shells >= n * 3 / 4, "of %d estimates %d reached the wall, %d had its shell",
	       n, reach, shells);
	CHECKF(fabs(s / n - 1) < 0.06, "mean/want=%g", s / n);
}

/* ---- degenerate cubes and photons ---- */

TEST(all_photons_at_one_point)
{
	tscene t;
	tphotons p = {0};
	ts_init(&t);
	ts_rect(&t, ts_object(&t, 0, 0), pm_v3(-1, -1, 0), pm_v3(2, 0, 0), pm_v3(0, 2, 0));
	pm_polyindex *pi = index_of(&t);
	pm_vec3 x = pm_v3(0.25f, -0.5f, 0);
	p.flux = 1e-3;
	for (int i = 0; i < 80; i++)
		tp_add(&p, x, unit(0.1, 0.2, 1), 0);
	est e = comp(pi, &p, x, UP, K);
	/* the minimum cube: half-size 1e-6 of the geometry's size 2 */
	CHECKF(GOOD(e.L) && e.L > 0, "L=%g", e.L);
	CHECKF(e.st.closed && e.st.h == PM_COMP_HMIN_REL * 2, "closed=%d h=%g", e.st.closed, e.st.h);
	double h = e.st.h, want = RHO / PM_PI * p.flux * K / (4 * h * h);
	CHECKF(fabs(e.L / want - 1) < 1e-9, "L=%g want=%g", e.L, want);
	/* all at one point away from x: every photon in the shell, closed */
	tphotons q = {0};
	q.flux = 1e-3;
	for (int i = 0; i < 80; i++)
		tp_add(&q, pm_v3(0.3f, -0.5f, 0), unit(0.1, 0.2, 1), 0);
	e = comp(pi, &q, x, UP, K);
	CHECKF(GOOD(e.L) && e.L > 0 && e.st.closed && e.st.shell == 0, "L=%g closed=%d", e.L, e.st.closed);
	/* at the world origin, where there is no scale from the position */
	tphotons z = {0};
	z.flux = 1;
	for (int i = 0; i < 60; i++)
		tp_add(&z, pm_v3(0, 0, 0), UP, 0);
	e = comp(pi, &z, pm_v3(0, 0, 0), UP, K);
	CHECKF(GOOD(e.L) && e.L > 0, "L=%g", e.L);
	pm_polyindex_free(pi);
	tp_free(&p);
	tp_free(&q);
	tp_free(&z);
}

/* Photons arriving in front of n that no polygon in the cube faces cannot
 * be spread and are skipped (and counted); the rest are unaffected. */
TEST(no_target_area_skipped)
{
	tscene t, empty;
	tphotons p = {0};
	pm_rng r = pm_rng_seed(8, 0);
	ts_init(&t);
	int f = ts_rect(&t, ts_object(&t, 1, 0), pm_v3(-1, -1, 0), pm_v3(2, 0, 0), pm_v3(0, 2, 0));
	p.flux = 1e-3;
	/* a third from straight above; a third from below the solid floor but
	 * in front of the tilted shading normal n (A_p = 0); a third skimming
	 * the floor at Psi.N_g = 1e-12, whose A_p is next to nothing while
	 * Psi.n = 0.7 (spread over it, each would be 1e12 times too bright) */
	for (int i = 0; i < 6000; i++)
		tp_rect(&p, &t, f, 1, i % 3 == 0 ? UP : i % 3 == 1 ? unit(1, 0, -0.2) : pm_v3(1, 0, 1e-12f), &r, 0);
	pm_vec3 n = unit(1, 0, 1), x = pm_v3(0.1f, 0.2f, 0);
	pm_polyindex *pi = index_of(&t);
	est e = comp(pi, &p, x, n, K);
	int good = 0, bad = 0;
	double dfar;
	int idx[K];
	knn(&p, x, K, linf, idx, &dfar);
	for (int i = 0; i < K; i++) {
		if (linf(p.pos[idx[i]], x) >= e.st.h)
			continue;       /* the shell */
		if (p.dir[idx[i]].z == 1)
			good++;
		else
			bad++;
	}
	double h = e.st.h, want = RHO / PM_PI * p.flux * good * (1 / sqrt(2.0)) / (4 * h * h);
	/* those from below lie on no surface facing them (hidden); those
	 * skimming it have next to no target area (skipped) */
	CHECKF(e.st.skipped + e.st.hidden == bad && e.st.skipped > 0 && e.st.hidden > 0 &&
	       e.st.front == good + bad, "skipped=%d hidden=%d front=%d good=%d bad=%d",
	       e.st.skipped, e.st.hidden, e.st.front, good, bad);
	CHECKF(bad > 0 && fabs(e.L / want - 1) < 1e-6, "L=%g want=%g", e.L, want);
	/* no polygons at all: everything skipped, 0 */
	ts_init(&empty);
	pm_polyindex *none = index_of(&empty);
	e = comp(none, &p, x, UP, K);
	CHECKF(e.L == 0 && e.st.hidden == e.st.front && e.st.front > 0, "L=%g hidden=%d front=%d",
	       e.L, e.st.hidden, e.st.front);
	/* a strong (mirror) surface is no photon surface: the same */
	tscene m;
	ts_init(&m);
	ts_rect(&m, ts_object(&m, 0, 1), pm_v3(-1, -1, 0), pm_v3(2, 0, 0), pm_v3(0, 2, 0));
	pm_polyindex *mi = index_of(&m);
	e = comp(mi, &p, x, UP, K);
	CHECKF(e.L == 0 && e.st.polys == 0, "L=%g polys=%d", e.L, e.st.polys);
	pm_polyindex_free(pi);
	pm_polyindex_free(none);
	pm_polyindex_free(mi);
	tp_free(&p);
}

/* A photon's target area is never below PM_COMP_FLOOR_REL of the cube's
 * face as x's plane sees it: on a 1 cm tile alone in a cube of some 0.8 m
 * (the other photons float in the air and count for nothing) the tile's
 * photons take the floor's weight, not 1 / (tile area); on a 20 cm tile
 * the floor is far below the tile and changes nothing. With a wall beside
 * the tile (the general path, not the cube of one polygon) the same. */
TEST(target_area_floor)
{
	for (int big = 0; big <= 1; big++)
		for (int wall = 0; wall <= 1; wall++) {
			tscene t;
			pm_rng r = pm_rng_seed(21, (uint64_t)(2 * big + wall));
			double side = big ? 0.2 : 0.01;
			ts_init(&t);
			ts_rect(&t, ts_object(&t, 0, 0), pm_v3((float)(-side / 2), (float)(-side / 2), 0),
			        pm_v3((float)side, 0, 0), pm_v3(0, (float)side, 0));
			if (wall)
				ts_rect(&t, ts_object(&t, 0, 0), pm_v3(0.3f, -0.5f, 0), pm_v3(0, 0, 0.5f),
				        pm_v3(0, 1, 0));
			pm_polyindex *pi = index_of(&t);
			pm_comp_scratch *sc = pm_comp_scratch_new(K);
			pm_vec3 x = pm_v3(0, 0, 0), pos[K], dir[K];
			double w[K];
			int on = 10, n = 0;
			/* on the tile, from above and aside (Psi.n = c) */
			for (; n < on; n++) {
				pos[n] = pm_v3((float)(side * (rnd(&r) - 0.5)), (float)(side * (rnd(&r) - 0.5)), 0);
				dir[n] = unit(0.2, 0.1, 1);
			}
			/* in the air above it, out to 0.4 (L-infinity) */
			for (; n < 40; n++) {
				pos[n] = pm_v3((float)(0.8 * rnd(&r) - 0.4), (float)(0.8 * rnd(&r) - 0.4),
				               (float)(0.05 + 0.35 * rnd(&r)));
				dir[n] = UP;
			}
			pm_comp_stats st;
			pm_comp_weights(pi, x, UP, pos, dir, n, 0, sc, w, &st);
			double area = side * side, fl = PM_COMP_FLOOR_REL * 4 * st.h * st.h;
			double want = 1 / (area > fl ? area : fl);
			int right = 0;
			for (int i = 0; i < on; i++)
				right += fabs(w[i] / want - 1) < 1e-6;
			/* the small tile's photons at most a tenth of 1 / area */
			CHECKF(sc && st.h > 0.3 && st.polys == 1 + wall && right == on && (big || w[0] * area < 0.1) &&
			       st.floored == (big ? 0 : on) && st.hidden == n - on - st.shell,
			       "big %d wall %d: h %g polys %d, %d of %d weights %g (w0 %g), floored %d, hidden %d",
			       big, wall, st.h, st.polys, right, on, want, w[0], st.floored, st.hidden);
			pm_comp_scratch_free(sc);
			pm_polyindex_free(pi);
		}
}

/* Photons at Psi.N = 1e-6: on a plain floor each still brings flux / A
 * (the cosine cancels); at a floor-wall edge the wall takes nearly all of
 * their target area, and the value matches eq. 3 worked by hand. */
TEST(grazing_photons)
{
	for (int solid = 0; solid <= 1; solid++) {
		tscene t;
		tphotons p = {0};
		pm_rng r = pm_rng_seed(9, (uint64_t)solid);
		ts_init(&t);
		int o = ts_object(&t, solid, 0);
		int f = ts_rect(&t, o, pm_v3(-1, -1, 0), pm_v3(2, 0, 0), pm_v3(0, 2, 0));
		pm_vec3 g = pm_v3(-1, 0, 1e-6f);     /* |g| = 1 in float */
		p.flux = 1e-3;
		tp_rect(&p, &t, f, 20000, g, &r, 0);
		pm_polyindex *pi = index_of(&t);
		pm_vec3 x = pm_v3(0.1f, 0.3f, 0);
		est e = comp(pi, &p, x, UP, K);
		int used = e.st.found - e.st.shell;
		double h = e.st.h, want = RHO / PM_PI * p.flux * used / (4 * h * h);
		CHECKF(GOOD(e.L) && fabs(e.L / want - 1) < 1e-6, "solid=%d L=%g want=%g", solid, e.L, want);
		pm_polyindex_free(pi);
		tp_free(&p);
	}
	/* A floor tilted by 9e-7 rad from the shading normal n = +z, photons at
	 * Psi.n = 1e-6: Psi.N_g is about 1e-7, and using it in A_p but Psi.n in
	 * the numerator would read 10 times too bright. Taken as the plane of x,
	 * each photon brings flux / A_g. */
	{
		tscene t;
		tphotons p = {0};
		pm_rng r = pm_rng_seed(9, 5);
		const float d = 9e-7f;
		pm_vec3 q[4] = {{-1, -1, d}, {1, -1, -d}, {1, 1, -d}, {-1, 1, d}};
		ts_init(&t);
		ts_poly(&t, ts_object(&t, 0, 0), 4, q);
		t.ro[0] = q[0];
		t.ru[0] = pm_sub(q[1], q[0]);
		t.rv[0] = pm_sub(q[3], q[0]);
		t.nrect = 1;
		p.flux = 1e-3;
		tp_rect(&p, &t, 0, 20000, pm_v3(-1, 0, 1e-6f), &r, 0);
		pm_polyindex *pi = index_of(&t);
		pm_vec3 x = pm_v3(0.1f, 0.3f, -0.1f * d);
		est e = comp(pi, &p, x, UP, K);
		double h = e.st.h, used = e.st.found - e.st.shell;
		double want = RHO / PM_PI * p.flux * used / (4 * h * h / cos((double)d));
		CHECKF(GOOD(e.L) && fabs(e.L / want - 1) < 1e-6, "tilted L=%g want=%g", e.L, want);
		pm_polyindex_free(pi);
		tp_free(&p);
	}
	/* the edge: floor (z = 0, x > 0) and wall (x = 0, facing +x) */
	tscene t;
	tphotons p = {0};
	pm_rng r = pm_rng_seed(9, 7);
	ts_init(&t);
	int o = ts_object(&t, 0, 0);
	int f = ts_rect(&t, o, pm_v3(0, -1, 0), pm_v3(1, 0, 0), pm_v3(0, 2, 0));
	int w = ts_rect(&t, o, pm_v3(0, -1, 0), pm_v3(0, 2, 0), pm_v3(0, 0, 1));
	pm_vec3 g = pm_v3(1, 0, 1e-6f);
	p.flux = 1e-3;
	tp_rect(&p, &t, f, 20, g, &r, 0);
	tp_rect(&p, &t, w, 20000, g, &r, 0);
	pm_polyindex *pi = index_of(&t);
	est e = comp(pi, &p, pm_v3(0, 0, 0), UP, K);
	double h = e.st.h, used = e.st.found - e.st.shell;
	double c = 1e-6f / sqrt(1 + 1e-12);
	double want = RHO / PM_PI * p.flux * used * c / (2 * h * h * c + 2 * h * h);
	CHECKF(GOOD(e.L) && e.L > 0 && fabs(e.L / want - 1) < 1e-6, "edge L=%g want=%g", e.L, want);
	pm_polyindex_free(pi);
	tp_free(&p);
}

/* Fewer photons than k: all of them count, in the closed cube just around
 * the farthest. An empty photon set gives 0. */
TEST(fewer_photons_than_k)
{
	tscene t;
	tphotons p = {0};
	pm_rng r = pm_rng_seed(10, 0);
	int f = ts_floor(&t);
	pm_polyindex *pi = index_of(&t);
	pm_vec3 x = pm_v3(0.05f, 0, 0);
	est e = comp(pi, &p, x, UP, K);
	CHECKF(e.L == 0 && e.st.found == 0, "empty L=%g", e.L);
	p.flux = 1e-3;
	tp_rect(&p, &t, f, 10, unit(0.3, 0, 1), &r, 0);
	e = comp(pi, &p, x, UP, K);
	double hk = 0;
	for (int i = 0; i < p.n; i++)
		hk = fmax(hk, linf(p.pos[i], x));
	double h = hk * (1 + PM_COMP_TAU_REL);
	double A = (fmin(1, x.x + h) - fmax(-1, x.x - h)) * (fmin(1, h) - fmax(-1, -h));
	double want = RHO / PM_PI * p.flux * 10 / A;
	CHECKF(e.st.closed && e.st.found == 10 && e.st.shell == 0, "closed=%d found=%d", e.st.closed, e.st.found);
	CHECKF(fabs(e.st.h / h - 1) < 1e-12, "h=%g want %g", e.st.h, h);
	CHECKF(fabs(e.L / want - 1) < 1e-9, "L=%g want=%g", e.L, want);
	pm_polyindex_free(pi);
	tp_free(&p);
}

/* Photons whose positions are not finite (no photon file holds one; the
 * reader refuses them, but pm_comp_weights is open to any caller) are not
 * used, and change nothing for the others: their weights are those of the
 * same call without them, bit for bit. A NaN axis beside a far finite one
 * once counted as that far distance and set the cube. */
TEST(photons_not_finite_unused)
{
	tscene t;
	tphotons p = {0};
	pm_rng r = pm_rng_seed(12, 0);
	int f = ts_floor(&t);
	pm_polyindex *pi = index_of(&t);
	pm_comp_scratch *sc = pm_comp_scratch_new(K);
	pm_vec3 x = pm_v3(0.1f, -0.05f, 0), pos[K], dir[K], gpos[K], gdir[K];
	double w[K], gw[K];
	int good = 30, n = 0, g = 0;
	p.flux = 1e-3;
	/* Within 0.25 of x: a cube far smaller than the bad photons' 0.9. */
	for (int i = 0; i < good; i++)
		tp_add(&p, pm_v3((float)(x.x + 0.5 * rnd(&r) - 0.25), (float)(x.y + 0.5 * rnd(&r) - 0.25), 0),
		       unit(0.3, 0.2, 0.9), f);
	const pm_vec3 bad[4] = {{NAN, 0.9f, 0}, {0.2f, INFINITY, 0}, {-0.9f, 0, NAN}, {-INFINITY, NAN, 0.5f}};
	for (int i = 0; i < good; i++) {
		if (i % 8 == 3 && n - g < 4) {
			pos[n] = bad[n - g];
			dir[n++] = unit(0.3, 0.2, 0.9);
		}
		gpos[g] = pos[n] = p.pos[i];
		gdir[g++] = dir[n++] = p.dir[i];
	}
	CHECKF(sc && n == good + 4 && g == good, "n=%d g=%d", n, g);
	pm_comp_stats st, gst;
	pm_comp_weights(pi, x, UP, pos, dir, n, 0, sc, w, &st);
	pm_comp_weights(pi, x, UP, gpos, gdir, g, 0, sc, gw, &gst);
	CHECKF(st.h == gst.h && st.front == gst.front, "h %g vs %g, front %d vs %d", st.h, gst.h, st.front,
	       gst.front);
	int same = 0, zero = 0, used = 0;
	for (int i = 0, j = 0; i < n; i++) {
		if (!(isfinite(pos[i].x) && isfinite(pos[i].y) && isfinite(pos[i].z))) {
			zero += w[i] == 0;
			continue;
		}
		same += memcmp(&w[i], &gw[j], sizeof w[i]) == 0;
		used += gw[j++] > 0;
	}
	CHECKF(zero == 4 && same == good && used > good / 2, "bad at 0: %d of 4, same: %d of %d, used %d", zero,
	       same, good, used);
	pm_comp_scratch_free(sc);
	pm_polyindex_free(pi);
	tp_free(&p);
}

/* ---- invariance ---- */

/* The concave edge moved by 1e4 and scaled by 1e-3 and 1e3 (flux scaled by
 * the square, so irradiance stays): each estimate the same to 1e-4. Photon
 * positions lie on a 2^-10 grid so that the moved ones are exact floats. */
static void
edge_scene(tscene *t, tphotons *p, double s, pm_vec3 off)
{
	pm_rng r = pm_rng_seed(11, 0);
	tscene base;
	ts_init(&base);
	int o = ts_object(&base, 0, 0);
	ts_rect(&base, o, pm_v3(0, -2, 0), pm_v3(2, 0, 0), pm_v3(0, 4, 0));
	ts_rect(&base, o, pm_v3(0, -2, 0), pm_v3(0, 4, 0), pm_v3(0, 0, 2));
	tphotons b = {0};
	b.flux = 1e-3;
	tp_beam(&b, &base, 3u, unit(0.5, 0.2, 1), 4000, &r, 1.0 / 1024);
	tp_beam(&b, &base, 3u, unit(1, -0.4, 0.3), 4000, &r, 1.0 / 1024);
	ts_init(t);
	o = ts_object(t, 0, 0);
	for (int i = 0; i < base.nrect; i++) {
		pm_vec3 c = base.ro[i];
		ts_rect(t, o, pm_v3((float)(c.x * s + off.x), (float)(c.y * s + off.y), (float)(c.z * s + off.z)),
		        pm_scale(base.ru[i], (float)s), pm_scale(base.rv[i], (float)s));
	}
	p->flux = b.flux * s * s;
	for (int i = 0; i < b.n; i++) {
		pm_vec3 c = b.pos[i];
		tp_add(p, pm_v3((float)(c.x * s + off.x), (float)(c.y * s + off.y), (float)(c.z * s + off.z)),
		       b.dir[i], b.on[i]);
	}
	tp_free(&b);
}

TEST(translation_and_scale)
{
	const double S[4] = {1, 1, 1e-3, 1e3};
	const pm_vec3 OFF[4] = {{0, 0, 0}, {1e4, -1e4, 1e4}, {0, 0, 0}, {0, 0, 0}};
	double L[4][10];
	for (int c = 0; c < 4; c++) {
		tscene t;
		tphotons p = {0};
		edge_scene(&t, &p, S[c], OFF[c]);
		pm_polyindex *pi = index_of(&t);
		for (int i = 0; i < 10; i++) {
			/* on the edge and beside it, on the 2^-10 grid */
			double y = (nearbyint((-1 + 0.2 * i) * 1024) + 1) / 1024, xx = i & 1 ? 0 : 0.0625;
			pm_vec3 x = pm_v3((float)(xx * S[c] + OFF[c].x), (float)(y * S[c] + OFF[c].y), OFF[c].z);
			L[c][i] = comp(pi, &p, x, UP, K).L;
			CHECKF(GOOD(L[c][i]) && L[c][i] > 0, "case %d L=%g", c, L[c][i]);
		}
		pm_polyindex_free(pi);
		tp_free(&p);
	}
	for (int c = 1; c < 4; c++)
		for (int i = 0; i < 10; i++)
			CHECKF(fabs(L[c][i] / L[0][i] - 1) < 1e-4, "case %d point %d: %.9g vs %.9g",
			       c, i, L[c][i], L[0][i]);
}

/* ---- the polygon index ---- */

static void
count_hit(void *ctx, uint32_t g)
{
	((int *)ctx)[g]++;
}

/* Random triangles, some on a mirror: every photon-surface triangle whose box
 * meets a query cube is reported exactly once, none that misses it by more
 * than float rounding, no mirror. */
TEST(polyindex_matches_brute_force)
{
	enum { NT = 60 };
	tscene t;
	pm_rng r = pm_rng_seed(12, 0);
	ts_init(&t);
	int od = ts_object(&t, 0, 0), om = ts_object(&t, 1, 1);
	for (int i = 0; i < NT; i++) {
		pm_vec3 a = pm_v3((float)(10 * rnd(&r)), (float)(10 * rnd(&r)), (float)(10 * rnd(&r)));
		pm_vec3 v[3] = {a, pm_add(a, pm_v3((float)rnd(&r), 0.1f, 0)),
		                pm_add(a, pm_v3(0, (float)rnd(&r), (float)rnd(&r)))};
		if (i % 7 == 3)   /* duplicates, for the median split */
			v[0] = t.verts[0], v[1] = t.verts[1], v[2] = t.verts[2];
		ts_poly(&t, i % 5 == 0 ? om : od, 3, v);
	}
	pm_polyindex *pi = index_of(&t);
	CHECKF(pi->nprims == NT - 12, "nprims=%u", pi->nprims);
	struct hits { int n[NT]; } h;
	for (int q = 0; q < 300; q++) {
		pm_dvec3 c = {12 * rnd(&r) - 1, 12 * rnd(&r) - 1, 12 * rnd(&r) - 1};
		double hs = q % 3 == 0 ? 0 : 2 * rnd(&r);
		memset(&h, 0, sizeof h);
		pm_polyindex_cube(pi, c, hs, count_hit, h.n);
		for (int i = 0; i < NT; i++) {
			double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
			for (int k = 0; k < 3; k++)
				for (int j = 0; j < 3; j++) {
					double v = pm_vget(t.verts[t.vidx[3 * i + j]], k);
					lo[k] = fmin(lo[k], v);
					hi[k] = fmax(hi[k], v);
				}
			double cc[3] = {c.x, c.y, c.z};
			int in = 1, near = 1;
			for (int k = 0; k < 3; k++) {
				in &= lo[k] <= cc[k] + hs && hi[k] >= cc[k] - hs;
				near &= lo[k] <= cc[k] + hs + 1e-5 && hi[k] >= cc[k] - hs - 1e-5;
			}
			int mirror = t.obj[i] == (uint32_t)om;
			CHECKF(h.n[i] <= 1, "query %d: triangle %d reported %d times", q, i, h.n[i]);
			CHECKF(!mirror || h.n[i] == 0, "query %d: mirror %d reported", q, i);
			CHECKF(mirror || !in || h.n[i] == 1, "query %d: triangle %d missed", q, i);
			CHECKF(near || h.n[i] == 0, "query %d: triangle %d far but reported", q, i);
		}
	}
	pm_polyindex_free(pi);
	/* a bad polygon is refused with a message */
	pm_polyindex *bad;
	pm_error err;
	t.vidx[4] = MAXV + 5;
	CHECK(pm_polyindex_build(&bad, &t.s, t.verts, &err) == -1 && bad == NULL);
	CHECKF(strstr(err.msg, "polygon 1: vertex") != NULL, "msg=%s", err.msg);
}

/* ---- the whole estimate ---- */

/* pm_estimate_compensated with a real kd-tree, packed photons and the
 * Lambertian BSDF gives what the weights and the decoded photons give; an
 * empty map gives 0; info reports the cube and the count. */
TEST(full_estimate_matches_core)
{
	tscene t;
	tphotons p = {0};
	pm_rng r = pm_rng_seed(13, 0);
	ts_init(&t);
	int o = ts_object(&t, 0, 0);
	ts_rect(&t, o, pm_v3(0, -2, 0), pm_v3(2, 0, 0), pm_v3(0, 4, 0));
	ts_rect(&t, o, pm_v3(0, -2, 0), pm_v3(0, 4, 0), pm_v3(0, 0, 2));
	p.flux = 1;
	tp_beam(&p, &t, 3u, unit(0.5, 0.2, 1), 3000, &r, 0);
	tp_beam(&p, &t, 3u, unit(1, -0.4, 0.3), 3000, &r, 0);
	pm_polyindex *pi = index_of(&t);

	pm_photons map;
	memset(&map, 0, sizeof map);
	map.p = malloc(p.n * sizeof *map.p);
	map.h.count = (uint64_t)p.n;
	map.h.emitted = 1000;
	for (int i = 0; i < p.n; i++) {
		pm_vec3 N = p.on[i] == 0 ? UP : pm_v3(1, 0, 0);
		pm_photon_pack(&map.p[i], p.pos[i], p.dir[i], N, pm_v3(2, 1, 0.5f));
	}
	pm_error err;
	CHECK(pm_kd_build(map.p, p.n, &err) == 0);
	/* the decoded photons, for the reference */
	tphotons d = {0};
	d.flux = 1;
	for (int i = 0; i < p.n; i++)
		tp_add(&d, pm_photon_pos(&map.p[i]), pm_photon_dir(&map.p[i]), 0);
	pm_vec3 power = pm_photon_power(&map.p[0]);

	pm_comp_scratch *sc = pm_comp_scratch_new(K);
	for (int i = 0; i < 8; i++) {
		/* on the floor (n = +z) or the wall (n = +x), some on the edge */
		float y = -1 + 0.25f * i, off = i & 1 ? 0 : 0.3f;
		pm_vec3 x = i & 2 ? pm_v3(off, y, 0) : pm_v3(0, y, off);
		pm_vec3 n = i & 2 ? UP : pm_v3(1, 0, 0);
		pm_estimate_info info;
		pm_vec3 L = pm_estimate_compensated(pi, &map, x, n, n, &t.mats[0], K, sc, &info);
		est e = comp(pi, &d, x, n, K);
		double f = 1.0 / map.h.emitted / p.flux;   /* reference flux 1 -> power/emitted */
		CHECKF(fabs(L.x / (e.L * power.x * f) - 1) < 1e-5, "x: %g vs %g", L.x, e.L * power.x * f);
		CHECKF(fabs(L.z / (e.L * power.z * f) - 1) < 1e-5, "z: %g vs %g", L.z, e.L * power.z * f);
		CHECKF(info.nphotons == K && info.size == (float)e.st.h, "info %d %g vs %g",
		       info.nphotons, info.size, e.st.h);
		const pm_comp_stats *st = pm_comp_last(sc);
		CHECKF(st->found == K && st->h == e.st.h, "stats found=%d h=%g", st->found, st->h);
	}
	pm_photons none;
	memset(&none, 0, sizeof none);
	none.h.emitted = 10;
	pm_estimate_info info;
	pm_vec3 L = pm_estimate_compensated(pi, &none, pm_v3(0, 0, 0), UP, UP, &t.mats[0], K, sc, &info);
	CHECK(L.x == 0 && L.y == 0 && L.z == 0 && info.nphotons == 0 && info.size == 0);
	CHECK(pm_comp_scratch_new(0) == NULL);
	pm_comp_scratch_free(sc);
	free(map.p);
	pm_polyindex_free(pi);
	tp_free(&p);
	tp_free(&d);
}

/* pm-render's reuse test compares a pixel's footprint with the square
 * around a disc as large as the estimate's support (info.disc). On a
 * uniform field of photons both estimates' supports hold the same k
 * photons, so their discs agree on average: the compensated cube counts as
 * the disc of its cross-section's area (its half-size itself would read
 * 0.886 of the classical radius, and the compensated pass reused less). */
TEST(support_discs_agree)
{
	tscene t;
	tphotons p = {0};
	pm_rng r = pm_rng_seed(29, 0);
	ts_init(&t);
	int o = ts_object(&t, 0, 0);
	ts_rect(&t, o, pm_v3(-4, -4, 0), pm_v3(8, 0, 0), pm_v3(0, 8, 0));
	pm_polyindex *pi = index_of(&t);
	tp_rect(&p, &t, 0, 40000, unit(0.3, -0.2, 1), &r, 0);
	pm_photons map;
	memset(&map, 0, sizeof map);
	map.p = malloc(p.n * sizeof *map.p);
	map.h.count = map.h.emitted = (uint64_t)p.n;
	for (int i = 0; i < p.n; i++)
		pm_photon_pack(&map.p[i], p.pos[i], p.dir[i], UP, pm_v3(1, 1, 1));
	pm_error err;
	CHECK(pm_kd_build(map.p, p.n, &err) == 0);
	pm_comp_scratch *sc = pm_comp_scratch_new(K);
	pm_nn *nn = malloc(K * sizeof *nn);
	double sum = 0, sumh = 0;
	int m = 0;
	for (int i = 0; i < 64; i++) {
		pm_vec3 x = pm_v3(-2 + 4 * pm_rng_f(&r), -2 + 4 * pm_rng_f(&r), 0);
		pm_estimate_info ic, ik;
		pm_estimate_compensated(pi, &map, x, UP, UP, &t.mats[0], K, sc, &ic);
		pm_estimate_classical(&map, x, UP, UP, &t.mats[0], K, nn, &ik);
		if (!(ik.disc > 0))
			continue;
		sum += ic.disc / ik.disc;
		sumh += ic.size / ik.disc;
		m++;
	}
	CHECKF(m == 64, "%d estimates", m);
	CHECKF(fabs(sum / m - 1) < 0.04, "compensated disc / classical disc: %g on average", sum / m);
	CHECKF(fabs(sumh / m - 1) > 0.08, "the cube's half-size alone: %g", sumh / m);
	free(nn);
	pm_comp_scratch_free(sc);
	free(map.p);
	tp_free(&p);
	pm_polyindex_free(pi);
}

/* ---- meshes: sheets ---- */

/* A grid of nu x nv quads, vertex (i, j) at f(i / nu, j / nv), shared by
 * its neighbours; one open object (a sheet, not a solid). */
typedef struct tmesh {
	pm_scene s;
	pm_material mat;
	pm_object obj;
	pm_vec3 *verts, *normal;
	uint32_t *start, *vidx, *pobj;
} tmesh;

static void
tm_grid(tmesh *m, int nu, int nv, pm_vec3 (*f)(double, double))
{
	memset(m, 0, sizeof *m);
	m->mat.kind = PM_MAT_DIFFUSE;
	m->mat.kd = pm_v3(RHO, RHO, RHO);
	m->obj.material = 0;
	m->verts = malloc((size_t)(nu + 1) * (nv + 1) * sizeof *m->verts);
	m->normal = malloc((size_t)nu * nv * sizeof *m->normal);
	m->start = malloc(((size_t)nu * nv + 1) * sizeof *m->start);
	m->vidx = malloc((size_t)nu * nv * 4 * sizeof *m->vidx);
	m->pobj = calloc((size_t)nu * nv, sizeof *m->pobj);
	for (int j = 0; j <= nv; j++)
		for (int i = 0; i <= nu; i++)
			m->verts[j * (nu + 1) + i] = f((double)i / nu, (double)j / nv);
	m->start[0] = 0;
	for (int j = 0, q = 0; j < nv; j++)
		for (int i = 0; i < nu; i++, q++) {
			uint32_t a = (uint32_t)(j * (nu + 1) + i), *v = m->vidx + 4 * q;
			v[0] = a;
			v[1] = a + 1;
			v[2] = a + 1 + (uint32_t)(nu + 1);
			v[3] = a + (uint32_t)(nu + 1);
			pm_dvec3 e1 = pm_dsub(pm_dfromf(m->verts[v[2]]), pm_dfromf(m->verts[v[0]]));
			pm_dvec3 e2 = pm_dsub(pm_dfromf(m->verts[v[3]]), pm_dfromf(m->verts[v[1]]));
			pm_dvec3 N = pm_dcross(e1, e2);
			N = pm_dscale(N, 1 / pm_dlen(N));
			m->normal[q] = pm_v3((float)N.x, (float)N.y, (float)N.z);
			m->start[q + 1] = 4 * (uint32_t)(q + 1);
		}
	m->s.mats = &m->mat;
	m->s.nmats = 1;
	m->s.objs = &m->obj;
	m->s.nobjs = 1;
	m->s.verts = m->verts;
	m->s.nverts = (uint32_t)((nu + 1) * (nv + 1));
	m->s.npolys = (uint32_t)(nu * nv);
	m->s.poly_start = m->start;
	m->s.poly_vert = m->vidx;
	m->s.poly_obj = m->pobj;
	m->s.poly_normal = m->normal;
}

static void
tm_free(tmesh *m)
{
	free(m->verts);
	free(m->normal);
	free(m->start);
	free(m->vidx);
	free(m->pobj);
}

static pm_vec3 flat2(double u, double v) { return pm_v3((float)(2 * u - 1), (float)(2 * v - 1), 0); }

#define CYL_R 1.5
#define CYL_T 0.35
static pm_vec3
cylinder(double u, double v)
{
	double t = CYL_T * (2 * u - 1);
	return pm_v3((float)(CYL_R * sin(t)), (float)(2 * v - 1), (float)(CYL_R * (cos(t) - 1)));
}

/* The k photons of p nearest x (L-infinity), weighed at x (normal n) in
 * the polygon index p1 with the switch *knob off (w1, st1), then in p2
 * with it on (w2, st2); knob may be NULL. Returns how many photons. */
static int
weigh_twice(const tphotons *p, pm_vec3 x, pm_vec3 n, int k, const pm_polyindex *p1,
            const pm_polyindex *p2, int *knob, pm_comp_scratch *sc, double *w1, double *w2,
            pm_comp_stats *st1, pm_comp_stats *st2)
{
	static int idx[4096];
	static pm_vec3 pos[4096], dir[4096];
	double dfar;
	int m = knn(p, x, k, linf, idx, &dfar), keep = knob ? *knob : 0;
	for (int a = 0; a < m; a++) {
		pos[a] = p->pos[idx[a]];
		dir[a] = p->dir[idx[a]];
	}
	if (knob)
		*knob = 0;
	pm_comp_weights(p1, x, n, pos, dir, m, 0, sc, w1, st1);
	if (knob)
		*knob = 1;
	pm_comp_weights(p2, x, n, pos, dir, m, 0, sc, w2, st2);
	if (knob)
		*knob = keep;
	return m;
}

/* The same floor as one quad and as a smooth mesh of 32 x 32 quads (1024
 * polygons in the cube, past any limit on polygons): the mesh is one sheet,
 * and every photon's target area (so the sum of weights) is the quad's to
 * rounding. */
TEST(tessellated_floor_is_one_quad)
{
	tscene t;
	tmesh m;
	tphotons p = {0};
	pm_rng r = pm_rng_seed(9, 1);
	static double w1[4096], w2[4096];
	int f = ts_floor(&t);
	tm_grid(&m, 32, 32, flat2);
	p.flux = 1e-3;
	for (int i = 0; i < 4000; i++)
		tp_rect(&p, &t, f, 1, pm_sample_cosine(UP, pm_rng_f(&r), pm_rng_f(&r)), &r, 0);
	pm_polyindex *p1 = index_of(&t), *p2;
	pm_error err;
	CHECK(pm_polyindex_build(&p2, &m.s, m.verts, &err) == 0);
	pm_comp_scratch *sc = pm_comp_scratch_new(400);
	int many = 0;
	for (int q = 0; q < 40; q++) {
		pm_vec3 x = pm_v3((float)(1.8 * rnd(&r) - 0.9), (float)(1.8 * rnd(&r) - 0.9), 0);
		int kk = q % 2 ? K : 400;
		double s1 = 0, s2 = 0;
		pm_comp_stats st1, st2;
		int n = weigh_twice(&p, x, UP, kk, p1, p2, NULL, sc, w1, w2, &st1, &st2);
		for (int a = 0; a < n; a++) {
			s1 += w1[a];
			s2 += w2[a];
		}
		many += st2.polys > 96;
		CHECKF(s1 > 0 && fabs(s2 / s1 - 1) < 1e-9, "query %d: mesh %.12g, quad %.12g", q, s2, s1);
		CHECKF(st1.hidden == st2.hidden && st1.skipped == st2.skipped, "hidden %d/%d", st1.hidden, st2.hidden);
	}
	CHECKF(many >= 10, "%d cubes over 96 polygons", many);
	pm_comp_scratch_free(sc);
	pm_polyindex_free(p1);
	pm_polyindex_free(p2);
	tm_free(&m);
	tp_free(&p);
}

/* The point (s, t) of tm_grid quad q, over its edges from the first corner. */
static pm_vec3
on_quad(const tmesh *m, uint32_t q, double s, double t)
{
	const pm_vec3 *v = m->verts, a = v[m->vidx[4 * q]], b = v[m->vidx[4 * q + 1]], c = v[m->vidx[4 * q + 3]];
	return pm_add(a, pm_add(pm_scale(pm_sub(b, a), (float)s), pm_scale(pm_sub(c, a), (float)t)));
}

/* A parallel beam along -d on m: each quad gets photons of flux 1e-3 in
 * proportion to its area times the cosine, dens to the unit area across
 * the beam, so the irradiance at x is 1e-3 dens (d . n). */
static void
beam_on(const tmesh *m, pm_vec3 d, double dens, pm_rng *r, tphotons *p)
{
	p->flux = 1e-3;
	for (uint32_t q = 0; q < m->s.npolys; q++) {
		const pm_vec3 *v = m->verts, a = v[m->vidx[4 * q]];
		pm_vec3 u = pm_sub(v[m->vidx[4 * q + 1]], a), w = pm_sub(v[m->vidx[4 * q + 3]], a);
		int cnt = (int)lround(dens * pm_len(pm_cross(u, w)) * pm_dot(m->normal[q], d));
		for (int i = 0; i < cnt; i++) {
			double s = rnd(r), t = rnd(r);
			tp_add(p, on_quad(m, q, s, t), d, 0);
		}
	}
}

typedef struct beam_run {
	double mean;   /* of the estimates over the exact */
	int minpolys;  /* the fewest polygons in a cube */
	int few;       /* cubes of 4 groups or fewer */
} beam_run;

/* nx estimates at random points of m's quads that face d by cos_min or
 * more and lie within |y| <= ymax, under beam_on(m, d, 20000), each over
 * the exact rho/pi E0 (d . n). */
static beam_run
beam_estimates(const tmesh *m, pm_vec3 d, uint64_t seed, double cos_min, double ymax, int nx)
{
	tphotons p = {0};
	pm_rng r = pm_rng_seed(9, seed);
	double dens = 20000, sum = 0;
	beam_run b = {.minpolys = INT_MAX};
	pm_polyindex *pi;
	pm_error err;
	beam_on(m, d, dens, &r, &p);
	CHECK(pm_polyindex_build(&pi, &m->s, m->verts, &err) == 0);
	for (int n = 0; n < nx;) {
		uint32_t q = (uint32_t)(rnd(&r) * m->s.npolys);
		if (pm_dot(m->normal[q], d) < cos_min || fabs(m->verts[m->vidx[4 * q]].y) > ymax)
			continue;
		double u = rnd(&r), v = rnd(&r);
		est e = comp(pi, &p, on_quad(m, q, u, v), m->normal[q], K);
		CHECKF(GOOD(e.L), "L=%g", e.L);
		sum += e.L / (RHO / PM_PI * dens * p.flux * pm_dot(d, m->normal[q]));
		b.minpolys = e.st.polys < b.minpolys ? e.st.polys : b.minpolys;
		b.few += e.st.groups <= 4;
		n++;
	}
	b.mean = sum / nx;
	pm_polyindex_free(pi);
	tp_free(&p);
	return b;
}

/* A curved sheet, 40 degrees of a cylinder as 40 x 8 quads, under a
 * parallel beam: the estimate's mean over 100 points is right within 5%
 * (each one spreads about 14%). */
TEST(curved_sheet_parallel_beam)
{
	tmesh m;
	tm_grid(&m, 40, 8, cylinder);
	beam_run b = beam_estimates(&m, unit(0.25, 0.1, 0.96), 2, -2, INFINITY, 100);
	CHECKF(fabs(b.mean - 1) < 0.05, "mean/want=%g", b.mean);
	tm_free(&m);
}

/* A tube of radius tube_r along y, its outside the front. */
static double tube_r;
static pm_vec3
tube(double u, double v)
{
	double t = 2 * PM_PI * u;
	return pm_v3((float)(tube_r * sin(t)), (float)(2 * v - 1), (float)(tube_r * cos(t)));
}

/* beam_estimates() on a tube of radius r, 48 facets around, at 400 lit
 * points (d . n >= 0.3) away from its ends. */
static beam_run
tube_estimates(double r)
{
	tmesh m;
	tube_r = r;
	tm_grid(&m, 48, 16, tube);
	beam_run b = beam_estimates(&m, unit(0.25, 0.1, 0.96), 3, 0.3, 0.8, 400);
	tm_free(&m);
	return b;
}

/* A tube about as thick as the cube under a parallel beam: each cube holds
 * much of its girth, normals turning through 100 degrees or more, one
 * smooth patch. Peeled into a few sheets (as lone facets, 5 to 35 groups
 * a cube here; on meshroom they cost each estimate twice its time), and
 * the estimates' mean right within 5 % (each one spreads about 34 %: a
 * cube's photons are mostly on facets x' does not see). */
TEST(bent_patch_peeled_into_sheets)
{
	beam_run b = tube_estimates(0.03);
	CHECKF(b.minpolys >= 12, "%d polygons", b.minpolys);
	CHECKF(b.few >= 380, "%d of 400 cubes in 4 groups or fewer", b.few);
	CHECKF(fabs(b.mean - 1) < 0.05, "mean/want=%g", b.mean);
}

/* A tube half as thick as the cube (it holds the whole girth): from x'
 * outside it, the near side counts on its front and the far side on its
 * back, and those sides point the same way; they must not be one sheet,
 * which would hide none of the far side's inside behind the near side.
 * As one, the mean read 0.21 of the exact. */
TEST(thin_tube_sides_apart)
{
	beam_run b = tube_estimates(0.015);
	CHECKF(b.minpolys >= 46, "%d polygons", b.minpolys);
	CHECKF(fabs(b.mean - 1) < 0.05, "mean/want=%g", b.mean);
}

/* tscene holding a 2 x 2 floor at z = 0 (twice, as two objects, if twice)
 * and under x a cloud of 150 small triangles facing every way, each its own
 * patch: more groups in the cube than fates are followed for. */
static void
floor_under_cloud(tscene *t, int twice, int ntri, double size)
{
	pm_rng r = pm_rng_seed(166, 2);
	ts_init(t);
	for (int i = 0; i < 1 + twice; i++)
		ts_rect(t, ts_object(t, 0, 0), pm_v3(-1, -1, 0), pm_v3(2, 0, 0), pm_v3(0, 2, 0));
	int cloud = ts_object(t, 0, 0);
	for (int i = 0; i < ntri; i++) {
		pm_vec3 c = pm_v3((float)(0.12 * rnd(&r) - 0.06), (float)(0.12 * rnd(&r) - 0.06),
		                  (float)(0.01 + 0.07 * rnd(&r))), v[3];
		for (int j = 0; j < 3; j++)
			v[j] = pm_add(c, pm_v3((float)(size * rnd(&r) - 0.5 * size), (float)(size * rnd(&r) - 0.5 * size),
			                       (float)(size * rnd(&r) - 0.5 * size)));
		ts_poly(t, cloud, 3, v);
	}
}

/* A floor given twice counts once in a cube of many groups too (fates
 * by rays): what lies on a polygon's plane covers it whatever the
 * direction. Every
 * photon's weight is the same as with the floor once (before, the second
 * copy was counted: torture seed 166 read 3 % dark under a subdivided
 * sphere). */
TEST(floor_twice_under_many_groups)
{
	static tscene t1, t2;
	tphotons p = {0};
	pm_rng r = pm_rng_seed(7, 3);
	double w1[K], w2[K];
	floor_under_cloud(&t1, 0, 150, 0.02);
	floor_under_cloud(&t2, 1, 150, 0.02);
	p.flux = 1e-3;
	for (int i = 0; i < 4000; i++)
		tp_rect(&p, &t1, 0, 1, pm_sample_cosine(UP, pm_rng_f(&r), pm_rng_f(&r)), &r, 0);
	pm_polyindex *p1 = index_of(&t1), *p2 = index_of(&t2);
	pm_comp_scratch *sc = pm_comp_scratch_new(K);
	for (int q = 0; q < 20; q++) {
		pm_vec3 x = pm_v3((float)(0.04 * rnd(&r) - 0.02), (float)(0.04 * rnd(&r) - 0.02), 0);
		double s1 = 0, s2 = 0;
		pm_comp_stats st1, st2;
		int n = weigh_twice(&p, x, UP, K, p1, p2, NULL, sc, w1, w2, &st1, &st2), same = 1;
		for (int a = 0; a < n; a++) {
			s1 += w1[a];
			s2 += w2[a];
			same &= fabs(w1[a] - w2[a]) <= 1e-12 * fabs(w1[a]);
		}
		CHECKF(st1.polys > 97 && st2.polys == st1.polys + 1, "query %d: %d, %d polygons", q, st1.polys, st2.polys);
		CHECKF(s1 > 0 && same, "query %d: weights %.12g once, %.12g twice", q, s1, s2);
	}
	pm_comp_scratch_free(sc);
	pm_polyindex_free(p1);
	pm_polyindex_free(p2);
	tp_free(&p);
}

/* A floor as grid x grid quads of one object (one polygon, or one flat
 * sheet, in a small cube), and with under set a small triangle of another
 * object just under it, in the cube but hidden from x' by the floor. */
static void
floor_over(tscene *t, int grid, int under)
{
	ts_init(t);
	int o = ts_object(t, 0, 0);
	for (int i = 0; i < grid; i++)
		for (int j = 0; j < grid; j++)
			ts_rect(t, o, pm_v3((float)(-1 + 2.0 * i / grid), (float)(-1 + 2.0 * j / grid), 0),
			        pm_v3((float)(2.0 / grid), 0, 0), pm_v3(0, (float)(2.0 / grid), 0));
	if (under) {
		pm_vec3 v[3] = {{-0.05f, -0.05f, -0.02f}, {0.05f, -0.05f, -0.02f}, {0, 0.05f, -0.02f}};
		ts_poly(t, ts_object(t, 0, 0), 3, v);
	}
}

/* The short paths of pm_comp_weights (a cube of one polygon; a cube of one
 * sheet and nothing else) against the general one: the same floor with a
 * triangle under it that adds no target area (x' does not see it) takes
 * the general path, and every photon's weight must be the same, to the
 * rounding of summing a sheet's facets in another order. */
TEST(short_paths_match_the_general_one)
{
	static tscene t1, t2;
	static double w1[K], w2[K];
	for (int grid = 1; grid <= 8; grid += 7) {
		tphotons p = {0};
		pm_rng r = pm_rng_seed(21, (uint64_t)grid);
		floor_over(&t1, grid, 0);
		floor_over(&t2, grid, 1);
		p.flux = 1e-3;
		for (int i = 0; i < 4000; i++)
			tp_rect(&p, &t1, (int)(rnd(&r) * grid * grid) % (grid * grid), 1,
			        pm_sample_cosine(UP, pm_rng_f(&r), pm_rng_f(&r)), &r, 0);
		pm_polyindex *p1 = index_of(&t1), *p2 = index_of(&t2);
		pm_comp_scratch *sc = pm_comp_scratch_new(K);
		for (int q = 0; q < 20; q++) {
			pm_vec3 x = pm_v3((float)(0.04 * rnd(&r) - 0.02), (float)(0.04 * rnd(&r) - 0.02), 0);
			double s1 = 0;
			pm_comp_stats st1, st2;
			int n = weigh_twice(&p, x, UP, K, p1, p2, NULL, sc, w1, w2, &st1, &st2), same = 1;
			for (int a = 0; a < n; a++) {
				s1 += w1[a];
				same &= fabs(w1[a] - w2[a]) <= 1e-12 * fabs(w1[a]);
			}
			CHECKF((grid == 1 ? st1.polys == 1 : st1.polys > 1) && st2.polys == st1.polys + 1,
			       "grid %d, query %d: %d, %d polygons", grid, q, st1.polys, st2.polys);
			CHECKF(s1 > 0 && same && st1.hidden == st2.hidden && st1.skipped == st2.skipped,
			       "grid %d, query %d: weights differ (sum %.12g), hidden %d, %d", grid, q, s1,
			       st1.hidden, st2.hidden);
		}
		pm_comp_scratch_free(sc);
		pm_polyindex_free(p1);
		pm_polyindex_free(p2);
		tp_free(&p);
	}
}

/* The weights of 20 estimates on the floor of t (photons from a cosine
 * sky over it), each made twice: with set(0), then with set(1) in force.
 * Counts the estimates whose weights (or counts of hidden and skipped
 * photons, or of polygons sampled or hidden whole) differ, and sums the
 * second runs' statistics; the first runs' must be nought where set(0)
 * turns a path off. */
typedef struct twins {
	int differ, minpolys;
	long cast[2], shadowed[2], waited[2], fcast[2];
} twins;

static twins
twin_weights(tscene *t, uint64_t seed, void (*set)(int))
{
	static double w1[K], w2[K];
	static int idx[4096];
	static pm_vec3 pos[4096], dir[4096];
	twins tw = {.minpolys = INT_MAX};
	tphotons p = {.flux = 1e-3};
	pm_rng r = pm_rng_seed(seed, 0);
	for (int i = 0; i < 4000; i++)
		tp_rect(&p, t, 0, 1, pm_sample_cosine(UP, pm_rng_f(&r), pm_rng_f(&r)), &r, 0);
	pm_polyindex *pi = index_of(t);
	pm_comp_scratch *sc = pm_comp_scratch_new(K);
	for (int q = 0; q < 20; q++) {
		pm_vec3 x = pm_v3((float)(0.06 * rnd(&r) - 0.03), (float)(0.06 * rnd(&r) - 0.03), 0);
		pm_comp_stats st1, st2;
		double dfar, s1 = 0;
		int n = knn(&p, x, K, linf, idx, &dfar), same = 1;
		for (int a = 0; a < n; a++) {
			pos[a] = p.pos[idx[a]];
			dir[a] = p.dir[idx[a]];
		}
		set(0);
		pm_comp_weights(pi, x, UP, pos, dir, n, 0, sc, w1, &st1);
		set(1);
		pm_comp_weights(pi, x, UP, pos, dir, n, 0, sc, w2, &st2);
		for (int a = 0; a < n; a++) {
			s1 += w1[a];
			same &= w1[a] == w2[a];
		}
		/* A polygon hidden whole takes no samples where it has a list to
		 * find that in (pm_comp_hidden_whole), and is sampled where what
		 * x' sees of it goes through the tree. */
		tw.differ += !(s1 > 0 && same && st1.hidden == st2.hidden && st1.skipped == st2.skipped &&
		               st1.sampled + st1.whole == st2.sampled + st2.whole);
		tw.minpolys = st1.polys < tw.minpolys ? st1.polys : tw.minpolys;
		tw.cast[0] += st1.cast;
		tw.cast[1] += st2.cast;
		tw.shadowed[0] += st1.shadowed;
		tw.shadowed[1] += st2.shadowed;
		tw.waited[0] += st1.waited;
		tw.waited[1] += st2.waited;
		tw.fcast[0] += st1.fcast;
		tw.fcast[1] += st2.fcast;
	}
	set(-1);
	pm_comp_scratch_free(sc);
	pm_polyindex_free(pi);
	tp_free(&p);
	return tw;
}

/* -1: the default. */
static void
set_cast_at(int on)
{
	pm_comp_cast_at = on < 0 ? 16 : on ? 9 : INT_MAX;
}

static void
set_shadow_from(int on)
{
	pm_comp_shadow_from = on < 0 ? 6 : on ? 1 : INT_MAX;
}

/* A polygon of a large cube with many that may hide it keeps no list, and
 * what x' sees of it is found through a tree (pm_comp_cast_at): the
 * weights must be the very same as with every list kept, on a floor under
 * a cloud of 60 triangles (fates by lists) and of 150 (by rays), and
 * the tree must have been asked. */
TEST(tree_sees_what_the_lists_see)
{
	static tscene t;
	long casts = 0;
	for (int ntri = 60; ntri <= 150; ntri += 90) {
		floor_under_cloud(&t, 0, ntri, 0.06);
		twins tw = twin_weights(&t, 33 + (uint64_t)ntri, set_cast_at);
		casts += tw.cast[1];
		CHECKF(tw.cast[0] == 0 && tw.minpolys >= 32, "cloud %d: %d polygons, %ld cast", ntri,
		       tw.minpolys, tw.cast[0]);
		CHECKF(tw.differ == 0, "cloud %d: weights differ in %d of 20 estimates", ntri, tw.differ);
	}
	CHECKF(casts > 40, "only %ld polygons went through the tree", casts);
}

/* A photon's fate test passes over the sample points outside a polygon's
 * shadow (pm_comp_shadow_from): the weights must be the very same as
 * testing every point, under clouds of 60 triangles of two sizes (fates
 * followed, many points whose fate depends on the direction), and points
 * must have been passed over. */
TEST(shadow_box_drops_no_hit)
{
	static tscene t;
	long shadowed = 0;
	for (int c = 0; c < 2; c++) {
		floor_under_cloud(&t, 0, 60, c ? 0.02 : 0.06);
		twins tw = twin_weights(&t, 35 + (uint64_t)c, set_shadow_from);
		shadowed += tw.shadowed[1];
		CHECKF(tw.shadowed[0] == 0 && tw.minpolys > 1, "cloud %d: %d polygons, %ld passed over", c,
		       tw.minpolys, tw.shadowed[0]);
		CHECKF(tw.differ == 0, "cloud %d: weights differ in %d of 20 estimates", c, tw.differ);
	}
	CHECKF(shadowed > 10000, "only %ld sample points passed over", shadowed);
}

/* A closed box (a solid) from lo to hi, its faces' normals outward. */
static void
ts_box(tscene *t, int obj, pm_vec3 lo, pm_vec3 hi)
{
	float dx = hi.x - lo.x, dy = hi.y - lo.y, dz = hi.z - lo.z;
	ts_rect(t, obj, lo, pm_v3(0, dy, 0), pm_v3(dx, 0, 0));
	ts_rect(t, obj, pm_v3(lo.x, lo.y, hi.z), pm_v3(dx, 0, 0), pm_v3(0, dy, 0));
	ts_rect(t, obj, lo, pm_v3(dx, 0, 0), pm_v3(0, 0, dz));
	ts_rect(t, obj, pm_v3(lo.x, hi.y, lo.z), pm_v3(0, 0, dz), pm_v3(dx, 0, 0));
	ts_rect(t, obj, lo, pm_v3(0, 0, dz), pm_v3(0, dy, 0));
	ts_rect(t, obj, pm_v3(hi.x, lo.y, lo.z), pm_v3(0, dy, 0), pm_v3(0, 0, dz));
}

/* n blocks (solids) of half-width b0 to b0 + 0.01 at rho0 to rho0 + drho
 * from the origin, around the estimates' x (|x|, |y| < 0.03) and none over
 * one: every other one standing on the floor, the rest sunk into it. */
static void
blocks_around(tscene *t, pm_rng *r, int n, double rho0, double drho, double b0)
{
	for (int i = 0; i < n; i++) {
		double a = 2 * PM_PI * rnd(r), rho = rho0 + drho * rnd(r), b = b0 + 0.01 * rnd(r);
		double x = rho * cos(a), y = rho * sin(a);
		double z0 = i % 2 ? 0 : -0.01 * rnd(r), z1 = 0.01 + 0.05 * rnd(r);
		ts_box(t, ts_object(t, 1, 0), pm_v3((float)(x - b), (float)(y - b), (float)z0),
		       pm_v3((float)(x + b), (float)(y + b), (float)z1));
	}
}

/* pm_comp_fate_cast_from as the library sets it, for the settings below
 * to restore. */
static int fate_cast_default;

/* Fronts wait where fates go by lists, as they do for these cubes of
 * under 100 polygons with rays off. */
static void
set_fronts_wait(int on)
{
	pm_comp_fronts_wait = on < 0 ? 1 : on;
	pm_comp_fate_cast_from = on < 0 ? fate_cast_default : INT_MAX;
}

/* The fronts of solids met from behind wait for the sample points
 * something else met (pm_comp_fronts_wait): the weights must be the very
 * same as testing them with the rest, on a floor with blocks standing on
 * it and sunk into it (solids the floor lies partly behind) under a cloud
 * of triangles (what else a backward ray meets, before or after a block),
 * and fronts must have waited. */
TEST(fronts_wait_change_nothing)
{
	static tscene t;
	long waited = 0;
	for (int c = 0; c < 2; c++) {
		pm_rng r = pm_rng_seed(77, (uint64_t)c);
		floor_under_cloud(&t, 0, 40, c ? 0.02 : 0.04);
		blocks_around(&t, &r, 6, 0.06, 0.03, 0.005);
		twins tw = twin_weights(&t, 37 + (uint64_t)c, set_fronts_wait);
		waited += tw.waited[1];
		CHECKF(tw.waited[0] == 0 && tw.minpolys > 1, "scene %d: %d polygons, %ld waited", c, tw.minpolys,
		       tw.waited[0]);
		CHECKF(tw.differ == 0, "scene %d: weights differ in %d of 20 estimates", c, tw.differ);
	}
	CHECKF(waited > 1000, "only %ld fronts waited", waited);
}

/* A shelf of books: boxes (solids) of different heights and widths in a
 * row on the floor, touching or 1 mm apart; with one, all one solid (not
 * convex). Returns how many; top[i] is book i's top face (its rectangle). */
static int
books(tscene *t, pm_rng *r, int *top, int max, int one)
{
	int nb = 0, obj = -1;
	double x0 = -0.07;
	ts_floor(t);
	while (x0 < 0.07 && nb < max) {
		double w = 0.008 + 0.012 * rnd(r), hgt = 0.03 + 0.02 * rnd(r);
		top[nb++] = t->nrect + 1;
		if (!one || obj < 0)
			obj = ts_object(t, 1, 0);
		ts_box(t, obj, pm_v3((float)x0, -0.03f, 0), pm_v3((float)(x0 + w), 0.03f, (float)hgt));
		x0 += w + (rnd(r) < 0.5 ? 0 : 0.001);
	}
	return nb;
}

/* A polygon one other hides whole from x' takes no lists and no samples
 * (pm_comp_hidden_whole): the weights must be the very same as sampling
 * it, for estimates on the tops of a shelf of books whose every face is
 * lit (the sides in the gaps between books hidden by x's own top, and by
 * the neighbours), the books apart and all one solid, and polygons must
 * have been found hidden whole. */
TEST(hidden_whole_changes_nothing)
{
	static tscene t;
	static double w1[K], w2[K];
	long whole[2] = {0, 0};
	int differ = 0, top[12];
	for (int c = 0; c < 4; c++) {
		pm_rng r = pm_rng_seed(91, (uint64_t)c);
		tphotons p = {.flux = 1e-3};
		int nb = books(&t, &r, top, 12, c >= 2);
		for (int i = 0; i < t.nrect; i++) {
			pm_vec3 N = pm_norm(pm_cross(t.ru[i], t.rv[i]));
			for (int j = 0; j < (i == 0 ? 2000 : 60); j++)
				tp_rect(&p, &t, i, 1, pm_sample_cosine(N, pm_rng_f(&r), pm_rng_f(&r)), &r, 0);
		}
		pm_polyindex *pi = index_of(&t);
		pm_comp_scratch *sc = pm_comp_scratch_new(K);
		for (int q = 0; q < 40; q++) {
			int b = top[(int)(rnd(&r) * nb) % nb];
			double a = 0.05 + 0.9 * rnd(&r), e = 0.05 + 0.9 * rnd(&r), sum = 0;
			pm_vec3 x = pm_add(t.ro[b], pm_add(pm_scale(t.ru[b], (float)a), pm_scale(t.rv[b], (float)e)));
			pm_comp_stats st1, st2;
			int n = weigh_twice(&p, x, UP, K, pi, pi, &pm_comp_hidden_whole, sc, w1, w2, &st1, &st2), same = 1;
			for (int i = 0; i < n; i++) {
				sum += w1[i];
				same &= w1[i] == w2[i];
			}
			differ += !(sum > 0 && same && st1.hidden == st2.hidden && st1.skipped == st2.skipped &&
			            st1.polys == st2.polys);
			whole[0] += st1.whole;
			whole[1] += st2.whole;
		}
		pm_comp_scratch_free(sc);
		pm_polyindex_free(pi);
		tp_free(&p);
	}
	CHECKF(differ == 0, "weights differ in %d of 160 estimates", differ);
	CHECKF(whole[0] == 0 && whole[1] > 100, "polygons hidden whole: %ld off, %ld on", whole[0], whole[1]);
}

/* Rays with set(1), lists with set(0), both counting every area by its
 * sample points (pm_comp_exact_overlap 0: rays know no single blocker). */
static void
set_fate_cast(int on)
{
	pm_comp_fate_cast_from = on < 0 ? fate_cast_default : on ? 97 : INT_MAX;
	pm_comp_exact_overlap = on < 0;
}

/* In a cube of 97 polygons or more (here) the fates of a polygon's points
 * are found by rays through a tree of the cube's polygons, not from lists
 * (pm_comp_fate_cast_from): the weights must be the very same as with the
 * lists, under clouds of 150 triangles of two sizes, alone and with blocks
 * (solids: backs met, fronts that open a ray, solids closed) standing on
 * and sunk into the floor, and some polygons' fates must have gone by rays. */
TEST(rays_find_the_fates_the_lists_find)
{
	static tscene t;
	long fcast = 0;
	for (int c = 0; c < 4; c++) {
		pm_rng r = pm_rng_seed(79, (uint64_t)c);
		floor_under_cloud(&t, 0, 150, c % 2 ? 0.02 : 0.05);
		blocks_around(&t, &r, c < 2 ? 0 : 8, 0.045, 0.04, 0.004);
		/* set(0) lists, set(1) rays: the rays' counts come second. */
		twins tw = twin_weights(&t, 41 + (uint64_t)c, set_fate_cast);
		fcast += tw.fcast[1];
		CHECKF(tw.fcast[0] == 0 && tw.minpolys >= 97, "scene %d: %d polygons, %ld by rays with lists", c,
		       tw.minpolys, tw.fcast[0]);
		CHECKF(tw.differ == 0, "scene %d: weights differ in %d of 20 estimates", c, tw.differ);
	}
	CHECKF(fcast > 1000, "only %ld polygons' fates went by rays", fcast);
}

/* A closed ball of radius 0.03 (its outside the front; the poles' quads
 * are triangles). Its quads are trapezoids, flat: on_quad()'s
 * parallelogram can leave them, bilinear() cannot. */
static pm_vec3
ball(double u, double v)
{
	double t = 2 * PM_PI * u, f = PM_PI * (v - 0.5);
	return pm_v3((float)(0.03 * cos(f) * sin(t)), (float)(0.03 * sin(f)), (float)(0.03 * cos(f) * cos(t)));
}

static pm_vec3
bilinear(const tmesh *m, uint32_t q, double s, double t)
{
	const uint32_t *v = m->vidx + 4 * q;
	pm_vec3 a = m->verts[v[0]], b = m->verts[v[1]], c = m->verts[v[2]], e = m->verts[v[3]];
	return pm_add(pm_add(pm_scale(a, (float)((1 - s) * (1 - t))), pm_scale(b, (float)(s * (1 - t)))),
	              pm_add(pm_scale(c, (float)(s * t)), pm_scale(e, (float)((1 - s) * t))));
}

/* A convex surface's sheets: where a cube on a ball not much larger than
 * the cube holds a hundred polygons or more in several sheets (it bends
 * past 45 degrees there, and takes in faces turned away from x'), fates
 * go by rays, and a facet behind whose plane every other group lies needs
 * none (no ray leaving it meets them): it is as plain as its lists leave
 * it. The weights must be the very same with lists and with rays, and
 * rays must leave the same facets unsampled as lists do (before, every lit
 * facet of such a cube was sampled and its points' rays followed, and the
 * weights differed from the lists' by rounding in 10 of 40 estimates). */
TEST(convex_sheets_need_no_fates)
{
	static int idx[4096];
	static pm_vec3 pos[4096], dir[4096];
	static double w1[K], w2[K];
	tmesh m;
	tphotons p = {0};
	pm_rng r = pm_rng_seed(9, 11);
	pm_vec3 d = unit(0.25, 0.1, 0.96);
	pm_polyindex *pi;
	pm_error err;
	long sampled[2] = {0, 0};
	int differ = 0, cast_cubes = 0;

	tm_grid(&m, 96, 48, ball);
	m.obj.solid = 1;
	/* 150 photons over the lit side, by area times the cosine (by
	 * rejection against 4e-6, just over the largest quad's area): cubes
	 * of 50 a third of the ball across, hundreds of facets each. */
	p.flux = 1e-3;
	for (int n = 0; n < 150;) {
		uint32_t q = (uint32_t)(rnd(&r) * m.s.npolys);
		const uint32_t *v = m.vidx + 4 * q;
		pm_vec3 a = m.verts[v[0]], b = m.verts[v[1]], c = m.verts[v[2]], e = m.verts[v[3]];
		double area = 0.5 * pm_len(pm_cross(pm_sub(c, a), pm_sub(e, b))), cs = pm_dot(m.normal[q], d);
		if (!(cs > 0) || rnd(&r) * 4e-6 > area * cs)
			continue;
		double s = rnd(&r), t = rnd(&r);
		tp_add(&p, bilinear(&m, q, s, t), d, 0);
		n++;
	}
	CHECK(pm_polyindex_build(&pi, &m.s, m.verts, &err) == 0);
	pm_comp_scratch *sc = pm_comp_scratch_new(K);
	for (int n = 0; n < 40;) {
		uint32_t q = (uint32_t)(rnd(&r) * m.s.npolys);
		if (pm_dot(m.normal[q], d) < 0.3)
			continue;
		double s = rnd(&r), t = rnd(&r);
		pm_vec3 x = bilinear(&m, q, s, t);
		pm_comp_stats st1, st2;
		double dfar;
		int k = knn(&p, x, K, linf, idx, &dfar), same = 1;
		for (int a = 0; a < k; a++) {
			pos[a] = p.pos[idx[a]];
			dir[a] = p.dir[idx[a]];
		}
		set_fate_cast(0);
		pm_comp_weights(pi, x, m.normal[q], pos, dir, k, 0, sc, w1, &st1);
		set_fate_cast(1);
		pm_comp_weights(pi, x, m.normal[q], pos, dir, k, 0, sc, w2, &st2);
		set_fate_cast(-1);
		for (int a = 0; a < k; a++)
			same &= w1[a] == w2[a];
		differ += !same || st1.hidden != st2.hidden || st1.skipped != st2.skipped;
		if (st2.polys >= 97 && st2.groups >= 2) {
			cast_cubes++;
			sampled[0] += st1.sampled;
			sampled[1] += st2.sampled;
		}
		n++;
	}
	CHECKF(differ == 0, "weights differ in %d of 40 estimates", differ);
	CHECKF(cast_cubes >= 20, "only %d of 40 cubes with fates by rays", cast_cubes);
	/* 159 both (11 141 by rays before). */
	CHECKF(sampled[1] == sampled[0], "%ld polygons sampled with rays, %ld with lists", sampled[1], sampled[0]);
	pm_comp_scratch_free(sc);
	pm_polyindex_free(pi);
	tp_free(&p);
	tm_free(&m);
}

/* Sample cells resolve the cube, not the mesh: a floor of tiles 1/32
 * across (flat2() at 64 x 64), each about a thousandth of the cube's
 * face, and a wall across it at y = 0.2 (off the tiles' rows) that hides
 * the floor beyond it from x' and may meet backward rays from the floor
 * in front. Photons arriving
 * straight down meet nothing, so their target area is the floor x' sees:
 * the cube's width times the depth up to the wall, exactly. The tiles are
 * sampled (every one has fates), one cell each, and the area must be the
 * exact one to within the row of tiles the wall stands on (before, each
 * tile had 2 x 2 cells: four times the points for a finer answer than a
 * tile of a cube's size ever gets). */
TEST(tiny_tiles_one_cell_each)
{
	static pm_vec3 pos[4096], dir[4096];
	static double w[4096];
	tmesh m;
	tphotons p = {0};
	pm_rng r = pm_rng_seed(31, 7);
	pm_polyindex *pi;
	pm_error err;
	const double h = 0.45, wall = 0.2, row = 1.0 / 32;
	const pm_vec3 x = pm_v3(0.013f, -0.021f, 0);

	tm_grid(&m, 64, 64, flat2);
	/* The wall: one more quad of the mesh, facing x (-y), its bottom
	 * edge on the floor, higher than the cube. */
	uint32_t nv = m.s.nverts, q = m.s.npolys;
	m.verts = realloc(m.verts, (nv + 4) * sizeof *m.verts);
	m.normal = realloc(m.normal, (q + 1) * sizeof *m.normal);
	m.start = realloc(m.start, (q + 2) * sizeof *m.start);
	m.vidx = realloc(m.vidx, 4 * (q + 1) * sizeof *m.vidx);
	m.pobj = realloc(m.pobj, (q + 1) * sizeof *m.pobj);
	CHECK(m.verts && m.normal && m.start && m.vidx && m.pobj);
	m.verts[nv] = pm_v3(-0.6f, (float)wall, 0);
	m.verts[nv + 1] = pm_v3(0.6f, (float)wall, 0);
	m.verts[nv + 2] = pm_v3(0.6f, (float)wall, 1);
	m.verts[nv + 3] = pm_v3(-0.6f, (float)wall, 1);
	for (int i = 0; i < 4; i++)
		m.vidx[4 * q + i] = nv + (uint32_t)i;
	m.normal[q] = pm_v3(0, -1, 0);
	m.pobj[q] = 0;
	m.start[q + 1] = m.start[q] + 4;
	m.s.verts = m.verts;
	m.s.poly_normal = m.normal;
	m.s.poly_start = m.start;
	m.s.poly_vert = m.vidx;
	m.s.poly_obj = m.pobj;
	m.s.nverts = nv + 4;
	m.s.npolys = q + 1;
	CHECK(pm_polyindex_build(&pi, &m.s, m.verts, &err) == 0);

	p.flux = 1e-3;
	for (int i = 0; i < 400; i++)
		tp_add(&p, pm_v3((float)(rnd(&r) - 0.5), (float)(rnd(&r) - 0.5), 0), UP, 0);
	int in = 0;
	for (int i = 0; i < p.n; i++)
		if (linf(p.pos[i], x) < h) {
			pos[in] = p.pos[i];
			dir[in++] = p.dir[i];
		}
	pm_comp_scratch *sc = pm_comp_scratch_new(in);
	pm_comp_stats st;
	pm_comp_weights_cube(pi, x, UP, pos, dir, in, h, sc, w, &st);

	double exact = 2 * h * (wall - (x.y - h)), worst = 0;
	int front = 0, wrong = 0;
	for (int i = 0; i < in; i++) {
		double y = pos[i].y;
		if (y < wall - row) {
			front++;
			if (!(w[i] > 0))
				wrong++;
			else
				worst = fmax(worst, fabs(1 / w[i] - exact));
		} else if (y > wall + row)
			wrong += w[i] != 0;
	}
	CHECKF(st.polys > 700 && st.sampled > 700, "%d polygons, %d sampled", st.polys, st.sampled);
	CHECKF(st.cells == st.sampled, "%d cells on %d polygons", st.cells, st.sampled);
	CHECKF(front > 100 && wrong == 0, "%d of %d photons in front of the wall or behind it wrong", wrong,
	       front);
	CHECKF(worst <= 2 * h * row, "target area off by %g of %g (a row of tiles: %g)", worst, exact,
	       2 * h * row);
	pm_comp_scratch_free(sc);
	pm_polyindex_free(pi);
	tp_free(&p);
	tm_free(&m);
}

/* The triangle a, b, c as a rectangle's corner and edges (ts_rect()'s
 * ro, ru, rv; its points are those with both coordinates' sum <= 1). */
static int
ts_tri(tscene *t, int obj, pm_vec3 a, pm_vec3 b, pm_vec3 c)
{
	pm_vec3 q[3] = {a, b, c};
	ts_poly(t, obj, 3, q);
	t->ro[t->nrect] = a;
	t->ru[t->nrect] = pm_sub(b, a);
	t->rv[t->nrect] = pm_sub(c, a);
	return t->nrect++;
}

/* A point of rectangle (or, with tri, triangle) i at coordinates drawn
 * from r. */
static pm_vec3
on_piece(const tscene *t, int i, int tri, pm_rng *r)
{
	double a = 0.02 + 0.96 * rnd(r), e = 0.02 + 0.96 * rnd(r);
	if (tri && a + e > 1) {
		a = 1 - a;
		e = 1 - e;
	}
	return pm_add(t->ro[i], pm_add(pm_scale(t->ru[i], (float)a), pm_scale(t->rv[i], (float)e)));
}

/* A height field z = a sin(f x + p) cos(g y + q) over [-1, 1]^2 as 11 x 11
 * quads of two triangles each (split along either diagonal), a up to
 * 0.03 + amax and f, g, p, q drawn from r, into object obj. */
static void
ts_bumps(tscene *t, int obj, double amax, int diag, pm_rng *r)
{
	double amp = 0.03 + amax * rnd(r), f = 1 + 3 * rnd(r), g = 1 + 3 * rnd(r);
	double ph = 6.3 * rnd(r), qh = 6.3 * rnd(r);
	pm_vec3 v[12][12];
	for (int i = 0; i <= 11; i++)
		for (int j = 0; j <= 11; j++) {
			double x = -1 + 2 * i / 11.0, yy = -1 + 2 * j / 11.0;
			v[i][j] = pm_v3((float)x, (float)yy, (float)(amp * sin(f * x + ph) * cos(g * yy + qh)));
		}
	for (int i = 0; i < 11; i++)
		for (int j = 0; j < 11; j++) {
			pm_vec3 a = v[i][j], b = v[i + 1][j], d = v[i + 1][j + 1], e = v[i][j + 1];
			if (diag) {
				ts_tri(t, obj, a, b, d);
				ts_tri(t, obj, a, d, e);
			} else {
				ts_tri(t, obj, a, b, e);
				ts_tri(t, obj, b, d, e);
			}
		}
}

typedef struct sheet_tally {
	int estimates, differ, counted, withnodes;
	long nodes[2];
} sheet_tally;

/* One photon on each piece of t (cosine about its normal), then count
 * estimates at points of random pieces, each weighed with
 * pm_comp_sheet_nodes off and on: the weights must agree within 1e-9 of
 * their sum, with the same hidden, skipped and polygon counts. */
static void
sheet_both_ways(const tscene *t, int tri, int count, pm_rng *r, sheet_tally *y)
{
	static double w1[K], w2[K];
	tphotons p = {.flux = 1e-3};
	for (int i = 0; i < t->nrect; i++) {
		pm_vec3 N = pm_norm(pm_cross(t->ru[i], t->rv[i]));
		tp_add(&p, on_piece(t, i, tri, r), pm_sample_cosine(N, pm_rng_f(r), pm_rng_f(r)), i);
	}
	pm_polyindex *pi = index_of(t);
	pm_comp_scratch *sc = pm_comp_scratch_new(K);
	for (int q = 0; q < count; q++) {
		int b = (int)(rnd(r) * t->nrect) % t->nrect;
		pm_vec3 x = on_piece(t, b, tri, r), nx = pm_norm(pm_cross(t->ru[b], t->rv[b]));
		pm_comp_stats st1, st2;
		double sum = 0, dmx = 0;
		int n = weigh_twice(&p, x, nx, K, pi, pi, &pm_comp_sheet_nodes, sc, w1, w2, &st1, &st2);
		for (int i = 0; i < n; i++) {
			sum += w1[i];
			dmx = fmax(dmx, fabs(w1[i] - w2[i]));
			y->counted += w1[i] > 0;
		}
		y->differ += !(sum > 0 && dmx <= 1e-9 * sum && st1.hidden == st2.hidden &&
		               st1.skipped == st2.skipped && st1.polys == st2.polys);
		y->withnodes += st2.nodes > 0;
		y->nodes[0] += st1.nodes;
		y->nodes[1] += st2.nodes;
		y->estimates++;
	}
	pm_comp_scratch_free(sc);
	pm_polyindex_free(pi);
	tp_free(&p);
}

/* A cube of one curved sheet takes the polygon index's nodes that lie
 * wholly inside it as one piece each (pm_comp_sheet_nodes): the weights
 * must be those of the polygons one by one, up to rounding, on a trough
 * z = c x^2 of 16 x 16 quads (one smooth patch, open or solid, photons
 * sparse enough that cubes hold dozens of quads), and on a solid ridge
 * (c < 0: x' lies behind the planes of x's own nearly flat neighbours,
 * which count all the same), and nodes must have been taken whole. */
TEST(sheet_nodes_as_polygons_say)
{
	static tscene t;
	sheet_tally y = {0};
	for (int c = 0; c < 6; c++) {
		pm_rng r = pm_rng_seed(57, (uint64_t)c);
		double curve = (c & 1 ? 0.6 : 0.25) * (c >= 4 ? -1 : 1);
		ts_init(&t);
		int obj = ts_object(&t, c >= 2, 0);
		for (int i = 0; i < 16; i++)
			for (int j = 0; j < 16; j++) {
				double x0 = -1 + i / 8.0, x1 = x0 + 1 / 8.0, y0 = -1 + j / 8.0;
				pm_vec3 o = pm_v3((float)x0, (float)y0, (float)(curve * x0 * x0));
				pm_vec3 u = pm_v3((float)(x1 - x0), 0, (float)(curve * (x1 * x1 - x0 * x0)));
				ts_rect(&t, obj, o, u, pm_v3(0, 1 / 8.0f, 0));
			}
		sheet_both_ways(&t, 0, 40, &r, &y);
	}
	CHECKF(y.differ == 0, "weights differ in %d of %d estimates", y.differ, y.estimates);
	CHECKF(y.nodes[0] == 0 && y.nodes[1] > 0, "nodes taken whole: %ld off, %ld on", y.nodes[0], y.nodes[1]);
	CHECKF(y.withnodes >= 20, "estimates with nodes taken whole: %d of %d", y.withnodes, y.estimates);
	CHECKF(y.counted > y.estimates * 20, "photons counted: %d", y.counted);
}

/* The same on generated bumps: z = a sin(f x + p) cos(g y + q) over
 * [-1, 1]^2 in 11 x 11 cells of two triangles each, amplitude and
 * frequencies drawn per scene (gentle swells to folds that bend past a
 * sheet within a cube, saddles, ridges), open and solid, the diagonal
 * either way. */
TEST(sheet_nodes_on_random_bumps)
{
	static tscene t;
	sheet_tally y = {0};
	for (int c = 0; c < 16; c++) {
		pm_rng r = pm_rng_seed(73, (uint64_t)c);
		ts_init(&t);
		ts_bumps(&t, ts_object(&t, c & 1, 0), 0.8, c & 2, &r);
		sheet_both_ways(&t, 1, 20, &r, &y);
	}
	CHECKF(y.differ == 0, "weights differ in %d of %d estimates", y.differ, y.estimates);
	CHECKF(y.nodes[0] == 0 && y.nodes[1] > 0, "nodes taken whole: %ld off, %ld on", y.nodes[0], y.nodes[1]);
	CHECKF(y.withnodes >= 20, "estimates with nodes taken whole: %d of %d", y.withnodes, y.estimates);
	CHECKF(y.counted > y.estimates * 20, "photons counted: %d", y.counted);
}

/* t: generated bumps (ts_bumps(), of a solid or not, amplitude up to
 * 0.03 + amax, diagonal diag) and, with ceiling, a ceiling over them at
 * z = 0.45; into p, one photon on about one bump triangle in two, its
 * direction cosine-distributed about the triangle's normal. Returns the
 * bump triangles (pieces 0 to that less one). */
static int
bumps_lit(tscene *t, pm_rng *r, int solid, double amax, int diag, int ceiling, tphotons *p)
{
	ts_init(t);
	ts_bumps(t, ts_object(t, solid, 0), amax, diag, r);
	int nb = t->nrect;
	if (ceiling)
		ts_rect(t, ts_object(t, 0, 0), pm_v3(-1, -1, 0.45f), pm_v3(0, 2, 0), pm_v3(2, 0, 0));
	for (int i = 0; i < nb; i++)
		if (rnd(r) < 0.5) {
			pm_vec3 N = pm_norm(pm_cross(t->ru[i], t->rv[i]));
			tp_add(p, on_piece(t, i, 1, r), pm_sample_cosine(N, pm_rng_f(r), pm_rng_f(r)), i);
		}
	return nb;
}

/* A point on one of the first nb pieces of t, drawn at random, and that
 * piece's normal. */
static pm_vec3
on_some(const tscene *t, int nb, pm_rng *r, pm_vec3 *n)
{
	int b = (int)(rnd(r) * nb) % nb;
	pm_vec3 x = on_piece(t, b, 1, r);
	*n = pm_norm(pm_cross(t->ru[b], t->rv[b]));
	return x;
}

/* Where fates go by rays, small facets of a sheet take the backward rays
 * of their cell's first facet (pm_comp_share_cells). Generated bumps of
 * 242 triangles under a ceiling (two groups), photons on about one facet
 * in two, so that a cube of K holds a hundred facets each smaller than a
 * sample cell: sharing must take place in most estimates and never with
 * the switch off, and with and without it the estimates (sums of weights)
 * must agree as points a cell apart do: within 5 % on average and 10 % in
 * nine estimates of ten. (Where most photons are hidden from x', the few
 * left can move by more: a facet's fate is one point's either way; but
 * by less than 60 % where only facets facing alike share, SHARE_COS:
 * 127 % without that rule, 40 % with it.) */
TEST(shared_points_on_random_bumps)
{
	static tscene t;
	static double w1[K], w2[K];
	double dsum = 0, dmax = 0;
	int estimates = 0, engaged = 0, leaked = 0, close = 0;
	for (int c = 0; c < 16; c++) {
		pm_rng r = pm_rng_seed(79, (uint64_t)c);
		tphotons p = {.flux = 1e-3};
		int nb = bumps_lit(&t, &r, 0, 0.25, 0, 1, &p);
		pm_polyindex *pi = index_of(&t);
		pm_comp_scratch *sc = pm_comp_scratch_new(K);
		for (int q = 0; q < 20; q++) {
			pm_vec3 nx, x = on_some(&t, nb, &r, &nx);
			pm_comp_stats st1, st2;
			double s1 = 0, s2 = 0;
			int n = weigh_twice(&p, x, nx, K, pi, pi, &pm_comp_share_cells, sc, w1, w2, &st1, &st2);
			for (int i = 0; i < n; i++) {
				s1 += w1[i];
				s2 += w2[i];
			}
			if (!(s1 > 0) && !(s2 > 0))
				continue;       /* every photon hidden from x' either way */
			double d = s1 > 0 ? fabs(s2 - s1) / s1 : 1;
			dsum += d;
			dmax = fmax(dmax, d);
			close += d <= 0.10;
			engaged += st2.shared > 0;
			leaked += st1.shared > 0;
			estimates++;
		}
		pm_comp_scratch_free(sc);
		pm_polyindex_free(pi);
		tp_free(&p);
	}
	printf("# shared points: %d of %d estimates, mean |difference| %.4f, max %.4f\n", engaged, estimates,
	       dsum / estimates, dmax);
	CHECKF(leaked == 0, "shared with the switch off in %d estimates", leaked);
	CHECKF(engaged >= estimates / 2, "shared in %d of %d estimates", engaged, estimates);
	CHECKF(dsum / estimates <= 0.05 && close >= 0.9 * estimates, "mean |difference| %.4f, within 10 %%: %d of %d",
	       dsum / estimates, close, estimates);
	CHECKF(dmax <= 0.6, "largest |difference| %.4f", dmax);
}

/* A photon's polygon found among its cell's of a grid over the cube
 * (pm_comp_photon_grid) must be the one every plane of its groups gives:
 * the very same weights, on generated bumps of 242 triangles, folded
 * (sheets peeled) and gentle under a ceiling (two groups), photons on
 * about one facet in two, estimates on the bumps; and cubes past the
 * grid's 48 polygons must have been most of them. */
TEST(photon_grid_changes_nothing)
{
	static tscene t;
	static double w1[K], w2[K];
	int estimates = 0, differ = 0, many = 0;
	for (int c = 0; c < 8; c++) {
		pm_rng r = pm_rng_seed(83, (uint64_t)c);
		tphotons p = {.flux = 1e-3};
		int nb = bumps_lit(&t, &r, c & 1, c & 2 ? 0.8 : 0.25, c & 4, !(c & 2), &p);
		pm_polyindex *pi = index_of(&t);
		pm_comp_scratch *sc = pm_comp_scratch_new(K);
		for (int q = 0; q < 20; q++) {
			pm_vec3 nx, x = on_some(&t, nb, &r, &nx);
			pm_comp_stats st1, st2;
			int n = weigh_twice(&p, x, nx, K, pi, pi, &pm_comp_photon_grid, sc, w1, w2, &st1, &st2), same = 1;
			for (int i = 0; i < n; i++)
				same &= w1[i] == w2[i];
			differ += !(same && st1.hidden == st2.hidden && st1.polys == st2.polys);
			many += st1.polys >= 48 && st1.groups > 1;
			estimates++;
		}
		pm_comp_scratch_free(sc);
		pm_polyindex_free(pi);
		tp_free(&p);
	}
	CHECKF(differ == 0, "weights differ in %d of %d estimates", differ, estimates);
	CHECKF(many >= estimates / 2, "cubes of 48 polygons or more in two groups or more: %d of %d", many, estimates);
}

int
main(void)
{
	fate_cast_default = pm_comp_fate_cast_from;
	RUN(floor_one_direction);
	RUN(floor_shrunk_cube);
	RUN(floor_random_directions);
	RUN(concave_edge);
	RUN(concave_edge_random_directions);
	RUN(room_corner);
	RUN(convex_edge_solid);
	RUN(standing_on_floor_and_rug);
	RUN(solid_of_several_parts);
	RUN(thin_walls);
	RUN(boundary_shell);
	RUN(all_photons_at_one_point);
	RUN(no_target_area_skipped);
	RUN(target_area_floor);
	RUN(grazing_photons);
	RUN(fewer_photons_than_k);
	RUN(photons_not_finite_unused);
	RUN(translation_and_scale);
	RUN(polyindex_matches_brute_force);
	RUN(full_estimate_matches_core);
	RUN(support_discs_agree);
	RUN(tessellated_floor_is_one_quad);
	RUN(curved_sheet_parallel_beam);
	RUN(bent_patch_peeled_into_sheets);
	RUN(thin_tube_sides_apart);
	RUN(floor_twice_under_many_groups);
	RUN(short_paths_match_the_general_one);
	RUN(tree_sees_what_the_lists_see);
	RUN(shadow_box_drops_no_hit);
	RUN(fronts_wait_change_nothing);
	RUN(hidden_whole_changes_nothing);
	RUN(sheet_nodes_as_polygons_say);
	RUN(sheet_nodes_on_random_bumps);
	RUN(shared_points_on_random_bumps);
	RUN(photon_grid_changes_nothing);
	RUN(rays_find_the_fates_the_lists_find);
	RUN(convex_sheets_need_no_fates);
	RUN(tiny_tiles_one_cell_each);
	return check_done();
}

