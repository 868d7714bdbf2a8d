/* oiio.h — OpenImageIO as a module loaded when first needed: the image
 * reader behind imagefile.h and the TextureSystem behind texfilter.h live
 * in pm-oiio.so (oiio.cpp), which the programs do not link. OpenImageIO
 * brings some 250 shared libraries (video, GIS and camera formats among
 * them) whose loading cost every program half a second of CPU at start,
 * scenes without images included.
 *
 * The module is looked for in $PM_PLUGIN_DIR if that is set (only there),
 * else in ../lib/pm beside the running program's directory (an installed
 * pm: PREFIX/bin, PREFIX/lib/pm), else in the build tree it was built in. */
#ifndef PM_OIIO_H
#define PM_OIIO_H

#include <stddef.h>

#include "scene/texfilter.h"

/* What the module offers (its one exported symbol, PM_OIIO_SYMBOL,
 * returns it). Errors are one line in msg (n bytes). */
typedef struct pm_oiio_api {
	/* Reads path whole: *px gets w * h * nc floats (malloc; row 0 the top),
	 * *srgb says the file held integers (sRGB-encoded). 0, or -1. */
	int (*read)(const char *path, int *w, int *h, int *nc, int *srgb, float **px,
	            char *msg, size_t n);
	pm_texfilter *(*tex_new)(int w, int h, const float *px);
	void (*tex_free)(pm_texfilter *f);
	int (*tex_lookup)(pm_texfilter *f, float s, float t, float dsdx, float dtdx,
	                  float dsdy, float dtdy, float rgb[3]);
} pm_oiio_api;

#define PM_OIIO_SYMBOL "pm_oiio_api_v1"
#define PM_OIIO_FILE "pm-oiio.so"

/* The module, loaded on the first call (thread-safe); NULL if it cannot be,
 * with why (n bytes) saying where it was looked for and what failed. */
const pm_oiio_api *pm_oiio(char *why, size_t n);

#endif
