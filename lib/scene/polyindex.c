/* polyindex.c — a bounding volume hierarchy over the photon-surface polygons
 * (those whose material is not strong), for the compensated estimate's
 * "polygons that meet the cube" (paper §3). See polyindex.h.
 *
 * Median split on the longest axis of the centroids' box (quickselect, so the
 * build is O(n log n) and the depth at most ceil(log2 n) + 1), leaves of up
 * to LEAF polygons. Queries walk the tree with a fixed stack and call back,
 * so they allocate nothing. */
#include "scene/polyindex.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/patch.h"
#include "scene/scene_poly.h"

#define LEAF 4
#define STACK 72     /* > depth of a median-split tree over 2^32 entries */

typedef struct builder {
	pm_polyindex *pi;
	float (*cen)[3];    /* centroid of each box, same order as prim/box */
} builder;

static void
swap_entries(builder *b, uint32_t i, uint32_t j)
{
	uint32_t t = b->pi->prim[i];
	float bx[6], c[3];

	b->pi->prim[i] = b->pi->prim[j];
	b->pi->prim[j] = t;
	memcpy(bx, b->pi->box[i], sizeof bx);
	memcpy(b->pi->box[i], b->pi->box[j], sizeof bx);
	memcpy(b->pi->box[j], bx, sizeof bx);
	memcpy(c, b->cen[i], sizeof c);
	memcpy(b->cen[i], b->cen[j], sizeof c);
	memcpy(b->cen[j], c, sizeof c);
}

/* Hoare quickselect (Hoare 1961, "Algorithm 65: Find"): afterwards entries
 * [lo, mid) have centroid <= that of mid, and (mid, hi) >= it. The pivot is
 * the median of three, so sorted input costs O(n). */
static void
select_mid(builder *b, uint32_t lo, uint32_t hi, uint32_t mid, int ax)
{
	while (hi - lo > 2) {
		uint32_t m = lo + (hi - lo) / 2;
		float x0 = b->cen[lo][ax], x1 = b->cen[m][ax], x2 = b->cen[hi - 1][ax];
		float piv = x0 < x1 ? (x1 < x2 ? x1 : (x0 < x2 ? x2 : x0))
		                    : (x0 < x2 ? x0 : (x1 < x2 ? x2 : x1));
		int64_t i = lo, j = (int64_t)hi - 1;
		for (;;) {
			while (b->cen[i][ax] < piv)
				i++;
			while (b->cen[j][ax] > piv)
				j--;
			if (i >= j)
				break;
			swap_entries(b, (uint32_t)i, (uint32_t)j);
			i++;
			j--;
		}
		/* [lo, j] <= piv <= [j+1, hi). The pivot is a sampled value, so
		 * both sides are nonempty; should that ever fail, finish by sorting
		 * rather than loop. */
		if (j < (int64_t)lo || j + 1 >= (int64_t)hi) {
			for (uint32_t a = lo + 1; a < hi; a++)
				for (uint32_t c = a; c > lo && b->cen[c - 1][ax] > b->cen[c][ax]; c--)
					swap_entries(b, c - 1, c);
			return;
		}
		if ((int64_t)mid <= j)
			hi = (uint32_t)j + 1;
		else
			lo = (uint32_t)j + 1;
	}
	if (hi - lo == 2 && b->cen[lo][ax] > b->cen[lo + 1][ax])
		swap_entries(b, lo, lo + 1);
}

/* A leaf's box, its entries' [lo, hi) together (an inner node's is its
 * children's together: the same floats, a minimum of minima). Plain
 * comparisons, not fminf() and fmaxf(): those are calls, and no box holds
 * a NaN. */
static void
leaf_box(pm_polyindex *pi, pm_bvh_node *nd, uint32_t lo, uint32_t hi)
{
	for (int k = 0; k < 3; k++) {
		nd->lo[k] = INFINITY;
		nd->hi[k] = -INFINITY;
	}
	for (uint32_t i = lo; i < hi; i++)
		for (int k = 0; k < 3; k++) {
			nd->lo[k] = pi->box[i][k] < nd->lo[k] ? pi->box[i][k] : nd->lo[k];
			nd->hi[k] = pi->box[i][3 + k] > nd->hi[k] ? pi->box[i][3 + k] : nd->hi[k];
		}
}

