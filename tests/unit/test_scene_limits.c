/* test_scene_limits.c — the range of formats/scene.md ("Range",
 * scene_limits.h) at its edges: each bound accepts its value and refuses
 * a value 1e-6 beyond it (a bound is met as written in a scene, whose
 * float may lie a rounding past it), for positions (with move), the camera, the
 * extent and power; and the loader reports a refusal at the line at
 * fault. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "scene/scene.h"
#include "scene/scene_limits.h"

static char dir[64];

static pm_camera_desc
camera(void)
{
	pm_camera_desc c = {pm_v3(0, 1, 3), pm_v3(0, 1, 0), pm_v3(0, 1, 0), 45, 8, 6};
	return c;
}

TEST(vertex_bound_with_move)
{
	pm_error e;
	double at[3] = {PM_COORD_MAX, -PM_COORD_MAX, 0};
	double past[3] = {0, 1.000001e12, 0};
	CHECK(pm_limits_vertex(at, pm_v3(0, 0, 0), "box", &e) == 0);
	CHECK(pm_limits_vertex(past, pm_v3(0, 0, 0), "box", &e) == -1);
	CHECKF(!strncmp(e.msg, "box: a vertex reaches", 21), "%s", e.msg);
	/* 1e12 at t = 0, beyond at t = 1 */
	CHECK(pm_limits_vertex(at, pm_v3(1e6f, 0, 0), "sphere", &e) == -1);
	CHECKF(strstr(e.msg, "with 'move'") != NULL, "%s", e.msg);
	double mid[3] = {0.5e12, 0, 0};
	CHECK(pm_limits_vertex(mid, pm_v3(-1.6e12f, 0, 0), "sphere", &e) == -1);
	CHECK(pm_limits_vertex(mid, pm_v3(-1.4e12f, 0, 0), "sphere", &e) == 0);
}

TEST(camera_bounds)
{
	pm_error e;
	pm_camera_desc c = camera();
	CHECK(pm_limits_camera(&c, &e) == 0);
	c.eye = pm_v3(1e12f, 1, 3);
	CHECKF(pm_limits_camera(&c, &e) == 0, "%s", e.msg);
	c.eye = pm_v3(1.000001e12f, 1, 3);
	CHECK(pm_limits_camera(&c, &e) == -1);
	CHECKF(!strncmp(e.msg, "camera: eye", 11), "%s", e.msg);
	c = camera();
	c.fov = (float)PM_FOV_MAX;
	CHECK(pm_limits_camera(&c, &e) == 0);
	c.fov = 179.9992f;
	CHECK(pm_limits_camera(&c, &e) == -1);
	c.fov = (float)PM_FOV_MIN;
	CHECK(pm_limits_camera(&c, &e) == 0);
	c.fov = (float)(PM_FOV_MIN * 0.999999);
	CHECK(pm_limits_camera(&c, &e) == -1);
	c = camera();
	c.eye = pm_v3(0, 0, 0);
	c.look = pm_v3(0, 0, -1e-12f);
	CHECKF(pm_limits_camera(&c, &e) == 0, "%s", e.msg);
	c.look = pm_v3(0, 0, -0.999e-12f);
	CHECK(pm_limits_camera(&c, &e) == -1);
	/* 1e-6 of the magnitude: look 0.5 from an eye at 1e6 is too close */
	c.eye = pm_v3(1e6f, 0, 0);
	c.look = pm_v3(1e6f, 0, 0.5f);
	CHECK(pm_limits_camera(&c, &e) == -1);
	c.look = pm_v3(1e6f, 0, 2);
	CHECK(pm_limits_camera(&c, &e) == 0);
	c = camera();
	c.up = pm_v3(0, 1e-12f, 0);
	CHECKF(pm_limits_camera(&c, &e) == 0, "%s", e.msg);
	c.up = pm_v3(0, 0.999e-12f, 0);
	CHECK(pm_limits_camera(&c, &e) == -1);
	CHECKF(!strncmp(e.msg, "camera: up is", 13), "%s", e.msg);
}

