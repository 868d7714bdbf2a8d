/* pm-tonemap — an 8-bit sRGB PNG preview of an EXR's beauty image or one of
 * its layers, with an exposure in stops (lib/pngout.h). Several inputs of
 * one height are set side by side, for comparisons like the paper's
 * figure 3. */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "compare.h"
#include "image.h"
#include "pngout.h"
#include "util.h"

static const char usage[] = "pm-tonemap [-ah] [-e EV] [-l NAME] -o OUT.png IN.exr [IN.exr ...]";

#define GAP 4   /* black columns between images set side by side */

static void
help(void)
{
	printf("usage: %s\n"
	       "Several inputs of the same height are shown side by side, %d pixels apart.\n"
	       "  -a, --abs          show absolute values (for signed images like pm-diff -o)\n"
	       "  -e, --exposure EV  multiply by 2^EV before the sRGB curve (default: 0)\n"
	       "  -h, --help         print this help and exit\n"
	       "  -l, --layer NAME   show NAME.R, NAME.G, NAME.B (or the single channel NAME\n"
	       "                     as grey) (default: the beauty R, G, B)\n"
	       "  -o, --output F     the PNG to write; - for stdout (required)\n", usage, GAP);
}

int
main(int argc, char **argv)
{
	static const struct option longopts[] = {
		{ "abs", no_argument, NULL, 'a' },
		{ "exposure", required_argument, NULL, 'e' },
		{ "help", no_argument, NULL, 'h' },
		{ "layer", required_argument, NULL, 'l' },
		{ "output", required_argument, NULL, 'o' },
		{ NULL, 0, NULL, 0 },
	};
	const char *layer = NULL, *outpath = NULL;
	const float *p[3];
	float *side[3];
	double ev = 0;
	pm_image img;
	pm_error err;
	int opt, absval = 0, n, w = 0, h = 0, x0 = 0;

	util_init(argc, argv);
	while ((opt = getopt_long(argc, argv, ":ae:hl:o:", longopts, NULL)) != -1) {
		switch (opt) {
		case 'a': absval = 1; break;
		case 'e': ev = parse_real(optarg, -100, 100, "--exposure", usage); break;
		case 'h': help(); return 0;
		case 'l': layer = optarg; break;
		case 'o': outpath = optarg; break;
		default: bad_option(usage, opt, argv);
		}
	}
	if (layer && !*layer)
		usage_err(usage, "--layer: empty name");
	if (!outpath)
		usage_err(usage, "no output: give -o OUT.png");
	if ((n = argc - optind) < 1)
		usage_err(usage, "no input image");
	/* First pass: sizes, so the output can be allocated once. */
	for (int i = 0; i < n; i++) {
		if (pm_image_read_exr(&img, argv[optind + i], &err))
			die_err(&err);
		if (i > 0 && img.height != h)
			die("'%s': height %d differs from '%s' (%d)", argv[optind + i], img.height,
			    argv[optind], h);
		h = img.height;
		w += img.width + (i > 0 ? GAP : 0);
		pm_image_free(&img);
	}
	for (int c = 0; c < 3; c++)
		if (!(side[c] = calloc((size_t)w * h, sizeof **side)))
			die("out of memory");
	for (int i = 0; i < n; i++) {
		if (pm_image_read_exr(&img, argv[optind + i], &err))
			die_err(&err);
		if (pm_layer_planes(&img, layer, p, &err))
			die("'%s': %s", argv[optind + i], err.msg);
		for (int c = 0; c < 3; c++)
			for (int y = 0; y < h; y++)
				for (int x = 0; x < img.width; x++) {
					float v = p[c][(size_t)y * img.width + x];
					side[c][(size_t)y * w + x0 + x] = absval ? fabsf(v) : v;
				}
		x0 += img.width + GAP;
		pm_image_free(&img);
	}
	if (pm_png_write(outpath, w, h, (const float *const *)side, ev, &err))
		die_err(&err);
	for (int c = 0; c < 3; c++)
		free(side[c]);
	return 0;
}
