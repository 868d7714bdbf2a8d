/* exrstat — statistics of an EXR's RGB (or one layer) over the image or a
 * window, for tests: "mean: ", "min: ", "max: ", "pixels: " lines, where a
 * pixel's value is the mean of its three channels.
 * With --dump, one "X Y VALUE" line per pixel of the window instead.
 * Usage: exrstat [--window X0,Y0,X1,Y1] [--layer NAME] [--pixel X,Y] [--dump] FILE.exr */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "formats/image.h"

int
main(int argc, char **argv)
{
	int x0 = 0, y0 = 0, x1 = -1, y1 = -1, px = -1, py = -1, dump = 0;
	const char *layer = NULL, *file = NULL;
	char names[3][64];
	const float *ch[3];
	pm_image img;
	pm_error err;
	double sum = 0, mn = INFINITY, mx = -INFINITY;
	long n = 0;

	for (int i = 1; i < argc; i++) {
		if (!strcmp(argv[i], "--window") && i + 1 < argc)
			sscanf(argv[++i], "%d,%d,%d,%d", &x0, &y0, &x1, &y1);
		else if (!strcmp(argv[i], "--layer") && i + 1 < argc)
			layer = argv[++i];
		else if (!strcmp(argv[i], "--dump"))
			dump = 1;
		else if (!strcmp(argv[i], "--pixel") && i + 1 < argc)
			sscanf(argv[++i], "%d,%d", &px, &py);
		else
			file = argv[i];
	}
	if (!file || pm_image_read_exr(&img, file, &err) != 0) {
		fprintf(stderr, "exrstat: %s\n", file ? err.msg : "no file");
		return 1;
	}
	for (int c = 0; c < 3; c++) {
		/* pm-render's one-channel layers. */
		if (layer && (!strcmp(layer, "size") || !strcmp(layer, "count") || !strcmp(layer, "edge")))
			snprintf(names[c], sizeof names[c], "%s", layer);
		else
			snprintf(names[c], sizeof names[c], "%s%s%c", layer ? layer : "", layer ? "." : "", "RGB"[c]);
		if (!(ch[c] = pm_image_chan(&img, names[c]))) {
			fprintf(stderr, "exrstat: no channel %s\n", names[c]);
			return 1;
		}
	}
	if (x1 < 0) x1 = img.width;
	if (y1 < 0) y1 = img.height;
	if (px >= 0) { x0 = px; y0 = py; x1 = px + 1; y1 = py + 1; }
	for (int y = y0; y < y1 && y < img.height; y++)
		for (int x = x0; x < x1 && x < img.width; x++) {
			size_t i = (size_t)y * img.width + x;
			double v = (ch[0][i] + ch[1][i] + ch[2][i]) / 3.0;
			if (dump)
				printf("%d %d %.9g\n", x, y, v);
			sum += v;
			mn = fmin(mn, v);
			mx = fmax(mx, v);
			n++;
		}
	if (!dump)
		printf("mean: %.9g\nmin: %.9g\nmax: %.9g\npixels: %ld\n", n ? sum / n : 0, mn, mx, n);
	pm_image_free(&img);
	return 0;
}
