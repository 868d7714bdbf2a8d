/* mitsuba.c — the Mitsuba 3 XML reader (readers.h). expat parses each file
 * into a small tree (elements, attributes, lines); <include>s are spliced
 * in, <default>s fill $name, and the tree is then read as Mitsuba reads
 * it: a sensor (perspective, fov_axis, to_world), a film, bsdfs by id or
 * nested, shapes (obj, ply, rectangle, cube, sphere, disk) with their area
 * emitters, and the other emitters. Mitsuba's camera looks along +z with
 * +x to the image's left; its to_world children apply in the order
 * written (each one after the ones before). */
#include <errno.h>
#include <expat.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec.h"
#include "import/ply.h"
#include "import/readers.h"

#define MAX_DEPTH 16

typedef struct xnode {
	char *name;
	char **attr;          /* key, value, ... */
	int nattr;
	struct xnode **kids;
	int nkids;
	pmi_src src;
} xnode;

typedef struct xparse {
	xnode *root, *stack[256];
	int depth, overflow, oom;
	int file;
	XML_Parser p;
} xparse;

typedef struct mreader {
	pmi_desc *d;
	pm_error *err;
	char dir[4096];
	char **defs;          /* name, value, ... from <default> */
	int ndefs;
	struct { char *id; int mat; } *bsdfs;
	int nbsdfs;
	struct { char *id; char file[256]; int desc; } *texs;
	int ntexs;
	int last_tex;        /* 1 + the desc texture pcolor last met, or 0 */
	int default_mat;
	const char *open_files[MAX_DEPTH];
	int nopen;
} mreader;

static void
xfree(xnode *n)
{
	if (!n)
		return;
	free(n->name);
	for (int i = 0; i < n->nattr; i++)
		free(n->attr[i]);
	free(n->attr);
	for (int i = 0; i < n->nkids; i++)
		xfree(n->kids[i]);
	free(n->kids);
	free(n);
}

static void XMLCALL
on_start(void *ud, const XML_Char *name, const XML_Char **atts)
{
	xparse *x = ud;
	xnode *n;

	if (x->oom || x->overflow)
		return;
	if (x->depth == 256) {
		x->overflow = 1;
		return;
	}
	if (!(n = calloc(1, sizeof *n)) || !(n->name = strdup(name))) {
		free(n);
		x->oom = 1;
		return;
	}
	n->src.file = x->file;
	n->src.line = (int)XML_GetCurrentLineNumber(x->p);
	for (int i = 0; atts[i]; i++)
		n->nattr++;
	if (n->nattr && !(n->attr = calloc(n->nattr, sizeof *n->attr)))
		x->oom = 1;
	for (int i = 0; !x->oom && i < n->nattr; i++)
		if (!(n->attr[i] = strdup(atts[i])))
			x->oom = 1;
	if (x->depth == 0)
		x->root = n;
	else {
		xnode *p = x->stack[x->depth - 1];
		xnode **k = realloc(p->kids, (p->nkids + 1) * sizeof *k);
		if (!k) {
			x->oom = 1;
			xfree(n);
			return;
		}
		p->kids = k;
		k[p->nkids++] = n;
	}
	x->stack[x->depth++] = n;
}

static void XMLCALL
on_end(void *ud, const XML_Char *name)
{
	xparse *x = ud;

	(void)name;
	if (x->depth > 0 && !x->overflow)
		x->depth--;
}

/* Parses path into a tree; errors name the file and line. */
static int
xml_load(mreader *M, const char *path, pmi_src from, xnode **out)
{
	FILE *f;
	xparse x;
	XML_Parser p;
	char buf[65536];
	int file = pmi_file(M->d, path), r = 0;

	*out = NULL;
	if (file < 0)
		return pm_seterr(M->err, "out of memory");
	if (!(f = fopen(path, "rb"))) {
		if (from.line)
			return pmi_err(M->d, from, M->err, "cannot open '%s': %s", path, strerror(errno));
		return pm_seterr(M->err, "cannot open '%s': %s", path, strerror(errno));
	}
	memset(&x, 0, sizeof x);
	x.file = file;
	if (!(p = XML_ParserCreate(NULL))) {
		fclose(f);
		return pm_seterr(M->err, "out of memory");
	}
	x.p = p;
	XML_SetUserData(p, &x);
	XML_SetElementHandler(p, on_start, on_end);
	for (;;) {
		size_t n = fread(buf, 1, sizeof buf, f);
		int last = n < sizeof buf;
		if (XML_Parse(p, buf, (int)n, last) == XML_STATUS_ERROR) {
			r = pmi_err(M->d, (pmi_src){ file, (int)XML_GetCurrentLineNumber(p) }, M->err, "XML: %s",
			            XML_ErrorString(XML_GetErrorCode(p)));
			break;
		}
		if (x.oom || x.overflow) {
			r = x.oom ? pm_seterr(M->err, "out of memory")
			          : pmi_err(M->d, (pmi_src){ file, (int)XML_GetCurrentLineNumber(p) }, M->err, "elements nested too deep");
			break;
		}
		if (last)
			break;
	}
	fclose(f);
	XML_ParserFree(p);
	if (r) {
		xfree(x.root);
		return -1;
	}
	*out = x.root;
	return 0;
}

/* ---- attributes and properties ---- */

static const char *
raw_attr(const xnode *n, const char *key)
{
	for (int i = 0; i + 1 < n->nattr; i += 2)
		if (!strcmp(n->attr[i], key))
			return n->attr[i + 1];
	return NULL;
}

