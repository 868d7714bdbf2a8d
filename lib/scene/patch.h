/* patch.h — a scene's polygons grouped into smooth patches: polygons of one
 * object that meet at a vertex (the same position) with normals less than
 * 30 degrees apart are in one patch, and so, through such neighbours, is
 * the whole smooth surface they belong to (a tessellated sphere, torus or
 * scanned head is one patch; a box is six). The view pass shares a pixel's
 * photon estimate among its camera samples that land on one patch
 * (lib/passes/render.c): the partition is fixed before any sample is
 * taken, which is what keeps that sharing unbiased. */
#ifndef PM_PATCH_H
#define PM_PATCH_H

#include <stdint.h>

#include "base/err.h"
#include "scene/scene.h"

/* Normals at least this aligned (cos 30 degrees) are one smooth surface. */
#define PM_PATCH_COS 0.866f

/* *patch gets s->npolys entries: each polygon's patch, the lowest polygon
 * number in it. The caller frees it. Deterministic. */
int pm_scene_patches(const pm_scene *s, uint32_t **patch, pm_error *err);
/* The same with the vertices at one shutter time (pm_scene_verts_at). */
int pm_scene_patches_at(const pm_scene *s, const pm_vec3 *verts, uint32_t **patch, pm_error *err);

#endif
