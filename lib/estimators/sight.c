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

void
pm_sight_box(const pm_dvec3 *v, int n, pm_dvec3 eye, double e, pm_sight *out)
{
	pm_dvec3 c = {0, 0, 0};
	double mmin = INFINITY, amax[2] = {0, 0};

	out->face = -1;
	for (int k = 0; k < n; k++)
		c = pm_dadd(c, pm_dsub(v[k], eye));
	int a = fabs(c.x) >= fabs(c.y) && fabs(c.x) >= fabs(c.z) ? 0 : fabs(c.y) >= fabs(c.z) ? 1 : 2;
	double s = at(c, a) < 0 ? -1 : 1;
	out->lo[0] = out->lo[1] = INFINITY;
	out->hi[0] = out->hi[1] = -INFINITY;
	for (int k = 0; k < n; k++) {
		pm_dvec3 d = pm_dsub(v[k], eye);
		double m = s * at(d, a);
		/* Also false for NaN. */
		if (!(m > 2 * e))
			return;
		mmin = m < mmin ? m : mmin;
		for (int i = 0; i < 2; i++) {
			double u = at(d, (a + 1 + i) % 3) / m;
			out->lo[i] = u < out->lo[i] ? u : out->lo[i];
			out->hi[i] = u > out->hi[i] ? u : out->hi[i];
			amax[i] = fabs(u) > amax[i] ? fabs(u) : amax[i];
		}
	}
	/* A point p + d (|d| <= e) of the polygon's neighbourhood: its u moves
	 * by (d_u - u d_m) / (m + d_m), at most e (1 + |u|) / (m - e); the
	 * polygon's points have m >= mmin and |u| within the vertices' (a
	 * central projection keeps segments straight). Rounding is far below
	 * the margin and the tolerance added to it. */
	double mg = e * (1 + amax[0] + amax[1]) / (mmin - e);
	mg += 1e-12 * (1 + amax[0] + amax[1]);
	for (int i = 0; i < 2; i++) {
		out->lo[i] -= mg;
		out->hi[i] += mg;
		/* Past the face's edge, directions belong to another face. */
		if (!(out->lo[i] > -1 && out->hi[i] < 1))
			return;
	}
	out->face = 2 * a + (s < 0);
}

/* The cells a box covers on its face: [c0, c1] in each coordinate. */
static void
cells(const pm_sight *b, int c0[2], int c1[2])
{
	for (int i = 0; i < 2; i++) {
		int lo = (int)floor((b->lo[i] + 1) * 0.5 * C), hi = (int)floor((b->hi[i] + 1) * 0.5 * C);
		c0[i] = lo < 0 ? 0 : lo > C - 1 ? C - 1 : lo;
		c1[i] = hi < 0 ? 0 : hi > C - 1 ? C - 1 : hi;
	}
}

static int
many(const pm_sight *b)
{
	int c0[2], c1[2];

	if (b->face < 0)
		return 1;
	cells(b, c0, c1);
	return (c1[0] - c0[0] + 1) * (c1[1] - c0[1] + 1) > MAX_CELLS;
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
		cells(&s[p], c0, c1);
		for (int i = c0[0]; i <= c1[0]; i++)
			for (int j = c0[1]; j <= c1[1]; j++)
				g->start[(s[p].face * C + i) * C + j + 1]++;
	}
	for (int i = 0; i < NCELL; i++)
		g->start[i + 1] += g->start[i];
	total = g->start[NCELL];
	if (!pm_grow((void **)&g->item, &g->itemcap, 0, total, sizeof *g->item))
		return 0;
	for (int p = 0; p < n; p++) {
		if (many(&s[p]))
			continue;
		cells(&s[p], c0, c1);
		for (int i = c0[0]; i <= c1[0]; i++)
			for (int j = c0[1]; j <= c1[1]; j++)
				g->item[g->start[(s[p].face * C + i) * C + j]++] = p;
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
	cells(q, c0, c1);
	for (int i = c0[0]; i <= c1[0]; i++)
		for (int j = c0[1]; j <= c1[1]; j++) {
			int cell = (q->face * C + i) * C + j;
			for (int t = g->start[cell]; t < g->start[cell + 1]; t++) {
				int p = g->item[t];
				if (mark[p] != stamp) {
					mark[p] = stamp;
					out[k++] = p;
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
