/* frame.c — the scene posed at one shutter time (see frame.h). */
#include "optics/frame.h"

#include <stdlib.h>
#include <string.h>

int
pm_frame_build(pm_frame *f, const pm_scene *s, float t, int needs, pm_error *err)
{
	memset(f, 0, sizeof *f);
	f->s = s;
	f->time = t;
	f->verts = malloc((s->nverts ? s->nverts : 1) * sizeof *f->verts);
	if (!f->verts)
		return pm_seterr(err, "out of memory");
	pm_scene_verts_at(s, t, f->verts);
	if (pm_accel_build(&f->accel, s, f->verts, err) != 0
	    || pm_lights_build(&f->lights, s, f->verts, t, err) != 0
	    || ((needs & PM_NEEDS_POLYINDEX) && pm_polyindex_build(&f->pi, s, f->verts, err) != 0)) {
		pm_frame_free(f);
		return -1;
	}
	return 0;
}

void
pm_frame_free(pm_frame *f)
{
	pm_polyindex_free(f->pi);
	pm_lights_free(&f->lights);
	pm_accel_free(f->accel);
	free(f->verts);
	memset(f, 0, sizeof *f);
}
