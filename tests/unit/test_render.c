/* test_render.c — the view pass's sharing of first-hit estimates within a
 * pixel (lib/passes/render.c, --estimates pixel), counted through an
 * estimator that only counts: how many estimates a picture of two patches
 * takes; and past a textured mirror, which shares nothing, the estimate on
 * one camera sample in N (--past-glossy), weighted so that the picture is
 * the same. */
#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "estimators/estimators.h"
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
	return pm_v3(1, 1, 1);
}

static const pm_estimator count_row = {"count", "counts its calls", 0, NULL, NULL, counting, NULL};

/* Every scene here: eight by eight pixels looking down -z at the origin. */
#define CAMERA "camera eye 0 0 10 look 0 0 0 up 0 1 0 fov 10 size 8 8\n"

/* Eight by eight pixels of two coplanar quads, each its own patch, meeting
 * along a line through the middle of row 3 (the camera sees y from -0.875
 * to 0.875, a row 0.21875 high). */
static const char scene[] =
	CAMERA
	"pointlight 0 0 5 power 10 10 10\n"
	"material white diffuse albedo 0.5 0.5 0.5\n"
	"quad white -5 -5 0  5 -5 0  5 0.109375 0  -5 0.109375 0\n"
	"quad white -5 0.109375 0  5 0.109375 0  5 5 0  -5 5 0\n";

/* The specular layer's least and greatest value over the image, where
 * render_count() was asked for them. */
static float spec_lo, spec_hi;

/* Renders s with o at time 0 into *img: 0, or -1 after a check failed. */
static int
render_with(const pm_scene *s, const pm_render_opts *o, pm_image *img)
{
	pm_frame f;
	pm_error err = {""};

	CHECKF(pm_frame_build(&f, s, 0, 0, &err) == 0, "%s", err.msg);
	if (err.msg[0])
		return -1;
	CHECKF(pm_render(&f, NULL, o, img, &err) == 0, "%s", err.msg);
	pm_frame_free(&f);
	return err.msg[0] ? -1 : 0;
}

static long
render_count_past(const pm_scene *s, int once, int spp, int past)
{
	pm_image img;
	pm_render_opts o = {.estimator = &count_row, .k = 50, .spp = spp, .light_samples = 1,
	                    .estimate_once = once, .past_glossy = past, .seed = 7};

	atomic_store(&made, 0);
	if (render_with(s, &o, &img) != 0)
		return -1;
	size_t npx = (size_t)img.width * img.height;
	spec_lo = INFINITY;
	spec_hi = -INFINITY;
	for (size_t i = 0; i < npx; i++)
		for (int c = 9; c < 12; c++) {
			float v = img.px[(size_t)c * npx + i];
			spec_lo = v < spec_lo ? v : spec_lo;
			spec_hi = v > spec_hi ? v : spec_hi;
		}
	pm_image_free(&img);
	return atomic_load(&made);
}

static long
render_count(const pm_scene *s, int once, int spp)
{
	return render_count_past(s, once, spp, 1);
}

/* Writes text to file name and loads it into s: 0, or -1 after a check
 * failed. */
static int
load(pm_scene *s, const char *name, const char *text)
{
	pm_error err = {""};
	FILE *fp = fopen(name, "wb");

	CHECK(fp != NULL);
	if (!fp)
		return -1;
	fputs(text, fp);
	fclose(fp);
	CHECKF(pm_scene_load(s, name, &err) == 0, "%s", err.msg);
	return err.msg[0] ? -1 : 0;
}

