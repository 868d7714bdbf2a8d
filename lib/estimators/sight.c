/* sight.c — polygons' directions from a point, and a grid of them (sight.h). */
#include "estimators/sight.h"

#include <math.h>
#include <stdlib.h>

#include "base/grow.h"

#define C PM_SIGHT_CELLS
#define NCELL (6 * C * C)
/* A box over more cells than this goes on the wide list. */
#define MAX_CELLS 32

static double
at(pm_dvec3 v, int a)
{
	return a == 0 ? v.x : a == 1 ? v.y : v.z;
}

/* The clipped polygons' vertices, at most; past it a polygon may meet any
 * direction (clipping by one plane can double a polygon that is not convex). */
#define CLIPV 96

/* Polygon v[0..n) clipped to the half-space wa x_a + wb x_b >= 0 (a
 * polygon that is not convex may come out with edges along the plane
 * that are not its own: its vertices still hold it). Returns the count
 * written to out, or -1 past CLIPV. */
static int
clip_half(const pm_dvec3 *v, int n, int a, double wa, int b, double wb, pm_dvec3 *out)
{
	int m = 0;

	for (int i = 0, j = n - 1; i < n; j = i++) {
		double gi = wa * at(v[i], a) + wb * at(v[i], b), gj = wa * at(v[j], a) + wb * at(v[j], b);
		if ((gj >= 0) != (gi >= 0)) {
			if (m == CLIPV)
				return -1;
			out[m++] = pm_dadd(v[j], pm_dscale(pm_dsub(v[i], v[j]), gj / (gj - gi)));
		}
		if (gi >= 0) {
			if (m == CLIPV)
				return -1;
			out[m++] = v[i];
		}
	}
	return m;
}

/* Vertices v[0..n) projected from the eye on the face of axis a and sign
 * s: the box of their two other coordinates over the axis one, widened by
 * what e moves a point. 0 if one lies within 2 e of the eye's plane (or
 * is NaN). */
static int
project(const pm_dvec3 *v, int n, pm_dvec3 eye, int a, double s, double e, double lo[2], double hi[2])
{
	double mmin = INFINITY, amax[2] = {0, 0};

	lo[0] = lo[1] = INFINITY;
	hi[0] = hi[1] = -INFINITY;
	for (int k = 0; k < n; k++) {
		pm_dvec3 d = pm_dsub(v[k], eye);
		double m = s * at(d, a);
		/* Also false for NaN. */
		if (!(m > 2 * e))
			return 0;
		mmin = m < mmin ? m : mmin;
		for (int i = 0; i < 2; i++) {
			double u = at(d, (a + 1 + i) % 3) / m;
			lo[i] = u < lo[i] ? u : lo[i];
			hi[i] = u > hi[i] ? u : hi[i];
			amax[i] = fabs(u) > amax[i] ? fabs(u) : amax[i];
		}
	}
	/* A point p + d (|d| <= e) of the polygon's neighbourhood: its u moves
	 * by (d_u - u d_m) / (m + d_m), at most e (1 + |u|) / (m - e); the
	 * polygon's points have m >= mmin and |u| within its vertices' (a
	 * central projection keeps segments straight). Rounding is far below
	 * the margin and the tolerance added to it. */
	double mg = e * (1 + amax[0] + amax[1]) / (mmin - e);
	mg += 1e-12 * (1 + amax[0] + amax[1]);
	for (int i = 0; i < 2; i++) {
		lo[i] -= mg;
		hi[i] += mg;
	}
	return 1;
}

/* Face f's box of polygon d[0..n) (relative to the eye): the part of it
 * in the pyramid |x_b|, |x_c| <= (1 + tau) s x_a, projected, widened by
 * what e moves a point (see pm_sight_box). 1: a box; 0: none of the
 * polygon is there; -1: a vertex there within 2 e of the eye's plane, or
 * too many vertices. */
static int
face_box(const pm_dvec3 *d, int n, int f, double tau, double e, double lo[2], double hi[2], pm_dvec3 *b0,
         pm_dvec3 *b1)
{
	int a = f / 2, m = n;
	double s = f & 1 ? -1 : 1;
	const pm_dvec3 *p = d;

	for (int k = 0; k < 4; k++) {
		pm_dvec3 *o = k & 1 ? b1 : b0;
		if ((m = clip_half(p, m, a, s * (1 + tau), (a + 1 + k / 2) % 3, k & 1 ? -1 : 1, o)) <= 0)
			return m;
		p = o;
	}
	return project(p, m, pm_dv3(0, 0, 0), a, s, e, lo, hi) ? 1 : -1;
}

