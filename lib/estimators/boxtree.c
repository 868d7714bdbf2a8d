/* boxtree.c — a tree of boxes for segment queries (boxtree.h). */
#include "estimators/boxtree.h"

#include <stdlib.h>

#include "base/grow.h"

/* Deep enough for any tree of up to 2^60 boxes: every split halves. */
#define STACK 64

/* Puts items[lo .. hi) in order around their k-th smallest centre mid[]
 * (those before k no larger, those after no smaller): a quickselect with
 * the median of three as pivot, the same order for the same boxes. */
static void
select_kth(int *items, const double *mid, int lo, int hi, int k)
{
	while (hi - lo > 2) {
		int a = items[lo], b = items[(lo + hi) / 2], c = items[hi - 1];
		double ma = mid[a], mb = mid[b], mc = mid[c];
		double p = ma < mb ? (mb < mc ? mb : ma < mc ? mc : ma) : (ma < mc ? ma : mb < mc ? mc : mb);
		int i = lo, j = hi - 1;
		while (i <= j) {
			while (mid[items[i]] < p)
				i++;
			while (mid[items[j]] > p)
				j--;
			if (i <= j) {
				int s = items[i];
				items[i++] = items[j];
				items[j--] = s;
			}
		}
		if (k <= j)
			hi = j + 1;
		else if (k >= i)
			lo = i;
		else
			return;
	}
	if (hi - lo == 2 && mid[items[lo]] > mid[items[lo + 1]]) {
		int s = items[lo];
		items[lo] = items[lo + 1];
		items[lo + 1] = s;
	}
}

/* Node v over items[first .. first + count): below it the halves split at
 * the median centre along the axis the centres spread most, then its box,
 * from its items at a leaf and from its children above (the same box: the
 * smallest of the children's lowest, less grow, is the lowest less grow).
 * cen holds the centres axis by axis, cen[k * n + b]. */
static void
build(pm_boxtree *t, const double (*lo)[3], const double (*hi)[3], double grow, int v, int first, int count,
      const double *cen, int n)
{
	pm_boxtree_node *nd = &t->node[v];
	double clo[3], chi[3];

	if (count <= PM_BOXTREE_LEAF) {
		for (int k = 0; k < 3; k++) {
			nd->lo[k] = INFINITY;
			nd->hi[k] = -INFINITY;
		}
		for (int i = first; i < first + count; i++) {
			int b = t->item[i];
			for (int k = 0; k < 3; k++) {
				nd->lo[k] = lo[b][k] < nd->lo[k] ? lo[b][k] : nd->lo[k];
				nd->hi[k] = hi[b][k] > nd->hi[k] ? hi[b][k] : nd->hi[k];
			}
		}
		for (int k = 0; k < 3; k++) {
			nd->lo[k] -= grow;
			nd->hi[k] += grow;
		}
		nd->first = first;
		nd->count = count;
		nd->tag = -1;
		return;
	}
	/* One pass for the three axes: each item's index read once. */
	const double *c0 = cen, *c1 = cen + (size_t)n, *c2 = cen + 2 * (size_t)n;
	for (int k = 0; k < 3; k++) {
		clo[k] = INFINITY;
		chi[k] = -INFINITY;
	}
	for (int i = first; i < first + count; i++) {
		int b = t->item[i];
		double x = c0[b], y = c1[b], z = c2[b];
		clo[0] = x < clo[0] ? x : clo[0];
		chi[0] = x > chi[0] ? x : chi[0];
		clo[1] = y < clo[1] ? y : clo[1];
		chi[1] = y > chi[1] ? y : chi[1];
		clo[2] = z < clo[2] ? z : clo[2];
		chi[2] = z > chi[2] ? z : chi[2];
	}
	int ax = chi[0] - clo[0] >= chi[1] - clo[1] && chi[0] - clo[0] >= chi[2] - clo[2] ? 0
	         : chi[1] - clo[1] >= chi[2] - clo[2] ? 1 : 2;
	int half = count / 2, c = t->nnode;
	select_kth(t->item, cen + (size_t)ax * n, first, first + count, first + half);
	t->nnode += 2;
	build(t, lo, hi, grow, c, first, half, cen, n);
	build(t, lo, hi, grow, c + 1, first + half, count - half, cen, n);
	nd = &t->node[v];
	for (int k = 0; k < 3; k++) {
		const pm_boxtree_node *l = &t->node[c], *r = &t->node[c + 1];
		nd->lo[k] = l->lo[k] < r->lo[k] ? l->lo[k] : r->lo[k];
		nd->hi[k] = l->hi[k] > r->hi[k] ? l->hi[k] : r->hi[k];
	}
	nd->first = c;
	nd->count = 0;
	nd->tag = -1;
}

