/* light.c — emitters and their sampling (see light.h). */
#include "optics/light.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "optics/bsdf.h"

int
pm_lights_build(pm_lights *L, const pm_scene *s, const pm_vec3 *verts, float t, pm_error *err)
{
	int n = s->nlights, k = 0;
	double acc = 0;

	L->l = NULL;
	L->cdf = NULL;
	L->tri_light = NULL;
	L->n = L->ntri = 0;
	L->total = pm_v3(0, 0, 0);
	for (uint32_t i = 0; i < s->ntris; i++) {
		const pm_material *m = &s->mats[s->objs[s->poly_obj[s->tri_poly[i]]].material];
		if (pm_maxc(m->emit) > 0)
			n++;
	}
	if (n == 0)
		return pm_seterr(err, "%s: scene has no lights", s->path);
	L->l = calloc((size_t)n, sizeof *L->l);
	L->cdf = calloc((size_t)n + 1, sizeof *L->cdf);
	L->tri_light = malloc((s->ntris ? s->ntris : 1) * sizeof *L->tri_light);
	if (!L->l || !L->cdf || !L->tri_light) {
		pm_lights_free(L);
		return pm_seterr(err, "out of memory");
	}
	for (int i = 0; i < s->nlights; i++, k++) {
		pm_light *l = &L->l[k];
		l->tri = -1;
		l->p0 = pm_scene_light_at(s, i, t);
		l->le = s->lights[i].power;
		l->power = s->lights[i].power;
	}
	for (uint32_t i = 0; i < s->ntris; i++) {
		const pm_material *m = &s->mats[s->objs[s->poly_obj[s->tri_poly[i]]].material];
		pm_light *l;
		pm_vec3 c;
		L->tri_light[i] = -1;
		if (!(pm_maxc(m->emit) > 0))
			continue;
		L->tri_light[i] = k;
		l = &L->l[k++];
		l->tri = (int)i;
		l->p0 = verts[s->tris[i][0]];
		l->e1 = pm_sub(verts[s->tris[i][1]], l->p0);
		l->e2 = pm_sub(verts[s->tris[i][2]], l->p0);
		c = pm_cross(l->e1, l->e2);
		l->area = 0.5f * pm_len(c);
		l->n = s->poly_normal[s->tri_poly[i]];
		l->twosided = m->emit_twosided;
		l->le = m->emit;
		l->power = pm_scale(m->emit, (float)PM_PI * l->area * (l->twosided ? 2.0f : 1.0f));
	}
	L->n = k;
	L->ntri = k - s->nlights;
	for (int i = 0; i < k; i++) {
		L->total = pm_add(L->total, L->l[i].power);
		acc += pm_lum(L->l[i].power);
		L->cdf[i + 1] = (float)acc;
	}
	if (!(acc > 0)) {
		pm_lights_free(L);
		return pm_seterr(err, "%s: the lights emit no power", s->path);
	}
	for (int i = 1; i <= k; i++)
		L->cdf[i] = (float)(L->cdf[i] / acc);
	L->cdf[k] = 1.0f;
	return 0;
}

void
pm_lights_free(pm_lights *L)
{
	free(L->l);
	free(L->cdf);
	free(L->tri_light);
	L->l = NULL;
	L->cdf = NULL;
	L->tri_light = NULL;
	L->n = L->ntri = 0;
}

/* Picks a light in proportion to power; *pdf is its probability. */
static int
lights_pick(const pm_lights *L, float u, float *pdf)
{
	int lo = 0, hi = L->n - 1;

	while (lo < hi) {
		int mid = (lo + hi) / 2;
		if (L->cdf[mid + 1] > u)
			hi = mid;
		else
			lo = mid + 1;
	}
	*pdf = L->cdf[lo + 1] - L->cdf[lo];
	return lo;
}

static pm_vec3
tri_point(const pm_light *l, float u1, float u2)
{
	float su = sqrtf(u1);

	return pm_add(l->p0, pm_add(pm_scale(l->e1, su * (1.0f - u2)), pm_scale(l->e2, su * u2)));
}

void
pm_lights_emit(const pm_lights *L, pm_rng *r, pm_vec3 *o, pm_vec3 *d, pm_vec3 *n, pm_vec3 *power)
{
	float u[6], pdf;

	/* The side is drawn only for two-sided lights, as it always was, so
	 * that the pseudo-random photons stay what they were. */
	for (int i = 0; i < 5; i++)
		u[i] = pm_rng_f(r);
	u[5] = L->l[lights_pick(L, u[0], &pdf)].twosided ? pm_rng_f(r) : 0;
	pm_lights_emit_u(L, u, o, d, n, power);
}

