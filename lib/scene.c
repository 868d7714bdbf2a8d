/* scene.c — loads the scene text format (formats/scene.md) into a pm_scene:
 * tokenizes and checks each statement, builds objects' polygons through the
 * shapes of scene_shape.c or mesh files (mesh.h), transforms them to world
 * space, and derives normals and triangles (scene_poly.h). */
#include "scene.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "maxpixels.h"
#include "mesh.h"
#include "photonfile.h"
#include "scene_id.h"
#include "scene_poly.h"
#include "scene_shape.h"

/* Bounds on what a scene may ask for; see formats/scene.md. */
#define MAX_FILE (64u << 20)        /* scene file bytes */
#define MAX_LINE 65536u             /* bytes in one line */
#define MAX_MATS 65536
#define MAX_OBJS (1 << 24)
#define MAX_LIGHTS (1 << 20)
#define MAX_VERTS (1u << 28)
#define MAX_POLYS (1u << 28)
#define MAX_TRIS (1u << 28)
#define MAX_POLY_VERTS (1u << 30)   /* polygon corners in all */

/* One affine map x -> m[0..2][0..2] x + m[.][3]. */
typedef struct { double m[3][4]; } xform;

typedef struct {
	pm_scene *s;
	pm_error *err;
	const char *path;   /* the scene file, for messages */
	char *dir;          /* its directory with a trailing '/', or "" */
	int line;
	char **tok;         /* the current line's tokens */
	int ntok, pos;
	const char *stmt;   /* the statement's keyword, for messages */
	char stmt_buf[600]; /* what stmt points to when it is not a token: it
	                       outlives the statement function that wrote it */
	/* capacities of the growing arrays in s */
	size_t cap_mats, cap_objs, cap_lights, cap_verts, cap_polys, cap_pverts, cap_tris;
	void *work;         /* triangulation scratch */
	size_t work_size;
	uint32_t (*tribuf)[3];
	size_t tribuf_n;
	int have_camera, have_threshold;
} parser;

