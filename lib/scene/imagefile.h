/* imagefile.h — image files (PNG, JPEG, TGA, EXR, HDR, PFM, TIFF, ...) read
 * whole as linear RGB floats, for environment maps and textures.
 *
 * Integer images (8 or 16 bits a channel) are decoded from sRGB to linear;
 * float and half images are taken as they are. One channel is grey (copied
 * to R, G, B); two are grey and alpha; of three or more the first three are
 * R, G, B (alpha and the rest are ignored). */
#ifndef PM_IMAGEFILE_H
#define PM_IMAGEFILE_H

#include "base/err.h"

typedef struct pm_rgbimage {
	int w, h;
	float *px;          /* w * h * 3 floats, row 0 the top, left to right */
} pm_rgbimage;

/* Reads path; on failure *im is empty and err says "'path': what". An image
 * without pixels, or larger than 2^28 pixels, is an error. */
int pm_rgbimage_read(const char *path, pm_rgbimage *im, pm_error *err);
void pm_rgbimage_free(pm_rgbimage *im);

/* The sRGB transfer function undone: an 8-bit code's linear value. */
float pm_srgb_to_linear(float v);

#endif
