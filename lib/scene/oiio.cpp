// oiio.cpp — pm-oiio.so, the module behind oiio.h: image files read with
// OpenImageIO, and its TextureSystem for filtered texture lookups. The
// texels are handed to the TextureSystem through an ImageInput of our own
// that reads them from memory ("automip" then builds the levels), each
// texture under a name of its own in one process-wide TextureSystem. Every
// C++ exception stops here.
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/texture.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <new>
#include <string>

extern "C" {
#include "scene/oiio.h"
}

#define MAX_PIXELS (1u << 28)

namespace {

struct texels {
	int w, h;
	const float *px;
};

// The textures in memory by name: the ImageInput's creator takes no
// argument, so open() finds its texels here.
std::mutex reg_lock;
std::map<std::string, texels> &
registry()
{
	static std::map<std::string, texels> r;
	return r;
}

class MemInput final : public OIIO::ImageInput {
public:
	const char *format_name() const override { return "pm-memory"; }
	bool open(const std::string &name, OIIO::ImageSpec &newspec) override
	{
		std::lock_guard<std::mutex> g(reg_lock);
		auto it = registry().find(name);
		if (it == registry().end())
			return false;
		t = it->second;
		m_spec = OIIO::ImageSpec(t.w, t.h, 3, OIIO::TypeDesc::FLOAT);
		newspec = m_spec;
		return true;
	}
	bool close() override { return true; }
	bool read_native_scanline(int subimage, int miplevel, int y, int, void *data) override
	{
		if (subimage != 0 || miplevel != 0 || y < 0 || y >= t.h)
			return false;
		std::memcpy(data, t.px + (size_t)y * t.w * 3, (size_t)t.w * 3 * sizeof(float));
		return true;
	}

private:
	texels t = {0, 0, nullptr};
};

OIIO::ImageInput *
create_input()
{
	return new MemInput;
}

OIIO::TextureSystem *
system()
{
	// One for the process (OpenImageIO's shared one is not used, so
	// nothing else can change its settings); never destroyed, as the
	// shared one is not.
	static OIIO::TextureSystem *ts = [] {
		OIIO::TextureSystem *s = OIIO::TextureSystem::create(false);
		s->attribute("automip", 1);
		s->attribute("autotile", 64);
		s->attribute("max_memory_MB", 512.0f);
		return s;
	}();
	return ts;
}

std::atomic<unsigned long> serial{0};

} // namespace

struct pm_texfilter {
	OIIO::ustring name;
	OIIO::TextureSystem::TextureHandle *handle;
};

static pm_texfilter *
tex_new(int w, int h, const float *px)
{
	try {
		char name[64];
		std::snprintf(name, sizeof name, "pm-texture-%lu", serial++);
		{
			std::lock_guard<std::mutex> g(reg_lock);
			registry()[name] = texels{w, h, px};
		}
		OIIO::TextureSystem *ts = system();
		OIIO::ustring u(name);
		OIIO::ImageSpec config;
		if (!ts->imagecache()->add_file(u, create_input, &config)) {
			std::lock_guard<std::mutex> g(reg_lock);
			registry().erase(name);
			return nullptr;
		}
		pm_texfilter *f = new pm_texfilter{u, ts->get_texture_handle(u)};
		return f;
	} catch (...) {
		return nullptr;
	}
}

static void
tex_free(pm_texfilter *f)
{
	if (!f)
		return;
	try {
		system()->invalidate(f->name, true);
		std::lock_guard<std::mutex> g(reg_lock);
		registry().erase(f->name.string());
	} catch (...) {
	}
	delete f;
}

static int
tex_lookup(pm_texfilter *f, float s, float t, float dsdx, float dtdx, float dsdy, float dtdy,
           float rgb[3])
{
	try {
		OIIO::TextureOpt opt;
		opt.swrap = opt.twrap = OIIO::TextureOpt::WrapPeriodic;
		opt.interpmode = OIIO::TextureOpt::InterpBilinear;
		OIIO::TextureSystem *ts = system();
		if (!ts->texture(f->handle, ts->get_perthread_info(), opt, s, t, dsdx, dtdx, dsdy,
		                 dtdy, 3, rgb)) {
			(void)ts->geterror();
			rgb[0] = rgb[1] = rgb[2] = 0;
			return -1;
		}
		return 0;
	} catch (...) {
		rgb[0] = rgb[1] = rgb[2] = 0;
		return -1;
	}
}

namespace {

// The first line of an OpenImageIO error, into msg.
void
say(char *msg, size_t n, const char *path, const char *what, std::string e)
{
	size_t nl = e.find('\n');
	if (nl != std::string::npos)
		e.resize(nl);
	std::snprintf(msg, n, "'%s': %s%s%s", path, what, e.empty() ? "" : ": ", e.c_str());
}

int
read_file(const char *path, int *w, int *h, int *nc, int *srgb, float **px, char *msg, size_t n)
{
	auto in = OIIO::ImageInput::open(path);
	if (!in) {
		std::string e = OIIO::geterror();
		say(msg, n, path, "cannot read image", e.empty() ? "unknown format" : e);
		return -1;
	}
	const OIIO::ImageSpec &spec = in->spec();
	if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1) {
		say(msg, n, path, "image has no pixels", "");
		return -1;
	}
	if ((unsigned long long)spec.width * (unsigned long long)spec.height > MAX_PIXELS) {
		std::snprintf(msg, n, "'%s': image larger than %u pixels", path, MAX_PIXELS);
		return -1;
	}
	size_t count = (size_t)spec.width * spec.height * spec.nchannels;
	float *buf = (float *)std::malloc(count * sizeof *buf);
	if (!buf) {
		say(msg, n, path, "out of memory", "");
		return -1;
	}
	if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, buf)) {
		std::free(buf);
		say(msg, n, path, "cannot read image", in->geterror());
		return -1;
	}
	in->close();
	OIIO::TypeDesc::BASETYPE bt = (OIIO::TypeDesc::BASETYPE)spec.format.basetype;
	*srgb = !(bt == OIIO::TypeDesc::FLOAT || bt == OIIO::TypeDesc::HALF || bt == OIIO::TypeDesc::DOUBLE);
	*w = spec.width;
	*h = spec.height;
	*nc = spec.nchannels;
	*px = buf;
	return 0;
}

int
read_image(const char *path, int *w, int *h, int *nc, int *srgb, float **px, char *msg, size_t n)
{
	*px = nullptr;
	try {
		return read_file(path, w, h, nc, srgb, px, msg, n);
	} catch (const std::bad_alloc &) {
		say(msg, n, path, "out of memory", "");
	} catch (const std::exception &e) {
		say(msg, n, path, "cannot read image", e.what());
	} catch (...) {
		say(msg, n, path, "cannot read image", "");
	}
	return -1;
}

const pm_oiio_api api = {read_image, tex_new, tex_free, tex_lookup};

} // namespace

extern "C" __attribute__((visibility("default"))) const pm_oiio_api *
pm_oiio_api_v1(void)
{
	return &api;
}