/* An attribute with $name replaced by its <default> (static storage). */
static const char *
attr(mreader *M, const xnode *n, const char *key)
{
	static char buf[4096];
	const char *v = raw_attr(n, key);

	if (!v || !strchr(v, '$'))
		return v;
	size_t k = 0;
	for (const char *p = v; *p && k + 1 < sizeof buf;) {
		if (*p == '$') {
			size_t l = 1;
			while (p[l] == '_' || (p[l] >= 'a' && p[l] <= 'z') || (p[l] >= 'A' && p[l] <= 'Z') || (p[l] >= '0' && p[l] <= '9'))
				l++;
			int found = 0;
			for (int i = 0; i + 1 < 2 * M->ndefs; i += 2)
				if (strlen(M->defs[i]) == l - 1 && !strncmp(M->defs[i], p + 1, l - 1)) {
					k += snprintf(buf + k, sizeof buf - k, "%s", M->defs[i + 1]);
					found = 1;
					break;
				}
			if (found) {
				p += l;
				continue;
			}
		}
		buf[k++] = *p++;
	}
	buf[k < sizeof buf ? k : sizeof buf - 1] = 0;
	return buf;
}

/* Up to n numbers separated by commas or spaces; returns how many. */
static int
numbers(const char *s, double *v, int n)
{
	int k = 0;
	char *end;

	while (s && *s && k < n) {
		while (*s == ' ' || *s == ',' || *s == '\t' || *s == '\n')
			s++;
		if (!*s)
			break;
		v[k] = strtod(s, &end);
		if (end == s)
			return -1;
		k++;
		s = end;
	}
	while (s && (*s == ' ' || *s == ',' || *s == '\t' || *s == '\n'))
		s++;
	return s && *s ? -1 : k;
}

/* The child property element named name (any tag), or NULL. */
static const xnode *
prop(mreader *M, const xnode *n, const char *name)
{
	for (int i = 0; i < n->nkids; i++) {
		const char *nm = attr(M, n->kids[i], "name");
		if (nm && !strcmp(nm, name))
			return n->kids[i];
	}
	return NULL;
}

static int
pfloat(mreader *M, const xnode *n, const char *name, double def, double *out)
{
	const xnode *p = prop(M, n, name);
	double v;

	*out = def;
	if (!p)
		return 0;
	if (numbers(attr(M, p, "value"), &v, 1) != 1)
		return pmi_err(M->d, p->src, M->err, "'%s': value is not a number", name);
	*out = v;
	return 0;
}

static const char *
pstring(mreader *M, const xnode *n, const char *name)
{
	const xnode *p = prop(M, n, name);
	return p ? attr(M, p, "value") : NULL;
}

static int
pbool(mreader *M, const xnode *n, const char *name)
{
	const char *v = pstring(M, n, name);
	return v && !strcmp(v, "true");
}

static int pcolor(mreader *M, const xnode *n, const char *name, double out[3], char *tex, size_t ntex);
static int resolve(mreader *M, const char *fn, char *out, size_t n);

/* A texture node pm can draw as a description texture: bitmap and
 * checkerboard (Mitsuba's squares are half a unit: pm's scale 2 2).
 * Returns 1 + its index, 0 for others (the constant colour is used and
 * reported), -1 on error. A to_uv transform is dropped with a note. */
static int
describe_texture(mreader *M, const xnode *n)
{
	const char *type = attr(M, n, "type");
	pmi_texture t;

	memset(&t, 0, sizeof t);
	t.su = t.sv = 1;
	if (!type)
		return 0;
	if (!strcmp(type, "bitmap")) {
		const char *fn = pstring(M, n, "filename");
		if (!fn)
			return pmi_err(M->d, n->src, M->err, "bitmap: no filename");
		if (resolve(M, fn, t.file, sizeof t.file))
			return pmi_err(M->d, n->src, M->err, "bitmap: file name too long");
		t.kind = PMI_TEX_IMAGE;
		/* Mitsuba's bitmap has v = 0 on its top row, pm's image on its
		 * bottom row: v becomes 1 - v. */
		t.sv = -1;
		t.ov = 1;
		const char *raw = pstring(M, n, "raw");
		if (raw && !strcmp(raw, "true"))
			pmi_note_add(M->d, n->src, "bitmap: raw (no sRGB decoding) not applied");
	} else if (!strcmp(type, "checkerboard")) {
		t.kind = PMI_TEX_CHECKER;
		t.su = t.sv = 2;
		t.c[0][0] = t.c[0][1] = t.c[0][2] = 0.4;
		t.c[1][0] = t.c[1][1] = t.c[1][2] = 0.2;
		int last = M->last_tex;
		if (pcolor(M, n, "color0", t.c[0], NULL, 0) < 0 || pcolor(M, n, "color1", t.c[1], NULL, 0) < 0)
			return -1;
		M->last_tex = last;
	} else
		return 0;
	for (int i = 0; i < n->nkids; i++)
		if (!strcmp(n->kids[i]->name, "transform")) {
			pmi_note_add(M->d, n->kids[i]->src, "texture %s: its transform dropped", type);
			break;
		}
	pmi_texture *d = pmi_add_texture(M->d, n->src);
	if (!d)
		return pm_seterr(M->err, "out of memory");
	t.src = n->src;
	*d = t;
	return (int)M->d->ntexs;
}

/* A colour property: rgb (3 numbers or 1), float, spectrum (a constant or
 * wavelength:value pairs, whose mean is taken), or a texture (its file in
 * tex). Returns 1 set, 0 absent, -1 error. */
