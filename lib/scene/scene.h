/* scene.h — the scene: camera, materials, polygon meshes, lights, motion.
 *
 * Loaded from the text format of formats/scene.md. Geometry is kept as planar
 * polygons (quads stay quads; the compensated estimate clips them, paper §3)
 * and also as triangles for ray casting. Vertices are stored in world space at
 * shutter time t = 0, after each object's transform; an object's linear motion
 * moves it by t * motion at time t in [0, 1]. */
#ifndef PM_SCENE_H
#define PM_SCENE_H

#include <stdint.h>

#include "base/err.h"
#include "base/vec.h"

enum pm_mat_kind { PM_MAT_DIFFUSE, PM_MAT_GLOSSY, PM_MAT_MIRROR, PM_MAT_GLASS };

typedef struct pm_material {
	char name[64];
	int kind;           /* enum pm_mat_kind */
	pm_vec3 kd;         /* diffuse albedo: diffuse, glossy */
	pm_vec3 ks;         /* glossy: specular albedo; mirror: reflectance; glass: tint */
	float exponent;     /* glossy: Blinn exponent */
	float ior;          /* glass: index of refraction (outside is 1) */
	pm_vec3 emit;       /* emitted radiance (W / m^2 / sr per channel); 0 if none */
	int emit_twosided;  /* emits on both sides (otherwise the front only) */
	/* Derived at load: 1 if the view path continues here (mirror, glass,
	 * glossy with exponent >= the scene's glossy threshold), 0 if photons are
	 * stored here and the radiance is estimated (diffuse, soft glossy). */
	int strong;
	/* Textures (formats/scene.md), each an index into scene->texs plus 1,
	 * 0 for none: of kd (albedo), of ks (reflect, tint), of the exponent. */
	int tkd, tks, texp;
} pm_material;

/* An image or a checkerboard, looked up at a point's (u, v) by
 * pm_hit_material (accel.h). */
enum pm_tex_kind { PM_TEX_IMAGE, PM_TEX_CHECKER };
typedef struct pm_texture {
	char name[64];
	int kind;           /* enum pm_tex_kind */
	int w, h;           /* image: w x h linear RGB texels, row 0 the top */
	float *px;
	pm_vec3 c1, c2;     /* checker: the colours of even and odd squares */
	float su, sv, ou, ov;  /* (u, v) -> (u su + ou, v sv + ov) first */
	struct pm_texfilter *filt;  /* image: its filtered lookups (texfilter.h) */
} pm_texture;

typedef struct pm_object {
	int material;       /* index into scene->mats */
	int solid;          /* 1: closed solid, one-sided, outward (front) normals;
	                       0: open sheet, two-sided */
	pm_vec3 motion;     /* world displacement over the shutter interval */
	uint32_t first_poly, npolys;  /* range in the polygon arrays */
	uint32_t first_tri, ntris;    /* range in the triangle arrays */
	uint32_t first_vert, nverts;  /* range in verts */
	int line;           /* scene line that made it, for messages */
	int smooth;         /* 1: its vertices carry shading normals (vnormal) */
	int has_uv;         /* 1: its vertices carry texture coordinates (vuv) */
} pm_object;

/* The lights that are not surfaces (formats/scene.md): point, spot,
 * distant and environment lights. */
enum pm_light_kind { PM_LIGHT_POINT, PM_LIGHT_SPOT, PM_LIGHT_DISTANT, PM_LIGHT_ENV };
enum pm_spot_falloff { PM_FALLOFF_SMOOTH, PM_FALLOFF_LINEAR };

typedef struct pm_pointlight {
	int kind;           /* enum pm_light_kind */
	pm_vec3 pos;        /* at t = 0 (point, spot) */
	/* point: power (W); spot: intensity on the axis (W/sr); distant:
	 * irradiance (W/m^2); environment: radiance (W/m^2/sr), constant or
	 * the image's scale (per channel). */
	pm_vec3 power;
	pm_vec3 motion;
	pm_vec3 dir;        /* spot: unit axis; distant: unit direction of travel */
	float outer, inner; /* spot: half-angles of the cone, degrees */
	int falloff;        /* spot: enum pm_spot_falloff */
	/* environment image: w x h RGB texels, row 0 the top (+y); rot turns
	 * the map's directions into the world's. NULL for a constant sky. */
	float *env;
	int env_w, env_h;
	float rot[3][3];
} pm_pointlight;

