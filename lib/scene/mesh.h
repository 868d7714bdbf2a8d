/* mesh.h — polygon mesh files (OBJ, PLY, OFF, STL, OM) read through OpenMesh.
 *
 * A C face on a small C++ shim (mesh.cpp): the caller gets plain arrays and
 * never sees a C++ type or exception. Faces stay polygons as written (no
 * triangulation); their vertex order is the file's winding. */
#ifndef PM_MESH_H
#define PM_MESH_H

#include <stdint.h>

#include "base/err.h"

/* Upper bounds the reader enforces, so a hostile file cannot make us allocate
 * without limit. */
#define PM_MESH_MAX_VERTS (1u << 28)
#define PM_MESH_MAX_FACES (1u << 28)
#define PM_MESH_MAX_FACE_VERTS 1024u   /* vertices of one polygon */
#define PM_MESH_MAX_BYTES (1ull << 31) /* file size */

typedef struct pm_meshdata {
	uint32_t nverts;
	double *verts;          /* 3 * nverts coordinates, as in the file */
	uint32_t nfaces;
	uint32_t *face_start;   /* nfaces + 1 entries into face_vert */
	uint32_t *face_vert;    /* vertex indices, face_start[nfaces] of them */
	/* Per-vertex normals as the file gives them (OBJ vn, PLY nx ny nz),
	 * 3 * nverts, not normalized; NULL if the file has none. */
	double *normals;
	/* Per-vertex texture coordinates (OBJ vt, PLY u v / s t /
	 * texture_u texture_v), 2 * nverts; NULL if the file has none. */
	double *uv;
	/* 1 if the mesh is a closed surface: no boundary halfedges (OpenMesh
	 * topology), or, corners at one position taken as one vertex (a
	 * polygon soup), every edge met once in each direction. Faces OpenMesh
	 * could only add as separate non-manifold pieces leave an edge met
	 * more than once, so such a mesh is not closed. */
	int closed;
	/* Faces OpenMesh dropped while reading (fewer than 3 distinct vertices
	 * or a repeated vertex; consecutive repeats are removed first). */
	uint32_t ndropped;
} pm_meshdata;

/* Reads the mesh file at path; the format follows the extension. On failure
 * err says "'PATH': cannot read mesh: reason" and *out is left empty. A file
 * that yields no faces is an error. OpenMesh's own diagnostics are silenced
 * during the read (they go to process-wide streams, so this function must not
 * run concurrently with other OpenMesh users). */
int pm_mesh_read(const char *path, pm_meshdata *out, pm_error *err);

void pm_mesh_free(pm_meshdata *m);

#endif
