/* test_estimators.c — the estimator table (lib/estimators/estimators.h): rows that
 * pm-render can dispatch through without knowing them, and the posed scene
 * (lib/optics/frame.h) that holds the polygon index exactly when a row needs it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "estimators/estimators.h"
#include "optics/frame.h"
#include "estimators/photonview.h"

TEST(rows_are_whole_and_named_once)
{
	int n = 0;
	for (const pm_estimator *e = pm_estimators; e->name; e++, n++) {
		CHECKF(*e->name && e->help && *e->help, "row %d", n);
		CHECKF(!e->scratch_new == !e->scratch_free, "%s: scratch new without free", e->name);
		CHECKF(!(e->estimate && e->image), "%s: both an estimate and an image", e->name);
		CHECKF(!(e->estimate || e->image) || (e->needs & PM_NEEDS_MAP),
		       "%s: reads photons but needs no map", e->name);
		CHECKF(!e->scratch_new || e->estimate, "%s: scratch for no estimate", e->name);
		CHECKF(pm_estimator_find(e->name) == e, "%s: found as another row", e->name);
	}
	CHECK(n >= 4);
	CHECK(pm_estimator_find("bogus") == NULL);
	CHECK(pm_estimator_find("") == NULL);
}

TEST(the_names_files_and_scripts_use)
{
	/* pm.estimator in every pass image, and the usage line in the order the
	 * man page gives them. */
	const char *want[] = {"classical", "compensated", "path", "photons"};
	for (int i = 0; i < 4; i++)
		CHECKF(pm_estimators[i].name && strcmp(pm_estimators[i].name, want[i]) == 0,
		       "row %d is %s", i, pm_estimators[i].name ? pm_estimators[i].name : "(end)");
	CHECK(pm_estimator_find("photons")->image == pm_photonview_image);
	CHECK(pm_estimator_find("path")->needs == 0);
}

TEST(scratch_comes_and_goes)
{
	for (const pm_estimator *e = pm_estimators; e->name; e++) {
		if (!e->scratch_new)
			continue;
		void *sc = e->scratch_new(50);
		CHECKF(sc != NULL, "%s", e->name);
		e->scratch_free(sc);
	}
}

static const char scene[] =
	"camera eye 0 0 10 look 0 0 0 up 0 1 0 fov 40 size 64 48\n"
	"pointlight 0 5 0 power 10 10 10\n"
	"material white diffuse albedo 0.5 0.5 0.5\n"
	"quad white -5 -1 -5  -5 -1 5  5 -1 5  5 -1 -5\n"
	"box white -1 -1 -1 1 1 1\n";

TEST(frame_poses_the_scene_and_builds_what_is_needed)
{
	pm_scene s;
	pm_frame f;
	pm_error err = {""};
	FILE *fp = fopen("frame.pms", "wb");

	CHECK(fp != NULL);
	if (!fp)
		return;
	fputs(scene, fp);
	fclose(fp);
	CHECKF(pm_scene_load(&s, "frame.pms", &err) == 0, "%s", err.msg);
	if (err.msg[0])
		return;
	for (int needs = 0; needs <= PM_NEEDS_POLYINDEX; needs++) {
		CHECKF(pm_frame_build(&f, &s, 0.25f, needs, &err) == 0, "%s", err.msg);
		pm_vec3 *v = malloc((s.nverts ? s.nverts : 1) * sizeof *v);
		pm_scene_verts_at(&s, 0.25f, v);
		CHECK(f.s == &s && f.time == 0.25f && f.accel && f.lights.n > 0);
		CHECK(memcmp(v, f.verts, s.nverts * sizeof *v) == 0);
		CHECK(!f.pi == !(needs & PM_NEEDS_POLYINDEX));
		free(v);
		pm_frame_free(&f);
		CHECK(f.verts == NULL && f.accel == NULL && f.pi == NULL);
	}
	pm_scene_free(&s);
}

int
main(void)
{
	RUN(rows_are_whole_and_named_once);
	RUN(the_names_files_and_scripts_use);
	RUN(scratch_comes_and_goes);
	RUN(frame_poses_the_scene_and_builds_what_is_needed);
	return check_done();
}
