/* test_scene.c — the scene loader: shapes, normals, transforms, meshes through
 * OpenMesh, triangulation, motion, the scene identities, error messages, and the
 * bundled example scenes. Scenes are written to a private temporary directory. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "scene/patch.h"
#include "scene/scene.h"

static char dir[64];

/* Writes text to dir/name and returns the full path (static buffer ring). */
static const char *
put(const char *name, const char *text)
{
	static char paths[8][256];
	static int k;
	char *path = paths[k++ % 8];
	snprintf(path, 256, "%s/%s", dir, name);
	FILE *f = fopen(path, "wb");
	if (!f) {
		perror(path);
		exit(1);
	}
	fputs(text, f);
	fclose(f);
	return path;
}

#define CAMERA "camera eye 0 0 10 look 0 0 0 up 0 1 0 fov 40 size 64 48\n"
#define LIGHT "pointlight 0 5 0 power 10 10 10\n"
#define WHITE "material white diffuse albedo 0.5 0.5 0.5\n"
#define HEAD CAMERA LIGHT WHITE
/* A unit cube of six quads, counter-clockwise seen from outside. */
#define CUBE_OBJ "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n" \
	"f 1 5 7 3\nf 2 4 8 6\nf 1 2 6 5\nf 3 7 8 4\nf 1 3 4 2\nf 5 6 8 7\n"

/* Loads a scene made of HEAD and body; fails the test if it does not load. */
static int
load(pm_scene *s, const char *body)
{
	char text[8192];
	pm_error err = {""};
	snprintf(text, sizeof text, "%s%s", HEAD, body);
	int r = pm_scene_load(s, put("t.pms", text), &err);
	CHECKF(r == 0, "load failed: %s", err.msg);
	return r;
}

static pm_vec3
centroid(const pm_scene *s, uint32_t poly)
{
	pm_vec3 c = pm_v3(0, 0, 0);
	uint32_t a = s->poly_start[poly], b = s->poly_start[poly + 1];
	for (uint32_t i = a; i < b; i++)
		c = pm_add(c, s->verts[s->poly_vert[i]]);
	return pm_scale(c, 1.0f / (float)(b - a));
}

static double
tri_area(const pm_scene *s, uint32_t t)
{
	pm_vec3 a = s->verts[s->tris[t][0]], b = s->verts[s->tris[t][1]], c = s->verts[s->tris[t][2]];
	return 0.5 * pm_len(pm_cross(pm_sub(b, a), pm_sub(c, a)));
}

/* Signed: positive when the triangle winds like its polygon. */
static double
tri_area_along(const pm_scene *s, uint32_t t)
{
	pm_vec3 a = s->verts[s->tris[t][0]], b = s->verts[s->tris[t][1]], c = s->verts[s->tris[t][2]];
	return 0.5 * pm_dot(pm_cross(pm_sub(b, a), pm_sub(c, a)), s->poly_normal[s->tri_poly[t]]);
}

static int
near3(pm_vec3 a, pm_vec3 b, float tol)
{
	return fabsf(a.x - b.x) <= tol && fabsf(a.y - b.y) <= tol && fabsf(a.z - b.z) <= tol;
}

/* Every polygon of object o faces away from (sign +1) or toward (-1) point c. */
static int
faces_from(const pm_scene *s, int o, pm_vec3 c, int sign)
{
	const pm_object *ob = &s->objs[o];
	for (uint32_t i = ob->first_poly; i < ob->first_poly + ob->npolys; i++)
		if (sign * pm_dot(s->poly_normal[i], pm_sub(centroid(s, i), c)) <= 0)
			return 0;
	return 1;
}

TEST(quad_normal_and_triangles)
{
	pm_scene s;
	if (load(&s, "quad white 0 0 0  2 0 0  2 1 0  0 1 0\ntriangle white 0 0 1  0 1 1  1 0 1\n"))
		return;
	CHECK(s.nobjs == 2 && s.npolys == 2 && s.ntris == 3 && s.nverts == 7);
	CHECK(s.objs[1].solid == 0 && s.poly_start[2] == 7);
	CHECK(near3(s.poly_normal[1], pm_v3(0, 0, -1), 1e-6f));
	CHECK(s.poly_start[1] - s.poly_start[0] == 4);
	CHECKF(near3(s.poly_normal[0], pm_v3(0, 0, 1), 1e-6f), "n=(%g %g %g)",
		s.poly_normal[0].x, s.poly_normal[0].y, s.poly_normal[0].z);
	CHECK(s.objs[0].solid == 0);
	double area = 0;
	CHECK(s.tri_poly[2] == 1);
	for (uint32_t t = 0; t < 2; t++) {
		CHECK(s.tri_poly[t] == 0);
		CHECKF(tri_area_along(&s, t) > 0, "triangle %u winds backward", t);
		area += tri_area(&s, t);
	}
	CHECKF(fabs(area - 2) < 1e-6, "area %g", area);
	CHECK(s.camera.width == 64 && s.camera.height == 48 && s.camera.fov == 40);
	CHECK(s.camera.eye.z == 10 && s.camera.up.y == 1);
	CHECK(s.nlights == 1 && s.lights[0].power.x == 10 && s.lights[0].pos.y == 5);
	pm_scene_free(&s);
}

