/* write.c — the description (desc.h) to a pm scene (write.h). The rules
 * that map other renderers' models onto pm's live here, one function each
 * for the camera, materials, textures and lights, so a new pm model
 * changes one function. Images a scene uses are copied beside it. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/atomic.h"
#include "base/fnv.h"
#include "base/vec.h"
#include "import/write.h"
#include "scene/imagefile.h"
#include "scene/scene.h"

/* pm's Blinn exponent for a microfacet roughness alpha: the Blinn lobe of
 * the Beckmann distribution of the same width, e = 2 / alpha^2 - 2
 * (Walter et al. 2007, eq. 30), kept within [1, 10^6] (a smooth surface's
 * lobe is then narrower than a pixel of any camera pm allows). */
static double
blinn_exponent(double alpha)
{
	if (alpha < 0.0014142)
		return 1e6;
	double e = 2 / (alpha * alpha) - 2;
	return e < 1 ? 1 : e;
}

/* Reflectance at normal incidence of an interface of relative ior eta. */
static double
f0_of(double eta)
{
	double r = (eta - 1) / (eta + 1);
	return r * r;
}

/* The share of diffuse light inside a coat of relative ior eta that the
 * coat reflects back in (total internal reflection included): the cosine-
 * weighted hemispherical mean of Fresnel's reflectance from inside. */
static double
internal_reflectance(double eta)
{
	enum { N = 2048 };
	double sum = 0;

	for (int i = 0; i < N; i++) {
		double ci = (i + 0.5) / N, si2 = 1 - ci * ci;
		double st2 = eta * eta * si2, F = 1;   /* inside to outside: n_t / n_i = 1 / eta */
		if (st2 < 1) {
			double ct = sqrt(1 - st2);
			double rs = (eta * ci - ct) / (eta * ci + ct), rp = (ci - eta * ct) / (ci + eta * ct);
			F = 0.5 * (rs * rs + rp * rp);
		}
		sum += F * 2 * ci / N;
	}
	return sum;
}

typedef struct pm_mat {
	int src;             /* desc material */
	double emit[3];
	int twosided;
	char name[64];
	int uses;
} pm_mat;

typedef struct wctx {
	pmi_desc *d;
	pm_error *err;
	int mirror;          /* the world is mirrored in x (see write_camera) */
	pm_mat *mats;
	size_t nmats, capmats;
	char dir[4096], stem[256];
	char **made;         /* files this call created, removed on failure */
	size_t nmade;
	char **meshes;       /* mesh and image file names the scene uses */
	size_t nmeshes;
	int *tex_state;      /* per desc texture: 0 not yet written, 1 written, -1 dropped */
} wctx;

static double
clamp01(double v, int *clamped)
{
	if (v < 0) {
		*clamped = 1;
		return 0;
	}
	if (v > 1) {
		*clamped = 1;
		return 1;
	}
	return v;
}

static void
mirror_point(const wctx *w, double p[3])
{
	if (w->mirror)
		p[0] = 0.0 - p[0];   /* +0, not -0, in the .pms */
}

/* ---- camera ---- */

static int
write_camera(wctx *w, FILE *f, int width, int height)
{
	pmi_camera *c = &w->d->cam;
	double R[3], U[3], F[3], eye[3];

	if (!c->set)
		return pm_seterr(w->err, "%s: no camera", w->d->nfiles ? w->d->files[0] : "scene");
	memcpy(R, c->right, sizeof R);
	memcpy(U, c->up, sizeof U);
	memcpy(F, c->fwd, sizeof F);
	memcpy(eye, c->pos, sizeof eye);
	/* pm's camera is right-handed: image right = view x up. A source frame
	 * whose right, up and view form a right-handed triple (pbrt's plain
	 * LookAt) would show mirrored, so the whole world is mirrored in x
	 * instead, which turns that frame into pm's. */
	double det = (R[1] * U[2] - R[2] * U[1]) * F[0] + (R[2] * U[0] - R[0] * U[2]) * F[1] +
	             (R[0] * U[1] - R[1] * U[0]) * F[2];
	w->mirror = det > 0;
	mirror_point(w, eye);
	mirror_point(w, U);
	mirror_point(w, F);
	double fl = sqrt(F[0] * F[0] + F[1] * F[1] + F[2] * F[2]);
	double ul = sqrt(U[0] * U[0] + U[1] * U[1] + U[2] * U[2]);
	double rl = sqrt(R[0] * R[0] + R[1] * R[1] + R[2] * R[2]);
	if (!(fl > 0 && ul > 0 && rl > 0))
		return pmi_err(w->d, c->src, w->err, "camera: degenerate view transform");
	double cosuf = (U[0] * F[0] + U[1] * F[1] + U[2] * F[2]) / (ul * fl);
	if (fabs(cosuf) > 1e-3 || fabs(rl / ul - 1) > 1e-3 || fabs(fl / ul - 1) > 1e-3)
		pmi_note_add(w->d, c->src, "camera: its transform skews or scales the view; made orthonormal");
	/* pm's fov is vertical. */
	double t = tan(c->fov * PM_PI / 360), ty;
	int axis = c->fov_axis;
	if (axis == PMI_FOV_SHORTER)
		axis = width >= height ? PMI_FOV_Y : PMI_FOV_X;
	else if (axis == PMI_FOV_LONGER)
		axis = width >= height ? PMI_FOV_X : PMI_FOV_Y;
	ty = axis == PMI_FOV_Y ? t : axis == PMI_FOV_X ? t * height / width
	   : t * height / sqrt((double)width * width + (double)height * height);
	double fovy = 2 * atan(ty) * 180 / PM_PI;
	if (!(fovy > 0 && fovy < 180))
		return pmi_err(w->d, c->src, w->err, "camera: vertical fov %g not in (0, 180)", fovy);
	fprintf(f, "camera eye %.9g %.9g %.9g  look %.9g %.9g %.9g  up %.9g %.9g %.9g  fov %.9g  size %d %d\n",
	        eye[0], eye[1], eye[2], eye[0] + F[0] / fl, eye[1] + F[1] / fl, eye[2] + F[2] / fl,
	        U[0] / ul, U[1] / ul, U[2] / ul, fovy, width, height);
	return 0;
}

/* ---- materials: one rule per kind (README, "Your own scenes") ---- */

/* The pm material line for desc material mi with emission emit; notes what
 * the rule approximates once per source material (first use). */
