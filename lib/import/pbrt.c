/* pbrt.c — the pbrt-v4 scene reader (readers.h): directives, parameter
 * lists, the graphics state and its stacks, named materials, coordinate
 * systems and object instances (flattened), with each shape brought to the
 * world and oriented as pbrt orients it: the front of a face is its
 * object-space winding's normal carried by the transform as a normal,
 * reversed by ReverseOrientation, and where the mesh has normals N the side
 * they point to (pbrt turns the geometric normal toward the shading one). */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec.h"
#include "import/ply.h"
#include "import/readers.h"

#define MAX_FILE_BYTES (1ull << 30)
#define MAX_INCLUDE_DEPTH 32

enum { TK_STR, TK_WORD, TK_LBRACK, TK_RBRACK, TK_EOF };

typedef struct token {
	int kind;
	int line;
	char *s;             /* TK_STR and TK_WORD: its text, NUL-terminated in place */
} token;

typedef struct lexer {
	char *buf;
	size_t len, pos;
	int line;
	int file;
	token peek;
	int has_peek;
} lexer;

typedef struct param {
	char type[24], name[64];
	double *num;
	int nnum;
	char **str;
	int nstr;
	int line;
} param;

typedef struct plist {
	param *p;
	int n;
} plist;

typedef struct gstate {
	pmi_mat4 ctm;
	int rev;
	int mat;             /* index into d->mats, -1 for pbrt's default diffuse */
	int area;            /* an AreaLightSource is active */
	double L[3], scale, power;
	int twosided;
	pmi_src area_src;
	int transform_only;  /* pushed by TransformBegin: restore only ctm */
} gstate;

typedef struct named { char *name; int index; pmi_mat4 m; } named;

typedef struct texture {
	char *name;
	int constant;
	double value[3];
	char file[256];
	int desc;            /* 1 + its index in the description's texs, or 0 */
} texture;

typedef struct object {
	char *name;
	pmi_shape *shapes;
	size_t n, cap;
} object;

typedef struct parser {
	pmi_desc *d;
	pm_error *err;
	char dir[4096];
	gstate gs;
	gstate *stack;
	int nstack, capstack;
	named *mats; int nmats;
	named *coords; int ncoords;
	texture *tex; int ntex;
	int last_tex;        /* the desc texture pcolor last returned 2 for */
	object *objs; int nobjs;
	int cur_obj;         /* -1 outside ObjectBegin */
	int depth;
	char *open_files[MAX_INCLUDE_DEPTH + 1];
	int default_mat;     /* d->mats index of pbrt's default, -1 until used */
	int film_w, film_h;
	pmi_src film_src;
} parser;

/* ---- lexing ---- */

static int
lex_next(parser *P, lexer *L, token *t)
{
	if (L->has_peek) {
		*t = L->peek;
		L->has_peek = 0;
		return 0;
	}
	for (;;) {
		while (L->pos < L->len && isspace((unsigned char)L->buf[L->pos])) {
			if (L->buf[L->pos] == '\n')
				L->line++;
			L->pos++;
		}
		if (L->pos < L->len && L->buf[L->pos] == '#') {
			while (L->pos < L->len && L->buf[L->pos] != '\n')
				L->pos++;
			continue;
		}
		break;
	}
	t->line = L->line;
	t->s = NULL;
	if (L->pos >= L->len) {
		t->kind = TK_EOF;
		return 0;
	}
	char c = L->buf[L->pos];
	if (c == '[' || c == ']') {
		t->kind = c == '[' ? TK_LBRACK : TK_RBRACK;
		L->pos++;
		return 0;
	}
	if (c == '"') {
		size_t b = ++L->pos, w = b;
		while (L->pos < L->len && L->buf[L->pos] != '"' && L->buf[L->pos] != '\n') {
			if (L->buf[L->pos] == '\\' && L->pos + 1 < L->len) {
				L->pos++;
				char e = L->buf[L->pos];
				L->buf[w++] = e == 'n' ? '\n' : e == 't' ? '\t' : e;
			} else
				L->buf[w++] = L->buf[L->pos];
			L->pos++;
		}
		if (L->pos >= L->len || L->buf[L->pos] != '"')
			return pmi_err(P->d, (pmi_src){ L->file, t->line }, P->err, "unterminated string");
		L->buf[w] = 0;
		L->pos++;
		t->kind = TK_STR;
		t->s = L->buf + b;
		return 0;
	}
	size_t b = L->pos;
	while (L->pos < L->len && !isspace((unsigned char)L->buf[L->pos]) &&
	       L->buf[L->pos] != '"' && L->buf[L->pos] != '[' && L->buf[L->pos] != ']' && L->buf[L->pos] != '#')
		L->pos++;
	/* A copy: the byte after a word may be a quote or bracket that the
	 * next token needs, so it cannot be overwritten with a NUL. */
	t->kind = TK_WORD;
	t->s = malloc(L->pos - b + 1);
	if (!t->s)
		return pm_seterr(P->err, "out of memory");
	memcpy(t->s, L->buf + b, L->pos - b);
	t->s[L->pos - b] = 0;
	return 0;
}

static void
tok_free(token *t)
{
	if (t->kind == TK_WORD)
		free(t->s);
	t->s = NULL;
}

static int
lex_peek(parser *P, lexer *L, token **t)
{
	if (!L->has_peek) {
		if (lex_next(P, L, &L->peek))
			return -1;
		L->has_peek = 1;
	}
	*t = &L->peek;
	return 0;
}

static pmi_src
src_at(const lexer *L, int line)
{
	return (pmi_src){ L->file, line };
}

static int
parse_number(const char *s, double *v)
{
	char *end;

	errno = 0;
	*v = strtod(s, &end);
	return *end || end == s || errno == ERANGE || !isfinite(*v) ? -1 : 0;
}

/* ---- parameter lists ---- */

static void
plist_free(plist *pl)
{
	for (int i = 0; i < pl->n; i++) {
		free(pl->p[i].num);
		for (int j = 0; j < pl->p[i].nstr; j++)
			free(pl->p[i].str[j]);
		free(pl->p[i].str);
	}
	free(pl->p);
	pl->p = NULL;
	pl->n = 0;
}

/* One value of a parameter into p: a number, a bool word or a string. */
static int
param_value(parser *P, lexer *L, param *p, token *t)
{
	if (t->kind == TK_STR) {
		char **s = realloc(p->str, (p->nstr + 1) * sizeof *s);
		if (!s || !(s[p->nstr] = strdup(t->s))) {
			if (s)
				p->str = s;
			return pm_seterr(P->err, "out of memory");
		}
		p->str = s;
		p->nstr++;
		return 0;
	}
	double v;
	if (t->kind != TK_WORD)
		return pmi_err(P->d, src_at(L, t->line), P->err, "parameter '%s': expected a value", p->name);
	if (strcmp(t->s, "true") == 0)
		v = 1;
	else if (strcmp(t->s, "false") == 0)
		v = 0;
	else if (parse_number(t->s, &v))
		return pmi_err(P->d, src_at(L, t->line), P->err, "parameter '%s': '%s' is not a number", p->name, t->s);
	if (p->nnum % 64 == 0) {
		double *n = realloc(p->num, (p->nnum + 64) * sizeof *n);
		if (!n)
			return pm_seterr(P->err, "out of memory");
		p->num = n;
	}
	p->num[p->nnum++] = v;
	return 0;
}

/* The "type name" value... pairs that follow a directive's own arguments. */
static int
parse_params(parser *P, lexer *L, plist *pl)
{
	token *pk, t;

	for (;;) {
		if (lex_peek(P, L, &pk))
			return -1;
		if (pk->kind != TK_STR)
			return 0;
		lex_next(P, L, &t);
		param p;
		memset(&p, 0, sizeof p);
		p.line = t.line;
		if (sscanf(t.s, "%23s %63s", p.type, p.name) != 2)
			return pmi_err(P->d, src_at(L, t.line), P->err, "expected \"type name\", got \"%s\"", t.s);
		param *np = realloc(pl->p, (pl->n + 1) * sizeof *np);
		if (!np)
			return pm_seterr(P->err, "out of memory");
		pl->p = np;
		pl->p[pl->n++] = p;
		param *cur = &pl->p[pl->n - 1];
		if (lex_next(P, L, &t))
			return -1;
		if (t.kind == TK_LBRACK) {
			for (;;) {
				if (lex_next(P, L, &t))
					return -1;
				if (t.kind == TK_RBRACK)
					break;
				if (t.kind == TK_EOF)
					return pmi_err(P->d, src_at(L, t.line), P->err, "parameter '%s': missing ']'", cur->name);
				int r = param_value(P, L, cur, &t);
				tok_free(&t);
				if (r)
					return -1;
			}
		} else {
			int r = t.kind == TK_EOF ? pmi_err(P->d, src_at(L, t.line), P->err, "parameter '%s': no value", cur->name)
			                        : param_value(P, L, cur, &t);
			tok_free(&t);
			if (r)
				return -1;
		}
	}
}

