/* light.c — emitters and their sampling (see light.h). */
#include "optics/light.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "optics/bsdf.h"

/* The spot's factor at cos theta from its axis (formats/scene.md). */
static float
spot_factor(const pm_light *l, float c)
{
	if (c < l->cos_outer)
		return 0;
	if (c >= l->cos_inner)
		return 1;
	if (l->falloff == PM_FALLOFF_LINEAR) {
		float th = acosf(fminf(c, 1.0f));
		return l->outer > l->inner ? fmaxf(0.0f, (l->outer - th) / (l->outer - l->inner)) : 0.0f;
	}
	float t = (c - l->cos_outer) / (l->cos_inner - l->cos_outer);
	return t * t * (3 - 2 * t);
}

/* 2 pi times the integral of the factor times sin theta over the cone. */
static double
spot_solid_angle(const pm_light *l)
{
	double ci = cos(l->inner), co = cos(l->outer), sum = 0;
	const int n = 4096;

	if (l->falloff == PM_FALLOFF_SMOOTH)    /* smoothstep in cos averages 1/2 */
		return 2 * PM_PI * ((1 - ci) + (ci - co) / 2);
	/* linear in the angle: the midpoint rule over [inner, outer] */
	for (int i = 0; i < n; i++) {
		double th = l->inner + (l->outer - l->inner) * (i + 0.5) / n;
		sum += (l->outer - th) / (l->outer - l->inner) * sin(th);
	}
	return 2 * PM_PI * ((1 - ci) + sum * (l->outer - l->inner) / n);
}

/* An orthonormal u, v with u x v = w (w unit). */
static void
basis(pm_vec3 w, pm_vec3 *u, pm_vec3 *v)
{
	pm_vec3 a = fabsf(w.x) > 0.5f ? pm_v3(0, 1, 0) : pm_v3(1, 0, 0);
	*u = pm_norm(pm_cross(a, w));
	*v = pm_cross(w, *u);
}

/* The map's direction of (phi, cos theta), turned into the world. */
static pm_vec3
env_dir(const pm_pointlight *e, float phi, float ct)
{
	float st = sqrtf(fmaxf(0.0f, 1 - ct * ct));
	float m[3] = {sinf(phi) * st, ct, -cosf(phi) * st};
	pm_vec3 d;
	d.x = e->rot[0][0] * m[0] + e->rot[0][1] * m[1] + e->rot[0][2] * m[2];
	d.y = e->rot[1][0] * m[0] + e->rot[1][1] * m[1] + e->rot[1][2] * m[2];
	d.z = e->rot[2][0] * m[0] + e->rot[2][1] * m[1] + e->rot[2][2] * m[2];
	return d;
}

/* Solid angle of a texel in row j of an h-row map w wide. */
static double
texel_solid_angle(int j, int w, int h)
{
	return 2 * PM_PI / w * (cos(PM_PI * j / h) - cos(PM_PI * (j + 1) / h));
}

static float
texel_mean(const float *t)
{
	return (t[0] + t[1] + t[2]) / 3.0f;
}

/* The sampling tables of an environment image (light.h), and its power. */
static int
env_tables(pm_lights *L, const pm_pointlight *e, pm_vec3 *power)
{
	int w = e->env_w, h = e->env_h;
	double tot = 0, rgb[3] = {0, 0, 0};

	L->env_marg = calloc((size_t)h + 1, sizeof *L->env_marg);
	L->env_cond = calloc((size_t)h * (w + 1), sizeof *L->env_cond);
	if (!L->env_marg || !L->env_cond)
		return -1;
	for (int j = 0; j < h; j++) {
		double *c = L->env_cond + (size_t)j * (w + 1), om = texel_solid_angle(j, w, h), row = 0;
		for (int i = 0; i < w; i++) {
			const float *t = e->env + 3 * ((size_t)j * w + i);
			row += texel_mean(t);
			c[i + 1] = row;
			for (int k = 0; k < 3; k++)
				rgb[k] += t[k] * om;
		}
		for (int i = 1; i <= w; i++)
			c[i] = row > 0 ? c[i] / row : (double)i / w;
		tot += row * om;
		L->env_marg[j + 1] = tot;
	}
	for (int j = 1; j <= h; j++)
		L->env_marg[j] = tot > 0 ? L->env_marg[j] / tot : (double)j / h;
	L->env_int = tot;
	*power = pm_v3((float)rgb[0], (float)rgb[1], (float)rgb[2]);
	return 0;
}