static void
material_line(wctx *w, const pm_mat *pmm, char *line, size_t n, int first)
{
	const pmi_material *m = &w->d->mats[pmm->src];
	const char *nm = pmm->name;
	int emits = pmm->emit[0] > 0 || pmm->emit[1] > 0 || pmm->emit[2] > 0;
	int cl = 0;
	double a[3], b[3], e = 0;
	char what[160] = "", tail[160] = "";
	char mname[80];
	int kind = m->kind;

	snprintf(mname, sizeof mname, m->name[0] ? "material '%s' (%s)" : "material%s (%s)", m->name, m->type);
	/* A texture pm draws replaces the colour it stands for: tx is the
	 * words to put where R G B would be. */
	char tx[32] = "";
	int textured = m->tex > 0 && w->tex_state[m->tex - 1] > 0;
	if (textured)
		snprintf(tx, sizeof tx, "tex t%d", m->tex - 1);
	if (first && m->texture[0] && !textured)
		pmi_note_add(w->d, m->src, "%s: texture '%s' not mapped: constant %.3g %.3g %.3g",
		             mname, m->texture, m->color[0], m->color[1], m->color[2]);
	if (first && textured && (kind == PMI_MAT_DIELECTRIC || kind == PMI_MAT_THIN || kind == PMI_MAT_INVISIBLE))
		pmi_note_add(w->d, m->src, "%s: texture '%s' dropped (pm's glass takes none here)", mname, m->texture);
	if (first && textured && kind == PMI_MAT_COATED)
		pmi_note_add(w->d, m->src, "%s: texture '%s' used as kd as it is (the coat's share of the base's light "
		             "applies to constant colours only)", mname, m->texture);
	if (emits && (kind == PMI_MAT_CONDUCTOR || kind == PMI_MAT_DIELECTRIC || kind == PMI_MAT_THIN ||
	              kind == PMI_MAT_INVISIBLE)) {
		if (first)
			pmi_note_add(w->d, m->src, "%s on an emitter: black diffuse (pm emitters are diffuse or glossy)", mname);
		kind = -1;
	}
	if (emits)
		snprintf(tail, sizeof tail, " emit %.9g %.9g %.9g%s", pmm->emit[0], pmm->emit[1], pmm->emit[2],
		         pmm->twosided ? " twosided" : "");
	switch (kind) {
	case -1:
	case PMI_MAT_INVISIBLE:
		snprintf(line, n, "material %s diffuse albedo 0 0 0%s\n", nm, tail);
		return;
	case PMI_MAT_DIFFUSE:
	case PMI_MAT_DIFFTRANS:
		for (int c = 0; c < 3; c++)
			a[c] = clamp01(m->color[c], &cl);
		if (textured)
			snprintf(line, n, "material %s diffuse albedo %s%s\n", nm, tx, tail);
		else
			snprintf(line, n, "material %s diffuse albedo %.9g %.9g %.9g%s\n", nm, a[0], a[1], a[2], tail);
		if (kind == PMI_MAT_DIFFTRANS)
			snprintf(what, sizeof what, "diffuse reflection kept, diffuse transmission %.3g dropped", m->trans[1]);
		break;
	case PMI_MAT_COATED: {
		/* Light enters the coat (1 - F0), the base reflects rho, a share
		 * Fi of it is reflected back in each time it meets the coat from
		 * below: rho (1 - F0)(1 - Fi) / (1 - rho Fi) leaves. */
		double f0 = f0_of(m->eta), fi = internal_reflectance(m->eta);
		e = blinn_exponent(m->alpha);
		for (int c = 0; c < 3; c++) {
			double rho = clamp01(m->color[c], &cl);
			a[c] = rho * (1 - f0) * (1 - fi) / (1 - rho * fi);
			b[c] = f0;
		}
		if (textured)
			snprintf(line, n, "material %s glossy kd %s ks %.9g %.9g %.9g exponent %.9g%s\n", nm,
			         tx, b[0], b[1], b[2], e, tail);
		else
			snprintf(line, n, "material %s glossy kd %.9g %.9g %.9g ks %.9g %.9g %.9g exponent %.9g%s\n", nm,
			         a[0], a[1], a[2], b[0], b[1], b[2], e, tail);
		snprintf(what, sizeof what, "diffuse under a coat (internal reflectance %.3g) plus a Blinn lobe of "
		         "F0 = %.3g, exponent %.4g (alpha %.3g)", fi, f0, e, m->alpha);
		break;
	}
	case PMI_MAT_CONDUCTOR:
		for (int c = 0; c < 3; c++)
			b[c] = clamp01(m->spec[c], &cl);
		if (m->alpha == 0 && textured) {
			snprintf(line, n, "material %s mirror reflect %s\n", nm, tx);
			snprintf(what, sizeof what, "mirror of its textured normal-incidence reflectance");
		} else if (textured) {
			e = blinn_exponent(m->alpha);
			snprintf(line, n, "material %s glossy kd 0 0 0 ks %s exponent %.9g%s\n", nm, tx, e, tail);
			snprintf(what, sizeof what, "Blinn glossy, ks textured (reflectance at normal incidence), "
			         "exponent %.4g (alpha %.3g)", e, m->alpha);
		} else if (m->alpha == 0) {
			snprintf(line, n, "material %s mirror reflect %.9g %.9g %.9g\n", nm, b[0], b[1], b[2]);
			snprintf(what, sizeof what, "mirror of its normal-incidence reflectance %.3g %.3g %.3g", b[0], b[1], b[2]);
		} else {
			e = blinn_exponent(m->alpha);
			snprintf(line, n, "material %s glossy kd 0 0 0 ks %.9g %.9g %.9g exponent %.9g%s\n", nm,
			         b[0], b[1], b[2], e, tail);
			snprintf(what, sizeof what, "Blinn glossy, ks %.3g %.3g %.3g (reflectance at normal incidence), "
			         "exponent %.4g (alpha %.3g)", b[0], b[1], b[2], e, m->alpha);
		}
		break;
	case PMI_MAT_DIELECTRIC:
		for (int c = 0; c < 3; c++)
			b[c] = clamp01(m->trans[c], &cl);
		snprintf(line, n, "material %s glass ior %.9g tint %.9g %.9g %.9g\n", nm, m->eta, b[0], b[1], b[2]);
		if (m->alpha > 0)
			snprintf(what, sizeof what, "smooth glass of ior %.4g (roughness alpha %.3g dropped)", m->eta, m->alpha);
		break;
	case PMI_MAT_THIN: {
		double r = f0_of(m->eta), tr = (1 - r) / (1 + r);
		snprintf(line, n, "material %s glass ior 1 tint %.9g %.9g %.9g\n", nm, tr, tr, tr);
		snprintf(what, sizeof what, "pane: straight transmission %.4g, its reflection %.3g dropped",
		         tr, 2 * r / (1 + r));
		break;
	}
	case PMI_MAT_PHONG: {
		double s = 1;
		for (int c = 0; c < 3; c++) {
			a[c] = clamp01(m->color[c], &cl);
			b[c] = clamp01(m->spec[c], &cl);
			if (a[c] + b[c] > 1)
				s = fmin(s, 1 / (a[c] + b[c]));
		}
		if (b[0] == 0 && b[1] == 0 && b[2] == 0) {
			if (textured)
				snprintf(line, n, "material %s diffuse albedo %s%s\n", nm, tx, tail);
			else
				snprintf(line, n, "material %s diffuse albedo %.9g %.9g %.9g%s\n", nm, a[0], a[1], a[2], tail);
			break;
		}
		if (textured) {
			/* pm scales a textured kd + ks down to 1 where it exceeds it. */
			snprintf(line, n, "material %s glossy kd %s ks %.9g %.9g %.9g exponent %.9g%s\n", nm, tx,
			         b[0], b[1], b[2], m->exponent > 1 ? m->exponent : 1, tail);
			break;
		}
		e = m->exponent > 1 ? m->exponent : 1;
		snprintf(line, n, "material %s glossy kd %.9g %.9g %.9g ks %.9g %.9g %.9g exponent %.9g%s\n", nm,
		         a[0] * s, a[1] * s, a[2] * s, b[0] * s, b[1] * s, b[2] * s, e, tail);
		if (s < 1)
			snprintf(what, sizeof what, "Kd + Ks exceeds 1: both scaled by %.3g", s);
		break;
	}
	}
	if (first && what[0])
		pmi_note_add(w->d, m->src, "%s: %s", mname, what);
	if (first && cl)
		pmi_note_add(w->d, m->src, "%s: colours clamped to [0, 1]", mname);
}