TEST(box_outward_and_inward)
{
	pm_scene s;
	if (load(&s, "box white -1 -2 -3 1 2 3\nbox white 10 10 10 12 12 12 inward\n"))
		return;
	CHECK(s.nobjs == 2 && s.npolys == 12 && s.ntris == 24);
	CHECK(s.objs[0].solid == 1 && s.objs[1].solid == 1);
	for (uint32_t i = 0; i < s.npolys; i++)
		CHECK(s.poly_start[i + 1] - s.poly_start[i] == 4);
	CHECK(faces_from(&s, 0, pm_v3(0, 0, 0), 1));
	CHECK(faces_from(&s, 1, pm_v3(11, 11, 11), -1));
	/* Each face's normal is a unit axis vector. */
	for (uint32_t i = 0; i < s.npolys; i++)
		CHECKF(fabsf(pm_maxc(pm_mul(s.poly_normal[i], s.poly_normal[i])) - 1) < 1e-6f,
			"face %u normal not axis-aligned", i);
	for (uint32_t t = 0; t < s.ntris; t++)
		CHECK(tri_area_along(&s, t) > 0);
	pm_scene_free(&s);
}

TEST(rotate_maps_x_to_y)
{
	pm_scene s;
	/* A quad facing +x through (1, 0, 0), turned 90 degrees about z. */
	if (load(&s, "quad white 1 0 0  1 1 0  1 1 1  1 0 1  rotate 0 0 1 90\n"))
		return;
	CHECKF(near3(s.verts[0], pm_v3(0, 1, 0), 1e-6f), "(%g %g %g)", s.verts[0].x, s.verts[0].y, s.verts[0].z);
	CHECK(near3(s.verts[1], pm_v3(-1, 1, 0), 1e-6f));
	CHECKF(near3(s.poly_normal[0], pm_v3(0, 1, 0), 1e-6f), "n=(%g %g %g)",
		s.poly_normal[0].x, s.poly_normal[0].y, s.poly_normal[0].z);
	pm_scene_free(&s);
}

TEST(transforms_apply_in_order)
{
	pm_scene s;
	if (load(&s, "quad white 1 0 0  2 0 0  2 1 0  1 1 0  scale 2 translate 1 0 0\n"
		     "quad white 1 0 0  2 0 0  2 1 0  1 1 0  translate 1 0 0 scale 2\n"
		     "quad white 1 0 0  2 0 0  2 1 0  1 1 0  scale 1 2 3 translate 0 0 5\n"))
		return;
	CHECK(near3(s.verts[0], pm_v3(3, 0, 0), 1e-6f));
	CHECK(near3(s.verts[4], pm_v3(4, 0, 0), 1e-6f));
	CHECK(near3(s.verts[10], pm_v3(2, 2, 5), 1e-6f));
	pm_scene_free(&s);
}

TEST(mirroring_scale_keeps_normals_outward)
{
	pm_scene s;
	if (load(&s, "box white 1 1 1 2 3 4 scale -1 1 1\n"
		     "box white 1 1 1 2 3 4 scale -1\n"
		     "box white 0 0 0 1 1 1 inward scale 1 -2 1\n"
		     "quad white 0 0 0  1 0 0  1 1 0  0 1 0 scale 1 1 -1\n"))
		return;
	CHECK(faces_from(&s, 0, pm_v3(-1.5f, 2, 2.5f), 1));
	CHECK(faces_from(&s, 1, pm_v3(-1.5f, -2, -2.5f), 1));
	CHECK(faces_from(&s, 2, pm_v3(0.5f, -1, 0.5f), -1));
	/* Normals transform by the inverse transpose: mirroring a sheet
	 * through its own plane turns its front from +z to -z. */
	CHECK(near3(s.poly_normal[18], pm_v3(0, 0, -1), 1e-6f));
	for (uint32_t t = 0; t < s.ntris; t++)
		CHECK(tri_area_along(&s, t) > 0);
	pm_scene_free(&s);
}

TEST(sphere_area_and_normals)
{
	pm_scene s;
	double prev_err = 1;
	for (int sub = 2; sub <= 6; sub += 2) {
		char body[256];
		snprintf(body, sizeof body, "sphere white 1 2 3 2 subdiv %d\n", sub);
		if (load(&s, body))
			return;
		uint32_t bands = 2u << sub;
		CHECK(s.objs[0].solid == 1);
		CHECKF(s.npolys == 2 * bands * bands, "subdiv %d: %u polygons", sub, s.npolys);
		double area = 0;
		for (uint32_t t = 0; t < s.ntris; t++)
			area += tri_area(&s, t);
		double want = 4 * PM_PI * 4, err = (want - area) / want;
		/* Inscribed: a little less than the sphere, converging as
		 * O(h^2) with the band width h. */
		CHECKF(err > 0 && err < 0.5 * pow(PM_PI / bands, 2) * 2, "subdiv %d: area %g of %g", sub, area, want);
		CHECKF(err < prev_err / 8, "subdiv %d: error %g after %g", sub, err, prev_err);
		prev_err = err;
		CHECK(faces_from(&s, 0, pm_v3(1, 2, 3), 1));
		for (uint32_t i = 0; i < s.nverts; i++)
			CHECK(fabsf(pm_len(pm_sub(s.verts[i], pm_v3(1, 2, 3))) - 2) < 1e-5f);
		pm_scene_free(&s);
	}
}

TEST(obj_cube_closed_quads)
{
	pm_scene s;
	put("cube.obj", CUBE_OBJ);
	if (load(&s, "mesh cube.obj white translate 5 0 0\n"))
		return;
	CHECK(s.nobjs == 1 && s.objs[0].solid == 1);
	CHECK(s.npolys == 6 && s.ntris == 12 && s.nverts == 8);
	for (uint32_t i = 0; i < s.npolys; i++)
		CHECK(s.poly_start[i + 1] - s.poly_start[i] == 4);
	CHECK(faces_from(&s, 0, pm_v3(5.5f, 0.5f, 0.5f), 1));
	pm_scene_free(&s);
}

