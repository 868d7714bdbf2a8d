/* clip.h — the area of a planar polygon inside an axis-aligned cube, for the
 * compensated radiance estimate (Hey & Purgathofer 2001, §3: "clip all
 * diffuse or soft glossy objects that intersect the cube into the cube; ...
 * calculate for each of these polygons its area A_g inside the cube").
 *
 * Coordinates are relative to the cube's centre, in double, so the result is
 * as precise far from the world origin as near it. The cube is closed: a
 * polygon lying exactly in a face plane (z = +h) is inside and keeps its
 * area; one a hair outside (z = h + eps) has none.
 *
 * The clipper is Sutherland & Hodgman's reentrant polygon clipper (1974,
 * "Reentrant Polygon Clipping", CACM 17(1)): the six face planes are stages
 * of a pipeline that pass vertices on one at a time, so clipping needs no
 * buffers and works for any number of vertices. For a concave polygon the
 * output may contain zero-width bridges along a face, which add nothing to
 * the signed area, so the area is exact for any simple polygon. */
#ifndef PM_CLIP_H
#define PM_CLIP_H

#include <stddef.h>

#include "base/vec.h"

/* Streaming state: fill with pm_clip_begin, feed the polygon's vertices in
 * order with pm_clip_vertex, read the area with pm_clip_end. Lives on the
 * caller's stack; no allocation. */
typedef struct pm_clipper {
	double h;
	int off;                   /* degenerate cube: everything is outside */
	struct {
		pm_dvec3 first, prev;
		int count, first_in, prev_in;
	} st[6];                   /* one per face plane */
	int first, next[6];        /* the stages that can cut, in order */
	pm_dvec3 o, prev, sum;     /* area: first output vertex, last, cross sum */
	pm_dvec3 vsum;             /* sum of the output vertices */
	int nout;
	pm_dvec3 *keep;            /* where to copy the output (pm_clip_keep) */
	int keepcap;
} pm_clipper;

/* Starts clipping against the closed cube [-h, h]^3. h <= 0 or not finite
 * gives area 0 for every polygon. */
void pm_clip_begin(pm_clipper *c, double h);

/* Next vertex, relative to the cube centre. */
void pm_clip_vertex(pm_clipper *c, pm_dvec3 v);

/* Closes the polygon and returns the area of its part inside the cube,
 * measured in the plane with unit normal `normal` (pass the polygon's normal;
 * a zero vector measures the plain vector area instead). Always finite and
 * >= 0. The clipper may then be reused with pm_clip_begin. */
double pm_clip_end(pm_clipper *c, pm_dvec3 normal);

/* After pm_clip_end: the mean of the clipped polygon's vertices, a point
 * inside it when the polygon is convex (0 if nothing was inside). */
pm_dvec3 pm_clip_middle(const pm_clipper *c);

/* After pm_clip_begin, before the vertices: the polygon's bounding box
 * (lo, hi per axis, relative to the centre), so that the face planes it
 * does not cross cost nothing. The result is the same as without. */
void pm_clip_bounds(pm_clipper *c, const double lo[3], const double hi[3]);
/* After pm_clip_begin: also copy the clipped polygon's vertices, in order,
 * to buf (room for cap). After pm_clip_end, pm_clip_kept gives their number,
 * or -1 if there were more than cap. */
void pm_clip_keep(pm_clipper *c, pm_dvec3 *buf, int cap);
int pm_clip_kept(const pm_clipper *c);

/* The same clipping for a polygon in an array v[0..n-1] (relative to the
 * centre), stage after stage over buffers rather than vertex by vertex: the
 * same vertices in the same order, so the same area and middle to the bit,
 * at a fraction of the streaming cost for the few-vertex polygons of a mesh
 * (where its buffers would overflow, it streams). lo, hi: the polygon's
 * bounds, as pm_clip_bounds; NULL for none. Writes the clipped polygon to
 * out (room for cap), and its area and middle as pm_clip_end and
 * pm_clip_middle give them; returns what pm_clip_kept would: the vertices
 * written, or -1 if there were more than cap. */
int pm_clip_array(const pm_dvec3 *v, int n, double h, const double *lo, const double *hi,
                  pm_dvec3 normal, pm_dvec3 *out, int cap, double *area, pm_dvec3 *middle);

/* The whole thing for a polygon in an array: v[0..n-1] relative to the
 * centre. */
double pm_clip_area(const pm_dvec3 *v, size_t n, pm_dvec3 normal, double h);

#endif