/* Where the whole neighbourhood of polygon v[0..n) lies inside one face
 * (most polygons): the box on it, at the cost of a projection. 0 where it
 * does not. */
static int
one_face(const pm_dvec3 *v, int n, pm_dvec3 eye, double e, pm_sight *out)
{
	pm_dvec3 c = {0, 0, 0};
	double lo[2], hi[2];

	for (int k = 0; k < n; k++)
		c = pm_dadd(c, pm_dsub(v[k], eye));
	int a = fabs(c.x) >= fabs(c.y) && fabs(c.x) >= fabs(c.z) ? 0 : fabs(c.y) >= fabs(c.z) ? 1 : 2;
	double s = at(c, a) < 0 ? -1 : 1;
	if (!project(v, n, eye, a, s, e, lo, hi))
		return 0;
	/* Past the face's edge, directions belong to another face too. */
	for (int i = 0; i < 2; i++)
		if (!(lo[i] > -1 && hi[i] < 1))
			return 0;
	int f = 2 * a + (s < 0);
	out->face = f;
	out->mask = 1u << f;
	for (int i = 0; i < 2; i++) {
		out->lo[f][i] = lo[i];
		out->hi[f][i] = hi[i];
	}
	return 1;
}

void
pm_sight_box(const pm_dvec3 *v, int n, pm_dvec3 eye, double e, int across, pm_sight *out)
{
	pm_dvec3 d[CLIPV], b0[CLIPV], b1[CLIPV];
	double dist = 0;

	out->face = -1;
	out->mask = 0;
	if (one_face(v, n, eye, e, out) || !across || n > CLIPV)
		return;
	for (int i = 0; i < n; i++)
		d[i] = pm_dsub(v[i], eye);
	/* dist: a floor under the polygon's distance from the eye in the max
	 * norm: its box's, or its plane's over sqrt 3 (a polygon whose box
	 * reaches round the eye may lie well away from it). */
	pm_dvec3 N = {0, 0, 0}, c = {0, 0, 0};
	for (int i = 0, j = n - 1; i < n; j = i++) {
		N = pm_dadd(N, pm_dcross(d[j], d[i]));
		c = pm_dadd(c, d[i]);
	}
	double ln = pm_dlen(N);
	if (ln > 0)
		dist = 0.999 * fabs(pm_ddot(N, c)) / (ln * n * sqrt(3));
	double lo[3], hi[3];
	for (int k = 0; k < 3; k++) {
		lo[k] = INFINITY;
		hi[k] = -INFINITY;
		for (int i = 0; i < n; i++) {
			lo[k] = at(d[i], k) < lo[k] ? at(d[i], k) : lo[k];
			hi[k] = at(d[i], k) > hi[k] ? at(d[i], k) : hi[k];
		}
		double g = lo[k] > 0 ? lo[k] : hi[k] < 0 ? -hi[k] : 0;
		dist = g > dist ? g : dist;
	}
	/* Also false for NaN. */
	if (!(dist > 4 * e))
		return;
	/* A point q within e of the polygon whose direction lies on face f
	 * (s q_a >= |q_b|, |q_c|, and s q_a >= dist - e) is within e of a
	 * point p of the polygon with |p_b| <= |q_b| + e <= s q_a + e and
	 * s p_a >= s q_a - e, so |p_b| <= (1 + tau) s p_a for any tau >=
	 * 2 e / (dist - 2 e): p lies in the part face_box() projects. */
	double tau = 2.5 * e / (dist - 2 * e);
	for (int f = 0; f < 6; f++) {
		/* None of it on the axis's side of the face. */
		if (f & 1 ? lo[f / 2] >= 0 : hi[f / 2] <= 0)
			continue;
		int r = face_box(d, n, f, tau, e, out->lo[f], out->hi[f], b0, b1);
		if (r < 0) {
			out->mask = 0;
			return;
		}
		out->mask |= (unsigned)r << f;
	}
	if (out->mask)
		out->face = __builtin_ctz(out->mask);
}

/* The cells box f of b covers on its face: [c0, c1] in each coordinate
 * (a box past the face's edge, by the margin, keeps to its edge cells). */
