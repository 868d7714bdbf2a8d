/* pngout.c — sRGB PNG previews through libpng (see pngout.h).
 *
 * libpng reports errors by longjmp out of its error callback; ours records
 * the message instead of printing it, and the warning callback stays quiet,
 * since library code never prints. */
#include "formats/pngout.h"

#include <math.h>
#include <png.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/atomic.h"

unsigned char
pm_srgb8(double v)
{
	double s;

	if (!(v > 0))
		return 0;
	/* IEC 61966-2-1: linear segment below 0.0031308, else a 1/2.4 power. */
	s = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
	if (s >= 1)
		return 255;
	return (unsigned char)lround(s * 255);
}

static void
png_fail(png_structp png, png_const_charp msg)
{
	pm_error *err = png_get_error_ptr(png);

	pm_seterr(err, "%s", msg);
	png_longjmp(png, 1);
}

static void
png_quiet(png_structp png, png_const_charp msg)
{
	(void)png;
	(void)msg;
}

static int
write_png(const char *path, int width, int height, const float *const rgb[3],
          const pm_tone *tone, pm_error *err)
{
	png_structp png;
	png_infop info = NULL;
	unsigned char *row;
	pm_out out;

	if (width < 1 || height < 1 || width > (1 << 24) || height > (1 << 24))
		return pm_seterr(err, "cannot write '%s': bad size %dx%d", path, width, height);
	row = malloc((size_t)width * 3);
	if (!row)
		return pm_seterr(err, "cannot write '%s': out of memory", path);
	if (pm_out_open(&out, path, err)) {
		free(row);
		return -1;
	}
	png = png_create_write_struct(PNG_LIBPNG_VER_STRING, err, png_fail, png_quiet);
	if (png)
		info = png_create_info_struct(png);
	if (!png || !info) {
		png_destroy_write_struct(&png, NULL);
		pm_seterr(err, "cannot write '%s': out of memory", path);
		goto fail;
	}
	if (setjmp(png_jmpbuf(png))) {
		png_destroy_write_struct(&png, &info);
		pm_preferr(err, "cannot write '%s'", path);
		goto fail;
	}
	png_init_io(png, out.f);
	png_set_IHDR(png, info, width, height, 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
	             PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
	png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_PERCEPTUAL);
	png_write_info(png, info);
	for (int y = 0; y < height; y++) {
		for (int x = 0; x < width; x++)
			for (int k = 0; k < 3; k++)
				row[3 * x + k] = pm_srgb8(pm_tone_apply(tone, rgb[k][(size_t)y * width + x]));
		png_write_row(png, row);
	}
	png_write_end(png, info);
	png_destroy_write_struct(&png, &info);
	free(row);
	return pm_out_commit(&out, err);
fail:
	free(row);
	pm_out_abort(&out);
	return -1;
}

int
pm_png_write(const char *path, int width, int height, const float *const rgb[3],
             const pm_tone *tone, pm_error *err)
{
	static const pm_tone linear = { .ev = 0, .curve = PM_CURVE_CLAMP, .white = 1 };

	/* Resolved here, not after write_png's setjmp. */
	return write_png(path, width, height, rgb, tone ? tone : &linear, err);
}
