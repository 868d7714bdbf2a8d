/* desc.h — a scene read from another renderer's file, before it becomes a
 * pm scene: what every reader (pbrt.c, mitsuba.c, objmtl.c) fills in and the
 * one writer (write.c) turns into a .pms. Everything here is in the source
 * renderer's world, in its units, and physically described (radiance,
 * intensity, reflectance at normal incidence, microfacet roughness), so the
 * writer maps each kind by one rule whatever the format (README, "Your own
 * scenes"). Each item keeps the file and line it came from. */
#ifndef PM_IMPORT_DESC_H
#define PM_IMPORT_DESC_H

#include <stddef.h>
#include <stdint.h>

#include "base/err.h"

/* Where an item came from: files[file] of the description, line (1-based;
 * 0 for a whole file). */
typedef struct pmi_src {
	int file;
	int line;
} pmi_src;

/* Which image axis the field of view spans. */
enum pmi_fov_axis { PMI_FOV_X, PMI_FOV_Y, PMI_FOV_SHORTER, PMI_FOV_LONGER, PMI_FOV_DIAGONAL };

typedef struct pmi_camera {
	int set;
	pmi_src src;
	/* In the source world: the eye, and the directions of the image's
	 * right edge, of its top and of the view. Whether they form a right-
	 * or left-handed frame is the source's business; the writer mirrors
	 * the world when pm's right-handed camera could not show it. */
	double pos[3], right[3], up[3], fwd[3];
	double fov;          /* full angle in degrees along fov_axis */
	int fov_axis;
	int width, height;   /* pixels */
} pmi_camera;

/* Materials as physics describes them; the writer's table maps each kind. */
enum pmi_mat_kind {
	PMI_MAT_DIFFUSE,     /* Lambertian: color */
	PMI_MAT_COATED,      /* color under a dielectric coat of ior eta, roughness alpha */
	PMI_MAT_CONDUCTOR,   /* metal: spec = reflectance at normal incidence, alpha */
	PMI_MAT_DIELECTRIC,  /* glass of ior eta, alpha, trans = tint */
	PMI_MAT_THIN,        /* thin dielectric pane of ior eta */
	PMI_MAT_DIFFTRANS,   /* color reflected, trans transmitted, both diffusely */
	PMI_MAT_PHONG,       /* color diffuse + spec specular with exponent (OBJ+MTL) */
	PMI_MAT_INVISIBLE,   /* no surface (pbrt's interface): only bounds a medium */
};

typedef struct pmi_material {
	char name[64];       /* the source's name, or "" */
	char type[32];       /* the source's type word, for reports */
	pmi_src src;
	int kind;
	double color[3], spec[3], trans[3];
	double eta;          /* index of refraction (dielectric, thin, coat) */
	double alpha;        /* microfacet roughness alpha, 0 = smooth */
	double exponent;     /* Phong exponent (PMI_MAT_PHONG) */
	/* A colour given by a texture: its name for reports, and tex, 1 +
	 * the index in texs of its description (0 where the reader could not
	 * describe it: the writer then uses color and reports the name). The
	 * texture replaces color (spec for a conductor). */
	char texture[256];
	int tex;
} pmi_material;

/* A texture pm can draw (formats/scene.md, "texture"): an image or a
 * checkerboard over the surface's (u, v) mapped to (u su + ou, v sv + ov). */
enum pmi_tex_kind { PMI_TEX_IMAGE, PMI_TEX_CHECKER };

typedef struct pmi_texture {
	pmi_src src;
	int kind;
	char file[4096];      /* image: its path as the reader resolved it */
	double c[2][3];       /* checker: the colours where floor(u) + floor(v)
	                       * is even and odd */
	double su, sv, ou, ov;
} pmi_texture;

enum pmi_shape_kind { PMI_SHAPE_MESH, PMI_SHAPE_SPHERE };

typedef struct pmi_shape {
	pmi_src src;
	int kind;
	int mat;              /* index into mats, -1 for none (the writer's default) */
	double emit[3];       /* radiance, all 0 for none */
	int twosided;         /* emits from both sides */
	double center[3], radius;   /* sphere */
	/* mesh: positions in the source world; polygons with corners counter-
	 * clockwise seen from the front (the side the surface's normal points
	 * to, which is where a one-sided emitter shines and what glass calls
	 * outside). uv may be NULL. */
	size_t nv, nface;
	float *v, *uv;
	float *n;             /* per-vertex shading normals, or NULL */
	uint32_t *start;      /* nface + 1 entries into idx */
	uint32_t *idx;
} pmi_shape;

enum pmi_light_kind { PMI_LIGHT_POINT, PMI_LIGHT_SPOT, PMI_LIGHT_DISTANT, PMI_LIGHT_INFINITE, PMI_LIGHT_OTHER };

