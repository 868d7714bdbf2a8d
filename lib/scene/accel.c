/* accel.c — Embree 3 ray casting (see accel.h). */
#include "scene/accel.h"

#include <embree3/rtcore.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/texfilter.h"

struct pm_accel {
	RTCDevice dev;
	RTCScene scn;
	const pm_scene *s;
	float eps_abs;      /* offset floor from the scene size (its bbox diagonal) */
};

static const char *
rtc_errstr(enum RTCError e)
{
	switch (e) {
	case RTC_ERROR_NONE: return "no error";
	case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
	case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
	case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
	case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported cpu";
	case RTC_ERROR_CANCELLED: return "cancelled";
	default: return "unknown error";
	}
}

int
pm_accel_build(pm_accel **out, const pm_scene *s, const pm_vec3 *verts, pm_error *err)
{
	pm_accel *a;
	RTCGeometry g;
	float *vb;
	unsigned *ib;
	pm_vec3 lo = pm_v3(FLT_MAX, FLT_MAX, FLT_MAX), hi = pm_neg(lo);

	*out = NULL;
	a = calloc(1, sizeof *a);
	if (!a)
		return pm_seterr(err, "out of memory");
	a->s = s;
	/* One build thread: Embree's BVH then cannot depend on scheduling,
	 * and neither can which of two equally near triangles a ray reports. */
	a->dev = rtcNewDevice("threads=1,verbose=0");
	if (!a->dev) {
		free(a);
		return pm_seterr(err, "cannot start embree: %s", rtc_errstr(rtcGetDeviceError(NULL)));
	}
	a->scn = rtcNewScene(a->dev);
	rtcSetSceneFlags(a->scn, RTC_SCENE_FLAG_ROBUST);
	rtcSetSceneBuildQuality(a->scn, RTC_BUILD_QUALITY_HIGH);
	if (s->ntris > 0) {
		g = rtcNewGeometry(a->dev, RTC_GEOMETRY_TYPE_TRIANGLE);
		vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
		                             3 * sizeof(float), s->nverts);
		ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
		                             3 * sizeof(unsigned), s->ntris);
		if (!vb || !ib) {
			rtcReleaseGeometry(g);
			pm_accel_free(a);
			return pm_seterr(err, "embree: cannot allocate %u triangles", s->ntris);
		}
		for (uint32_t i = 0; i < s->nverts; i++) {
			vb[3 * i] = verts[i].x;
			vb[3 * i + 1] = verts[i].y;
			vb[3 * i + 2] = verts[i].z;
			lo = pm_v3(fminf(lo.x, verts[i].x), fminf(lo.y, verts[i].y), fminf(lo.z, verts[i].z));
			hi = pm_v3(fmaxf(hi.x, verts[i].x), fmaxf(hi.y, verts[i].y), fmaxf(hi.z, verts[i].z));
		}
		memcpy(ib, s->tris, (size_t)s->ntris * 3 * sizeof(unsigned));
		rtcCommitGeometry(g);
		rtcAttachGeometry(a->scn, g);
		rtcReleaseGeometry(g);
	} else {
		lo = hi = pm_v3(0, 0, 0);
	}
	rtcCommitScene(a->scn);
	if (rtcGetDeviceError(a->dev) != RTC_ERROR_NONE) {
		enum RTCError e = rtcGetDeviceError(a->dev);
		pm_accel_free(a);
		return pm_seterr(err, "embree: %s", rtc_errstr(e));
	}
	a->eps_abs = 1e-5f * pm_len(pm_sub(hi, lo));
	*out = a;
	return 0;
}

void
pm_accel_free(pm_accel *a)
{
	if (!a)
		return;
	if (a->scn)
		rtcReleaseScene(a->scn);
	if (a->dev)
		rtcReleaseDevice(a->dev);
	free(a);
}

static void
setray(struct RTCRay *r, pm_vec3 o, pm_vec3 d, float tmin, float tmax)
{
	r->org_x = o.x; r->org_y = o.y; r->org_z = o.z;
	r->dir_x = d.x; r->dir_y = d.y; r->dir_z = d.z;
	r->tnear = tmin;
	r->tfar = tmax;
	r->time = 0;
	r->mask = (unsigned)-1;
	r->id = 0;
	r->flags = 0;
}

