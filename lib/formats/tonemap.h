/* tonemap.h — from linear radiance to display values for previews:
 * an exposure in stops, then a tone curve, then sRGB (pngout.h).
 *
 * Curves, on each channel's exposed value x:
 *   clamp     x, cut at 1: everything at or above 1 is white.
 *   reinhard  x (1 + x / w^2) / (1 + x), 1 from x = w on: Reinhard et al.,
 *             "Photographic Tone Reproduction for Digital Images" (2002),
 *             eq. 4, per channel. Its slope at 0 is 1, so shadows look as
 *             under clamp; values up to the white point w keep detail. */
#ifndef PM_TONEMAP_H
#define PM_TONEMAP_H

#include <stddef.h>

typedef enum pm_curve { PM_CURVE_CLAMP, PM_CURVE_REINHARD } pm_curve;

typedef struct pm_tone {
	double ev;          /* exposure: values are multiplied by 2^ev */
	pm_curve curve;
	double white;       /* reinhard's white point, in exposed units (> 0) */
} pm_tone;

/* The key auto exposure maps the log-average luminance to (Reinhard 2002,
 * section 3.1: "middle grey"). */
#define PM_AUTO_KEY 0.18

/* "clamp" or "reinhard" to a curve; -1 for anything else. */
int pm_curve_parse(const char *name);
const char *pm_curve_name(pm_curve c);

/* The display value in [0, 1] (before sRGB encoding) of linear value v.
 * Non-decreasing in v; NaN and v <= 0 give 0. */
double pm_tone_apply(const pm_tone *t, double v);

/* Auto exposure: the EV that maps the log-average Rec. 709 luminance of
 * the n pixels rgb[k][i] to PM_AUTO_KEY, rounded to 1/100 stop (so that the
 * EV printed with two decimals and given back as an exposure is the same
 * number) and kept within [-100, 100]. Pixels whose luminance is not
 * positive and finite (black borders, NaN) are left out, which makes the
 * result independent of the image's scale. Sets *logavg to that average
 * and returns the number of pixels used; with none, *ev = 0 and
 * *logavg = 0. The sum runs in pixel order: the same image gives the same
 * EV. */
size_t pm_auto_exposure(const float *const rgb[3], size_t n, double *ev, double *logavg);

#endif
