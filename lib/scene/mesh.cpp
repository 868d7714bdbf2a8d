// mesh.cpp — the OpenMesh shim behind mesh.h: reads a polygon mesh file into
// plain arrays. Every C++ exception stops here; nothing C++ crosses into C.

// OpenMesh 9's property vectors default-construct VectorT without
// initializing it, which GCC reports when it inlines them into this file.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <new>
#include <sstream>
#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include <sys/stat.h>

extern "C" {
#include "scene/mesh.h"
}

namespace {

// Double precision points, so that large coordinates in a file survive until
// the scene applies its transforms.
struct Traits : public OpenMesh::DefaultTraits {
	typedef OpenMesh::Vec3d Point;
};
typedef OpenMesh::PolyMesh_ArrayKernelT<Traits> Mesh;

struct TooBig {
	const char *what;
};

// The stock importer, with bounds on what a file may make us allocate and a
// count of the faces that could not be added. Consecutive repeated vertices
// (a face "1 2 2 3") are removed first, since OpenMesh would drop the face.
class Importer : public OpenMesh::IO::ImporterT<Mesh> {
public:
	typedef OpenMesh::VertexHandle VertexHandle;
	typedef OpenMesh::FaceHandle FaceHandle;
	typedef std::vector<VertexHandle> VHandles;

	// fsize bounds the counts: a mesh has at most one vertex or face per
	// byte of its file, so a header cannot make us reserve more.
	Importer(Mesh &m, unsigned long long fsize)
	    : OpenMesh::IO::ImporterT<Mesh>(m), fsize(fsize) {}

	uint32_t dropped = 0;

	VertexHandle add_vertex(const OpenMesh::Vec3f &p) override
	{
		count_vertex();
		return ImporterT<Mesh>::add_vertex(p);
	}
	VertexHandle add_vertex(const OpenMesh::Vec3d &p) override
	{
		count_vertex();
		return ImporterT<Mesh>::add_vertex(p);
	}
	VertexHandle add_vertex() override
	{
		count_vertex();
		return ImporterT<Mesh>::add_vertex();
	}

	FaceHandle add_face(const VHandles &in) override
	{
		if (in.size() > PM_MESH_MAX_FACE_VERTS)
			throw TooBig{"a face has too many vertices"};
		if (++nfaces > PM_MESH_MAX_FACES || nfaces > fsize)
			throw TooBig{"too many faces"};
		VHandles v;
		for (size_t i = 0; i < in.size(); i++) {
			// OpenMesh trusts the indices its readers hand over.
			if (!in[i].is_valid() || (size_t)in[i].idx() >= n_vertices())
				throw TooBig{"a face refers to a vertex that does not exist"};
			if (v.empty() || v.back() != in[i])
				v.push_back(in[i]);
		}
		while (v.size() > 1 && v.back() == v.front())
			v.pop_back();
		FaceHandle fh;
		if (v.size() >= 3)
			fh = ImporterT<Mesh>::add_face(v);
		if (!fh.is_valid())
			dropped++;
		return fh;
	}

	void reserve(unsigned nv, unsigned ne, unsigned nf) override
	{
		// Headers (OFF, PLY) announce counts; do not trust them with memory.
		if (nv > PM_MESH_MAX_VERTS || nf > PM_MESH_MAX_FACES || nv > fsize || nf > fsize)
			throw TooBig{"the header announces more vertices or faces than the file can hold"};
		ImporterT<Mesh>::reserve(nv, ne, nf);
	}

private:
	uint64_t nverts = 0, nfaces = 0;
	unsigned long long fsize;