static int copy_image(wctx *w, const char *src, pmi_src at, char *name, size_t n);

/* Writes texture ti as pm's texture tTI (its image copied beside the
 * scene) and marks it written, or dropped if its image cannot be read. */
static int
texture_line(wctx *w, int ti, FILE *f)
{
	const pmi_texture *t = &w->d->texs[ti];
	char name[512];

	if (t->kind == PMI_TEX_IMAGE) {
		int r = copy_image(w, t->file, t->src, name, sizeof name);
		if (r < 0)
			return -1;
		if (r > 0) {
			w->tex_state[ti] = -1;
			return 0;
		}
		fprintf(f, "texture t%d image %s", ti, name);
	} else {
		double c[2][3];
		int cl = 0;
		for (int k = 0; k < 2; k++)
			for (int i = 0; i < 3; i++)
				c[k][i] = clamp01(t->c[k][i], &cl);
		if (cl)
			pmi_note_add(w->d, t->src, "checkerboard colours clamped to [0, 1]");
		fprintf(f, "texture t%d checker %.9g %.9g %.9g  %.9g %.9g %.9g", ti, c[0][0], c[0][1], c[0][2],
		        c[1][0], c[1][1], c[1][2]);
	}
	fprintf(f, " scale %.9g %.9g offset %.9g %.9g\n", t->su, t->sv, t->ou, t->ov);
	w->tex_state[ti] = 1;
	return 0;
}

/* The pm material for a shape: one per source material, emission and
 * sidedness. */
static const pm_mat *
material_for(wctx *w, const pmi_shape *s, FILE *f)
{
	int mi = s->mat;

	for (size_t i = 0; i < w->nmats; i++) {
		pm_mat *p = &w->mats[i];
		if (p->src == mi && !memcmp(p->emit, s->emit, sizeof p->emit) && p->twosided == s->twosided) {
			p->uses++;
			return p;
		}
	}
	if (w->nmats == w->capmats) {
		size_t nc = w->capmats ? 2 * w->capmats : 16;
		pm_mat *m = realloc(w->mats, nc * sizeof *m);
		if (!m)
			return NULL;
		w->mats = m;
		w->capmats = nc;
	}
	int first = 1;
	for (size_t i = 0; i < w->nmats; i++)
		if (w->mats[i].src == mi)
			first = 0;
	pm_mat *p = &w->mats[w->nmats];
	memset(p, 0, sizeof *p);
	p->src = mi;
	memcpy(p->emit, s->emit, sizeof p->emit);
	p->twosided = s->twosided;
	p->uses = 1;
	/* A name pm accepts: the source's, cut to safe characters. */
	char clean[40] = "";
	const char *sn = w->d->mats[mi].name;
	size_t k = 0;
	for (size_t i = 0; sn[i] && k < sizeof clean - 1; i++)
		clean[k++] = (sn[i] >= 'a' && sn[i] <= 'z') || (sn[i] >= 'A' && sn[i] <= 'Z') ||
		             (sn[i] >= '0' && sn[i] <= '9') || sn[i] == '-' || sn[i] == '.' ? sn[i] : '_';
	clean[k] = 0;
	snprintf(p->name, sizeof p->name, "m%zu%s%s", w->nmats, k ? "-" : "", clean);
	w->nmats++;
	int ti = w->d->mats[mi].tex - 1;
	if (ti >= 0 && w->tex_state[ti] == 0 && texture_line(w, ti, f))
		return NULL;
	char line[512];
	material_line(w, p, line, sizeof line, first);
	fputs(line, f);
	return p;
}

/* ---- lights: pm has them all with pbrt-v4's and Mitsuba 3's units
 * (formats/scene.md), so each maps one to one ---- */

static int
positive(const double c[3])
{
	return c[0] > 0 || c[1] > 0 || c[2] > 0;
}

/* The axis and angle (degrees) of the rotation part of r (columns
 * normalized); -1 if it mirrors or is degenerate. */
