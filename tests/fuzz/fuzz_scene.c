/* fuzz_scene.c — fuzz target for the scene parser (pm_scene_load in
 * lib/scene/scene.c, formats/scene.md). Whatever the bytes, it must return 0 or
 * -1 with a one-line "FILE:LINE: message" (or a message naming the file);
 * an accepted scene must satisfy the invariants scene.h promises. Two small
 * meshes (cube.obj, tri.off) sit beside the scene so that mesh lines have
 * something to load. */
#define _GNU_SOURCE
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "scene/scene.h"

static void
require(int cond, const char *what)
{
	if (!cond) {
		fprintf(stderr, "fuzz_scene: %s\n", what);
		abort();
	}
}

static void
meshes(void)
{
	static int done;
	static const char cube[] =
		"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
		"f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";
	static const char tri[] = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

	if (done)
		return;
	fuzz_file("cube.obj", (const uint8_t *)cube, sizeof cube - 1);
	fuzz_file("tri.off", (const uint8_t *)tri, sizeof tri - 1);
	done = 1;
}

static void
check_scene(const pm_scene *s)
{
	require(s->camera.width >= 1 && s->camera.height >= 1, "empty image size");
	require(s->camera.fov > 0 && s->camera.fov < 180, "fov out of range");
	require(s->poly_start && s->poly_start[0] == 0, "polygon array contract");
	for (uint32_t i = 0; i < s->npolys; i++) {
		require(s->poly_start[i + 1] >= s->poly_start[i] + 3, "polygon with fewer than 3 corners");
		require(s->poly_obj[i] < (uint32_t)s->nobjs, "polygon of no object");
		require(isfinite(s->poly_normal[i].x) && isfinite(s->poly_normal[i].y) &&
		        isfinite(s->poly_normal[i].z), "non-finite normal");
		for (uint32_t k = s->poly_start[i]; k < s->poly_start[i + 1]; k++)
			require(s->poly_vert[k] < s->nverts, "corner index out of range");
	}
	for (uint32_t i = 0; i < s->nverts; i++)
		require(isfinite(s->verts[i].x) && isfinite(s->verts[i].y) && isfinite(s->verts[i].z),
		        "non-finite vertex");
	for (uint32_t i = 0; i < s->ntris; i++) {
		require(s->tri_poly[i] < s->npolys, "triangle of no polygon");
		for (int k = 0; k < 3; k++)
			require(s->tris[i][k] < s->nverts, "triangle index out of range");
	}
	for (int o = 0; o < s->nobjs; o++)
		require(s->objs[o].material >= 0 && s->objs[o].material < s->nmats, "object without material");
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	pm_scene s;
	pm_error err = {""};
	const char *path;

	meshes();
	path = fuzz_file("scene.pms", data, size);
	if (pm_scene_load(&s, path, &err) != 0) {
		require(err.msg[0] && !strchr(err.msg, '\n'), "failure without a one-line message");
		return 0;
	}
	check_scene(&s);
	pm_scene_free(&s);
	return 0;
}
