/* desc.c — the neutral scene description: its arrays, notes and the
 * transform arithmetic the readers share (see desc.h). */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec.h"
#include "import/desc.h"

void
pmi_init(pmi_desc *d)
{
	memset(d, 0, sizeof *d);
}

void
pmi_shape_free(pmi_shape *s)
{
	free(s->v);
	free(s->uv);
	free(s->n);
	free(s->start);
	free(s->idx);
	s->v = s->uv = s->n = NULL;
	s->start = s->idx = NULL;
	s->nv = s->nface = 0;
}

void
pmi_free(pmi_desc *d)
{
	for (int i = 0; i < d->nfiles; i++)
		free(d->files[i]);
	free(d->files);
	for (size_t i = 0; i < d->nshapes; i++)
		pmi_shape_free(&d->shapes[i]);
	free(d->shapes);
	free(d->mats);
	free(d->lights);
	free(d->texs);
	free(d->notes);
	memset(d, 0, sizeof *d);
}

int
pmi_file(pmi_desc *d, const char *path)
{
	char **f;

	for (int i = 0; i < d->nfiles; i++)
		if (strcmp(d->files[i], path) == 0)
			return i;
	if (!(f = realloc(d->files, (d->nfiles + 1) * sizeof *f)))
		return -1;
	d->files = f;
	if (!(f[d->nfiles] = strdup(path)))
		return -1;
	return d->nfiles++;
}

/* One more zeroed element of size sz in *arr, growing it by doubling. */
static void *
grow(void **arr, size_t *n, size_t *cap, size_t sz)
{
	if (*n == *cap) {
		size_t nc = *cap ? *cap * 2 : 16;
		void *p = realloc(*arr, nc * sz);
		if (!p)
			return NULL;
		*arr = p;
		*cap = nc;
	}
	char *e = (char *)*arr + (*n)++ * sz;
	memset(e, 0, sz);
	return e;
}

pmi_material *
pmi_add_material(pmi_desc *d, pmi_src src)
{
	pmi_material *m = grow((void **)&d->mats, &d->nmats, &d->capmats, sizeof *m);
	if (m) {
		m->src = src;
		m->eta = 1.5;
	}
	return m;
}

pmi_shape *
pmi_add_shape(pmi_desc *d, pmi_src src)
{
	pmi_shape *s = grow((void **)&d->shapes, &d->nshapes, &d->capshapes, sizeof *s);
	if (s) {
		s->src = src;
		s->mat = -1;
	}
	return s;
}

pmi_light *
pmi_add_light(pmi_desc *d, pmi_src src)
{
	pmi_light *l = grow((void **)&d->lights, &d->nlights, &d->caplights, sizeof *l);
	if (l)
		l->src = src;
	return l;
}

pmi_texture *
pmi_add_texture(pmi_desc *d, pmi_src src)
{
	pmi_texture *t = grow((void **)&d->texs, &d->ntexs, &d->captexs, sizeof *t);
	if (t) {
		t->src = src;
		t->su = t->sv = 1;
	}
	return t;
}

int
pmi_note_add(pmi_desc *d, pmi_src src, const char *fmt, ...)
{
	char msg[300];
	va_list ap;
	pmi_note *n;

	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	for (size_t i = 0; i < d->nnotes; i++)
		if (strcmp(d->notes[i].msg, msg) == 0) {
			d->notes[i].count++;
			return 0;
		}
	if (!(n = grow((void **)&d->notes, &d->nnotes, &d->capnotes, sizeof *n)))
		return -1;
	n->src = src;
	n->count = 1;
	memcpy(n->msg, msg, sizeof msg);
	return 0;
}

const char *
pmi_where(const pmi_desc *d, pmi_src src, char *buf, size_t n)
{
	const char *f = src.file >= 0 && src.file < d->nfiles ? d->files[src.file] : "?";

	if (src.line > 0)
		snprintf(buf, n, "%s:%d", f, src.line);
	else
		snprintf(buf, n, "%s", f);
	return buf;
}

int
pmi_err(const pmi_desc *d, pmi_src src, pm_error *err, const char *fmt, ...)
{
	char msg[400], where[300];
	va_list ap;

	va_start(ap, fmt);
	vsnprintf(msg, sizeof msg, fmt, ap);
	va_end(ap);
	return pm_seterr(err, "%s: %s", pmi_where(d, src, where, sizeof where), msg);
}

pmi_mat4
pmi_identity(void)
{
	pmi_mat4 a;

	memset(&a, 0, sizeof a);
	for (int i = 0; i < 4; i++)
		a.m[i][i] = 1;
	return a;
}

pmi_mat4
pmi_mul(pmi_mat4 a, pmi_mat4 b)
{
	pmi_mat4 c;

	for (int i = 0; i < 4; i++)
		for (int j = 0; j < 4; j++) {
			double s = 0;
			for (int k = 0; k < 4; k++)
				s += a.m[i][k] * b.m[k][j];
			c.m[i][j] = s;
		}
	return c;
}