static param *
pfind(plist *pl, const char *name)
{
	for (int i = 0; i < pl->n; i++)
		if (strcmp(pl->p[i].name, name) == 0)
			return &pl->p[i];
	return NULL;
}

static double
pfloat(plist *pl, const char *name, double def)
{
	param *p = pfind(pl, name);
	return p && p->nnum > 0 ? p->num[0] : def;
}

/* A bool written bare (true) or quoted ("true"). */
static int
pbool(plist *pl, const char *name, int def)
{
	param *p = pfind(pl, name);
	if (!p)
		return def;
	if (p->nnum)
		return p->num[0] != 0;
	return p->nstr ? !strcmp(p->str[0], "true") : def;
}

static const char *
pstring(plist *pl, const char *name, const char *def)
{
	param *p = pfind(pl, name);
	return p && p->nstr > 0 ? p->str[0] : def;
}

/* pbrt-v4 names metals' spectra "metal-Au-eta", "metal-Au-k". */
static int
metal_f0(const char *name, double f0[3])
{
	char sym[16];

	if (sscanf(name, "metal-%15[^-]-", sym) != 1)
		return -1;
	return pmi_metal_f0(sym, f0);
}

/* A spectrum-valued parameter as RGB. Returns 1 if found (rgb, a constant
 * texture, or approximated with a note), 0 if absent, 2 if it names an
 * image texture (file in texfile, out unchanged), -1 on error. */
static int
pcolor(parser *P, lexer *L, plist *pl, const char *name, double out[3], char *texfile, size_t ntex)
{
	param *p = pfind(pl, name);

	if (!p)
		return 0;
	pmi_src at = src_at(L, p->line);
	if (!strcmp(p->type, "rgb") || !strcmp(p->type, "color")) {
		if (p->nnum != 3)
			return pmi_err(P->d, at, P->err, "'%s': rgb wants 3 numbers, got %d", name, p->nnum);
		memcpy(out, p->num, 3 * sizeof *out);
		return 1;
	}
	if (!strcmp(p->type, "float")) {
		if (p->nnum < 1)
			return pmi_err(P->d, at, P->err, "'%s': no value", name);
		out[0] = out[1] = out[2] = p->num[0];
		return 1;
	}
	if (!strcmp(p->type, "texture")) {
		if (p->nstr != 1)
			return pmi_err(P->d, at, P->err, "'%s': texture wants a name", name);
		for (int i = 0; i < P->ntex; i++)
			if (!strcmp(P->tex[i].name, p->str[0])) {
				if (P->tex[i].constant) {
					memcpy(out, P->tex[i].value, 3 * sizeof *out);
					return 1;
				}
				if (texfile)
					snprintf(texfile, ntex, "%s", P->tex[i].file[0] ? P->tex[i].file : p->str[0]);
				P->last_tex = P->tex[i].desc;
				return 2;
			}
		return pmi_err(P->d, at, P->err, "'%s': unknown texture '%s'", name, p->str[0]);
	}
	if (!strcmp(p->type, "blackbody")) {
		out[0] = out[1] = out[2] = 1;
		pmi_note_add(P->d, at, "'%s': blackbody spectrum taken as white of the same luminance", name);
		return 1;
	}
	if (!strcmp(p->type, "spectrum")) {
		if (p->nstr == 1) {
			if (metal_f0(p->str[0], out) == 0)
				return 1;
			out[0] = out[1] = out[2] = 1;
			pmi_note_add(P->d, at, "'%s': named spectrum '%s' taken as white", name, p->str[0]);
			return 1;
		}
		if (p->nnum >= 2 && p->nnum % 2 == 0) {
			double s = 0;
			for (int i = 1; i < p->nnum; i += 2)
				s += p->num[i];
			out[0] = out[1] = out[2] = s / (p->nnum / 2);
			pmi_note_add(P->d, at, "'%s': sampled spectrum taken as grey (its mean)", name);
			return 1;
		}
		return pmi_err(P->d, at, P->err, "'%s': bad spectrum", name);
	}
	return pmi_err(P->d, at, P->err, "'%s': unknown type '%s'", name, p->type);
}

/* ---- materials ---- */

static double
roughness_alpha(parser *P, lexer *L, plist *pl, pmi_src at)
{
	double r = pfloat(pl, "roughness", 0);
	double u = pfloat(pl, "uroughness", r), v = pfloat(pl, "vroughness", r);
	int remap = pbool(pl, "remaproughness", 1);

	if (u != v)
		pmi_note_add(P->d, at, "anisotropic roughness %g x %g taken as isotropic %g", u, v, sqrt(u * v));
	r = sqrt(fabs(u * v));
	/* pbrt-v4's TrowbridgeReitzDistribution::RoughnessToAlpha: sqrt. */
	return remap ? sqrt(r) : r;
}

static void
fresnel_f0(const double eta[3], const double k[3], double f0[3])
{
	for (int c = 0; c < 3; c++)
		f0[c] = ((eta[c] - 1) * (eta[c] - 1) + k[c] * k[c]) /
		        ((eta[c] + 1) * (eta[c] + 1) + k[c] * k[c]);
}

/* Fills m from a pbrt material type and its parameters. */
static int
make_material(parser *P, lexer *L, pmi_material *m, const char *type, plist *pl, pmi_src at)
{
	snprintf(m->type, sizeof m->type, "%s", type);
	m->color[0] = m->color[1] = m->color[2] = 0.5;
	m->trans[0] = m->trans[1] = m->trans[2] = 1;
	int r = 0;

	if (!strcmp(type, "diffuse") || !strcmp(type, "coateddiffuse")) {
		m->kind = type[0] == 'd' ? PMI_MAT_DIFFUSE : PMI_MAT_COATED;
		if ((r = pcolor(P, L, pl, "reflectance", m->color, m->texture, sizeof m->texture)) < 0)
			return -1;
		if (m->kind == PMI_MAT_COATED) {
			m->alpha = roughness_alpha(P, L, pl, at);
			param *e = pfind(pl, "eta");
			m->eta = e && e->nnum ? e->num[0] : 1.5;
		}
	} else if (!strcmp(type, "conductor") || !strcmp(type, "coatedconductor")) {
		double eta[3] = { 0.2, 0.92, 1.1 }, k[3] = { 3.91, 2.45, 2.14 };
		const char *ename = !strcmp(type, "conductor") ? "eta" : "conductor.eta";
		const char *kname = !strcmp(type, "conductor") ? "k" : "conductor.k";
		m->kind = PMI_MAT_CONDUCTOR;
		if (!strcmp(type, "coatedconductor"))
			pmi_note_add(P->d, at, "coatedconductor: its coat dropped, the conductor kept");
		if ((r = pcolor(P, L, pl, "reflectance", m->spec, m->texture, sizeof m->texture)) < 0)
			return -1;
		if (r == 0) {
			param *pe = pfind(pl, ename);
			if (pe && pe->nstr == 1 && metal_f0(pe->str[0], m->spec) == 0)
				;
			else {
				/* pbrt-v4's default is copper (metal-Cu-eta, metal-Cu-k). */
				if (pcolor(P, L, pl, ename, eta, NULL, 0) < 0 || pcolor(P, L, pl, kname, k, NULL, 0) < 0)
					return -1;
				fresnel_f0(eta, k, m->spec);
			}
		}
		m->alpha = roughness_alpha(P, L, pl, at);
	} else if (!strcmp(type, "dielectric") || !strcmp(type, "thindielectric")) {
		m->kind = type[0] == 'd' ? PMI_MAT_DIELECTRIC : PMI_MAT_THIN;
		param *e = pfind(pl, "eta");
		m->eta = 1.5;
		if (e && e->nnum)
			m->eta = e->num[0];
		else if (e && e->nstr) {
			static const struct { const char *n; double eta; } g[] = {
				{"glass-BK7", 1.5168}, {"glass-BAF10", 1.6700}, {"glass-FK51A", 1.4866},
				{"glass-LASF9", 1.8503}, {"glass-F5", 1.6034}, {"glass-F10", 1.6200}, {"glass-F11", 1.6209},
			};
			size_t i;
			for (i = 0; i < sizeof g / sizeof *g; i++)
				if (!strcmp(e->str[0], g[i].n))
					break;
			m->eta = i < sizeof g / sizeof *g ? g[i].eta : 1.5;
			pmi_note_add(P->d, at, "eta '%s': dispersion dropped, ior %g", e->str[0], m->eta);
		}
		m->alpha = roughness_alpha(P, L, pl, at);
	} else if (!strcmp(type, "diffusetransmission")) {
		m->kind = PMI_MAT_DIFFTRANS;
		m->color[0] = m->color[1] = m->color[2] = 0.25;
		m->trans[0] = m->trans[1] = m->trans[2] = 0.25;
		if (pcolor(P, L, pl, "reflectance", m->color, m->texture, sizeof m->texture) < 0 ||
		    pcolor(P, L, pl, "transmittance", m->trans, NULL, 0) < 0)
			return -1;
	} else if (!strcmp(type, "interface") || !strcmp(type, "")) {
		m->kind = PMI_MAT_INVISIBLE;
	} else {
		m->kind = PMI_MAT_DIFFUSE;
		pmi_note_add(P->d, at, "material type '%s': pm has no model for it, grey diffuse 0.5 used", type);
	}
	return 0;
}

