/* photon.c — the 20-byte photon record (shared-exponent power, octahedral
 * direction). The byte layout is specified in formats/photons.md ("The
 * record"); keep the two in step. The file around the records is
 * photonfile.c. */
#include "formats/photon.h"

#include <float.h>
#include <math.h>
#include <string.h>

_Static_assert(sizeof(pm_photon) == PM_PHOTON_BYTES, "pm_photon must be 20 bytes");
_Static_assert(sizeof(float) == 4 && FLT_MANT_DIG == 24 && FLT_MAX_EXP == 128,
               "the record stores IEEE 754 binary32 positions");

/* Bit fields of the 64-bit word (formats/photons.md, "Record"). */
#define POW_BITS 10
#define EXP_SHIFT 30
#define DIR_U_SHIFT 38
#define DIR_V_SHIFT 50
#define AXIS_SHIFT 62
#define DIR_BITS 12
#define DIR_MAX 4095            /* 2^12 - 1 */
/* value_c = m_c * 2^(E - EXP_BIAS); with EXP_BIAS = 128 + 10 the largest
 * channel's mantissa lies in [512, 1023] whenever 2^-128 <= max < 2^127. */
#define EXP_BIAS 138

static uint64_t
word(const pm_photon *p)
{
	return (uint64_t)p->bits[0] | (uint64_t)p->bits[1] << 32;
}

static void
setword(pm_photon *p, uint64_t w)
{
	p->bits[0] = (uint32_t)w;
	p->bits[1] = (uint32_t)(w >> 32);
}

/* Shared-exponent RGB in the spirit of RGBE (Ward 1991) and RGB9E5, with
 * 10-bit mantissas. The largest channel's mantissa is at least 512, so
 * every channel's error is at most 2^-10 of the largest channel (half a unit
 * against 512 units). Values below the range underflow gradually (E = 1, mantissas < 512)
 * and then to zero; values at or above 2^127 saturate at 1023 * 2^117. */
static uint64_t
pack_power(pm_vec3 power)
{
	double v[3] = {power.x, power.y, power.z}, mx = 0;
	uint64_t m[3];
	int e, E;

	for (int c = 0; c < 3; c++) {
		if (!(v[c] > 0))        /* negative, zero or NaN */
			v[c] = 0;
		if (v[c] > DBL_MAX)
			v[c] = DBL_MAX;
		if (v[c] > mx)
			mx = v[c];
	}
	if (mx == 0)
		return 0;
	frexp(mx, &e);                  /* mx = f * 2^e, f in [0.5, 1) */
	E = e + 128;
	if (E < 1)
		E = 1;
	for (;;) {
		int sat = E > 255;
		if (sat)
			E = 255;
		uint64_t top = 0;
		for (int c = 0; c < 3; c++) {
			double s = floor(ldexp(v[c], EXP_BIAS - E) + 0.5);
			m[c] = s > 1023 ? (sat ? 1023 : 1024) : (uint64_t)s;
			if (m[c] > top)
				top = m[c];
		}
		if (top == 1024) {      /* rounding carried out of the mantissa */
			E++;
			continue;
		}
		if (top == 0)
			return 0;
		break;
	}
	return m[0] | m[1] << 10 | m[2] << 20 | (uint64_t)E << EXP_SHIFT;
}

/* 2^e for e in [-149, 127], built from its bits: exactly ldexpf(1, e),
 * without its call (ldexpf and scalbnf were 11 % of the classical
 * estimate's instructions). Below 2^-126 the value is a subnormal. */
static inline float
pow2f(int e)
{
	uint32_t b = e >= -126 ? (uint32_t)(e + 127) << 23 : 1u << (e + 149);
	float f;
	memcpy(&f, &b, sizeof f);
	return f;
}

static pm_vec3
unpack_power(uint64_t w)
{
	int E = (int)(w >> EXP_SHIFT & 0xff);
	float s;

	if (E == 0)
		return pm_v3(0, 0, 0);
	s = pow2f(E - EXP_BIAS);
	return pm_v3((float)(w & 0x3ff) * s, (float)(w >> 10 & 0x3ff) * s,
	             (float)(w >> 20 & 0x3ff) * s);
}

/* Octahedral map (Cigolle et al. 2014, "A Survey of Efficient Representations
 * for Independent Unit Vectors", JCGT 3(2), §3.1): code c in 0..4095 stands
 * for the coordinate (2c - 4095) / 4095 in [-1, 1]. The decode is the one
 * place the float arithmetic is defined; pack tests candidates with it so
 * the side-of-surface guarantee holds for what readers actually see. */
static pm_vec3
oct_decode(unsigned cu, unsigned cv)
{
	float px = ((float)(2 * (int)cu) - (float)DIR_MAX) / (float)DIR_MAX;
	float py = ((float)(2 * (int)cv) - (float)DIR_MAX) / (float)DIR_MAX;
	float z = 1.0f - fabsf(px) - fabsf(py);
	float x = px, y = py;

	if (z < 0) {
		x = (1.0f - fabsf(py)) * copysignf(1.0f, px);
		y = (1.0f - fabsf(px)) * copysignf(1.0f, py);
	}
	return pm_norm(pm_v3(x, y, z));
}