static int
pcolor(mreader *M, const xnode *n, const char *name, double out[3], char *tex, size_t ntex)
{
	const xnode *p = prop(M, n, name);

	if (!p) {
		/* A reference to a texture by id: <ref name="reflectance" id="t"/> */
		return 0;
	}
	if (!strcmp(p->name, "texture") || !strcmp(p->name, "ref")) {
		const char *id = attr(M, p, "id");
		const char *fn = !strcmp(p->name, "texture") ? pstring(M, p, "filename") : NULL;
		int desc = 0;
		if (!strcmp(p->name, "texture")) {
			if ((desc = describe_texture(M, p)) < 0)
				return -1;
		} else
			for (int i = 0; id && i < M->ntexs; i++)
				if (!strcmp(M->texs[i].id, id)) {
					fn = M->texs[i].file;
					desc = M->texs[i].desc;
				}
		M->last_tex = desc;
		if (tex)
			snprintf(tex, ntex, "%s", fn ? fn : (attr(M, p, "type") ? attr(M, p, "type") : "texture"));
		return 1;
	}
	const char *v = attr(M, p, "value");
	double a[3];
	int k;
	if (!strcmp(p->name, "spectrum") && v && strchr(v, ':')) {
		double s = 0;
		int cnt = 0;
		for (const char *q = v; q && *q;) {
			double wl, val;
			int used;
			if (sscanf(q, " %lf : %lf%n", &wl, &val, &used) != 2)
				return pmi_err(M->d, p->src, M->err, "'%s': bad spectrum", name);
			s += val;
			cnt++;
			q += used;
			while (*q == ',' || *q == ' ')
				q++;
		}
		out[0] = out[1] = out[2] = cnt ? s / cnt : 0;
		pmi_note_add(M->d, p->src, "'%s': sampled spectrum taken as grey (its mean)", name);
		return 1;
	}
	if ((k = numbers(v, a, 3)) == 1)
		a[1] = a[2] = a[0];
	else if (k != 3)
		return pmi_err(M->d, p->src, M->err, "'%s': want 1 or 3 numbers", name);
	memcpy(out, a, sizeof a);
	return 1;
}

/* An ior: a number or one of Mitsuba's named materials. */
static int
pior(mreader *M, const xnode *n, const char *name, double def, double *out)
{
	static const struct { const char *n; double v; } t[] = {
		{"vacuum", 1.0}, {"helium", 1.000036}, {"hydrogen", 1.000132}, {"air", 1.000277},
		{"carbon dioxide", 1.00045}, {"water", 1.3330}, {"acetone", 1.36}, {"ethanol", 1.361},
		{"carbon tetrachloride", 1.461}, {"glycerol", 1.4729}, {"benzene", 1.501},
		{"silicone oil", 1.52045}, {"bromine", 1.661}, {"water ice", 1.31}, {"fused quartz", 1.458},
		{"pyrex", 1.470}, {"acrylic glass", 1.49}, {"polypropylene", 1.49}, {"bk7", 1.5046},
		{"sodium chloride", 1.544}, {"amber", 1.55}, {"pet", 1.5750}, {"diamond", 2.419},
	};
	const char *v = pstring(M, n, name);
	*out = def;
	if (!v)
		return 0;
	if (numbers(v, out, 1) == 1)
		return 0;
	for (size_t i = 0; i < sizeof t / sizeof *t; i++)
		if (!strcmp(v, t[i].n)) {
			*out = t[i].v;
			return 0;
		}
	return pmi_err(M->d, prop(M, n, name)->src, M->err, "'%s': unknown ior '%s'", name, v);
}

/* ---- transforms ---- */

static int
point3(mreader *M, const xnode *t, const char *key, double v[3], double def)
{
	const char *s = attr(M, t, key);
	v[0] = v[1] = v[2] = def;
	if (!s)
		return 0;
	if (numbers(s, v, 3) != 3)
		return pmi_err(M->d, t->src, M->err, "%s: '%s' wants 3 numbers", t->name, key);
	return 0;
}

static int
xyz(mreader *M, const xnode *t, double v[3], double def)
{
	const char *val = attr(M, t, "value");
	int k;

	if (val) {
		if ((k = numbers(val, v, 3)) == 1)
			v[1] = v[2] = v[0];
		else if (k != 3)
			return pmi_err(M->d, t->src, M->err, "%s: value wants 1 or 3 numbers", t->name);
		return 0;
	}
	const char *ax[3] = { "x", "y", "z" };
	for (int i = 0; i < 3; i++) {
		const char *s = attr(M, t, ax[i]);
		v[i] = def;
		if (s && numbers(s, &v[i], 1) != 1)
			return pmi_err(M->d, t->src, M->err, "%s: '%s' is not a number", t->name, ax[i]);
	}
	return 0;
}