static int
find_named(named *a, int n, const char *name)
{
	for (int i = 0; i < n; i++)
		if (!strcmp(a[i].name, name))
			return i;
	return -1;
}

static int
add_named(named **a, int *n, const char *name, int index, pmi_mat4 m)
{
	int i = find_named(*a, *n, name);

	if (i < 0) {
		named *na = realloc(*a, (*n + 1) * sizeof *na);
		if (!na)
			return -1;
		*a = na;
		i = (*n)++;
		if (!(na[i].name = strdup(name)))
			return -1;
	}
	(*a)[i].index = index;
	(*a)[i].m = m;
	return 0;
}

/* A material from the "mix" type: pbrt picks one of its two at random per
 * hit, the second with probability amount; two diffuse ones blend exactly,
 * otherwise the more likely one stands for both. */
static int
make_mix(parser *P, lexer *L, pmi_material *m, plist *pl, pmi_src at)
{
	param *ms = pfind(pl, "materials");
	double amt = pfloat(pl, "amount", 0.5);
	int a, b;

	if (!ms || ms->nstr != 2)
		return pmi_err(P->d, at, P->err, "mix: wants \"string materials\" with two names");
	if ((a = find_named(P->mats, P->nmats, ms->str[0])) < 0 || (b = find_named(P->mats, P->nmats, ms->str[1])) < 0)
		return pmi_err(P->d, at, P->err, "mix: unknown material '%s'", a < 0 ? ms->str[0] : ms->str[1]);
	const pmi_material *ma = &P->d->mats[P->mats[a].index], *mb = &P->d->mats[P->mats[b].index];
	char name[64];
	snprintf(name, sizeof name, "%s", m->name);
	if (ma->kind == PMI_MAT_DIFFUSE && mb->kind == PMI_MAT_DIFFUSE) {
		*m = *ma;
		for (int c = 0; c < 3; c++)
			m->color[c] = (1 - amt) * ma->color[c] + amt * mb->color[c];
		pmi_note_add(P->d, at, "mix of two diffuse materials: one diffuse of the blended colour");
	} else {
		*m = amt > 0.5 ? *mb : *ma;
		pmi_note_add(P->d, at, "mix: '%s' (weight %g) stands for the mix", amt > 0.5 ? ms->str[1] : ms->str[0],
		             amt > 0.5 ? amt : 1 - amt);
	}
	snprintf(m->name, sizeof m->name, "%s", name);
	snprintf(m->type, sizeof m->type, "mix");
	m->src = at;
	return 0;
}

/* ---- shapes ---- */

static int
push_shape(parser *P, pmi_shape *s)
{
	pmi_shape *dst;

	if (P->cur_obj >= 0) {
		object *o = &P->objs[P->cur_obj];
		if (o->n == o->cap) {
			size_t nc = o->cap ? 2 * o->cap : 8;
			pmi_shape *ns = realloc(o->shapes, nc * sizeof *ns);
			if (!ns)
				return -1;
			o->shapes = ns;
			o->cap = nc;
		}
		dst = &o->shapes[o->n++];
		*dst = *s;
		return 0;
	}
	if (!(dst = pmi_add_shape(P->d, s->src)))
		return -1;
	*dst = *s;
	return 0;
}

/* The area light's radiance for a shape of area A (pbrt-v4's
 * DiffuseAreaLight: L x scale, or with power, scaled so the shape emits
 * that power: L x scale x power / (sides pi A)). */
static void
area_radiance(const gstate *g, double A, double out[3])
{
	double k = g->scale;

	if (g->power > 0 && A > 0)
		k *= g->power / ((g->twosided ? 2 : 1) * PM_PI * A);
	for (int c = 0; c < 3; c++)
		out[c] = g->L[c] * k;
}

/* Orients a mesh read in object space, brings it to the world and keeps it. */
static int
finish_mesh(parser *P, lexer *L, pmi_shape *s, const float *N, pmi_src at)
{
	s->src = at;
	s->mat = P->gs.mat;
	if (N) {
		/* Face each polygon toward its corners' normals, in object space
		 * (the transform carries both alike). */
		for (size_t f = 0; f < s->nface; f++) {
			double n[3] = { 0, 0, 0 }, g[3] = { 0, 0, 0 };
			uint32_t b = s->start[f], k = s->start[f + 1] - b;
			for (uint32_t i = 0; i < k; i++) {
				const float *p = s->v + 3 * (size_t)s->idx[b + i], *q = s->v + 3 * (size_t)s->idx[b + (i + 1) % k];
				g[0] += ((double)p[1] - q[1]) * ((double)p[2] + q[2]);
				g[1] += ((double)p[2] - q[2]) * ((double)p[0] + q[0]);
				g[2] += ((double)p[0] - q[0]) * ((double)p[1] + q[1]);
				for (int c = 0; c < 3; c++)
					n[c] += N[3 * (size_t)s->idx[b + i] + c];
			}
			if (g[0] * n[0] + g[1] * n[1] + g[2] * n[2] < 0)
				for (uint32_t i = 0; i < k / 2; i++) {
					uint32_t t = s->idx[b + i];
					s->idx[b + i] = s->idx[b + k - 1 - i];
					s->idx[b + k - 1 - i] = t;
				}
		}
	}
	if (N && s->nv && !s->n) {
		/* Kept as the shading normals pm interpolates. */
		if (!(s->n = malloc(3 * s->nv * sizeof *s->n))) {
			pmi_shape_free(s);
			return pm_seterr(P->err, "out of memory");
		}
		memcpy(s->n, N, 3 * s->nv * sizeof *s->n);
	}
	pmi_shape_xform(s, P->gs.ctm, P->gs.rev);
	if (P->gs.area) {
		double A = 0, amin = INFINITY, amax = 0;
		for (size_t f = 0; f < s->nface; f++) {
			double a = pmi_face_area(s, f);
			A += a;
			amin = fmin(amin, a);
			amax = fmax(amax, a);
		}
		/* pbrt makes one light per triangle, each given the power. */
		area_radiance(&P->gs, s->nface ? A / s->nface : 0, s->emit);
		if (P->gs.power > 0 && s->nface > 1)
			pmi_note_add(P->d, at, "area light 'power' applies to each of the %zu faces, as in pbrt%s",
			             s->nface, amax > 1.001 * amin ? " (their mean area used)" : "");
		s->twosided = P->gs.twosided;
	}
	if (push_shape(P, s)) {
		pmi_shape_free(s);
		return pm_seterr(P->err, "out of memory");
	}
	return 0;
}

static int
resolve_path(parser *P, const char *name, char *out, size_t n)
{
	if (name[0] == '/')
		return snprintf(out, n, "%s", name) >= (int)n ? -1 : 0;
	return snprintf(out, n, "%s%s", P->dir, name) >= (int)n ? -1 : 0;
}

/* Loop subdivision (Loop 1987) of a triangle mesh, levels times: every edge
 * gets a vertex at 3/8 of its ends plus 1/8 of the opposite corners (1/2 of
 * the ends on a boundary), every old vertex moves to (1 - n beta) of itself
 * plus beta of each neighbour. */
