/* test_camera.c — the camera conventions of formats/scene.md. */
#include <math.h>

#include "scene/camera.h"
#include "check.h"

static pm_camera_desc
desc(void)
{
	pm_camera_desc d = {.eye = {1, 2, 3}, .look = {1, 2, -7}, .up = {0, 1, 0},
	                    .fov = 90, .width = 200, .height = 100};
	return d;
}

TEST(centre_is_forward)
{
	pm_camera c;
	pm_camera_desc d = desc();
	CHECK(pm_camera_init(&c, &d, NULL) == 0);
	pm_vec3 v = pm_camera_dir(&c, 100, 50);
	CHECKF(fabsf(v.x) < 1e-6f && fabsf(v.y) < 1e-6f && fabsf(v.z + 1) < 1e-6f, "%g %g %g", v.x, v.y, v.z);
}

/* Looking down -z with up +y, right is +x; raster y grows downward; the
 * full vertical fov of 90 degrees puts the top edge at 45 degrees up and the
 * square pixels put the right edge at atan(2) for a 2:1 image. */
TEST(edges_and_orientation)
{
	pm_camera c;
	pm_camera_desc d = desc();
	pm_camera_init(&c, &d, NULL);
	pm_vec3 top = pm_camera_dir(&c, 100, 0), right = pm_camera_dir(&c, 200, 50);
	pm_vec3 tl = pm_camera_dir(&c, 0.5f, 0.5f);
	CHECKF(fabsf(atan2f(top.y, -top.z) - (float)PM_PI / 4) < 1e-5f, "top %g", atan2f(top.y, -top.z));
	CHECKF(fabsf(atan2f(right.x, -right.z) - atanf(2)) < 1e-5f, "right %g", atan2f(right.x, -right.z));
	CHECK(tl.x < 0 && tl.y > 0);
}

TEST(bad_cameras)
{
	pm_camera c;
	pm_error err;
	pm_camera_desc d = desc();
	d.look = d.eye;
	CHECK(pm_camera_init(&c, &d, &err) == -1);
	d = desc();
	d.up = pm_v3(0, 0, 1);
	CHECK(pm_camera_init(&c, &d, &err) == -1);
}

int
main(void)
{
	RUN(centre_is_forward);
	RUN(edges_and_orientation);
	RUN(bad_cameras);
	return check_done();
}
