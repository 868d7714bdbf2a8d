/* scene_poly.h — plane geometry of one polygon for the scene loader: Newell
 * normal, degeneracy and flatness tests, ear-clipping triangulation.
 *
 * A polygon is given as vertex positions v and a list of n indices into v,
 * counter-clockwise seen from the front. Arithmetic is in double. */
#ifndef PM_SCENE_POLY_H
#define PM_SCENE_POLY_H

#include <stddef.h>
#include <stdint.h>

#include "base/vec.h"

/* Newell's method (Sutherland, Sproull & Schumacker 1974; see also Tampieri,
 * "Newell's Method for Computing the Plane Equation of a Polygon", Graphics
 * Gems III): the sum of the edge cross products. Its length is twice the area
 * of the polygon's projection on its plane, its direction the front normal;
 * for a triangle it equals (v1 - v0) x (v2 - v0). */
pm_dvec3 pm_poly_newell(const pm_vec3 *v, const uint32_t *idx, uint32_t n);

/* 1 if the polygon has (near-)zero area: its mean width, 2 * area / size, is
 * below what float coordinates of this size and magnitude resolve. */
int pm_poly_degenerate(const pm_vec3 *v, const uint32_t *idx, uint32_t n);

/* 1 if every vertex lies within a small relative tolerance of the plane
 * through the centroid with Newell normal nrm (nonzero). */
int pm_poly_planar(const pm_vec3 *v, const uint32_t *idx, uint32_t n, pm_dvec3 nrm);

/* Ear clipping (Meisters 1975, "Polygons have ears"; as in Eberly,
 * "Triangulation by Ear Clipping"): projects the polygon on the plane normal
 * to nrm and cuts off convex vertices whose triangle holds no other vertex.
 * Correct for simple polygons, concave ones included; for others it still
 * ends, with a fallback cut. Triangles keep the polygon's winding; each entry
 * of tri is three vertex indices (values from idx). Collinear vertices are cut
 * without emitting a zero-area triangle, so at most n - 2 triangles result.
 * work must hold PM_POLY_WORK_BYTES(n) bytes, suitably aligned for double.
 * Returns the number of triangles written. */
#define PM_POLY_WORK_BYTES(n) ((size_t)(n) * (2 * sizeof(double) + sizeof(uint32_t)))
uint32_t pm_poly_triangulate(const pm_vec3 *v, const uint32_t *idx, uint32_t n,
	pm_dvec3 nrm, uint32_t (*tri)[3], void *work);

#endif
