/* polyindex.h — the index over a scene's photon-surface polygons that the
 * compensated estimate asks "which polygons may meet this cube?" (paper §3),
 * at one shutter time.
 *
 * A bounding volume hierarchy with median splits: float boxes that bound the
 * float vertices exactly, queries with the cube rounded outward to float, so
 * no polygon that touches the closed cube is ever missed. Read-only after
 * build, so any number of threads may query it at once. */
#ifndef PM_POLYINDEX_H
#define PM_POLYINDEX_H

#include <stdint.h>

#include "base/err.h"
#include "scene/scene.h"
#include "base/vec.h"

typedef struct pm_polyindex pm_polyindex;

/* verts: the scene's vertices at the pass's time (pm_scene_verts_at); the
 * index keeps pointers to s and verts, which must outlive it. */
int pm_polyindex_build(pm_polyindex **out, const pm_scene *s,
                       const pm_vec3 *verts, pm_error *err);
void pm_polyindex_free(pm_polyindex *pi);

typedef struct pm_bvh_node {
	float lo[3], hi[3];
	uint32_t a;       /* leaf: first entry in prim[]; inner: right child */
	uint32_t n;       /* leaf: entries (> 0); inner: 0 (left child is next) */
} pm_bvh_node;

/* What the polygons under one node share, for the compensated estimate,
 * which takes a node that lies wholly inside its cube as one piece of a
 * sheet rather than polygon by polygon. Areas are of the whole polygons,
 * unit normals their poly_normal's, both in double. */
#define PM_AGG_MIXED UINT32_MAX
typedef struct pm_bvh_agg {
	pm_dvec3 V;                /* sum of area times unit normal */
	pm_dvec3 M;                /* V's direction (unit), 0 if V is 0 */
	double cmin;               /* least N . M over the polygons: a cone */
	uint32_t patch;            /* the smooth patch of them all, or PM_AGG_MIXED */
	int32_t obj;               /* the object of them all, or -1 */
	uint32_t count;            /* polygons */
} pm_bvh_agg;

struct pm_polyindex {
	const pm_scene *s;
	const pm_vec3 *verts;      /* the scene's vertices at the pass's time */
	uint32_t nprims;           /* photon-surface polygons */
	uint32_t *prim;            /* their polygon numbers, in leaf order */
	float (*box)[6];           /* their boxes (lo xyz, hi xyz), same order */
	pm_bvh_node *node;
	uint32_t nnodes;
	double extent;             /* largest side of all their boxes together */
	unsigned char *convex;     /* per object: a convex solid */
	uint32_t *patch;           /* per polygon: its smooth patch (scene/patch.h) */
	pm_bvh_agg *agg;           /* per node */
	pm_dvec3 *pn;              /* per entry (prim order): unit normal, */
	double *pa;                /* ... and area */
};

/* Calls fn(ctx, polygon) for every photon-surface polygon whose bounding box
 * meets the closed cube of half-size h centred at c (each at most once). */
typedef void (*pm_polyindex_fn)(void *ctx, uint32_t poly);
void pm_polyindex_cube(const pm_polyindex *pi, pm_dvec3 c, double h,
                       pm_polyindex_fn fn, void *ctx);

/* The query box of pm_polyindex_cube: the cube rounded outward to float
 * (lo xyz, hi xyz), and the test it applies to a box. */
void pm_polyindex_query_box(pm_dvec3 c, double h, float q[6]);
static inline int
pm_polyindex_overlaps(const float *lo, const float *hi, const float q[6])
{
	return lo[0] <= q[3] && hi[0] >= q[0] && lo[1] <= q[4] && hi[1] >= q[1]
	    && lo[2] <= q[5] && hi[2] >= q[2];
}

#endif