int
pm_boxtree_build(pm_boxtree *t, const double (*lo)[3], const double (*hi)[3], int n, double grow)
{
	t->nnode = 0;
	if (n <= 0)
		return 1;
	if (!pm_grow((void **)&t->node, &t->nodecap, 0, 2 * n, sizeof *t->node) ||
	    !pm_grow((void **)&t->item, &t->itemcap, 0, n, sizeof *t->item) ||
	    !pm_grow((void **)&t->mid, &t->midcap, 0, 3 * n, sizeof *t->mid))
		return 0;
	for (int i = 0; i < n; i++) {
		t->item[i] = i;
		for (int k = 0; k < 3; k++)
			t->mid[k * n + i] = 0.5 * (lo[i][k] + hi[i][k]);
	}
	t->nnode = 1;
	build(t, lo, hi, grow, 0, 0, n, t->mid, n);
	return 1;
}

void
pm_boxtree_tag(pm_boxtree *t, const int *tag)
{
	/* Children come after their parent. */
	for (int v = t->nnode - 1; v >= 0; v--) {
		pm_boxtree_node *nd = &t->node[v];
		if (nd->count > 0) {
			nd->tag = tag[t->item[nd->first]];
			for (int i = nd->first + 1; i < nd->first + nd->count; i++)
				nd->tag = tag[t->item[i]] == nd->tag ? nd->tag : -1;
		} else
			nd->tag = t->node[nd->first].tag == t->node[nd->first + 1].tag ? t->node[nd->first].tag : -1;
	}
}

/* Segments a + s d (s in [0, 1]) as the walks ask them: 1 / d along each
 * axis (infinity where d is 0, either sign) and whether d is negative
 * there, so that the box's near and far sides need no sorting, and the
 * origins' extreme along each axis that makes the entry earliest (near)
 * and the exit latest (far). For one segment both are its a; for a beam
 * of parallel ones, from a box of origins, the entry is then no later and
 * the exit no earlier than any one's, in floating point too (rounding is
 * monotone). */
typedef struct seg {
	double near[3], far[3], inv[3];
	int neg[3];
} seg;

static seg
seg_of(pm_dvec3 lo, pm_dvec3 hi, pm_dvec3 d)
{
	seg q;
	double l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z}, dv[3] = {d.x, d.y, d.z};

	for (int k = 0; k < 3; k++) {
		q.inv[k] = dv[k] != 0 ? 1 / dv[k] : INFINITY;
		q.neg[k] = dv[k] < 0;
		q.near[k] = q.neg[k] ? l[k] : h[k];
		q.far[k] = q.neg[k] ? h[k] : l[k];
	}
	return q;
}

/* The part of segment q, s in [0, smax], in node box nd: its entry s, or 2
 * if it misses. Where d is 0 along an axis, origins outside the box's slab
 * give an infinity that misses, and one on its side a NaN, which the
 * comparisons pass over (the closed box holds it). */
static inline double
entry(const pm_boxtree_node *nd, const seg *q, double smax)
{
	double s0 = 0, s1 = smax;

	for (int k = 0; k < 3; k++) {
		double u = ((q->neg[k] ? nd->hi[k] : nd->lo[k]) - q->near[k]) * q->inv[k];
		double v = ((q->neg[k] ? nd->lo[k] : nd->hi[k]) - q->far[k]) * q->inv[k];
		s0 = u > s0 ? u : s0;
		s1 = v < s1 ? v : s1;
	}
	return s0 > s1 ? 2 : s0;
}

