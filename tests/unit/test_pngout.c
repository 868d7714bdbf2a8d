/* test_pngout.c — the sRGB encoding of previews against the IEC 61966-2-1
 * formula evaluated here, and a PNG written then read back with libpng. */
#include <math.h>
#include <png.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "formats/pngout.h"

TEST(srgb8_known_values)
{
	CHECK(pm_srgb8(0) == 0 && pm_srgb8(-1) == 0 && pm_srgb8(NAN) == 0);
	CHECK(pm_srgb8(1) == 255 && pm_srgb8(1e30) == 255 && pm_srgb8(INFINITY) == 255);
	CHECKF(pm_srgb8(0.5) == 188, "%d", pm_srgb8(0.5));
	CHECKF(pm_srgb8(0.25) == 137, "%d", pm_srgb8(0.25));
	CHECKF(pm_srgb8(0.18) == 118, "%d", pm_srgb8(0.18));
	/* Linear segment: 12.92 * 0.002 * 255 = 6.59 -> 7. */
	CHECKF(pm_srgb8(0.002) == 7, "%d", pm_srgb8(0.002));
}

TEST(srgb8_monotone_and_matches_formula)
{
	int bad = 0, prev = 0;

	for (int i = 0; i <= 10000; i++) {
		double v = i / 10000.0;
		double s = v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1 / 2.4) - 0.055;
		int want = (int)floor(s * 255 + 0.5), got = pm_srgb8(v);
		if (got != want || got < prev)
			bad++;
		prev = got;
	}
	CHECKF(bad == 0, "%d mismatches", bad);
}

TEST(png_round_trip)
{
	enum { W = 5, H = 3 };
	float r[W * H], g[W * H], b[W * H];
	const float *rgb[3] = { r, g, b };
	unsigned char buf[W * H * 3];
	png_image im;
	pm_error err = { "" };
	int bad = 0;

	for (int i = 0; i < W * H; i++)
		r[i] = i / 14.0f, g[i] = 0.5f, b[i] = (i % W == 0) ? 2.0f : 0.0f;
	CHECKF(pm_png_write("t.png", W, H, rgb, &(pm_tone){ .ev = -1 }, &err) == 0, "%s", err.msg);
	memset(&im, 0, sizeof im);
	im.version = PNG_IMAGE_VERSION;
	CHECK(png_image_begin_read_from_file(&im, "t.png"));
	CHECK(im.width == W && im.height == H);
	im.format = PNG_FORMAT_RGB;
	CHECK(png_image_finish_read(&im, NULL, buf, 0, NULL));
	for (int i = 0; i < W * H; i++)
		if (buf[3 * i] != pm_srgb8(r[i] / 2) || buf[3 * i + 1] != 137 ||
		    buf[3 * i + 2] != (i % W == 0 ? 255 : 0))
			bad++;
	CHECKF(bad == 0, "%d wrong pixels", bad);
	/* No tone: EV 0 and clamp, so 0.5 -> 188 and 2 -> 255. */
	CHECKF(pm_png_write("t.png", W, H, rgb, NULL, &err) == 0, "%s", err.msg);
	memset(&im, 0, sizeof im);
	im.version = PNG_IMAGE_VERSION;
	im.format = PNG_FORMAT_RGB;
	CHECK(png_image_begin_read_from_file(&im, "t.png"));
	im.format = PNG_FORMAT_RGB;
	CHECK(png_image_finish_read(&im, NULL, buf, 0, NULL));
	CHECKF(buf[1] == 188 && buf[2] == 255, "%d %d", buf[1], buf[2]);
	CHECK(pm_png_write("no/such/dir/t.png", W, H, rgb, &(pm_tone){ 0 }, &err) == -1 &&
	      strstr(err.msg, "'no/such/dir/t.png'"));
}

int
main(void)
{
	RUN(srgb8_known_values);
	RUN(srgb8_monotone_and_matches_formula);
	RUN(png_round_trip);
	return check_done();
}
