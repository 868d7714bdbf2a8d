/* accel.h — ray casting against the scene's triangles at one shutter time,
 * through Embree 3 (embree3/rtcore.h).
 *
 * Built once per pass from the scene's vertices at the pass's time; then
 * read-only and safe to query from many threads. The BVH is built on one
 * thread so the result cannot depend on the thread count. */
#ifndef PM_ACCEL_H
#define PM_ACCEL_H

#include "base/err.h"
#include "scene/scene.h"
#include "base/vec.h"

typedef struct pm_accel pm_accel;

typedef struct pm_hit {
	float t;            /* distance along the (unit) ray direction */
	pm_vec3 p;          /* hit point */
	pm_vec3 ng;         /* unit geometric front normal of the polygon hit */
	uint32_t tri, poly; /* triangle and polygon index */
	int obj;            /* object index */
	float u, v;         /* barycentrics: p = (1-u-v) t0 + u t1 + v t2 of tris[tri] */
} pm_hit;

/* The shading normal at h, toward the front: its vertices' normals
 * interpolated (scene.h, vnormal) if its object is smooth, else h->ng; ng
 * too where the interpolation fails or faces away from ng. */
pm_vec3 pm_hit_shading(const pm_scene *s, const pm_hit *h);

/* The material at h: its object's, or, where that material has textures,
 * a copy in *tmp with them looked up at h's texture coordinates (its
 * vertices' (u, v) interpolated; (0, 0) for an object without).
 * Reflectances are clamped to [0, 1], and a glossy kd + ks above 1 in a
 * channel scaled down to 1, so no texel makes energy. */
const pm_material *pm_hit_material(const pm_scene *s, const pm_hit *h, pm_material *tmp);

/* pm_hit_material with each texture averaged over the footprint whose
 * axes a1, a2 (world space, in the facet's plane) are centred at h: a
 * camera pixel's where a camera ray first meets a surface
 * (pm_pixel_footprint), so a distant texture reads its mean there and
 * does not alias. a1 = a2 = 0 is pm_hit_material. */
const pm_material *pm_hit_material_fp(const pm_scene *s, const pm_hit *h, pm_vec3 a1, pm_vec3 a2,
                                      pm_material *tmp);

/* The footprint's axes, on h's facet, of a camera sample that spans the
 * angle pixel_angle seen along the ray direction d: across, pixel_angle * h->t;
 * along d's slant, that over the cosine to the facet (the cosine taken no
 * smaller than 0.02). */
void pm_pixel_footprint(const pm_hit *h, pm_vec3 d, float pixel_angle, pm_vec3 *a1, pm_vec3 *a2);

/* A texture's value at (u, v) (formats/scene.md): bilinear between texels
 * of an image repeated in u and v, v = 0 its bottom row. */
pm_vec3 pm_texture_at(const pm_texture *t, float u, float v);

/* Its mean over the footprint centred at (u, v) with axes (du1, dv1) and
 * (du2, dv2) in (u, v) (before the texture's scale): a checker's exact
 * mean over the footprint's bounding box; an image's from OpenImageIO's
 * MIP levels (texfilter.h) where the footprint spans more than a texel,
 * else pm_texture_at. */
pm_vec3 pm_texture_filtered(const pm_texture *t, float u, float v, float du1, float dv1,
                            float du2, float dv2);

/* verts: positions at the pass's time (pm_scene_verts_at); copied. */
int pm_accel_build(pm_accel **out, const pm_scene *s, const pm_vec3 *verts, pm_error *err);
void pm_accel_free(pm_accel *a);

/* Closest hit of the ray o + t d, t in (tmin, tmax); returns 1 and fills *h,
 * or 0 for a miss. d must be unit length. A ray Embree cannot take (a
 * coordinate beyond 1.8e18 or NaN) misses, and is occluded below. */
int pm_accel_hit(const pm_accel *a, pm_vec3 o, pm_vec3 d, float tmin, float tmax, pm_hit *h);

/* 1 if anything blocks the segment o + t d, t in (tmin, tmax). */
int pm_accel_occluded(const pm_accel *a, pm_vec3 o, pm_vec3 d, float tmin, float tmax);

/* A ray origin nudged off a surface at p with unit normal ng toward the side
 * of direction d, by an amount that scales with the scene's size and with
 * the coordinates' magnitude (float spacing), so self-hits are avoided near
 * and far from the origin alike. */
pm_vec3 pm_accel_offset(const pm_accel *a, pm_vec3 p, pm_vec3 ng, pm_vec3 d);

/* The size of that nudge at p: also how far short of a target point a
 * shadow ray must stop so as not to hit the target's own surface. */
float pm_accel_eps(const pm_accel *a, pm_vec3 p);

#endif