TEST(off_and_ply_read)
{
	pm_scene s;
	/* The same cube as CUBE_OBJ, 0-based, in OFF and ASCII PLY. */
	static const char *const body = "8 6 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n"
		"4 0 4 6 2\n4 1 3 7 5\n4 0 1 5 4\n4 2 6 7 3\n4 0 2 3 1\n4 4 5 7 6\n";
	char text[1024];
	snprintf(text, sizeof text, "OFF\n%s", body);
	put("cube.off", text);
	put("cube.ply", "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n"
		"property float z\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n"
		"0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n"
		"4 0 4 6 2\n4 1 3 7 5\n4 0 1 5 4\n4 2 6 7 3\n4 0 2 3 1\n4 4 5 7 6\n");
	if (load(&s, "mesh cube.off white\nmesh cube.ply white translate 2 0 0\n"))
		return;
	CHECK(s.nobjs == 2 && s.objs[0].solid == 1 && s.objs[1].solid == 1);
	CHECK(s.npolys == 12 && s.poly_start[12] == 48);
	CHECK(faces_from(&s, 0, pm_v3(0.5f, 0.5f, 0.5f), 1));
	CHECK(faces_from(&s, 1, pm_v3(2.5f, 0.5f, 0.5f), 1));
	pm_scene_free(&s);
}

/* A polygon soup (every face with corners of its own, as flat-shaded
 * exports write): closed once corners at one position are one vertex, so a
 * soup cube is a solid; without one face, or with one face twice, it is not. */
TEST(obj_soup_cube_closed_by_position)
{
	static const int q[6][4] = {{1, 5, 7, 3}, {2, 4, 8, 6}, {1, 2, 6, 5}, {3, 7, 8, 4}, {1, 3, 4, 2}, {5, 6, 8, 7}};
	static const char *const corner[8] = {"0 0 0", "1 0 0", "0 1 0", "1 1 0", "0 0 1", "1 0 1", "0 1 1", "1 1 1"};
	char text[2048];
	for (int variant = 0; variant < 3; variant++) {
		int n = 0, nf = variant == 1 ? 5 : 6;
		for (int f = 0; f < nf; f++)
			for (int c = 0; c < 4; c++)
				n += snprintf(text + n, sizeof text - (size_t)n, "v %s\n", corner[q[f][c] - 1]);
		for (int f = 0; f < nf; f++)
			n += snprintf(text + n, sizeof text - (size_t)n, "f %d %d %d %d\n", 4 * f + 1, 4 * f + 2, 4 * f + 3, 4 * f + 4);
		if (variant == 2)
			n += snprintf(text + n, sizeof text - (size_t)n, "f 1 2 3 4\n");
		put("soup.obj", text);
		pm_scene s;
		if (load(&s, "mesh soup.obj white\n"))
			return;
		CHECKF(s.objs[0].solid == (variant == 0), "variant %d: solid %d", variant, s.objs[0].solid);
		pm_scene_free(&s);
	}
}

/* A closed surface round the camera's eye is a room seen from inside
 * (formats/scene.md, "Solids: which side is matter"): it is turned over,
 * faces, triangles and shading normals alike, unless it is a one-sided
 * emitter or glass. The head's eye is (0, 0, 10); "A" puts a cube of side
 * 4 round it. A lamp shut in a solid the eye is outside of turns nothing. */
#define A " scale 4 translate -2 -2 8"
TEST(closed_surface_round_the_eye_turned_over)
{
	static const struct {
		const char *body;
		int inward;   /* object 0 faces its centre as written */
		int turned;
	} v[] = {
		{"mesh cube.obj white" A "\n", 0, 1},
		{"mesh cube.obj white scale 4\npointlight 2 2 2 power 1 1 1\n", 0, 0},
		{"mesh cubein.obj white" A "\n", 1, 0},
		{"sphere white 0 0 10 1.5 subdiv 2\n", 0, 1},
		{"box white -2 -2 8  2 2 12\n", 0, 1},
		{"box white -2 -2 8  2 2 12 inward\n", 1, 0},
		{"material glow diffuse albedo 0.5 0.5 0.5 emit 1 1 1 twosided\nmesh cube.obj glow" A "\n", 0, 1},
		{"material glow diffuse albedo 0.5 0.5 0.5 emit 1 1 1\nmesh cube.obj glow" A "\n", 0, 0},
		{"material clear glass ior 1.5\nmesh cube.obj clear" A "\n", 0, 0},
		{"mesh cube.obj white" A " smooth\n", 0, 1},
	};
	put("cube.obj", CUBE_OBJ);
	put("cubein.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"
		"f 3 7 5 1\nf 6 8 4 2\nf 5 6 2 1\nf 4 8 7 3\nf 2 4 3 1\nf 7 8 6 5\n");
	for (size_t i = 0; i < sizeof v / sizeof v[0]; i++) {
		pm_scene s;
		if (load(&s, v[i].body))
			return;
		const pm_object *o = &s.objs[0];
		pm_vec3 c = pm_v3(0, 0, 0);
		for (uint32_t k = o->first_vert; k < o->first_vert + o->nverts; k++)
			c = pm_add(c, pm_scale(s.verts[k], 1.0f / (float)o->nverts));
		CHECKF(o->solid == 1, "variant %zu: not solid", i);
		CHECKF(faces_from(&s, 0, c, v[i].turned != v[i].inward ? -1 : 1), "variant %zu: turned %d expected",
		       i, v[i].turned);
		for (uint32_t t = o->first_tri; t < o->first_tri + o->ntris; t++)
			CHECKF(tri_area_along(&s, t) > 0, "variant %zu: triangle %u against its polygon", i, t);
		CHECK(!o->smooth || s.vnormal);
		for (uint32_t k = o->first_vert; s.vnormal && o->smooth && k < o->first_vert + o->nverts; k++)
			CHECKF(pm_dot(s.vnormal[k], pm_sub(s.verts[k], c)) < 0, "variant %zu: shading normal %u", i, k);
		pm_scene_free(&s);
	}
}
#undef A

