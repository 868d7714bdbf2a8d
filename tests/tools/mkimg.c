/* mkimg — writes a small EXR for tests, so image tools can be tested
 * without a renderer.
 *
 * Usage: mkimg [-a KEY=VALUE]... [-c NAME=VALUE]... [-n X,Y] [-p ramp]
 *              [-v R,G,B] OUT.exr WIDTH HEIGHT
 *   -v R,G,B     beauty R, G, B constants (default 0.5,0.5,0.5)
 *   -p ramp      pattern instead: R = x, G = y, B = x + y*WIDTH (pixel index)
 *   -c NAME=V    an extra channel holding the constant V (repeatable)
 *   -a KEY=V     a string attribute (repeatable)
 *   -n X,Y       make G at pixel (X, Y) NaN */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "formats/image.h"

static void
fail(const char *msg)
{
	fprintf(stderr, "mkimg: %s\n", msg);
	exit(1);
}

int
main(int argc, char **argv)
{
	const char *attr[64], *chan[64], *pat = NULL;
	int nattr = 0, nchan = 0, nx = -1, ny = -1, opt, w, h;
	double v[3] = { 0.5, 0.5, 0.5 };
	const char *rgb[] = { "R", "G", "B" };
	pm_image img;
	pm_error err;

	while ((opt = getopt(argc, argv, "a:c:n:p:v:")) != -1) {
		switch (opt) {
		case 'a': if (nattr < 64) attr[nattr++] = optarg; break;
		case 'c': if (nchan < 64) chan[nchan++] = optarg; break;
		case 'n': if (sscanf(optarg, "%d,%d", &nx, &ny) != 2) fail("bad -n"); break;
		case 'p': pat = optarg; break;
		case 'v': if (sscanf(optarg, "%lf,%lf,%lf", &v[0], &v[1], &v[2]) != 3) fail("bad -v"); break;
		default: fail("bad option");
		}
	}
	if (argc - optind != 3)
		fail("usage: mkimg [-a KEY=V] [-c NAME=V] [-n X,Y] [-p ramp] [-v R,G,B] OUT.exr W H");
	w = atoi(argv[optind + 1]);
	h = atoi(argv[optind + 2]);
	if (pm_image_init(&img, w, h, 3, rgb, &err))
		fail(err.msg);
	for (int y = 0; y < h; y++)
		for (int x = 0; x < w; x++)
			for (int k = 0; k < 3; k++) {
				float *p = img.px + ((size_t)k * h + y) * w + x;
				if (pat && strcmp(pat, "ramp") == 0)
					*p = k == 0 ? x : k == 1 ? y : x + (float)y * w;
				else
					*p = (float)v[k];
			}
	if (nx >= 0 && nx < w && ny >= 0 && ny < h)
		pm_image_chan(&img, "G")[(size_t)ny * w + nx] = NAN;
	for (int i = 0; i < nchan; i++) {
		char name[64];
		const char *eq = strchr(chan[i], '=');
		float *p;
		if (!eq || eq - chan[i] >= (int)sizeof name)
			fail("bad -c");
		snprintf(name, sizeof name, "%.*s", (int)(eq - chan[i]), chan[i]);
		if (!(p = pm_image_add_chan(&img, name, &err)))
			fail(err.msg);
		for (size_t j = 0; j < (size_t)w * h; j++)
			p[j] = (float)atof(eq + 1);
	}
	for (int i = 0; i < nattr; i++) {
		char key[256];
		const char *eq = strchr(attr[i], '=');
		if (!eq || eq - attr[i] >= (int)sizeof key)
			fail("bad -a");
		snprintf(key, sizeof key, "%.*s", (int)(eq - attr[i]), attr[i]);
		if (pm_image_set_attr(&img, key, eq + 1, &err))
			fail(err.msg);
	}
	if (pm_image_write_exr(&img, argv[optind], &err))
		fail(err.msg);
	pm_image_free(&img);
	return 0;
}