TEST(emit_bound)
{
	pm_error e;
	pm_material m;
	memset(&m, 0, sizeof m);
	m.emit = pm_v3(0, (float)PM_RADIANCE_MAX, 0);
	CHECK(pm_limits_material(&m, "material 'x'", &e) == 0);
	m.emit.y = 1.000001e30f;
	CHECK(pm_limits_material(&m, "material 'x'", &e) == -1);
	CHECKF(!strncmp(e.msg, "material 'x': emit", 18), "%s", e.msg);
}

/* Loads text as a scene; the message (or "") in msg. */
static int
load(const char *text, char *msg, size_t n)
{
	char path[128];
	snprintf(path, sizeof path, "%s/s.pms", dir);
	FILE *f = fopen(path, "w");
	if (!f)
		return -2;
	fputs(text, f);
	fclose(f);
	pm_scene s;
	pm_error e = {""};
	int r = pm_scene_load(&s, path, &e);
	snprintf(msg, n, "%s", r ? strstr(e.msg, "s.pms:") : "");
	if (r == 0)
		pm_scene_free(&s);
	return r;
}

#define HEAD "camera eye 0 0 1 look 0 0 0 up 0 1 0 fov 45 size 8 6\n" \
	"material w diffuse albedo 0.5 0.5 0.5\n"

TEST(extent_and_power_in_the_loader)
{
	char msg[600];
	/* 1e-9 across: in; a little less: out, at the last line */
	CHECKF(load(HEAD "box w 0 0 0 1e-9 1e-9 1e-9\npointlight 0 0 0 power 1e-19 1e-19 1e-19\n",
	            msg, sizeof msg) == 0, "%s", msg);
	CHECK(load(HEAD "box w 0 0 0 0.9e-9 0.9e-9 0.9e-9\npointlight 0 0 0 power 1e-19 1e-19 1e-19\n",
	           msg, sizeof msg) == -1);
	CHECKF(!strncmp(msg, "s.pms:4: the scene is 9e-10 across", 34), "%s", msg);
	/* power against the extent: 2 across, so 4e30 W is the most */
	CHECKF(load(HEAD "box w -1 -1 -1 1 1 1 inward\npointlight 0 0 0 power 1e30 1 1\n",
	            msg, sizeof msg) == 0, "%s", msg);
	CHECK(load(HEAD "box w -0.1 -0.1 -0.1 0.1 0.1 0.1 inward\npointlight 0 0 0 power 1e29 1 1\n",
	           msg, sizeof msg) == -1);
	CHECKF(strstr(msg, "s.pms:4: pointlight 1 of the file: power 1e+29") == msg, "%s", msg);
	/* all lights together: two of 6e29 W pass one by one, not in sum */
	CHECK(load(HEAD "box w -1 -1 -1 1 1 1 inward\npointlight 0 0 0 power 6e29 1 1\n"
	           "pointlight 0 0 0.5 power 6e29 1 1\n", msg, sizeof msg) == -1);
	CHECKF(strstr(msg, "s.pms:5: the lights emit 1.2e+30 W in all") == msg, "%s", msg);
	/* an emitter's power is pi emit area: 1e30 over 1 m^2 is 3.1e30 W */
	CHECK(load(HEAD "material l diffuse albedo 0 0 0 emit 1e30 0 0\n"
	           "quad l 0 0 0  1 0 0  1 1 0  0 1 0\n", msg, sizeof msg) == -1);
	CHECKF(strstr(msg, "the lights emit 3.14e+30 W in all") != NULL, "%s", msg);
	/* the statement at fault: a translate past the range, line 3 */
	CHECK(load(HEAD "box w 0 0 0 1 1 1 translate 0 0 -2e12\npointlight 0 0 0 power 1 1 1\n",
	           msg, sizeof msg) == -1);
	CHECKF(!strncmp(msg, "s.pms:3: box: a vertex reaches -2e+12", 37), "%s", msg);
}

int
main(void)
{
	snprintf(dir, sizeof dir, "/tmp/pm-test-limits-XXXXXX");
	if (!mkdtemp(dir)) {
		perror("mkdtemp");
		return 1;
	}
	RUN(vertex_bound_with_move);
	RUN(camera_bounds);
	RUN(emit_bound);
	RUN(extent_and_power_in_the_loader);
	char path[128];
	snprintf(path, sizeof path, "%s/s.pms", dir);
	unlink(path);
	rmdir(dir);
	return check_done();
}