/* Embree asserts, and so aborts, on a ray it cannot trace: an origin or
 * direction beyond 1.844e18 or not a number, or a NaN bound. A scene in
 * range (scene_limits.h) makes none; should a degenerate sample still give
 * a NaN, it costs that ray, not the run. */
static int
traceable(pm_vec3 o, pm_vec3 d, float tmin, float tmax)
{
	const float big = 1.8e18f;
	return fabsf(o.x) <= big && fabsf(o.y) <= big && fabsf(o.z) <= big
		&& fabsf(d.x) <= big && fabsf(d.y) <= big && fabsf(d.z) <= big
		&& !isnan(tmin) && !isnan(tmax);
}

int
pm_accel_hit(const pm_accel *a, pm_vec3 o, pm_vec3 d, float tmin, float tmax, pm_hit *h)
{
	struct RTCIntersectContext ctx;
	struct RTCRayHit rh;

	if (!traceable(o, d, tmin, tmax))
		return 0;
	rtcInitIntersectContext(&ctx);
	setray(&rh.ray, o, d, tmin, tmax);
	rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
	rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
	rtcIntersect1(a->scn, &ctx, &rh);
	if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
		return 0;
	h->t = rh.ray.tfar;
	h->p = pm_add(o, pm_scale(d, h->t));
	h->tri = rh.hit.primID;
	h->poly = a->s->tri_poly[h->tri];
	h->ng = a->s->poly_normal[h->poly];
	h->obj = (int)a->s->poly_obj[h->poly];
	h->u = rh.hit.u;
	h->v = rh.hit.v;
	return 1;
}

int
pm_accel_occluded(const pm_accel *a, pm_vec3 o, pm_vec3 d, float tmin, float tmax)
{
	struct RTCIntersectContext ctx;
	struct RTCRay r;

	if (!traceable(o, d, tmin, tmax))
		return 1;
	rtcInitIntersectContext(&ctx);
	setray(&r, o, d, tmin, tmax);
	rtcOccluded1(a->scn, &ctx, &r);
	return r.tfar < 0;
}

float
pm_accel_eps(const pm_accel *a, pm_vec3 p)
{
	/* A few float spacings of the largest coordinate, so that far from
	 * the origin the nudge still clears the rounding of the hit point. */
	float m = fmaxf(fabsf(p.x), fmaxf(fabsf(p.y), fabsf(p.z)));
	return a->eps_abs + 8.0f * FLT_EPSILON * m;
}

pm_vec3
pm_accel_offset(const pm_accel *a, pm_vec3 p, pm_vec3 ng, pm_vec3 d)
{
	float eps = pm_accel_eps(a, p);
	return pm_add(p, pm_scale(ng, pm_dot(ng, d) >= 0 ? eps : -eps));
}

pm_vec3
pm_hit_shading(const pm_scene *s, const pm_hit *h)
{
	const uint32_t *t;
	pm_vec3 n;

	if (!s->vnormal || !s->objs[h->obj].smooth)
		return h->ng;
	t = s->tris[h->tri];
	n = pm_add(pm_add(pm_scale(s->vnormal[t[0]], 1.0f - h->u - h->v), pm_scale(s->vnormal[t[1]], h->u)),
	           pm_scale(s->vnormal[t[2]], h->v));
	float l = pm_len(n);
	if (!(l > 0) || !(pm_dot(n, h->ng) > 0))
		return h->ng;
	return pm_scale(n, 1.0f / l);
}

static const float *
texel(const pm_texture *t, int x, int y)
{
	x %= t->w;
	y %= t->h;
	x += x < 0 ? t->w : 0;
	y += y < 0 ? t->h : 0;
	return t->px + 3 * ((size_t)y * t->w + x);
}

