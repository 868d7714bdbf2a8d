/* compare.c — finiteness checks and image error metrics (see compare.h).
 * relMSE divides by b^2 + 0.01 as pbrt-v4's imgtool does, so that black
 * reference pixels do not dominate. */
#include "passes/compare.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>

int
pm_plane_finite(const float *p, int width, int height, const char *name, pm_error *err)
{
	size_t n = (size_t)width * height;

	for (size_t i = 0; i < n; i++)
		if (!isfinite(p[i]))
			return pm_seterr(err, "channel '%s' pixel (%zu, %zu) is %s", name,
			                 i % (size_t)width, i / (size_t)width,
			                 isnan(p[i]) ? "nan" : "inf");
	return 0;
}

int
pm_layer_planes(const pm_image *img, const char *layer, const float *out[3], pm_error *err)
{
	static const char *const suffix[3] = { "R", "G", "B" };
	char name[PM_CHAN_NAME + 8];

	for (int k = 0; k < 3; k++) {
		if (layer && *layer)
			snprintf(name, sizeof name, "%s.%s", layer, suffix[k]);
		else
			snprintf(name, sizeof name, "%s", suffix[k]);
		out[k] = pm_image_chan(img, name);
		if (!out[k] && layer && *layer && pm_image_chan(img, layer)) {
			out[0] = out[1] = out[2] = pm_image_chan(img, layer);
			return 0;
		}
		if (!out[k])
			return pm_seterr(err, "no channel '%s'", name);
	}
	return 0;
}

int
pm_compare(const float *const a[3], const float *const b[3], const float *mask,
           int width, int height, pm_diff *d, pm_error *err)
{
	size_t n = (size_t)width * height;
	double se = 0, rel = 0, ae = 0, maxd = 0, sa = 0, sb = 0;
	long long count = 0;

	for (size_t i = 0; i < n; i++) {
		if (mask && !(mask[i] > 0.5f))
			continue;
		count++;
		for (int c = 0; c < 3; c++) {
			double va = a[c][i], vb = b[c][i], e = va - vb;
			se += e * e;
			rel += e * e / (vb * vb + 0.01);
			ae += fabs(e);
			if (fabs(e) > maxd)
				maxd = fabs(e);
			sa += va;
			sb += vb;
		}
	}
	if (count == 0)
		return pm_seterr(err, "mask selects no pixels");
	n = (size_t)count * 3;
	d->rmse = sqrt(se / n);
	d->relmse = rel / n;
	d->mae = ae / n;
	d->max_abs = maxd;
	d->mean_a = sa / n;
	d->mean_b = sb / n;
	d->pixels = count;
	return 0;
}
