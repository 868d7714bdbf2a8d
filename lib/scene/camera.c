/* camera.c — pinhole camera rays (see camera.h). */
#include "scene/camera.h"

#include <math.h>

int
pm_camera_init(pm_camera *c, const pm_camera_desc *d, pm_error *err)
{
	pm_vec3 f = pm_sub(d->look, d->eye), r;

	if (pm_len(f) == 0)
		return pm_seterr(err, "camera: eye and look are the same point");
	f = pm_norm(f);
	r = pm_cross(f, d->up);
	if (pm_len(r) < 1e-6f * pm_len(d->up) || pm_len(d->up) == 0)
		return pm_seterr(err, "camera: up is parallel to the view direction");
	c->eye = d->eye;
	c->f = f;
	c->r = pm_norm(r);
	c->u = pm_cross(c->r, f);
	c->tan_half = tanf(0.5f * d->fov * (float)PM_PI / 180.0f);
	c->width = d->width;
	c->height = d->height;
	return 0;
}

pm_vec3
pm_camera_dir(const pm_camera *c, float sx, float sy)
{
	float x = (2.0f * sx / (float)c->width - 1.0f) * c->tan_half * (float)c->width / (float)c->height;
	float y = (1.0f - 2.0f * sy / (float)c->height) * c->tan_half;

	return pm_norm(pm_add(c->f, pm_add(pm_scale(c->r, x), pm_scale(c->u, y))));
}
