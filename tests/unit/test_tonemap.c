/* test_tonemap.c — the tone curves against their formulas (tonemap.h),
 * their shape (monotone; reinhard below white until its white point), and
 * auto exposure on synthetic images. */
#include <math.h>
#include <stdlib.h>

#include "check.h"
#include "formats/pngout.h"
#include "formats/tonemap.h"

/* sRGB code of a display value in [0, 1], IEC 61966-2-1, written out here. */
static int
code(double d)
{
	double s = d <= 0.0031308 ? 12.92 * d : 1.055 * pow(d, 1 / 2.4) - 0.055;
	return (int)floor(s * 255 + 0.5);
}

TEST(curve_names)
{
	CHECK(pm_curve_parse("clamp") == PM_CURVE_CLAMP);
	CHECK(pm_curve_parse("reinhard") == PM_CURVE_REINHARD);
	CHECK(pm_curve_parse("filmic") == -1 && pm_curve_parse("") == -1);
	CHECK(pm_curve_parse(pm_curve_name(PM_CURVE_REINHARD)) == PM_CURVE_REINHARD);
}

TEST(known_values)
{
	pm_tone c = { .ev = 1, .curve = PM_CURVE_CLAMP, .white = 4 };
	pm_tone r = { .ev = 0, .curve = PM_CURVE_REINHARD, .white = 4 };

	/* clamp: 0.25 * 2^1 = 0.5 -> 188; 0.6 * 2 = 1.2 -> white. */
	CHECKF(pm_srgb8(pm_tone_apply(&c, 0.25)) == 188, "%d", pm_srgb8(pm_tone_apply(&c, 0.25)));
	CHECK(pm_tone_apply(&c, 0.6) == 1);
	/* reinhard, w = 4: 1 -> 1 (1 + 1/16) / 2 = 0.53125 -> 193;
	 * 2 -> 2 (1 + 2/16) / 3 = 0.75 -> 225. */
	CHECKF(fabs(pm_tone_apply(&r, 1) - 0.53125) < 1e-15, "%.17g", pm_tone_apply(&r, 1));
	CHECKF(pm_srgb8(pm_tone_apply(&r, 1)) == code(0.53125) && code(0.53125) == 193,
	       "%d %d", pm_srgb8(pm_tone_apply(&r, 1)), code(0.53125));
	CHECKF(fabs(pm_tone_apply(&r, 2) - 0.75) < 1e-15, "%.17g", pm_tone_apply(&r, 2));
	CHECK(pm_srgb8(pm_tone_apply(&r, 2)) == 225);
	r.ev = -1;
	CHECKF(fabs(pm_tone_apply(&r, 4) - 0.75) < 1e-15, "exposure before the curve: %.17g",
	       pm_tone_apply(&r, 4));
	CHECK(pm_tone_apply(&r, 0) == 0 && pm_tone_apply(&r, -3) == 0 && pm_tone_apply(&r, NAN) == 0);
	CHECK(pm_tone_apply(&r, INFINITY) == 1);
}

TEST(curves_monotone_reinhard_white_only_at_its_white_point)
{
	int bad = 0, below = 0;

	for (int curve = 0; curve < 2; curve++)
		for (double w = 0.5; w <= 16; w *= 2) {
			pm_tone t = { .ev = 0, .curve = curve, .white = w };
			double prev = 0;
			int prevc = 0;
			for (int i = 0; i <= 20000; i++) {
				double x = 2 * w * i / 20000, d = pm_tone_apply(&t, x);
				int cd = pm_srgb8(d);
				if (d < prev || cd < prevc || d > 1)
					bad++;
				if (curve == PM_CURVE_REINHARD && x < w && !(d < 1))
					below++;
				prev = d;
				prevc = cd;
			}
			if (curve == PM_CURVE_REINHARD && pm_tone_apply(&t, w) != 1)
				below++;
		}
	CHECKF(bad == 0, "%d steps down", bad);
	CHECKF(below == 0, "%d values white before the white point", below);
}

TEST(reinhard_keeps_highlights_clamp_does_not)
{
	pm_tone c = { .curve = PM_CURVE_CLAMP, .white = 4 };
	pm_tone r = { .curve = PM_CURVE_REINHARD, .white = 4 };
	int c1 = pm_srgb8(pm_tone_apply(&r, 1.5)), c2 = pm_srgb8(pm_tone_apply(&r, 2.5)),
	    c3 = pm_srgb8(pm_tone_apply(&r, 3.5));

	CHECK(pm_srgb8(pm_tone_apply(&c, 1.5)) == 255 && pm_srgb8(pm_tone_apply(&c, 3.5)) == 255);
	CHECKF(c1 < c2 && c2 < c3 && c3 < 255, "%d %d %d", c1, c2, c3);
}

static double
auto_ev(float v, int n, int nblack)
{
	float *px = malloc((size_t)(n + nblack) * sizeof *px);
	const float *rgb[3] = { px, px, px };
	double ev, la;
	size_t used;

	for (int i = 0; i < n + nblack; i++)
		px[i] = i < n ? v : (i % 2 ? 0 : NAN);
	used = pm_auto_exposure(rgb, (size_t)(n + nblack), &ev, &la);
	free(px);
	return used == (size_t)n ? ev : NAN;
}

TEST(auto_exposure_scale_free)
{
	pm_tone t = { .curve = PM_CURVE_REINHARD, .white = 4 };
	double lo = auto_ev(0.01f, 1000, 0), hi = auto_ev(1000, 1000, 0);
	int clo, chi;

	/* log2(0.18 / 0.01) = 4.17, log2(0.18 / 1000) = -12.44 */
	CHECKF(lo == 4.17 && hi == -12.44, "%.17g %.17g", lo, hi);
	t.ev = lo;
	clo = pm_srgb8(pm_tone_apply(&t, 0.01));
	t.ev = hi;
	chi = pm_srgb8(pm_tone_apply(&t, 1000));
	t.ev = 0;
	CHECKF(clo == chi && chi == pm_srgb8(pm_tone_apply(&t, PM_AUTO_KEY)), "%d %d", clo, chi);
	/* Black and NaN pixels are left out. */
	CHECKF(auto_ev(0.01f, 1000, 500) == lo, "%.17g", auto_ev(0.01f, 1000, 500));
}

TEST(auto_exposure_log_average)
{
	/* Half the pixels 0.02, half 2: log-average 0.2, EV log2(0.9) = -0.152
	 * -> -0.15; grey pixels, so luminance is the value. */
	float px[4] = { 0.02f, 2, 0.02f, 2 };
	const float *rgb[3] = { px, px, px };
	float black[3] = { 0, 0, 0 };
	const float *krgb[3] = { black, black, black };
	double ev, la;

	CHECK(pm_auto_exposure(rgb, 4, &ev, &la) == 4);
	CHECKF(fabs(la - 0.2) < 1e-6 && ev == -0.15, "%.17g %.17g", la, ev);
	CHECK(pm_auto_exposure(krgb, 3, &ev, &la) == 0 && ev == 0);
}

int
main(void)
{
	RUN(curve_names);
	RUN(known_values);
	RUN(curves_monotone_reinhard_white_only_at_its_white_point);
	RUN(reinhard_keeps_highlights_clamp_does_not);
	RUN(auto_exposure_scale_free);
	RUN(auto_exposure_log_average);
	return check_done();
}
