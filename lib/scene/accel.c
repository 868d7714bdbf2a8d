/* accel.c — Embree 3 ray casting (see accel.h). */
#include "scene/accel.h"

#include <embree3/rtcore.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

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

int
pm_accel_hit(const pm_accel *a, pm_vec3 o, pm_vec3 d, float tmin, float tmax, pm_hit *h)
{
	struct RTCIntersectContext ctx;
	struct RTCRayHit rh;

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

static pm_vec3
clamp01(pm_vec3 a)
{
	return pm_v3(fminf(fmaxf(a.x, 0.0f), 1.0f), fminf(fmaxf(a.y, 0.0f), 1.0f), fminf(fmaxf(a.z, 0.0f), 1.0f));
}

const pm_material *
pm_hit_material(const pm_scene *s, const pm_hit *h, pm_material *tmp)
{
	const pm_material *m = &s->mats[s->objs[h->obj].material];
	float u = 0, v = 0;

	if (!(m->tkd | m->tks | m->texp))
		return m;
	if (s->vuv && s->objs[h->obj].has_uv) {
		const uint32_t *t = s->tris[h->tri];
		float w0 = 1.0f - h->u - h->v;
		u = w0 * s->vuv[t[0]][0] + h->u * s->vuv[t[1]][0] + h->v * s->vuv[t[2]][0];
		v = w0 * s->vuv[t[0]][1] + h->u * s->vuv[t[1]][1] + h->v * s->vuv[t[2]][1];
	}
	*tmp = *m;
	if (m->tkd)
		tmp->kd = clamp01(pm_texture_at(&s->texs[m->tkd - 1], u, v));
	if (m->tks)
		tmp->ks = clamp01(pm_texture_at(&s->texs[m->tks - 1], u, v));
	if (m->texp)
		tmp->exponent = fmaxf(pm_lum(pm_texture_at(&s->texs[m->texp - 1], u, v)), 1e-3f);
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
