/* overlap.h — how much of one polygon another hides along a direction,
 * inside the compensated estimate's cube.
 *
 * When exactly one layer (a rug over a floor, a picture over a wall, a
 * table top over the floor) can be met by the backward rays from a fully
 * seen convex polygon, the part of the polygon whose rays meet it is its
 * overlap with the layer projected along the photon's direction: the
 * estimate takes that area exactly instead of from sample points
 * (compensate.c). All geometry in double, relative to the cube centre. */
#ifndef PM_OVERLAP_H
#define PM_OVERLAP_H

#include "base/vec.h"

/* Most vertices a polygon of n vertices can have after clipping to the
 * cube: every face plane adds at most one. */
#define PM_OVERLAP_MAXV(n) ((n) + 6)

/* Clips polygon in[0..n-1] (relative to the centre) to the closed cube
 * [-h, h]^3 (Sutherland-Hodgman, 6 planes); out has room for n + 6
 * vertices. Returns the number of vertices out (0 if nothing is inside). */
int pm_clip_poly(const pm_dvec3 *in, int n, double h, pm_dvec3 *out);

/* 1 if the polygon is convex in the plane with unit normal N (collinear
 * vertices allowed), 0 otherwise. */
int pm_poly_convex(const pm_dvec3 *v, int n, pm_dvec3 N);

/* Area of the part of convex polygon b (unit normal nb) covered by polygon
 * a projected onto b's plane along direction d (d . nb != 0): the area of b
 * hidden behind a for light travelling along d. scratch has room for
 * 2 * (na + nb) + 8 vertices. Returns 0 if d is parallel to b's plane. */
double pm_overlap_area(const pm_dvec3 *a, int na, const pm_dvec3 *b, int nb,
                       pm_dvec3 nb_unit, pm_dvec3 d, pm_dvec3 *scratch);

#endif
