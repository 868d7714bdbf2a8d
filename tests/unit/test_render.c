/* test_render.c — the view pass's sharing of first-hit estimates within a
 * pixel (lib/passes/render.c, --estimates pixel), counted through an
 * estimator that only counts: how many estimates a picture of two patches
 * takes. */
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "passes/render.h"

static atomic_long made;

static pm_vec3
counting(const pm_est_in *in, void *sc, pm_vec3 x, pm_vec3 n, pm_vec3 ns, pm_vec3 wo,
         const pm_material *m, pm_estimate_info *info)
{
	atomic_fetch_add(&made, 1);
	memset(info, 0, sizeof *info);
	/* A support far wider than a pixel's footprint: reuse is always
	 * allowed, so the count follows from the rule alone. */
	info->disc = 1e3f;
	info->size = 1e3f;
	info->nphotons = 1;
	return pm_v3(0, 0, 0);
}

static const pm_estimator count_row = {"count", "counts its calls", 0, NULL, NULL, counting, NULL};

/* Eight by eight pixels of two coplanar quads, each its own patch, meeting
 * along a line through the middle of row 3 (the camera sees y from -0.875
 * to 0.875, a row 0.21875 high). */
static const char scene[] =
	"camera eye 0 0 10 look 0 0 0 up 0 1 0 fov 10 size 8 8\n"
	"pointlight 0 0 5 power 10 10 10\n"
	"material white diffuse albedo 0.5 0.5 0.5\n"
	"quad white -5 -5 0  5 -5 0  5 0.109375 0  -5 0.109375 0\n"
	"quad white -5 0.109375 0  5 0.109375 0  5 5 0  -5 5 0\n";

static long
render_count(const pm_scene *s, int once, int spp)
{
	pm_frame f;
	pm_image img;
	pm_error err = {""};
	pm_render_opts o = {.estimator = &count_row, .k = 50, .spp = spp, .light_samples = 1,
	                    .estimate_once = once, .seed = 7};

	atomic_store(&made, 0);
	CHECKF(pm_frame_build(&f, s, 0, 0, &err) == 0, "%s", err.msg);
	if (err.msg[0])
		return -1;
	CHECKF(pm_render(&f, NULL, &o, &img, &err) == 0, "%s", err.msg);
	pm_frame_free(&f);
	if (err.msg[0])
		return -1;
	pm_image_free(&img);
	return atomic_load(&made);
}

TEST(every_patch_of_a_pixel_gives_its_word_to_the_next)
{
	pm_scene s;
	pm_error err = {""};
	FILE *fp = fopen("render.pms", "wb");

	CHECK(fp != NULL);
	if (!fp)
		return;
	fputs(scene, fp);
	fclose(fp);
	CHECKF(pm_scene_load(&s, "render.pms", &err) == 0, "%s", err.msg);
	if (err.msg[0])
		return;
	/* A row on one patch: its first pixel has no word from a previous
	 * one, so its first estimate is used once and the next one reused
	 * (2); each later pixel reuses its first (1). The row along the line
	 * sees both patches in every pixel (64 samples, half on each side):
	 * 4 in its first pixel, then 2, one a patch, whichever patch the
	 * pixel's first sample lands on. Taking the previous pixel's word on
	 * its first patch only gives 3 there. */
	long want = 7 * (2 + 7 * 1) + (4 + 7 * 2);
	long got = render_count(&s, 1, 64);
	CHECKF(got == want, "%ld estimates, want %ld", got, want);
	/* --estimates sample: one a camera sample whatever the rule */
	got = render_count(&s, 0, 64);
	CHECKF(got == 8 * 8 * 64, "%ld estimates a sample, want %d", got, 8 * 8 * 64);
	pm_scene_free(&s);
}

int
main(void)
{
	RUN(every_patch_of_a_pixel_gives_its_word_to_the_next);
	return check_done();
}
