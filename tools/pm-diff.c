/* pm-diff — compares image A against reference B: RMSE, relMSE (as pbrt-v4's
 * imgtool), mean absolute and maximum error, means, over all pixels or those
 * a mask selects (lib/compare.h). Prints "key: value" lines. */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>

#include "compare.h"
#include "image.h"
#include "util.h"

static const char usage[] = "pm-diff [-h] [-l NAME] [-m MASK.exr [-c CHANNEL]] A.exr B.exr";

static void
help(void)
{
	printf("usage: %s\n"
	       "  -h, --help       print this help and exit\n"
	       "  -l, --layer NAME compare NAME.R, NAME.G, NAME.B (or the single channel\n"
	       "                   NAME) (default: the beauty R, G, B)\n"
	       "  -m, --mask M     count only pixels where M's mask channel > 0.5 (default: all)\n"
	       "  -c, --mask-channel C  the mask channel, e.g. edge (pm-render's edge layer);\n"
	       "                   !C selects pixels where C <= 0.5 instead (default: R)\n"
	       "Prints rmse, relmse, mae, max_abs, mean_a, mean_b, pixels; B is the reference.\n",
	       usage);
}

static void
load(pm_image *img, const char *path, const char *layer, const float *p[3])
{
	pm_error err;

	if (pm_image_read_exr(img, path, &err))
		die_err(&err);
	if (pm_layer_planes(img, layer, p, &err))
		die("'%s': %s", path, err.msg);
	for (int c = 0; c < img->nchan; c++) {
		const float *plane = img->px + (size_t)c * img->width * img->height;
		if ((plane == p[0] || plane == p[1] || plane == p[2]) &&
		    pm_plane_finite(plane, img->width, img->height, img->chan[c], &err))
			die("'%s': %s", path, err.msg);
	}
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
		{ "help", no_argument, NULL, 'h' },
		{ "layer", required_argument, NULL, 'l' },
		{ "mask", required_argument, NULL, 'm' },
		{ "mask-channel", required_argument, NULL, 'c' },
		{ NULL, 0, NULL, 0 },
	};
	const char *layer = NULL, *maskpath = NULL, *maskchan = "R";
	const float *pa[3], *pb[3], *mask = NULL;
	float *inv = NULL;
	pm_image a, b, m;
	pm_diff d;
	pm_error err;
	int opt;

	util_init(argc, argv);
	while ((opt = getopt_long(argc, argv, ":c:hl:m:", longopts, NULL)) != -1) {
		switch (opt) {
		case 'c': maskchan = optarg; break;
		case 'h': help(); return 0;
		case 'l': layer = optarg; break;
		case 'm': maskpath = optarg; break;
		default: bad_option(opt, argv);
		}
	}
	if (layer && !*layer)
		usage_err(usage, "--layer: empty name");
	if (argc - optind != 2)
		usage_err(usage, "want two images, got %d", argc - optind);
	load(&a, argv[optind], layer, pa);
	load(&b, argv[optind + 1], layer, pb);
	if (a.width != b.width || a.height != b.height)
		die("'%s': size %dx%d differs from '%s' (%dx%d)", argv[optind], a.width, a.height,
		    argv[optind + 1], b.width, b.height);
	if (maskpath) {
		if (pm_image_read_exr(&m, maskpath, &err))
			die_err(&err);
		if (m.width != a.width || m.height != a.height)
			die("'%s': size %dx%d differs from '%s' (%dx%d)", maskpath, m.width, m.height,
			    argv[optind], a.width, a.height);
		if (!(mask = pm_image_chan(&m, maskchan + (*maskchan == '!'))))
			die("'%s': no channel '%s'", maskpath, maskchan + (*maskchan == '!'));
		if (*maskchan == '!') {
			size_t n = (size_t)m.width * m.height;
			if (!(inv = malloc(n * sizeof *inv)))
				die("out of memory");
			for (size_t i = 0; i < n; i++)
				inv[i] = mask[i] > 0.5f ? 0.0f : 1.0f;
			mask = inv;
		}
	}
	if (pm_compare(pa, pb, mask, a.width, a.height, &d, &err))
		die("'%s': %s", maskpath ? maskpath : argv[optind], err.msg);
	printf("rmse: %.9g\nrelmse: %.9g\nmae: %.9g\nmax_abs: %.9g\nmean_a: %.9g\nmean_b: %.9g\n"
	       "pixels: %lld\n", d.rmse, d.relmse, d.mae, d.max_abs, d.mean_a, d.mean_b, d.pixels);
	if (fflush(stdout) != 0 || ferror(stdout))
		die("cannot write stdout");
	return 0;
}