static int
transform(mreader *M, const xnode *tr, pmi_mat4 *out)
{
	pmi_mat4 m = pmi_identity();

	for (int i = 0; i < tr->nkids; i++) {
		const xnode *t = tr->kids[i];
		pmi_mat4 s = pmi_identity();
		double v[16];
		if (!strcmp(t->name, "translate")) {
			if (xyz(M, t, v, 0))
				return -1;
			s = pmi_translate(v[0], v[1], v[2]);
		} else if (!strcmp(t->name, "scale")) {
			if (xyz(M, t, v, 1))
				return -1;
			s = pmi_scale(v[0], v[1], v[2]);
		} else if (!strcmp(t->name, "rotate")) {
			double ang = 0;
			const char *a = attr(M, t, "angle");
			if (attr(M, t, "value")) {
				if (numbers(attr(M, t, "value"), v, 3) != 3)
					return pmi_err(M->d, t->src, M->err, "rotate: value wants 3 numbers");
			} else if (xyz(M, t, v, 0))
				return -1;
			if (!a || numbers(a, &ang, 1) != 1)
				return pmi_err(M->d, t->src, M->err, "rotate: no angle");
			if (v[0] == 0 && v[1] == 0 && v[2] == 0)
				return pmi_err(M->d, t->src, M->err, "rotate: axis 0 0 0");
			s = pmi_rotate(ang, v[0], v[1], v[2]);
		} else if (!strcmp(t->name, "matrix")) {
			int k = numbers(attr(M, t, "value"), v, 16);
			if (k == 16) {
				for (int r = 0; r < 4; r++)
					for (int c = 0; c < 4; c++)
						s.m[r][c] = v[4 * r + c];
			} else if (k == 9) {
				for (int r = 0; r < 3; r++)
					for (int c = 0; c < 3; c++)
						s.m[r][c] = v[3 * r + c];
			} else
				return pmi_err(M->d, t->src, M->err, "matrix: want 16 (or 9) numbers");
		} else if (!strcmp(t->name, "lookat")) {
			double o[3], tg[3], up[3];
			if (point3(M, t, "origin", o, 0) || point3(M, t, "target", tg, 0) || point3(M, t, "up", up, 0))
				return -1;
			double d[3] = { tg[0] - o[0], tg[1] - o[1], tg[2] - o[2] };
			double dl = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
			if (!attr(M, t, "up"))
				up[1] = 1;
			double l[3] = { up[1] * d[2] - up[2] * d[1], up[2] * d[0] - up[0] * d[2], up[0] * d[1] - up[1] * d[0] };
			double ll = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
			if (!(dl > 0) || !(ll > 0))
				return pmi_err(M->d, t->src, M->err, "lookat: origin equals target, or up parallel to the view");
			for (int k = 0; k < 3; k++) {
				d[k] /= dl;
				l[k] /= ll;
			}
			double nu[3] = { d[1] * l[2] - d[2] * l[1], d[2] * l[0] - d[0] * l[2], d[0] * l[1] - d[1] * l[0] };
			for (int k = 0; k < 3; k++) {
				s.m[k][0] = l[k];
				s.m[k][1] = nu[k];
				s.m[k][2] = d[k];
				s.m[k][3] = o[k];
			}
		} else
			return pmi_err(M->d, t->src, M->err, "transform: unknown element <%s>", t->name);
		m = pmi_mul(s, m);
	}
	*out = m;
	return 0;
}

static int
to_world(mreader *M, const xnode *n, pmi_mat4 *out)
{
	*out = pmi_identity();
	for (int i = 0; i < n->nkids; i++)
		if (!strcmp(n->kids[i]->name, "transform")) {
			const char *nm = attr(M, n->kids[i], "name");
			if (!nm || !strcmp(nm, "to_world"))
				return transform(M, n->kids[i], out);
		}
	return 0;
}

/* ---- bsdfs ---- */

static int bsdf(mreader *M, const xnode *b, pmi_material *m);

static const xnode *
nested_bsdf(const xnode *b, int which)
{
	int k = 0;
	for (int i = 0; i < b->nkids; i++)
		if (!strcmp(b->kids[i]->name, "bsdf") || !strcmp(b->kids[i]->name, "ref"))
			if (k++ == which)
				return b->kids[i];
	return NULL;
}

static int
bsdf_ref(mreader *M, const xnode *r, pmi_material *m)
{
	if (!strcmp(r->name, "bsdf"))
		return bsdf(M, r, m);
	const char *id = attr(M, r, "id");
	for (int i = 0; id && i < M->nbsdfs; i++)
		if (!strcmp(M->bsdfs[i].id, id)) {
			pmi_src s = m->src;
			*m = M->d->mats[M->bsdfs[i].mat];
			m->src = s;
			return 0;
		}
	return pmi_err(M->d, r->src, M->err, "ref: no bsdf with id '%s'", id ? id : "");
}

