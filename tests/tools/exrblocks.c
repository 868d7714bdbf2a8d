/* exrblocks — compares an image A with a reference B block by block, for
 * make check-scenes: the larger of the two is box-downsampled by an integer
 * factor to the other's size, both are cut into a G x G grid of blocks
 * (default 16), and the relative differences of the block means (of the
 * three channels' mean) are summarized. Prints "key: value" lines:
 * mean_a, mean_b, mean_ratio (A / B), block_rel_rms, block_rel_p90,
 * block_rel_max, the worst block's grid position, and blocks_skipped:
 * blocks holding a pixel that is not finite in either image (a reference's
 * light source may be stored as infinity) count in neither image's mean.
 * --map prints the G x G signed block differences in percent.
 * Usage: exrblocks [--grid G] [--map] A.exr B.exr */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "formats/image.h"

/* The image's channel mean, box-averaged by f in both axes. */
static double *
grey(const char *path, int *w, int *h, int f)
{
	pm_image img;
	pm_error err;
	const float *c[3];

	if (pm_image_read_exr(&img, path, &err)) {
		fprintf(stderr, "exrblocks: %s\n", err.msg);
		exit(1);
	}
	for (int k = 0; k < 3; k++)
		if (!(c[k] = pm_image_chan(&img, (const char[][2]){ "R", "G", "B" }[k]))) {
			fprintf(stderr, "exrblocks: '%s': no RGB\n", path);
			exit(1);
		}
	*w = img.width / f;
	*h = img.height / f;
	double *g = calloc((size_t)*w * *h, sizeof *g);
	if (!g)
		exit(1);
	for (int y = 0; y < *h * f; y++)
		for (int x = 0; x < *w * f; x++) {
			size_t i = (size_t)y * img.width + x;
			g[(size_t)(y / f) * *w + x / f] += (c[0][i] + c[1][i] + c[2][i]) / (3.0 * f * f);
		}
	pm_image_free(&img);
	return g;
}

static int
cmp(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

static void
size_of(const char *path, int *w, int *h)
{
	pm_image img;
	pm_error err;

	if (pm_image_read_exr(&img, path, &err)) {
		fprintf(stderr, "exrblocks: %s\n", err.msg);
		exit(1);
	}
	*w = img.width;
	*h = img.height;
	pm_image_free(&img);
}

int
main(int argc, char **argv)
{
	int G = 16, i = 1, map = 0;

	for (;;) {
		if (argc > i + 1 && !strcmp(argv[i], "--grid")) {
			G = atoi(argv[i + 1]);
			i += 2;
		} else if (argc > i && !strcmp(argv[i], "--map")) {
			map = 1;
			i++;
		} else
			break;
	}
	if (argc - i != 2 || G < 1) {
		fprintf(stderr, "usage: exrblocks [--grid G] A.exr B.exr\n");
		return 2;
	}
	int wa, ha, wb, hb, fa = 1, fb = 1;
	size_of(argv[i], &wa, &ha);
	size_of(argv[i + 1], &wb, &hb);
	if (wb >= wa && wb % wa == 0 && hb % ha == 0 && wb / wa == hb / ha)
		fb = wb / wa;
	else if (wa % wb == 0 && ha % hb == 0 && wa / wb == ha / hb)
		fa = wa / wb;
	else {
		fprintf(stderr, "exrblocks: sizes %dx%d and %dx%d differ by no integer factor\n", wa, ha, wb, hb);
		return 1;
	}
	double *a = grey(argv[i], &wa, &ha, fa), *b = grey(argv[i + 1], &wb, &hb, fb);
	int w = wa, h = ha;
	if (w < G || h < G || G > 64) {
		fprintf(stderr, "exrblocks: image %dx%d smaller than the grid\n", w, h);
		return 1;
	}
	double sa = 0, sb = 0, BA[4096], BB[4096];
	int ok[4096], skipped = 0;
	long npix = 0;
	for (int by = 0; by < G; by++)
		for (int bx = 0; bx < G; bx++) {
			double ba = 0, bb = 0;
			for (int y = by * h / G; y < (by + 1) * h / G; y++)
				for (int x = bx * w / G; x < (bx + 1) * w / G; x++) {
					ba += a[(size_t)y * w + x];
					bb += b[(size_t)y * w + x];
				}
			int k = by * G + bx;
			BA[k] = ba;
			BB[k] = bb;
			ok[k] = isfinite(ba) && isfinite(bb);
			if (ok[k]) {
				sa += ba;
				sb += bb;
				npix += (long)((by + 1) * h / G - by * h / G) * ((bx + 1) * w / G - bx * w / G);
			} else
				skipped++;
		}
	double rel[4096], rms = 0, mx = 0;
	int worst = 0, n = 0;
	for (int by = 0; by < G; by++)
		for (int bx = 0; bx < G; bx++) {
			int k = by * G + bx;
			double ba = BA[k], bb = BB[k];
			if (!ok[k]) {
				if (map)
					printf("  skip");
				if (map && bx == G - 1)
					printf("\n");
				continue;
			}
			/* Relative to the block's reference, floored at a tenth of
			 * the image mean so black corners do not divide by 0. */
			double floor_ = 0.1 * sb / npix * ((h / G) * (w / G));
			double r = fabs(ba - bb) / fmax(bb, floor_);
			if (map)
				printf("%6.1f%s", 100 * (ba - bb) / fmax(bb, floor_), bx == G - 1 ? "\n" : "");
			rel[n++] = r;
			rms += r * r;
			if (r > mx) {
				mx = r;
				worst = k;
			}
		}
	qsort(rel, n, sizeof *rel, cmp);
	printf("mean_a: %.6g\nmean_b: %.6g\nmean_ratio: %.6g\nblock_rel_rms: %.6g\nblock_rel_p90: %.6g\n"
	       "block_rel_max: %.6g\nworst_block: %d,%d\nblocks_skipped: %d\nsize: %dx%d\n", sa / npix, sb / npix,
	       sa / sb, n ? sqrt(rms / n) : 0, n ? rel[(int)(0.9 * (n - 1))] : 0, mx, worst % G, worst / G, skipped, w, h);
	free(a);
	free(b);
	return 0;
}
