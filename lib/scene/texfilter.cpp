// texfilter.cpp — the OpenImageIO TextureSystem shim behind texfilter.h.
// The texels are handed to the TextureSystem through an ImageInput of our
// own that reads them from memory ("automip" then builds the levels), each
// texture under a name of its own in one process-wide TextureSystem. Every
// C++ exception stops here.
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/imagecache.h>
#include <OpenImageIO/texture.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <map>
#include <mutex>
#include <new>
#include <string>

extern "C" {
#include "scene/texfilter.h"
}

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

extern "C" pm_texfilter *
pm_texfilter_new(int w, int h, const float *px)
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

extern "C" void
pm_texfilter_free(pm_texfilter *f)
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

extern "C" int
pm_texfilter_lookup(pm_texfilter *f, float s, float t, float dsdx, float dtdx, float dsdy,
                    float dtdy, float rgb[3])
{
	rgb[0] = rgb[1] = rgb[2] = 0;
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
