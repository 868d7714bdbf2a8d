/* compare.h — checking and comparing image planes: finiteness (so NaN and
 * Inf are refused with the pixel named) and the error metrics pm-diff
 * reports, after pbrt-v4's imgtool (MSE, relMSE).
 *
 * Planes are width x height floats, row 0 at the top (as in image.h). */
#ifndef PM_COMPARE_H
#define PM_COMPARE_H

#include "base/err.h"
#include "formats/image.h"

/* 0 if every value is finite; else -1 with "channel 'NAME' pixel (X, Y) is
 * nan" (or inf) for the first bad pixel in row-major order. */
int pm_plane_finite(const float *p, int width, int height, const char *name, pm_error *err);

/* The three planes of a layer: NULL or "" gives the beauty R, G, B; NAME
 * gives NAME.R, NAME.G, NAME.B, or, for a single-channel layer such as
 * "count", the channel NAME three times (grey). -1 if absent. */
int pm_layer_planes(const pm_image *img, const char *layer, const float *out[3], pm_error *err);

typedef struct pm_diff {
	double rmse;        /* sqrt(mean (a-b)^2) */
	double relmse;      /* mean (a-b)^2 / (b^2 + 0.01) */
	double mae;         /* mean |a-b| */
	double max_abs;     /* max |a-b| */
	double mean_a, mean_b;
	long long pixels;   /* pixels counted */
} pm_diff;

/* Compares three planes a[0..2] against the reference b[0..2]; means are
 * over the counted pixels and the three channels. With mask non-NULL only
 * pixels whose mask value is > 0.5 count; -1 if none does. */
int pm_compare(const float *const a[3], const float *const b[3], const float *mask,
               int width, int height, pm_diff *d, pm_error *err);

#endif
