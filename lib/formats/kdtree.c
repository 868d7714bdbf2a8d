/* kdtree.c — the photon map's left-balanced kd-tree (Jensen 1996, "Global
 * Illumination using Photon Maps"; Jensen 2001, "Realistic Image Synthesis
 * Using Photon Mapping", §6.3): build by median selection, validation, and
 * k-nearest-neighbour queries under L2 and L-infinity. */
#include "formats/kdtree.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/rng.h"

/* Deep enough for 2^32 - 1 photons (depth 32). */
#define MAX_DEPTH 64

int
pm_kd_depth(size_t n)
{
	int d = 0;

	while (n) {
		d++;
		n >>= 1;
	}
	return d;
}

/* Size of the left subtree of a left-balanced (complete) tree of m nodes:
 * the full levels above the last split evenly, and the last level fills from
 * the left. */
static size_t
left_size(size_t m)
{
	size_t full = 1, half;         /* full = 2^d with 2^d - 1 <= m < 2^(d+1) - 1 */

	while (2 * full - 1 <= m)
		full *= 2;
	half = full / 2;               /* the last full level's width ... */
	if (half == 0)
		return 0;
	size_t last = m - (full - 1);  /* nodes on the partial last level */
	return half - 1 + (last < half ? last : half);
}

/* Hoare partition with a median-of-three pivot drawn from a generator seeded
 * by the node, so the tree is the same on every run and thread count while
 * sorted or adversarial input still splits evenly on average (Hoare 1961,
 * "Algorithm 65: FIND"). Afterwards a[kth] holds the kth smallest coordinate,
 * everything before it is <= and everything after is >=. */
static void
select_kth(pm_photon *a, size_t m, size_t kth, int axis, pm_rng *r)
{
	size_t lo = 0, hi = m - 1;

	while (hi > lo) {
		size_t span = hi - lo + 1;
		float c[3];
		for (int t = 0; t < 3; t++)
			c[t] = a[lo + (size_t)(((uint64_t)pm_rng_u32(r) * span) >> 32)].pos[axis];
		float pv = c[0] < c[1] ? (c[1] < c[2] ? c[1] : c[0] < c[2] ? c[2] : c[0])
		                       : (c[0] < c[2] ? c[0] : c[1] < c[2] ? c[2] : c[1]);
		size_t i = lo, j = hi;
		for (;;) {
			while (a[i].pos[axis] < pv)
				i++;
			while (a[j].pos[axis] > pv)
				j--;
			if (i >= j)
				break;
			pm_photon t = a[i];
			a[i] = a[j];
			a[j] = t;
			i++;
			j--;
		}
		/* [lo, j] <= pv <= [j+1, hi]; when i > j + 1 the middle equals pv. */
		if (i == j) {
			/* the scans met on an element equal to pv */
			if (kth < i)
				hi = i - 1;
			else if (kth > i)
				lo = i + 1;
			else
				return;
		} else if (kth <= j) {
			hi = j;
		} else if (kth >= i) {
			lo = i;
		} else {
			return;
		}
	}
}

/* Places the m photons of src as the subtree rooted at heap index i of dst.
 * src is scratch space; dst receives the tree. */
static void
build(pm_photon *src, size_t m, pm_photon *dst, size_t i)
{
	float lo[3], hi[3];
	int axis = 0;
	size_t l;
	pm_rng r;

	if (m == 0)
		return;
	if (m == 1) {
		dst[i] = src[0];
		pm_photon_set_axis(&dst[i], PM_AXIS_NONE);
		return;
	}
	for (int a = 0; a < 3; a++)
		lo[a] = hi[a] = src[0].pos[a];
	for (size_t j = 1; j < m; j++)
		for (int a = 0; a < 3; a++) {
			float v = src[j].pos[a];
			lo[a] = v < lo[a] ? v : lo[a];
			hi[a] = v > hi[a] ? v : hi[a];
		}
	for (int a = 1; a < 3; a++)
		if (hi[a] - lo[a] > hi[axis] - lo[axis])
			axis = a;
	l = left_size(m);
	r = pm_rng_seed(0x6b642d747265650aull, i);
	select_kth(src, m, l, axis, &r);
	dst[i] = src[l];
	pm_photon_set_axis(&dst[i], axis);
	/* Subtrees are disjoint in src and dst, so big ones can be built by
	 * other threads without changing the result. */
#pragma omp task if (m > 100000)
	build(src, l, dst, 2 * i + 1);
#pragma omp task if (m > 100000)
	build(src + l + 1, m - l - 1, dst, 2 * i + 2);
#pragma omp taskwait
}