/* Continuous octahedral coordinates of unit d, scaled to [0, 4095]. */
static void
oct_continuous(pm_vec3 d, double *su, double *sv)
{
	double l1 = fabs((double)d.x) + fabs((double)d.y) + fabs((double)d.z);
	double px = d.x / l1, py = d.y / l1;

	if (d.z < 0) {
		double qx = (1 - fabs(py)) * (px < 0 ? -1 : 1);
		double qy = (1 - fabs(px)) * (py < 0 ? -1 : 1);
		px = qx;
		py = qy;
	}
	*su = fmin(fmax((px + 1) * 0.5 * DIR_MAX, 0), DIR_MAX);
	*sv = fmin(fmax((py + 1) * 0.5 * DIR_MAX, 0), DIR_MAX);
}

static int
side_ok(pm_vec3 dec, pm_vec3 n, int side)
{
	float s = pm_dot(dec, n);
	return side > 0 ? s > 0 : side < 0 ? s < 0 : 1;
}

/* Best code in the square [u0-r, u0+r+1] x [v0-r, v0+r+1] (clamped) whose
 * decoded direction is on the required side; returns 0 if there is none. */
static int
oct_search(pm_vec3 d, pm_vec3 n, int side, int u0, int v0, int r, unsigned *bu, unsigned *bv)
{
	double best = -2;
	int found = 0;

	for (int u = u0 - r; u <= u0 + 1 + r; u++) {
		if (u < 0 || u > DIR_MAX)
			continue;
		for (int v = v0 - r; v <= v0 + 1 + r; v++) {
			if (v < 0 || v > DIR_MAX)
				continue;
			pm_vec3 dec = oct_decode((unsigned)u, (unsigned)v);
			double c = (double)dec.x * d.x + (double)dec.y * d.y + (double)dec.z * d.z;
			if (c > best && side_ok(dec, n, side)) {
				best = c;
				*bu = (unsigned)u;
				*bv = (unsigned)v;
				found = 1;
			}
		}
	}
	return found;
}

static uint64_t
pack_dir(pm_vec3 d, pm_vec3 n)
{
	double su, sv;
	unsigned bu = 0, bv = 0;
	int side, u0, v0;
	float s;

	if (!pm_vfinite(d) || !(fabsf(d.x) + fabsf(d.y) + fabsf(d.z) > 0))
		d = pm_v3(0, 0, 1);
	s = pm_dot(d, n);
	side = s > 0 ? 1 : s < 0 ? -1 : 0;
	oct_continuous(d, &su, &sv);
	u0 = (int)floor(su);
	v0 = (int)floor(sv);
	/* The four codes around the point almost always include one on the
	 * right side (a linear function positive inside a cell is positive at
	 * a corner); near the map's creases or when float rounding bites, look
	 * further out. A right-side code always exists within a few cells of a
	 * direction on that side, so the last resort is the plain nearest. */
	for (int r = 0; r <= 64; r = r ? 2 * r : 1)
		if (oct_search(d, n, side, u0, v0, r, &bu, &bv))
			return (uint64_t)bu << DIR_U_SHIFT | (uint64_t)bv << DIR_V_SHIFT;
	oct_search(d, n, 0, u0, v0, 0, &bu, &bv);
	return (uint64_t)bu << DIR_U_SHIFT | (uint64_t)bv << DIR_V_SHIFT;
}

void
pm_photon_pack(pm_photon *p, pm_vec3 pos, pm_vec3 dir, pm_vec3 n, pm_vec3 power)
{
	p->pos[0] = pos.x;
	p->pos[1] = pos.y;
	p->pos[2] = pos.z;
	setword(p, pack_power(power) | pack_dir(dir, n) | (uint64_t)PM_AXIS_NONE << AXIS_SHIFT);
}

pm_vec3
pm_photon_pos(const pm_photon *p)
{
	return pm_v3(p->pos[0], p->pos[1], p->pos[2]);
}

pm_vec3
pm_photon_dir(const pm_photon *p)
{
	uint64_t w = word(p);
	return oct_decode((unsigned)(w >> DIR_U_SHIFT & DIR_MAX), (unsigned)(w >> DIR_V_SHIFT & DIR_MAX));
}

pm_vec3
pm_photon_power(const pm_photon *p)
{
	return unpack_power(word(p));
}

int
pm_photon_axis(const pm_photon *p)
{
	return (int)(p->bits[1] >> 30);
}

void
pm_photon_set_axis(pm_photon *p, int axis)
{
	p->bits[1] = (p->bits[1] & 0x3fffffffu) | (uint32_t)(axis & 3) << 30;
}

static void
put32(unsigned char *b, uint32_t v)
{
	b[0] = (unsigned char)v;
	b[1] = (unsigned char)(v >> 8);
	b[2] = (unsigned char)(v >> 16);
	b[3] = (unsigned char)(v >> 24);
}

static uint32_t
get32(const unsigned char *b)
{
	return (uint32_t)b[0] | (uint32_t)b[1] << 8 | (uint32_t)b[2] << 16 | (uint32_t)b[3] << 24;
}

void
pm_photon_encode(const pm_photon *p, unsigned char out[PM_PHOTON_BYTES])
{
	for (int i = 0; i < 3; i++) {
		uint32_t u;
		memcpy(&u, &p->pos[i], 4);
		put32(out + 4 * i, u);
	}
	put32(out + 12, p->bits[0]);
	put32(out + 16, p->bits[1]);
}

void
pm_photon_decode(pm_photon *p, const unsigned char in[PM_PHOTON_BYTES])
{
	for (int i = 0; i < 3; i++) {
		uint32_t u = get32(in + 4 * i);
		memcpy(&p->pos[i], &u, 4);
	}
	p->bits[0] = get32(in + 12);
	p->bits[1] = get32(in + 16);
}