static int
loop_subdivide(pmi_shape *s, int levels)
{
	for (int lv = 0; lv < levels; lv++) {
		size_t nv = s->nv, nf = s->nface, ne = 0;
		/* Edges in a hash table keyed by the vertex pair. */
		size_t cap = 1;
		while (cap < 6 * nf + 16)
			cap <<= 1;
		uint32_t *ek = malloc(cap * 2 * sizeof *ek), *emid = malloc(cap * sizeof *emid);
		uint32_t *eopp = malloc(cap * 2 * sizeof *eopp);
		int *ecount = calloc(cap, sizeof *ecount);
		double *acc = calloc(nv * 3, sizeof *acc);
		int *val = calloc(nv, sizeof *val), *bnd = calloc(nv, sizeof *bnd);
		if (!ek || !emid || !eopp || !ecount || !acc || !val || !bnd) {
			free(ek); free(emid); free(eopp); free(ecount); free(acc); free(val); free(bnd);
			return -1;
		}
		uint32_t *fe = malloc(nf * 3 * sizeof *fe);
		if (!fe) {
			free(ek); free(emid); free(eopp); free(ecount); free(acc); free(val); free(bnd);
			return -1;
		}
		for (size_t f = 0; f < nf; f++)
			for (int i = 0; i < 3; i++) {
				uint32_t a = s->idx[3 * f + i], b = s->idx[3 * f + (i + 1) % 3], o = s->idx[3 * f + (i + 2) % 3];
				uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
				size_t h = ((size_t)lo * 2654435761u ^ (size_t)hi * 40503u) & (cap - 1);
				while (ecount[h] && !(ek[2 * h] == lo && ek[2 * h + 1] == hi))
					h = (h + 1) & (cap - 1);
				if (!ecount[h]) {
					ek[2 * h] = lo; ek[2 * h + 1] = hi;
					emid[h] = (uint32_t)(nv + ne++);
				}
				if (ecount[h] < 2)
					eopp[2 * h + ecount[h]] = o;
				ecount[h]++;
				fe[3 * f + i] = (uint32_t)h;
			}
		float *nvp = malloc((nv + ne) * 3 * sizeof *nvp);
		uint32_t *nidx = malloc(nf * 12 * sizeof *nidx), *nstart = malloc((nf * 4 + 1) * sizeof *nstart);
		if (!nvp || !nidx || !nstart) {
			free(nvp); free(nidx); free(nstart); free(fe);
			free(ek); free(emid); free(eopp); free(ecount); free(acc); free(val); free(bnd);
			return -1;
		}
		for (size_t h = 0; h < cap; h++) {
			if (!ecount[h])
				continue;
			uint32_t a = ek[2 * h], b = ek[2 * h + 1], m = emid[h];
			for (int c = 0; c < 3; c++) {
				double pa = s->v[3 * a + c], pb = s->v[3 * b + c];
				nvp[3 * m + c] = ecount[h] == 2
				    ? (float)(0.375 * (pa + pb) + 0.125 * (s->v[3 * eopp[2 * h] + c] + s->v[3 * eopp[2 * h + 1] + c]))
				    : (float)(0.5 * (pa + pb));
			}
			if (ecount[h] == 1) {
				bnd[a] = bnd[b] = 1;
			}
		}
		for (size_t h = 0; h < cap; h++) {
			if (!ecount[h])
				continue;
			uint32_t a = ek[2 * h], b = ek[2 * h + 1];
			int boundary = ecount[h] == 1;
			/* Interior vertices average all neighbours, boundary ones only
			 * their boundary neighbours. */
			if (!bnd[a] || boundary) {
				val[a]++;
				for (int c = 0; c < 3; c++) acc[3 * a + c] += s->v[3 * b + c];
			}
			if (!bnd[b] || boundary) {
				val[b]++;
				for (int c = 0; c < 3; c++) acc[3 * b + c] += s->v[3 * a + c];
			}
		}
		for (size_t i = 0; i < nv; i++) {
			int n = val[i];
			double beta = bnd[i] ? 0.125 : n == 3 ? 3.0 / 16 : 3.0 / (8.0 * n), keep = bnd[i] ? 0.75 : 1 - n * beta;
			for (int c = 0; c < 3; c++)
				nvp[3 * i + c] = n ? (float)(keep * s->v[3 * i + c] + beta * acc[3 * i + c]) : s->v[3 * i + c];
		}
		for (size_t f = 0; f < nf; f++) {
			uint32_t v0 = s->idx[3 * f], v1 = s->idx[3 * f + 1], v2 = s->idx[3 * f + 2];
			uint32_t m01 = emid[fe[3 * f]], m12 = emid[fe[3 * f + 1]], m20 = emid[fe[3 * f + 2]];
			uint32_t t[12] = { v0, m01, m20, m01, v1, m12, m20, m12, v2, m01, m12, m20 };
			memcpy(nidx + 12 * f, t, sizeof t);
		}
		for (size_t i = 0; i <= nf * 4; i++)
			nstart[i] = (uint32_t)(3 * i);
		free(s->v); free(s->idx); free(s->start); free(s->uv);
		s->uv = NULL;
		s->v = nvp; s->idx = nidx; s->start = nstart;
		s->nv = nv + ne; s->nface = nf * 4;
		free(fe); free(ek); free(emid); free(eopp); free(ecount); free(acc); free(val); free(bnd);
	}
	return 0;
}

/* Points, indices and optional N and uv of trianglemesh, bilinearmesh and
 * loopsubdiv into a mesh; corners per face: 3, or 4 for bilinear patches
 * (pbrt's order p00 p10 p01 p11, turned into a cycle). */
static int
inline_mesh(parser *P, lexer *L, plist *pl, pmi_src at, const char *what, int per, pmi_shape *s, float **N)
{
	param *pp = pfind(pl, "P"), *pi = pfind(pl, per == 3 && !strcmp(what, "loopsubdiv") ? "indices" : "indices");
	param *pn = pfind(pl, "N"), *puv = pfind(pl, "uv");
	if (!pp || pp->nnum == 0 || pp->nnum % 3)
		return pmi_err(P->d, at, P->err, "%s: \"point3 P\" missing or not a multiple of 3 numbers", what);
	size_t nv = pp->nnum / 3, ni = pi ? (size_t)pi->nnum : 0;
	if (!pi) {
		if (nv != (size_t)per)
			return pmi_err(P->d, at, P->err, "%s: no \"integer indices\" and not exactly %d points", what, per);
		ni = per;
	}
	if (ni == 0 || ni % per)
		return pmi_err(P->d, at, P->err, "%s: %zu indices, not a multiple of %d", what, ni, per);
	if (pn && pn->nnum != pp->nnum)
		return pmi_err(P->d, at, P->err, "%s: %d normal numbers for %d point numbers", what, pn->nnum, pp->nnum);
	if (puv && puv->nnum != (int)(2 * nv))
		puv = NULL;
	memset(s, 0, sizeof *s);
	if (pmi_mesh_alloc(s, nv, ni / per, ni, puv != NULL))
		return pm_seterr(P->err, "out of memory");
	for (size_t i = 0; i < 3 * nv; i++)
		s->v[i] = (float)pp->num[i];
	if (puv)
		for (size_t i = 0; i < 2 * nv; i++)
			s->uv[i] = (float)puv->num[i];
	for (size_t i = 0; i < ni; i++) {
		double v = pi ? pi->num[i] : (double)i;
		if (!(v >= 0 && v < (double)nv && v == floor(v))) {
			pmi_shape_free(s);
			return pmi_err(P->d, at, P->err, "%s: index %g out of range (%zu points)", what, v, nv);
		}
		s->idx[i] = (uint32_t)v;
	}
	if (per == 4)
		for (size_t f = 0; f < ni / 4; f++) {
			uint32_t t = s->idx[4 * f + 2];
			s->idx[4 * f + 2] = s->idx[4 * f + 3];
			s->idx[4 * f + 3] = t;
		}
	for (size_t f = 0; f <= ni / per; f++)
		s->start[f] = (uint32_t)(f * per);
	*N = NULL;
	if (pn) {
		if (!(*N = malloc(3 * nv * sizeof **N))) {
			pmi_shape_free(s);
			return pm_seterr(P->err, "out of memory");
		}
		for (size_t i = 0; i < 3 * nv; i++)
			(*N)[i] = (float)pn->num[i];
	}
	return 0;
}