/* Depth first through the nodes keep() passes (q its question), f asked
 * of each item of a leaf it passes until f returns nonzero; returns that,
 * or 0. Inlined with each keep(). */
static inline int
walk(const pm_boxtree *t, int (*keep)(const pm_boxtree_node *nd, const void *q), const void *q,
     int (*f)(void *ctx, int i), void *ctx)
{
	int stack[STACK], sp = 0, r;

	if (t->nnode == 0)
		return 0;
	stack[sp++] = 0;
	while (sp > 0) {
		const pm_boxtree_node *nd = &t->node[stack[--sp]];
		if (!keep(nd, q))
			continue;
		if (nd->count == 0) {
			stack[sp++] = nd->first + 1;
			stack[sp++] = nd->first;
			continue;
		}
		for (int i = nd->first; i < nd->first + nd->count; i++)
			if ((r = f(ctx, t->item[i])) != 0)
				return r;
	}
	return 0;
}

static inline int
seg_keep(const pm_boxtree_node *nd, const void *q)
{
	return entry(nd, q, 1) <= 1;
}

int
pm_boxtree_segment(const pm_boxtree *t, pm_dvec3 a, pm_dvec3 b, int (*f)(void *ctx, int i), void *ctx)
{
	seg q = seg_of(a, a, pm_dsub(b, a));

	return walk(t, seg_keep, &q, f, ctx);
}

void
pm_boxtree_beam(const pm_boxtree *t, pm_dvec3 lo, pm_dvec3 hi, pm_dvec3 d, int skip, double *smax,
                void (*f)(void *ctx, int i), void *ctx)
{
	seg q = seg_of(lo, hi, d);
	double at[STACK];
	int stack[STACK], sp = 0;

	if (t->nnode == 0)
		return;
	if ((at[0] = entry(&t->node[0], &q, *smax)) > 1)
		return;
	stack[sp++] = 0;
	while (sp > 0) {
		sp--;
		if (at[sp] > *smax)
			continue;
		const pm_boxtree_node *nd = &t->node[stack[sp]];
		if (nd->tag >= 0 && nd->tag == skip)
			continue;
		if (nd->count > 0) {
			for (int i = nd->first; i < nd->first + nd->count; i++)
				f(ctx, t->item[i]);
			continue;
		}
		/* The nearer child on top; a child the segment misses, not at all. */
		double e0 = entry(&t->node[nd->first], &q, *smax);
		double e1 = entry(&t->node[nd->first + 1], &q, *smax);
		int c0 = nd->first, c1 = nd->first + 1;
		if (e1 > e0) {
			double e = e0;
			e0 = e1;
			e1 = e;
			c0 = nd->first + 1;
			c1 = nd->first;
		}
		if (e0 <= 1) {
			stack[sp] = c0;
			at[sp++] = e0;
		}
		if (e1 <= 1) {
			stack[sp] = c1;
			at[sp++] = e1;
		}
	}
}

typedef struct halfq {
	pm_dvec3 N;
	double d;
	int skip;
} halfq;

static inline int
half_keep(const pm_boxtree_node *nd, const void *vq)
{
	const halfq *q = vq;
	pm_dvec3 N = q->N;
	if (nd->tag >= 0 && nd->tag == q->skip)
		return 0;
	return (N.x > 0 ? nd->hi[0] : nd->lo[0]) * N.x + (N.y > 0 ? nd->hi[1] : nd->lo[1]) * N.y +
	       (N.z > 0 ? nd->hi[2] : nd->lo[2]) * N.z > q->d;
}

int
pm_boxtree_halfspace(const pm_boxtree *t, pm_dvec3 N, double d, int skip, int (*f)(void *ctx, int i),
                     void *ctx)
{
	halfq q = {N, d, skip};
	return walk(t, half_keep, &q, f, ctx);
}

void
pm_boxtree_free(pm_boxtree *t)
{
	free(t->node);
	free(t->item);
	free(t->mid);
}
