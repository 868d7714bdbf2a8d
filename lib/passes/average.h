/* average.h — pass-weighted averaging of images that keeps, per pixel and
 * RGB channel, the mean and the sum of squared deviations between passes
 * (M2), so that averages of averages equal the average of all passes and the
 * spread between passes gives a per-pixel standard error.
 *
 * Merging uses Chan, Golub & LeVeque's pairwise update of Welford's
 * statistics ("Updating formulae and a pairwise algorithm for computing
 * sample variances", 1979): with n = na + nb and d = mean_b - mean_a,
 *   mean = mean_a + d * nb / n,   M2 = M2a + M2b + d^2 * na * nb / n.
 * formats/image.md describes the channels (m2.*, stderr.*). */
#ifndef PM_AVERAGE_H
#define PM_AVERAGE_H

#include <stddef.h>

#include "base/err.h"
#include "formats/image.h"

/* Merges len values of a set b (nb passes, means mb, sums of squared
 * deviations m2b) into a set a (na passes, means mean, sums m2), in place.
 * m2 may be NULL to merge means only; m2b NULL means M2b = 0 (e.g. one
 * pass). Nothing happens when na + nb == 0. */
void pm_moments_merge(double na, double *mean, double *m2,
                      double nb, const float *mb, const float *m2b, size_t len);

/* Standard error of the mean from n passes: sqrt(M2 / (n-1) / n), 0 when
 * n < 2. */
double pm_moments_stderr(double n, double m2);

/* An image's pass count: its "pm.passes" attribute (a whole number in
 * [1, 2^53]), or 1 if absent. */
int pm_image_passes(const pm_image *img, double *passes, pm_error *err);

/* A running average over images of one size. Averaged channels: every
 * channel of the first image except m2.* and stderr.*, which must include
 * R, G, B; a channel missing from a later image is dropped. */
typedef struct pm_avg {
	int width, height;
	double n;                     /* passes so far */
	int nchan;                    /* averaged channels */
	char (*chan)[PM_CHAN_NAME];
	double *mean;                 /* nchan planes of width*height */
	double *m2;                   /* 3 planes: R, G, B */
} pm_avg;

/* Zeroes a (no allocation). */
void pm_avg_init(pm_avg *a);
void pm_avg_free(pm_avg *a);

/* Adds img, which stands for `passes` passes. Its m2.R/G/B channels, if all
 * present, are its M2; else M2 = 0. Fails (a unchanged) if the size
 * differs, R, G or B is missing, or a channel used holds NaN/Inf or a
 * negative M2; the message does not name the file. */
int pm_avg_add(pm_avg *a, const pm_image *img, double passes, pm_error *err);

/* Makes out: the averaged channels, m2.R/G/B and stderr.R/G/B (float),
 * and pm.passes. No other attributes. */
int pm_avg_image(const pm_avg *a, pm_image *out, pm_error *err);

/* Mean over pixels of R, G, B, and mean over pixels and RGB of the
 * standard error. */
void pm_avg_stats(const pm_avg *a, double *mean, double *mean_stderr);

#endif