static int
shape_body(parser *P, lexer *L, const char *type, plist *pl, pmi_src at)
{
	pmi_shape s;
	float *N = NULL;
	int r;

	memset(&s, 0, sizeof s);
	if (P->gs.mat >= 0 && P->d->mats[P->gs.mat].kind == PMI_MAT_INVISIBLE && !P->gs.area) {
		pmi_note_add(P->d, at, "shape with the interface material (no surface): dropped");
		return 0;
	}
	if (pfind(pl, "alpha"))
		pmi_note_add(P->d, at, "%s: alpha (cut-out) dropped", type);
	if (!strcmp(type, "trianglemesh") || !strcmp(type, "bilinearmesh") || !strcmp(type, "loopsubdiv")) {
		if (inline_mesh(P, L, pl, at, type, type[0] == 'b' ? 4 : 3, &s, &N))
			return -1;
		if (!strcmp(type, "loopsubdiv")) {
			int lv = (int)pfloat(pl, "levels", 3);
			free(N);
			N = NULL;
			if (lv > 6) {
				pmi_note_add(P->d, at, "loopsubdiv: %d levels cut to 6", lv);
				lv = 6;
			}
			if (loop_subdivide(&s, lv < 0 ? 0 : lv)) {
				pmi_shape_free(&s);
				return pm_seterr(P->err, "out of memory");
			}
			pmi_note_add(P->d, at, "loopsubdiv: subdivided %d times, not to the limit surface", lv);
		}
	} else if (!strcmp(type, "plymesh")) {
		const char *fn = pstring(pl, "filename", NULL);
		char path[4096];
		pm_error e;
		if (!fn)
			return pmi_err(P->d, at, P->err, "plymesh: no \"string filename\"");
		if (resolve_path(P, fn, path, sizeof path))
			return pmi_err(P->d, at, P->err, "plymesh: path too long");
		if (pmi_ply_read(path, &s, &N, &e))
			return pmi_err(P->d, at, P->err, "%s", e.msg);
		if (pfind(pl, "displacement"))
			pmi_note_add(P->d, at, "plymesh: displacement dropped");
	} else if (!strcmp(type, "sphere")) {
		double rad = pfloat(pl, "radius", 1);
		if (pfind(pl, "zmin") || pfind(pl, "zmax") || pfind(pl, "phimax"))
			pmi_note_add(P->d, at, "sphere: zmin/zmax/phimax dropped (a whole sphere)");
		pmi_mat4 m = P->gs.ctm;
		double c0[3], ax[3][3], len[3];
		/* pm spheres are spheres: an ellipsoid's mean radius is used. */
		for (int i = 0; i < 3; i++) {
			double e[3] = { i == 0, i == 1, i == 2 };
			pmi_xform_vector(m, e, ax[i]);
			len[i] = sqrt(ax[i][0] * ax[i][0] + ax[i][1] * ax[i][1] + ax[i][2] * ax[i][2]);
		}
		if (fabs(len[0] - len[1]) > 1e-6 * len[0] || fabs(len[0] - len[2]) > 1e-6 * len[0])
			pmi_note_add(P->d, at, "sphere under a non-uniform scale: a sphere of the mean radius");
		double o[3] = { 0, 0, 0 };
		pmi_xform_point(m, o, c0);
		s.kind = PMI_SHAPE_SPHERE;
		s.src = at;
		s.mat = P->gs.mat;
		memcpy(s.center, c0, sizeof c0);
		s.radius = rad * cbrt(len[0] * len[1] * len[2]);
		if (P->gs.rev != (pmi_det3(m) < 0) && P->gs.area && !P->gs.twosided)
			pmi_note_add(P->d, at, "sphere emitting inward (ReverseOrientation): emits outward in pm");
		if (P->gs.area) {
			area_radiance(&P->gs, 4 * PM_PI * s.radius * s.radius, s.emit);
			s.twosided = P->gs.twosided;
		}
		if (push_shape(P, &s))
			return pm_seterr(P->err, "out of memory");
		return 0;
	} else if (!strcmp(type, "disk")) {
		double rad = pfloat(pl, "radius", 1), ri = pfloat(pl, "innerradius", 0);
		double h = pfloat(pl, "height", 0), phimax = pfloat(pl, "phimax", 360);
		if (pmi_disk_mesh(&s, rad, ri, h, phimax)) {
			pmi_shape_free(&s);
			return pm_seterr(P->err, "out of memory");
		}
		if (P->gs.area) {
			/* The analytic area, as pbrt's Disk::Area. */
			gstate g = P->gs;
			s.src = at;
			s.mat = P->gs.mat;
			pmi_shape_xform(&s, P->gs.ctm, P->gs.rev);
			double sc = sqrt(fabs(pmi_det3(P->gs.ctm)));
			area_radiance(&g, phimax / 360 * PM_PI * (rad * rad - ri * ri) * sc * sc, s.emit);
			s.twosided = g.twosided;
			if (push_shape(P, &s)) {
				pmi_shape_free(&s);
				return pm_seterr(P->err, "out of memory");
			}
			return 0;
		}
	} else if (!strcmp(type, "cylinder") || !strcmp(type, "cone") || !strcmp(type, "paraboloid") ||
	           !strcmp(type, "hyperboloid") || !strcmp(type, "curve")) {
		pmi_note_add(P->d, at, "shape '%s': pm cannot represent it, dropped", type);
		return 0;
	} else
		return pmi_err(P->d, at, P->err, "unknown shape '%s'", type);
	r = finish_mesh(P, L, &s, N, at);
	free(N);
	return r;
}

/* pbrt-v4 does not support area lights in object instances: it warns, and
 * the shape stays in the object without emitting (measured with pbrt-v4;
 * an object made only of such shapes it leaves empty, which pm-import does
 * not imitate). */
static int
do_shape(parser *P, lexer *L, const char *type, plist *pl, pmi_src at)
{
	int area = P->gs.area, r;

	if (P->cur_obj >= 0 && area) {
		pmi_note_add(P->d, at, "area light on a shape inside ObjectBegin: it does not emit (as in pbrt)");
		P->gs.area = 0;
	}
	r = shape_body(P, L, type, pl, at);
	P->gs.area = area;
	return r;
}

/* ---- lights ---- */

static int
do_light(parser *P, lexer *L, const char *type, plist *pl, pmi_src at)
{
	pmi_light *l = pmi_add_light(P->d, at);
	double from[3] = { 0, 0, 0 }, to[3] = { 0, 0, 1 }, col[3] = { 1, 1, 1 };
	double scale = pfloat(pl, "scale", 1), power = pfloat(pl, "power", -1);
	param *p;

	if (!l)
		return pm_seterr(P->err, "out of memory");
	snprintf(l->type, sizeof l->type, "%s", type);
	if ((p = pfind(pl, "from")) && p->nnum == 3)
		memcpy(from, p->num, sizeof from);
	if ((p = pfind(pl, "to")) && p->nnum == 3)
		memcpy(to, p->num, sizeof to);
	pmi_xform_point(P->gs.ctm, from, l->pos);
	double d[3] = { to[0] - from[0], to[1] - from[1], to[2] - from[2] };
	pmi_xform_vector(P->gs.ctm, d, l->dir);
	if (!strcmp(type, "point") || !strcmp(type, "spot") || !strcmp(type, "goniometric") || !strcmp(type, "projection")) {
		if (pcolor(P, L, pl, "I", col, NULL, 0) < 0)
			return -1;
		l->kind = !strcmp(type, "point") ? PMI_LIGHT_POINT : !strcmp(type, "spot") ? PMI_LIGHT_SPOT : PMI_LIGHT_OTHER;
		l->cone = pfloat(pl, "coneangle", 30);
		l->falloff = pfloat(pl, "conedeltaangle", 5);
		/* pbrt-v4: power sets scale so the light emits it: 4 pi I for a
		 * point light, 2 pi I (1 - (cos a0 + cos a1) / 2) for a spot. */
		if (power > 0)
			scale *= l->kind == PMI_LIGHT_SPOT
			    ? power / (2 * PM_PI * (1 - 0.5 * (cos(l->cone * PM_PI / 180) + cos((l->cone - l->falloff) * PM_PI / 180))))
			    : power / (4 * PM_PI);
	} else if (!strcmp(type, "distant")) {
		l->kind = PMI_LIGHT_DISTANT;
		if (pcolor(P, L, pl, "L", col, NULL, 0) < 0)
			return -1;
		double E = pfloat(pl, "illuminance", -1);
		if (E > 0)
			scale *= E;
	} else if (!strcmp(type, "infinite")) {
		l->kind = PMI_LIGHT_INFINITE;
		if (pcolor(P, L, pl, "L", col, NULL, 0) < 0)
			return -1;
		const char *fn = pstring(pl, "filename", "");
		if (fn[0]) {
			if (resolve_path(P, fn, l->map, sizeof l->map))
				return pmi_err(P->d, at, P->err, "infinite: file name too long");
			l->equal_area = 1;
			col[0] = col[1] = col[2] = 1;
			/* The image's frame: the light's transform. */
			l->has_rot = 1;
			for (int i = 0; i < 3; i++)
				for (int k = 0; k < 3; k++)
					l->rot[i][k] = P->gs.ctm.m[i][k];
		}
		/* pbrt-v4: illuminance sets scale so the upward hemisphere
		 * receives it; a constant sky of L gives pi L. */
		double E = pfloat(pl, "illuminance", -1);
		if (E > 0 && !fn[0])
			scale *= E / PM_PI;
		else if (E > 0)
			pmi_note_add(P->d, at, "infinite: illuminance with an image not applied (scale %g used)", scale);
		l->map_scale = scale;
	} else
		return pmi_err(P->d, at, P->err, "unknown light '%s'", type);
	for (int c = 0; c < 3; c++)
		l->color[c] = col[c] * scale;
	return 0;
}

/* ---- textures ---- */

/* The description of a pbrt-v4 texture pm can draw: imagemap and
 * checkerboard with the "uv" mapping (uscale, vscale, udelta, vdelta are
 * pm's scale and offset), and scale of one of those by a constant. Others
 * keep tx->desc 0: the material's constant colour is used and reported. */