	void count_vertex()
	{
		if (++nverts > PM_MESH_MAX_VERTS || nverts > fsize)
			throw TooBig{"too many vertices"};
	}
};

// Silences OpenMesh's process-wide diagnostic streams for one scope: our
// caller reports problems as one line of its own.
class Quiet {
public:
	Quiet()
	    : err(omerr().is_enabled()), log(omlog().is_enabled()),
	      out(omout().is_enabled())
	{
		omerr().disable();
		omlog().disable();
		omout().disable();
	}
	~Quiet()
	{
		if (err)
			omerr().enable();
		if (log)
			omlog().enable();
		if (out)
			omout().enable();
	}

private:
	bool err, log, out;
};

std::string extension(const char *path)
{
	const char *slash = std::strrchr(path, '/');
	const char *base = slash ? slash + 1 : path;
	const char *dot = std::strrchr(base, '.');
	if (!dot || dot == base)
		return "";
	std::string e(dot + 1);
	for (auto &c : e)
		if (c >= 'A' && c <= 'Z')
			c = char(c - 'A' + 'a');
	return e;
}

// OpenMesh's PLY reader crashes on some malformed headers (a property
// before any element, for one), so the header is checked here first against
// the PLY grammar (Turk 1994, "The PLY Polygon File Format"): magic, one
// format line, elements with counts the file could hold, typed properties,
// end_header within 64 KiB. Returns NULL if it is sound, else the problem.
// OpenMesh reads a PLY's texture coordinates as u v or s t only; files
// also name them texture_u texture_v or texture_s texture_t (as pbrt-v4
// reads them). If the header does, *data gets the file with those names
// shortened in its header, and the result is true.
bool ply_texture_names(const char *path, std::string &data)
{
	std::ifstream f(path, std::ios::binary);
	std::ostringstream all;
	all << f.rdbuf();
	data = all.str();
	size_t end = data.find("end_header");
	if (!f || end == std::string::npos)
		return false;
	bool changed = false;
	static const char *const from[] = {"property float texture_u", "property float texture_v",
		"property float texture_s", "property float texture_t",
		"property double texture_u", "property double texture_v",
		"property double texture_s", "property double texture_t"};
	for (const char *k : from) {
		size_t at = data.find(k);
		if (at != std::string::npos && at < end) {
			size_t name = data.find("texture_", at);
			data.erase(name, 8);
			end -= 8;
			changed = true;
		}
	}
	return changed;
}

const char *ply_header_problem(const char *path, unsigned long long fsize)
{
	static const char *const types[] = {"char", "uchar", "short", "ushort", "int", "uint",
		"float", "double", "int8", "uint8", "int16", "uint16", "int32", "uint32",
		"float32", "float64"};
	auto is_type = [](const std::string &t) {
		for (const char *k : types)
			if (t == k)
				return true;
		return false;
	};
	FILE *f = std::fopen(path, "rb");
	if (!f)
		return "cannot open";
	std::string all;
	int c;
	while (all.size() < 65536 && (c = std::getc(f)) != EOF)
		all.push_back((char)c);
	std::fclose(f);
	std::vector<std::vector<std::string>> lines;
	size_t pos = 0;
	bool ended = false;
	while (pos < all.size()) {
		size_t nl = all.find('\n', pos);
		if (nl == std::string::npos)
			break;
		std::string line = all.substr(pos, nl - pos);
		pos = nl + 1;
		if (!line.empty() && line.back() == '\r')
			line.pop_back();
		std::vector<std::string> w;
		size_t i = 0;
		while (i < line.size()) {
			while (i < line.size() && (line[i] == ' ' || line[i] == '\t'))
				i++;
			size_t j = i;
			while (j < line.size() && line[j] != ' ' && line[j] != '\t')
				j++;
			if (j > i)
				w.push_back(line.substr(i, j - i));
			i = j;
		}
		if (!w.empty() && w[0] == "end_header") {
			ended = true;
			break;
		}
		lines.push_back(w);
	}
	if (!ended)
		return "malformed PLY header (no end_header in the first 64 KiB)";
	if (lines.empty() || lines[0].size() != 1 || lines[0][0] != "ply")
		return "malformed PLY header (no 'ply' magic)";
	bool format = false, element = false;
	for (size_t i = 1; i < lines.size(); i++) {
		const auto &w = lines[i];
		if (w.empty())
			return "malformed PLY header (empty line)";
		if (w[0] == "comment" || w[0] == "obj_info")
			continue;
		if (w[0] == "format") {
			if (format || w.size() != 3 || w[2] != "1.0" ||
			    (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian"))
				return "malformed PLY header (bad format line)";
			format = true;
		} else if (w[0] == "element") {
			if (w.size() != 3 || w[2].empty() || w[2].size() > 19 ||
			    w[2].find_first_not_of("0123456789") != std::string::npos ||
			    std::strtoull(w[2].c_str(), nullptr, 10) > fsize)
				return "malformed PLY header (bad element line, or a count the file cannot hold)";
			element = true;
		} else if (w[0] == "property") {
			if (!element)
				return "malformed PLY header (a property before any element)";
			bool ok = (w.size() == 3 && is_type(w[1])) ||
			          (w.size() == 5 && w[1] == "list" && is_type(w[2]) && is_type(w[3]));
			if (!ok)
				return "malformed PLY header (bad property line)";
		} else {
			return "malformed PLY header (unknown keyword)";
		}
	}
	if (!format)
		return "malformed PLY header (no format line)";
	return nullptr;
}

// OpenMesh's OBJ reader asserts (aborts) on a face corner without a vertex
// index ("f /1 2 3"), so face lines are checked first: every corner must be
// INDEX[/[TEX][/[NORMAL]]] with a nonzero, possibly negative, INDEX.
// Returns NULL if they are sound, else the problem.
const char *obj_faces_problem(const char *path)
{
	FILE *f = std::fopen(path, "rb");
	if (!f)
		return "cannot open";
	std::string line;
	int c;
	bool bad = false;
	do {
		c = std::getc(f);
		if (c != EOF && c != '\n') {
			line.push_back((char)c);
			if (line.size() > (1u << 20)) {
				bad = true;
				break;
			}
			continue;
		}
		size_t i = 0;
		while (i < line.size() && (line[i] == ' ' || line[i] == '\t'))
			i++;
		if (i + 1 < line.size() && line[i] == 'f' && (line[i + 1] == ' ' || line[i + 1] == '\t')) {
			i++;
			for (;;) {
				while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r'))
					i++;
				if (i >= line.size() || line[i] == '#')
					break;
				size_t j = i + (line[i] == '-');
				size_t d = j;
				bool zero = true;
				for (; d < line.size() && line[d] >= '0' && line[d] <= '9'; d++)
					if (line[d] != '0')
						zero = false;
				if (d == j || zero) {
					bad = true;
					break;
				}
				while (d < line.size() && line[d] != ' ' && line[d] != '\t' && line[d] != '\r')
					d++;
				i = d;
			}
		}
		line.clear();
	} while (c != EOF && !bad);
	std::fclose(f);
	return bad ? "malformed OBJ face line (a corner without a vertex index, or index 0)" : nullptr;
}

// 1 if the faces close a surface when corners at one position are one
// vertex: every edge, taken in its face's direction, is met once and its
// reverse once. A flat-shaded export writes every face with vertices of its
// own (a polygon soup), which OpenMesh's topology sees as all boundary.
int closed_by_position(const std::vector<double> &verts, const std::vector<uint32_t> &start,
                       const std::vector<uint32_t> &fv)
{
	size_t nv = verts.size() / 3;
	std::vector<uint32_t> order(nv), id(nv);
	for (size_t i = 0; i < nv; i++)
		order[i] = (uint32_t)i;
	auto pos = [&](uint32_t i) {
		return std::array<double, 3>{verts[3 * i], verts[3 * i + 1], verts[3 * i + 2]};
	};
	std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return pos(a) < pos(b); });
	for (size_t i = 0, k = 0; i < nv; i++) {
		if (i > 0 && pos(order[i]) != pos(order[i - 1]))
			k++;
		id[order[i]] = (uint32_t)k;
	}
	std::vector<std::pair<uint32_t, uint32_t>> e;
	e.reserve(fv.size());
	for (size_t f = 0; f + 1 < start.size(); f++)
		for (uint32_t c = start[f]; c < start[f + 1]; c++) {
			uint32_t nx = c + 1 < start[f + 1] ? c + 1 : start[f];
			e.emplace_back(id[fv[c]], id[fv[nx]]);
		}
	std::sort(e.begin(), e.end());
	for (size_t i = 0; i < e.size(); i++) {
		if (e[i].first == e[i].second || (i > 0 && e[i] == e[i - 1]))
			return 0;
		if (!std::binary_search(e.begin(), e.end(), std::make_pair(e[i].second, e[i].first)))
			return 0;
	}
	return 1;
}

int fail(pm_meshdata *out, pm_error *err, const char *path, const char *why)
{
	pm_mesh_free(out);
	return pm_seterr(err, "'%s': cannot read mesh: %s", path, why);
}

int read(const char *path, pm_meshdata *out, pm_error *err)
{
	// Find out why a file cannot be opened ourselves: OpenMesh only says no.
	FILE *f = std::fopen(path, "rb");
	if (!f)
		return fail(out, err, path, std::strerror(errno));
	struct stat st;
	int serr = fstat(fileno(f), &st) ? errno : 0;
	std::fclose(f);
	if (serr)
		return fail(out, err, path, std::strerror(serr));
	if (!S_ISREG(st.st_mode))
		return fail(out, err, path, "not a regular file");
	if ((unsigned long long)st.st_size > PM_MESH_MAX_BYTES)
		return fail(out, err, path, "file larger than 2 GiB");

	// OpenMesh's can_read() opens "dummy.EXT" for some formats, so it
	// cannot answer this; the readers it registers are known.
	std::string ext = extension(path);
	static const char *const known[] = {"obj", "ply", "off", "stl", "stla", "stlb", "om"};
	bool ok = false;
	for (const char *k : known)
		ok = ok || ext == k;
	if (!ok)
		return fail(out, err, path, "unknown format (expected .obj, .ply, .off, .stl or .om)");

	if (ext == "obj") {
		const char *why = obj_faces_problem(path);
		if (why)
			return fail(out, err, path, why);
	}
	if (ext == "ply") {
		const char *why = ply_header_problem(path, (unsigned long long)st.st_size);
		if (why)
			return fail(out, err, path, why);
	}

	Quiet quiet;

	Mesh mesh;
	Importer imp(mesh, (unsigned long long)st.st_size);
	// Vertex normals are read when the file has them (OBJ vn, PLY nx ny nz).
	OpenMesh::IO::Options opt = OpenMesh::IO::Options::VertexNormal;
	opt += OpenMesh::IO::Options::VertexTexCoord;
	mesh.request_vertex_normals();
	mesh.request_vertex_texcoords2D();
	try {
		std::string ply;
		if (ext == "ply" && ply_texture_names(path, ply)) {
			std::istringstream in(ply);
			ok = OpenMesh::IO::IOManager().read(in, ".ply", imp, opt);
		} else {
			ok = OpenMesh::IO::IOManager().read(path, imp, opt);
		}
	} catch (const TooBig &e) {
		return fail(out, err, path, e.what);
	}
	if (!ok)
		return fail(out, err, path, "malformed or unreadable file");
	if (mesh.n_faces() == 0)
		return fail(out, err, path, "no faces");
	if (mesh.n_vertices() > PM_MESH_MAX_VERTS || mesh.n_faces() > PM_MESH_MAX_FACES)
		return fail(out, err, path, "too many vertices or faces");

	std::vector<double> verts(3 * mesh.n_vertices());
	for (auto v : mesh.vertices()) {
		const Mesh::Point &p = mesh.point(v);
		for (int k = 0; k < 3; k++)
			verts[3 * v.idx() + k] = p[k];
	}
	std::vector<uint32_t> start, fv;
	start.reserve(mesh.n_faces() + 1);
	for (auto fh : mesh.faces()) {
		start.push_back((uint32_t)fv.size());
		// Walk next-halfedges from the face's own halfedge: the winding
		// the face was added with.
		auto h0 = mesh.halfedge_handle(fh), h = h0;
		size_t n = 0;
		do {
			fv.push_back((uint32_t)mesh.from_vertex_handle(h).idx());
			h = mesh.next_halfedge_handle(h);
			if (++n > PM_MESH_MAX_FACE_VERTS)
				return fail(out, err, path, "a face has too many vertices");
		} while (h != h0);
	}
	start.push_back((uint32_t)fv.size());

	int closed = 1;
	for (auto h : mesh.halfedges())
		if (mesh.is_boundary(h)) {
			closed = 0;
			break;
		}
	if (!closed)
		closed = closed_by_position(verts, start, fv);

	if (opt.check(OpenMesh::IO::Options::VertexNormal)) {
		out->normals = (double *)std::malloc(verts.size() * sizeof(double));
		if (!out->normals)
			return fail(out, err, path, "out of memory");
		for (auto v : mesh.vertices()) {
			const Mesh::Normal &n = mesh.normal(v);
			for (int k = 0; k < 3; k++)
				out->normals[3 * v.idx() + k] = n[k];
		}
	}
	if (opt.check(OpenMesh::IO::Options::VertexTexCoord)) {
		out->uv = (double *)std::malloc(2 * mesh.n_vertices() * sizeof(double));
		if (!out->uv)
			return fail(out, err, path, "out of memory");
		for (auto v : mesh.vertices()) {
			const Mesh::TexCoord2D &t = mesh.texcoord2D(v);
			out->uv[2 * v.idx()] = t[0];
			out->uv[2 * v.idx() + 1] = t[1];
		}
	}
	out->verts = (double *)std::malloc(verts.size() * sizeof(double));
	out->face_start = (uint32_t *)std::malloc(start.size() * sizeof(uint32_t));
	out->face_vert = (uint32_t *)std::malloc(fv.size() * sizeof(uint32_t));
	if (!out->verts || !out->face_start || !out->face_vert)
		return fail(out, err, path, "out of memory");
	std::memcpy(out->verts, verts.data(), verts.size() * sizeof(double));
	std::memcpy(out->face_start, start.data(), start.size() * sizeof(uint32_t));
	std::memcpy(out->face_vert, fv.data(), fv.size() * sizeof(uint32_t));
	out->nverts = (uint32_t)mesh.n_vertices();
	out->nfaces = (uint32_t)mesh.n_faces();
	out->closed = closed;
	out->ndropped = imp.dropped;
	return 0;
}

} // namespace

extern "C" int pm_mesh_read(const char *path, pm_meshdata *out, pm_error *err)
{
	std::memset(out, 0, sizeof *out);
	try {
		return read(path, out, err);
	} catch (const std::bad_alloc &) {
		return fail(out, err, path, "out of memory");
	} catch (const std::exception &e) {
		return fail(out, err, path, e.what());
	} catch (...) {
		return fail(out, err, path, "unexpected error in openmesh");
	}
}

extern "C" void pm_mesh_free(pm_meshdata *m)
{
	if (!m)
		return;
	std::free(m->verts);
	std::free(m->normals);
	std::free(m->uv);
	std::free(m->face_start);
	std::free(m->face_vert);
	std::memset(m, 0, sizeof *m);
}