static uint32_t
build_node(builder *b, uint32_t lo, uint32_t hi)
{
	pm_polyindex *pi = b->pi;
	uint32_t id = pi->nnodes++;
	pm_bvh_node *nd = &pi->node[id];
	float clo[3] = {INFINITY, INFINITY, INFINITY}, chi[3] = {-INFINITY, -INFINITY, -INFINITY};
	int ax = 0;

	if (hi - lo <= LEAF) {
		leaf_box(pi, nd, lo, hi);
		nd->a = lo;
		nd->n = hi - lo;
		return id;
	}
	/* A centroid that is NaN (a polygon of NaN vertices only) is passed
	 * over, as fminf() and fmaxf() pass it over. */
	for (uint32_t i = lo; i < hi; i++)
		for (int k = 0; k < 3; k++) {
			float c = b->cen[i][k];
			clo[k] = c < clo[k] ? c : clo[k];
			chi[k] = c > chi[k] ? c : chi[k];
		}
	for (int k = 1; k < 3; k++)
		if (chi[k] - clo[k] > chi[ax] - clo[ax])
			ax = k;
	uint32_t mid = lo + (hi - lo) / 2;
	select_mid(b, lo, hi, mid, ax);
	nd->n = 0;
	const pm_bvh_node *l = &pi->node[build_node(b, lo, mid)];
	const pm_bvh_node *r = &pi->node[build_node(b, mid, hi)];
	nd->a = (uint32_t)(r - pi->node);     /* node[] does not move: sized up front */
	for (int k = 0; k < 3; k++) {
		nd->lo[k] = r->lo[k] < l->lo[k] ? r->lo[k] : l->lo[k];
		nd->hi[k] = r->hi[k] > l->hi[k] ? r->hi[k] : l->hi[k];
	}
	return id;
}

/* 1 if o is a closed solid whose every vertex lies behind (or on) the plane
 * of each of its polygons: a convex solid, whose faces never hide one
 * another from a point outside it. Objects too large to check cost-free
 * (faces x vertices above 2^25) count as not convex. */
static int
convex_solid(const pm_scene *s, const pm_object *o, const pm_vec3 *verts)
{
	double size = 0;

	if (!o->solid || o->npolys < 4 || (double)o->npolys * o->nverts > (double)(1 << 25))
		return 0;
	for (uint32_t v = o->first_vert + 1; v < o->first_vert + o->nverts; v++)
		size = fmax(size, pm_dlen(pm_dsub(pm_dfromf(verts[v]), pm_dfromf(verts[o->first_vert]))));
	for (uint32_t g = o->first_poly; g < o->first_poly + o->npolys; g++) {
		pm_dvec3 N = pm_dfromf(s->poly_normal[g]);
		pm_dvec3 p = pm_dfromf(verts[s->poly_vert[s->poly_start[g]]]);
		for (uint32_t v = o->first_vert; v < o->first_vert + o->nverts; v++)
			if (pm_ddot(N, pm_dsub(pm_dfromf(verts[v]), p)) > 1e-5 * size)
				return 0;
	}
	return 1;
}

/* Entry i's unit normal and area (Newell's sum along the normal, as the
 * compensated estimate's clipping measures a polygon wholly inside its
 * cube), from the absolute vertices. */
static void
entry_shape(pm_polyindex *pi, uint32_t i)
{
	const pm_scene *s = pi->s;
	uint32_t g = pi->prim[i], v0 = s->poly_start[g];
	pm_dvec3 N = pm_dfromf(s->poly_normal[g]);
	double len = pm_dlen(N);

	N = len > 0 ? pm_dscale(N, 1 / len) : pm_dv3(0, 0, 0);
	double a = 0.5 * fabs(pm_ddot(pm_poly_newell(pi->verts, s->poly_vert + v0, s->poly_start[g + 1] - v0), N));
	pi->pn[i] = N;
	pi->pa[i] = isfinite(a) ? a : 0;
}

/* Patches of this many polygons or more are a dense mesh's. */
#define DENSE_PATCH 64

/* 1 if half the photon-surface polygons or more lie in patches of
 * DENSE_PATCH polygons: only then do the nodes' aggregates pay for the
 * walk that looks for nodes to take whole (compensate.c, sheet_walk();
 * elsewhere it cost a cube of one polygon 1-2 %). 0 also out of room. */
static int
dense_patches(const pm_polyindex *pi)
{
	uint32_t *cnt = calloc((size_t)pi->s->npolys + 1, sizeof *cnt), dense = 0;

	if (!cnt)
		return 0;
	for (uint32_t i = 0; i < pi->nprims; i++)
		if (pi->patch[pi->prim[i]] < pi->s->npolys)
			cnt[pi->patch[pi->prim[i]]]++;
	for (uint32_t i = 0; i < pi->nprims; i++)
		dense += pi->patch[pi->prim[i]] < pi->s->npolys && cnt[pi->patch[pi->prim[i]]] >= DENSE_PATCH;
	free(cnt);
	return dense >= pi->nprims - dense;
}