static int
axis_angle(const double r[3][3], double axis[3], double *deg)
{
	double q[3][3];
	for (int k = 0; k < 3; k++) {
		double l = sqrt(r[0][k] * r[0][k] + r[1][k] * r[1][k] + r[2][k] * r[2][k]);
		if (!(l > 0))
			return -1;
		for (int i = 0; i < 3; i++)
			q[i][k] = r[i][k] / l;
	}
	double det = q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1]) - q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0]) +
	             q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0]);
	if (det < 0)
		return -1;
	double c = fmax(-1, fmin(1, 0.5 * (q[0][0] + q[1][1] + q[2][2] - 1)));
	double a[3] = { q[2][1] - q[1][2], q[0][2] - q[2][0], q[1][0] - q[0][1] };
	double l = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
	if (l < 1e-6) {
		/* 0 or 180 degrees: the axis is the column of q + I with the
		 * largest norm. */
		int best = 0;
		double bn = -1;
		for (int k = 0; k < 3; k++) {
			double v[3] = { q[0][k], q[1][k], q[2][k] };
			v[k] += 1;
			double n2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
			if (n2 > bn) {
				bn = n2;
				best = k;
			}
		}
		for (int i = 0; i < 3; i++)
			a[i] = q[i][best] + (i == best);
		l = sqrt(bn);
	}
	for (int i = 0; i < 3; i++)
		axis[i] = a[i] / l;
	*deg = acos(c) * 180 / PM_PI;
	return 0;
}

static int write_file(wctx *w, const char *path, const char *buf, size_t len);
static int remember(char ***arr, size_t *n, const char *s);
static void put_f32(FILE *f, float x);

/* Writes buf (then freed) beside the scene as STEM-HASH.EXT, named by the
 * hash of its bytes (name gets it), once however often the scene uses it. */
static int
keep_file(wctx *w, const char *ext, char *buf, size_t len, char *name, size_t n)
{
	char path[4700];
	int seen = 0;

	snprintf(name, n, "%s-%016llx%s", w->stem, (unsigned long long)pm_fnv1a(PM_FNV_OFFSET, buf, len), ext);
	snprintf(path, sizeof path, "%s%s", w->dir, name);
	for (size_t i = 0; i < w->nmeshes; i++)
		if (!strcmp(w->meshes[i], name))
			seen = 1;
	int r = !seen && (write_file(w, path, buf, len) || remember(&w->meshes, &w->nmeshes, name));
	free(buf);
	if (r)
		return w->err->msg[0] ? -1 : pm_seterr(w->err, "out of memory");
	return 0;
}

/* pbrt-v4's equal-area octahedral map (Clarberg 2008): the point of the
 * unit square, row 0 at the top, that direction d (light space, +z the
 * square's centre) falls on. */
static void
sphere_to_square(const double d[3], double *u, double *v)
{
	double x = fabs(d[0]), y = fabs(d[1]), z = fabs(d[2]);
	double r = sqrt(fmax(0, 1 - z)), a = fmax(x, y), b = fmin(x, y);
	double phi = a == 0 ? 0 : atan(b / a) * 2 / PM_PI;
	if (x < y)
		phi = 1 - phi;
	double vv = phi * r, uu = r - vv;
	if (d[2] < 0) {
		double t = uu;
		uu = 1 - vv;
		vv = 1 - t;
	}
	uu = copysign(uu, d[0]);
	vv = copysign(vv, d[1]);
	*u = 0.5 * (uu + 1);
	*v = 0.5 * (vv + 1);
}

/* pbrt-v4's equal-area sky image resampled (nearest texel) into the
 * lat-long map pm reads, 2N x N for an N x N square, in pm's world (the
 * light's rotation and the world's mirror applied), written beside the
 * scene as a PFM. 1 (noted) if it cannot be read or is not square. */
static int
equal_area_sky(wctx *w, const pmi_light *l, char *name, size_t n)
{
	pm_rgbimage im;
	pm_error e;
	pmi_mat4 a = pmi_identity(), inv;

	if (pm_rgbimage_read(l->map, &im, &e)) {
		pmi_note_add(w->d, l->src, "environment image: %s: dropped", e.msg);
		return 1;
	}
	if (im.w != im.h) {
		pmi_note_add(w->d, l->src, "environment image '%s' is %d x %d, not pbrt-v4's equal-area square: dropped",
		             l->map, im.w, im.h);
		pm_rgbimage_free(&im);
		return 1;
	}
	for (int i = 0; i < 3; i++)
		for (int k = 0; k < 3; k++)
			a.m[i][k] = l->rot[i][k];
	if (pmi_invert(a, &inv)) {
		pm_rgbimage_free(&im);
		pmi_note_add(w->d, l->src, "environment image under a singular transform: dropped");
		return 1;
	}
	int N = im.w, W = 2 * N, H = N;
	char *buf = NULL;
	size_t len = 0;
	FILE *f = open_memstream(&buf, &len);
	if (!f) {
		pm_rgbimage_free(&im);
		return pm_seterr(w->err, "out of memory");
	}
	fprintf(f, "PF\n%d %d\n-1\n", W, H);
	/* PFM rows run bottom to top. */
	for (int j = H - 1; j >= 0; j--)
		for (int i = 0; i < W; i++) {
			double phi = 2 * PM_PI * (i + 0.5) / W, th = PM_PI * (j + 0.5) / H;
			double d[3] = { sin(phi) * sin(th), cos(th), -cos(phi) * sin(th) }, dl[3], u, v;
			if (w->mirror)
				d[0] = -d[0];
			pmi_xform_vector(inv, d, dl);
			double len2 = sqrt(dl[0] * dl[0] + dl[1] * dl[1] + dl[2] * dl[2]);
			for (int c = 0; c < 3; c++)
				dl[c] /= len2;
			sphere_to_square(dl, &u, &v);
			int x = (int)(u * N), y = (int)(v * N);
			x = x < 0 ? 0 : x >= N ? N - 1 : x;
			y = y < 0 ? 0 : y >= N ? N - 1 : y;
			for (int c = 0; c < 3; c++)
				put_f32(f, im.px[3 * ((size_t)y * N + x) + c]);
		}
	pm_rgbimage_free(&im);
	if (fclose(f)) {
		free(buf);
		return pm_seterr(w->err, "out of memory");
	}
	if (keep_file(w, ".pfm", buf, len, name, n))
		return -1;
	pmi_note_add(w->d, l->src, "environment image '%s': pbrt-v4's equal-area square resampled to a %d x %d "
	             "lat-long map (nearest texel)", l->map, W, H);
	return 0;
}

