/* boxtree.h — a tree of axis-aligned boxes, to find the boxes a segment
 * passes through without trying every one.
 *
 * The compensated estimate asks, for each sample point y on a polygon of
 * its cube, whether the segment from x' to y crosses a polygon that may
 * hide it. In a cube of thousands of facets (a rough or scanned mesh) that
 * was a list per polygon, hundreds long, tried for every point: the cost
 * grew with the square of the facets. The tree over the polygons' boxes
 * brings each point's question down to the few boxes near its segment
 * (compensate.c, seen_cast()). */
#ifndef PM_BOXTREE_H
#define PM_BOXTREE_H

#include "base/vec.h"

/* Boxes per leaf, at most. */
#define PM_BOXTREE_LEAF 4

typedef struct pm_boxtree_node {
	double lo[3], hi[3];
	int first, count;      /* a leaf: items [first, first + count); an inner
	                          node: count 0, children first and first + 1 */
	int tag;               /* the tag every item below has, or -1
	                          (pm_boxtree_tag()) */
} pm_boxtree_node;

typedef struct pm_boxtree {
	pm_boxtree_node *node;
	int nnode, nodecap;
	int *item;             /* box numbers, leaf by leaf */
	int itemcap;
	double *mid;           /* scratch: box centres, axis by axis, while building */
	int midcap;
} pm_boxtree;

/* Fills t with boxes lo[i], hi[i] (i < n, each lo <= hi, finite), each grown
 * by grow on every side. t starts zeroed and is reused across calls; the
 * tree's shape depends only on the boxes. 0 on a failed allocation. */
int pm_boxtree_build(pm_boxtree *t, const double (*lo)[3], const double (*hi)[3], int n, double grow);

/* Tags the tree's boxes, tag[i] >= 0 for box i, so that the walks below
 * can pass over every node whose boxes all have the tag they are told to
 * skip (a building tags none). */
void pm_boxtree_tag(pm_boxtree *t, const int *tag);

/* Calls f(ctx, i) for every box i the segment a-b may pass through (every
 * one it does, perhaps some more), until f returns nonzero; returns that
 * value, or 0. */
int pm_boxtree_segment(const pm_boxtree *t, pm_dvec3 a, pm_dvec3 b, int (*f)(void *ctx, int i), void *ctx);

/* Calls f(ctx, i) for every box i that one of the parallel segments from a
 * to a + d, a any origin in the box lo-hi, may pass through no further
 * than *smax of the way (0 <= *smax <= 1; every box some such segment
 * enters, perhaps some more), nearer boxes first as far as the tree tells;
 * f may lower *smax (the furthest any segment still needs: hits found),
 * and boxes entered beyond it are passed over from then on. One walk for
 * rays from points near each other: a box is tested once, not once a ray;
 * for one ray, lo and hi are its origin. Boxes tagged skip (if skip >= 0)
 * may be left out. */
void pm_boxtree_beam(const pm_boxtree *t, pm_dvec3 lo, pm_dvec3 hi, pm_dvec3 d, int skip, double *smax,
                     void (*f)(void *ctx, int i), void *ctx);

/* Calls f(ctx, i) for every box i with some point p where N . p > d (the
 * box as grown; perhaps some more; boxes tagged skip, if skip >= 0, may be
 * left out), until f returns nonzero; returns that value, or 0. */
int pm_boxtree_halfspace(const pm_boxtree *t, pm_dvec3 N, double d, int skip, int (*f)(void *ctx, int i),
                         void *ctx);

void pm_boxtree_free(pm_boxtree *t);

#endif