TEST(obj_open_plane_is_sheet)
{
	pm_scene s;
	put("plane.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
	if (load(&s, "mesh plane.obj white\n"))
		return;
	CHECK(s.nobjs == 1 && s.objs[0].solid == 0);
	CHECK(s.npolys == 2 && s.ntris == 2);
	CHECK(near3(s.poly_normal[0], pm_v3(0, 0, 1), 1e-6f));
	pm_scene_free(&s);
}

TEST(obj_degenerate_faces_dropped)
{
	pm_scene s;
	put("degen.obj",
		"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\nv 1 0 0\n"
		"f 1 2 3\n"        /* fine */
		"f 1 3 4\n"        /* fine */
		"f 1 2 5\n"        /* collinear: no area */
		"f 1 1 2\n"        /* a repeated index: two distinct vertices */
		"f 2 6 3\n"        /* 2 and 6 are the same point: an edge */
		"f 1 2 2 3\n"      /* a repeat in a row: a triangle */
		"f 1 2 6 3 4\n");  /* same point in a row: a quad */
	if (load(&s, "mesh degen.obj white\n"))
		return;
	CHECKF(s.npolys == 4, "%u polygons", s.npolys);
	CHECK(s.poly_start[3] - s.poly_start[2] == 3);
	CHECK(s.poly_start[4] - s.poly_start[3] == 4);
	for (uint32_t i = 0; i < s.npolys; i++)
		CHECK(pm_vfinite(s.poly_normal[i]) && near3(s.poly_normal[i], pm_v3(0, 0, 1), 1e-6f));
	pm_scene_free(&s);
}

TEST(concave_polygon_ear_clipping)
{
	pm_scene s;
	/* An L of area 3, starting at a corner from which a fan would leave
	 * the polygon. */
	put("ell.obj", "v 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nv 0 0 0\nv 2 0 0\nf 1 2 3 4 5 6\n");
	if (load(&s, "mesh ell.obj white\n"))
		return;
	CHECK(s.npolys == 1 && s.poly_start[1] == 6);
	CHECKF(s.ntris == 4, "%u triangles", s.ntris);
	double sum = 0;
	for (uint32_t t = 0; t < s.ntris; t++) {
		CHECKF(tri_area_along(&s, t) > 0, "triangle %u winds backward", t);
		sum += tri_area(&s, t);
	}
	CHECKF(fabs(sum - 3) < 1e-6, "triangles cover %g, want 3", sum);
	pm_scene_free(&s);
}

TEST(nonplanar_face_split)
{
	pm_scene s;
	put("bent.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0.5\nv 0 1 0\nf 1 2 3 4\n");
	if (load(&s, "mesh bent.obj white\n"))
		return;
	CHECK(s.npolys == 2 && s.ntris == 2);
	for (uint32_t i = 0; i < s.npolys; i++)
		CHECK(s.poly_start[i + 1] - s.poly_start[i] == 3 && s.poly_normal[i].z > 0.5f);
	pm_scene_free(&s);
}

/* Smooth patches: a tessellated sphere is one, a box six; a soup (every
 * face its own vertices) joins where its faces meet flat and splits where
 * they fold at 90 degrees; two objects never share one. */
TEST(smooth_patches)
{
	pm_scene s;
	pm_error err = {""};
	uint32_t *patch;
	put("soup.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 0 0\nv 1 1 0\nv 0 1 0\n"
	                "v 1 0 0\nv 1 0 -1\nv 1 1 -1\nf 1 2 3\nf 4 5 6\nf 7 8 9\n");
	if (load(&s, "box white 0 0 0  1 1 1\nsphere white 3 0 0 1 subdiv 2\n"
	             "mesh soup.obj white translate 5 0 0\n"
	             "quad white 0 0 3  1 0 3  1 1 3  0 1 3\nquad white 1 0 3  2 0 3  2 1 3  1 1 3\n"))
		return;
	CHECK(s.nobjs == 5);
	CHECK(pm_scene_patches(&s, &patch, &err) == 0);
	const pm_object *box = &s.objs[0], *sph = &s.objs[1], *soup = &s.objs[2];
	for (uint32_t i = box->first_poly; i < box->first_poly + box->npolys; i++)
		CHECKF(patch[i] == i, "box face %u in patch %u", i, patch[i]);
	for (uint32_t i = sph->first_poly; i < sph->first_poly + sph->npolys; i++)
		CHECKF(patch[i] == sph->first_poly, "sphere facet %u in patch %u", i, patch[i]);
	CHECK(sph->npolys > 16);
	CHECK(soup->npolys == 3);
	uint32_t f = soup->first_poly;
	/* the two flat halves of the square: one patch; the folded face: its own */
	CHECK(patch[f] == f && patch[f + 1] == f && patch[f + 2] == f + 2);
	CHECK(patch[s.objs[3].first_poly] == s.objs[3].first_poly);
	CHECK(patch[s.objs[4].first_poly] == s.objs[4].first_poly);
	free(patch);
	pm_scene_free(&s);
}

/* The patches against every pair of polygons compared outright: a random
 * soup over a 9 x 9 grid of heights (creased and flat by turns) and two
 * flat triangles that meet at one corner only, in two objects at the same
 * place. Two polygons of one object share a patch where a chain of pairs
 * joins them, each pair meeting at a point with normals within
 * PM_PATCH_COS; the patch's name is its lowest polygon. */
static uint32_t
root_of(uint32_t *up, uint32_t i)
{
	while (up[i] != i)
		i = up[i];
	return i;
}

TEST(smooth_patches_as_pairs_say)
{
	enum { G = 9 };
	static char obj[64 * 1024];
	size_t len = 0;
	unsigned r = 12345;
	double z[G][G];
	pm_scene s;
	pm_error err = {""};
	uint32_t *patch;

	for (int i = 0; i < G; i++)
		for (int j = 0; j < G; j++) {
			r = r * 1103515245u + 12345u;
			z[i][j] = (i + j) % 3 == 0 ? 0 : (double)((r >> 16) % 7) / 6;
		}
	for (int i = 0; i + 1 < G; i++)
		for (int j = 0; j + 1 < G; j++)
			for (int t = 0; t < 2; t++) {
				int a[3][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}}, b[3][2] = {{i, j}, {i + 1, j + 1}, {i, j + 1}};
				for (int k = 0; k < 3; k++) {
					int *q = t ? b[k] : a[k];
					len += (size_t)snprintf(obj + len, sizeof obj - len, "v %d %d %.17g\n", q[0], q[1],
					                        z[q[0]][q[1]]);
				}
				len += (size_t)snprintf(obj + len, sizeof obj - len, "f -3 -2 -1\n");
			}
	len += (size_t)snprintf(obj + len, sizeof obj - len, "v 20 0 0\nv 21 0 0\nv 21 1 0\nf -3 -2 -1\n"
	                        "v 21 1 0\nv 22 1 0\nv 22 2 0\nf -3 -2 -1\n");
	put("grid.obj", obj);
	if (load(&s, "mesh grid.obj white\nmesh grid.obj white\n"))
		return;
	CHECK(pm_scene_patches(&s, &patch, &err) == 0);
	uint32_t n = s.npolys, *up = malloc(n * sizeof *up);
	for (uint32_t p = 0; p < n; p++)
		up[p] = p;
	for (uint32_t p = 0; p < n; p++)
		for (uint32_t q = p + 1; q < n; q++) {
			int meet = 0;
			for (uint32_t a = s.poly_start[p]; a < s.poly_start[p + 1] && !meet; a++)
				for (uint32_t b = s.poly_start[q]; b < s.poly_start[q + 1] && !meet; b++) {
					pm_vec3 u = s.verts[s.poly_vert[a]], v = s.verts[s.poly_vert[b]];
					meet = u.x == v.x && u.y == v.y && u.z == v.z;
				}
			if (!meet || s.poly_obj[p] != s.poly_obj[q] ||
			    pm_dot(s.poly_normal[p], s.poly_normal[q]) < PM_PATCH_COS)
				continue;
			uint32_t rp = root_of(up, p), rq = root_of(up, q);
			up[rp > rq ? rp : rq] = rp < rq ? rp : rq;
		}
	uint32_t npatch = 0, wrong = 0;
	for (uint32_t p = 0; p < n; p++) {
		wrong += patch[p] != root_of(up, p);
		npatch += patch[p] == p;
	}
	CHECKF(wrong == 0, "%u of %u polygons in another patch than their pairs say", wrong, n);
	/* Neither one patch nor none joined, and the two objects apart. */
	CHECKF(npatch > 2 && npatch < n / 2, "%u patches of %u polygons", npatch, n);
	const pm_object *g2 = &s.objs[s.nobjs - 1];
	CHECKF(s.nobjs >= 2 && g2->npolys == n / 2 && patch[g2->first_poly] >= g2->first_poly,
	       "the second grid's first polygon in patch %u", patch[g2->first_poly]);
	CHECKF(patch[g2->first_poly + g2->npolys - 1] == g2->first_poly + g2->npolys - 2,
	       "the triangles meeting at a corner apart");
	free(up);
	free(patch);
	pm_scene_free(&s);
}