static int
perr(parser *p, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

static int
perr(parser *p, const char *fmt, ...)
{
	char msg[sizeof p->err->msg];
	va_list ap;
	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	return pm_seterr(p->err, "%s:%d: %s", p->path, p->line, msg);
}

/* Grows *arr to hold at least need elements of size elem. */
static int
grow(parser *p, void *arrp, size_t *cap, size_t need, size_t elem)
{
	void **arr = arrp;
	if (need <= *cap)
		return 0;
	size_t n = *cap ? *cap : 16;
	while (n < need)
		n = n > SIZE_MAX / 2 ? need : n * 2;
	if (n > SIZE_MAX / elem)
		return perr(p, "out of memory");
	void *q = realloc(*arr, n * elem);
	if (!q)
		return perr(p, "out of memory");
	*arr = q;
	*cap = n;
	return 0;
}

/* ---- numbers and tokens ---- */

/* A decimal float as the format allows it: [+-] digits [. digits]
 * [e [+-] digits], with digits on at least one side of the point. */
static int
decimal_syntax(const char *t)
{
	int digits = 0;
	if (*t == '+' || *t == '-')
		t++;
	while (*t >= '0' && *t <= '9')
		t++, digits++;
	if (*t == '.')
		for (t++; *t >= '0' && *t <= '9'; t++)
			digits++;
	if (!digits)
		return 0;
	if (*t == 'e' || *t == 'E') {
		t++;
		if (*t == '+' || *t == '-')
			t++;
		if (!(*t >= '0' && *t <= '9'))
			return 0;
		while (*t >= '0' && *t <= '9')
			t++;
	}
	return *t == '\0';
}

static int
looks_nonfinite(const char *t)
{
	if (*t == '+' || *t == '-')
		t++;
	return !strcasecmp(t, "nan") || !strcasecmp(t, "inf") || !strcasecmp(t, "infinity");
}

static int
is_number(const char *t)
{
	return decimal_syntax(t) || looks_nonfinite(t);
}

static const char *
peek(parser *p)
{
	return p->pos < p->ntok ? p->tok[p->pos] : NULL;
}

/* Reads n numbers into out; after names what they follow, for messages. The
 * values must fit a float. */
static int
numbers(parser *p, int n, double *out, const char *after)
{
	for (int i = 0; i < n; i++) {
		const char *t = peek(p);
		if (!t || !is_number(t)) {
			if (n == 1)
				return perr(p, "%s: expected a number after %s", p->stmt, after);
			return perr(p, "%s: expected %d numbers after %s", p->stmt, n, after);
		}
		if (looks_nonfinite(t))
			return perr(p, "%s: '%s' is not a finite number", p->stmt, t);
		errno = 0;
		double d = strtod(t, NULL);
		if (!isfinite(d) || fabs(d) > 3.0e38)
			return perr(p, "%s: number '%s' out of range", p->stmt, t);
		out[i] = d;
		p->pos++;
	}
	return 0;
}

static int
vec3(parser *p, pm_vec3 *v, const char *after)
{
	double d[3];
	if (numbers(p, 3, d, after))
		return -1;
	*v = pm_v3((float)d[0], (float)d[1], (float)d[2]);
	return 0;
}

static int
count_numbers_ahead(parser *p)
{
	int n = 0;
	while (p->pos + n < p->ntok && is_number(p->tok[p->pos + n]))
		n++;
	return n;
}

static int
in01(pm_vec3 v)
{
	return v.x >= 0 && v.x <= 1 && v.y >= 0 && v.y <= 1 && v.z >= 0 && v.z <= 1;
}

static int
nonneg(pm_vec3 v)
{
	return v.x >= 0 && v.y >= 0 && v.z >= 0;
}

/* ---- statements ---- */

static int
st_camera(parser *p)
{
	pm_camera_desc *c = &p->s->camera;
	int seen[5] = {0};
	static const char *const words[5] = {"eye", "look", "up", "fov", "size"};

	if (p->have_camera)
		return perr(p, "camera: a second camera (there must be exactly one)");
	p->have_camera = p->line;
	while (peek(p)) {
		const char *w = peek(p);
		int k;
		for (k = 0; k < 5 && strcmp(w, words[k]); k++)
			;
		if (k == 5)
			return perr(p, "camera: unknown word '%s' (expected eye, look, up, fov or size)", w);
		if (seen[k])
			return perr(p, "camera: '%s' given twice", w);
		seen[k] = 1;
		p->pos++;
		char after[16];
		snprintf(after, sizeof after, "'%s'", w);
		double d[2];
		switch (k) {
		case 0: if (vec3(p, &c->eye, after)) return -1; break;
		case 1: if (vec3(p, &c->look, after)) return -1; break;
		case 2: if (vec3(p, &c->up, after)) return -1; break;
		case 3:
			if (numbers(p, 1, d, after))
				return -1;
			if (!(d[0] > 0 && d[0] < 180))
				return perr(p, "camera: fov must be between 0 and 180 degrees, got %g", d[0]);
			c->fov = (float)d[0];
			break;
		case 4:
			if (numbers(p, 2, d, after))
				return -1;
			for (int i = 0; i < 2; i++)
				if (!(d[i] >= 1 && d[i] <= 65535 && d[i] == floor(d[i])))
					return perr(p, "camera: size must be whole numbers from 1 to 65535, got %g", d[i]);
			c->width = (int)d[0];
			c->height = (int)d[1];
			uint64_t lim = pm_max_pixels();
			if ((uint64_t)c->width * (uint64_t)c->height > lim)
				return perr(p, "camera: size %dx%d is more than %llu pixels "
				            "(a typo? set PM_MAX_PIXELS to allow more)",
				            c->width, c->height, (unsigned long long)lim);
			break;
		}
	}
	for (int k = 0; k < 5; k++)
		if (!seen[k])
			return perr(p, "camera: missing '%s'", words[k]);
	pm_vec3 f = pm_sub(c->look, c->eye);
	if (!(pm_len(f) > 0))
		return perr(p, "camera: eye and look are the same point");
	pm_vec3 r = pm_cross(f, c->up);
	if (!(pm_len(r) > 1e-6f * pm_len(f) * pm_len(c->up)))
		return perr(p, "camera: up is zero or parallel to the view direction");
	return 0;
}

static int
st_threshold(parser *p)
{
	double d;
	if (p->have_threshold)
		return perr(p, "glossy_threshold: given twice");
	p->have_threshold = 1;
	if (numbers(p, 1, &d, "'glossy_threshold'"))
		return -1;
	if (!(d > 0))
		return perr(p, "glossy_threshold: must be > 0, got %g", d);
	if (peek(p))
		return perr(p, "glossy_threshold: unexpected '%s'", peek(p));
	p->s->glossy_threshold = (float)d;
	return 0;
}

static int
find_material(const pm_scene *s, const char *name)
{
	for (int i = 0; i < s->nmats; i++)
		if (!strcmp(s->mats[i].name, name))
			return i;
	return -1;
}

static int
st_material(parser *p)
{
	pm_scene *s = p->s;
	pm_material m;
	memset(&m, 0, sizeof m);
	const char *name = peek(p);
	if (!name)
		return perr(p, "material: expected a name");
	if (strlen(name) >= sizeof m.name)
		return perr(p, "material: name '%.20s...' longer than %zu bytes", name, sizeof m.name - 1);
	if (find_material(s, name) >= 0)
		return perr(p, "material: '%s' is defined twice", name);
	strcpy(m.name, name);
	p->pos++;
	const char *kind = peek(p);
	static const char *const kinds[4] = {"diffuse", "glossy", "mirror", "glass"};
	if (!kind)
		return perr(p, "material '%s': expected a kind (diffuse, glossy, mirror or glass)", name);
	for (m.kind = 0; m.kind < 4 && strcmp(kind, kinds[m.kind]); m.kind++)
		;
	if (m.kind == 4)
		return perr(p, "material '%s': unknown kind '%s' (expected diffuse, glossy, mirror or glass)", name, kind);
	p->pos++;

	/* Which words each kind takes; "required" ones must appear. */
	enum { W_ALBEDO, W_KD, W_KS, W_EXPONENT, W_REFLECT, W_IOR, W_TINT, W_EMIT, W_TWOSIDED, NW };
	static const char *const words[NW] = {"albedo", "kd", "ks", "exponent", "reflect",
		"ior", "tint", "emit", "twosided"};
	static const unsigned allowed[4] = {
		1u << W_ALBEDO | 1u << W_EMIT | 1u << W_TWOSIDED,
		1u << W_KD | 1u << W_KS | 1u << W_EXPONENT | 1u << W_EMIT | 1u << W_TWOSIDED,
		1u << W_REFLECT,
		1u << W_IOR | 1u << W_TINT,
	};
	static const unsigned required[4] = {
		1u << W_ALBEDO, 1u << W_KD | 1u << W_KS | 1u << W_EXPONENT, 1u << W_REFLECT, 1u << W_IOR,
	};
	unsigned seen = 0;
	double d;
	const char *stmt = p->stmt_buf;
	snprintf(p->stmt_buf, sizeof p->stmt_buf, "material '%s'", name);
	p->stmt = stmt;
	m.ks = pm_v3(1, 1, 1);  /* glass tint when none is given */
	while (peek(p)) {
		const char *w = peek(p);
		int k;
		for (k = 0; k < NW && strcmp(w, words[k]); k++)
			;
		if (k == NW || !(allowed[m.kind] >> k & 1))
			return perr(p, "%s: unexpected '%s' for a %s material", stmt, w, kinds[m.kind]);
		if (seen >> k & 1)
			return perr(p, "%s: '%s' given twice", stmt, w);
		seen |= 1u << k;
		p->pos++;
		char after[16];
		snprintf(after, sizeof after, "'%s'", w);
		switch (k) {
		case W_ALBEDO: case W_KD:
			if (vec3(p, &m.kd, after)) return -1;
			if (!in01(m.kd)) return perr(p, "%s: %s must be in [0, 1]", stmt, w);
			break;
		case W_KS: case W_REFLECT: case W_TINT:
			if (vec3(p, &m.ks, after)) return -1;
			if (!in01(m.ks)) return perr(p, "%s: %s must be in [0, 1]", stmt, w);
			break;
		case W_EXPONENT:
			if (numbers(p, 1, &d, after)) return -1;
			if (!(d > 0)) return perr(p, "%s: exponent must be > 0, got %g", stmt, d);
			m.exponent = (float)d;
			break;
		case W_IOR:
			if (numbers(p, 1, &d, after)) return -1;
			if (!(d > 0)) return perr(p, "%s: ior must be > 0, got %g", stmt, d);
			m.ior = (float)d;
			break;
		case W_EMIT:
			if (vec3(p, &m.emit, after)) return -1;
			if (!nonneg(m.emit)) return perr(p, "%s: emit must be >= 0", stmt);
			break;
		case W_TWOSIDED:
			m.emit_twosided = 1;
			break;
		}
	}
	for (int k = 0; k < NW; k++)
		if ((required[m.kind] >> k & 1) && !(seen >> k & 1))
			return perr(p, "%s: missing '%s'", stmt, words[k]);
	if (m.kind == PM_MAT_GLOSSY) {
		pm_vec3 t = pm_add(m.kd, m.ks);
		if (!(t.x <= 1 && t.y <= 1 && t.z <= 1))
			return perr(p, "%s: kd + ks exceeds 1 (the surface would create energy)", stmt);
	}
	if (s->nmats >= MAX_MATS)
		return perr(p, "material: more than %d materials", MAX_MATS);
	if (grow(p, &s->mats, &p->cap_mats, (size_t)s->nmats + 1, sizeof *s->mats))
		return -1;
	s->mats[s->nmats++] = m;
	return 0;
}

static int
st_pointlight(parser *p)
{
	pm_pointlight l;
	memset(&l, 0, sizeof l);
	int have_power = 0, have_move = 0;
	if (vec3(p, &l.pos, "'pointlight'"))
		return -1;
	while (peek(p)) {
		const char *w = peek(p);
		if (!strcmp(w, "power") && !have_power) {
			p->pos++;
			have_power = 1;
			if (vec3(p, &l.power, "'power'"))
				return -1;
			if (!nonneg(l.power) || !(pm_maxc(l.power) > 0))
				return perr(p, "pointlight: power must be >= 0 and not all zero");
		} else if (!strcmp(w, "move") && !have_move) {
			p->pos++;
			have_move = 1;
			if (vec3(p, &l.motion, "'move'"))
				return -1;
		} else if (!strcmp(w, "power") || !strcmp(w, "move")) {
			return perr(p, "pointlight: '%s' given twice", w);
		} else {
			return perr(p, "pointlight: unexpected '%s' (expected power or move)", w);
		}
	}
	if (!have_power)
		return perr(p, "pointlight: missing 'power'");
	pm_scene *s = p->s;
	if (s->nlights >= MAX_LIGHTS)
		return perr(p, "pointlight: more than %d point lights", MAX_LIGHTS);
	if (grow(p, &s->lights, &p->cap_lights, (size_t)s->nlights + 1, sizeof *s->lights))
		return -1;
	s->lights[s->nlights++] = l;
	return 0;
}

/* ---- transforms ---- */

static void
xf_identity(xform *x)
{
	memset(x, 0, sizeof *x);
	x->m[0][0] = x->m[1][1] = x->m[2][2] = 1;
}

/* x = a then x (a applied after what x already does). */
static void
xf_then(xform *x, const double a[3][4])
{
	xform r;
	for (int i = 0; i < 3; i++) {
		for (int j = 0; j < 4; j++) {
			double v = j == 3 ? a[i][3] : 0;
			for (int k = 0; k < 3; k++)
				v += a[i][k] * x->m[k][j];
			r.m[i][j] = v;
		}
	}
	*x = r;
}

static double
xf_det(const xform *x)
{
	const double (*m)[4] = x->m;
	return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
		- m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
		+ m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* The words after an object's own coordinates: transforms in the order
 * written, one optional 'move', and the shape's own flags (inward for box,
 * subdiv for sphere). */
typedef struct {
	xform xf;
	pm_vec3 motion;
	int inward;   /* -1: not allowed */
	int subdiv;   /* -1: not allowed */
} tail;

static int
parse_tail(parser *p, tail *t)
{
	int have_move = 0, have_subdiv = 0;
	xf_identity(&t->xf);
	t->motion = pm_v3(0, 0, 0);
	while (peek(p)) {
		const char *w = peek(p);
		double d[4], a[3][4];
		memset(a, 0, sizeof a);
		if (!strcmp(w, "scale")) {
			p->pos++;
			int n = count_numbers_ahead(p) >= 3 ? 3 : 1;
			if (count_numbers_ahead(p) == 2)
				return perr(p, "%s: expected 1 or 3 numbers after 'scale'", p->stmt);
			if (numbers(p, n, d, "'scale'"))
				return -1;
			for (int i = 0; i < 3; i++) {
				a[i][i] = d[n == 3 ? i : 0];
				if (a[i][i] == 0)
					return perr(p, "%s: scale must not be zero", p->stmt);
			}
			xf_then(&t->xf, a);
		} else if (!strcmp(w, "rotate")) {
			p->pos++;
			if (numbers(p, 4, d, "'rotate'"))
				return -1;
			double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
			if (!(len > 0))
				return perr(p, "%s: rotate axis must not be zero", p->stmt);
			/* Rodrigues' rotation formula: right-handed about the axis. */
			double k[3] = {d[0] / len, d[1] / len, d[2] / len};
			double th = d[3] * PM_PI / 180, c = cos(th), sn = sin(th);
			for (int i = 0; i < 3; i++)
				for (int j = 0; j < 3; j++)
					a[i][j] = (i == j ? c : 0) + (1 - c) * k[i] * k[j];
			a[0][1] -= sn * k[2]; a[0][2] += sn * k[1];
			a[1][0] += sn * k[2]; a[1][2] -= sn * k[0];
			a[2][0] -= sn * k[1]; a[2][1] += sn * k[0];
			xf_then(&t->xf, a);
		} else if (!strcmp(w, "translate")) {
			p->pos++;
			if (numbers(p, 3, d, "'translate'"))
				return -1;
			for (int i = 0; i < 3; i++) {
				a[i][i] = 1;
				a[i][3] = d[i];
			}
			xf_then(&t->xf, a);
		} else if (!strcmp(w, "move")) {
			p->pos++;
			if (have_move++)
				return perr(p, "%s: 'move' given twice", p->stmt);
			if (vec3(p, &t->motion, "'move'"))
				return -1;
		} else if (!strcmp(w, "inward") && t->inward == 0) {
			p->pos++;
			t->inward = 1;
		} else if (!strcmp(w, "subdiv") && t->subdiv >= 0) {
			p->pos++;
			if (have_subdiv++)
				return perr(p, "%s: 'subdiv' given twice", p->stmt);
			if (numbers(p, 1, d, "'subdiv'"))
				return -1;
			if (!(d[0] >= 1 && d[0] <= PM_SPHERE_MAX_SUBDIV && d[0] == floor(d[0])))
				return perr(p, "%s: subdiv must be a whole number from 1 to %d, got %g",
					p->stmt, PM_SPHERE_MAX_SUBDIV, d[0]);
			t->subdiv = (int)d[0];
		} else {
			return perr(p, "%s: unexpected '%s'", p->stmt, w);
		}
	}
	return 0;
}

/* ---- building objects ---- */

static int
add_polygon(parser *p, const uint32_t *idx, uint32_t n, pm_dvec3 nrm, uint32_t obj)
{
	pm_scene *s = p->s;
	if (s->npolys >= MAX_POLYS)
		return perr(p, "%s: more than %u polygons in the scene", p->stmt, MAX_POLYS);
	uint32_t first = s->npolys ? s->poly_start[s->npolys] : 0;
	if ((uint64_t)first + n > MAX_POLY_VERTS)
		return perr(p, "%s: more than %u polygon corners in the scene", p->stmt, MAX_POLY_VERTS);
	size_t need = (size_t)s->npolys + 2, c1 = p->cap_polys, c2 = p->cap_polys;
	if (grow(p, &s->poly_start, &p->cap_polys, need, sizeof *s->poly_start)
	    || grow(p, &s->poly_obj, &c1, need, sizeof *s->poly_obj)
	    || grow(p, &s->poly_normal, &c2, need, sizeof *s->poly_normal))
		return -1;
	if (grow(p, &s->poly_vert, &p->cap_pverts, (size_t)first + n, sizeof *s->poly_vert))
		return -1;
	memcpy(s->poly_vert + first, idx, n * sizeof *idx);
	double l = pm_dlen(nrm);
	s->poly_start[s->npolys] = first;
	s->poly_start[s->npolys + 1] = first + n;
	s->poly_obj[s->npolys] = obj;
	s->poly_normal[s->npolys] = pm_v3((float)(nrm.x / l), (float)(nrm.y / l), (float)(nrm.z / l));
	s->npolys++;
	return 0;
}

static int
add_triangle(parser *p, const uint32_t t[3])
{
	pm_scene *s = p->s;
	if (s->ntris >= MAX_TRIS)
		return perr(p, "%s: more than %u triangles in the scene", p->stmt, MAX_TRIS);
	size_t c1 = p->cap_tris;
	if (grow(p, &s->tris, &p->cap_tris, (size_t)s->ntris + 1, sizeof *s->tris)
	    || grow(p, &s->tri_poly, &c1, (size_t)s->ntris + 1, sizeof *s->tri_poly))
		return -1;
	memcpy(s->tris[s->ntris], t, sizeof s->tris[0]);
	s->tri_poly[s->ntris] = s->npolys - 1;
	s->ntris++;
	return 0;
}

/* Adds one face (scene vertex indices, already in front winding): drops it
 * if it has no area, keeps it whole if planar, else splits it. */
static int
add_face(parser *p, uint32_t *idx, uint32_t n, uint32_t obj)
{
	const pm_vec3 *v = p->s->verts;
	uint32_t m = 0;

	/* Repeated positions in a row (and around the end) would make zero
	 * length edges. */
	for (uint32_t i = 0; i < n; i++) {
		pm_vec3 a = v[idx[i]];
		if (m > 0) {
			pm_vec3 b = v[idx[m - 1]];
			if (a.x == b.x && a.y == b.y && a.z == b.z)
				continue;
		}
		idx[m++] = idx[i];
	}
	while (m > 1) {
		pm_vec3 a = v[idx[m - 1]], b = v[idx[0]];
		if (!(a.x == b.x && a.y == b.y && a.z == b.z))
			break;
		m--;
	}
	if (m < 3 || pm_poly_degenerate(v, idx, m))
		return 0;

	if (grow(p, &p->work, &p->work_size, PM_POLY_WORK_BYTES(m), 1)
	    || grow(p, &p->tribuf, &p->tribuf_n, m, sizeof *p->tribuf))
		return -1;
	pm_dvec3 nrm = pm_poly_newell(v, idx, m);
	uint32_t nt = pm_poly_triangulate(v, idx, m, nrm, p->tribuf, p->work);
	if (pm_poly_planar(v, idx, m, nrm)) {
		if (add_polygon(p, idx, m, nrm, obj))
			return -1;
		for (uint32_t i = 0; i < nt; i++)
			if (add_triangle(p, p->tribuf[i]))
				return -1;
		return 0;
	}
	/* Not planar: every triangle becomes a polygon of its own. */
	for (uint32_t i = 0; i < nt; i++) {
		if (pm_poly_degenerate(v, p->tribuf[i], 3))
			continue;
		if (add_polygon(p, p->tribuf[i], 3, pm_poly_newell(v, p->tribuf[i], 3), obj)
		    || add_triangle(p, p->tribuf[i]))
			return -1;
	}
	return 0;
}

/* Appends an object made of the shape sh (its vertices in object space) with
 * tail t; solid says whether it is a closed surface. */
static int
add_object(parser *p, int mat, const pm_shape *sh, const tail *t, int solid, int flip)
{
	pm_scene *s = p->s;
	if (s->nobjs >= MAX_OBJS)
		return perr(p, "%s: more than %d objects", p->stmt, MAX_OBJS);
	if ((uint64_t)s->nverts + sh->nverts > MAX_VERTS)
		return perr(p, "%s: more than %u vertices in the scene", p->stmt, MAX_VERTS);
	if (grow(p, &s->objs, &p->cap_objs, (size_t)s->nobjs + 1, sizeof *s->objs)
	    || grow(p, &s->verts, &p->cap_verts, (size_t)s->nverts + sh->nverts, sizeof *s->verts))
		return -1;

	uint32_t base = s->nverts;
	const double (*m)[4] = t->xf.m;
	for (uint32_t i = 0; i < sh->nverts; i++) {
		const double *x = sh->verts + 3 * (size_t)i;
		double w[3];
		for (int k = 0; k < 3; k++)
			w[k] = m[k][0] * x[0] + m[k][1] * x[1] + m[k][2] * x[2] + m[k][3];
		pm_vec3 f = pm_v3((float)w[0], (float)w[1], (float)w[2]);
		if (!pm_vfinite(f) || fabs(w[0]) > 3e38 || fabs(w[1]) > 3e38 || fabs(w[2]) > 3e38)
			return perr(p, "%s: vertex coordinates out of range", p->stmt);
		s->verts[base + i] = f;
	}
	s->nverts += sh->nverts;

	/* A mirroring transform turns counter-clockwise into clockwise:
	 * reverse the faces so normals still point the way they did. */
	if (xf_det(&t->xf) < 0)
		flip = !flip;

	pm_object *o = &s->objs[s->nobjs];
	memset(o, 0, sizeof *o);
	o->material = mat;
	o->solid = solid;
	o->motion = t->motion;
	o->first_poly = s->npolys;
	o->first_tri = s->ntris;
	o->first_vert = base;
	o->nverts = sh->nverts;
	o->line = p->line;

	uint32_t *idx = NULL;
	size_t cap = 0;
	for (uint32_t f = 0; f < sh->nfaces; f++) {
		uint32_t a = sh->face_start[f], n = sh->face_start[f + 1] - a;
		if (grow(p, &idx, &cap, n ? n : 1, sizeof *idx)) {
			free(idx);
			return -1;
		}
		for (uint32_t i = 0; i < n; i++)
			idx[i] = base + sh->face_vert[a + (flip ? n - 1 - i : i)];
		if (add_face(p, idx, n, (uint32_t)s->nobjs)) {
			free(idx);
			return -1;
		}
	}
	free(idx);
	o->npolys = s->npolys - o->first_poly;
	o->ntris = s->ntris - o->first_tri;
	if (o->npolys == 0)
		return perr(p, "%s: no polygon with nonzero area", p->stmt);
	s->nobjs++;
	return 0;
}

static int
material_arg(parser *p, int *mat)
{
	const char *name = peek(p);
	if (!name)
		return perr(p, "%s: expected a material name", p->stmt);
	*mat = find_material(p->s, name);
	if (*mat < 0)
		return perr(p, "%s: unknown material '%s'", p->stmt, name);
	p->pos++;
	return 0;
}

static int
st_quad(parser *p)
{
	int mat;
	double c[12];
	tail t = {.inward = -1, .subdiv = -1};
	if (material_arg(p, &mat) || numbers(p, 12, c, "the material"))
		return -1;
	if (parse_tail(p, &t))
		return -1;
	int why = pm_shape_quad_check(c);
	if (why)
		return perr(p, "quad: %s", pm_shape_quad_problem(why));
	pm_shape sh;
	if (pm_shape_polygon(&sh, c, 4))
		return perr(p, "out of memory");
	int r = add_object(p, mat, &sh, &t, 0, 0);
	pm_shape_free(&sh);
	return r;
}

static int
st_triangle(parser *p)
{
	int mat;
	double c[9];
	tail t = {.inward = -1, .subdiv = -1};
	if (material_arg(p, &mat) || numbers(p, 9, c, "the material"))
		return -1;
	if (parse_tail(p, &t))
		return -1;
	pm_dvec3 a = pm_dv3(c[0], c[1], c[2]);
	pm_dvec3 e1 = pm_dsub(pm_dv3(c[3], c[4], c[5]), a), e2 = pm_dsub(pm_dv3(c[6], c[7], c[8]), a);
	double size = fmax(pm_dlen(e1), pm_dlen(e2));
	if (!(pm_dlen(pm_dcross(e1, e2)) > 1e-9 * size * size))
		return perr(p, "triangle: zero area (corners coincide or lie on a line)");
	pm_shape sh;
	if (pm_shape_polygon(&sh, c, 3))
		return perr(p, "out of memory");
	int r = add_object(p, mat, &sh, &t, 0, 0);
	pm_shape_free(&sh);
	return r;
}

static int
st_box(parser *p)
{
	int mat;
	double c[6];
	tail t = {.inward = 0, .subdiv = -1};
	if (material_arg(p, &mat) || numbers(p, 6, c, "the material"))
		return -1;
	if (parse_tail(p, &t))
		return -1;
	for (int k = 0; k < 3; k++)
		if (!(c[k] < c[k + 3]))
			return perr(p, "box: the first corner must be below the second in x, y and z");
	pm_shape sh;
	if (pm_shape_box(&sh, c))
		return perr(p, "out of memory");
	int r = add_object(p, mat, &sh, &t, 1, t.inward);
	pm_shape_free(&sh);
	return r;
}

static int
st_sphere(parser *p)
{
	int mat;
	double c[4];
	tail t = {.inward = -1, .subdiv = 0};
	if (material_arg(p, &mat) || numbers(p, 4, c, "the material"))
		return -1;
	if (!(c[3] > 0))
		return perr(p, "sphere: radius must be > 0, got %g", c[3]);
	if (parse_tail(p, &t))
		return -1;
	pm_shape sh;
	if (pm_shape_sphere(&sh, c, t.subdiv ? t.subdiv : PM_SPHERE_DEFAULT_SUBDIV))
		return perr(p, "out of memory");
	int r = add_object(p, mat, &sh, &t, 1, 0);
	pm_shape_free(&sh);
	return r;
}

static int
st_mesh(parser *p)
{
	const char *file = peek(p);
	int mat;
	tail t = {.inward = -1, .subdiv = -1};
	if (!file)
		return perr(p, "mesh: expected a file name");
	p->pos++;
	if (material_arg(p, &mat) || parse_tail(p, &t))
		return -1;

	size_t len = strlen(p->dir) + strlen(file) + 1;
	char *path = malloc(len);
	if (!path)
		return perr(p, "out of memory");
	snprintf(path, len, "%s%s", file[0] == '/' ? "" : p->dir, file);
	pm_meshdata md;
	if (pm_mesh_read(path, &md, p->err)) {
		pm_mesh_free(&md);
		free(path);
		return pm_preferr(p->err, "%s:%d", p->path, p->line);
	}
	pm_shape sh = {md.nverts, md.verts, md.nfaces, md.face_start, md.face_vert};
	/* Messages about the mesh's geometry name the file. */
	snprintf(p->stmt_buf, sizeof p->stmt_buf, "mesh '%s'", path);
	p->stmt = p->stmt_buf;
	int r = add_object(p, mat, &sh, &t, md.closed, 0);
	pm_mesh_free(&md);
	free(path);
	return r;
}

/* Splits line (NUL-terminated, comment already cut) into p->tok. */
static void
tokenize(parser *p, char *line)
{
	p->ntok = 0;
	p->pos = 0;
	for (char *c = line; *c;) {
		while (*c == ' ' || *c == '\t' || *c == '\r' || *c == '\v' || *c == '\f')
			*c++ = '\0';
		if (!*c)
			break;
		p->tok[p->ntok++] = c;
		while (*c && !(*c == ' ' || *c == '\t' || *c == '\r' || *c == '\v' || *c == '\f'))
			c++;
	}
}

static int
statement(parser *p)
{
	static const struct {
		const char *word;
		int (*fn)(parser *);
	} st[] = {
		{"camera", st_camera}, {"glossy_threshold", st_threshold},
		{"material", st_material}, {"mesh", st_mesh}, {"quad", st_quad}, {"triangle", st_triangle},
		{"box", st_box}, {"sphere", st_sphere}, {"pointlight", st_pointlight},
	};
	const char *w = p->tok[0];
	for (size_t i = 0; i < sizeof st / sizeof st[0]; i++)
		if (!strcmp(w, st[i].word)) {
			p->stmt = w;
			p->pos = 1;
			return st[i].fn(p);
		}
	return perr(p, "unknown statement '%s'", w);
}

static int
read_file(const char *path, char **data, size_t *len, pm_error *err)
{
	FILE *f = fopen(path, "rb");
	struct stat st;
	if (!f)
		return pm_seterr(err, "cannot open '%s': %s", path, strerror(errno));
	if (fstat(fileno(f), &st) || !S_ISREG(st.st_mode)) {
		fclose(f);
		return pm_seterr(err, "cannot read '%s': not a regular file", path);
	}
	if ((uint64_t)st.st_size > MAX_FILE) {
		fclose(f);
		return pm_seterr(err, "'%s': scene file larger than %u MiB", path, MAX_FILE >> 20);
	}
	char *b = malloc((size_t)st.st_size + 1);
	if (!b) {
		fclose(f);
		return pm_seterr(err, "'%s': out of memory", path);
	}
	size_t n = fread(b, 1, (size_t)st.st_size + 1, f);
	int bad = ferror(f);
	fclose(f);
	if (bad || n > (size_t)st.st_size) {
		free(b);
		return pm_seterr(err, "cannot read '%s': %s", path, bad ? "read error" : "file grew while reading");
	}
	b[n] = '\0';
	*data = b;
	*len = n;
	return 0;
}

static int
parse(parser *p, char *data, size_t len)
{
	pm_scene *s = p->s;
	char *c = data, *end = data + len;

	p->line = 0;
	while (c < end) {
		char *nl = memchr(c, '\n', (size_t)(end - c));
		char *e = nl ? nl : end;
		p->line++;
		if ((size_t)(e - c) > MAX_LINE)
			return perr(p, "line longer than %u bytes", MAX_LINE);
		if (memchr(c, '\0', (size_t)(e - c)))
			return perr(p, "line contains a NUL byte (not a text file?)");
		*e = '\0';
		char *hash = strchr(c, '#');
		if (hash)
			*hash = '\0';
		tokenize(p, c);
		if (p->ntok > 0 && statement(p))
			return -1;
		c = e + 1;
	}
	if (p->line == 0)
		p->line = 1;
	/* Whole-file checks, reported at the last line. */
	if (!p->have_camera)
		return perr(p, "no camera (a scene needs exactly one 'camera' line)");
	int lit = s->nlights > 0;
	for (int i = 0; i < s->nobjs && !lit; i++)
		lit = pm_maxc(s->mats[s->objs[i].material].emit) > 0;
	if (!lit)
		return perr(p, "no light (add a pointlight or an object with an emitting material)");
	for (int i = 0; i < s->nmats; i++) {
		pm_material *m = &s->mats[i];
		m->strong = m->kind == PM_MAT_MIRROR || m->kind == PM_MAT_GLASS
			|| (m->kind == PM_MAT_GLOSSY && m->exponent >= s->glossy_threshold);
	}
	return 0;
}

int
pm_scene_load(pm_scene *s, const char *path, pm_error *err)
{
	parser p;
	char *data = NULL;
	size_t len = 0;
	int r = -1;

	memset(s, 0, sizeof *s);
	memset(&p, 0, sizeof p);
	p.s = s;
	p.err = err;
	p.path = path;
	s->glossy_threshold = 100;
	if (read_file(path, &data, &len, err))
		return -1;
	if (len >= sizeof PM_PHOTONS_MAGIC - 1 && !memcmp(data, PM_PHOTONS_MAGIC, sizeof PM_PHOTONS_MAGIC - 1)) {
		free(data);
		return pm_seterr(err, "'%s': a photon file, not a scene", path);
	}
	s->path = strdup(path);
	const char *slash = strrchr(path, '/');
	size_t dl = slash ? (size_t)(slash - path) + 1 : 0;
	p.dir = malloc(dl + 1);
	p.tok = malloc((MAX_LINE / 2 + 2) * sizeof *p.tok);
	if (!s->path || !p.dir || !p.tok) {
		pm_seterr(err, "'%s': out of memory", path);
		goto out;
	}
	memcpy(p.dir, path, dl);
	p.dir[dl] = '\0';
	r = parse(&p, data, len);
	if (r == 0 && s->npolys == 0) {
		/* Keep the array contract (npolys + 1 entries) for empty scenes. */
		s->poly_start = calloc(1, sizeof *s->poly_start);
		if (!s->poly_start)
			r = pm_seterr(err, "'%s': out of memory", path);
	}
	if (r == 0)
		pm_scene_identify(s);
out:
	free(data);
	free(p.dir);
	free(p.tok);
	free(p.work);
	free(p.tribuf);
	if (r)
		pm_scene_free(s);
	return r;
}

void
pm_scene_free(pm_scene *s)
{
	free(s->path);
	free(s->mats);
	free(s->objs);
	free(s->lights);
	free(s->verts);
	free(s->poly_start);
	free(s->poly_vert);
	free(s->poly_obj);
	free(s->poly_normal);
	free(s->tris);
	free(s->tri_poly);
	memset(s, 0, sizeof *s);
}

void
pm_scene_verts_at(const pm_scene *s, float t, pm_vec3 *out)
{
	for (int o = 0; o < s->nobjs; o++) {
		const pm_object *ob = &s->objs[o];
		pm_vec3 d = pm_scale(ob->motion, t);
		for (uint32_t i = ob->first_vert; i < ob->first_vert + ob->nverts; i++)
			out[i] = pm_add(s->verts[i], d);
	}
}

pm_vec3
pm_scene_light_at(const pm_scene *s, int i, float t)
{
	return pm_add(s->lights[i].pos, pm_scale(s->lights[i].motion, t));
}