static int
write_lights(wctx *w, FILE *f)
{
	int n = 0, nenv = 0;

	for (size_t i = 0; i < w->d->nlights; i++) {
		const pmi_light *l = &w->d->lights[i];
		double p[3], q[3], c[3];
		for (int k = 0; k < 3; k++)
			c[k] = fmax(l->color[k], 0);
		memcpy(p, l->pos, sizeof p);
		mirror_point(w, p);
		switch (l->kind) {
		case PMI_LIGHT_POINT:
			if (!positive(c)) {
				pmi_note_add(w->d, l->src, "point light of zero intensity: dropped");
				break;
			}
			/* An isotropic point light of intensity I emits 4 pi I. */
			fprintf(f, "pointlight %.9g %.9g %.9g power %.9g %.9g %.9g\n", p[0], p[1], p[2],
			        4 * PM_PI * c[0], 4 * PM_PI * c[1], 4 * PM_PI * c[2]);
			n++;
			break;
		case PMI_LIGHT_SPOT: {
			double outer = l->cone, inner = l->cone - l->falloff;
			double dl = sqrt(l->dir[0] * l->dir[0] + l->dir[1] * l->dir[1] + l->dir[2] * l->dir[2]);
			if (!positive(c) || !(dl > 0) || !(outer > 0)) {
				pmi_note_add(w->d, l->src, "spot light of zero intensity, direction or cone: dropped");
				break;
			}
			if (outer > 90) {
				pmi_note_add(w->d, l->src, "spot light cone of %g degrees: cut to 90 (pm's widest)", outer);
				outer = 90;
			}
			inner = fmin(fmax(inner, 0), outer);
			for (int k = 0; k < 3; k++)
				q[k] = l->pos[k] + l->dir[k] / dl;
			mirror_point(w, q);
			fprintf(f, "spotlight %.9g %.9g %.9g to %.9g %.9g %.9g intensity %.9g %.9g %.9g cone %.9g %.9g falloff %s\n",
			        p[0], p[1], p[2], q[0], q[1], q[2], c[0], c[1], c[2], outer, inner,
			        l->linear ? "linear" : "smooth");
			n++;
			break;
		}
		case PMI_LIGHT_DISTANT:
			memcpy(q, l->dir, sizeof q);
			mirror_point(w, q);
			if (!positive(c) || !(q[0] != 0 || q[1] != 0 || q[2] != 0)) {
				pmi_note_add(w->d, l->src, "distant light of zero irradiance or direction: dropped");
				break;
			}
			fprintf(f, "distantlight dir %.9g %.9g %.9g irradiance %.9g %.9g %.9g\n", q[0], q[1], q[2],
			        c[0], c[1], c[2]);
			n++;
			break;
		case PMI_LIGHT_INFINITE:
			if (nenv) {
				pmi_note_add(w->d, l->src, "a second environment light: dropped (pm has at most one)");
				break;
			}
			if (!l->map[0]) {
				if (!positive(c)) {
					pmi_note_add(w->d, l->src, "environment light of zero radiance: dropped");
					break;
				}
				fprintf(f, "envlight radiance %.9g %.9g %.9g\n", c[0], c[1], c[2]);
			} else {
				char name[512];
				double axis[3], deg = 0, sc = l->map_scale > 0 ? l->map_scale : 1;
				if (l->equal_area) {
					int r = equal_area_sky(w, l, name, sizeof name);
					if (r < 0)
						return -1;
					if (r > 0)
						break;
					fprintf(f, "envlight image %s scale %.9g\n", name, sc);
					nenv++;
					n++;
					break;
				}
				if (w->mirror) {
					pmi_note_add(w->d, l->src, "environment image in a mirrored world: pm cannot mirror it, dropped");
					break;
				}
				if (l->has_rot && axis_angle(l->rot, axis, &deg)) {
					pmi_note_add(w->d, l->src, "environment image with a mirroring or degenerate to_world: dropped");
					break;
				}
				int r = copy_image(w, l->map, l->src, name, sizeof name);
				if (r < 0)
					return -1;
				if (r > 0)
					break;
				fprintf(f, "envlight image %s scale %.9g", name, sc);
				if (deg > 1e-9)
					fprintf(f, " rotate %.9g %.9g %.9g %.9g", axis[0], axis[1], axis[2], deg);
				fputc('\n', f);
			}
			nenv++;
			n++;
			break;
		default:
			pmi_note_add(w->d, l->src, "light '%s': pm has no such light, dropped", l->type);
			break;
		}
	}
	return n;
}

/* ---- meshes ---- */

static int
remember(char ***arr, size_t *n, const char *s)
{
	char **a = realloc(*arr, (*n + 1) * sizeof *a);
	if (!a)
		return -1;
	*arr = a;
	if (!(a[*n] = strdup(s)))
		return -1;
	(*n)++;
	return 0;
}

static void
put_u32(FILE *f, uint32_t v)
{
	unsigned char b[4] = { v & 255, v >> 8 & 255, v >> 16 & 255, v >> 24 };
	fwrite(b, 1, 4, f);
}

static void
put_f32(FILE *f, float x)
{
	uint32_t u;
	memcpy(&u, &x, 4);
	put_u32(f, u);
}


/* The mesh with equal positions welded (so a closed surface whose file
 * repeats vertices at uv seams is a closed solid to pm; with_uv welds
 * only where (u, v) are equal too, as a texture needs, and shading
 * normals only where they are equal) and faces of no area dropped, as a
 * binary PLY in memory. */