static int
describe_texture(parser *P, lexer *L, texture *tx, const char *cls, const char *kind, plist *pl, pmi_src at)
{
	const char *map = pstring(pl, "mapping", "uv");
	pmi_texture t;

	memset(&t, 0, sizeof t);
	t.src = at;
	t.su = pfloat(pl, "uscale", 1);
	t.sv = pfloat(pl, "vscale", 1);
	t.ou = pfloat(pl, "udelta", 0);
	t.ov = pfloat(pl, "vdelta", 0);
	if (!strcmp(cls, "scale")) {
		/* scale: "tex" times "scale", either a texture or a constant. */
		param *pt = pfind(pl, "tex");
		double k = pfloat(pl, "scale", 1);
		if (!pt || strcmp(pt->type, "texture") || pt->nstr != 1 || (pfind(pl, "scale") && strcmp(pfind(pl, "scale")->type, "float")))
			return 0;
		for (int i = 0; i < P->ntex; i++)
			if (!strcmp(P->tex[i].name, pt->str[0]) && P->tex[i].desc) {
				t = P->d->texs[P->tex[i].desc - 1];
				if (t.kind == PMI_TEX_CHECKER)
					for (int c = 0; c < 3; c++)
						t.c[0][c] *= k, t.c[1][c] *= k;
				else if (k != 1)
					pmi_note_add(P->d, at, "scale texture: factor %g on an image dropped (pm images are "
					             "not scaled)", k);
				goto add;
			}
		return 0;
	}
	if (strcmp(map, "uv") != 0) {
		pmi_note_add(P->d, at, "texture mapping '%s' not mapped: the material's constant colour used", map);
		return 0;
	}
	if (!strcmp(cls, "imagemap")) {
		const char *fn = pstring(pl, "filename", NULL);
		if (!fn)
			return pmi_err(P->d, at, P->err, "imagemap: no \"string filename\"");
		t.kind = PMI_TEX_IMAGE;
		if (resolve_path(P, fn, t.file, sizeof t.file))
			return pmi_err(P->d, at, P->err, "imagemap: file name too long");
		if (pfloat(pl, "scale", 1) != 1 || pbool(pl, "invert", 0))
			pmi_note_add(P->d, at, "imagemap: scale/invert dropped (pm images are used as they are)");
		const char *enc = pstring(pl, "encoding", "sRGB");
		if (strcmp(enc, "sRGB") != 0)
			pmi_note_add(P->d, at, "imagemap: encoding '%s' not applied (pm decodes 8-bit images as sRGB)", enc);
	} else if (!strcmp(cls, "checkerboard")) {
		if ((int)pfloat(pl, "dimension", 2) != 2) {
			pmi_note_add(P->d, at, "3D checkerboard not mapped: the material's constant colour used");
			return 0;
		}
		t.kind = PMI_TEX_CHECKER;
		t.c[0][0] = t.c[0][1] = t.c[0][2] = 1;
		int r0 = pcolor(P, L, pl, "tex1", t.c[0], NULL, 0), r1 = pcolor(P, L, pl, "tex2", t.c[1], NULL, 0);
		if (r0 < 0 || r1 < 0)
			return -1;
		if (r0 == 2 || r1 == 2) {
			pmi_note_add(P->d, at, "checkerboard of textures not mapped: the material's constant colour used");
			return 0;
		}
	} else
		return 0;
	(void)kind;
add:;
	pmi_texture *d = pmi_add_texture(P->d, at);
	if (!d)
		return pm_seterr(P->err, "out of memory");
	*d = t;
	tx->desc = (int)P->d->ntexs;
	return 0;
}

/* ---- the directives ---- */

static int parse_file(parser *P, const char *path, pmi_src from);

static int
want(parser *P, lexer *L, token *t, int kind, const char *dir, const char *what)
{
	if (lex_next(P, L, t))
		return -1;
	if (t->kind != kind) {
		tok_free(t);
		return pmi_err(P->d, src_at(L, t->line), P->err, "%s: expected %s", dir, what);
	}
	return 0;
}

/* n numbers, bracketed or not. */
static int
numbers(parser *P, lexer *L, const char *dir, double *v, int n)
{
	token t, *pk;
	int br = 0;

	if (lex_peek(P, L, &pk))
		return -1;
	if (pk->kind == TK_LBRACK) {
		lex_next(P, L, &t);
		br = 1;
	}
	for (int i = 0; i < n; i++) {
		if (lex_next(P, L, &t))
			return -1;
		if (t.kind != TK_WORD || parse_number(t.s, &v[i])) {
			tok_free(&t);
			return pmi_err(P->d, src_at(L, t.line), P->err, "%s: expected %d numbers", dir, n);
		}
		tok_free(&t);
	}
	if (br) {
		if (lex_next(P, L, &t))
			return -1;
		if (t.kind != TK_RBRACK) {
			tok_free(&t);
			return pmi_err(P->d, src_at(L, t.line), P->err, "%s: expected ']' after %d numbers", dir, n);
		}
	}
	return 0;
}

static pmi_mat4
from_pbrt_matrix(const double v[16])
{
	pmi_mat4 m;

	/* pbrt's Transform and ConcatTransform list the matrix column by
	 * column (it transposes what it reads). */
	for (int i = 0; i < 4; i++)
		for (int j = 0; j < 4; j++)
			m.m[i][j] = v[4 * j + i];
	return m;
}

static int
do_camera(parser *P, lexer *L, const char *type, plist *pl, pmi_src at)
{
	pmi_camera *c = &P->d->cam;
	pmi_mat4 w;

	if (strcmp(type, "perspective") != 0)
		return pmi_err(P->d, at, P->err, "camera '%s': pm has only the perspective (pinhole) camera", type);
	if (pmi_invert(P->gs.ctm, &w))
		return pmi_err(P->d, at, P->err, "camera: the current transform is singular");
	double o[3] = { 0, 0, 0 }, ex[3] = { 1, 0, 0 }, ey[3] = { 0, 1, 0 }, ez[3] = { 0, 0, 1 };
	c->set = 1;
	c->src = at;
	pmi_xform_point(w, o, c->pos);
	pmi_xform_vector(w, ex, c->right);
	pmi_xform_vector(w, ey, c->up);
	pmi_xform_vector(w, ez, c->fwd);
	c->fov = pfloat(pl, "fov", 90);
	c->fov_axis = PMI_FOV_SHORTER;
	if (pfloat(pl, "lensradius", 0) > 0)
		pmi_note_add(P->d, at, "camera: depth of field (lensradius) dropped: a pinhole");
	if (pfind(pl, "screenwindow") || pfind(pl, "frameaspectratio"))
		pmi_note_add(P->d, at, "camera: screenwindow/frameaspectratio dropped");
	if (!(c->fov > 0 && c->fov < 180))
		return pmi_err(P->d, at, P->err, "camera: fov %g not in (0, 180)", c->fov);
	return add_named(&P->coords, &P->ncoords, "camera", 0, w) ? pm_seterr(P->err, "out of memory") : 0;
}

static int
push_state(parser *P, int transform_only)
{
	if (P->nstack == P->capstack) {
		int nc = P->capstack ? 2 * P->capstack : 16;
		gstate *s = realloc(P->stack, nc * sizeof *s);
		if (!s)
			return pm_seterr(P->err, "out of memory");
		P->stack = s;
		P->capstack = nc;
	}
	P->stack[P->nstack] = P->gs;
	P->stack[P->nstack++].transform_only = transform_only;
	return 0;
}

static int
pop_state(parser *P, lexer *L, int line, int transform_only, const char *dir)
{
	if (P->nstack == 0)
		return pmi_err(P->d, src_at(L, line), P->err, "%s without a matching begin", dir);
	gstate *s = &P->stack[--P->nstack];
	if (s->transform_only != transform_only)
		return pmi_err(P->d, src_at(L, line), P->err, "%s closes a %s", dir,
		               s->transform_only ? "TransformBegin" : "AttributeBegin");
	if (transform_only)
		P->gs.ctm = s->ctm;
	else
		P->gs = *s;
	return 0;
}

static int
copy_shape(pmi_shape *dst, const pmi_shape *src)
{
	*dst = *src;
	dst->v = dst->uv = dst->n = NULL;
	dst->idx = dst->start = NULL;
	if (src->kind != PMI_SHAPE_MESH)
		return 0;
	size_t nc = src->start[src->nface];
	if (pmi_mesh_alloc(dst, src->nv, src->nface, nc, src->uv != NULL))
		return -1;
	memcpy(dst->v, src->v, src->nv * 3 * sizeof *dst->v);
	if (src->uv)
		memcpy(dst->uv, src->uv, src->nv * 2 * sizeof *dst->uv);
	if (src->n) {
		if (!(dst->n = malloc(src->nv * 3 * sizeof *dst->n)))
			return -1;
		memcpy(dst->n, src->n, src->nv * 3 * sizeof *dst->n);
	}
	memcpy(dst->start, src->start, (src->nface + 1) * sizeof *dst->start);
	memcpy(dst->idx, src->idx, nc * sizeof *dst->idx);
	return 0;
}