static void
cells(const pm_sight *b, int f, int c0[2], int c1[2])
{
	for (int i = 0; i < 2; i++) {
		double l = b->lo[f][i] < -1 ? -1 : b->lo[f][i], h = b->hi[f][i] > 1 ? 1 : b->hi[f][i];
		int lo = (int)floor((l + 1) * 0.5 * C), hi = (int)floor((h + 1) * 0.5 * C);
		c0[i] = lo < 0 ? 0 : lo > C - 1 ? C - 1 : lo;
		c1[i] = hi < 0 ? 0 : hi > C - 1 ? C - 1 : hi;
	}
}

static int
many(const pm_sight *b)
{
	int c0[2], c1[2], n = 0;

	if (b->face < 0)
		return 1;
	for (unsigned m = b->mask; m; m &= m - 1) {
		cells(b, __builtin_ctz(m), c0, c1);
		n += (c1[0] - c0[0] + 1) * (c1[1] - c0[1] + 1);
	}
	return n > MAX_CELLS;
}

int
pm_sight_grid_build(pm_sight_grid *g, const pm_sight *s, int n)
{
	int c0[2], c1[2], total = 0;

	if (!pm_grow((void **)&g->start, &g->startcap, 0, NCELL + 1, sizeof *g->start) ||
	    !pm_grow((void **)&g->wide, &g->widecap, 0, n, sizeof *g->wide))
		return 0;
	for (int i = 0; i <= NCELL; i++)
		g->start[i] = 0;
	g->nwide = 0;
	/* Counts per cell, shifted one up, then their running sums. */
	for (int p = 0; p < n; p++) {
		if (many(&s[p])) {
			g->wide[g->nwide++] = p;
			continue;
		}
		for (unsigned m = s[p].mask; m; m &= m - 1) {
			int f = __builtin_ctz(m);
			cells(&s[p], f, c0, c1);
			for (int i = c0[0]; i <= c1[0]; i++)
				for (int j = c0[1]; j <= c1[1]; j++)
					g->start[(f * C + i) * C + j + 1]++;
		}
	}
	for (int i = 0; i < NCELL; i++)
		g->start[i + 1] += g->start[i];
	total = g->start[NCELL];
	if (!pm_grow((void **)&g->item, &g->itemcap, 0, total, sizeof *g->item))
		return 0;
	for (int p = 0; p < n; p++) {
		if (many(&s[p]))
			continue;
		for (unsigned m = s[p].mask; m; m &= m - 1) {
			int f = __builtin_ctz(m);
			cells(&s[p], f, c0, c1);
			for (int i = c0[0]; i <= c1[0]; i++)
				for (int j = c0[1]; j <= c1[1]; j++)
					g->item[g->start[(f * C + i) * C + j]++] = p;
		}
	}
	/* The fill moved each start to the next cell's: move them back. */
	for (int i = NCELL; i > 0; i--)
		g->start[i] = g->start[i - 1];
	g->start[0] = 0;
	g->nitem = total;
	return 1;
}

/* out[0..k-1] without group skip's polygons, in order (none left out
 * without grp or with skip < 0): one pass over what the query found, kept
 * out of its walk over the cells, where a test per item cost the plain
 * queries more than it saved (scanned +0.5 %). Returns how many stay. */
static int
leave_out(const int *grp, int skip, int *out, int k)
{
	int m = 0;

	if (!grp || skip < 0)
		return k;
	for (int i = 0; i < k; i++)
		if (grp[out[i]] != skip)
			out[m++] = out[i];
	return m;
}

int
pm_sight_grid_query(const pm_sight_grid *g, int n, const pm_sight *q, const int *grp, int skip,
                    int *out, int *mark, int stamp)
{
	int c0[2], c1[2], k = 0;

	if (q->face < 0) {
		for (int p = 0; p < n; p++) {
			mark[p] = stamp;
			out[k++] = p;
		}
		return leave_out(grp, skip, out, k);
	}
	for (int i = 0; i < g->nwide; i++) {
		mark[g->wide[i]] = stamp;
		out[k++] = g->wide[i];
	}
	for (unsigned m = q->mask; m; m &= m - 1) {
		int f = __builtin_ctz(m);
		cells(q, f, c0, c1);
		for (int i = c0[0]; i <= c1[0]; i++)
			for (int j = c0[1]; j <= c1[1]; j++) {
				int cell = (f * C + i) * C + j;
				for (int t = g->start[cell]; t < g->start[cell + 1]; t++) {
					int p = g->item[t];
					if (mark[p] != stamp) {
						mark[p] = stamp;
						out[k++] = p;
					}
				}
			}
	}
	return leave_out(grp, skip, out, k);
}

void
pm_sight_grid_free(pm_sight_grid *g)
{
	free(g->start);
	free(g->item);
	free(g->wide);
}