/* The scene's bounding sphere at this time: the box of its vertices'
 * centre, and the farthest vertex (a little more, so that the disk of
 * distant photons covers every surface). */
static void
bounds(pm_lights *L, const pm_scene *s, const pm_vec3 *verts)
{
	pm_vec3 lo = pm_v3(FLT_MAX, FLT_MAX, FLT_MAX), hi = pm_scale(lo, -1);
	float r2 = 0;

	if (s->nverts == 0) {
		L->center = pm_v3(0, 0, 0);
		L->radius = 1;
		return;
	}
	for (uint32_t i = 0; i < s->nverts; i++) {
		lo = pm_v3(fminf(lo.x, verts[i].x), fminf(lo.y, verts[i].y), fminf(lo.z, verts[i].z));
		hi = pm_v3(fmaxf(hi.x, verts[i].x), fmaxf(hi.y, verts[i].y), fmaxf(hi.z, verts[i].z));
	}
	L->center = pm_scale(pm_add(lo, hi), 0.5f);
	for (uint32_t i = 0; i < s->nverts; i++) {
		pm_vec3 v = pm_sub(verts[i], L->center);
		r2 = fmaxf(r2, pm_dot(v, v));
	}
	L->radius = sqrtf(r2) * 1.001f + 1e-6f * pm_maxc(pm_v3(fabsf(L->center.x), fabsf(L->center.y),
	                                                        fabsf(L->center.z)));
	if (!(L->radius > 0))
		L->radius = 1;
}

/* One light that is not a surface, from its scene description. */
static int
light_from(pm_lights *L, pm_light *l, const pm_scene *s, int i, float t)
{
	const pm_pointlight *d = &s->lights[i];
	double area = PM_PI * (double)L->radius * L->radius;

	l->tri = -1;
	l->le = d->power;
	l->dir = d->dir;
	switch (d->kind) {
	case PM_LIGHT_POINT:
		l->kind = PM_EMIT_POINT;
		l->p0 = pm_scene_light_at(s, i, t);
		l->power = d->power;
		break;
	case PM_LIGHT_SPOT:
		l->kind = PM_EMIT_SPOT;
		l->p0 = pm_scene_light_at(s, i, t);
		l->outer = d->outer * (float)(PM_PI / 180);
		l->inner = d->inner * (float)(PM_PI / 180);
		l->cos_outer = cosf(l->outer);
		l->cos_inner = cosf(l->inner);
		l->falloff = d->falloff;
		l->power = pm_scale(d->power, (float)spot_solid_angle(l));
		break;
	case PM_LIGHT_DISTANT:
		l->kind = PM_EMIT_DISTANT;
		l->power = pm_scale(d->power, (float)area);
		break;
	case PM_LIGHT_ENV:
		l->kind = PM_EMIT_ENV;
		L->env = (int)(l - L->l);
		L->envsrc = d;
		if (d->env) {
			if (env_tables(L, d, &l->power))
				return -1;
			l->power = pm_scale(l->power, (float)area);
		} else {
			l->power = pm_scale(d->power, (float)(4 * PM_PI * area));
		}
		break;
	}
	return 0;
}

