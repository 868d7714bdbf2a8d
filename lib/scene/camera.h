/* camera.h — the pinhole look-at camera (formats/scene.md):
 * f = normalize(look - eye), r = normalize(f x up), u = r x f; image x runs
 * along +r, image y runs down along -u; fov is the full vertical angle;
 * pixel (0,0) is the top-left pixel and covers raster [0,1] x [0,1]. */
#ifndef PM_CAMERA_H
#define PM_CAMERA_H

#include "base/err.h"
#include "scene/scene.h"
#include "base/vec.h"

typedef struct pm_camera {
	pm_vec3 eye, f, r, u;
	float tan_half;     /* tan(fov / 2) */
	int width, height;
} pm_camera;

/* Fails if look == eye or up is parallel to the view direction. */
int pm_camera_init(pm_camera *c, const pm_camera_desc *d, pm_error *err);

/* Unit direction of the ray through raster position (sx, sy), sx in
 * [0, width], sy in [0, height]. */
pm_vec3 pm_camera_dir(const pm_camera *c, float sx, float sy);

#endif
