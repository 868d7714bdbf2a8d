/* write.h — the one writer: a scene description (desc.h) becomes a pm
 * scene, DIR/NAME.pms plus the binary PLY meshes it names beside it.
 * Materials and lights map to pm's models by one rule per kind (the table
 * in README, "Your own scenes"); every approximation or drop is added to
 * d->notes and written as a comment at the top of the .pms. */
#ifndef PM_IMPORT_WRITE_H
#define PM_IMPORT_WRITE_H

#include "base/err.h"
#include "import/desc.h"

typedef struct pmi_write_opts {
	int width, height;        /* image size; 0 keeps the source's */
	const char *command;      /* recorded in the .pms header, or NULL */
} pmi_write_opts;

/* Writes the scene. The result appears whole or not at all: meshes are
 * written first under names made from their contents (NAME-HASH.ply, so a
 * previous scene's meshes are never overwritten with other bytes), the
 * .pms is checked by loading it as pm does, and only then renamed into
 * place; meshes of the previous NAME.pms that the new one no longer uses
 * are removed afterwards. On failure every file this call created is
 * removed (and DIR, if it made it). */
int pmi_write(pmi_desc *d, const char *pms_path, const pmi_write_opts *o, pm_error *err);

/* A camera for a source without one (OBJ): the view along -z with +y up
 * that fits the bounding sphere of all shapes into the shorter image axis
 * at a field of view of fov degrees. -1 if there is no geometry. */
int pmi_frame_camera(pmi_desc *d, double fov, pm_error *err);

#endif