TEST(every_patch_of_a_pixel_gives_its_word_to_the_next)
{
	pm_scene s;

	if (load(&s, "render.pms", scene) != 0)
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

/* The same two patches meeting along a column: x = 0.109375 runs
 * through the middle of column 4; the left one of material LEFT. */
#define COLUMN(LEFT) \
	"quad " LEFT " -5 -5 0  0.109375 -5 0  0.109375 5 0  -5 5 0\n" \
	"quad white 0.109375 -5 0  5 -5 0  5 5 0  0.109375 5 0\n"

static const char column_scene[] =
	CAMERA
	"pointlight 0 0 5 power 10 10 10\n"
	"material white diffuse albedo 0.5 0.5 0.5\n"
	COLUMN("white");

TEST(a_patch_new_to_the_row_takes_the_word_on_the_others)
{
	pm_scene s;

	if (load(&s, "column.pms", column_scene) != 0)
		return;
	/* Each row: its first pixel decides and reuses the next (2),
	 * columns 1-3 reuse (1 each); column 4 sees the right patch for the
	 * first time, which the previous pixel's yes on the left one lets
	 * it reuse at once (1 + 1, not 1 + 2); columns 5-7 reuse (1 each). */
	long want = 8 * (2 + 3 * 1 + 2 + 3 * 1);
	long got = render_count(&s, 1, 64);
	CHECKF(got == want, "%ld estimates, want %ld", got, want);
	pm_scene_free(&s);
}

/* The column's left patch black (an emitter's usual material): no
 * estimate is made there, since it would be 0 whatever the photons. */
static const char black_scene[] =
	CAMERA
	"pointlight 0 0 5 power 10 10 10\n"
	"material white diffuse albedo 0.5 0.5 0.5\n"
	"material black diffuse albedo 0 0 0 emit 1 1 1\n"
	COLUMN("black");

TEST(no_estimate_on_a_surface_that_reflects_nothing)
{
	pm_scene s;

	if (load(&s, "black.pms", black_scene) != 0)
		return;
	/* Each row: columns 0-3 see black only (none); column 4 sees the
	 * white patch first in the row, with no word from column 3, so it
	 * decides and reuses the next (2); columns 5-7 reuse (1 each). */
	long want = 8 * (2 + 3 * 1);
	long got = render_count(&s, 1, 64);
	CHECKF(got == want, "%ld estimates, want %ld", got, want);
	/* --estimates sample: every sample on the white half, none on the
	 * black: 32 a pixel in column 4 (half its samples, give or take),
	 * 64 in columns 5-7, so between 8 * 3 * 64 and 8 * 4 * 64. */
	got = render_count(&s, 0, 64);
	CHECKF(got > 8 * 3 * 64 && got < 8 * 4 * 64, "--estimates sample: %ld estimates", got);
	pm_scene_free(&s);
}

/* A lamp's edge down the middle of column 4, nothing beyond it; and a lamp
 * below the view's diagonal. */
static const char edge_scene[] =
	CAMERA
	"material lamp diffuse albedo 0 0 0 emit 1 1 1\n"
	"quad lamp -5 -5 0  0.109375 -5 0  0.109375 5 0  -5 5 0\n";
static const char diagonal_scene[] =
	CAMERA
	"material lamp diffuse albedo 0 0 0 emit 1 1 1\n"
	"triangle lamp -5 -5 0  5 -5 0  5 5 0\n";

/* The image's total layer rendered with spp samples and seed: a malloc'ed
 * copy of its 8 x 8 pixels, or NULL after a check failed. */
static float *
render_total(const pm_scene *s, int spp, uint64_t seed)
{
	pm_image img;
	pm_render_opts o = {.estimator = &count_row, .k = 50, .spp = spp, .light_samples = 1,
	                    .estimate_once = 1, .past_glossy = 1, .seed = seed};
	float *v = malloc(64 * sizeof *v);

	CHECK(v != NULL);
	if (!v || render_with(s, &o, &img) != 0) {
		free(v);
		return NULL;
	}
	memcpy(v, img.px, 64 * sizeof *v);
	pm_image_free(&img);
	return v;
}

/* A pixel's camera samples one to a cell of a 4 x 4 grid over it (16
 * samples): the pixel the lamp's edge halves has 8 on the lamp whatever
 * the seed (independent points put 8 there one time in five), and the
 * lamp below the diagonal covers half the picture on average. */
TEST(camera_samples_one_to_a_cell_of_the_pixel)
{
	pm_scene s;
	int exact = 0;

	if (load(&s, "edge.pms", edge_scene) != 0)
		return;
	for (uint64_t seed = 1; seed <= 4; seed++) {
		float *v = render_total(&s, 16, seed);
		if (!v)
			break;
		for (int y = 0; y < 8; y++) {
			float full = v[8 * y], half = v[8 * y + 4];
			CHECKF(full > 0 && v[8 * y + 3] == full && v[8 * y + 5] == 0, "row %d: %g %g %g", y,
			       full, v[8 * y + 3], v[8 * y + 5]);
			exact += fabsf(half - 0.5f * full) <= 1e-6f * full;
		}
		free(v);
	}
	CHECKF(exact == 32, "%d of 32 pixels on the edge read half the lamp", exact);
	pm_scene_free(&s);

	if (load(&s, "diagonal.pms", diagonal_scene) != 0)
		return;
	double sum = 0, lamp = 0;
	for (uint64_t seed = 1; seed <= 16; seed++) {
		float *v = render_total(&s, 16, seed);
		if (!v)
			break;
		for (int i = 0; i < 64; i++) {
			sum += v[i];
			lamp = v[i] > lamp ? v[i] : lamp;
		}
		free(v);
	}
	/* Per pixel on the diagonal 4 cells are cut (sd 1/16), 8 such pixels
	 * an image: the mean's sd is 0.14 % over 16 images. */
	double mean = sum / (16 * 64 * lamp);
	CHECKF(fabs(mean - 0.5) < 0.003, "the lamp covers %.4f of the picture, want 0.5", mean);
	pm_scene_free(&s);
}

/* A floor (albedo 0.5) lit by a square lamp of radiance 1 to one side,
 * out of view, facing down: nothing else, so each pixel of the path
 * tracer's picture is the floor's (0.5 / pi) E, E the lamp's irradiance
 * there (Lambert's formula for a polygon: half the sum over its edges of
 * the angle each subtends times the cosine of its plane through the
 * point). */
static const char lamp_scene[] =
	CAMERA
	"material white diffuse albedo 0.5 0.5 0.5\n"
	"material lamp diffuse albedo 0 0 0 emit 1 1 1\n"
	"quad white -5 -5 0  5 -5 0  5 5 0  -5 5 0\n"
	"quad lamp 1.5 -0.5 1  1.5 0.5 1  2.5 0.5 1  2.5 -0.5 1\n";

static double
lamp_irradiance(double x, double y)
{
	const double v[4][3] = {{1.5, -0.5, 1}, {1.5, 0.5, 1}, {2.5, 0.5, 1}, {2.5, -0.5, 1}};
	double e = 0;

	for (int i = 0; i < 4; i++) {
		const double *a = v[i], *b = v[(i + 1) % 4];
		double p[3] = {a[0] - x, a[1] - y, a[2]}, q[3] = {b[0] - x, b[1] - y, b[2]};
		double c[3] = {p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]};
		double lp = sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), lq = sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]);
		double lc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
		double beta = acos((p[0] * q[0] + p[1] * q[1] + p[2] * q[2]) / (lp * lq));
		e += beta * c[2] / lc;
	}
	return 0.5 * fabs(e);
}

