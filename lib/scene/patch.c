/* patch.c — smooth patches (patch.h): the polygons' corners sorted by
 * object and position, so that the polygons meeting at one point are
 * neighbours in that order; those pairs with aligned normals joined in a
 * union-find whose roots are the lowest polygon numbers. Positions compare
 * by their float bits, so a polygon soup (every face its own vertices, as
 * flat-shaded exports write them) joins as a shared-vertex mesh does. */
#include "scene/patch.h"

#include <stdlib.h>
#include <string.h>

typedef struct corner {
	uint32_t obj, key[3], poly;
} corner;

static int
cmp_corner(const void *pa, const void *pb)
{
	const corner *a = pa, *b = pb;

	if (a->obj != b->obj)
		return a->obj < b->obj ? -1 : 1;
	for (int i = 0; i < 3; i++)
		if (a->key[i] != b->key[i])
			return a->key[i] < b->key[i] ? -1 : 1;
	return (a->poly > b->poly) - (a->poly < b->poly);
}

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

int
pm_scene_patches(const pm_scene *s, uint32_t **patch, pm_error *err)
{
	return pm_scene_patches_at(s, s->verts, patch, err);
}

int
pm_scene_patches_at(const pm_scene *s, const pm_vec3 *verts, uint32_t **patch, pm_error *err)
{
	uint32_t n = s->npolys, nc = n ? s->poly_start[n] : 0, *up;
	corner *c;

	*patch = NULL;
	up = malloc((n ? n : 1) * sizeof *up);
	c = malloc((nc ? nc : 1) * sizeof *c);
	if (!up || !c) {
		free(up);
		free(c);
		return pm_seterr(err, "out of memory for %u polygons' patches", n);
	}
	for (uint32_t i = 0; i < n; i++) {
		up[i] = i;
		for (uint32_t v = s->poly_start[i]; v < s->poly_start[i + 1]; v++) {
			pm_vec3 p = verts[s->poly_vert[v]];
			c[v] = (corner){s->poly_obj[i], {bits(p.x), bits(p.y), bits(p.z)}, i};
		}
	}
	qsort(c, nc, sizeof *c, cmp_corner);
	for (uint32_t a = 0, b; a < nc; a = b) {
		for (b = a + 1; b < nc && c[b].obj == c[a].obj && !memcmp(c[b].key, c[a].key, sizeof c[a].key); b++)
			;
		/* The polygons at this point, pairwise: a pole of a sphere has
		 * as many as the sphere has segments. */
		for (uint32_t i = a; i < b; i++)
			for (uint32_t j = i + 1; j < b; j++) {
				uint32_t p = c[i].poly, q = c[j].poly, rp, rq;
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
	free(c);
	for (uint32_t i = 0; i < n; i++)
		up[i] = find(up, i);
	*patch = up;
	return 0;
}
