/* average.c — pass-weighted running averages with per-pixel variance (see
 * average.h; the merge is Chan, Golub & LeVeque 1979). Sums are kept in
 * double so that a thousand merges lose nothing visible in float output. */
#include "passes/average.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "passes/compare.h"

static const char *const rgb[3] = { "R", "G", "B" };
static const char *const m2name[3] = { "m2.R", "m2.G", "m2.B" };
static const char *const sename[3] = { "stderr.R", "stderr.G", "stderr.B" };

void
pm_moments_merge(double na, double *mean, double *m2,
                 double nb, const float *mb, const float *m2b, size_t len)
{
	double n = na + nb;

	if (n <= 0)
		return;
	for (size_t i = 0; i < len; i++) {
		double d = (double)mb[i] - mean[i];
		mean[i] += d * nb / n;
		if (m2)
			m2[i] += (m2b ? (double)m2b[i] : 0.0) + d * d * na * nb / n;
	}
}

double
pm_moments_stderr(double n, double m2)
{
	return n < 2 ? 0.0 : sqrt(m2 / (n - 1) / n);
}

int
pm_image_passes(const pm_image *img, double *passes, pm_error *err)
{
	const char *s = pm_image_attr(img, "pm.passes");
	unsigned long long v;
	char *end;

	*passes = 1;
	if (!s)
		return 0;
	errno = 0;
	v = strtoull(s, &end, 10);
	if (*s < '0' || *s > '9' || *end || errno || v < 1 || v > (1ULL << 53))
		return pm_seterr(err, "pm.passes '%.40s' is not a whole number in [1, 2^53]", s);
	*passes = (double)v;
	return 0;
}

void
pm_avg_init(pm_avg *a)
{
	memset(a, 0, sizeof *a);
}

void
pm_avg_free(pm_avg *a)
{
	free(a->chan);
	free(a->mean);
	free(a->m2);
	memset(a, 0, sizeof *a);
}

static int
averaged(const char *name)
{
	return strncmp(name, "m2.", 3) != 0 && strncmp(name, "stderr.", 7) != 0;
}

static int
first_image(pm_avg *a, const pm_image *img, pm_error *err)
{
	size_t plane = (size_t)img->width * img->height;
	int n = 0;

	for (int c = 0; c < img->nchan; c++)
		n += averaged(img->chan[c]);
	a->chan = malloc(n * sizeof *a->chan);
	a->mean = calloc((size_t)n * plane, sizeof *a->mean);
	a->m2 = calloc(3 * plane, sizeof *a->m2);
	if (!a->chan || !a->mean || !a->m2) {
		pm_avg_free(a);
		return pm_seterr(err, "out of memory averaging %dx%d images", img->width, img->height);
	}
	for (int c = 0; c < img->nchan; c++)
		if (averaged(img->chan[c]))
			memcpy(a->chan[a->nchan++], img->chan[c], PM_CHAN_NAME);
	a->width = img->width;
	a->height = img->height;
	return 0;
}