int
pm_lights_build(pm_lights *L, const pm_scene *s, const pm_vec3 *verts, float t, pm_error *err)
{
	int n = s->nlights, k = 0;
	double acc = 0;

	L->l = NULL;
	L->cdf = NULL;
	L->tri_light = NULL;
	L->env_marg = L->env_cond = NULL;
	L->env = -1;
	L->envsrc = NULL;
	L->n = L->ntri = 0;
	L->total = pm_v3(0, 0, 0);
	bounds(L, s, verts);
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
	for (int i = 0; i < s->nlights; i++, k++)
		if (light_from(L, &L->l[k], s, i, t)) {
			pm_lights_free(L);
			return pm_seterr(err, "out of memory");
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
		l->kind = PM_EMIT_TRI;
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
	free(L->env_marg);
	free(L->env_cond);
	L->env_marg = L->env_cond = NULL;
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

/* The bin of a table of n bins (cdf: n + 1 entries from 0 to 1) that holds
 * u, never one of zero width; *rest is u's place within it, in [0, 1). */
static int
table_pick(const double *cdf, int n, float u, float *rest)
{
	int lo = 0, hi = n - 1;

	while (lo < hi) {
		int mid = (lo + hi) / 2;
		if (cdf[mid + 1] > u)
			hi = mid;
		else
			lo = mid + 1;
	}
	double w = cdf[lo + 1] - cdf[lo];
	*rest = w > 0 ? fminf((float)((u - cdf[lo]) / w), 0x1.fffffep-1f) : 0.0f;
	return lo;
}

/* A direction toward the sky from (u1, u2), in proportion to the image's
 * texels (uniform within a texel's solid angle, so the density is each
 * texel's share over its solid angle) or uniform for a constant sky: its
 * radiance in *le, its solid-angle density in *pdf (light not yet picked). */
static pm_vec3
env_sample(const pm_lights *L, float u1, float u2, pm_vec3 *le, float *pdf)
{
	const pm_pointlight *e = L->envsrc;
	int w = e->env_w, h = e->env_h, i, j;
	float ru, rv;

	if (!e->env) {
		*le = e->power;
		*pdf = (float)(1 / (4 * PM_PI));
		return pm_sample_sphere(u1, u2);
	}
	j = table_pick(L->env_marg, h, u2, &rv);
	const double *c = L->env_cond + (size_t)j * (w + 1);
	i = table_pick(c, w, u1, &ru);
	float c0 = cosf((float)PM_PI * (float)j / (float)h), c1 = cosf((float)PM_PI * (float)(j + 1) / (float)h);
	const float *t = e->env + 3 * ((size_t)j * w + i);
	*le = pm_v3(t[0], t[1], t[2]);
	*pdf = (float)((L->env_marg[j + 1] - L->env_marg[j]) * (c[i + 1] - c[i]) / texel_solid_angle(j, w, h));
	return env_dir(e, 2 * (float)PM_PI * ((float)i + ru) / (float)w, c0 + (c1 - c0) * rv);
}

pm_vec3
pm_lights_env(const pm_lights *L, pm_vec3 d, float *pdf)
{
	const pm_pointlight *e = L->envsrc;
	float pick;

	*pdf = 0;
	if (L->env < 0)
		return pm_v3(0, 0, 0);
	pick = L->cdf[L->env + 1] - L->cdf[L->env];
	if (!e->env) {
		*pdf = pick * (float)(1 / (4 * PM_PI));
		return e->power;
	}
	/* The map's direction: the rotation's transpose undoes it. */
	float lx = e->rot[0][0] * d.x + e->rot[1][0] * d.y + e->rot[2][0] * d.z;
	float ly = e->rot[0][1] * d.x + e->rot[1][1] * d.y + e->rot[2][1] * d.z;
	float lz = e->rot[0][2] * d.x + e->rot[1][2] * d.y + e->rot[2][2] * d.z;
	int w = e->env_w, h = e->env_h;
	float phi = atan2f(lx, -lz);
	if (phi < 0)
		phi += 2 * (float)PM_PI;
	int i = (int)(phi / (2 * (float)PM_PI) * (float)w);
	int j = (int)(acosf(fmaxf(-1.0f, fminf(1.0f, ly))) / (float)PM_PI * (float)h);
	i = i < 0 ? 0 : i >= w ? w - 1 : i;
	j = j < 0 ? 0 : j >= h ? h - 1 : j;
	const double *c = L->env_cond + (size_t)j * (w + 1);
	const float *t = e->env + 3 * ((size_t)j * w + i);
	*pdf = pick * (float)((L->env_marg[j + 1] - L->env_marg[j]) * (c[i + 1] - c[i])
	                      / texel_solid_angle(j, w, h));
	return pm_v3(t[0], t[1], t[2]);
}

/* A point of the disk of radius r about c perpendicular to the unit w. */
static pm_vec3
disk_point(pm_vec3 c, pm_vec3 w, float r, float u1, float u2)
{
	pm_vec3 a, b;
	float rr = r * sqrtf(u1), t = 2 * (float)PM_PI * u2;

	basis(w, &a, &b);
	return pm_add(c, pm_add(pm_scale(a, rr * cosf(t)), pm_scale(b, rr * sinf(t))));
}

/* A direction in the spot's cone, uniform over its solid angle; the power a
 * photon along it carries, before the pick probability. */
static pm_vec3
spot_emit(const pm_light *l, float u1, float u2, pm_vec3 *power)
{
	pm_vec3 a, b;
	float ct = 1 - u1 * (1 - l->cos_outer), st = sqrtf(fmaxf(0.0f, 1 - ct * ct));
	float ph = 2 * (float)PM_PI * u2;
	float omega = 2 * (float)PM_PI * (1 - l->cos_outer);

	basis(l->dir, &a, &b);
	*power = pm_scale(l->le, spot_factor(l, ct) * omega);
	return pm_add(pm_scale(l->dir, ct), pm_add(pm_scale(a, st * cosf(ph)), pm_scale(b, st * sinf(ph))));
}

void
pm_lights_emit_u(const pm_lights *L, const float u[6], pm_vec3 *o, pm_vec3 *d, pm_vec3 *n,
                 pm_vec3 *power)
{
	float pdf;
	const pm_light *l = &L->l[lights_pick(L, u[0], &pdf)];
	float u1 = u[1], u2 = u[2], u3 = u[3], u4 = u[4], r = L->radius, dpdf;
	pm_vec3 le, w;

	*power = pm_scale(l->power, 1.0f / pdf);
	switch (l->kind) {
	case PM_EMIT_POINT:
		*o = l->p0;
		*d = pm_sample_sphere(u1, u2);
		*n = *d;
		return;
	case PM_EMIT_SPOT:
		*o = l->p0;
		*d = spot_emit(l, u3, u4, power);
		*power = pm_scale(*power, 1.0f / pdf);
		*n = *d;
		return;
	case PM_EMIT_DISTANT:
		/* From a disk upstream of the bounding sphere, covering it. */
		*d = l->dir;
		*o = disk_point(pm_sub(L->center, pm_scale(l->dir, r)), l->dir, r, u1, u2);
		*n = *d;
		return;
	case PM_EMIT_ENV:
		w = env_sample(L, u3, u4, &le, &dpdf);
		*d = pm_neg(w);
		*o = disk_point(pm_add(L->center, pm_scale(w, r)), w, r, u1, u2);
		*n = *d;
		*power = dpdf > 0 ? pm_scale(le, (float)PM_PI * r * r / (dpdf * pdf)) : pm_v3(0, 0, 0);
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

	return pm_lights_sample_u(L, x, u0, u1, u2, wi, dist, li, spdf, NULL);
}

int
pm_lights_sample_u(const pm_lights *L, pm_vec3 x, float u0, float u1, float u2, pm_vec3 *wi,
                   float *dist, pm_vec3 *li, float *spdf, float *cosl)
{
	float pdf;
	const pm_light *l = &L->l[lights_pick(L, u0, &pdf)];
	pm_vec3 p, v;
	float d2, d, cl;

	if (cosl)
		*cosl = 0;

	if (l->kind == PM_EMIT_DISTANT || l->kind == PM_EMIT_ENV) {
		float dp = 0;
		pm_vec3 le = l->le;
		*wi = pm_neg(l->dir);
		if (l->kind == PM_EMIT_ENV)
			*wi = env_sample(L, u1, u2, &le, &dp);
		*dist = INFINITY;
		if (l->kind == PM_EMIT_ENV && !(dp > 0))
			return 0;
		*li = pm_scale(le, 1.0f / (pdf * (dp > 0 ? dp : 1.0f)));
		*spdf = pdf * dp;
		return 1;
	}
	p = l->tri < 0 ? l->p0 : tri_point(l, u1, u2);
	v = pm_sub(p, x);
	d2 = pm_dot(v, v);
	if (!(d2 > 0))
		return 0;
	d = sqrtf(d2);
	*wi = pm_scale(v, 1.0f / d);
	*dist = d;
	if (l->kind == PM_EMIT_POINT) {
		*li = pm_scale(l->le, 1.0f / (4.0f * (float)PM_PI * d2 * pdf));
		*spdf = 0;
		return 1;
	}
	if (l->kind == PM_EMIT_SPOT) {
		float f = spot_factor(l, -pm_dot(*wi, l->dir));
		if (!(f > 0))
			return 0;
		*li = pm_scale(l->le, f / (d2 * pdf));
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
	if (cosl)
		*cosl = cl;
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