typedef struct pmi_light {
	pmi_src src;
	int kind;
	char type[32];        /* the source's type word */
	double pos[3];        /* point, spot */
	double dir[3];        /* spot, distant: the direction light travels */
	double color[3];      /* point, spot: intensity (W/sr); distant: irradiance
	                       * on a surface facing it; infinite: radiance */
	double cone, falloff; /* spot: the cone's half-angle and the width of
	                       * its falloff inside it, degrees */
	int linear;           /* spot: falloff linear in the angle (Mitsuba),
	                       * else smoothstep in the cosine (pbrt-v4) */
	char map[4096];       /* infinite: an environment image, or "" */
	int equal_area;       /* map is pbrt-v4's equal-area square, else lat-long */
	double map_scale;     /* infinite map: multiplies its texels (0 = 1) */
	int has_rot;          /* infinite map: rot is its to_world's linear part */
	double rot[3][3];
} pmi_light;

typedef struct pmi_note {
	pmi_src src;
	int count;            /* how many times the same message was noted */
	char msg[300];
} pmi_note;

typedef struct pmi_desc {
	char **files; int nfiles;
	pmi_camera cam;
	pmi_material *mats; size_t nmats, capmats;
	pmi_shape *shapes; size_t nshapes, capshapes;
	pmi_light *lights; size_t nlights, caplights;
	pmi_texture *texs; size_t ntexs, captexs;
	pmi_note *notes; size_t nnotes, capnotes;
} pmi_desc;

void pmi_init(pmi_desc *d);
void pmi_free(pmi_desc *d);

/* The index of file path in d->files (added if new), or -1 out of memory. */
int pmi_file(pmi_desc *d, const char *path);

/* New zeroed items at the end of their arrays; NULL out of memory. */
pmi_material *pmi_add_material(pmi_desc *d, pmi_src src);
pmi_shape *pmi_add_shape(pmi_desc *d, pmi_src src);
pmi_light *pmi_add_light(pmi_desc *d, pmi_src src);
pmi_texture *pmi_add_texture(pmi_desc *d, pmi_src src);   /* scale 1 1, offset 0 0 */
void pmi_shape_free(pmi_shape *s);

/* Records what was approximated or dropped. The same message noted again
 * counts up the first one's count. Returns -1 out of memory. */
int pmi_note_add(pmi_desc *d, pmi_src src, const char *fmt, ...)
	__attribute__((format(printf, 3, 4)));

/* "FILE:LINE" of src into buf (returns buf). */
const char *pmi_where(const pmi_desc *d, pmi_src src, char *buf, size_t n);

/* An error at src: "FILE:LINE: message". Returns -1. */
int pmi_err(const pmi_desc *d, pmi_src src, pm_error *err, const char *fmt, ...)
	__attribute__((format(printf, 4, 5)));

/* Reflectance at normal incidence, linear RGB, of the metal with chemical
 * symbol sym (Au, Ag, Cu, Al, CuZn, Cr, Ni, Ti, Fe, Pt, W, Hg); -1 if
 * unknown. */
int pmi_metal_f0(const char *sym, double f0[3]);

/* 4x4 affine transforms, row-major, acting on column vectors. */
typedef struct pmi_mat4 { double m[4][4]; } pmi_mat4;
pmi_mat4 pmi_identity(void);
pmi_mat4 pmi_mul(pmi_mat4 a, pmi_mat4 b);          /* a b: b applied first */
int pmi_invert(pmi_mat4 a, pmi_mat4 *out);         /* -1 if singular */
pmi_mat4 pmi_translate(double x, double y, double z);
pmi_mat4 pmi_scale(double x, double y, double z);
pmi_mat4 pmi_rotate(double deg, double x, double y, double z);  /* right-handed about the axis */
double pmi_det3(pmi_mat4 a);
void pmi_xform_point(pmi_mat4 a, const double p[3], double out[3]);
void pmi_xform_vector(pmi_mat4 a, const double v[3], double out[3]);

/* Transforms a mesh shape's positions by a in place and keeps every face's
 * front on the same side of the surface (a mirroring transform reverses
 * the corner order), then flips every face if flip is set. */
void pmi_shape_xform(pmi_shape *s, pmi_mat4 a, int flip);

/* Area of polygon f of a mesh shape (source world units). */
double pmi_face_area(const pmi_shape *s, size_t f);

/* Appends to a mesh shape: faces with start/idx as given (nface faces) over
 * nv new vertices. Returns -1 out of memory. For readers building meshes. */
int pmi_mesh_alloc(pmi_shape *s, size_t nv, size_t nface, size_t ncorners, int with_uv);

/* A mesh of a disk of radius r (inner radius ri) in the xy plane at height
 * h, front toward +z, phimax degrees of it, as pbrt and Mitsuba define
 * disks. Returns -1 out of memory. */
int pmi_disk_mesh(pmi_shape *s, double r, double ri, double h, double phimax);

#endif