static int
bsdf(mreader *M, const xnode *b, pmi_material *m)
{
	const char *type = attr(M, b, "type");
	double ext;
	char name[64];

	snprintf(name, sizeof name, "%s", m->name);
	if (!type)
		return pmi_err(M->d, b->src, M->err, "bsdf without a type");
	m->src = b->src;
	snprintf(m->type, sizeof m->type, "%s", type);
	m->color[0] = m->color[1] = m->color[2] = 0.5;
	m->trans[0] = m->trans[1] = m->trans[2] = 1;
	m->spec[0] = m->spec[1] = m->spec[2] = 1;
	m->texture[0] = 0;
	if (!strcmp(type, "diffuse")) {
		m->kind = PMI_MAT_DIFFUSE;
		if (pcolor(M, b, "reflectance", m->color, m->texture, sizeof m->texture) < 0)
			return -1;
	} else if (!strcmp(type, "plastic") || !strcmp(type, "roughplastic")) {
		double in;
		m->kind = PMI_MAT_COATED;
		if (pcolor(M, b, "diffuse_reflectance", m->color, m->texture, sizeof m->texture) < 0 ||
		    pior(M, b, "int_ior", 1.49, &in) || pior(M, b, "ext_ior", 1.000277, &ext) ||
		    pfloat(M, b, "alpha", type[0] == 'r' ? 0.1 : 0, &m->alpha))
			return -1;
		m->eta = in / ext;
	} else if (!strcmp(type, "conductor") || !strcmp(type, "roughconductor")) {
		const char *mat = pstring(M, b, "material");
		double eta[3], k[3], sr[3] = { 1, 1, 1 };
		m->kind = PMI_MAT_CONDUCTOR;
		if (pcolor(M, b, "eta", eta, NULL, 0) == 1 && pcolor(M, b, "k", k, NULL, 0) == 1) {
			for (int c = 0; c < 3; c++)
				m->spec[c] = ((eta[c] - 1) * (eta[c] - 1) + k[c] * k[c]) / ((eta[c] + 1) * (eta[c] + 1) + k[c] * k[c]);
		} else if (mat && strcmp(mat, "none") != 0) {
			if (pmi_metal_f0(mat, m->spec)) {
				m->spec[0] = m->spec[1] = m->spec[2] = 0.9;
				pmi_note_add(M->d, b->src, "conductor material '%s' unknown: grey 0.9", mat);
			}
		}
		/* Otherwise Mitsuba 3's default material "none": a perfect
		 * reflector (spec stays 1). */
		if (pcolor(M, b, "specular_reflectance", sr, NULL, 0) < 0)
			return -1;
		for (int c = 0; c < 3; c++)
			m->spec[c] *= sr[c];
		double au, av;
		if (pfloat(M, b, "alpha", type[0] == 'r' ? 0.1 : 0, &m->alpha) ||
		    pfloat(M, b, "alpha_u", m->alpha, &au) || pfloat(M, b, "alpha_v", m->alpha, &av))
			return -1;
		if (au != av)
			pmi_note_add(M->d, b->src, "anisotropic alpha %g x %g taken as %g", au, av, sqrt(au * av));
		m->alpha = sqrt(au * av);
	} else if (!strcmp(type, "dielectric") || !strcmp(type, "roughdielectric") || !strcmp(type, "thindielectric")) {
		double in;
		m->kind = type[0] == 't' ? PMI_MAT_THIN : PMI_MAT_DIELECTRIC;
		if (pior(M, b, "int_ior", 1.5046, &in) || pior(M, b, "ext_ior", 1.000277, &ext) ||
		    pfloat(M, b, "alpha", type[0] == 'r' ? 0.1 : 0, &m->alpha) ||
		    pcolor(M, b, "specular_transmittance", m->trans, NULL, 0) < 0)
			return -1;
		m->eta = in / ext;
	} else if (!strcmp(type, "twosided") || !strcmp(type, "bumpmap") || !strcmp(type, "normalmap") ||
	           !strcmp(type, "mask")) {
		const xnode *in = nested_bsdf(b, 0);
		if (!in)
			return pmi_err(M->d, b->src, M->err, "%s: no nested bsdf", type);
		if (type[0] != 't')
			pmi_note_add(M->d, b->src, "%s: dropped, its nested bsdf used", type);
		if (bsdf_ref(M, in, m))
			return -1;
	} else if (!strcmp(type, "blendbsdf")) {
		const xnode *a = nested_bsdf(b, 0), *c = nested_bsdf(b, 1);
		double w;
		pmi_material ma = *m, mb = *m;
		if (!a || !c)
			return pmi_err(M->d, b->src, M->err, "blendbsdf: wants two nested bsdfs");
		if (pfloat(M, b, "weight", 0.5, &w) || bsdf_ref(M, a, &ma) || bsdf_ref(M, c, &mb))
			return -1;
		if (ma.kind == PMI_MAT_DIFFUSE && mb.kind == PMI_MAT_DIFFUSE) {
			*m = ma;
			for (int k = 0; k < 3; k++)
				m->color[k] = (1 - w) * ma.color[k] + w * mb.color[k];
		} else {
			*m = w > 0.5 ? mb : ma;
			pmi_note_add(M->d, b->src, "blendbsdf: the bsdf of weight %g stands for the blend", w > 0.5 ? w : 1 - w);
		}
	} else if (!strcmp(type, "principled")) {
		double metal, rough;
		m->kind = PMI_MAT_COATED;
		m->eta = 1.5;
		if (pcolor(M, b, "base_color", m->color, m->texture, sizeof m->texture) < 0 ||
		    pfloat(M, b, "metallic", 0, &metal) || pfloat(M, b, "roughness", 0.5, &rough))
			return -1;
		m->alpha = rough * rough;
		if (metal > 0.5) {
			m->kind = PMI_MAT_CONDUCTOR;
			memcpy(m->spec, m->color, sizeof m->spec);
		}
		pmi_note_add(M->d, b->src, "principled: taken as %s", metal > 0.5 ? "a conductor" : "a coated diffuse");
	} else {
		m->kind = PMI_MAT_DIFFUSE;
		pmi_note_add(M->d, b->src, "bsdf '%s': pm has no model for it, grey diffuse 0.5", type);
	}
	snprintf(m->name, sizeof m->name, "%s", name);
	snprintf(m->type, sizeof m->type, "%s", type);
	m->src = b->src;
	return 0;
}

/* A top-level or nested bsdf as a new description material. */
static int
add_bsdf(mreader *M, const xnode *b, int *index)
{
	pmi_material tmp;

	memset(&tmp, 0, sizeof tmp);
	const char *id = attr(M, b, "id");
	snprintf(tmp.name, sizeof tmp.name, "%s", id ? id : "");
	tmp.eta = 1.5;
	M->last_tex = 0;
	if (bsdf_ref(M, b, &tmp))
		return -1;
	if (tmp.texture[0])
		tmp.tex = M->last_tex;
	if (id)
		snprintf(tmp.name, sizeof tmp.name, "%s", id);
	pmi_material *m = pmi_add_material(M->d, b->src);
	if (!m)
		return pm_seterr(M->err, "out of memory");
	*m = tmp;
	m->src = b->src;
	*index = (int)M->d->nmats - 1;
	return 0;
}

/* ---- shapes ---- */

static int
resolve(mreader *M, const char *fn, char *out, size_t n)
{
	return snprintf(out, n, "%s%s", fn[0] == '/' ? "" : M->dir, fn) >= (int)n ? -1 : 0;
}

static int
quads(pmi_shape *s, const float *v, int nv, const uint32_t *q, int nq)
{
	if (pmi_mesh_alloc(s, nv, nq, 4 * (size_t)nq, 0))
		return -1;
	memcpy(s->v, v, 3 * nv * sizeof *v);
	memcpy(s->idx, q, 4 * nq * sizeof *q);
	for (int i = 0; i <= nq; i++)
		s->start[i] = 4 * i;
	return 0;
}

