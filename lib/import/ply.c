/* ply.c — the PLY reader of ply.h. The header says which elements and
 * properties follow; vertices and faces are kept, other elements skipped.
 * Every count is bounded before it is trusted, every index checked. */
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "import/ply.h"

#define MAX_COUNT (1u << 28)
#define MAX_PROPS 64

enum { T_NONE, T_I8, T_U8, T_I16, T_U16, T_I32, T_U32, T_F32, T_F64 };
enum { F_ASCII, F_LE, F_BE };

typedef struct prop {
	char name[64];
	int type;            /* scalar type, or the list's item type */
	int count_type;      /* list count type, T_NONE for a scalar */
} prop;

typedef struct element {
	char name[64];
	uint64_t count;
	int nprops;
	prop props[MAX_PROPS];
} element;

typedef struct reader {
	gzFile gz;
	const char *path;
	int format;
	unsigned char buf[65536];
	int len, pos;
	int eof;
} reader;

static int
type_of(const char *s)
{
	static const struct { const char *n; int t; } names[] = {
		{"char", T_I8}, {"int8", T_I8}, {"uchar", T_U8}, {"uint8", T_U8},
		{"short", T_I16}, {"int16", T_I16}, {"ushort", T_U16}, {"uint16", T_U16},
		{"int", T_I32}, {"int32", T_I32}, {"uint", T_U32}, {"uint32", T_U32},
		{"float", T_F32}, {"float32", T_F32}, {"double", T_F64}, {"float64", T_F64},
	};
	for (size_t i = 0; i < sizeof names / sizeof *names; i++)
		if (strcmp(s, names[i].n) == 0)
			return names[i].t;
	return T_NONE;
}

static int
type_size(int t)
{
	static const int sz[] = { 0, 1, 1, 2, 2, 4, 4, 4, 8 };
	return sz[t];
}

static int
fill(reader *r)
{
	if (r->eof)
		return -1;
	r->len = gzread(r->gz, r->buf, sizeof r->buf);
	r->pos = 0;
	if (r->len <= 0) {
		r->eof = 1;
		return -1;
	}
	return 0;
}

static int
getbyte(reader *r)
{
	if (r->pos >= r->len && fill(r))
		return -1;
	return r->buf[r->pos++];
}

/* One header line without its newline; -1 at end of file. */
static int
getline_hdr(reader *r, char *line, size_t n)
{
	size_t k = 0;
	int c;

	while ((c = getbyte(r)) != '\n') {
		if (c < 0)
			return -1;
		if (c != '\r' && k + 1 < n)
			line[k++] = (char)c;
	}
	line[k] = 0;
	return 0;
}

