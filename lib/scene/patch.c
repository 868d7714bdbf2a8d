/* patch.c — smooth patches (patch.h): the polygons' corners grouped by
 * object and position, so that the polygons meeting at one point are found
 * together; those pairs with aligned normals joined in a union-find whose
 * roots are the lowest polygon numbers, which makes the result the same
 * whatever order the pairs come in. Positions compare by their float bits,
 * so a polygon soup (every face its own vertices, as flat-shaded exports
 * write them) joins as a shared-vertex mesh does. */
#include "scene/patch.h"

#include <stdlib.h>
#include <string.h>

/* A point: an object and the bits of a position. */
typedef struct point {
	uint32_t obj, key[3];
} point;

static uint32_t
find(uint32_t *up, uint32_t i)
{
	while (up[i] != i) {
		up[i] = up[up[i]];
		i = up[i];
	}
	return i;
}

static uint32_t
bits(float f)
{
	uint32_t u;

	f = f == 0 ? 0.0f : f;  /* -0 and +0 are one point */
	memcpy(&u, &f, sizeof u);
	return u;
}

static uint64_t
point_hash(const point *p)
{
	uint64_t h = p->obj;

	for (int i = 0; i < 3; i++)
		h = (h ^ p->key[i]) * 0x9e3779b97f4a7c15u;
	return h ^ (h >> 29);
}

int
pm_scene_patches(const pm_scene *s, uint32_t **patch, pm_error *err)
{
	return pm_scene_patches_at(s, s->verts, patch, err);
}

int
pm_scene_patches_at(const pm_scene *s, const pm_vec3 *verts, uint32_t **patch, pm_error *err)
{
	uint32_t n = s->npolys, nc = n ? s->poly_start[n] : 0, np = 0, *up, *slot, *of, *first, *by;
	size_t cap = 16;
	point *pt;

	*patch = NULL;
	while (cap < 2 * (size_t)nc)
		cap *= 2;
	up = malloc((n ? n : 1) * sizeof *up);
	pt = malloc((nc ? nc : 1) * sizeof *pt);
	of = malloc((nc ? nc : 1) * sizeof *of);
	first = malloc(((size_t)nc + 1) * sizeof *first);
	by = malloc((nc ? nc : 1) * sizeof *by);
	slot = malloc(cap * sizeof *slot);
	if (!up || !pt || !of || !first || !by || !slot) {
		free(up);
		free(pt);
		free(of);
		free(first);
		free(by);
		free(slot);
		return pm_seterr(err, "out of memory for %u polygons' patches", n);
	}
	/* Each corner's point numbered in a hash table (open addressing, at
	 * most half full), then the corners listed point by point. */
	memset(slot, 0xff, cap * sizeof *slot);
	for (uint32_t i = 0; i < n; i++) {
		up[i] = i;
		for (uint32_t v = s->poly_start[i]; v < s->poly_start[i + 1]; v++) {
			pm_vec3 p = verts[s->poly_vert[v]];
			point q = {s->poly_obj[i], {bits(p.x), bits(p.y), bits(p.z)}};
			size_t h = point_hash(&q) & (cap - 1);
			while (slot[h] != UINT32_MAX && memcmp(&pt[slot[h]], &q, sizeof q))
				h = (h + 1) & (cap - 1);
			if (slot[h] == UINT32_MAX) {
				slot[h] = np;
				pt[np++] = q;
			}
			of[v] = slot[h];
		}
	}
	memset(first, 0, ((size_t)np + 1) * sizeof *first);
	for (uint32_t v = 0; v < nc; v++)
		first[of[v] + 1]++;
	for (uint32_t a = 0; a < np; a++)
		first[a + 1] += first[a];
	for (uint32_t i = 0; i < n; i++)
		for (uint32_t v = s->poly_start[i]; v < s->poly_start[i + 1]; v++)
			by[first[of[v]]++] = i;
	/* first[a] is now where point a + 1's polygons start. */
	for (uint32_t a = 0, b0 = 0; a < np; b0 = first[a++]) {
		/* The polygons at this point, pairwise: a pole of a sphere has
		 * as many as the sphere has segments. */
		for (uint32_t i = b0; i < first[a]; i++)
			for (uint32_t j = i + 1; j < first[a]; j++) {
				uint32_t p = by[i], q = by[j], rp, rq;
				if (pm_dot(s->poly_normal[p], s->poly_normal[q]) < PM_PATCH_COS)
					continue;
				rp = find(up, p);
				rq = find(up, q);
				if (rp < rq)
					up[rq] = rp;
				else if (rq < rp)
					up[rp] = rq;
			}
	}
	free(pt);
	free(of);
	free(first);
	free(by);
	free(slot);
	for (uint32_t i = 0; i < n; i++)
		up[i] = find(up, i);
	*patch = up;
	return 0;
}