static int
shape(mreader *M, const xnode *n)
{
	const char *type = attr(M, n, "type");
	pmi_shape s;
	pmi_mat4 tw;
	float *N = NULL;

	memset(&s, 0, sizeof s);
	if (!type)
		return pmi_err(M->d, n->src, M->err, "shape without a type");
	if (to_world(M, n, &tw))
		return -1;
	if (!strcmp(type, "obj") || !strcmp(type, "ply")) {
		const char *fn = pstring(M, n, "filename");
		char path[4200];
		pm_error e;
		if (!fn)
			return pmi_err(M->d, n->src, M->err, "shape '%s': no filename", type);
		if (resolve(M, fn, path, sizeof path))
			return pmi_err(M->d, n->src, M->err, "path too long");
		if (type[0] == 'o') {
			if (pmi_read_obj_mesh(path, &s, &e))
				return pmi_err(M->d, n->src, M->err, "%s", e.msg);
			/* Mitsuba 3's obj loader turns the file's v into 1 - v
			 * unless flip_tex_coords is false (its uv are then those
			 * its bitmap reads with v = 0 on the top row). */
			const char *ft = pstring(M, n, "flip_tex_coords");
			if (s.uv && !(ft && !strcmp(ft, "false")))
				for (size_t i = 0; i < s.nv; i++)
					s.uv[2 * i + 1] = 1 - s.uv[2 * i + 1];
			if (pbool(M, n, "face_normals")) {
				free(s.n);
				s.n = NULL;
			}
		} else if (pmi_ply_read(path, &s, &N, &e))
			return pmi_err(M->d, n->src, M->err, "%s", e.msg);
		else
			s.n = N;   /* shading normals, carried by to_world below */
	} else if (!strcmp(type, "rectangle")) {
		static const float v[] = { -1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0 };
		static const uint32_t q[] = { 0, 1, 2, 3 };
		if (quads(&s, v, 4, q, 1) || !(s.uv = malloc(8 * sizeof *s.uv))) {
			pmi_shape_free(&s);
			return pm_seterr(M->err, "out of memory");
		}
		/* Mitsuba's rectangle: (u, v) = ((x + 1) / 2, (y + 1) / 2). */
		for (int i = 0; i < 4; i++) {
			s.uv[2 * i] = 0.5f * (v[3 * i] + 1);
			s.uv[2 * i + 1] = 0.5f * (v[3 * i + 1] + 1);
		}
	} else if (!strcmp(type, "cube")) {
		static const float v[] = { -1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1, -1, -1, 1, 1, -1, 1, 1, 1, 1, -1, 1, 1 };
		/* counter-clockwise seen from outside */
		static const uint32_t q[] = { 0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 3, 7, 6, 2, 0, 4, 7, 3, 1, 2, 6, 5 };
		if (quads(&s, v, 8, q, 6))
			return pm_seterr(M->err, "out of memory");
	} else if (!strcmp(type, "disk")) {
		if (pmi_disk_mesh(&s, 1, 0, 0, 360))
			return pm_seterr(M->err, "out of memory");
	} else if (!strcmp(type, "sphere")) {
		double c[3] = { 0, 0, 0 }, r;
		const xnode *cp = prop(M, n, "center");
		if (cp && point3(M, cp, "x", c, 0) == 0 && attr(M, cp, "value"))
			numbers(attr(M, cp, "value"), c, 3);
		if (cp && !attr(M, cp, "value")) {
			xyz(M, cp, c, 0);
		}
		if (pfloat(M, n, "radius", 1, &r))
			return -1;
		s.kind = PMI_SHAPE_SPHERE;
		memcpy(s.center, c, sizeof c);
		s.radius = r;
	} else {
		pmi_note_add(M->d, n->src, "shape '%s': pm cannot represent it, dropped", type);
		return 0;
	}
	s.src = n->src;
	pmi_shape_xform(&s, tw, pbool(M, n, "flip_normals"));
	/* bsdf: nested or referenced; else Mitsuba's default diffuse 0.5. */
	s.mat = -1;
	for (int i = 0; i < n->nkids; i++) {
		const xnode *k = n->kids[i];
		if (!strcmp(k->name, "bsdf") || (!strcmp(k->name, "ref") && (!attr(M, k, "name") || !strcmp(attr(M, k, "name"), "bsdf")))) {
			if (!strcmp(k->name, "ref")) {
				const char *id = attr(M, k, "id");
				for (int j = 0; id && j < M->nbsdfs; j++)
					if (!strcmp(M->bsdfs[j].id, id))
						s.mat = M->bsdfs[j].mat;
				if (s.mat < 0) {
					pmi_shape_free(&s);
					return pmi_err(M->d, k->src, M->err, "ref: no bsdf with id '%s'", id ? id : "");
				}
			} else if (add_bsdf(M, k, &s.mat)) {
				pmi_shape_free(&s);
				return -1;
			}
		} else if (!strcmp(k->name, "emitter")) {
			const char *et = attr(M, k, "type");
			if (!et || strcmp(et, "area") != 0) {
				pmi_shape_free(&s);
				return pmi_err(M->d, k->src, M->err, "a shape's emitter must be of type area");
			}
			s.emit[0] = s.emit[1] = s.emit[2] = 1;
			if (pcolor(M, k, "radiance", s.emit, NULL, 0) < 0) {
				pmi_shape_free(&s);
				return -1;
			}
		}
	}
	if (s.mat < 0) {
		if (M->default_mat < 0) {
			pmi_material *m = pmi_add_material(M->d, n->src);
			if (!m) {
				pmi_shape_free(&s);
				return pm_seterr(M->err, "out of memory");
			}
			m->kind = PMI_MAT_DIFFUSE;
			snprintf(m->type, sizeof m->type, "diffuse");
			snprintf(m->name, sizeof m->name, "default");
			m->color[0] = m->color[1] = m->color[2] = 0.5;
			M->default_mat = (int)M->d->nmats - 1;
		}
		s.mat = M->default_mat;
	}
	pmi_shape *dst = pmi_add_shape(M->d, n->src);
	if (!dst) {
		pmi_shape_free(&s);
		return pm_seterr(M->err, "out of memory");
	}
	*dst = s;
	return 0;
}