/* The shadow rays of a pixel's samples share one set of strata over the
 * lamp (its two triangles and the points on them): over the 64 pixels of
 * floor, the path tracer's picture is within 2.5 % of the exact value
 * (root mean square; 5.5 % with each sample's rays stratified alone) and
 * within 1 % on average. */
TEST(shadow_rays_of_a_pixel_stratified_together)
{
	pm_scene s;
	pm_image img;
	pm_render_opts o = {.estimator = pm_estimator_find("path"), .k = 50, .spp = 16, .light_samples = 4,
	                    .estimate_once = 1, .past_glossy = 1, .seed = 3};
	double sum = 0, sum2 = 0;

	if (load(&s, "lamp.pms", lamp_scene) != 0)
		return;
	int bad = render_with(&s, &o, &img);
	pm_scene_free(&s);
	if (bad)
		return;
	for (int y = 0; y < 8; y++)
		for (int x = 0; x < 8; x++) {
			/* The pixel's centre on the floor: 0.21875 a pixel, y up. */
			double e = img.px[8 * y + x] / (0.5 / PM_PI *
			           lamp_irradiance(-0.875 + 0.21875 * (x + 0.5), 0.875 - 0.21875 * (y + 0.5))) - 1;
			sum += e;
			sum2 += e * e;
		}
	pm_image_free(&img);
	CHECKF(sqrt(sum2 / 64) < 0.025, "the pixels %.2f %% off (rms)", 100 * sqrt(sum2 / 64));
	CHECKF(fabs(sum / 64) < 0.01, "the pixels %.2f %% off on average", 100 * sum / 64);
}

