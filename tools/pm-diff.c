/* pm-diff — compares image A against reference B: RMSE, relMSE (as pbrt-v4's
 * imgtool), mean absolute and maximum error, means, over all pixels or those
 * a mask selects (lib/passes/compare.h). Prints "key: value" lines. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "passes/compare.h"
#include "formats/image.h"
#include "options.h"
#include "util.h"

static const char usage[] = "pm-diff [-h] [-l NAME] [-m MASK.exr [-c CHANNEL]] [-o ERR.exr] A.exr B.exr";

static const opt opts[] = {
	{ 'l', "layer", "NAME", "compare NAME.R, NAME.G, NAME.B (or the single channel "
	  "NAME)", "the beauty R, G, B", 0 },
	{ 'm', "mask", "M", "count only pixels where M's mask channel > 0.5", "all", 0 },
	{ 'c', "mask-channel", "C", "the mask channel, e.g. edge (pm-render's edge layer); "
	  "!C selects pixels where C <= 0.5 instead", "R", 0 },
	{ 'o', "output", "ERR.exr", "also write the relative error map (A - B) / B per "
	  "channel (A - B where B = 0) as R, G, B", "none", 0 },
	{ 0, NULL, NULL, NULL, NULL, 0 },
};

static const tool diff = {
	usage,
	"Compares image A against the reference B.",
	opts,
	"Prints rmse, relmse, mae, max_abs, mean_a, mean_b, pixels; B is the reference.\n"
	"One of A, B and M may be -, an EXR read from stdin.\n",
};

static void
load(pm_image *img, const char *path, const char *layer, const float *p[3])
{
	pm_error err;
	char nm[300];

	shown_name(path, nm, sizeof nm);
	if (pm_image_read_exr(img, path, &err))
		die_err(&err);
	if (pm_layer_planes(img, layer, p, &err))
		die("%s: %s", nm, err.msg);
	for (int c = 0; c < img->nchan; c++) {
		const float *plane = img->px + (size_t)c * img->width * img->height;
		if ((plane == p[0] || plane == p[1] || plane == p[2]) &&
		    pm_plane_finite(plane, img->width, img->height, img->chan[c], &err))
			die("%s: %s", nm, err.msg);
	}
}

/* The signed relative error per pixel and channel, for looking at where an
 * estimate is off (edges, corners) rather than by how much overall. */
static void
write_errmap(const char *path, const float *const pa[3], const float *const pb[3], int w, int h)
{
	static const char *const names[3] = {"R", "G", "B"};
	size_t n = (size_t)w * h;
	pm_image e;
	pm_error err;

	if (pm_image_init(&e, w, h, 3, names, &err))
		die_err(&err);
	for (int c = 0; c < 3; c++) {
		float *d = pm_image_chan(&e, names[c]);
		for (size_t i = 0; i < n; i++)
			d[i] = pb[c][i] != 0 ? (pa[c][i] - pb[c][i]) / pb[c][i] : pa[c][i] - pb[c][i];
	}
	if (pm_image_set_attr(&e, "pm.command", cmdline(), &err) || pm_image_write_exr(&e, path, &err))
		die_err(&err);
	pm_image_free(&e);
}

int
main(int argc, char **argv)
{
	const char *layer = NULL, *maskpath = NULL, *maskchan = "R", *errpath = NULL;
	const float *pa[3], *pb[3], *mask = NULL;
	float *inv = NULL;
	pm_image a, b, m;
	pm_diff d;
	pm_error err;
	char na[300], nb[300];
	int opt;

	opt_init(&diff, argc, argv);
	while ((opt = opt_next(&diff, argc, argv)) != -1) {
		switch (opt) {
		case 'c': maskchan = optarg; break;
		case 'l': layer = optarg; break;
		case 'm': maskpath = optarg; break;
		case 'o': errpath = optarg; break;
		}
	}
	if (layer && !*layer)
		usage_err(usage, "--layer: empty name");
	if (argc - optind != 2)
		usage_err(usage, "want two images, got %d", argc - optind);
	if (errpath && strcmp(errpath, "-") == 0)
		usage_err(usage, "-o -: the statistics go to stdout; give the error map a file name");
	{
		char *in[3] = { argv[optind], argv[optind + 1], (char *)maskpath };
		if (errpath)
			check_output(usage, errpath, OUT_EXR, in, maskpath ? 3 : 2);
		else
			check_stdin_once(usage, in, maskpath ? 3 : 2);
	}
	load(&a, argv[optind], layer, pa);
	load(&b, argv[optind + 1], layer, pb);
	if (a.width != b.width || a.height != b.height)
		die("%s: size %dx%d differs from %s (%dx%d)", shown_name(argv[optind], na, sizeof na),
		    a.width, a.height, shown_name(argv[optind + 1], nb, sizeof nb), b.width, b.height);
	if (maskpath) {
		if (pm_image_read_exr(&m, maskpath, &err))
			die_err(&err);
		if (m.width != a.width || m.height != a.height)
			die("%s: size %dx%d differs from %s (%dx%d)", shown_name(maskpath, nb, sizeof nb),
			    m.width, m.height, shown_name(argv[optind], na, sizeof na), a.width, a.height);
		if (!(mask = pm_image_chan(&m, maskchan + (*maskchan == '!'))))
			die("%s: no channel '%s'", shown_name(maskpath, nb, sizeof nb), maskchan + (*maskchan == '!'));
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
		die("%s: %s", shown_name(maskpath ? maskpath : argv[optind], na, sizeof na), err.msg);
	if (errpath)
		write_errmap(errpath, pa, pb, a.width, a.height);
	printf("rmse: %.9g\nrelmse: %.9g\nmae: %.9g\nmax_abs: %.9g\nmean_a: %.9g\nmean_b: %.9g\n"
	       "pixels: %lld\n", d.rmse, d.relmse, d.mae, d.max_abs, d.mean_a, d.mean_b, d.pixels);
	if (fflush(stdout) != 0 || ferror(stdout))
		die("cannot write stdout");
	pm_image_free(&a);
	pm_image_free(&b);
	if (maskpath)
		pm_image_free(&m);
	free(inv);
	return 0;
}
