/* sight.h — where a point sees each polygon, as a box on one face of the
 * cube of directions around it, and a grid of those boxes to find the
 * polygons one polygon's box meets.
 *
 * The compensated estimate asks, for each polygon P of its cube, which
 * others may hide part of P from x'. A polygon B can only hide part of P if
 * some ray from x' meets both (each widened by e): their boxes then meet.
 * On a rough mesh with hundreds of facets in the cube, most pairs are far
 * apart as x' sees them, and the grid finds the few that are not without
 * testing every pair (compensate.c, pair_lists). */
#ifndef PM_SIGHT_H
#define PM_SIGHT_H

#include "base/vec.h"

/* Cells per side of one face of the grid. */
#define PM_SIGHT_CELLS 16

/* A polygon's directions from the eye: for each face f of the cube of
 * directions it reaches (bit f of mask; f = 2 axis + 1 if the axis points
 * away), the box [lo[f], hi[f]] of the two other coordinates over the axis
 * coordinate, widened so that it holds every point within e of the
 * polygon whose direction lies on that face (a polygon across an edge of
 * the cube has a box on each face it reaches). face: the first of them,
 * or -1: the polygon comes within a few e of the eye, or has too many
 * vertices to clip, or reaches across an edge of the cube where that was
 * not asked for: it may meet any direction. */
typedef struct pm_sight {
	int face;
	unsigned mask;
	double lo[6][2], hi[6][2];
} pm_sight;

/* The box of polygon v[0..n-1] (flat, any shape, n >= 1) seen from eye;
 * with across 0, only where it lies on one face (a box across faces costs
 * clipping the polygon to each, which pays only where a grid of many
 * boxes is queried). */
void pm_sight_box(const pm_dvec3 *v, int n, pm_dvec3 eye, double e, int across, pm_sight *out);

/* 1 if some direction may be in both boxes. */
static inline int
pm_sight_meet(const pm_sight *a, const pm_sight *b)
{
	if (a->face < 0 || b->face < 0)
		return 1;
	for (unsigned m = a->mask & b->mask; m; m &= m - 1) {
		int f = __builtin_ctz(m);
		if (a->lo[f][0] <= b->hi[f][0] && b->lo[f][0] <= a->hi[f][0] && a->lo[f][1] <= b->hi[f][1] &&
		    b->lo[f][1] <= a->hi[f][1])
			return 1;
	}
	return 0;
}

/* The boxes of n polygons in cells; polygons with face -1 or a box over
 * many cells are kept on one list every query returns. */
typedef struct pm_sight_grid {
	int *start;      /* 6 x CELLS x CELLS + 1 offsets into item */
	int *item;
	int nitem, itemcap;
	int *wide;       /* polygons every query returns */
	int nwide, widecap;
	int startcap;
} pm_sight_grid;

/* Fills g with boxes s[0..n-1]; g starts zeroed and is reused across
 * calls. 0 on a failed allocation. */
int pm_sight_grid_build(pm_sight_grid *g, const pm_sight *s, int n);

/* Writes to out the polygons whose boxes may meet q (a superset: test
 * each with pm_sight_meet), each once: mark[] holds stamp for those
 * written, and maybe for others (mark has room for n, its other values
 * below stamp). out has room for n. Returns how many. With q->face -1,
 * every polygon. With grp (each polygon's group) and skip >= 0, the
 * polygons of group skip are left out (the asking polygon's own sheet,
 * which hides none of it: on a dense mesh most of what a query finds). */
int pm_sight_grid_query(const pm_sight_grid *g, int n, const pm_sight *q, const int *grp, int skip,
                        int *out, int *mark, int stamp);

void pm_sight_grid_free(pm_sight_grid *g);

#endif
