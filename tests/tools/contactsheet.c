/* contactsheet — a grid of EXR images in one PNG, for the torture report
 * (tests/torture/report.sh): rows of COLS images, 4 pixels apart. Each row
 * gets one exposure, chosen so that the mean of its reference column (-r)
 * reads 0.2 (linear), so dim and bright scenes both show; columns given
 * with -a are signed relative-error maps (pm-diff -o) shown as |value| x 8
 * (12.5% error is white; -g), as examples/room/compare.sh does.
 *
 * Usage: contactsheet -o OUT.png [-c COLS] [-r REFCOL] [-a ERRCOL]... [-g GAIN] [-f N] [-s SCALE]
 *                     FILE.exr...
 *   -c COLS    images per row (default 4)
 *   -r REFCOL  the column (1-based) whose mean sets the row's exposure
 *              (default 1); 0: each image its own, from its own mean
 *   -a ERRCOL  a column of error maps (repeatable)
 *   -g GAIN    the error columns' gain (default 8: 12.5% error is white)
 *   -f N       show the error columns box-filtered, N x N (odd; clipped at
 *              the border), before taking |value|: the local error, with
 *              less of the noise (default 1: per pixel)
 *   -s SCALE   enlarge every pixel to SCALE x SCALE (default 1)
 * The number of FILEs must be a multiple of COLS; all images of a row must
 * have the same size (rows may differ; the sheet is as wide as the widest). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "formats/image.h"
#include "formats/pngout.h"

#define GAP 4

static void
die(const char *msg)
{
	fprintf(stderr, "contactsheet: %s\n", msg);
	exit(1);
}

int
main(int argc, char **argv)
{
	const char *out = NULL;
	int cols = 4, refcol = 1, scale = 1, filt = 1, opt, errcol[64] = { 0 };
	double egain = 8;
	pm_error err;

	while ((opt = getopt(argc, argv, "o:c:r:a:f:g:s:")) != -1) {
		switch (opt) {
		case 'o': out = optarg; break;
		case 'c': cols = atoi(optarg); break;
		case 'r': refcol = atoi(optarg); break;
		case 'a': { int c = atoi(optarg); if (c >= 1 && c <= 64) errcol[c - 1] = 1; else die("bad -a"); } break;
		case 's': scale = atoi(optarg); break;
		case 'f': filt = atoi(optarg); break;
		case 'g': egain = atof(optarg); break;
		default:
			fprintf(stderr, "usage: contactsheet -o OUT.png [-c COLS] [-r REFCOL] [-a ERRCOL]... [-g GAIN] [-f N] [-s SCALE] FILE.exr...\n");
			return 2;
		}
	}
	int nf = argc - optind;
	if (!out || cols < 1 || cols > 64 || refcol < 0 || refcol > cols || scale < 1 || scale > 16 || filt < 1 || filt > 31 || filt % 2 == 0 || !(egain > 0) ||
	    nf < cols || nf % cols) {
		fprintf(stderr, "usage: contactsheet -o OUT.png [-c COLS] [-r REFCOL] [-a ERRCOL]... [-g GAIN] [-f N] [-s SCALE] FILE.exr...\n");
		return 2;
	}
	int rows = nf / cols;
	pm_image *img = calloc((size_t)nf, sizeof *img);
	int *rw = calloc((size_t)rows, sizeof *rw), *rh = calloc((size_t)rows, sizeof *rh);
	if (!img || !rw || !rh)
		die("out of memory");
	int W = 0, H = 0;
	for (int i = 0; i < nf; i++) {
		if (pm_image_read_exr(&img[i], argv[optind + i], &err)) {
			fprintf(stderr, "contactsheet: %s\n", err.msg);
			return 1;
		}
		if (!pm_image_chan(&img[i], "R") || !pm_image_chan(&img[i], "G") || !pm_image_chan(&img[i], "B")) {
			fprintf(stderr, "contactsheet: '%s': no R, G, B channels\n", argv[optind + i]);
			return 1;
		}
		int r = i / cols;
		if (i % cols == 0) {
			rw[r] = img[i].width;
			rh[r] = img[i].height;
		} else if (img[i].width != rw[r] || img[i].height != rh[r]) {
			fprintf(stderr, "contactsheet: '%s': size differs from its row's\n", argv[optind + i]);
			return 1;
		}
	}
	for (int r = 0; r < rows; r++) {
		int w = cols * rw[r] * scale + (cols - 1) * GAP;
		if (w > W) W = w;
		H += rh[r] * scale + (r ? GAP : 0);
	}
	float *plane[3];
	for (int k = 0; k < 3; k++)
		if (!(plane[k] = calloc((size_t)W * H, sizeof(float))))
			die("out of memory");
	int y0 = 0;
	for (int r = 0; r < rows; r++) {
		for (int c = 0; c < cols; c++) {
			const pm_image *im = &img[r * cols + c];
			/* the exposure from the row's reference image (or this one) */
			const pm_image *ref = &img[r * cols + (refcol ? refcol - 1 : c)];
			double sum = 0, gain;
			size_t np = (size_t)ref->width * ref->height;
			for (int k = 0; k < 3; k++) {
				const float *p = pm_image_chan(ref, k == 0 ? "R" : k == 1 ? "G" : "B");
				for (size_t j = 0; j < np; j++)
					if (isfinite(p[j])) sum += p[j];
			}
			gain = sum > 0 ? 0.2 / (sum / (3.0 * np)) : 1;
			int x0 = c * (rw[r] * scale + GAP);
			for (int k = 0; k < 3; k++) {
				const float *p = pm_image_chan(im, k == 0 ? "R" : k == 1 ? "G" : "B");
				for (int y = 0; y < im->height * scale; y++)
					for (int x = 0; x < im->width * scale; x++) {
						int px = x / scale, py = y / scale, h2 = filt / 2, n = 0;
						double v = 0;
						if (errcol[c] && filt > 1) {
							for (int yy = py - h2; yy <= py + h2; yy++)
								for (int xx = px - h2; xx <= px + h2; xx++)
									if (xx >= 0 && yy >= 0 && xx < im->width && yy < im->height) {
										v += p[(size_t)yy * im->width + xx];
										n++;
									}
							v /= n;
						} else
							v = p[(size_t)py * im->width + px];
						v = errcol[c] ? fabs(v) * egain : v * gain;
						plane[k][(size_t)(y0 + y) * W + x0 + x] = (float)v;
					}
			}
		}
		y0 += rh[r] * scale + GAP;
	}
	if (pm_png_write(out, W, H, (const float *const *)plane, &(pm_tone){ .curve = PM_CURVE_CLAMP }, &err)) {
		fprintf(stderr, "contactsheet: %s\n", err.msg);
		return 1;
	}
	for (int i = 0; i < nf; i++)
		pm_image_free(&img[i]);
	for (int k = 0; k < 3; k++)
		free(plane[k]);
	free(img);
	free(rw);
	free(rh);
	return 0;
}
