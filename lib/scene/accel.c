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