int
pm_avg_add(pm_avg *a, const pm_image *img, double passes, pm_error *err)
{
	size_t plane = (size_t)img->width * img->height;
	const float *m2in[3];
	int have_m2 = 1, keep = 0;

	if (a->chan && (img->width != a->width || img->height != a->height))
		return pm_seterr(err, "size %dx%d differs from %dx%d",
		                 img->width, img->height, a->width, a->height);
	if (!(passes >= 1))
		return pm_seterr(err, "pass count %g is below 1", passes);
	for (int k = 0; k < 3; k++) {
		if (!pm_image_chan(img, rgb[k]))
			return pm_seterr(err, "no channel '%s'", rgb[k]);
		m2in[k] = pm_image_chan(img, m2name[k]);
		if (!m2in[k])
			have_m2 = 0;
	}
	for (int c = 0; c < img->nchan; c++) {
		const float *p = img->px + (size_t)c * plane;
		int used = averaged(img->chan[c]) || (have_m2 && strncmp(img->chan[c], "m2.", 3) == 0);
		if (used && pm_plane_finite(p, img->width, img->height, img->chan[c], err))
			return -1;
	}
	for (int k = 0; k < 3 && have_m2; k++)
		for (size_t i = 0; i < plane; i++)
			if (m2in[k][i] < 0)
				return pm_seterr(err, "channel '%s' pixel (%zu, %zu) is negative",
				                 m2name[k], i % img->width, i / img->width);
	if (!a->chan && first_image(a, img, err))
		return -1;

	/* Keep only the channels this image shares, compacting the planes. */
	for (int c = 0; c < a->nchan; c++) {
		if (!pm_image_chan(img, a->chan[c]))
			continue;
		if (keep != c) {
			memcpy(a->chan[keep], a->chan[c], PM_CHAN_NAME);
			memmove(a->mean + keep * plane, a->mean + c * plane, plane * sizeof *a->mean);
		}
		keep++;
	}
	a->nchan = keep;

	for (int c = 0; c < a->nchan; c++) {
		double *mean = a->mean + c * plane;
		const float *in = pm_image_chan(img, a->chan[c]);
		double *m2 = NULL;
		const float *m2b = NULL;
		for (int k = 0; k < 3; k++)
			if (strcmp(a->chan[c], rgb[k]) == 0) {
				m2 = a->m2 + k * plane;
				m2b = have_m2 ? m2in[k] : NULL;
			}
		pm_moments_merge(a->n, mean, m2, passes, in, m2b, plane);
	}
	a->n += passes;
	return 0;
}

int
pm_avg_image(const pm_avg *a, pm_image *out, pm_error *err)
{
	size_t plane = (size_t)a->width * a->height;
	const char **names = malloc((a->nchan + 6) * sizeof *names);
	char passes[32];
	int r;

	if (!names)
		return pm_seterr(err, "out of memory");

	for (int c = 0; c < a->nchan; c++)
		names[c] = a->chan[c];
	for (int k = 0; k < 3; k++) {
		names[a->nchan + k] = m2name[k];
		names[a->nchan + 3 + k] = sename[k];
	}
	r = pm_image_init(out, a->width, a->height, a->nchan + 6, names, err);
	free(names);
	if (r)
		return -1;
	for (int c = 0; c < a->nchan; c++) {
		float *p = pm_image_chan(out, a->chan[c]);
		for (size_t i = 0; i < plane; i++)
			p[i] = (float)a->mean[c * plane + i];
	}
	for (int k = 0; k < 3; k++) {
		float *m2 = pm_image_chan(out, m2name[k]), *se = pm_image_chan(out, sename[k]);
		for (size_t i = 0; i < plane; i++) {
			m2[i] = (float)a->m2[k * plane + i];
			se[i] = (float)pm_moments_stderr(a->n, a->m2[k * plane + i]);
		}
	}
	snprintf(passes, sizeof passes, "%.0f", a->n);
	if (pm_image_set_attr(out, "pm.passes", passes, err)) {
		pm_image_free(out);
		return -1;
	}
	return 0;
}

void
pm_avg_stats(const pm_avg *a, double *mean, double *mean_stderr)
{
	size_t plane = (size_t)a->width * a->height;
	double sm = 0, ss = 0;

	for (int k = 0; k < 3; k++) {
		const double *m = NULL;
		for (int c = 0; c < a->nchan; c++)
			if (strcmp(a->chan[c], rgb[k]) == 0)
				m = a->mean + c * plane;
		for (size_t i = 0; i < plane; i++) {
			sm += m ? m[i] : 0;
			ss += pm_moments_stderr(a->n, a->m2[k * plane + i]);
		}
	}
	*mean = plane ? sm / (3.0 * plane) : 0;
	*mean_stderr = plane ? ss / (3.0 * plane) : 0;
}
