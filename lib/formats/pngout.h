/* pngout.h — 8-bit sRGB PNG previews of float radiance (libpng).
 *
 * (Not "png.h": lib/ is on the include path and would hide libpng's.) */
#ifndef PM_PNGOUT_H
#define PM_PNGOUT_H

#include "base/err.h"
#include "formats/tonemap.h"

/* The 8-bit sRGB code of a linear value: sRGB transfer function (IEC
 * 61966-2-1), clamped to [0, 1], times 255, rounded. NaN gives 0. */
unsigned char pm_srgb8(double linear);

/* Writes a width x height RGB PNG atomically (see atomic.h; "-" is stdout):
 * pixel (x, y) of channel k is pm_srgb8(pm_tone_apply(tone,
 * rgb[k][y * width + x])); a NULL tone is EV 0 and clamp. Row 0 is the
 * top row. */
int pm_png_write(const char *path, int width, int height, const float *const rgb[3],
                 const pm_tone *tone, pm_error *err);

#endif