TEST(motion)
{
	pm_scene s;
	if (load(&s, "box white 0 0 0 1 1 1 move 2 4 6\nquad white 0 0 0  1 0 0  1 1 0  0 1 0\n"
		     "pointlight 1 1 1 power 1 1 1 move 0 0 -2\n"))
		return;
	pm_vec3 *v = malloc(s.nverts * sizeof *v);
	pm_scene_verts_at(&s, 0.5f, v);
	for (uint32_t i = 0; i < 8; i++)
		CHECK(near3(v[i], pm_add(s.verts[i], pm_v3(1, 2, 3)), 1e-6f));
	for (uint32_t i = 8; i < s.nverts; i++)
		CHECK(near3(v[i], s.verts[i], 0));
	pm_scene_verts_at(&s, 0, v);
	CHECK(near3(v[0], s.verts[0], 0));
	CHECK(near3(pm_scene_light_at(&s, 1, 0.25f), pm_v3(1, 1, 0.5f), 1e-6f));
	CHECK(near3(pm_scene_light_at(&s, 0, 1), pm_v3(0, 5, 0), 0));
	free(v);
	pm_scene_free(&s);
}

TEST(materials_strong_and_soft)
{
	pm_scene s;
	if (load(&s, "material shiny glossy kd 0.2 0.2 0.2 ks 0.7 0.7 0.7 exponent 200\n"
		     "material satin glossy exponent 20 ks 0.3 0.3 0.3 kd 0.5 0.5 0.5\n"
		     "material m mirror reflect 0.9 0.9 0.9\n"
		     "material g glass ior 1.5\n"
		     "material lamp diffuse albedo 0 0 0 emit 5 4 3 twosided\n"))
		return;
	CHECK(s.nmats == 6 && s.glossy_threshold == 100);
	CHECK(!s.mats[0].strong && pm_mat_is_photon_surface(&s.mats[0]));
	CHECK(s.mats[1].strong && s.mats[1].kind == PM_MAT_GLOSSY && s.mats[1].exponent == 200);
	CHECK(!s.mats[2].strong && s.mats[2].kd.x == 0.5f && s.mats[2].ks.x == 0.3f);
	CHECK(s.mats[3].strong && s.mats[3].ks.y == 0.9f);
	CHECK(s.mats[4].strong && s.mats[4].ior == 1.5f && s.mats[4].ks.z == 1);
	CHECK(!s.mats[5].strong && s.mats[5].emit.x == 5 && s.mats[5].emit_twosided);
	pm_scene_free(&s);
	if (load(&s, "glossy_threshold 10\nmaterial satin glossy kd 0.5 0.5 0.5 ks 0.3 0.3 0.3 exponent 20\n"))
		return;
	CHECK(s.glossy_threshold == 10 && s.mats[1].strong);
	pm_scene_free(&s);
}

