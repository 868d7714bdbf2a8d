/* imagefile.c — image files through the OpenImageIO module (oiio.h), made
 * linear RGB here. */
#include "scene/imagefile.h"

#include <math.h>
#include <stdlib.h>

#include "scene/oiio.h"

float
pm_srgb_to_linear(float v)
{
	/* IEC 61966-2-1. */
	return v <= 0.04045f ? v / 12.92f : powf((v + 0.055f) / 1.055f, 2.4f);
}

int
pm_rgbimage_read(const char *path, pm_rgbimage *im, pm_error *err)
{
	char msg[400];
	const pm_oiio_api *io = pm_oiio(msg, sizeof msg);
	int w, h, nc, srgb;
	float *buf, *px;

	im->w = im->h = 0;
	im->px = NULL;
	if (!io)
		return pm_seterr(err, "'%s': cannot read image: %s", path, msg);
	if (io->read(path, &w, &h, &nc, &srgb, &buf, msg, sizeof msg))
		return pm_seterr(err, "%s", msg);
	px = malloc((size_t)w * h * 3 * sizeof *px);
	if (!px) {
		free(buf);
		return pm_seterr(err, "'%s': out of memory", path);
	}
	/* One channel is grey, two grey and alpha; of more, the first three. */
	for (size_t i = 0; i < (size_t)w * h; i++)
		for (int c = 0; c < 3; c++) {
			float v = buf[i * nc + (nc >= 3 ? c : 0)];
			px[3 * i + c] = srgb ? pm_srgb_to_linear(v) : v;
		}
	free(buf);
	im->w = w;
	im->h = h;
	im->px = px;
	return 0;
}

void
pm_rgbimage_free(pm_rgbimage *im)
{
	free(im->px);
	im->px = NULL;
	im->w = im->h = 0;
}