typedef struct pm_camera_desc {
	pm_vec3 eye, look, up;
	float fov;          /* full vertical angle, degrees */
	int width, height;  /* pixels */
} pm_camera_desc;

typedef struct pm_scene {
	char *path;              /* as given to pm_scene_load */
	/* Identities (formats/scene.md, "Scene identity"; scene_id.h): of what
	 * the light pass depends on, and of that plus the camera. */
	uint64_t light_hash, view_hash;
	pm_camera_desc camera;
	float glossy_threshold;  /* Blinn exponent at or above which glossy is strong */

	pm_material *mats;  int nmats;
	pm_object *objs;    int nobjs;
	pm_pointlight *lights; int nlights;

	pm_vec3 *verts;     uint32_t nverts;  /* world space at t = 0 */
	/* Shading normals per vertex (unit, toward the front; motion only
	 * translates, so they hold at every time), or NULL if no object is
	 * smooth; 0 for the vertices of objects that are not. */
	pm_vec3 *vnormal;
	/* Texture coordinates per vertex (u, v), or NULL if no object has
	 * them; 0 for the vertices of objects that have not. */
	float (*vuv)[2];
	pm_texture *texs;   int ntexs;

	/* Planar polygons (>= 3 vertices, nonzero area, counter-clockwise seen
	 * from the front). Polygon i has vertices poly_vert[poly_start[i] ..
	 * poly_start[i+1]-1]; poly_normal[i] is its unit normal (Newell's method,
	 * equal to the triangle convention (v1-v0)x(v2-v0) for triangles);
	 * poly_obj[i] is its object. Not necessarily convex. */
	uint32_t npolys;
	uint32_t *poly_start;    /* npolys + 1 entries */
	uint32_t *poly_vert;
	uint32_t *poly_obj;
	pm_vec3 *poly_normal;

	/* Triangulation of the polygons for ray casting (ear clipping, so correct
	 * for concave polygons too). tri_poly[i] is the polygon it came from;
	 * each triangle's winding matches its polygon's. */
	uint32_t ntris;
	uint32_t (*tris)[3];
	uint32_t *tri_poly;
} pm_scene;

/* Loads a scene file; mesh paths in it are relative to the scene file's
 * directory. A camera larger than pm_max_pixels() (maxpixels.h) is refused.
 * On failure err says "FILE:LINE: what is wrong" (or names the
 * mesh file) and *s is left empty. */
int pm_scene_load(pm_scene *s, const char *path, pm_error *err);
void pm_scene_free(pm_scene *s);

/* Vertex positions at shutter time t in [0, 1]: out[i] = verts[i] +
 * t * motion of the vertex's object. out has s->nverts entries. */
void pm_scene_verts_at(const pm_scene *s, float t, pm_vec3 *out);

/* Position of light i (point or spot) at time t. */
pm_vec3 pm_scene_light_at(const pm_scene *s, int i, float t);

/* 1 if photons are stored and radiance estimated at this material (diffuse
 * or soft glossy), 0 if the path continues (mirror, glass, strong glossy). */
static inline int pm_mat_is_photon_surface(const pm_material *m)
{
	return !m->strong;
}

/* 1 if m reflects nothing (an emitter's usual black, a black paint): its
 * BSDF is 0 for every pair of directions, so a photon estimate there is
 * 0 whatever the photons, and a view pass need not make one. Call it on
 * the material with its textures looked up (pm_hit_material). */
static inline int pm_mat_is_black(const pm_material *m)
{
	int kd0 = m->kd.x == 0 && m->kd.y == 0 && m->kd.z == 0;
	int ks0 = m->ks.x == 0 && m->ks.y == 0 && m->ks.z == 0;
	return kd0 && (m->kind == PM_MAT_DIFFUSE || (m->kind == PM_MAT_GLOSSY && ks0));
}

#endif