pm_vec3
pm_texture_at(const pm_texture *t, float u, float v)
{
	u = u * t->su + t->ou;
	v = v * t->sv + t->ov;
	if (!(fabsf(u) < 1e7f && fabsf(v) < 1e7f))
		u = v = 0;
	if (t->kind == PM_TEX_CHECKER)
		return ((long)floorf(u) + (long)floorf(v)) % 2 == 0 ? t->c1 : t->c2;
	/* Texel centres at half-integers: (x + 0.5) / w. */
	float fx = u * (float)t->w - 0.5f, fy = (1.0f - v) * (float)t->h - 0.5f;
	float x0 = floorf(fx), y0 = floorf(fy), ax = fx - x0, ay = fy - y0;
	int ix = (int)fmodf(x0, (float)t->w), iy = (int)fmodf(y0, (float)t->h);
	const float *a = texel(t, ix, iy), *b = texel(t, ix + 1, iy);
	const float *c = texel(t, ix, iy + 1), *d = texel(t, ix + 1, iy + 1);
	float r[3];
	for (int k = 0; k < 3; k++)
		r[k] = (1 - ay) * ((1 - ax) * a[k] + ax * b[k]) + ay * ((1 - ax) * c[k] + ax * d[k]);
	return pm_v3(r[0], r[1], r[2]);
}

/* The integral of [floor(x) is odd] from 0 to x. */
static double
odd_integral(double x)
{
	double f = floor(x / 2);
	return f + fmax(x - 2 * f - 1, 0.0);
}

/* The share of [x - r, x + r] on which floor is odd. */
static double
odd_share(double x, double r)
{
	if (!(r > 1e-6))
		return fmod(fabs(floor(x)), 2.0);
	return (odd_integral(x + r) - odd_integral(x - r)) / (2 * r);
}

pm_vec3
pm_texture_filtered(const pm_texture *t, float u, float v, float du1, float dv1, float du2,
                    float dv2)
{
	float wu = (fabsf(du1) + fabsf(du2)) * fabsf(t->su), wv = (fabsf(dv1) + fabsf(dv2)) * fabsf(t->sv);
	float us = u * t->su + t->ou, vs = v * t->sv + t->ov;

	if (!(wu < 1e6f && wv < 1e6f) || !(fabsf(us) < 1e7f && fabsf(vs) < 1e7f))
		return pm_texture_at(t, u, v);
	if (t->kind == PM_TEX_CHECKER) {
		if (!(wu > 0 || wv > 0))
			return pm_texture_at(t, u, v);
		/* The footprint's bounding box, half-widths half its extent:
		 * floor(u) and floor(v) are independent across it, and the
		 * squares of c2 are where exactly one of them is odd. */
		double pu = odd_share(us, 0.5 * wu), pv = odd_share(vs, 0.5 * wv);
		float q = (float)(pu * (1 - pv) + pv * (1 - pu));
		return pm_add(pm_scale(t->c1, 1 - q), pm_scale(t->c2, q));
	}
	if (!t->filt || !(fmaxf(wu * (float)t->w, wv * (float)t->h) > 1))
		return pm_texture_at(t, u, v);
	float rgb[3];
	if (pm_texfilter_lookup(t->filt, us, 1.0f - vs, du1 * t->su, -dv1 * t->sv, du2 * t->su,
	                        -dv2 * t->sv, rgb) != 0)
		return pm_texture_at(t, u, v);
	return pm_v3(rgb[0], rgb[1], rgb[2]);
}

void
pm_pixel_footprint(const pm_hit *h, pm_vec3 d, float pixel_angle, pm_vec3 *a1, pm_vec3 *a2)
{
	float w = h->t * pixel_angle, c = pm_dot(d, h->ng);
	pm_vec3 e1 = pm_sub(h->ng, pm_scale(d, c)), e2;

	if (!(w > 0) || !(pm_len(e1) > 1e-6f)) {
		/* Head on (or no width): a square of side w in the facet. */
		pm_vec3 x = fabsf(h->ng.x) < 0.9f ? pm_v3(1, 0, 0) : pm_v3(0, 1, 0);
		e1 = pm_norm(pm_cross(h->ng, x));
		*a1 = pm_scale(e1, w > 0 ? w : 0);
		*a2 = pm_scale(pm_cross(h->ng, e1), w > 0 ? w : 0);
		return;
	}
	/* e1: across the pixel toward the facet's tilt, slanted onto the
	 * facet along d; e2: across it the other way, in the facet already. */
	e1 = pm_norm(e1);
	e2 = pm_norm(pm_cross(d, e1));
	c = fabsf(c) > 0.02f ? c : c < 0 ? -0.02f : 0.02f;
	*a1 = pm_scale(pm_sub(e1, pm_scale(d, pm_dot(e1, h->ng) / c)), w);
	*a2 = pm_scale(e2, w);
}

