/* texfilter.c — texfilter.h through the OpenImageIO module (oiio.h). */
#include "scene/texfilter.h"

#include "scene/oiio.h"

pm_texfilter *
pm_texfilter_new(int w, int h, const float *px)
{
	char why[400];
	const pm_oiio_api *io = pm_oiio(why, sizeof why);

	return io ? io->tex_new(w, h, px) : NULL;
}

void
pm_texfilter_free(pm_texfilter *f)
{
	/* A filter exists only if the module was loaded. */
	if (f)
		pm_oiio(NULL, 0)->tex_free(f);
}

int
pm_texfilter_lookup(pm_texfilter *f, float s, float t, float dsdx, float dtdx, float dsdy,
                    float dtdy, float rgb[3])
{
	return pm_oiio(NULL, 0)->tex_lookup(f, s, t, dsdx, dtdx, dsdy, dtdy, rgb);
}
