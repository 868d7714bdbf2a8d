/* ply.h — PLY meshes as renderers' scenes ship them: ASCII or binary of
 * either byte order, optionally gzip-compressed (.ply.gz, read through
 * zlib), triangles, quads and larger polygons, per-vertex normals and
 * texture coordinates named u/v, s/t or texture_u/texture_v. */
#ifndef PM_IMPORT_PLY_H
#define PM_IMPORT_PLY_H

#include "base/err.h"
#include "import/desc.h"

/* Reads path into the mesh shape s (positions as in the file, faces as
 * written, uv if the file has them) and, if the file has nx ny nz, a
 * malloc'd array of 3 floats per vertex into *normals (else NULL). On
 * failure err names the file (and the element at fault) and s is freed. */
int pmi_ply_read(const char *path, pmi_shape *s, float **normals, pm_error *err);

#endif