/* The aggregates of node id over entries [lo, hi); returns hi. */
static uint32_t
aggregate(pm_polyindex *pi, uint32_t id, uint32_t lo)
{
	const pm_bvh_node *nd = &pi->node[id];
	pm_bvh_agg *A = &pi->agg[id];
	uint32_t hi;

	if (nd->n > 0)
		hi = nd->a + nd->n;
	else
		hi = aggregate(pi, nd->a, aggregate(pi, id + 1, lo));
	*A = (pm_bvh_agg){.patch = pi->patch[pi->prim[lo]], .obj = (int32_t)pi->s->poly_obj[pi->prim[lo]]};
	for (uint32_t i = lo; i < hi; i++) {
		uint32_t g = pi->prim[i];
		A->V = pm_dadd(A->V, pm_dscale(pi->pn[i], pi->pa[i]));
		if (pi->patch[g] != A->patch)
			A->patch = PM_AGG_MIXED;
		if ((int32_t)pi->s->poly_obj[g] != A->obj)
			A->obj = -1;
	}
	double l = pm_dlen(A->V);
	A->M = l > 0 && isfinite(l) ? pm_dscale(A->V, 1 / l) : pm_dv3(0, 0, 0);
	A->cmin = l > 0 && isfinite(l) ? 1 : -2;
	for (uint32_t i = lo; i < hi && A->cmin > -2; i++)
		A->cmin = fmin(A->cmin, pm_ddot(pi->pn[i], A->M));
	A->count = hi - lo;
	return hi;
}

int
pm_polyindex_build(pm_polyindex **out, const pm_scene *s, const pm_vec3 *verts,
                   pm_error *err)
{
	pm_polyindex *pi;
	builder b = {0};
	uint32_t n = 0, j = 0;
	float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};

	*out = NULL;
	/* The scene loader checked all of this; a hand-built scene may not have. */
	for (uint32_t i = 0; i < s->npolys; i++) {
		uint32_t o = s->poly_obj[i];
		if (o >= (uint32_t)s->nobjs || s->objs[o].material < 0
		    || s->objs[o].material >= s->nmats)
			return pm_seterr(err, "polygon %u: object or material out of range", i);
		if (s->poly_start[i + 1] < s->poly_start[i] + 3)
			return pm_seterr(err, "polygon %u: fewer than 3 vertices", i);
		for (uint32_t v = s->poly_start[i]; v < s->poly_start[i + 1]; v++)
			if (s->poly_vert[v] >= s->nverts)
				return pm_seterr(err, "polygon %u: vertex %u out of range", i, s->poly_vert[v]);
		if (pm_mat_is_photon_surface(&s->mats[s->objs[o].material]))
			n++;
	}
	pi = calloc(1, sizeof *pi);
	if (!pi)
		return pm_seterr(err, "out of memory");
	pi->s = s;
	pi->verts = verts;
	pi->nprims = n;
	if (n > 0) {
		/* n < 2^32, so 2n - 1 nodes fit a size_t and the ids fit uint32 */
		pi->prim = malloc((size_t)n * sizeof *pi->prim);
		pi->box = malloc((size_t)n * sizeof *pi->box);
		pi->node = malloc((2 * (size_t)n - 1) * sizeof *pi->node);
		b.cen = malloc((size_t)n * sizeof *b.cen);
		if (!pi->prim || !pi->box || !pi->node || !b.cen) {
			free(b.cen);
			pm_polyindex_free(pi);
			return pm_seterr(err, "out of memory");
		}
	}
	for (uint32_t i = 0; i < s->npolys; i++) {
		if (!pm_mat_is_photon_surface(&s->mats[s->objs[s->poly_obj[i]].material]))
			continue;
		float *bx = pi->box[j];
		for (int k = 0; k < 3; k++) {
			bx[k] = INFINITY;
			bx[3 + k] = -INFINITY;
		}
		for (uint32_t v = s->poly_start[i]; v < s->poly_start[i + 1]; v++) {
			pm_vec3 p = verts[s->poly_vert[v]];
			for (int k = 0; k < 3; k++) {
				float c = pm_vget(p, k);
				/* fminf() and fmaxf() without the calls: a NaN
				 * coordinate is passed over. */
				bx[k] = c < bx[k] ? c : bx[k];
				bx[3 + k] = c > bx[3 + k] ? c : bx[3 + k];
			}
		}
		for (int k = 0; k < 3; k++) {
			b.cen[j][k] = 0.5f * bx[k] + 0.5f * bx[3 + k];
			lo[k] = bx[k] < lo[k] ? bx[k] : lo[k];
			hi[k] = bx[3 + k] > hi[k] ? bx[3 + k] : hi[k];
		}
		pi->prim[j++] = i;
	}
	if (n > 0) {
		b.pi = pi;
		build_node(&b, 0, n);
		for (int k = 0; k < 3; k++)
			pi->extent = fmax(pi->extent, (double)hi[k] - lo[k]);
		if (!isfinite(pi->extent))
			pi->extent = 0;
	}
	free(b.cen);
	pi->convex = calloc((size_t)s->nobjs + 1, 1);
	if (!pi->convex) {
		pm_polyindex_free(pi);
		return pm_seterr(err, "out of memory");
	}
	for (int o = 0; o < s->nobjs; o++)
		pi->convex[o] = (unsigned char)convex_solid(s, &s->objs[o], verts);
	if (pm_scene_patches_at(s, verts, &pi->patch, err) != 0) {
		pm_polyindex_free(pi);
		return -1;
	}
	if (n > 0 && pi->patch && dense_patches(pi) &&
	    !(pi->agg = malloc((size_t)pi->nnodes * sizeof *pi->agg))) {
		pm_polyindex_free(pi);
		return pm_seterr(err, "out of memory");
	}
	if (pi->agg) {
		pi->pn = malloc((size_t)n * sizeof *pi->pn);
		pi->pa = malloc((size_t)n * sizeof *pi->pa);
		if (!pi->pn || !pi->pa) {
			pm_polyindex_free(pi);
			return pm_seterr(err, "out of memory");
		}
		for (uint32_t i = 0; i < n; i++)
			entry_shape(pi, i);
		aggregate(pi, 0, 0);
	}
	*out = pi;
	return 0;
}

