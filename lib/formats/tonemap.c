/* tonemap.c — exposure, tone curves and auto exposure (see tonemap.h). */
#include "formats/tonemap.h"

#include <math.h>
#include <string.h>

static const char *const names[] = { "clamp", "reinhard" };

int
pm_curve_parse(const char *name)
{
	for (int c = 0; c < (int)(sizeof names / sizeof names[0]); c++)
		if (strcmp(name, names[c]) == 0)
			return c;
	return -1;
}

const char *
pm_curve_name(pm_curve c)
{
	return names[c];
}

double
pm_tone_apply(const pm_tone *t, double v)
{
	double x = v * exp2(t->ev), w = t->white;

	if (!(x > 0))
		return 0;
	if (t->curve == PM_CURVE_REINHARD) {
		/* At and past w the formula reaches or passes 1; it is also
		 * where rounding could otherwise let x / w^2 overflow. */
		if (x >= w)
			return 1;
		return x * (1 + x / (w * w)) / (1 + x);
	}
	return x < 1 ? x : 1;
}

size_t
pm_auto_exposure(const float *const rgb[3], size_t n, double *ev, double *logavg)
{
	double sum = 0, e;
	size_t used = 0;

	for (size_t i = 0; i < n; i++) {
		double y = 0.2126 * rgb[0][i] + 0.7152 * rgb[1][i] + 0.0722 * rgb[2][i];
		if (y > 0 && isfinite(y)) {
			sum += log(y);
			used++;
		}
	}
	if (!used) {
		*ev = *logavg = 0;
		return 0;
	}
	*logavg = exp(sum / (double)used);
	e = round(log2(PM_AUTO_KEY / *logavg) * 100) / 100;
	*ev = e < -100 ? -100 : e > 100 ? 100 : e;
	return used;
}
