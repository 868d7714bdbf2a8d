/* texfilter.h — filtered (mipmapped) lookups of an image texture held in
 * memory, with OpenImageIO's TextureSystem, so that a texture seen from far
 * away reads its average over the pixel's footprint rather than whichever
 * texel the point lands on (aliasing). The texels stay pm's: linear RGB as
 * imagefile.h reads them, and OpenImageIO builds the MIP levels from them
 * (no file is read or written). Lookups are thread-safe and depend only on
 * their arguments, not on the thread or the order of calls. */
#ifndef PM_TEXFILTER_H
#define PM_TEXFILTER_H

typedef struct pm_texfilter pm_texfilter;

/* A filter over w x h linear RGB texels px (row 0 the top), which must
 * outlive it; NULL if out of memory. */
pm_texfilter *pm_texfilter_new(int w, int h, const float *px);
void pm_texfilter_free(pm_texfilter *f);

/* The texture's value over the footprint of (s, t) (s from the left edge,
 * t from the top, both periodic in [0, 1)) whose axes are (dsdx, dtdx) and
 * (dsdy, dtdy), in those units: bilinear within the MIP levels, anisotropic
 * across them. Returns 0, or -1 if OpenImageIO failed (rgb is then 0). */
int pm_texfilter_lookup(pm_texfilter *f, float s, float t, float dsdx, float dtdx,
                        float dsdy, float dtdy, float rgb[3]);

#endif