static int
directive(parser *P, lexer *L, token *t)
{
	const char *d = t->s;
	pmi_src at = src_at(L, t->line);
	plist pl = { NULL, 0 };
	token a;
	double v[16];
	int r = 0;

#define ARG_STR() do { if (want(P, L, &a, TK_STR, d, "a quoted string")) return -1; } while (0)
	if (!strcmp(d, "Translate") || !strcmp(d, "Scale")) {
		if (numbers(P, L, d, v, 3))
			return -1;
		P->gs.ctm = pmi_mul(P->gs.ctm, d[0] == 'T' ? pmi_translate(v[0], v[1], v[2]) : pmi_scale(v[0], v[1], v[2]));
	} else if (!strcmp(d, "Rotate")) {
		if (numbers(P, L, d, v, 4))
			return -1;
		P->gs.ctm = pmi_mul(P->gs.ctm, pmi_rotate(v[0], v[1], v[2], v[3]));
	} else if (!strcmp(d, "LookAt")) {
		if (numbers(P, L, d, v, 9))
			return -1;
		/* pbrt's LookAt: the camera's x is up x dir, its y dir x x. */
		double dir[3] = { v[3] - v[0], v[4] - v[1], v[5] - v[2] }, up[3] = { v[6], v[7], v[8] };
		double dl = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
		double ul = sqrt(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]);
		if (!(dl > 0) || !(ul > 0))
			return pmi_err(P->d, at, P->err, "LookAt: eye equals look, or up is 0");
		for (int i = 0; i < 3; i++) {
			dir[i] /= dl;
			up[i] /= ul;
		}
		double rt[3] = { up[1] * dir[2] - up[2] * dir[1], up[2] * dir[0] - up[0] * dir[2], up[0] * dir[1] - up[1] * dir[0] };
		double rl = sqrt(rt[0] * rt[0] + rt[1] * rt[1] + rt[2] * rt[2]);
		if (!(rl > 1e-9))
			return pmi_err(P->d, at, P->err, "LookAt: up is parallel to the view direction");
		for (int i = 0; i < 3; i++)
			rt[i] /= rl;
		double nu[3] = { dir[1] * rt[2] - dir[2] * rt[1], dir[2] * rt[0] - dir[0] * rt[2], dir[0] * rt[1] - dir[1] * rt[0] };
		pmi_mat4 wc = pmi_identity(), cw;
		for (int i = 0; i < 3; i++) {
			wc.m[i][0] = rt[i];
			wc.m[i][1] = nu[i];
			wc.m[i][2] = dir[i];
			wc.m[i][3] = v[i];
		}
		pmi_invert(wc, &cw);
		P->gs.ctm = pmi_mul(P->gs.ctm, cw);
	} else if (!strcmp(d, "Transform") || !strcmp(d, "ConcatTransform")) {
		if (numbers(P, L, d, v, 16))
			return -1;
		pmi_mat4 m = from_pbrt_matrix(v);
		P->gs.ctm = d[0] == 'T' ? m : pmi_mul(P->gs.ctm, m);
	} else if (!strcmp(d, "Identity")) {
		P->gs.ctm = pmi_identity();
	} else if (!strcmp(d, "CoordinateSystem") || !strcmp(d, "CoordSysTransform")) {
		ARG_STR();
		if (d[5] == 'i') {
			if (add_named(&P->coords, &P->ncoords, a.s, 0, P->gs.ctm))
				return pm_seterr(P->err, "out of memory");
		} else {
			int i = find_named(P->coords, P->ncoords, a.s);
			if (i < 0)
				return pmi_err(P->d, at, P->err, "CoordSysTransform: unknown coordinate system '%s'", a.s);
			P->gs.ctm = P->coords[i].m;
		}
	} else if (!strcmp(d, "AttributeBegin") || !strcmp(d, "TransformBegin")) {
		return push_state(P, d[0] == 'T');
	} else if (!strcmp(d, "AttributeEnd") || !strcmp(d, "TransformEnd")) {
		return pop_state(P, L, t->line, d[0] == 'T', d);
	} else if (!strcmp(d, "ReverseOrientation")) {
		P->gs.rev = !P->gs.rev;
	} else if (!strcmp(d, "WorldBegin")) {
		P->gs.ctm = pmi_identity();
		if (add_named(&P->coords, &P->ncoords, "world", 0, P->gs.ctm))
			return pm_seterr(P->err, "out of memory");
	} else if (!strcmp(d, "WorldEnd")) {
		;
	} else if (!strcmp(d, "ActiveTransform")) {
		if (want(P, L, &a, TK_WORD, d, "All, StartTime or EndTime"))
			return -1;
		if (strcmp(a.s, "All") != 0)
			pmi_note_add(P->d, at, "ActiveTransform %s: motion blur dropped, both times use the same transforms", a.s);
		tok_free(&a);
	} else if (!strcmp(d, "TransformTimes")) {
		return numbers(P, L, d, v, 2);
	} else if (!strcmp(d, "Include") || !strcmp(d, "Import")) {
		char path[4096];
		ARG_STR();
		if (resolve_path(P, a.s, path, sizeof path))
			return pmi_err(P->d, at, P->err, "%s: path too long", d);
		return parse_file(P, path, at);
	} else if (!strcmp(d, "ObjectBegin")) {
		ARG_STR();
		if (P->cur_obj >= 0)
			return pmi_err(P->d, at, P->err, "ObjectBegin inside ObjectBegin");
		object *o = realloc(P->objs, (P->nobjs + 1) * sizeof *o);
		if (!o)
			return pm_seterr(P->err, "out of memory");
		P->objs = o;
		memset(&o[P->nobjs], 0, sizeof *o);
		if (!(o[P->nobjs].name = strdup(a.s)))
			return pm_seterr(P->err, "out of memory");
		P->cur_obj = P->nobjs++;
		return push_state(P, 0);
	} else if (!strcmp(d, "ObjectEnd")) {
		if (P->cur_obj < 0)
			return pmi_err(P->d, at, P->err, "ObjectEnd without ObjectBegin");
		P->cur_obj = -1;
		return pop_state(P, L, t->line, 0, "ObjectEnd");
	} else if (!strcmp(d, "ObjectInstance")) {
		ARG_STR();
		int i;
		for (i = P->nobjs - 1; i >= 0; i--)
			if (!strcmp(P->objs[i].name, a.s))
				break;
		if (i < 0)
			return pmi_err(P->d, at, P->err, "ObjectInstance: unknown object '%s'", a.s);
		for (size_t k = 0; k < P->objs[i].n; k++) {
			pmi_shape c;
			if (copy_shape(&c, &P->objs[i].shapes[k])) {
				pmi_shape_free(&c);
				return pm_seterr(P->err, "out of memory");
			}
			pmi_shape_xform(&c, P->gs.ctm, 0);
			if (push_shape(P, &c)) {
				pmi_shape_free(&c);
				return pm_seterr(P->err, "out of memory");
			}
		}
	} else if (!strcmp(d, "Camera") || !strcmp(d, "Film") || !strcmp(d, "Shape") || !strcmp(d, "Material") ||
	           !strcmp(d, "MakeNamedMaterial") || !strcmp(d, "LightSource") || !strcmp(d, "AreaLightSource") ||
	           !strcmp(d, "Sampler") || !strcmp(d, "Integrator") || !strcmp(d, "PixelFilter") ||
	           !strcmp(d, "Accelerator") || !strcmp(d, "ColorSpace") || !strcmp(d, "MakeNamedMedium") ||
	           !strcmp(d, "Attribute")) {
		ARG_STR();
		if (parse_params(P, L, &pl)) {
			plist_free(&pl);
			return -1;
		}
		if (!strcmp(d, "Camera"))
			r = do_camera(P, L, a.s, &pl, at);
		else if (!strcmp(d, "Film")) {
			P->film_w = (int)pfloat(&pl, "xresolution", 1280);
			P->film_h = (int)pfloat(&pl, "yresolution", 720);
			P->film_src = at;
			if (pfind(&pl, "cropwindow") || pfind(&pl, "pixelbounds"))
				pmi_note_add(P->d, at, "Film: cropwindow/pixelbounds dropped: the whole image");
		} else if (!strcmp(d, "Shape"))
			r = do_shape(P, L, a.s, &pl, at);
		else if (!strcmp(d, "Material") || !strcmp(d, "MakeNamedMaterial")) {
			pmi_material *m = pmi_add_material(P->d, at);
			int idx = (int)P->d->nmats - 1;
			if (!m)
				r = pm_seterr(P->err, "out of memory");
			else if (d[0] == 'M' && d[1] == 'a' && d[4] == 'N') {
				const char *type = pstring(&pl, "type", NULL);
				snprintf(m->name, sizeof m->name, "%s", a.s);
				if (!type)
					r = pmi_err(P->d, at, P->err, "MakeNamedMaterial '%s': no \"string type\"", a.s);
				else
					P->last_tex = 0;
				r = !strcmp(type, "mix") ? make_mix(P, L, m, &pl, at) : make_material(P, L, m, type, &pl, at);
				if (m->texture[0])
					m->tex = P->last_tex;
				if (!r && add_named(&P->mats, &P->nmats, a.s, idx, pmi_identity()))
					r = pm_seterr(P->err, "out of memory");
			} else {
				P->last_tex = 0;
				r = !strcmp(a.s, "mix") ? make_mix(P, L, m, &pl, at) : make_material(P, L, m, a.s, &pl, at);
				if (m->texture[0])
					m->tex = P->last_tex;
				P->gs.mat = idx;
			}
		} else if (!strcmp(d, "LightSource"))
			r = do_light(P, L, a.s, &pl, at);
		else if (!strcmp(d, "AreaLightSource")) {
			if (strcmp(a.s, "diffuse") != 0)
				r = pmi_err(P->d, at, P->err, "AreaLightSource '%s': only \"diffuse\" exists", a.s);
			else {
				P->gs.area = 1;
				P->gs.L[0] = P->gs.L[1] = P->gs.L[2] = 1;
				if (pcolor(P, L, &pl, "L", P->gs.L, NULL, 0) < 0)
					r = -1;
				P->gs.scale = pfloat(&pl, "scale", 1);
				P->gs.power = pfloat(&pl, "power", -1);
				P->gs.twosided = pbool(&pl, "twosided", 0);
				P->gs.area_src = at;
				if (pfind(&pl, "filename"))
					pmi_note_add(P->d, at, "AreaLightSource: image (filename) dropped, L used");
			}
		} else if (!strcmp(d, "Integrator")) {
			double md = pfloat(&pl, "maxdepth", 5);
			if (md < 64)
				pmi_note_add(P->d, at, "Integrator maxdepth %g: pm follows paths up to 64 bounces "
				             "(brighter where light interreflects)", md);
		} else if (!strcmp(d, "MakeNamedMedium"))
			pmi_note_add(P->d, at, "medium '%s': participating media dropped", a.s);
		else if (!strcmp(d, "Attribute"))
			pmi_note_add(P->d, at, "Attribute \"%s\": default parameters dropped", a.s);
	} else if (!strcmp(d, "Option")) {
		/* Option "type name" VALUE: renderer settings, none of them pm's. */
		token t, *pk;
		ARG_STR();
		if (lex_peek(P, L, &pk))
			return -1;
		if (pk->kind == TK_LBRACK) {
			lex_next(P, L, &t);
			do {
				if (lex_next(P, L, &t))
					return -1;
				if (t.kind == TK_EOF)
					return pmi_err(P->d, at, P->err, "Option: missing ']'");
				int k = t.kind;
				tok_free(&t);
				if (k == TK_RBRACK)
					break;
			} while (1);
		} else if (pk->kind == TK_WORD || pk->kind == TK_STR) {
			lex_next(P, L, &t);
			tok_free(&t);
		} else
			return pmi_err(P->d, at, P->err, "Option: no value");
	} else if (!strcmp(d, "NamedMaterial")) {
		ARG_STR();
		int i = find_named(P->mats, P->nmats, a.s);
		if (i < 0)
			return pmi_err(P->d, at, P->err, "NamedMaterial: unknown material '%s'", a.s);
		P->gs.mat = P->mats[i].index;
	} else if (!strcmp(d, "Texture")) {
		token cls, kind;
		ARG_STR();
		char *name = strdup(a.s);
		if (!name)
			return pm_seterr(P->err, "out of memory");
		if (want(P, L, &kind, TK_STR, d, "a type") || want(P, L, &cls, TK_STR, d, "a class") || parse_params(P, L, &pl)) {
			free(name);
			plist_free(&pl);
			return -1;
		}
		texture *tx = realloc(P->tex, (P->ntex + 1) * sizeof *tx);
		if (!tx) {
			free(name);
			plist_free(&pl);
			return pm_seterr(P->err, "out of memory");
		}
		P->tex = tx;
		tx = &P->tex[P->ntex++];
		memset(tx, 0, sizeof *tx);
		tx->name = name;
		if (!strcmp(cls.s, "constant")) {
			tx->constant = 1;
			tx->value[0] = tx->value[1] = tx->value[2] = 1;
			r = pcolor(P, L, &pl, "value", tx->value, NULL, 0) < 0 ? -1 : 0;
		} else {
			snprintf(tx->file, sizeof tx->file, "%s", pstring(&pl, "filename", cls.s));
			r = describe_texture(P, L, tx, cls.s, kind.s, &pl, at);
		}
	} else if (!strcmp(d, "MediumInterface")) {
		token b, *pk;
		ARG_STR();
		if (lex_peek(P, L, &pk))
			return -1;
		if (pk->kind == TK_STR)
			lex_next(P, L, &b);
	} else
		return pmi_err(P->d, at, P->err, "unknown directive '%s'", d);
	plist_free(&pl);
	return r;
