/* scene.c — the parsing half of the scene loader: reads the scene text
 * format (formats/scene.md) line by line, tokenizes and checks each
 * statement, loads mesh files (mesh.h) and shapes (scene_shape.h), and hands
 * the checked values to scene_build.h, which owns the arrays. */
#include "scene/scene.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "base/maxpixels.h"
#include "scene/imagefile.h"
#include "scene/mesh.h"
#include "formats/photonfile.h"
#include "scene/scene_build.h"
#include "scene/scene_id.h"
#include "scene/scene_orient.h"
#include "scene/scene_limits.h"
#include "scene/texfilter.h"

/* Bounds on what a scene may ask for; see formats/scene.md. */
#define MAX_FILE (64u << 20)        /* scene file bytes */
#define MAX_LINE 65536u             /* bytes in one line */

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
	pm_scene_build *b;  /* the arrays, grown as statements are read */
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

/* A builder's message, at the current line. */
static int
berr(parser *p, const pm_error *e)
{
	return perr(p, "%s", e->msg);
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
	pm_error e;
	if (pm_limits_camera(c, &e))
		return berr(p, &e);
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
find_texture(const pm_scene *s, const char *name)
{
	for (int i = 0; i < s->ntexs; i++)
		if (!strcmp(s->texs[i].name, name))
			return i;
	return -1;
}

/* The largest of a texture's values (each the mean of R, G, B) and, in
 * *lo, the smallest. */
static float
tex_range(const pm_texture *t, float *lo)
{
	float hi;
	if (t->kind == PM_TEX_CHECKER) {
		float a = pm_lum(t->c1), b = pm_lum(t->c2);
		*lo = fminf(a, b);
		return fmaxf(a, b);
	}
	*lo = INFINITY;
	hi = -INFINITY;
	for (size_t i = 0; i < (size_t)t->w * t->h; i++) {
		float v = (t->px[3 * i] + t->px[3 * i + 1] + t->px[3 * i + 2]) / 3;
		*lo = fminf(*lo, v);
		hi = fmaxf(hi, v);
	}
	return hi;
}

static float
tex_max(const pm_texture *t)
{
	float lo;
	return tex_range(t, &lo);
}

/* "tex NAME" where a material takes a colour or (scalar) a number: *slot
 * gets the texture's index plus 1. A scalar texture must be > 0 throughout. */
static int
tex_arg(parser *p, int *slot, int scalar)
{
	p->pos++;
	const char *name = peek(p);
	if (!name)
		return perr(p, "%s: expected a texture name after 'tex'", p->stmt);
	int i = find_texture(p->s, name);
	if (i < 0)
		return perr(p, "%s: unknown texture '%s'", p->stmt, name);
	p->pos++;
	float lo;
	tex_range(&p->s->texs[i], &lo);
	if (scalar && !(lo > 0))
		return perr(p, "%s: texture '%s' has values <= 0 (an exponent must be > 0)", p->stmt, name);
	*slot = i + 1;
	return 0;
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
			if (peek(p) && !strcmp(peek(p), "tex")) {
				if (tex_arg(p, &m.tkd, 0)) return -1;
				m.kd = pm_v3(0.5f, 0.5f, 0.5f);
				break;
			}
			if (vec3(p, &m.kd, after)) return -1;
			if (!in01(m.kd)) return perr(p, "%s: %s must be in [0, 1]", stmt, w);
			break;
		case W_KS: case W_REFLECT: case W_TINT:
			if (peek(p) && !strcmp(peek(p), "tex")) {
				if (tex_arg(p, &m.tks, 0)) return -1;
				m.ks = pm_v3(0.5f, 0.5f, 0.5f);
				break;
			}
			if (vec3(p, &m.ks, after)) return -1;
			if (!in01(m.ks)) return perr(p, "%s: %s must be in [0, 1]", stmt, w);
			break;
		case W_EXPONENT:
			if (peek(p) && !strcmp(peek(p), "tex")) {
				if (tex_arg(p, &m.texp, 1)) return -1;
				m.exponent = tex_max(&s->texs[m.texp - 1]);
				break;
			}
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
	if (m.kind == PM_MAT_GLOSSY && !m.tkd && !m.tks) {
		pm_vec3 t = pm_add(m.kd, m.ks);
		if (!(t.x <= 1 && t.y <= 1 && t.z <= 1))
			return perr(p, "%s: kd + ks exceeds 1 (the surface would create energy)", stmt);
	}
	pm_error e;
	if (pm_build_material(p->b, &m, &e))
		return berr(p, &e);
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
	pm_error e;
	if (pm_build_light(p->b, &l, &e))
		return berr(p, &e);
	return 0;
}

/* The words after an object's own coordinates: transforms in the order
 * written, one optional 'move', and the shape's own flags (inward for box,
 * subdiv for sphere). */
typedef struct {
	pm_xform xf;
	pm_vec3 motion;
	int inward;   /* -1: not allowed */
	int subdiv;   /* -1: not allowed */
	int shading;  /* 0: not allowed; else SHADE_* */
} tail;

/* An object's shading normals: as its shape gives them (a mesh file's),
 * computed from its faces (smooth), or none (flat). */
enum { SHADE_DEFAULT = 1, SHADE_SMOOTH, SHADE_FLAT };

/* The rotation by d[3] degrees about the axis d[0..2] into a (which is
 * zeroed, translation included). */
static int
rotation(parser *p, const double d[4], double a[3][4])
{
	double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
	if (!(len > 0))
		return perr(p, "%s: rotate axis must not be zero", p->stmt);
	/* Rodrigues' rotation formula: right-handed about the axis. */
	double k[3] = {d[0] / len, d[1] / len, d[2] / len};
	double th = d[3] * PM_PI / 180, c = cos(th), sn = sin(th);
	memset(a, 0, 3 * sizeof a[0]);
	for (int i = 0; i < 3; i++)
		for (int j = 0; j < 3; j++)
			a[i][j] = (i == j ? c : 0) + (1 - c) * k[i] * k[j];
	a[0][1] -= sn * k[2]; a[0][2] += sn * k[1];
	a[1][0] += sn * k[2]; a[1][2] -= sn * k[0];
	a[2][0] -= sn * k[1]; a[2][1] += sn * k[0];
	return 0;
}

static int
parse_tail(parser *p, tail *t)
{
	int have_move = 0, have_subdiv = 0;
	pm_xform_identity(&t->xf);
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
			pm_xform_then(&t->xf, a);
		} else if (!strcmp(w, "rotate")) {
			p->pos++;
			if (numbers(p, 4, d, "'rotate'"))
				return -1;
			if (rotation(p, d, a))
				return -1;
			pm_xform_then(&t->xf, a);
		} else if (!strcmp(w, "translate")) {
			p->pos++;
			if (numbers(p, 3, d, "'translate'"))
				return -1;
			for (int i = 0; i < 3; i++) {
				a[i][i] = 1;
				a[i][3] = d[i];
			}
			pm_xform_then(&t->xf, a);
		} else if (!strcmp(w, "move")) {
			p->pos++;
			if (have_move++)
				return perr(p, "%s: 'move' given twice", p->stmt);
			if (vec3(p, &t->motion, "'move'"))
				return -1;
		} else if ((!strcmp(w, "smooth") || !strcmp(w, "flat")) && t->shading) {
			p->pos++;
			if (t->shading != SHADE_DEFAULT)
				return perr(p, "%s: 'smooth' or 'flat' given twice", p->stmt);
			t->shading = w[0] == 's' ? SHADE_SMOOTH : SHADE_FLAT;
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

/* Appends an object made of the shape sh (its vertices in object space) with
 * tail t; solid says whether it is a closed surface. */
static int
add_object(parser *p, int mat, const pm_shape *sh, const tail *t, int solid, int flip)
{
	int normals = t->shading == SHADE_SMOOTH && !sh->normals ? PM_NORMALS_SMOOTH
	            : t->shading != SHADE_FLAT && sh->normals ? PM_NORMALS_SHAPE : PM_NORMALS_FLAT;
	pm_build_obj ob = {sh, t->xf, t->motion, mat, solid, flip, p->line, p->stmt, normals};
	pm_error e;
	if (pm_build_object(p->b, &ob, &e))
		return berr(p, &e);
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

/* The corners of a quad (n = 4) or a triangle (n = 3) after the material,
 * and the statement's tail, into *mat, c and *t; -1 with the error said. */
static int
flat_args(parser *p, int n, int *mat, double *c, tail *t)
{
	*t = (tail){.inward = -1, .subdiv = -1};
	if (material_arg(p, mat) || numbers(p, 3 * n, c, "the material"))
		return -1;
	return parse_tail(p, t);
}

/* A flat polygon of n corners c, each with its uv from uv, as an object. */
static int
add_flat(parser *p, int mat, const double *c, int n, const double *uv, const tail *t)
{
	pm_shape sh;
	size_t sz = 2 * (size_t)n * sizeof *uv;
	if (pm_shape_polygon(&sh, c, n) || !(sh.uv = malloc(sz))) {
		pm_shape_free(&sh);
		return perr(p, "out of memory");
	}
	memcpy(sh.uv, uv, sz);
	int r = add_object(p, mat, &sh, t, 0, 0);
	pm_shape_free(&sh);
	return r;
}

static int
st_quad(parser *p)
{
	static const double quv[8] = {0, 0, 1, 0, 1, 1, 0, 1};
	int mat;
	double c[12];
	tail t;
	if (flat_args(p, 4, &mat, c, &t))
		return -1;
	int why = pm_shape_quad_check(c);
	if (why)
		return perr(p, "quad: %s", pm_shape_quad_problem(why));
	return add_flat(p, mat, c, 4, quv, &t);
}

static int
st_triangle(parser *p)
{
	static const double tuv[6] = {0, 0, 1, 0, 0, 1};
	int mat;
	double c[9];
	tail t;
	if (flat_args(p, 3, &mat, c, &t))
		return -1;
	pm_dvec3 a = pm_dv3(c[0], c[1], c[2]);
	pm_dvec3 e1 = pm_dsub(pm_dv3(c[3], c[4], c[5]), a), e2 = pm_dsub(pm_dv3(c[6], c[7], c[8]), a);
	double size = fmax(pm_dlen(e1), pm_dlen(e2));
	if (!(pm_dlen(pm_dcross(e1, e2)) > 1e-9 * size * size))
		return perr(p, "triangle: zero area (corners coincide or lie on a line)");
	return add_flat(p, mat, c, 3, tuv, &t);
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
	tail t = {.inward = -1, .subdiv = 0, .shading = SHADE_DEFAULT};
	if (material_arg(p, &mat) || numbers(p, 4, c, "the material"))
		return -1;
	if (!(c[3] > 0))
		return perr(p, "sphere: radius must be > 0, got %g", c[3]);
	if (parse_tail(p, &t))
		return -1;
	pm_shape sh;
	if (pm_shape_sphere(&sh, c, t.subdiv ? t.subdiv : PM_SPHERE_DEFAULT_SUBDIV))
		return perr(p, "out of memory");
	/* Smooth: the true sphere's normals at the vertices. */
	if (t.shading == SHADE_SMOOTH && !(sh.normals = malloc(3 * (size_t)sh.nverts * sizeof *sh.normals))) {
		pm_shape_free(&sh);
		return perr(p, "out of memory");
	}
	for (uint32_t i = 0; sh.normals && i < 3 * sh.nverts; i++)
		sh.normals[i] = (sh.verts[i] - c[i % 3]) / c[3];
	int r = add_object(p, mat, &sh, &t, 1, 0);
	pm_shape_free(&sh);
	return r;
}

static int
st_mesh(parser *p)
{
	const char *file = peek(p);
	int mat;
	tail t = {.inward = -1, .subdiv = -1, .shading = SHADE_DEFAULT};
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
	/* smooth: normals computed from the faces, not the file's. */
	pm_shape sh = {md.nverts, md.verts, md.nfaces, md.face_start, md.face_vert,
	               t.shading == SHADE_SMOOTH ? NULL : md.normals, md.uv};
	/* Messages about the mesh's geometry name the file. */
	snprintf(p->stmt_buf, sizeof p->stmt_buf, "mesh '%s'", path);
	p->stmt = p->stmt_buf;
	int r = add_object(p, mat, &sh, &t, md.closed, 0);
	pm_mesh_free(&md);
	free(path);
	return r;
}

/* Reads the image file (relative to the scene's directory) for statement
 * what, every texel times scale, each of which must then be a finite value
 * >= 0. */
static int
image_arg(parser *p, const char *file, float scale, pm_rgbimage *im)
{
	size_t len = strlen(p->dir) + strlen(file) + 1;
	char *path = malloc(len);
	if (!path)
		return perr(p, "out of memory");
	snprintf(path, len, "%s%s", file[0] == '/' ? "" : p->dir, file);
	if (pm_rgbimage_read(path, im, p->err)) {
		free(path);
		return pm_preferr(p->err, "%s:%d", p->path, p->line);
	}
	for (size_t i = 0; i < (size_t)im->w * im->h * 3; i++) {
		float v = im->px[i] * scale;
		if (!(v >= 0 && v <= 3e38f)) {
			int r = perr(p, "%s: '%s': texel (%zu, %zu) is %g, not a finite value >= 0", p->stmt,
			             path, i / 3 % (size_t)im->w, i / 3 / (size_t)im->w, (double)v);
			free(path);
			pm_rgbimage_free(im);
			return r;
		}
		im->px[i] = v;
	}
	free(path);
	return 0;
}

static int
st_texture(parser *p)
{
	pm_texture t;
	memset(&t, 0, sizeof t);
	t.su = t.sv = 1;
	const char *name = peek(p), *kind, *file = NULL;
	int have_scale = 0, have_offset = 0;
	double d[2];
	if (!name)
		return perr(p, "texture: expected a name");
	if (strlen(name) >= sizeof t.name)
		return perr(p, "texture: name '%.20s...' longer than %zu bytes", name, sizeof t.name - 1);
	if (find_texture(p->s, name) >= 0)
		return perr(p, "texture: '%s' is defined twice", name);
	strcpy(t.name, name);
	p->pos++;
	kind = peek(p);
	if (kind && !strcmp(kind, "image")) {
		t.kind = PM_TEX_IMAGE;
		p->pos++;
		if (!(file = peek(p)))
			return perr(p, "texture: expected a file name after 'image'");
		p->pos++;
	} else if (kind && !strcmp(kind, "checker")) {
		t.kind = PM_TEX_CHECKER;
		p->pos++;
		if (vec3(p, &t.c1, "'checker'") || vec3(p, &t.c2, "'checker'"))
			return -1;
		if (!nonneg(t.c1) || !nonneg(t.c2))
			return perr(p, "texture: checker colours must be >= 0");
	} else {
		return perr(p, "texture '%s': expected 'image' or 'checker'", name);
	}
	while (peek(p)) {
		const char *w = peek(p);
		int sc = !strcmp(w, "scale");
		if (!sc && strcmp(w, "offset"))
			return perr(p, "texture: unexpected '%s' (expected scale or offset)", w);
		if (sc ? have_scale++ : have_offset++)
			return perr(p, "texture: '%s' given twice", w);
		p->pos++;
		if (numbers(p, 2, d, sc ? "'scale'" : "'offset'"))
			return -1;
		if (sc) {
			t.su = (float)d[0];
			t.sv = (float)d[1];
		} else {
			t.ou = (float)d[0];
			t.ov = (float)d[1];
		}
	}
	if (file) {
		pm_rgbimage im;
		if (image_arg(p, file, 1, &im))
			return -1;
		t.w = im.w;
		t.h = im.h;
		t.px = im.px;
		if (!(t.filt = pm_texfilter_new(t.w, t.h, t.px))) {
			free(t.px);
			return perr(p, "texture '%s': OpenImageIO's TextureSystem refused it", name);
		}
	}
	pm_error e;
	if (pm_build_texture(p->b, &t, &e)) {
		pm_texfilter_free(t.filt);
		free(t.px);
		return berr(p, &e);
	}
	return 0;
}

static int
st_disk(parser *p)
{
	int mat;
	double c[7];
	tail t = {.inward = -1, .subdiv = -1};
	if (material_arg(p, &mat) || numbers(p, 7, c, "the material"))
		return -1;
	if (!(c[6] > 0))
		return perr(p, "disk: radius must be > 0, got %g", c[6]);
	pm_dvec3 n = pm_dv3(c[3], c[4], c[5]);
	if (!(pm_dlen(n) > 0))
		return perr(p, "disk: the normal must not be zero");
	if (parse_tail(p, &t))
		return -1;
	pm_shape sh;
	if (pm_shape_disk(&sh, pm_dv3(c[0], c[1], c[2]), n, c[6]))
		return perr(p, "out of memory");
	int r = add_object(p, mat, &sh, &t, 0, 0);
	pm_shape_free(&sh);
	return r;
}

/* A light's colour after word w: each channel >= 0, not all 0. */
static int
light_colour(parser *p, pm_vec3 *v, const char *w)
{
	char after[24];
	snprintf(after, sizeof after, "'%s'", w);
	if (vec3(p, v, after))
		return -1;
	if (!nonneg(*v) || !(pm_maxc(*v) > 0))
		return perr(p, "%s: %s must be >= 0 and not all zero", p->stmt, w);
	return 0;
}

/* The index of w in words (n of them), after checking it was not seen. */
static int
light_word(parser *p, const char *const *words, int n, unsigned *seen)
{
	const char *w = peek(p);
	int k;
	for (k = 0; k < n && strcmp(w, words[k]); k++)
		;
	if (k == n) {
		char list[200] = "";
		for (int i = 0; i < n; i++)
			snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s",
			         i == 0 ? "" : i == n - 1 ? " or " : ", ", words[i]);
		return perr(p, "%s: unexpected '%s' (expected %s)", p->stmt, w, list);
	}
	if (*seen >> k & 1)
		return perr(p, "%s: '%s' given twice", p->stmt, w);
	*seen |= 1u << k;
	p->pos++;
	return k;
}

static int
st_spotlight(parser *p)
{
	enum { W_TO, W_INTENSITY, W_CONE, W_FALLOFF, W_MOVE, NW };
	static const char *const words[NW] = {"to", "intensity", "cone", "falloff", "move"};
	pm_pointlight l;
	pm_vec3 to = {0};
	unsigned seen = 0;
	double d[2];
	memset(&l, 0, sizeof l);
	l.kind = PM_LIGHT_SPOT;
	if (vec3(p, &l.pos, "'spotlight'"))
		return -1;
	while (peek(p)) {
		int k = light_word(p, words, NW, &seen);
		const char *f;
		switch (k) {
		case W_TO:
			if (vec3(p, &to, "'to'"))
				return -1;
			break;
		case W_INTENSITY:
			if (light_colour(p, &l.power, "intensity"))
				return -1;
			break;
		case W_CONE:
			if (numbers(p, 2, d, "'cone'"))
				return -1;
			if (!(d[0] > 0 && d[0] <= 90 && d[1] >= 0 && d[1] <= d[0]))
				return perr(p, "spotlight: cone needs 0 < OUTER <= 90 and 0 <= INNER <= OUTER degrees, got %g %g",
				            d[0], d[1]);
			l.outer = (float)d[0];
			l.inner = (float)d[1];
			break;
		case W_FALLOFF:
			f = peek(p);
			if (f && !strcmp(f, "smooth"))
				l.falloff = PM_FALLOFF_SMOOTH;
			else if (f && !strcmp(f, "linear"))
				l.falloff = PM_FALLOFF_LINEAR;
			else
				return perr(p, "spotlight: falloff must be smooth or linear");
			p->pos++;
			break;
		case W_MOVE:
			if (vec3(p, &l.motion, "'move'"))
				return -1;
			break;
		default:
			return -1;
		}
	}
	for (int k = 0; k < W_FALLOFF; k++)
		if (!(seen >> k & 1))
			return perr(p, "spotlight: missing '%s'", words[k]);
	l.dir = pm_sub(to, l.pos);
	if (!(pm_len(l.dir) > 0))
		return perr(p, "spotlight: 'to' is the light's own position (no direction)");
	l.dir = pm_norm(l.dir);
	pm_error e;
	if (pm_build_light(p->b, &l, &e))
		return berr(p, &e);
	return 0;
}

static int
st_distantlight(parser *p)
{
	enum { W_DIR, W_IRRADIANCE, NW };
	static const char *const words[NW] = {"dir", "irradiance"};
	pm_pointlight l;
	unsigned seen = 0;
	memset(&l, 0, sizeof l);
	l.kind = PM_LIGHT_DISTANT;
	while (peek(p)) {
		int k = light_word(p, words, NW, &seen);
		if (k < 0)
			return -1;
		if (k == W_DIR ? vec3(p, &l.dir, "'dir'") : light_colour(p, &l.power, "irradiance"))
			return -1;
		if (k == W_DIR && !(pm_len(l.dir) > 0))
			return perr(p, "distantlight: dir must not be zero");
	}
	for (int k = 0; k < NW; k++)
		if (!(seen >> k & 1))
			return perr(p, "distantlight: missing '%s'", words[k]);
	l.dir = pm_norm(l.dir);
	pm_error e;
	if (pm_build_light(p->b, &l, &e))
		return berr(p, &e);
	return 0;
}

static int
st_envlight(parser *p)
{
	pm_pointlight l;
	const char *w = peek(p), *file = NULL;
	double scale = 1, d[4], a[3][4];
	int have_scale = 0;
	memset(&l, 0, sizeof l);
	l.kind = PM_LIGHT_ENV;
	for (int i = 0; i < 3; i++)
		l.rot[i][i] = 1;
	for (int i = 0; i < p->s->nlights; i++)
		if (p->s->lights[i].kind == PM_LIGHT_ENV)
			return perr(p, "envlight: a second environment light (at most one)");
	if (w && !strcmp(w, "radiance")) {
		p->pos++;
		if (light_colour(p, &l.power, "radiance"))
			return -1;
		if (peek(p))
			return perr(p, "envlight: unexpected '%s'", peek(p));
	} else if (w && !strcmp(w, "image")) {
		p->pos++;
		if (!(file = peek(p)))
			return perr(p, "envlight: expected a file name after 'image'");
		p->pos++;
		while ((w = peek(p))) {
			p->pos++;
			if (!strcmp(w, "scale") && !have_scale++) {
				if (numbers(p, 1, &scale, "'scale'"))
					return -1;
				if (!(scale > 0))
					return perr(p, "envlight: scale must be > 0, got %g", scale);
			} else if (!strcmp(w, "rotate")) {
				if (numbers(p, 4, d, "'rotate'") || rotation(p, d, a))
					return -1;
				float r[3][3];
				for (int i = 0; i < 3; i++)
					for (int j = 0; j < 3; j++)
						r[i][j] = (float)(a[i][0] * l.rot[0][j] + a[i][1] * l.rot[1][j]
						                  + a[i][2] * l.rot[2][j]);
				memcpy(l.rot, r, sizeof r);
			} else {
				return perr(p, "envlight: unexpected '%s' (expected scale or rotate)", w);
			}
		}
		pm_rgbimage im;
		l.power = pm_v3(1, 1, 1);
		if (image_arg(p, file, (float)scale, &im))
			return -1;
		l.env = im.px;
		l.env_w = im.w;
		l.env_h = im.h;
	} else {
		return perr(p, "envlight: expected 'radiance' or 'image'");
	}
	pm_error e;
	if (pm_build_light(p->b, &l, &e)) {
		free(l.env);
		return berr(p, &e);
	}
	return 0;
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
		{"disk", st_disk}, {"spotlight", st_spotlight}, {"distantlight", st_distantlight},
		{"envlight", st_envlight}, {"texture", st_texture},
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
		return perr(p, "no light (add a pointlight, spotlight, distantlight, envlight "
		            "or an object with an emitting material)");
	pm_error e;
	if (pm_limits_scene(s, &e))
		return berr(p, &e);
	for (int i = 0; i < s->nmats; i++) {
		pm_material *m = &s->mats[i];
		m->strong = m->kind == PM_MAT_MIRROR || m->kind == PM_MAT_GLASS
			|| (m->kind == PM_MAT_GLOSSY && m->exponent >= s->glossy_threshold);
	}
	pm_scene_orient_solids(s);
	return 0;
}

int
pm_scene_load(pm_scene *s, const char *path, pm_error *err)
{
	parser p;
	pm_scene_build b;
	char *data = NULL;
	size_t len = 0;
	int r = -1;

	memset(s, 0, sizeof *s);
	memset(&p, 0, sizeof p);
	memset(&b, 0, sizeof b);
	b.s = s;
	p.b = &b;
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
	pm_build_free(&b);
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
	for (int i = 0; i < s->nlights; i++)
		free(s->lights[i].env);
	free(s->lights);
	free(s->verts);
	free(s->vnormal);
	free(s->vuv);
	for (int i = 0; i < s->ntexs; i++) {
		pm_texfilter_free(s->texs[i].filt);
		free(s->texs[i].px);
	}
	free(s->texs);
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