static int
mesh_ply(wctx *w, const pmi_shape *s, int with_uv, char **buf, size_t *len, size_t *kept)
{
	enum { K = 8 };   /* x y z u v nx ny nz */
	int with_n = s->n != NULL;
	size_t cap = 1;
	while (cap < 2 * s->nv + 16)
		cap <<= 1;
	int64_t *slot = malloc(cap * sizeof *slot);
	uint32_t *remap = malloc((s->nv ? s->nv : 1) * sizeof *remap);
	float *pv = malloc((s->nv ? s->nv : 1) * K * sizeof *pv);
	size_t nu = 0;
	FILE *f;

	if (!slot || !remap || !pv) {
		free(slot); free(remap); free(pv);
		return -1;
	}
	for (size_t i = 0; i < cap; i++)
		slot[i] = -1;
	for (size_t i = 0; i < s->nv; i++) {
		float p[K] = { s->v[3 * i], s->v[3 * i + 1], s->v[3 * i + 2], 0, 0, 0, 0, 0 };
		if (with_uv) {
			p[3] = s->uv[2 * i];
			p[4] = s->uv[2 * i + 1];
		}
		if (with_n)
			memcpy(p + 5, s->n + 3 * i, 3 * sizeof *p);
		if (w->mirror) {
			p[0] = -p[0];
			p[5] = -p[5];
		}
		for (int c = 0; c < K; c++)
			if (p[c] == 0)
				p[c] = 0;   /* -0 and +0 weld */
		uint64_t h = pm_fnv1a(PM_FNV_OFFSET, p, sizeof p);
		size_t k = h & (cap - 1);
		while (slot[k] >= 0 && memcmp(pv + K * slot[k], p, sizeof p) != 0)
			k = (k + 1) & (cap - 1);
		if (slot[k] < 0) {
			slot[k] = (int64_t)nu;
			memcpy(pv + K * nu, p, sizeof p);
			nu++;
		}
		remap[i] = (uint32_t)slot[k];
	}
	free(slot);
	if (!(f = open_memstream(buf, len))) {
		free(remap); free(pv);
		return -1;
	}
	/* Which faces have area, and their corners after welding. */
	double ext = 0;
	for (size_t i = 0; i < nu; i++)
		for (int c = 0; c < 3; c++)
			ext = fmax(ext, fabs(pv[K * i + c]));
	size_t nf = 0, nfan = 0;
	unsigned char *keep = calloc(s->nface ? s->nface : 1, 1);
	if (!keep) {
		fclose(f); free(*buf); free(remap); free(pv);
		return -1;
	}
	for (size_t fi = 0; fi < s->nface; fi++) {
		uint32_t b = s->start[fi], k = s->start[fi + 1] - b;
		double a = pmi_face_area(s, fi), size = 0;
		for (uint32_t i = 0; i < k; i++) {
			const float *p = s->v + 3 * (size_t)s->idx[b + i], *q = s->v + 3 * (size_t)s->idx[b + (i + 1) % k];
			size = fmax(size, sqrt(((double)p[0] - q[0]) * (p[0] - q[0]) + ((double)p[1] - q[1]) * (p[1] - q[1]) +
			                       ((double)p[2] - q[2]) * (p[2] - q[2])));
		}
		/* pm drops a polygon whose mean width 2A/size is at most
		 * 1e-6 (size + extent); twice that margin here. */
		if (k >= 3 && size > 0 && 2 * a / size > 2e-6 * (size + ext)) {
			keep[fi] = 1;
			nf++;
			nfan += k > 255 ? k - 3 : 0;
		}
	}
	fprintf(f, "ply\nformat binary_little_endian 1.0\ncomment pm-import\nelement vertex %zu\n"
	        "property float x\nproperty float y\nproperty float z\n%s%selement face %zu\n"
	        "property list uchar uint vertex_indices\nend_header\n", nu,
	        with_n ? "property float nx\nproperty float ny\nproperty float nz\n" : "",
	        with_uv ? "property float u\nproperty float v\n" : "", nf + nfan);
	for (size_t i = 0; i < nu; i++) {
		for (int c = 0; c < 3; c++)
			put_f32(f, pv[K * i + c]);
		for (int c = 5; c < (with_n ? 8 : 5); c++)
			put_f32(f, pv[K * i + c]);
		for (int c = 3; c < (with_uv ? 5 : 3); c++)
			put_f32(f, pv[K * i + c]);
	}
	for (size_t fi = 0; fi < s->nface; fi++) {
		if (!keep[fi])
			continue;
		uint32_t b = s->start[fi], k = s->start[fi + 1] - b;
		/* Mirroring the world reverses every face to keep its front. */
#define CORNER(i) remap[s->idx[b + (w->mirror ? k - 1 - (i) : (i))]]
		if (k <= 255) {
			fputc((int)k, f);
			for (uint32_t i = 0; i < k; i++)
				put_u32(f, CORNER(i));
		} else
			for (uint32_t i = 1; i + 1 < k; i++) {
				fputc(3, f);
				put_u32(f, CORNER(0));
				put_u32(f, CORNER(i));
				put_u32(f, CORNER(i + 1));
			}
#undef CORNER
	}
	free(keep);
	free(remap);
	free(pv);
	*kept = nf;
	return fclose(f) ? -1 : 0;
}

static int
write_file(wctx *w, const char *path, const char *buf, size_t len)
{
	pm_out o;
	struct stat st;
	int existed = stat(path, &st) == 0;

	if (pm_out_open(&o, path, w->err))
		return -1;
	if (fwrite(buf, 1, len, o.f) != len) {
		pm_out_abort(&o);
		return pm_seterr(w->err, "cannot write '%s': %s", path, strerror(errno));
	}
	if (pm_out_commit(&o, w->err))
		return -1;
	if (!existed && remember(&w->made, &w->nmade, path))
		return pm_seterr(w->err, "out of memory");
	return 0;
}

/* Copies image file src beside the scene as STEM-HASH.EXT (the hash of
 * its bytes), so the scene directory holds all it needs; its name in
 * name. 1 (noted) if src cannot be read, -1 on a write error. */
static int
copy_image(wctx *w, const char *src, pmi_src at, char *name, size_t n)
{
	FILE *in = fopen(src, "rb");
	char *buf = NULL;
	size_t len = 0, cap = 0, k;

	if (!in) {
		pmi_note_add(w->d, at, "image '%s' cannot be read (%s): dropped", src, strerror(errno));
		return 1;
	}
	for (;;) {
		if (len == cap) {
			char *nb = realloc(buf, cap = cap ? 2 * cap : 65536);
			if (!nb) {
				free(buf);
				fclose(in);
				return pm_seterr(w->err, "out of memory");
			}
			buf = nb;
		}
		if (!(k = fread(buf + len, 1, cap - len, in)))
			break;
		len += k;
	}
	int bad = ferror(in);
	fclose(in);
	if (bad || len == 0) {
		free(buf);
		pmi_note_add(w->d, at, "image '%s' cannot be read or is empty: dropped", src);
		return 1;
	}
	const char *base = strrchr(src, '/'), *dot;
	base = base ? base + 1 : src;
	dot = strrchr(base, '.');
	char ext[16] = "";
	if (dot && strlen(dot) < sizeof ext && strcspn(dot, " \t#") == strlen(dot))
		snprintf(ext, sizeof ext, "%s", dot);
	if (keep_file(w, ext, buf, len, name, n))
		return -1;
	return 0;
}

