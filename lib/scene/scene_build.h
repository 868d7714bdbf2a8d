/* scene_build.h — the building half of the scene loader: a pm_scene's
 * arrays grown one material, light and object at a time from values that
 * scene.c has already parsed and checked. It knows nothing of tokens or
 * lines; its messages start with the statement they came from (`what`), and
 * scene.c puts "FILE:LINE: " before them. */
#ifndef PM_SCENE_BUILD_H
#define PM_SCENE_BUILD_H

#include <stddef.h>
#include <stdint.h>

#include "base/err.h"
#include "scene/scene.h"
#include "scene/scene_shape.h"

/* One affine map x -> m[0..2][0..2] x + m[.][3]. */
typedef struct { double m[3][4]; } pm_xform;

void pm_xform_identity(pm_xform *x);
/* x = a then x (a applied after what x already does). */
void pm_xform_then(pm_xform *x, const double a[3][4]);

/* The scene being built and what building needs besides it. Zero it, set
 * s, and release the scratch with pm_build_free (s keeps the arrays). */
typedef struct pm_scene_build {
	pm_scene *s;
	/* capacities of the growing arrays in s */
	size_t cap_mats, cap_objs, cap_lights, cap_verts, cap_polys, cap_pverts, cap_tris;
	size_t cap_vnormal, cap_vuv, cap_texs;
	void *work;         /* triangulation scratch */
	size_t work_size;
	uint32_t (*tribuf)[3];
	size_t tribuf_n;
} pm_scene_build;

/* An object: a shape in object space placed by xf. */
typedef struct pm_build_obj {
	const pm_shape *shape;
	pm_xform xf;
	pm_vec3 motion;     /* world displacement over the shutter interval */
	int material;       /* index into s->mats */
	int solid;          /* a closed surface (pm_object.solid) */
	int flip;           /* reverse the shape's faces */
	int line;           /* pm_object.line */
	const char *what;   /* the statement, for messages: "box", "mesh 'x.obj'" */
	int normals;        /* PM_NORMALS_*: the object's shading normals */
} pm_build_obj;

enum {
	PM_NORMALS_FLAT,    /* none: the facets' own */
	PM_NORMALS_SHAPE,   /* the shape's (shape->normals), transformed */
	PM_NORMALS_SMOOTH,  /* each vertex's faces' normals weighted by their angle there */
};

/* Each appends one item to b->s; 0, or -1 with a message when a bound of
 * formats/scene.md is passed, out of memory, or (objects) a vertex is out of
 * float range or no face has area. Faces with repeated corners lose them,
 * faces without area are dropped, non-planar faces split into triangles. */
int pm_build_material(pm_scene_build *b, const pm_material *m, pm_error *err);
int pm_build_texture(pm_scene_build *b, const pm_texture *t, pm_error *err);
int pm_build_light(pm_scene_build *b, const pm_pointlight *l, pm_error *err);
int pm_build_object(pm_scene_build *b, const pm_build_obj *ob, pm_error *err);

void pm_build_free(pm_scene_build *b);

#endif