int
pm_kd_build(pm_photon *p, size_t n, pm_error *err)
{
	pm_photon *tmp;

	if (n > UINT32_MAX)
		return pm_seterr(err, "%zu photons exceed the kd-tree limit of %u", n, UINT32_MAX);
	if (n == 0)
		return 0;
	tmp = malloc(n * sizeof *tmp);
	if (!tmp)
		return pm_seterr(err, "out of memory for a kd-tree of %zu photons", n);
	memcpy(tmp, p, n * sizeof *tmp);
#pragma omp parallel if (n > 100000)
#pragma omp single
	build(tmp, n, p, 0);
	free(tmp);
	return 0;
}

/* Bounds that the ancestors' splits put on node i: lo/hi per axis and the
 * node that set each bound (for the message). */
typedef struct {
	float lo[3], hi[3];
	size_t lon[3], hin[3];
} bounds;

static int
validate(const pm_photon *p, size_t n, size_t i, const bounds *b, pm_error *err)
{
	const float *q = p[i].pos;
	size_t l = 2 * i + 1;
	bounds c;
	int a;

	for (a = 0; a < 3; a++) {
		if (q[a] < b->lo[a])
			return pm_seterr(err, "node %zu lies left of the split at node %zu", i, b->lon[a]);
		if (q[a] > b->hi[a])
			return pm_seterr(err, "node %zu lies right of the split at node %zu", i, b->hin[a]);
	}
	if (l >= n)
		return 0;
	a = pm_photon_axis(&p[i]);
	if (a > 2)
		return pm_seterr(err, "node %zu has children but no split axis", i);
	c = *b;
	c.hi[a] = q[a];
	c.hin[a] = i;
	if (validate(p, n, l, &c, err))
		return -1;
	if (l + 1 >= n)
		return 0;
	c = *b;
	c.lo[a] = q[a];
	c.lon[a] = i;
	return validate(p, n, l + 1, &c, err);
}

/* Every node within the bounds of all its ancestors' splits: one O(n) walk
 * instead of comparing each subtree against each ancestor. */
int
pm_kd_validate(const pm_photon *p, size_t n, pm_error *err)
{
	bounds b;

	if (n == 0)
		return 0;
	for (int a = 0; a < 3; a++) {
		b.lo[a] = -INFINITY;
		b.hi[a] = INFINITY;
		b.lon[a] = b.hin[a] = 0;
	}
	return validate(p, n, 0, &b, err);
}

/* ---- k nearest ------------------------------------------------------- */

/* The result heap orders neighbours by (distance, index), so that ties at
 * the k-th distance resolve the same way whatever the visiting order. A
 * distance is never negative nor -0 (a sum of squares, or fabsf), and the
 * bits of such floats order as the floats do, so (distance, index) is one
 * 64-bit key: one compare where the pair's two were most of the heap's
 * time. A NaN distance's key is above every number's, as "not less" was. */
static inline uint64_t
nn_key(float d, uint32_t idx)
{
	uint32_t b;
	memcpy(&b, &d, sizeof b);
	return (uint64_t)b << 32 | idx;
}

static inline int
nn_less(float da, uint32_t ia, float db, uint32_t ib)
{
	return nn_key(da, ia) < nn_key(db, ib);
}