static pm_vec3
clamp01(pm_vec3 a)
{
	return pm_v3(fminf(fmaxf(a.x, 0.0f), 1.0f), fminf(fmaxf(a.y, 0.0f), 1.0f), fminf(fmaxf(a.z, 0.0f), 1.0f));
}

/* How (u, v) changes along the world-space vectors a1 and a2 on h's
 * triangle: its uv's gradients in the triangle's plane, dotted with them. */
static void
uv_along(const pm_scene *s, const pm_hit *h, pm_vec3 a1, pm_vec3 a2, float duv[4])
{
	const uint32_t *t = s->tris[h->tri];
	pm_vec3 e1 = pm_sub(s->verts[t[1]], s->verts[t[0]]), e2 = pm_sub(s->verts[t[2]], s->verts[t[0]]);
	double a = pm_dot(e1, e1), b = pm_dot(e1, e2), c = pm_dot(e2, e2), det = a * c - b * b;
	double p1 = pm_dot(e1, a1), q1 = pm_dot(e2, a1), p2 = pm_dot(e1, a2), q2 = pm_dot(e2, a2);

	for (int k = 0; k < 2; k++) {
		double d1 = s->vuv[t[1]][k] - s->vuv[t[0]][k], d2 = s->vuv[t[2]][k] - s->vuv[t[0]][k];
		double al = (c * d1 - b * d2) / det, be = (a * d2 - b * d1) / det;
		duv[k] = (float)(al * p1 + be * q1);
		duv[2 + k] = (float)(al * p2 + be * q2);
	}
	for (int k = 0; k < 4; k++)
		if (!(fabsf(duv[k]) < 1e30f))
			duv[0] = duv[1] = duv[2] = duv[3] = 0;
}

static pm_vec3
lookup(const pm_texture *t, float u, float v, const float *duv)
{
	return duv ? pm_texture_filtered(t, u, v, duv[0], duv[1], duv[2], duv[3])
	           : pm_texture_at(t, u, v);
}

const pm_material *
pm_hit_material(const pm_scene *s, const pm_hit *h, pm_material *tmp)
{
	return pm_hit_material_fp(s, h, pm_v3(0, 0, 0), pm_v3(0, 0, 0), tmp);
}

const pm_material *
pm_hit_material_fp(const pm_scene *s, const pm_hit *h, pm_vec3 a1, pm_vec3 a2, pm_material *tmp)
{
	const pm_material *m = &s->mats[s->objs[h->obj].material];
	float u = 0, v = 0, duv[4];
	const float *fp = NULL;

	if (!(m->tkd | m->tks | m->texp))
		return m;
	if (s->vuv && s->objs[h->obj].has_uv) {
		const uint32_t *t = s->tris[h->tri];
		float w0 = 1.0f - h->u - h->v;
		u = w0 * s->vuv[t[0]][0] + h->u * s->vuv[t[1]][0] + h->v * s->vuv[t[2]][0];
		v = w0 * s->vuv[t[0]][1] + h->u * s->vuv[t[1]][1] + h->v * s->vuv[t[2]][1];
		if (pm_len(a1) > 0 || pm_len(a2) > 0) {
			uv_along(s, h, a1, a2, duv);
			fp = duv;
		}
	}
	*tmp = *m;
	if (m->tkd)
		tmp->kd = clamp01(lookup(&s->texs[m->tkd - 1], u, v, fp));
	if (m->tks)
		tmp->ks = clamp01(lookup(&s->texs[m->tks - 1], u, v, fp));
	if (m->texp)
		tmp->exponent = fmaxf(pm_lum(lookup(&s->texs[m->texp - 1], u, v, fp)), 1e-3f);
	if (m->kind == PM_MAT_GLOSSY) {
		float sc[3] = {tmp->kd.x + tmp->ks.x, tmp->kd.y + tmp->ks.y, tmp->kd.z + tmp->ks.z};
		float f[3];
		for (int k = 0; k < 3; k++)
			f[k] = sc[k] > 1 ? 1 / sc[k] : 1;
		tmp->kd = pm_mul(tmp->kd, pm_v3(f[0], f[1], f[2]));
		tmp->ks = pm_mul(tmp->ks, pm_v3(f[0], f[1], f[2]));
	}
	return tmp;
}