/* Gauss-Jordan with partial pivoting. */
int
pmi_invert(pmi_mat4 a, pmi_mat4 *out)
{
	pmi_mat4 r = pmi_identity();

	for (int c = 0; c < 4; c++) {
		int p = c;
		for (int i = c + 1; i < 4; i++)
			if (fabs(a.m[i][c]) > fabs(a.m[p][c]))
				p = i;
		if (!(fabs(a.m[p][c]) > 1e-300))
			return -1;
		for (int j = 0; j < 4; j++) {
			double t = a.m[c][j]; a.m[c][j] = a.m[p][j]; a.m[p][j] = t;
			t = r.m[c][j]; r.m[c][j] = r.m[p][j]; r.m[p][j] = t;
		}
		double inv = 1 / a.m[c][c];
		for (int j = 0; j < 4; j++) {
			a.m[c][j] *= inv;
			r.m[c][j] *= inv;
		}
		for (int i = 0; i < 4; i++)
			if (i != c) {
				double f = a.m[i][c];
				for (int j = 0; j < 4; j++) {
					a.m[i][j] -= f * a.m[c][j];
					r.m[i][j] -= f * r.m[c][j];
				}
			}
	}
	*out = r;
	return 0;
}

pmi_mat4
pmi_translate(double x, double y, double z)
{
	pmi_mat4 a = pmi_identity();

	a.m[0][3] = x;
	a.m[1][3] = y;
	a.m[2][3] = z;
	return a;
}

pmi_mat4
pmi_scale(double x, double y, double z)
{
	pmi_mat4 a = pmi_identity();

	a.m[0][0] = x;
	a.m[1][1] = y;
	a.m[2][2] = z;
	return a;
}

pmi_mat4
pmi_rotate(double deg, double x, double y, double z)
{
	pmi_mat4 a = pmi_identity();
	double l = sqrt(x * x + y * y + z * z);

	if (!(l > 0))
		return a;
	x /= l; y /= l; z /= l;
	double s = sin(deg * PM_PI / 180), c = cos(deg * PM_PI / 180), t = 1 - c;
	a.m[0][0] = x * x * t + c;     a.m[0][1] = x * y * t - z * s; a.m[0][2] = x * z * t + y * s;
	a.m[1][0] = x * y * t + z * s; a.m[1][1] = y * y * t + c;     a.m[1][2] = y * z * t - x * s;
	a.m[2][0] = x * z * t - y * s; a.m[2][1] = y * z * t + x * s; a.m[2][2] = z * z * t + c;
	return a;
}

double
pmi_det3(pmi_mat4 a)
{
	return a.m[0][0] * (a.m[1][1] * a.m[2][2] - a.m[1][2] * a.m[2][1]) -
	       a.m[0][1] * (a.m[1][0] * a.m[2][2] - a.m[1][2] * a.m[2][0]) +
	       a.m[0][2] * (a.m[1][0] * a.m[2][1] - a.m[1][1] * a.m[2][0]);
}

void
pmi_xform_point(pmi_mat4 a, const double p[3], double out[3])
{
	double r[3];

	for (int i = 0; i < 3; i++)
		r[i] = a.m[i][0] * p[0] + a.m[i][1] * p[1] + a.m[i][2] * p[2] + a.m[i][3];
	memcpy(out, r, sizeof r);
}

void
pmi_xform_vector(pmi_mat4 a, const double v[3], double out[3])
{
	double r[3];

	for (int i = 0; i < 3; i++)
		r[i] = a.m[i][0] * v[0] + a.m[i][1] * v[1] + a.m[i][2] * v[2];
	memcpy(out, r, sizeof r);
}

static void
reverse_face(pmi_shape *s, size_t f)
{
	uint32_t *a = s->idx + s->start[f], n = s->start[f + 1] - s->start[f];

	for (uint32_t i = 0; i < n / 2; i++) {
		uint32_t t = a[i];
		a[i] = a[n - 1 - i];
		a[n - 1 - i] = t;
	}
}

void
pmi_shape_xform(pmi_shape *s, pmi_mat4 a, int flip)
{
	if (s->kind == PMI_SHAPE_SPHERE) {
		pmi_xform_point(a, s->center, s->center);
		s->radius *= cbrt(fabs(pmi_det3(a)));
		return;
	}
	for (size_t i = 0; i < s->nv; i++) {
		double p[3] = { s->v[3 * i], s->v[3 * i + 1], s->v[3 * i + 2] };
		pmi_xform_point(a, p, p);
		for (int k = 0; k < 3; k++)
			s->v[3 * i + k] = (float)p[k];
	}
	pmi_mat4 inv;
	if (s->n && pmi_invert(a, &inv) == 0)
		for (size_t i = 0; i < s->nv; i++) {
			/* A normal goes by the inverse transpose. */
			double n[3], l = 0;
			for (int r = 0; r < 3; r++) {
				n[r] = 0;
				for (int c = 0; c < 3; c++)
					n[r] += inv.m[c][r] * s->n[3 * i + c];
				l += n[r] * n[r];
			}
			l = l > 0 ? 1 / sqrt(l) : 0;
			for (int r = 0; r < 3; r++)
				s->n[3 * i + r] = (float)(n[r] * l);
		}
	if ((pmi_det3(a) < 0) != (flip != 0))
		for (size_t f = 0; f < s->nface; f++)
			reverse_face(s, f);
}

