/* scene_shape.h — the scene format's built-in shapes (quad, box, sphere, disk) as
 * vertex and polygon lists in object space, before the object's transform.
 * Faces are counter-clockwise seen from the front (outside, for solids). */
#ifndef PM_SCENE_SHAPE_H
#define PM_SCENE_SHAPE_H

#include <stdint.h>

#include "base/vec.h"

#define PM_SPHERE_MAX_SUBDIV 10
#define PM_SPHERE_DEFAULT_SUBDIV 4

/* The same layout as pm_meshdata, so mesh files and shapes build objects
 * through one path. */
typedef struct pm_shape {
	uint32_t nverts;
	double *verts;          /* 3 * nverts */
	uint32_t nfaces;
	uint32_t *face_start;   /* nfaces + 1 */
	uint32_t *face_vert;
	double *normals;        /* 3 * nverts shading normals, or NULL */
	double *uv;             /* 2 * nverts texture coordinates, or NULL */
} pm_shape;

/* Checks the 4 corners c[12] of a quad: 0 if usable, else a code for
 * pm_shape_quad_problem (zero area, not coplanar, edges crossing). */
int pm_shape_quad_check(const double c[12]);
const char *pm_shape_quad_problem(int code);

/* Each returns 0, or -1 if out of memory. Free with pm_shape_free. */
/* One face with corners c[0 .. 3n-1] (n = 3 for a triangle, 4 for a quad). */
int pm_shape_polygon(pm_shape *sh, const double *c, uint32_t n);
/* Axis-aligned box from corner c[0..2] to c[3..5] (c[k] < c[k+3]): 8
 * vertices, 6 quads with outward normals. */
int pm_shape_box(pm_shape *sh, const double c[6]);
/* Sphere of center c[0..2] and radius c[3], as a latitude-longitude grid:
 * 2^(subdiv+1) bands of latitude around the y axis and twice as many of
 * longitude; quads between bands, triangles at the poles. The vertices lie on
 * the sphere. */
int pm_shape_sphere(pm_shape *sh, const double c[4], int subdiv);

/* Disk of center c, front normal n (not zero) and radius r: one polygon of
 * PM_DISK_CORNERS corners, its radius stretched so that its area is pi r^2. */
#define PM_DISK_CORNERS 64
int pm_shape_disk(pm_shape *sh, pm_dvec3 c, pm_dvec3 n, double r);

void pm_shape_free(pm_shape *sh);

#endif
