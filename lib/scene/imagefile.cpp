// imagefile.cpp — the OpenImageIO shim behind imagefile.h: one image file
// read into linear RGB floats. Every C++ exception stops here.
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <new>
#include <string>
#include <vector>

extern "C" {
#include "scene/imagefile.h"
}

#define MAX_PIXELS (1u << 28)

extern "C" float
pm_srgb_to_linear(float v)
{
	// IEC 61966-2-1.
	return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

static int
read_image(const char *path, pm_rgbimage *im, pm_error *err)
{
	auto in = OIIO::ImageInput::open(path);
	if (!in) {
		std::string e = OIIO::geterror();
		size_t nl = e.find('\n');
		if (nl != std::string::npos)
			e.resize(nl);
		return pm_seterr(err, "'%s': cannot read image: %s", path,
		                 e.empty() ? "unknown format" : e.c_str());
	}
	const OIIO::ImageSpec &spec = in->spec();
	int w = spec.width, h = spec.height, nc = spec.nchannels;
	if (w <= 0 || h <= 0 || nc <= 0 || spec.depth > 1)
		return pm_seterr(err, "'%s': image has no pixels", path);
	if ((unsigned long long)w * (unsigned long long)h > MAX_PIXELS)
		return pm_seterr(err, "'%s': image larger than %u pixels", path, MAX_PIXELS);
	std::vector<float> buf((size_t)w * h * nc);
	if (!in->read_image(0, 0, 0, nc, OIIO::TypeDesc::FLOAT, buf.data())) {
		std::string e = in->geterror();
		size_t nl = e.find('\n');
		if (nl != std::string::npos)
			e.resize(nl);
		return pm_seterr(err, "'%s': cannot read image: %s", path, e.c_str());
	}
	in->close();
	OIIO::TypeDesc::BASETYPE bt = (OIIO::TypeDesc::BASETYPE)spec.format.basetype;
	bool srgb = !(bt == OIIO::TypeDesc::FLOAT || bt == OIIO::TypeDesc::HALF
	              || bt == OIIO::TypeDesc::DOUBLE);
	float *px = (float *)malloc((size_t)w * h * 3 * sizeof *px);
	if (!px)
		return pm_seterr(err, "'%s': out of memory", path);
	for (size_t i = 0; i < (size_t)w * h; i++)
		for (int c = 0; c < 3; c++) {
			float v = buf[i * nc + (nc >= 3 ? c : 0)];
			px[3 * i + c] = srgb ? pm_srgb_to_linear(v) : v;
		}
	im->w = w;
	im->h = h;
	im->px = px;
	return 0;
}

extern "C" int
pm_rgbimage_read(const char *path, pm_rgbimage *im, pm_error *err)
{
	im->w = im->h = 0;
	im->px = nullptr;
	try {
		return read_image(path, im, err);
	} catch (const std::bad_alloc &) {
		return pm_seterr(err, "'%s': out of memory", path);
	} catch (const std::exception &e) {
		return pm_seterr(err, "'%s': cannot read image: %s", path, e.what());
	} catch (...) {
		return pm_seterr(err, "'%s': cannot read image", path);
	}
}

extern "C" void
pm_rgbimage_free(pm_rgbimage *im)
{
	free(im->px);
	im->px = nullptr;
	im->w = im->h = 0;
}