void
pm_lights_emit_u(const pm_lights *L, const float u[6], pm_vec3 *o, pm_vec3 *d, pm_vec3 *n,
                 pm_vec3 *power)
{
	float pdf;
	const pm_light *l = &L->l[lights_pick(L, u[0], &pdf)];
	float u1 = u[1], u2 = u[2], u3 = u[3], u4 = u[4];

	*power = pm_scale(l->power, 1.0f / pdf);
	if (l->tri < 0) {
		*o = l->p0;
		*d = pm_sample_sphere(u1, u2);
		*n = *d;
		return;
	}
	/* Uniform point, cosine-weighted direction about the emitting side:
	 * the flux leaving a Lambertian emitter (pi Le A in all). */
	*o = tri_point(l, u1, u2);
	*n = l->n;
	if (l->twosided && u[5] < 0.5f)
		*n = pm_neg(l->n);
	*d = pm_sample_cosine(*n, u3, u4);
}

int
pm_lights_sample(const pm_lights *L, pm_vec3 x, pm_rng *r, pm_vec3 *wi, float *dist,
                 pm_vec3 *li, float *spdf)
{
	float u0 = pm_rng_f(r), u1 = pm_rng_f(r), u2 = pm_rng_f(r);

	return pm_lights_sample_u(L, x, u0, u1, u2, wi, dist, li, spdf);
}

int
pm_lights_sample_u(const pm_lights *L, pm_vec3 x, float u0, float u1, float u2, pm_vec3 *wi,
                   float *dist, pm_vec3 *li, float *spdf)
{
	float pdf;
	const pm_light *l = &L->l[lights_pick(L, u0, &pdf)];
	pm_vec3 p, v;
	float d2, d, cl;

	p = l->tri < 0 ? l->p0 : tri_point(l, u1, u2);
	v = pm_sub(p, x);
	d2 = pm_dot(v, v);
	if (!(d2 > 0))
		return 0;
	d = sqrtf(d2);
	*wi = pm_scale(v, 1.0f / d);
	*dist = d;
	if (l->tri < 0) {
		*li = pm_scale(l->le, 1.0f / (4.0f * (float)PM_PI * d2 * pdf));
		*spdf = 0;
		return 1;
	}
	cl = -pm_dot(*wi, l->n);
	if (cl < 0 && l->twosided)
		cl = -cl;
	if (!(cl > 0))
		return 0;
	*li = pm_scale(l->le, cl * l->area / (d2 * pdf));
	*spdf = pdf * d2 / (cl * l->area);
	return 1;
}

float
pm_lights_pdf(const pm_lights *L, uint32_t tri, pm_vec3 x, pm_vec3 p)
{
	int i = L->tri_light[tri];
	const pm_light *l;
	pm_vec3 v;
	float d2, cl;

	if (i < 0)
		return 0;
	l = &L->l[i];
	v = pm_sub(p, x);
	d2 = pm_dot(v, v);
	cl = -pm_dot(v, l->n) / sqrtf(d2);
	if (cl < 0 && l->twosided)
		cl = -cl;
	if (!(cl > 0) || !(l->area > 0))
		return 0;
	return (L->cdf[i + 1] - L->cdf[i]) * d2 / (cl * l->area);
}

int
pm_lights_first(const pm_lights *L, pm_vec3 o, pm_vec3 d, float *t, int *light)
{
	int best = -1;
	float tb = FLT_MAX;

	if (L->ntri > PM_LIGHTS_SCAN)
		return -1;
	/* Moller & Trumbore (1997), both sides. */
	for (int i = 0; i < L->n; i++) {
		const pm_light *l = &L->l[i];
		if (l->tri < 0)
			continue;
		pm_vec3 p = pm_cross(d, l->e2);
		float det = pm_dot(l->e1, p);
		if (det == 0.0f)
			continue;
		float inv = 1.0f / det;
		pm_vec3 s = pm_sub(o, l->p0);
		float u = pm_dot(s, p) * inv;
		if (u < 0.0f || u > 1.0f)
			continue;
		pm_vec3 q = pm_cross(s, l->e1);
		float v = pm_dot(d, q) * inv;
		if (v < 0.0f || u + v > 1.0f)
			continue;
		float tt = pm_dot(l->e2, q) * inv;
		if (tt > 0.0f && tt < tb) {
			tb = tt;
			best = i;
		}
	}
	if (best < 0)
		return 0;
	*t = tb;
	*light = best;
	return 1;
}