static int
write_shape(wctx *w, const pmi_shape *s, FILE *f, const pm_mat *pmm)
{
	if (s->kind == PMI_SHAPE_SPHERE) {
		double c[3];
		memcpy(c, s->center, sizeof c);
		mirror_point(w, c);
		if (!(s->radius > 0)) {
			pmi_note_add(w->d, s->src, "sphere of radius 0: dropped");
			return 0;
		}
		/* Emitters finer: their area (radiance x area is their power)
		 * is 0.05 % short at subdiv 5, 0.2 % at pm's default 4. */
		int emits = s->emit[0] > 0 || s->emit[1] > 0 || s->emit[2] > 0;
		if (w->d->mats[s->mat].tex > 0 && w->tex_state[w->d->mats[s->mat].tex - 1] > 0)
			pmi_note_add(w->d, s->src, "textured sphere: pm's spheres have no (u, v), the texture is read at (0, 0)");
		/* smooth: shaded with the true sphere's normals, as pbrt-v4 and
		 * Mitsuba 3 shade their analytic spheres. */
		fprintf(f, "sphere %s %.9g %.9g %.9g %.9g subdiv %d smooth\n", pmm->name, c[0], c[1], c[2], s->radius,
		        emits ? 5 : 4);
		return 1;
	}
	char *buf = NULL, name[512];
	size_t len = 0, kept = 0;
	if (s->mat >= 0 && w->d->mats[s->mat].tex > 0 && w->tex_state[w->d->mats[s->mat].tex - 1] > 0 && !s->uv)
		pmi_note_add(w->d, s->src, "textured shape without (u, v): pm reads its texture at (0, 0)");
	int with_uv = s->uv && s->mat >= 0 && w->d->mats[s->mat].tex > 0 && w->tex_state[w->d->mats[s->mat].tex - 1] > 0;
	if (mesh_ply(w, s, with_uv, &buf, &len, &kept))
		return pm_seterr(w->err, "out of memory");
	if (kept == 0) {
		free(buf);
		pmi_note_add(w->d, s->src, "shape with no face of nonzero area: dropped");
		return 0;
	}
	if (kept < s->nface)
		pmi_note_add(w->d, s->src, "faces of (nearly) zero area dropped");
	if (keep_file(w, ".ply", buf, len, name, sizeof name))
		return -1;
	fprintf(f, "mesh %s %s\n", name, pmm->name);
	return 1;
}

/* The mesh files an earlier NAME.pms written by pm-import names (by the
 * NAME-HASH.ply pattern), so those the new scene no longer uses can be
 * removed once it is in place. */
static void
old_meshes(wctx *w, const char *pms, char ***names, size_t *n)
{
	FILE *f = fopen(pms, "r");
	char line[4096], name[512];
	size_t sl = strlen(w->stem);

	if (!f)
		return;
	while (fgets(line, sizeof line, f))
		if ((sscanf(line, "mesh %511s", name) == 1 || sscanf(line, "texture %*s image %511s", name) == 1 ||
		     sscanf(line, "envlight image %511s", name) == 1) &&
		    strncmp(name, w->stem, sl) == 0 && strlen(name) >= sl + 17 && name[sl] == '-' &&
		    strspn(name + sl + 1, "0123456789abcdef") == 16 && (!name[sl + 17] || name[sl + 17] == '.') &&
		    remember(names, n, name))
			break;
	fclose(f);
}

static int
write_body(wctx *w, FILE *body, int width, int height, int *nlights)
{
	if (write_camera(w, body, width, height))
		return -1;
	FILE *mats;
	char *mbuf = NULL;
	size_t mlen = 0;
	char *obuf = NULL;
	size_t olen = 0;
	FILE *objs = open_memstream(&obuf, &olen);
	if (!objs || !(mats = open_memstream(&mbuf, &mlen))) {
		if (objs)
			fclose(objs);
		free(obuf);
		return pm_seterr(w->err, "out of memory");
	}
	int r = 0;
	*nlights = 0;
	for (size_t i = 0; i < w->d->nshapes && !r; i++) {
		const pmi_shape *s = &w->d->shapes[i];
		int emits = s->emit[0] > 0 || s->emit[1] > 0 || s->emit[2] > 0;
		if (s->mat < 0 || (size_t)s->mat >= w->d->nmats) {
			r = pmi_err(w->d, s->src, w->err, "shape without a material");
			break;
		}
		if (w->d->mats[s->mat].kind == PMI_MAT_INVISIBLE && !emits)
			continue;
		const pm_mat *pmm = material_for(w, s, mats);
		if (!pmm) {
			r = w->err->msg[0] ? -1 : pm_seterr(w->err, "out of memory");
			break;
		}
		int k = write_shape(w, s, objs, pmm);
		if (k < 0)
			r = -1;
		else if (k > 0 && emits)
			(*nlights)++;
	}
	if (!r) {
		int nl = write_lights(w, objs);
		if (nl < 0)
			r = -1;
		else
			*nlights += nl;
	}
	int e1 = fclose(mats), e2 = fclose(objs);
	if (!r && (e1 || e2))
		r = pm_seterr(w->err, "out of memory");
	if (!r) {
		fwrite(mbuf, 1, mlen, body);
		fwrite(obuf, 1, olen, body);
	}
	free(mbuf);
	free(obuf);
	return r;
}