/* The next value of type t as a double; -1 if the file ends. */
static int
get_value(reader *r, int t, double *out)
{
	unsigned char b[8];
	int n = type_size(t);

	if (r->format == F_ASCII) {
		char tok[64];
		int c, k = 0;
		while ((c = getbyte(r)) == ' ' || c == '\t' || c == '\n' || c == '\r')
			;
		while (c >= 0 && c != ' ' && c != '\t' && c != '\n' && c != '\r') {
			if (k < 63)
				tok[k++] = (char)c;
			c = getbyte(r);
		}
		if (k == 0)
			return -1;
		tok[k] = 0;
		char *end;
		*out = strtod(tok, &end);
		return *end ? -2 : 0;
	}
	for (int i = 0; i < n; i++) {
		int c = getbyte(r);
		if (c < 0)
			return -1;
		b[r->format == F_LE ? i : n - 1 - i] = (unsigned char)c;
	}
	switch (t) {
	case T_I8: *out = (int8_t)b[0]; break;
	case T_U8: *out = b[0]; break;
	case T_I16: *out = (int16_t)(b[0] | b[1] << 8); break;
	case T_U16: *out = (uint16_t)(b[0] | b[1] << 8); break;
	case T_I32: *out = (int32_t)((uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24); break;
	case T_U32: *out = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24; break;
	case T_F32: {
		uint32_t u = (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
		float f;
		memcpy(&f, &u, 4);
		*out = f;
		break;
	}
	case T_F64: {
		uint64_t u = 0;
		double d;
		for (int i = 7; i >= 0; i--)
			u = u << 8 | b[i];
		memcpy(&d, &u, 8);
		*out = d;
		break;
	}
	}
	return 0;
}

static int
fail(pmi_shape *s, float **normals, pm_error *err, const char *path, const char *fmt, const char *what, long long a, long long b)
{
	char msg[200];

	snprintf(msg, sizeof msg, fmt, what, a, b);
	pmi_shape_free(s);
	free(*normals);
	*normals = NULL;
	return pm_seterr(err, "'%s': %s", path, msg);
}

int
pmi_ply_read(const char *path, pmi_shape *s, float **normals, pm_error *err)
{
	reader *r = calloc(1, sizeof *r);
	element el[16];
	int nel = 0, vi = -1, fi = -1, rc;
	char line[1024];
	uint32_t *fidx = NULL;

	*normals = NULL;
	memset(s, 0, sizeof *s);
	if (!r)
		return pm_seterr(err, "out of memory");
	r->path = path;
	if (!(r->gz = gzopen(path, "rb"))) {
		free(r);
		return pm_seterr(err, "'%s': cannot open: %s", path, strerror(errno ? errno : ENOENT));
	}
#define FAIL(...) do { rc = fail(s, normals, err, path, __VA_ARGS__); goto out; } while (0)
	if (getline_hdr(r, line, sizeof line) || strcmp(line, "ply") != 0)
		FAIL("%snot a PLY file (no 'ply' line)", "", 0, 0);
	r->format = -1;
	for (;;) {
		char w[4][64];
		int nw;
		if (getline_hdr(r, line, sizeof line))
			FAIL("%sheader ends before end_header", "", 0, 0);
		nw = sscanf(line, "%63s %63s %63s %63s", w[0], w[1], w[2], w[3]);
		if (nw <= 0 || strcmp(w[0], "comment") == 0 || strcmp(w[0], "obj_info") == 0)
			continue;
		if (strcmp(w[0], "end_header") == 0)
			break;
		if (strcmp(w[0], "format") == 0 && nw >= 2) {
			r->format = strcmp(w[1], "ascii") == 0 ? F_ASCII :
			            strcmp(w[1], "binary_little_endian") == 0 ? F_LE :
			            strcmp(w[1], "binary_big_endian") == 0 ? F_BE : -1;
			if (r->format < 0)
				FAIL("unknown format '%s'", w[1], 0, 0);
		} else if (strcmp(w[0], "element") == 0 && nw == 3) {
			char *end;
			unsigned long long c = strtoull(w[2], &end, 10);
			if (*end || c > MAX_COUNT)
				FAIL("element '%s': count %lld not in [0, %lld]", w[1], (long long)c, MAX_COUNT);
			if (nel == 16)
				FAIL("%smore than 16 elements", "", 0, 0);
			memset(&el[nel], 0, sizeof el[nel]);
			snprintf(el[nel].name, sizeof el[nel].name, "%s", w[1]);
			el[nel].count = c;
			if (strcmp(w[1], "vertex") == 0)
				vi = nel;
			else if (strcmp(w[1], "face") == 0)
				fi = nel;
			nel++;
		} else if (strcmp(w[0], "property") == 0 && nel > 0) {
			element *e = &el[nel - 1];
			prop *p = &e->props[e->nprops];
			if (e->nprops == MAX_PROPS)
				FAIL("element '%s' has more than %lld properties", e->name, MAX_PROPS, 0);
			memset(p, 0, sizeof *p);
			if (nw == 4 && strcmp(w[1], "list") != 0)
				FAIL("bad property line '%.80s'", line, 0, 0);
			if (strcmp(w[1], "list") == 0) {
				char name[64];
				if (sscanf(line, "%*s %*s %*s %*s %63s", name) != 1)
					FAIL("bad property line '%.80s'", line, 0, 0);
				p->count_type = type_of(w[2]);
				p->type = type_of(w[3]);
				if (p->count_type == T_NONE || p->type == T_NONE || p->count_type >= T_F32)
					FAIL("bad list property '%.80s'", line, 0, 0);
				snprintf(p->name, sizeof p->name, "%s", name);
			} else {
				if (nw != 3 || (p->type = type_of(w[1])) == T_NONE)
					FAIL("bad property line '%.80s'", line, 0, 0);
				snprintf(p->name, sizeof p->name, "%s", w[2]);
			}
			e->nprops++;
		} else
			FAIL("unknown header line '%.80s'", line, 0, 0);
	}
	if (r->format < 0)
		FAIL("%sno format line", "", 0, 0);
	if (vi < 0 || fi < 0)
		FAIL("%sneeds a vertex and a face element", "", 0, 0);

	/* Which property is which. */
	int px = -1, py = -1, pz = -1, pnx = -1, pny = -1, pnz = -1, pu = -1, pv = -1, plist = -1;
	for (int i = 0; i < el[vi].nprops; i++) {
		const char *n = el[vi].props[i].name;
		if (el[vi].props[i].count_type != T_NONE)
			continue;
		if (!strcmp(n, "x")) px = i;
		else if (!strcmp(n, "y")) py = i;
		else if (!strcmp(n, "z")) pz = i;
		else if (!strcmp(n, "nx")) pnx = i;
		else if (!strcmp(n, "ny")) pny = i;
		else if (!strcmp(n, "nz")) pnz = i;
		else if (!strcmp(n, "u") || !strcmp(n, "s") || !strcmp(n, "texture_u") || !strcmp(n, "texture_s")) pu = i;
		else if (!strcmp(n, "v") || !strcmp(n, "t") || !strcmp(n, "texture_v") || !strcmp(n, "texture_t")) pv = i;
	}
	for (int i = 0; i < el[fi].nprops; i++)
		if (el[fi].props[i].count_type != T_NONE &&
		    (!strcmp(el[fi].props[i].name, "vertex_indices") || !strcmp(el[fi].props[i].name, "vertex_index")))
			plist = i;
	if (px < 0 || py < 0 || pz < 0)
		FAIL("%svertices lack x, y or z", "", 0, 0);
	if (plist < 0)
		FAIL("%sfaces lack a vertex_indices list", "", 0, 0);
	int has_n = pnx >= 0 && pny >= 0 && pnz >= 0, has_uv = pu >= 0 && pv >= 0;
	size_t nv = el[vi].count, nf = el[fi].count, cap = nf * 3 + 16, nidx = 0;
	s->kind = PMI_SHAPE_MESH;
	s->v = malloc((nv ? nv : 1) * 3 * sizeof *s->v);
	s->uv = has_uv ? malloc((nv ? nv : 1) * 2 * sizeof *s->uv) : NULL;
	s->start = malloc((nf + 1) * sizeof *s->start);
	fidx = malloc(cap * sizeof *fidx);
	if (has_n)
		*normals = malloc((nv ? nv : 1) * 3 * sizeof **normals);
	if (!s->v || !s->start || !fidx || (has_uv && !s->uv) || (has_n && !*normals))
		FAIL("%sout of memory", "", 0, 0);
	s->start[0] = 0;
	for (int e = 0; e < nel; e++) {
		for (uint64_t k = 0; k < el[e].count; k++) {
			for (int i = 0; i < el[e].nprops; i++) {
				const prop *p = &el[e].props[i];
				double val;
				int g;
				if (p->count_type == T_NONE) {
					if ((g = get_value(r, p->type, &val)))
						FAIL(g == -1 ? "truncated in %s %lld" : "bad number in %s %lld", el[e].name, (long long)k, 0);
					if (e == vi) {
						if (i == px) s->v[3 * k] = (float)val;
						else if (i == py) s->v[3 * k + 1] = (float)val;
						else if (i == pz) s->v[3 * k + 2] = (float)val;
						else if (has_uv && i == pu) s->uv[2 * k] = (float)val;
						else if (has_uv && i == pv) s->uv[2 * k + 1] = (float)val;
						else if (has_n && i == pnx) (*normals)[3 * k] = (float)val;
						else if (has_n && i == pny) (*normals)[3 * k + 1] = (float)val;
						else if (has_n && i == pnz) (*normals)[3 * k + 2] = (float)val;
					}
					continue;
				}
				if ((g = get_value(r, p->count_type, &val)))
					FAIL("%struncated or bad list in %s %lld", el[e].name, (long long)k, 0);
				if (val < 0 || val > 1024)
					FAIL("%s %lld: list of %lld items", el[e].name, (long long)k, (long long)val);
				int cnt = (int)val;
				if (e == fi && i == plist && (cnt < 3))
					FAIL("face %s%lld has %lld corners", "", (long long)k, cnt);
				for (int j = 0; j < cnt; j++) {
					if ((g = get_value(r, p->type, &val)))
						FAIL("%struncated or bad list in %s %lld", el[e].name, (long long)k, 0);
					if (e == fi && i == plist) {
						if (!(val >= 0 && val < (double)nv))
							FAIL("face %s%lld: vertex index %lld out of range", "", (long long)k, (long long)val);
						if (nidx == cap) {
							uint32_t *t = realloc(fidx, (cap *= 2) * sizeof *t);
							if (!t)
								FAIL("%sout of memory", "", 0, 0);
							fidx = t;
						}
						fidx[nidx++] = (uint32_t)val;
					}
				}
			}
			if (e == fi)
				s->start[k + 1] = (uint32_t)nidx;
		}
	}
	s->nv = nv;
	s->nface = nf;
	s->idx = fidx;
	fidx = NULL;
	rc = 0;
	if (nf == 0)
		FAIL("%sno faces", "", 0, 0);
out:
	free(fidx);
	gzclose(r->gz);
	free(r);
	return rc;
#undef FAIL
}