double
pmi_face_area(const pmi_shape *s, size_t f)
{
	double n[3] = { 0, 0, 0 };
	uint32_t b = s->start[f], k = s->start[f + 1] - b;

	/* Newell's method: twice the vector area. */
	for (uint32_t i = 0; i < k; i++) {
		const float *p = s->v + 3 * (size_t)s->idx[b + i];
		const float *q = s->v + 3 * (size_t)s->idx[b + (i + 1) % k];
		n[0] += ((double)p[1] - q[1]) * ((double)p[2] + q[2]);
		n[1] += ((double)p[2] - q[2]) * ((double)p[0] + q[0]);
		n[2] += ((double)p[0] - q[0]) * ((double)p[1] + q[1]);
	}
	return 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

int
pmi_mesh_alloc(pmi_shape *s, size_t nv, size_t nface, size_t ncorners, int with_uv)
{
	s->kind = PMI_SHAPE_MESH;
	s->nv = nv;
	s->nface = nface;
	s->v = malloc((nv ? nv : 1) * 3 * sizeof *s->v);
	s->uv = with_uv ? malloc((nv ? nv : 1) * 2 * sizeof *s->uv) : NULL;
	s->start = malloc((nface + 1) * sizeof *s->start);
	s->idx = malloc((ncorners ? ncorners : 1) * sizeof *s->idx);
	if (!s->v || !s->start || !s->idx || (with_uv && !s->uv))
		return -1;
	s->start[0] = 0;
	return 0;
}

int
pmi_disk_mesh(pmi_shape *s, double r, double ri, double h, double phimax)
{
	enum { N = 96 };
	int full = phimax >= 360, seg = full ? N : (int)ceil(N * phimax / 360);
	int ring = full ? seg : seg + 1;

	if (seg < 1)
		seg = 1, ring = 2;
	if (ri > 0 || !full) {
		/* Quads between the inner and outer rings (the inner may be the
		 * centre, for a partial disk). */
		if (pmi_mesh_alloc(s, 2 * (size_t)ring, seg, 4 * (size_t)seg, 0))
			return -1;
		for (int i = 0; i < ring; i++) {
			double phi = (full ? 2 * PM_PI / seg : phimax * PM_PI / 180 / seg) * i;
			float *o = s->v + 6 * i;
			o[0] = (float)(r * cos(phi)); o[1] = (float)(r * sin(phi)); o[2] = (float)h;
			o[3] = (float)(ri * cos(phi)); o[4] = (float)(ri * sin(phi)); o[5] = (float)h;
		}
		for (int i = 0; i < seg; i++) {
			uint32_t a = 2 * i, b = 2 * ((i + 1) % ring);
			uint32_t *q = s->idx + 4 * i;
			q[0] = a + 1; q[1] = a; q[2] = b; q[3] = b + 1;
			s->start[i + 1] = 4 * (i + 1);
		}
		return 0;
	}
	if (pmi_mesh_alloc(s, N, 1, N, 0))
		return -1;
	for (int i = 0; i < N; i++) {
		double phi = 2 * PM_PI * i / N;
		s->v[3 * i] = (float)(r * cos(phi));
		s->v[3 * i + 1] = (float)(r * sin(phi));
		s->v[3 * i + 2] = (float)h;
		s->idx[i] = i;
	}
	s->start[1] = N;
	return 0;
}

int
pmi_metal_f0(const char *sym, double f0[3])
{
	/* From the metals' measured complex indices of refraction at the sRGB
	 * primaries' wavelengths (Fresnel at normal incidence). */
	static const struct { const char *m; double r, g, b; } tab[] = {
		{"Au", 1.000, 0.766, 0.336}, {"Ag", 0.972, 0.960, 0.915}, {"Cu", 0.955, 0.638, 0.538},
		{"Al", 0.913, 0.922, 0.924}, {"CuZn", 0.910, 0.778, 0.423}, {"Cr", 0.550, 0.556, 0.554},
		{"Ni", 0.660, 0.609, 0.526}, {"Ti", 0.542, 0.497, 0.449}, {"Fe", 0.562, 0.565, 0.578},
		{"Pt", 0.673, 0.637, 0.585}, {"W", 0.504, 0.498, 0.478}, {"Hg", 0.781, 0.779, 0.779},
	};
	for (size_t i = 0; i < sizeof tab / sizeof *tab; i++)
		if (!strcmp(sym, tab[i].m)) {
			f0[0] = tab[i].r;
			f0[1] = tab[i].g;
			f0[2] = tab[i].b;
			return 0;
		}
	return -1;
}
