/* edge.c — is a point within one cube of an edge or corner? (edge.h).
 * Used to tell the pixels whose estimate's support reaches another surface
 * (where classical and compensated estimates differ, paper §1) from the rest. */
#include <math.h>

#include "estimators/clip.h"
#include "estimators/edge.h"

typedef struct edge_query {
	const pm_polyindex *pi;
	pm_dvec3 x;
	double h;
	int found;
} edge_query;

static void
visit(void *ctx, uint32_t poly)
{
	edge_query *q = ctx;
	const pm_scene *s = q->pi->s;
	pm_dvec3 n = pm_dfromf(s->poly_normal[poly]), v0;
	pm_clipper c;

	if (q->found)
		return;
	v0 = pm_dsub(pm_dfromf(q->pi->verts[s->poly_vert[s->poly_start[poly]]]), q->x);
	/* In the plane of x (up to float rounding of the vertices): not an edge. */
	if (fabs(pm_ddot(v0, n)) <= 1e-4 * q->h)
		return;
	uint32_t nv = s->poly_start[poly + 1] - s->poly_start[poly];
	if (nv <= 16) {
		/* The array clipper: the same area, for less. */
		pm_dvec3 v[16], out[64], mid;
		double a;
		for (uint32_t i = 0; i < nv; i++)
			v[i] = pm_dsub(pm_dfromf(q->pi->verts[s->poly_vert[s->poly_start[poly] + i]]), q->x);
		pm_clip_array(v, (int)nv, q->h, NULL, NULL, n, out, 64, &a, &mid);
		q->found = a > 0;
		return;
	}
	pm_clip_begin(&c, q->h);
	for (uint32_t i = s->poly_start[poly]; i < s->poly_start[poly + 1]; i++)
		pm_clip_vertex(&c, pm_dsub(pm_dfromf(q->pi->verts[s->poly_vert[i]]), q->x));
	if (pm_clip_end(&c, n) > 0)
		q->found = 1;
}

int
pm_polyindex_near_edge(const pm_polyindex *pi, pm_vec3 x, double h)
{
	edge_query q = {pi, pm_dfromf(x), h, 0};

	if (!pi || !(h > 0))
		return 0;
	pm_polyindex_cube(pi, q.x, h, visit, &q);
	return q.found;
}
