/* pm-tonemap — an 8-bit sRGB PNG preview of an EXR's beauty image or one of
 * its layers: an exposure in stops (given, or automatic from the
 * log-average luminance), then a tone curve (lib/formats/tonemap.h). Several inputs
 * of one height are set side by side under one exposure, for comparisons
 * like the paper's figure 3. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "passes/compare.h"
#include "formats/image.h"
#include "formats/pngout.h"
#include "formats/tonemap.h"
#include "options.h"
#include "util.h"

static const char usage[] =
	"pm-tonemap [-ahq] [-c CURVE] [-e EV|auto] [-l NAME] [-w WHITE] -o OUT.png IN.exr|- [IN.exr ...]";

#define GAP 4   /* black columns between images set side by side */

/* Filled in main: they show GAP and PM_AUTO_KEY. */
static char about[200], exposure_help[400];

static const opt opts[] = {
	{ 'a', "abs", NULL, "show absolute values (for signed images like pm-diff -o)", NULL, 0 },
	{ 'c', "curve", "CURVE", "tone curve after the exposure: reinhard (highlights "
	  "compressed, white only from --white on) or clamp "
	  "(values at or above 1 are white)", "reinhard", 0 },
	{ 'e', "exposure", "EV", exposure_help, "auto", 0 },
	{ 'l', "layer", "NAME", "show NAME.R, NAME.G, NAME.B (or the single channel NAME "
	  "as grey)", "the beauty R, G, B", 0 },
	{ 'o', "output", "F", "the PNG to write; - for stdout", "none: required", 0 },
	{ 'q', "quiet", NULL, "do not print the auto exposure", "print it", 1 },
	{ 'w', "white", "WHITE", "reinhard's white point, in exposed units", "4", 0 },
	{ 0, NULL, NULL, NULL, NULL, 0 },
};

static const tool tonemap = { usage, about, opts, NULL };

/* One input's planes, copied out of its image (which is freed at once, so
 * that stdin is read only once and memory holds only what is shown). */
typedef struct shown {
	int w, h;
	float *p[3];
} shown;

static void
load(shown *s, const char *path, const char *layer, int absval)
{
	const float *p[3];
	char name[300];
	pm_image img;
	pm_error err;
	size_t n;

	if (pm_image_read_exr(&img, path, &err))
		die_err(&err);
	if (pm_layer_planes(&img, layer, p, &err))
		die("%s: %s", shown_name(path, name, sizeof name), err.msg);
	s->w = img.width;
	s->h = img.height;
	n = (size_t)s->w * s->h;
	for (int c = 0; c < 3; c++) {
		if (!(s->p[c] = malloc(n * sizeof *s->p[c])))
			die("out of memory");
		for (size_t i = 0; i < n; i++)
			s->p[c][i] = absval ? fabsf(p[c][i]) : p[c][i];
	}
	pm_image_free(&img);
}

int
main(int argc, char **argv)
{
	const char *layer = NULL, *outpath = NULL;
	/* Auto exposure and a curve that keeps highlights by default, so that
	 * a scene lit by 2 W or by 5000 W previews alike, and lamps and the
	 * ceiling around them keep their detail. */
	pm_tone tone = { .ev = 0, .curve = PM_CURVE_REINHARD, .white = 4 };
	shown *in;
	float *side[3];
	pm_error err;
	double logavg = 0;
	size_t used = 0;
	int opt, absval = 0, autoev = 1, quiet = 0, curve, n, w = 0, h = 0, x0 = 0;

	snprintf(about, sizeof about,
	         "Several inputs of the same height are shown side by side, %d pixels apart,\n"
	         "under one exposure. An input - is an EXR read from stdin.", GAP);
	snprintf(exposure_help, sizeof exposure_help,
	         "multiply by 2^EV before the curve, or auto: map the "
	         "log-average luminance to middle grey (%.2f) and print "
	         "the EV chosen on stderr, to give back as -e EV", PM_AUTO_KEY);
	opt_init(&tonemap, argc, argv);
	while ((opt = opt_next(&tonemap, argc, argv)) != -1) {
		switch (opt) {
		case 'a': absval = 1; break;
		case 'c':
			if ((curve = pm_curve_parse(optarg)) < 0)
				usage_err(usage, "--curve: unknown curve '%s' (clamp or reinhard)", optarg);
			tone.curve = curve;
			break;
		case 'e':
			autoev = strcmp(optarg, "auto") == 0;
			if (!autoev)
				tone.ev = parse_real(optarg, -100, 100, "--exposure", usage);
			break;
		case 'l': layer = optarg; break;
		case 'o': outpath = optarg; break;
		case 'q': quiet = 1; break;
		case 'w': tone.white = parse_real(optarg, 1e-6, 1e30, "--white", usage); break;
		}
	}
	if (layer && !*layer)
		usage_err(usage, "--layer: empty name");
	if (!outpath)
		usage_err(usage, "no output: give -o OUT.png");
	if ((n = argc - optind) < 1)
		usage_err(usage, "no input image");
	check_output(usage, outpath, OUT_PNG, argv + optind, n);
	if (!(in = calloc(n, sizeof *in)))
		die("out of memory");
	for (int i = 0; i < n; i++) {
		load(&in[i], argv[optind + i], layer, absval);
		if (i > 0 && in[i].h != h) {
			char a[300], b[300];
			die("%s: height %d differs from %s (%d)", shown_name(argv[optind + i], a, sizeof a),
			    in[i].h, shown_name(argv[optind], b, sizeof b), h);
		}
		h = in[i].h;
		w += in[i].w + (i > 0 ? GAP : 0);
	}
	for (int c = 0; c < 3; c++)
		if (!(side[c] = calloc((size_t)w * h, sizeof **side)))
			die("out of memory");
	for (int i = 0; i < n; i++) {
		for (int c = 0; c < 3; c++) {
			for (int y = 0; y < h; y++)
				memcpy(side[c] + (size_t)y * w + x0, in[i].p[c] + (size_t)y * in[i].w,
				       (size_t)in[i].w * sizeof **side);
			free(in[i].p[c]);
		}
		x0 += in[i].w + GAP;
	}
	free(in);
	/* The gaps are black and so left out, like any black pixel. */
	if (autoev)
		used = pm_auto_exposure((const float *const *)side, (size_t)w * h, &tone.ev, &logavg);
	if (pm_png_write(outpath, w, h, (const float *const *)side, &tone, &err))
		die_err(&err);
	/* Only once the PNG is written, so a failed run says one thing. */
	if (autoev && !quiet && used)
		warn("exposure %+.2f EV (auto: log-average luminance %.4g to %.2f)",
		     tone.ev, logavg, PM_AUTO_KEY);
	else if (autoev && !quiet)
		warn("exposure %+.2f EV (auto: the image is black)", tone.ev);
	for (int c = 0; c < 3; c++)
		free(side[c]);
	return 0;
}
