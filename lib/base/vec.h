/* vec.h — small 3-vector math, float (pm_vec3) and double (pm_dvec3).
 * Header-only; every function is static inline and pure. */
#ifndef PM_VEC_H
#define PM_VEC_H

#include <math.h>

typedef struct { float x, y, z; } pm_vec3;
typedef struct { double x, y, z; } pm_dvec3;

#define PM_PI 3.14159265358979323846

static inline pm_vec3 pm_v3(float x, float y, float z) { pm_vec3 v = {x, y, z}; return v; }
static inline pm_vec3 pm_add(pm_vec3 a, pm_vec3 b) { return pm_v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline pm_vec3 pm_sub(pm_vec3 a, pm_vec3 b) { return pm_v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline pm_vec3 pm_mul(pm_vec3 a, pm_vec3 b) { return pm_v3(a.x * b.x, a.y * b.y, a.z * b.z); }
static inline pm_vec3 pm_scale(pm_vec3 a, float s) { return pm_v3(a.x * s, a.y * s, a.z * s); }
static inline pm_vec3 pm_neg(pm_vec3 a) { return pm_v3(-a.x, -a.y, -a.z); }
static inline float pm_dot(pm_vec3 a, pm_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline pm_vec3 pm_cross(pm_vec3 a, pm_vec3 b)
{
	return pm_v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline float pm_len(pm_vec3 a) { return sqrtf(pm_dot(a, a)); }
static inline pm_vec3 pm_norm(pm_vec3 a)
{
	float l = pm_len(a);
	return l > 0 ? pm_scale(a, 1.0f / l) : a;
}
static inline float pm_maxc(pm_vec3 a) { return fmaxf(a.x, fmaxf(a.y, a.z)); }
static inline float pm_lum(pm_vec3 a) { return (a.x + a.y + a.z) / 3.0f; }
static inline float pm_vget(pm_vec3 a, int i) { return i == 0 ? a.x : i == 1 ? a.y : a.z; }
static inline int pm_vfinite(pm_vec3 a) { return isfinite(a.x) && isfinite(a.y) && isfinite(a.z); }

/* An orthonormal basis (t, b, n) around unit n (Duff et al. 2017, "Building an
 * Orthonormal Basis, Revisited"): continuous except at the sign flip. */
static inline void pm_basis(pm_vec3 n, pm_vec3 *t, pm_vec3 *b)
{
	float s = copysignf(1.0f, n.z);
	float a = -1.0f / (s + n.z);
	float c = n.x * n.y * a;
	*t = pm_v3(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
	*b = pm_v3(c, s + n.y * n.y * a, -n.y);
}

static inline pm_dvec3 pm_dv3(double x, double y, double z) { pm_dvec3 v = {x, y, z}; return v; }
static inline pm_dvec3 pm_dfromf(pm_vec3 a) { return pm_dv3(a.x, a.y, a.z); }
static inline pm_dvec3 pm_dadd(pm_dvec3 a, pm_dvec3 b) { return pm_dv3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline pm_dvec3 pm_dsub(pm_dvec3 a, pm_dvec3 b) { return pm_dv3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline pm_dvec3 pm_dscale(pm_dvec3 a, double s) { return pm_dv3(a.x * s, a.y * s, a.z * s); }
static inline double pm_ddot(pm_dvec3 a, pm_dvec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline pm_dvec3 pm_dcross(pm_dvec3 a, pm_dvec3 b)
{
	return pm_dv3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double pm_dlen(pm_dvec3 a) { return sqrt(pm_ddot(a, a)); }

#endif
