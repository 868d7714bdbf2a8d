/* pm-tonemap — an 8-bit sRGB PNG preview of an EXR's beauty image or one of
 * its layers, with an exposure in stops (lib/pngout.h). */
#include <getopt.h>
#include <stdio.h>

#include "compare.h"
#include "image.h"
#include "pngout.h"
#include "util.h"

static const char usage[] = "pm-tonemap [-h] [-e EV] [-l NAME] -o OUT.png IN.exr";

static void
help(void)
{
	printf("usage: %s\n"
	       "  -e, --exposure EV  multiply by 2^EV before the sRGB curve (default: 0)\n"
	       "  -h, --help         print this help and exit\n"
	       "  -l, --layer NAME   show NAME.R, NAME.G, NAME.B (or the single channel NAME\n"
	       "                     as grey) (default: the beauty R, G, B)\n"
	       "  -o, --output F     the PNG to write; - for stdout (required)\n", usage);
}

/* getopt's own messages would add a second line; say it once, our way. */
static void
bad_option(int opt, char **argv)
{
	if (opt == ':')
		usage_err(usage, "option '%s' needs an argument", argv[optind - 1]);
	if (optopt)
		usage_err(usage, "unknown option '-%c'", optopt);
	usage_err(usage, "unknown option '%s'", argv[optind - 1]);
}

int
main(int argc, char **argv)
{
	static const struct option longopts[] = {
		{ "exposure", required_argument, NULL, 'e' },
		{ "help", no_argument, NULL, 'h' },
		{ "layer", required_argument, NULL, 'l' },
		{ "output", required_argument, NULL, 'o' },
		{ NULL, 0, NULL, 0 },
	};
	const char *layer = NULL, *outpath = NULL;
	const float *p[3];
	double ev = 0;
	pm_image img;
	pm_error err;
	int opt;

	util_init(argc, argv);
	while ((opt = getopt_long(argc, argv, ":e:hl:o:", longopts, NULL)) != -1) {
		switch (opt) {
		case 'e': ev = parse_real(optarg, -100, 100, "--exposure", usage); break;
		case 'h': help(); return 0;
		case 'l': layer = optarg; break;
		case 'o': outpath = optarg; break;
		default: bad_option(opt, argv);
		}
	}
	if (layer && !*layer)
		usage_err(usage, "--layer: empty name");
	if (!outpath)
		usage_err(usage, "no output: give -o OUT.png");
	if (argc - optind != 1)
		usage_err(usage, "want one input image, got %d", argc - optind);
	if (pm_image_read_exr(&img, argv[optind], &err))
		die_err(&err);
	if (pm_layer_planes(&img, layer, p, &err))
		die("'%s': %s", argv[optind], err.msg);
	if (pm_png_write(outpath, img.width, img.height, p, ev, &err))
		die_err(&err);
	pm_image_free(&img);
	return 0;
}