static inline void
heap_up(pm_nn *h, int j)
{
	pm_nn e = h[j];
	while (j > 0) {
		int par = (j - 1) / 2;
		if (!nn_less(h[par].d, h[par].idx, e.d, e.idx))
			break;
		h[j] = h[par];
		j = par;
	}
	h[j] = e;
}

static inline void
heap_down(pm_nn *h, int cnt)
{
	pm_nn e = h[0];
	int j = 0;
	for (;;) {
		int c = 2 * j + 1;
		if (c >= cnt)
			break;
		if (c + 1 < cnt && nn_less(h[c].d, h[c].idx, h[c + 1].d, h[c + 1].idx))
			c++;
		if (!nn_less(e.d, e.idx, h[c].d, h[c].idx))
			break;
		h[j] = h[c];
		j = c;
	}
	h[j] = e;
}

/* Depth-first descent, near child first, far children on a stack with their
 * split-plane distance; a far subtree is entered only if that distance could
 * still beat the current k-th neighbour (Friedman, Bentley & Finkel 1977).
 * Float distances make the pruning exact: the rounded distance to any point
 * beyond a plane is never below the rounded distance to the plane. */
static inline __attribute__((always_inline)) int
knn(const pm_photon *p, size_t n, const float x[3], int k, int linf,
    float dmax, pm_nn *out, float *dfar)
{
	struct { uint32_t i; float d; } st[MAX_DEPTH];
	int sp = 0, cnt = 0;
	size_t i = 0;

	for (;;) {
		for (;;) {
			const float *q = p[i].pos;
			/* the children sit side by side at 2i+1: fetch them while
			 * this node is processed (the deep levels are cache misses) */
			size_t l = 2 * i + 1;
			if (l < n)
				__builtin_prefetch(&p[l]);
			float dx = x[0] - q[0], dy = x[1] - q[1], dz = x[2] - q[2];
			float d;
			if (linf) {
				/* plain compares: the operands are never NaN here, and
				 * fmaxf's NaN rules cost a library call */
				float ax = fabsf(dx), ay = fabsf(dy), az = fabsf(dz);
				d = ax > ay ? ax : ay;
				d = d > az ? d : az;
			} else {
				d = dx * dx + dy * dy + dz * dz;
			}
			if (cnt < k) {
				if (d < dmax) {
					out[cnt].d = d;
					out[cnt].idx = (uint32_t)i;
					heap_up(out, cnt++);
				}
			} else if (nn_less(d, (uint32_t)i, out[0].d, out[0].idx)) {
				out[0].d = d;
				out[0].idx = (uint32_t)i;
				heap_down(out, cnt);
			}
			if (l >= n)
				break;
			unsigned a = p[i].bits[1] >> 30;
			if (a > 2)      /* not a built tree; stay in bounds */
				a = 2;
			float diff = x[a] - q[a];
			float dp = linf ? fabsf(diff) : diff * diff;
			size_t nearc = diff < 0 ? l : l + 1, farc = diff < 0 ? l + 1 : l;
			if (farc < n && (cnt < k ? dp < dmax : dp <= out[0].d)) {
				st[sp].i = (uint32_t)farc;
				st[sp].d = dp;
				sp++;
			}
			if (nearc >= n)
				break;
			i = nearc;
		}
		for (;;) {
			if (sp == 0)
				goto done;
			sp--;
			if (cnt < k ? st[sp].d < dmax : st[sp].d <= out[0].d) {
				i = st[sp].i;
				break;
			}
		}
	}
done:
	*dfar = cnt ? out[0].d : 0;
	return cnt;
}

int
pm_kd_knn(const pm_photon *p, size_t n, const float x[3], int k,
          enum pm_metric metric, float dmax, pm_nn *out, float *dfar)
{
	if (n == 0 || k <= 0) {
		*dfar = 0;
		return 0;
	}
	if (metric == PM_LINF)
		return knn(p, n, x, k, 1, dmax, out, dfar);
	return knn(p, n, x, k, 0, dmax, out, dfar);
}