/* A mirror whose reflectance is a texture (a checker of one grey, 0.5)
 * fills the view and the floor of a closed box; every camera ray reflects
 * off it to the box's ceiling, where its estimate is taken. The lamp is
 * under the mirror, which hides it from the ceiling, so the specular layer
 * is 0.5 times the estimate (1) and nothing else. */
static const char mirror_scene[] =
	CAMERA
	"pointlight 0 0 -0.5 power 10 10 10\n"
	"texture grey checker 0.5 0.5 0.5  0.5 0.5 0.5 scale 4 4\n"
	"material white diffuse albedo 0.5 0.5 0.5\n"
	"material m mirror reflect tex grey\n"
	"box white -6 -6 -1  6 6 12 inward\n"
	"quad m -6 -6 0  6 -6 0  6 6 0  -6 6 0\n";

TEST(past_a_mirror_that_shares_nothing_one_sample_in_n)
{
	pm_scene s;

	if (load(&s, "mirror.pms", mirror_scene) != 0)
		return;
	/* Every sample at 1; samples 0, 4, ... 60 at 4; 0 and 4 of 5 at 4,
	 * each weighted 5 / 2; 0 of 3 at 4 (one sample, weighted 3). */
	static const struct { int spp, past; long want; } c[] = {
		{64, 1, 64}, {64, 4, 16}, {64, 16, 4}, {5, 4, 2}, {3, 4, 1}, {1, 4, 1},
	};
	for (size_t i = 0; i < sizeof c / sizeof c[0]; i++) {
		long got = render_count_past(&s, 1, c[i].spp, c[i].past);
		CHECKF(got == 64 * c[i].want, "-p %d --past-glossy %d: %ld estimates, want %ld",
		       c[i].spp, c[i].past, got, 64 * c[i].want);
		CHECKF(fabsf(spec_lo - 0.5f) < 1e-6f && fabsf(spec_hi - 0.5f) < 1e-6f,
		       "-p %d --past-glossy %d: specular layer %.9g to %.9g, want 0.5", c[i].spp,
		       c[i].past, spec_lo, spec_hi);
	}
	/* --estimates sample: every sample, whatever N */
	long got = render_count_past(&s, 0, 64, 4);
	CHECKF(got == 64 * 64, "--estimates sample: %ld estimates, want %d", got, 64 * 64);
	pm_scene_free(&s);
}

int
main(void)
{
	RUN(every_patch_of_a_pixel_gives_its_word_to_the_next);
	RUN(a_patch_new_to_the_row_takes_the_word_on_the_others);
	RUN(past_a_mirror_that_shares_nothing_one_sample_in_n);
	RUN(no_estimate_on_a_surface_that_reflects_nothing);
	RUN(camera_samples_one_to_a_cell_of_the_pixel);
	RUN(shadow_rays_of_a_pixel_stratified_together);
	return check_done();
}
