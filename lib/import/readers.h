/* readers.h — one reader per source format, each filling a pmi_desc
 * (desc.h). A reader records in d->notes every feature it dropped or could
 * only approximate; on failure err holds one line "FILE:LINE: message" and
 * d holds whatever was read (free it with pmi_free). */
#ifndef PM_IMPORT_READERS_H
#define PM_IMPORT_READERS_H

#include "base/err.h"
#include "import/desc.h"

/* pbrt-v4 scene files (pbrt.c). The camera frame is pbrt's: a plain
 * LookAt gives a left-handed one, which the writer mirrors. */
int pmi_read_pbrt(const char *path, pmi_desc *d, pm_error *err);

/* Mitsuba 3 XML scenes (mitsuba.c), parsed with expat. */
int pmi_read_mitsuba(const char *path, pmi_desc *d, pm_error *err);

/* Wavefront OBJ with its MTL libraries (objmtl.c). No camera: the caller
 * sets one (pmi_frame_camera frames the geometry). */
int pmi_read_obj(const char *path, pmi_desc *d, pm_error *err);

/* An OBJ's faces as one mesh, its materials ignored (Mitsuba's obj
 * shapes), with the file's uv and vertex normals where every group has
 * them. On failure err names the file and line and s is empty. */
int pmi_read_obj_mesh(const char *path, pmi_shape *s, pm_error *err);

/* Which reader a file wants, by its extension (.pbrt, .xml, .obj, any
 * case); NULL if none. */
typedef int (*pmi_reader)(const char *path, pmi_desc *d, pm_error *err);
pmi_reader pmi_reader_for(const char *path);

#endif