/* The light and view identities of a scene text (meshes as put before). */
static int
ids(const char *text, uint64_t *light, uint64_t *view)
{
	pm_scene s;
	pm_error err = {""};
	int r = pm_scene_load(&s, put("h.pms", text), &err);
	CHECKF(r == 0, "load failed: %s", err.msg);
	*light = r ? 0 : s.light_hash;
	*view = r ? 0 : s.view_hash;
	if (r == 0)
		pm_scene_free(&s);
	return r;
}

#define ID_GLOSSY "material satin glossy kd 0.5 0.5 0.5 ks 0.3 0.3 0.3 exponent 20\n"
#define ID_BODY ID_GLOSSY "mesh plane.obj white\nmesh cube.obj satin translate 3 0 0\n"

/* Comments, white space, number spellings, material names and the camera do
 * not enter the light identity; every value the photons depend on does. */
TEST(identity)
{
	static const char *same_light[] = {
		/* comments, blank lines, tabs, spellings of the same float */
		"# a comment\n" CAMERA "\n" LIGHT "\t" WHITE ID_BODY "  # trailing\n",
		CAMERA "pointlight 0.0 5e0 0 power 10.00 1e1 10\n" WHITE ID_BODY,
		/* another name for the same material */
		CAMERA LIGHT "material blanc diffuse albedo 0.5 0.5 0.5\n" ID_GLOSSY
			"mesh plane.obj blanc\nmesh cube.obj satin translate 3 0 0\n",
	};
	static const char *other_light[] = {
		CAMERA LIGHT "material white diffuse albedo 0.5 0.6 0.5\n" ID_BODY,   /* albedo */
		CAMERA "pointlight 0 5 0 power 10 10 11\n" WHITE ID_BODY,             /* light power */
		CAMERA "pointlight 0 5.001 0 power 10 10 10\n" WHITE ID_BODY,         /* light position */
		HEAD ID_GLOSSY "mesh plane.obj white\nmesh cube.obj satin translate 3 0 0.001\n",
		HEAD ID_GLOSSY "mesh plane.obj white\nmesh cube.obj white translate 3 0 0\n",
		"glossy_threshold 15\n" HEAD ID_BODY,                                 /* satin turns strong */
		"glossy_threshold 50\n" HEAD ID_BODY,                                 /* satin stays soft */
	};
	const char *base = HEAD ID_BODY;
	uint64_t l0, v0, l, v;

	put("plane.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
	put("cube.obj", CUBE_OBJ);
	if (ids(base, &l0, &v0))
		return;
	CHECK(ids(base, &l, &v) == 0 && l == l0 && v == v0);
	for (size_t i = 0; i < sizeof same_light / sizeof *same_light; i++)
		if (ids(same_light[i], &l, &v) == 0)
			CHECKF(l == l0 && v == v0, "case %zu: light %016llx view %016llx, want %016llx %016llx", i,
			       (unsigned long long)l, (unsigned long long)v, (unsigned long long)l0,
			       (unsigned long long)v0);
	for (size_t i = 0; i < sizeof other_light / sizeof *other_light; i++)
		if (ids(other_light[i], &l, &v) == 0)
			CHECKF(l != l0 && v != v0, "case %zu: identity unchanged", i);

	/* the camera: the same light pass, another view */
	char cam[4096];
	snprintf(cam, sizeof cam, "%s%s", "camera eye 0 0 9 look 0 0 0 up 0 1 0 fov 40 size 64 48\n",
	         LIGHT WHITE ID_BODY);
	if (ids(cam, &l, &v) == 0)
		CHECK(l == l0 && v != v0);

	/* a mesh file: a comment in it does not count, a moved vertex does */
	put("plane.obj", "# exported\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
	if (ids(base, &l, &v) == 0)
		CHECK(l == l0 && v == v0);
	put("plane.obj", "v 0 0 0\nv 1 0 0\nv 1 1.5 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
	if (ids(base, &l, &v) == 0)
		CHECK(l != l0 && v != v0);
}

/* formats/scene.md's byte sequence for the identities, written out by hand
 * for one small scene: the page, not only the code, says what is hashed. */
static uint64_t spec_h;
static void
spec_u32(uint32_t v)
{
	for (int i = 0; i < 4; i++)
		spec_h = (spec_h ^ ((v >> (8 * i)) & 0xff)) * 1099511628211ull;
}
static void
spec_f32s(int n, ...)
{
	va_list ap;
	va_start(ap, n);
	for (int i = 0; i < n; i++) {
		float f = (float)va_arg(ap, double);
		uint32_t u;
		memcpy(&u, &f, 4);
		spec_u32(u);
	}
	va_end(ap);
}

TEST(identity_as_documented)
{
	pm_scene s;
	pm_error err = {""};
	const char *path = put("spec.pms", CAMERA LIGHT WHITE "triangle white 0 0 0  1 0 0  0 1 0\n");

	if (pm_scene_load(&s, path, &err)) {
		CHECKF(0, "%s", err.msg);
		return;
	}
	spec_h = 14695981039346656037ull;
	spec_f32s(1, 100.0);                                   /* glossy threshold */
	spec_u32(1);                                           /* materials */
	spec_u32(0);                                           /* diffuse */
	spec_f32s(3, 0.5, 0.5, 0.5);                           /* albedo */
	spec_f32s(3, 1.0, 1.0, 1.0);                           /* ks: not given */
	spec_f32s(2, 0.0, 0.0);                                /* exponent, ior */
	spec_f32s(3, 0.0, 0.0, 0.0);                           /* emit */
	spec_u32(0);                                           /* not twosided */
	spec_u32(1);                                           /* objects */
	spec_u32(0), spec_u32(0);                              /* material 0, a sheet */
	spec_f32s(3, 0.0, 0.0, 0.0);                           /* move */
	spec_u32(1), spec_u32(3);                              /* polygons, vertices */
	spec_u32(1);                                           /* point lights */
	spec_f32s(9, 0.0, 5.0, 0.0, 10.0, 10.0, 10.0, 0.0, 0.0, 0.0);
	spec_u32(3);                                           /* vertices */
	spec_f32s(9, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0);
	spec_u32(1);                                           /* polygons */
	spec_u32(3), spec_u32(0), spec_u32(1), spec_u32(2);
	uint64_t light = spec_h;
	CHECKF(s.light_hash == light, "light_hash %016llx, documented %016llx",
	       (unsigned long long)s.light_hash, (unsigned long long)light);

	spec_h = 14695981039346656037ull;
	spec_u32((uint32_t)light), spec_u32((uint32_t)(light >> 32));
	spec_f32s(10, 0.0, 0.0, 10.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 40.0);
	spec_u32(64), spec_u32(48);
	CHECKF(s.view_hash == spec_h, "view identity %016llx, documented %016llx",
	       (unsigned long long)s.view_hash, (unsigned long long)spec_h);
	pm_scene_free(&s);
}

/* Each malformed scene must fail with exactly "FILE:LINE: " and a message
 * containing want. */
static void
bad(const char *text, int line, const char *want)
{
	pm_scene s;
	pm_error err = {""};
	const char *path = put("bad.pms", text);
	char prefix[300];
	snprintf(prefix, sizeof prefix, "%s:%d: ", path, line);
	int r = pm_scene_load(&s, path, &err);
	CHECKF(r == -1, "loaded, want '%s'", want);
	CHECKF(!strncmp(err.msg, prefix, strlen(prefix)) && strstr(err.msg, want),
		"got '%s', want '%s...%s'", err.msg, prefix, want);
	CHECK(s.nobjs == 0 && s.npolys == 0 && s.verts == NULL && s.path == NULL);
}

TEST(malformed_scenes)
{
	bad(HEAD "qaud white 0 0 0 1 0 0 1 1 0 0 1 0\n", 4, "unknown statement 'qaud'");
	bad("camera eye 0 0 look 0 0 0 up 0 1 0 fov 40 size 64 48\n", 1,
		"camera: expected 3 numbers after 'eye'");
	bad(HEAD "quad white 0 0 0 1 0 0 1 1 0 0 1 nan\n", 4, "quad: 'nan' is not a finite number");
	bad(HEAD "box white 0 0 0 1 1 1e999\n", 4, "box: number '1e999' out of range");
	bad(HEAD "box white 0 0 0 1 1 1x\n", 4, "box: expected 6 numbers after the material");
	bad(HEAD "\n# comment\nbox whte 0 0 0 1 1 1\n", 6, "box: unknown material 'whte'");
	bad(HEAD "material white diffuse albedo 1 1 1\n", 4, "material: 'white' is defined twice");
	bad(LIGHT WHITE "box white 0 0 0 1 1 1\n", 3, "no camera");
	bad(HEAD CAMERA, 4, "camera: a second camera");
	bad(CAMERA WHITE "box white 0 0 0 1 1 1\n", 3, "no light");
	bad(CAMERA "material lamp diffuse albedo 0.5 0.5 0.5 emit 1 1 1\n" WHITE "box white 0 0 0 1 1 1\n",
		4, "no light");
	bad(CAMERA "material w diffuse albedo 1.2 0.5 0.5\n", 2,
		"material 'w': albedo must be in [0, 1]");
	bad(HEAD "material g glossy kd 0.6 0.6 0.6 ks 0.5 0.3 0.3 exponent 10\n", 4,
		"material 'g': kd + ks exceeds 1");
	bad(HEAD "material g glossy kd 0.2 0.2 0.2 ks 0.5 0.3 0.3\n", 4, "material 'g': missing 'exponent'");
	bad(HEAD "material g glass ior 0\n", 4, "material 'g': ior must be > 0");
	bad(HEAD "mesh nosuch.obj white\n", 4, "nosuch.obj': cannot read mesh: No such file or directory");
	put("junk.obj", "this is not\na mesh at all\n\x01\x02\x03\n");
	bad(HEAD "mesh junk.obj white\n", 4, "junk.obj': cannot read mesh: no faces");
	put("junk.xyz", "v 0 0 0\n");
	bad(HEAD "mesh junk.xyz white\n", 4, "junk.xyz': cannot read mesh: unknown format");
	bad("camera eye 0 0 10 look 0 0 0 up 0 1 0 fov 40 size -64 48\n", 1,
		"camera: size must be whole numbers from 1 to 65535, got -64");
	bad("camera eye 0 0 10 look 0 0 0 up 0 1 0 fov 180 size 64 48\n", 1,
		"camera: fov must be between 0 and 180");
	bad("camera eye 0 0 10 look 0 0 0 up 0 0 1 fov 40 size 64 48\n", 1,
		"camera: up is zero or parallel");
	bad("camera eye 0 0 10 look 0 0 0 up 0 1 0 size 64 48\n", 1, "camera: missing 'fov'");
	bad(HEAD "box white 0 0 0 1 1 1 spin 3\n", 4, "box: unexpected 'spin'");
	bad(HEAD "box white 1 0 0 0 1 1\n", 4, "box: the first corner must be below");
	bad(HEAD "quad white 0 0 0 1 0 0 1 1 1 0 1 0\n", 4, "quad: corners are not coplanar");
	bad(HEAD "quad white 0 0 0 3 2 0 3 0 0 0 1 0\n", 4, "quad: edges cross");
	bad(HEAD "triangle white 0 0 0 1 1 1 2 2 2\n", 4, "triangle: zero area");
	bad(HEAD "quad white 0 0 0 1 0 0 2 0 0 3 0 0\n", 4, "quad: zero area");
	bad(HEAD "sphere white 0 0 0 1 subdiv 11\n", 4, "sphere: subdiv must be a whole number from 1 to 10");
	bad(HEAD "box white 0 0 0 1 1 1 scale 0\n", 4, "box: scale must not be zero");
	bad(HEAD "pointlight 0 0 0 power -1 1 1\n", 4, "pointlight: power must be >= 0");

	/* A line longer than the limit. */
	size_t n = 70000;
	char *big = malloc(n + 200);
	strcpy(big, HEAD "# ");
	size_t l = strlen(big);
	memset(big + l, 'x', n);
	strcpy(big + l + n, "\n");
	bad(big, 4, "line longer than 65536 bytes");
	free(big);

	/* A file that does not open names the file. */
	pm_scene s;
	pm_error err = {""};
	char path[300];
	snprintf(path, sizeof path, "%s/none.pms", dir);
	CHECK(pm_scene_load(&s, path, &err) == -1);
	CHECKF(strstr(err.msg, "cannot open '") && strstr(err.msg, "none.pms': No such file"), "%s", err.msg);
}

static void
example(const char *rel, pm_scene *s, int *ok)
{
	const char *top = getenv("PM_TOP");
	char path[1024];
	pm_error err = {""};
	snprintf(path, sizeof path, "%s/%s", top ? top : ".", rel);
	*ok = pm_scene_load(s, path, &err) == 0;
	CHECKF(*ok, "%s", err.msg);
}

TEST(example_cornell)
{
	pm_scene s;
	int ok;
	example("examples/cornell/cornell.pms", &s, &ok);
	if (!ok)
		return;
	/* Four walls and the light as quads, the warped left wall as two
	 * triangles, two closed blocks of six quads. */
	CHECKF(s.npolys == 19, "%u polygons", s.npolys);
	int quads = 0;
	for (uint32_t i = 0; i < s.npolys; i++)
		quads += s.poly_start[i + 1] - s.poly_start[i] == 4;
	CHECKF(quads == 17, "%d quads", quads);
	int solids = 0, emitters = 0;
	for (int o = 0; o < s.nobjs; o++) {
		solids += s.objs[o].solid;
		emitters += pm_maxc(s.mats[s.objs[o].material].emit) > 0;
	}
	CHECK(solids == 2 && emitters == 1);
	CHECK(s.camera.width == 256 && s.camera.height == 256 && fabsf(s.camera.fov - 39.3f) < 0.1f);
	/* The light faces down into the box. */
	for (int o = 0; o < s.nobjs; o++)
		if (pm_maxc(s.mats[s.objs[o].material].emit) > 0)
			CHECK(s.poly_normal[s.objs[o].first_poly].y < -0.999f);
	pm_scene_free(&s);
}

TEST(example_room)
{
	pm_scene s;
	int ok;
	example("examples/room/room.pms", &s, &ok);
	if (!ok)
		return;
	int strong_glossy = 0, glass = 0, meshes_closed = 0, emitters = 0;
	for (int m = 0; m < s.nmats; m++) {
		strong_glossy += s.mats[m].kind == PM_MAT_GLOSSY && s.mats[m].strong;
		glass += s.mats[m].kind == PM_MAT_GLASS;
	}
	for (int o = 0; o < s.nobjs; o++) {
		meshes_closed += s.objs[o].solid;
		if (pm_maxc(s.mats[s.objs[o].material].emit) > 0) {
			emitters++;
			/* The cove strips shine at the ceiling. */
			CHECK(s.poly_normal[s.objs[o].first_poly].y > 0.999f);
		}
	}
	CHECK(strong_glossy >= 1 && glass == 1 && emitters >= 1);
	CHECKF(s.nobjs >= 10 && meshes_closed >= 8, "%d objects, %d solid", s.nobjs, meshes_closed);
	pm_scene_free(&s);
}

int
main(void)
{
	snprintf(dir, sizeof dir, "/tmp/pm-test-scene-XXXXXX");
	if (!mkdtemp(dir)) {
		perror("mkdtemp");
		return 1;
	}
	RUN(quad_normal_and_triangles);
	RUN(box_outward_and_inward);
	RUN(rotate_maps_x_to_y);
	RUN(transforms_apply_in_order);
	RUN(mirroring_scale_keeps_normals_outward);
	RUN(sphere_area_and_normals);
	RUN(obj_cube_closed_quads);
	RUN(off_and_ply_read);
	RUN(obj_soup_cube_closed_by_position);
	RUN(closed_surface_round_the_eye_turned_over);
	RUN(obj_open_plane_is_sheet);
	RUN(obj_degenerate_faces_dropped);
	RUN(concave_polygon_ear_clipping);
	RUN(nonplanar_face_split);
	RUN(smooth_patches);
	RUN(smooth_patches_as_pairs_say);
	RUN(motion);
	RUN(materials_strong_and_soft);
	RUN(identity);
	RUN(identity_as_documented);
	RUN(malformed_scenes);
	RUN(example_cornell);
	RUN(example_room);
	static const char *const files[] = {"t.pms", "h.pms", "bad.pms", "cube.obj", "plane.obj",
		"degen.obj", "cubein.obj", "ell.obj", "soup.obj", "grid.obj", "bent.obj", "junk.obj", "junk.xyz", "cube.off", "cube.ply"};
	char path[300];
	for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
		snprintf(path, sizeof path, "%s/%s", dir, files[i]);
		unlink(path);
	}
	rmdir(dir);
	return check_done();
}