/* ---- emitters and the sensor ---- */

static int
emitter(mreader *M, const xnode *n)
{
	const char *type = attr(M, n, "type");
	pmi_mat4 tw;
	pmi_light *l;

	if (!type)
		return pmi_err(M->d, n->src, M->err, "emitter without a type");
	if (!strcmp(type, "area"))
		return pmi_err(M->d, n->src, M->err, "an area emitter belongs inside a shape");
	if (to_world(M, n, &tw) || !(l = pmi_add_light(M->d, n->src)))
		return M->err->msg[0] ? -1 : pm_seterr(M->err, "out of memory");
	snprintf(l->type, sizeof l->type, "%s", type);
	double o[3] = { 0, 0, 0 }, z[3] = { 0, 0, 1 };
	pmi_xform_point(tw, o, l->pos);
	pmi_xform_vector(tw, z, l->dir);
	const xnode *pp = prop(M, n, "position");
	if (pp) {
		if (attr(M, pp, "value") ? numbers(attr(M, pp, "value"), l->pos, 3) != 3 : xyz(M, pp, l->pos, 0))
			return pmi_err(M->d, pp->src, M->err, "position: want 3 numbers");
	}
	l->color[0] = l->color[1] = l->color[2] = 1;
	if (!strcmp(type, "point") || !strcmp(type, "spot")) {
		l->kind = type[0] == 'p' ? PMI_LIGHT_POINT : PMI_LIGHT_SPOT;
		double beam;
		if (pcolor(M, n, "intensity", l->color, NULL, 0) < 0 || pfloat(M, n, "cutoff_angle", 20, &l->cone) ||
		    pfloat(M, n, "beam_width", l->cone * 0.75, &beam))
			return -1;
		/* Mitsuba 3: full intensity within beam_width, falling linearly
		 * in the angle to 0 at cutoff_angle. */
		l->falloff = l->cone - beam;
		l->linear = 1;
	} else if (!strcmp(type, "directional")) {
		l->kind = PMI_LIGHT_DISTANT;
		const xnode *dp = prop(M, n, "direction");
		if (dp && numbers(attr(M, dp, "value") ? attr(M, dp, "value") : "", l->dir, 3) != 3 && xyz(M, dp, l->dir, 0))
			return -1;
		if (pcolor(M, n, "irradiance", l->color, NULL, 0) < 0)
			return -1;
	} else if (!strcmp(type, "constant") || !strcmp(type, "envmap")) {
		l->kind = PMI_LIGHT_INFINITE;
		if (pcolor(M, n, "radiance", l->color, NULL, 0) < 0)
			return -1;
		const char *fn = pstring(M, n, "filename");
		if (fn && resolve(M, fn, l->map, sizeof l->map))
			return pmi_err(M->d, n->src, M->err, "envmap: file name too long");
		if (pfloat(M, n, "scale", 1, &l->map_scale))
			return -1;
		l->has_rot = 1;
		for (int i = 0; i < 3; i++)
			for (int k = 0; k < 3; k++)
				l->rot[i][k] = tw.m[i][k];
	} else
		l->kind = PMI_LIGHT_OTHER;
	return 0;
}

static int
sensor(mreader *M, const xnode *n)
{
	const char *type = attr(M, n, "type");
	pmi_camera *c = &M->d->cam;
	pmi_mat4 tw;

	if (!type || strcmp(type, "perspective") != 0)
		return pmi_err(M->d, n->src, M->err, "sensor '%s': pm has only the perspective (pinhole) camera",
		               type ? type : "");
	if (to_world(M, n, &tw))
		return -1;
	double o[3] = { 0, 0, 0 }, ex[3] = { -1, 0, 0 }, ey[3] = { 0, 1, 0 }, ez[3] = { 0, 0, 1 };
	pmi_xform_point(tw, o, c->pos);
	pmi_xform_vector(tw, ex, c->right);
	pmi_xform_vector(tw, ey, c->up);
	pmi_xform_vector(tw, ez, c->fwd);
	c->set = 1;
	c->src = n->src;
	const char *ax = pstring(M, n, "fov_axis");
	c->fov_axis = !ax || !strcmp(ax, "x") ? PMI_FOV_X : !strcmp(ax, "y") ? PMI_FOV_Y :
	              !strcmp(ax, "diagonal") ? PMI_FOV_DIAGONAL : !strcmp(ax, "smaller") ? PMI_FOV_SHORTER :
	              !strcmp(ax, "larger") ? PMI_FOV_LONGER : -1;
	if (c->fov_axis < 0)
		return pmi_err(M->d, prop(M, n, "fov_axis")->src, M->err, "fov_axis '%s' unknown", ax);
	if (prop(M, n, "fov")) {
		if (pfloat(M, n, "fov", 0, &c->fov))
			return -1;
	} else {
		/* focal_length in 35 mm equivalent (default 50mm): the diagonal
		 * of the 36 x 24 mm frame. */
		const char *fl = pstring(M, n, "focal_length");
		double f = 50;
		if (fl && sscanf(fl, "%lf", &f) != 1)
			return pmi_err(M->d, n->src, M->err, "focal_length '%s'", fl);
		c->fov = 2 * atan(sqrt(36.0 * 36 + 24 * 24) / (2 * f)) * 180 / PM_PI;
		c->fov_axis = PMI_FOV_DIAGONAL;
	}
	if (!(c->fov > 0 && c->fov < 180))
		return pmi_err(M->d, n->src, M->err, "fov %g not in (0, 180)", c->fov);
	c->width = 768;
	c->height = 576;
	for (int i = 0; i < n->nkids; i++)
		if (!strcmp(n->kids[i]->name, "film")) {
			double w, h;
			if (pfloat(M, n->kids[i], "width", 768, &w) || pfloat(M, n->kids[i], "height", 576, &h))
				return -1;
			c->width = (int)w;
			c->height = (int)h;
			if (c->width < 1 || c->height < 1)
				return pmi_err(M->d, n->kids[i]->src, M->err, "film %dx%d", c->width, c->height);
			if (prop(M, n->kids[i], "crop_width") || prop(M, n->kids[i], "crop_offset_x"))
				pmi_note_add(M->d, n->kids[i]->src, "film crop dropped: the whole image");
		}
	return 0;
}