int
pmi_write(pmi_desc *d, const char *pms_path, const pmi_write_opts *o, pm_error *err)
{
	wctx w;
	char *body = NULL, *text = NULL;
	size_t blen = 0, tlen = 0;
	FILE *bf = NULL, *tf = NULL;
	int r = -1, made_dir = 0, nlights = 0;
	struct stat st;

	memset(&w, 0, sizeof w);
	w.d = d;
	w.err = err;
	err->msg[0] = 0;
	if (!(w.tex_state = calloc(d->ntexs + 1, sizeof *w.tex_state)))
		return pm_seterr(err, "out of memory");
	const char *sl = strrchr(pms_path, '/');
	const char *base = sl ? sl + 1 : pms_path;
	if (sl)
		snprintf(w.dir, sizeof w.dir, "%.*s/", (int)(sl - pms_path), pms_path);
	snprintf(w.stem, sizeof w.stem, "%.*s", (int)strcspn(base, "."), base);
	if (!w.stem[0] || strcspn(base, " \t#") != strlen(base))
		return pm_seterr(err, "'%s': the scene's name must not be empty or hold spaces or '#'", pms_path);
	if (w.dir[0] && stat(w.dir, &st) != 0) {
		if (mkdir(w.dir, 0777) != 0)
			return pm_seterr(err, "cannot create directory '%s': %s", w.dir, strerror(errno));
		made_dir = 1;
	}
	int width = o && o->width > 0 ? o->width : d->cam.width;
	int height = o && o->height > 0 ? o->height : d->cam.height;
	if (!(bf = open_memstream(&body, &blen))) {
		pm_seterr(err, "out of memory");
		goto out;
	}
	if (write_body(&w, bf, width, height, &nlights)) {
		fclose(bf);
		bf = NULL;
		goto out;
	}
	if (fclose(bf)) {
		bf = NULL;
		pm_seterr(err, "out of memory");
		goto out;
	}
	bf = NULL;
	if (nlights == 0) {
		pm_seterr(err, "%s: no light pm can render (every light was dropped; see the notes)",
		           d->nfiles ? d->files[0] : "scene");
		goto out;
	}
	if (!(tf = open_memstream(&text, &tlen))) {
		pm_seterr(err, "out of memory");
		goto out;
	}
	fprintf(tf, "# pm scene imported from %s by pm-import\n", d->nfiles ? d->files[0] : "?");
	if (o && o->command)
		fprintf(tf, "# command: %s\n", o->command);
	if (d->nnotes)
		fprintf(tf, "# approximated or dropped (source file:line):\n");
	for (size_t i = 0; i < d->nnotes; i++) {
		char where[300];
		fprintf(tf, "#   %s: %s", pmi_where(d, d->notes[i].src, where, sizeof where), d->notes[i].msg);
		if (d->notes[i].count > 1)
			fprintf(tf, " (%d times)", d->notes[i].count);
		fputc('\n', tf);
	}
	fwrite(body, 1, blen, tf);
	if (fclose(tf)) {
		tf = NULL;
		pm_seterr(err, "out of memory");
		goto out;
	}
	tf = NULL;
	/* Check the scene as pm reads it before it replaces anything. */
	{
		char check[4700];
		pm_scene sc;
		pm_error e;
		snprintf(check, sizeof check, "%s.%s%scheck-%ld.pms", w.dir, w.stem, PM_TMP_MARK, (long)getpid());
		FILE *cf = fopen(check, "wb");
		if (!cf || fwrite(text, 1, tlen, cf) != tlen || fclose(cf)) {
			if (cf)
				unlink(check);
			pm_seterr(err, "cannot write '%s': %s", check, strerror(errno));
			goto out;
		}
		int lr = pm_scene_load(&sc, check, &e);
		unlink(check);
		if (lr) {
			/* Out of pm's range (formats/scene.md, "Range") is the
			 * input's doing: name it, and the statement without the
			 * temporary file's name. Anything else is the writer's. */
			const char *m = e.msg;
			size_t cl = strlen(check);
			if (!strncmp(m, check, cl) && m[cl] == ':')
				m += cl + 1 + strspn(m + cl + 1, "0123456789:") ;
			m += strspn(m, " ");
			if (strstr(e.msg, "\"Range\"") && d->nfiles > 0)
				pm_seterr(err, "%s: the scene is beyond what pm renders: %s", d->files[0], m);
			else
				pm_seterr(err, "the imported scene does not load (a pm-import bug): %s", e.msg);
			goto out;
		}
		pm_scene_free(&sc);
	}
	{
		char **old = NULL;
		size_t nold = 0;
		old_meshes(&w, pms_path, &old, &nold);
		int wr = write_file(&w, pms_path, text, tlen);
		for (size_t i = 0; i < nold; i++) {
			int used = 0;
			for (size_t k = 0; k < w.nmeshes; k++)
				used |= !strcmp(w.meshes[k], old[i]);
			if (!wr && !used) {
				char path[4700];
				snprintf(path, sizeof path, "%s%s", w.dir, old[i]);
				unlink(path);
			}
			free(old[i]);
		}
		free(old);
		if (wr)
			goto out;
	}
	r = 0;
out:
	if (bf)
		fclose(bf);
	if (tf)
		fclose(tf);
	free(body);
	free(text);
	if (r) {
		for (size_t i = 0; i < w.nmade; i++)
			unlink(w.made[i]);
		if (made_dir)
			rmdir(w.dir);
	}
	for (size_t i = 0; i < w.nmade; i++)
		free(w.made[i]);
	free(w.made);
	for (size_t i = 0; i < w.nmeshes; i++)
		free(w.meshes[i]);
	free(w.meshes);
	free(w.mats);
	free(w.tex_state);
	return r;
}

int
pmi_frame_camera(pmi_desc *d, double fov, pm_error *err)
{
	double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };

	for (size_t i = 0; i < d->nshapes; i++) {
		const pmi_shape *s = &d->shapes[i];
		if (s->kind == PMI_SHAPE_SPHERE)
			for (int c = 0; c < 3; c++) {
				lo[c] = fmin(lo[c], s->center[c] - s->radius);
				hi[c] = fmax(hi[c], s->center[c] + s->radius);
			}
		else
			for (size_t k = 0; k < s->nv; k++)
				for (int c = 0; c < 3; c++) {
					lo[c] = fmin(lo[c], s->v[3 * k + c]);
					hi[c] = fmax(hi[c], s->v[3 * k + c]);
				}
	}
	if (!(lo[0] <= hi[0]))
		return pm_seterr(err, "%s: no geometry to frame", d->nfiles ? d->files[0] : "scene");
	double c[3], r = 0;
	for (int k = 0; k < 3; k++) {
		c[k] = 0.5 * (lo[k] + hi[k]);
		r += 0.25 * (hi[k] - lo[k]) * (hi[k] - lo[k]);
	}
	r = sqrt(r);
	if (!(r > 0))
		r = 1;
	double dist = r / sin(fov * PM_PI / 360);
	pmi_camera *cam = &d->cam;
	cam->set = 1;
	cam->src = (pmi_src){ 0, 0 };
	cam->pos[0] = c[0];
	cam->pos[1] = c[1];
	cam->pos[2] = c[2] + dist;
	memset(cam->right, 0, sizeof cam->right);
	memset(cam->up, 0, sizeof cam->up);
	memset(cam->fwd, 0, sizeof cam->fwd);
	cam->right[0] = 1;
	cam->up[1] = 1;
	cam->fwd[2] = -1;
	cam->fov = fov;
	cam->fov_axis = PMI_FOV_SHORTER;
	return 0;
}
