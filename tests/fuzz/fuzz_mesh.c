/* fuzz_mesh.c — fuzz target for mesh loading through OpenMesh (pm_mesh_read
 * in lib/scene/mesh.cpp). The first byte picks the format (obj, off, ply, stl,
 * om), the rest is the file. Whatever the bytes, the shim must return 0 or
 * -1 with a one-line message and never let a C++ exception out; an accepted
 * mesh must have indices in range and finite-or-not coordinates copied as
 * they are. */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "scene/mesh.h"

static void
require(int cond, const char *what)
{
	if (!cond) {
		fprintf(stderr, "fuzz_mesh: %s\n", what);
		abort();
	}
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	static const char *const ext[] = {"obj", "off", "ply", "stl", "om"};
	char name[32];
	pm_meshdata m;
	pm_error err = {""};
	const char *path;

	if (size < 1)
		return 0;
	snprintf(name, sizeof name, "in.%s", ext[data[0] % 5]);
	path = fuzz_file(name, data + 1, size - 1);
	if (pm_mesh_read(path, &m, &err) != 0) {
		require(err.msg[0] && !strchr(err.msg, '\n'), "failure without a one-line message");
		return 0;
	}
	require(m.nfaces > 0 && m.face_start[0] == 0, "face array contract");
	for (uint32_t f = 0; f < m.nfaces; f++) {
		require(m.face_start[f + 1] >= m.face_start[f] + 3, "face with fewer than 3 corners");
		for (uint32_t k = m.face_start[f]; k < m.face_start[f + 1]; k++)
			require(m.face_vert[k] < m.nverts, "vertex index out of range");
	}
	pm_mesh_free(&m);
	return 0;
}