#undef ARG_STR
}

static int
parse_file(parser *P, const char *path, pmi_src from)
{
	lexer L;
	FILE *f;
	int r = 0;

	if (P->depth >= MAX_INCLUDE_DEPTH)
		return pmi_err(P->d, from, P->err, "includes nested more than %d deep", MAX_INCLUDE_DEPTH);
	for (int i = 0; i < P->depth; i++)
		if (!strcmp(P->open_files[i], path))
			return pmi_err(P->d, from, P->err, "'%s' includes itself (recursion)", path);
	memset(&L, 0, sizeof L);
	L.line = 1;
	if ((L.file = pmi_file(P->d, path)) < 0)
		return pm_seterr(P->err, "out of memory");
	if (!(f = fopen(path, "rb"))) {
		if (from.line)
			return pmi_err(P->d, from, P->err, "cannot open '%s': %s", path, strerror(errno));
		return pm_seterr(P->err, "cannot open '%s': %s", path, strerror(errno));
	}
	size_t cap = 1 << 16;
	L.buf = malloc(cap + 1);
	for (size_t n; L.buf && (n = fread(L.buf + L.len, 1, cap - L.len, f)) > 0;) {
		L.len += n;
		if (L.len == cap) {
			if (cap >= MAX_FILE_BYTES) {
				free(L.buf);
				fclose(f);
				return pmi_err(P->d, (pmi_src){ L.file, 0 }, P->err, "larger than 1 GiB");
			}
			char *nb = realloc(L.buf, 2 * cap + 1);
			if (!nb) {
				free(L.buf);
				L.buf = NULL;
				break;
			}
			L.buf = nb;
			cap *= 2;
		}
	}
	int rerr = ferror(f);
	fclose(f);
	if (!L.buf)
		return pm_seterr(P->err, "out of memory");
	if (rerr) {
		free(L.buf);
		return pmi_err(P->d, (pmi_src){ L.file, 0 }, P->err, "read error");
	}
	L.buf[L.len] = 0;
	if (memchr(L.buf, 0, L.len)) {
		free(L.buf);
		return pmi_err(P->d, (pmi_src){ L.file, 0 }, P->err, "a NUL byte: not a pbrt text file");
	}
	P->open_files[P->depth++] = (char *)path;
	for (;;) {
		token t;
		if ((r = lex_next(P, &L, &t)))
			break;
		if (t.kind == TK_EOF)
			break;
		if (t.kind != TK_WORD) {
			r = pmi_err(P->d, src_at(&L, t.line), P->err, "expected a directive, got %s",
			            t.kind == TK_STR ? "a string" : "a bracket");
			break;
		}
		r = directive(P, &L, &t);
		tok_free(&t);
		if (r)
			break;
	}
	if (L.has_peek)
		tok_free(&L.peek);
	P->depth--;
	free(L.buf);
	return r;
}

int
pmi_read_pbrt(const char *path, pmi_desc *d, pm_error *err)
{
	parser P;
	int r;

	memset(&P, 0, sizeof P);
	P.d = d;
	P.err = err;
	P.cur_obj = -1;
	P.gs.ctm = pmi_identity();
	P.gs.mat = -1;
	P.default_mat = -1;
	P.film_w = 1280;
	P.film_h = 720;
	const char *sl = strrchr(path, '/');
	if (sl)
		snprintf(P.dir, sizeof P.dir, "%.*s/", (int)(sl - path), path);
	r = parse_file(&P, path, (pmi_src){ 0, 0 });
	if (!r && P.cur_obj >= 0)
		r = pmi_err(d, (pmi_src){ 0, 0 }, err, "ObjectBegin '%s' never ends", P.objs[P.cur_obj].name);
	if (!r && !d->cam.set) {
		/* pbrt's default camera: at the origin looking down +z, fov 90. */
		d->cam.set = 1;
		d->cam.right[0] = d->cam.up[1] = d->cam.fwd[2] = 1;
		d->cam.fov = 90;
		d->cam.fov_axis = PMI_FOV_SHORTER;
		pmi_note_add(d, (pmi_src){ 0, 0 }, "no Camera: pbrt's default (origin, +z, fov 90)");
	}
	d->cam.width = P.film_w;
	d->cam.height = P.film_h;
	if (!r && (P.film_w < 1 || P.film_h < 1))
		r = pmi_err(d, P.film_src, err, "Film: resolution %dx%d", P.film_w, P.film_h);
	/* Shapes with no material get pbrt's default: diffuse 0.5. */
	for (size_t i = 0; !r && i < d->nshapes; i++)
		if (d->shapes[i].mat < 0) {
			if (P.default_mat < 0) {
				pmi_material *m = pmi_add_material(d, d->shapes[i].src);
				if (!m) {
					r = pm_seterr(err, "out of memory");
					break;
				}
				snprintf(m->type, sizeof m->type, "diffuse");
				snprintf(m->name, sizeof m->name, "default");
				m->color[0] = m->color[1] = m->color[2] = 0.5;
				P.default_mat = (int)d->nmats - 1;
			}
			d->shapes[i].mat = P.default_mat;
		}
	for (int i = 0; i < P.nmats; i++)
		free(P.mats[i].name);
	free(P.mats);
	for (int i = 0; i < P.ncoords; i++)
		free(P.coords[i].name);
	free(P.coords);
	for (int i = 0; i < P.ntex; i++)
		free(P.tex[i].name);
	free(P.tex);
	for (int i = 0; i < P.nobjs; i++) {
		for (size_t k = 0; k < P.objs[i].n; k++)
			pmi_shape_free(&P.objs[i].shapes[k]);
		free(P.objs[i].shapes);
		free(P.objs[i].name);
	}
	free(P.objs);
	free(P.stack);
	return r;
}
