/* frame.h — the scene posed at one shutter time: its vertices at t, the
 * ray-casting structure and the lights over them, and the polygon index
 * when an estimator asks for it. What both passes cast rays against, built
 * in one call and freed in one. */
#ifndef PM_FRAME_H
#define PM_FRAME_H

#include "scene/accel.h"
#include "base/err.h"
#include "optics/light.h"
#include "scene/polyindex.h"
#include "scene/scene.h"

/* A bit of pm_frame_build's needs: build the polygon index too. */
#define PM_NEEDS_POLYINDEX 1

typedef struct pm_frame {
	const pm_scene *s;
	float time;
	pm_vec3 *verts;        /* s's vertices at time */
	pm_accel *accel;
	pm_lights lights;
	pm_polyindex *pi;      /* NULL unless needs has PM_NEEDS_POLYINDEX */
} pm_frame;

/* Poses s at time t in [0,1]. needs: PM_NEEDS_POLYINDEX or 0; other bits
 * are ignored, so an estimator's needs can be passed as they are. s must
 * outlive f. On failure nothing is left to free. */
int pm_frame_build(pm_frame *f, const pm_scene *s, float t, int needs, pm_error *err);
void pm_frame_free(pm_frame *f);

#endif