/* ---- the scene ---- */

static int
scene_children(mreader *M, xnode *root)
{
	for (int i = 0; i < root->nkids; i++) {
		xnode *k = root->kids[i];
		int r = 0;
		if (!strcmp(k->name, "default")) {
			const char *nm = raw_attr(k, "name"), *v = raw_attr(k, "value");
			if (!nm || !v)
				return pmi_err(M->d, k->src, M->err, "default: wants name and value");
			char **nd = realloc(M->defs, 2 * (M->ndefs + 1) * sizeof *nd);
			if (!nd)
				return pm_seterr(M->err, "out of memory");
			M->defs = nd;
			nd[2 * M->ndefs] = strdup(nm);
			nd[2 * M->ndefs + 1] = strdup(v);
			M->ndefs++;
		} else if (!strcmp(k->name, "include")) {
			const char *fn = attr(M, k, "filename");
			char path[4200];
			xnode *sub;
			if (!fn || resolve(M, fn, path, sizeof path))
				return pmi_err(M->d, k->src, M->err, "include: no filename");
			for (int j = 0; j < M->nopen; j++)
				if (!strcmp(M->open_files[j], path))
					return pmi_err(M->d, k->src, M->err, "'%s' includes itself (recursion)", path);
			if (M->nopen == MAX_DEPTH)
				return pmi_err(M->d, k->src, M->err, "includes nested more than %d deep", MAX_DEPTH);
			if (xml_load(M, path, k->src, &sub))
				return -1;
			if (strcmp(sub->name, "scene") != 0) {
				pmi_src s = sub->src;
				xfree(sub);
				return pmi_err(M->d, s, M->err, "the root element of an included file must be <scene>");
			}
			M->open_files[M->nopen++] = path;
			r = scene_children(M, sub);
			M->nopen--;
			xfree(sub);
		} else if (!strcmp(k->name, "sensor"))
			r = sensor(M, k);
		else if (!strcmp(k->name, "bsdf")) {
			int idx;
			const char *id = attr(M, k, "id");
			r = add_bsdf(M, k, &idx);
			if (!r && id) {
				void *nb = realloc(M->bsdfs, (M->nbsdfs + 1) * sizeof *M->bsdfs);
				if (!nb)
					return pm_seterr(M->err, "out of memory");
				M->bsdfs = nb;
				M->bsdfs[M->nbsdfs].id = strdup(id);
				M->bsdfs[M->nbsdfs++].mat = idx;
			}
		} else if (!strcmp(k->name, "texture")) {
			const char *id = attr(M, k, "id"), *fn = pstring(M, k, "filename");
			void *nt = realloc(M->texs, (M->ntexs + 1) * sizeof *M->texs);
			if (!nt)
				return pm_seterr(M->err, "out of memory");
			M->texs = nt;
			M->texs[M->ntexs].id = strdup(id ? id : "");
			snprintf(M->texs[M->ntexs].file, 256, "%s", fn ? fn : "texture");
			if ((M->texs[M->ntexs++].desc = describe_texture(M, k)) < 0)
				return -1;
		} else if (!strcmp(k->name, "shape"))
			r = shape(M, k);
		else if (!strcmp(k->name, "emitter"))
			r = emitter(M, k);
		else if (!strcmp(k->name, "integrator") || !strcmp(k->name, "sampler") || !strcmp(k->name, "film") ||
		         !strcmp(k->name, "rfilter"))
			;
		else if (!strcmp(k->name, "medium"))
			pmi_note_add(M->d, k->src, "medium: participating media dropped");
		else
			return pmi_err(M->d, k->src, M->err, "unknown element <%s> in <scene>", k->name);
		if (r)
			return -1;
	}
	return 0;
}

int
pmi_read_mitsuba(const char *path, pmi_desc *d, pm_error *err)
{
	mreader M;
	xnode *root;
	int r;

	memset(&M, 0, sizeof M);
	M.d = d;
	M.err = err;
	M.default_mat = -1;
	err->msg[0] = 0;
	const char *sl = strrchr(path, '/');
	if (sl)
		snprintf(M.dir, sizeof M.dir, "%.*s/", (int)(sl - path), path);
	if (xml_load(&M, path, (pmi_src){ 0, 0 }, &root))
		return -1;
	if (strcmp(root->name, "scene") != 0)
		r = pmi_err(d, root->src, err, "root element <%s>, want <scene>", root->name);
	else {
		const char *v = raw_attr(root, "version");
		if (v && atoi(v) < 2)
			pmi_note_add(d, root->src, "scene version %s: read as Mitsuba 3", v);
		M.open_files[M.nopen++] = path;
		r = scene_children(&M, root);
	}
	if (!r && !d->cam.set)
		r = pmi_err(d, root->src, err, "no <sensor>");
	xfree(root);
	for (int i = 0; i < 2 * M.ndefs; i++)
		free(M.defs[i]);
	free(M.defs);
	for (int i = 0; i < M.nbsdfs; i++)
		free(M.bsdfs[i].id);
	free(M.bsdfs);
	for (int i = 0; i < M.ntexs; i++)
		free(M.texs[i].id);
	free(M.texs);
	return r;
}