void
pm_polyindex_free(pm_polyindex *pi)
{
	if (!pi)
		return;
	free(pi->prim);
	free(pi->box);
	free(pi->node);
	free(pi->convex);
	free(pi->patch);
	free(pi->agg);
	free(pi->pn);
	free(pi->pa);
	free(pi);
}

#define overlaps pm_polyindex_overlaps

/* nextafterf(x, dir * INFINITY), dir = -1 or 1, inlined for finite x:
 * libm's is a call, made six times an estimate. */
static inline float
step_float(float x, int dir)
{
	uint32_t b;

	if (!isfinite(x))
		return nextafterf(x, dir * INFINITY);
	if (x == 0)
		return dir * 0x1p-149f;
	memcpy(&b, &x, sizeof b);
	b += (x > 0) == (dir > 0) ? 1 : (uint32_t)-1;
	memcpy(&x, &b, sizeof x);
	return x;
}

void
pm_polyindex_query_box(pm_dvec3 c, double h, float q[6])
{
	double cc[3] = {c.x, c.y, c.z};

	/* Round the cube outward to float so that float boxes that touch the
	 * exact cube always pass. */
	for (int k = 0; k < 3; k++) {
		q[k] = step_float((float)(cc[k] - h), -1);
		q[3 + k] = step_float((float)(cc[k] + h), 1);
	}
}

void
pm_polyindex_cube(const pm_polyindex *pi, pm_dvec3 c, double h,
                  pm_polyindex_fn fn, void *ctx)
{
	uint32_t stack[STACK];
	int top = 0;
	float q[6];

	if (!pi || pi->nprims == 0 || !(h >= 0))
		return;
	pm_polyindex_query_box(c, h, q);
	/* Children are tested before they are pushed, so a node on the stack
	 * is known to meet the cube; the visiting order (left before right) is
	 * the same as testing on popping, so callers see the same sequence. */
	if (!overlaps(pi->node[0].lo, pi->node[0].hi, q))
		return;
	stack[top++] = 0;
	while (top > 0) {
		const pm_bvh_node *nd = &pi->node[stack[--top]];
		for (;;) {
			if (nd->n > 0) {
				for (uint32_t i = nd->a; i < nd->a + nd->n; i++)
					if (overlaps(pi->box[i], pi->box[i] + 3, q))
						fn(ctx, pi->prim[i]);
				break;
			}
			const pm_bvh_node *l = nd + 1, *r = &pi->node[nd->a];
			int hl = overlaps(l->lo, l->hi, q), hr = overlaps(r->lo, r->hi, q);
			if (hl && hr) {
				if (top + 1 > STACK)
					return;     /* cannot happen with median splits; never overrun */
				stack[top++] = nd->a;
				nd = l;
			} else if (hl)
				nd = l;
			else if (hr)
				nd = r;
			else
				break;
		}
	}
}
