/* photon.c — the 20-byte photon record (shared-exponent power, octahedral
 * direction) and the photon file reader and writer. The byte layout and the
 * header keys are specified in formats/photons.md; keep the two in step. */
#include "photon.h"

#include <errno.h>
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "kdtree.h"
#include "version.h"

_Static_assert(sizeof(pm_photon) == PM_PHOTON_BYTES, "pm_photon must be 20 bytes");
_Static_assert(sizeof(float) == 4 && FLT_MANT_DIG == 24 && FLT_MAX_EXP == 128,
               "the record stores IEEE 754 binary32 positions");

/* Bit fields of the 64-bit word (formats/photons.md, "The record"). */
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

#define MAX_COUNT 4294967295u   /* photon indices are uint32 */
#define MAX_LINE 65536
#define MAX_HEADER (1 << 20)

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

static pm_vec3
unpack_power(uint64_t w)
{
	int E = (int)(w >> EXP_SHIFT & 0xff);
	float s;

	if (E == 0)
		return pm_v3(0, 0, 0);
	s = ldexpf(1.0f, E - EXP_BIAS);
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

/* ---- the file ---------------------------------------------------------- */

/* Message prefix: 'x.pm' quoted, stdin/stdout bare. */
static void
fname(char *buf, size_t n, const char *name, int out)
{
	if (strcmp(name, "-") == 0)
		snprintf(buf, n, "%s", out ? "stdout" : "stdin");
	else
		snprintf(buf, n, "'%s'", name);
}

static int
parse_u64(const char *s, uint64_t *v)
{
	uint64_t x = 0;

	if (!*s)
		return -1;
	for (; *s; s++) {
		if (*s < '0' || *s > '9')
			return -1;
		if (x > (UINT64_MAX - (uint64_t)(*s - '0')) / 10)
			return -1;
		x = x * 10 + (uint64_t)(*s - '0');
	}
	*v = x;
	return 0;
}

static int
parse_hex64(const char *s, uint64_t *v)
{
	uint64_t x = 0;
	size_t n = strlen(s);

	if (n != 16)
		return -1;
	for (; *s; s++) {
		int d = *s >= '0' && *s <= '9' ? *s - '0'
		      : *s >= 'a' && *s <= 'f' ? *s - 'a' + 10
		      : *s >= 'A' && *s <= 'F' ? *s - 'A' + 10 : -1;
		if (d < 0)
			return -1;
		x = x << 4 | (uint64_t)d;
	}
	*v = x;
	return 0;
}

static int
seeds_ok(const char *s)
{
	return strlen(s) < sizeof ((pm_photon_header *)0)->seeds &&
	       strspn(s, "0123456789,.-") == strlen(s);
}

/* One header line without its '\n' into buf (MAX_LINE + 1 bytes).
 * Returns the length, -1 at EOF before any byte, -2 if EOF cut the line,
 * -3 if too long, -4 on a NUL byte, -5 on a read error. */
static long
getline_bounded(FILE *f, char *buf, size_t *total)
{
	size_t n = 0;
	int c;

	while ((c = getc(f)) != EOF) {
		++*total;
		if (c == '\n') {
			buf[n] = 0;
			return (long)n;
		}
		if (c == 0)
			return -4;
		if (n == MAX_LINE)
			return -3;
		buf[n++] = (char)c;
		if (*total > MAX_HEADER)
			return -3;
	}
	if (ferror(f))
		return -5;
	return n == 0 ? -1 : -2;
}

enum { K_VERSION, K_ENDIAN, K_RECSIZE, K_KDTREE, K_COUNT, K_EMITTED, K_BBOX,
       K_HASH, K_TIME, K_SEEDS, K_COMMAND, K_PM_VERSION, K_N };
static const char *const keynames[K_N] = {
	"version", "endian", "record_size", "kdtree", "count", "emitted", "bbox",
	"light_hash", "time", "seeds", "command", "pm_version",
};

static int
add_history(char **hist, const char *line)
{
	size_t old = *hist ? strlen(*hist) : 0, add = strlen(line);
	char *h = realloc(*hist, old + add + 2);

	if (!h)
		return -1;
	if (old)
		h[old++] = '\n';
	memcpy(h + old, line, add + 1);
	*hist = h;
	return 0;
}

/* Parses one key's value into h; returns 0 or -1 with a message (without the
 * file prefix) in err. */
static int
parse_value(pm_photon_header *h, int key, const char *val, pm_error *err)
{
	uint64_t u;
	char *end;

	switch (key) {
	case K_VERSION:
		if (parse_u64(val, &u) || u == 0 || u > INT_MAX)
			return pm_seterr(err, "bad version '%.40s'", val);
		h->version = (int)u;
		return 0;
	case K_ENDIAN:
		if (strcmp(val, "little") != 0)
			return pm_seterr(err, "endian=%.40s is not supported (only little)", val);
		return 0;
	case K_RECSIZE:
		if (strcmp(val, "20") != 0)
			return pm_seterr(err, "record_size=%.40s is not supported (this pm reads %d-byte records)",
			                 val, PM_PHOTON_BYTES);
		return 0;
	case K_KDTREE:
		if (strcmp(val, "0") != 0 && strcmp(val, "1") != 0)
			return pm_seterr(err, "bad kdtree '%.40s' (want 0 or 1)", val);
		h->kdtree = val[0] - '0';
		return 0;
	case K_COUNT:
		if (parse_u64(val, &u))
			return pm_seterr(err, "bad count '%.40s'", val);
		if (u > MAX_COUNT)
			return pm_seterr(err, "count %llu exceeds the limit of %u photons",
			                 (unsigned long long)u, MAX_COUNT);
		h->count = u;
		return 0;
	case K_EMITTED:
		if (parse_u64(val, &u))
			return pm_seterr(err, "bad emitted '%.40s'", val);
		h->emitted = u;
		return 0;
	case K_BBOX: {
		const char *s = val;
		for (int i = 0; i < 6; i++) {
			if (i > 0 && *s++ != ' ')
				return pm_seterr(err, "bad bbox '%.80s' (want 6 numbers)", val);
			if (*s == ' ' || !*s)
				return pm_seterr(err, "bad bbox '%.80s' (want 6 numbers)", val);
			errno = 0;
			h->bbox[i] = strtof(s, &end);
			if (end == s || (*end && *end != ' '))
				return pm_seterr(err, "bad bbox '%.80s' (want 6 numbers)", val);
			if (!isfinite(h->bbox[i]))
				return pm_seterr(err, "bbox '%.80s' is not finite", val);
			s = end;
		}
		if (*s)
			return pm_seterr(err, "bad bbox '%.80s' (want 6 numbers)", val);
		return 0;
	}
	case K_HASH:
		if (parse_hex64(val, &h->light_hash))
			return pm_seterr(err, "bad light_hash '%.40s' (want 16 hex digits)", val);
		return 0;
	case K_TIME:
		h->time = strtod(val, &end);
		if (end == val || *end || val[0] == ' ')
			return pm_seterr(err, "bad time '%.40s'", val);
		if (!isfinite(h->time))
			return pm_seterr(err, "time '%.40s' is not finite", val);
		return 0;
	case K_SEEDS:
		if (!seeds_ok(val))
			return pm_seterr(err, "bad seeds '%.40s' (want numbers separated by commas, under 256 characters)", val);
		snprintf(h->seeds, sizeof h->seeds, "%s", val);
		return 0;
	case K_PM_VERSION:
		/* Which pm wrote the file, for people: nothing depends on it. */
		return 0;
	case K_COMMAND:
		/* An empty line records nothing (and could not be written back:
		 * the history is a '\n'-joined string). */
		if (*val && add_history(&h->history, val))
			return pm_seterr(err, "out of memory");
		return 0;
	}
	return pm_seterr(err, "internal error: key %d", key);
}

static int
read_header(pm_photons *out, FILE *f, const char *name, char **raw, pm_error *err)
{
	static const char magic[] = PM_PHOTONS_MAGIC;
	pm_photon_header *h = &out->h;
	char fn[600], *line = NULL, *rawbuf = NULL;
	pm_error first;
	size_t total = 0, rawlen = 0;
	int seen[K_N] = {0}, lineno = 1, bad = 0, c;

	memset(out, 0, sizeof *out);
	fname(fn, sizeof fn, name, 0);
	for (size_t i = 0; i < sizeof magic - 1; i++) {
		c = getc(f);
		if (c == EOF && ferror(f))
			return pm_seterr(err, "cannot read %s: %s", fn, strerror(errno));
		if (c == EOF && i == 0)
			return pm_seterr(err, "%s: empty, not a photon file", fn);
		if (c != (unsigned char)magic[i])
			return pm_seterr(err, "%s: not a photon file (no PM-PHOTONS magic)", fn);
	}
	total = sizeof magic - 1;
	line = malloc(MAX_LINE + 1);
	if (raw)
		rawbuf = malloc(MAX_HEADER + 2);
	if (!line || (raw && !rawbuf)) {
		pm_seterr(err, "%s: out of memory", fn);
		goto fail;
	}
	if (rawbuf) {
		memcpy(rawbuf, magic, sizeof magic - 1);
		rawlen = sizeof magic - 1;
	}
	for (;;) {
		long n = getline_bounded(f, line, &total);
		char *eq;
		int key;

		lineno++;
		if (n == -1 || n == -2) {
			pm_seterr(err, "%s: truncated header (line %d)", fn, lineno);
			goto fail;
		}
		if (n == -3) {
			if (total > MAX_HEADER)
				pm_seterr(err, "%s: header longer than %d bytes", fn, MAX_HEADER);
			else
				pm_seterr(err, "%s: line %d: header line longer than %d bytes", fn, lineno, MAX_LINE);
			goto fail;
		}
		if (n == -4) {
			pm_seterr(err, "%s: line %d: NUL byte in header", fn, lineno);
			goto fail;
		}
		if (n == -5) {
			pm_seterr(err, "cannot read %s: %s", fn, strerror(errno));
			goto fail;
		}
		if (rawbuf) {
			memcpy(rawbuf + rawlen, line, (size_t)n);
			rawlen += (size_t)n;
			rawbuf[rawlen++] = '\n';
		}
		if (n == 0)
			break;
		if (bad)        /* keep reading: a newer version explains it */
			continue;
		eq = strchr(line, '=');
		if (!eq) {
			pm_seterr(&first, "line %d: expected key=value, got '%.40s'", lineno, line);
			bad = 1;
			continue;
		}
		*eq = 0;
		for (key = 0; key < K_N; key++)
			if (strcmp(line, keynames[key]) == 0)
				break;
		if (key == K_N && strcmp(line, "scene_hash") == 0) {
			/* Before light_hash, files carried a hash of the scene
			 * file's bytes, which cannot be compared with a scene now. */
			pm_seterr(&first, "photon file of an older pm (it records scene_hash, not light_hash): shoot it again");
			bad = 1;
			continue;
		}
		if (key == K_N) {
			pm_seterr(&first, "line %d: unknown key '%.40s'", lineno, line);
			bad = 1;
			continue;
		}
		if (seen[key] && key != K_COMMAND) {
			pm_seterr(&first, "line %d: duplicate key '%s'", lineno, line);
			bad = 1;
			continue;
		}
		seen[key] = 1;
		if (parse_value(h, key, eq + 1, &first)) {
			if (key == K_VERSION) {
				pm_seterr(err, "%s: line %d: %s", fn, lineno, first.msg);
				goto fail;
			}
			char tmp[sizeof first.msg];
			snprintf(tmp, sizeof tmp, "%s", first.msg);
			pm_seterr(&first, "line %d: %s", lineno, tmp);
			bad = 1;
		}
	}
	if (!seen[K_VERSION]) {
		pm_seterr(err, "%s: missing key 'version'", fn);
		goto fail;
	}
	if (h->version > PM_PHOTONS_VERSION) {
		pm_seterr(err, "%s: photon file version %d is newer than this pm (%d)",
		          fn, h->version, PM_PHOTONS_VERSION);
		goto fail;
	}
	if (bad) {
		pm_seterr(err, "%s: %s", fn, first.msg);
		goto fail;
	}
	for (int k = 0; k < K_N; k++)
		if (!seen[k] && k != K_COMMAND && k != K_PM_VERSION) {
			pm_seterr(err, "%s: missing key '%s'", fn, keynames[k]);
			goto fail;
		}
	if (h->count > 0 && h->emitted == 0) {
		pm_seterr(err, "%s: %llu photons but emitted=0", fn, (unsigned long long)h->count);
		goto fail;
	}
	for (int i = 0; i < 3; i++)
		if (h->count > 0 && !(h->bbox[i] <= h->bbox[3 + i])) {
			pm_seterr(err, "%s: bbox minimum exceeds maximum", fn);
			goto fail;
		}
	free(line);
	if (raw) {
		rawbuf[rawlen] = 0;
		*raw = rawbuf;
	}
	return 0;
fail:
	free(line);
	free(rawbuf);
	free(h->history);
	h->history = NULL;
	return -1;
}

int
pm_photons_read_header(pm_photons *out, FILE *f, const char *name, char **raw, pm_error *err)
{
	return read_header(out, f, name, raw, err);
}

/* Records arrive through a staging buffer and the array grows only as they
 * do, so a header promising 4 billion photons on a short stream costs no
 * more memory than the stream. */
int
pm_photons_read_records(pm_photons *ph, FILE *f, const char *name, pm_error *err)
{
	enum { CHUNK = 1 << 18 };   /* records encoded at once, in parallel */
	const pm_photon_header *h = &ph->h;
	unsigned char *buf;
	pm_photon *p = NULL;
	size_t got = 0, cap = 0;
	char fn[600];
	int c;

	fname(fn, sizeof fn, name, 0);
	buf = malloc((size_t)CHUNK * PM_PHOTON_BYTES);
	if (!buf)
		return pm_seterr(err, "%s: out of memory", fn);
	while (got < h->count) {
		size_t want = h->count - got < CHUNK ? (size_t)(h->count - got) : CHUNK;
		size_t n = fread(buf, PM_PHOTON_BYTES, want, f);
		if (n > 0 && got + n > cap) {
			size_t nc = cap ? cap : CHUNK;
			while (nc < got + n)
				nc *= 2;
			if (nc > h->count)
				nc = (size_t)h->count;
			pm_photon *q = realloc(p, nc * sizeof *p);
			if (!q) {
				pm_seterr(err, "%s: out of memory for %zu photons", fn, nc);
				goto fail;
			}
			p = q;
			cap = nc;
		}
		for (size_t i = 0; i < n; i++)
			pm_photon_decode(&p[got + i], buf + i * PM_PHOTON_BYTES);
		got += n;
		if (n < want) {
			if (ferror(f))
				pm_seterr(err, "cannot read %s: %s", fn, strerror(errno));
			else
				pm_seterr(err, "%s: truncated: %llu photons promised, %zu present",
				          fn, (unsigned long long)h->count, got);
			goto fail;
		}
	}
	c = getc(f);
	if (c != EOF) {
		pm_seterr(err, "%s: trailing data after %llu photons", fn, (unsigned long long)h->count);
		goto fail;
	}
	if (ferror(f)) {
		pm_seterr(err, "cannot read %s: %s", fn, strerror(errno));
		goto fail;
	}
	for (size_t i = 0; i < got; i++) {
		const float *q = p[i].pos;
		if (!isfinite(q[0]) || !isfinite(q[1]) || !isfinite(q[2])) {
			pm_seterr(err, "%s: photon %zu has a non-finite position", fn, i);
			goto fail;
		}
		for (int a = 0; a < 3; a++)
			if (q[a] < h->bbox[a] || q[a] > h->bbox[3 + a]) {
				pm_seterr(err, "%s: photon %zu lies outside the header's bbox", fn, i);
				goto fail;
			}
	}
	/* Powers need no check: every code decodes to a finite value >= 0. */
	if (h->kdtree && pm_kd_validate(p, got, err)) {
		pm_preferr(err, "%s: not a valid kd-tree", fn);
		goto fail;
	}
	free(buf);
	ph->p = p;
	return 0;
fail:
	free(buf);
	free(p);
	return -1;
}

int
pm_photons_read(pm_photons *out, FILE *f, const char *name, pm_error *err)
{
	if (read_header(out, f, name, NULL, err))
		return -1;
	if (pm_photons_read_records(out, f, name, err)) {
		pm_photons_free(out);
		return -1;
	}
	return 0;
}

/* Checks that the header can be written and read back: the writer refuses
 * anything the reader would refuse. Computes the bbox of the records. */
static int
check_for_write(const pm_photons *ph, const char *fn, float bbox[6], size_t *hlen, pm_error *err)
{
	const pm_photon_header *h = &ph->h;
	size_t len = 300 + strlen(h->seeds) + strlen(PM_VERSION);
	const char *s;

	if (h->count > MAX_COUNT)
		return pm_seterr(err, "%s: %llu photons exceed the limit of %u",
		                 fn, (unsigned long long)h->count, MAX_COUNT);
	if (h->count > 0 && !ph->p)
		return pm_seterr(err, "%s: no photon records", fn);
	if (h->count > 0 && h->emitted == 0)
		return pm_seterr(err, "%s: %llu photons but emitted=0", fn, (unsigned long long)h->count);
	if (!isfinite(h->time))
		return pm_seterr(err, "%s: time is not finite", fn);
	if (h->kdtree != 0 && h->kdtree != 1)
		return pm_seterr(err, "%s: kdtree must be 0 or 1", fn);
	if (!seeds_ok(h->seeds))
		return pm_seterr(err, "%s: bad seeds '%.40s'", fn, h->seeds);
	for (s = h->history; s && *s;) {
		size_t n = strcspn(s, "\n");
		if (n + 8 > MAX_LINE)
			return pm_seterr(err, "%s: history line longer than %d bytes", fn, MAX_LINE - 8);
		len += n + 9;
		s += n;
		if (*s)
			s++;
	}
	if (len > MAX_HEADER)
		return pm_seterr(err, "%s: header (history) longer than %d bytes", fn, MAX_HEADER);
	*hlen = len;
	for (int a = 0; a < 6; a++)
		bbox[a] = 0;
	if (h->count == 0)
		return 0;
	/* In parallel: min and max are exact, so the result does not depend
	 * on the split; a non-finite position is then found again in order,
	 * so the message names the first. */
	float l0 = INFINITY, l1 = INFINITY, l2 = INFINITY, u0 = -INFINITY, u1 = -INFINITY, u2 = -INFINITY;
	int bad = 0;
	#pragma omp parallel for reduction(min: l0, l1, l2) reduction(max: u0, u1, u2) reduction(|: bad)
	for (size_t i = 0; i < h->count; i++) {
		const float *q = ph->p[i].pos;
		bad |= !isfinite(q[0]) || !isfinite(q[1]) || !isfinite(q[2]);
		l0 = q[0] < l0 ? q[0] : l0;
		l1 = q[1] < l1 ? q[1] : l1;
		l2 = q[2] < l2 ? q[2] : l2;
		u0 = q[0] > u0 ? q[0] : u0;
		u1 = q[1] > u1 ? q[1] : u1;
		u2 = q[2] > u2 ? q[2] : u2;
	}
	if (bad)
		for (size_t i = 0; i < h->count; i++) {
			const float *q = ph->p[i].pos;
			if (!isfinite(q[0]) || !isfinite(q[1]) || !isfinite(q[2]))
				return pm_seterr(err, "%s: photon %zu has a non-finite position", fn, i);
		}
	bbox[0] = l0; bbox[1] = l1; bbox[2] = l2;
	bbox[3] = u0; bbox[4] = u1; bbox[5] = u2;
	return 0;
}

int
pm_photons_write(const pm_photons *ph, FILE *f, const char *name, pm_error *err)
{
	enum { CHUNK = 1 << 18 };   /* records encoded at once, in parallel */
	const pm_photon_header *h = &ph->h;
	unsigned char *buf;
	float bb[6];
	size_t hlen;
	char fn[600];
	const char *s;

	fname(fn, sizeof fn, name, 1);
	if (check_for_write(ph, fn, bb, &hlen, err))
		return -1;
	fprintf(f, "PM-PHOTONS\nversion=%d\nendian=little\nrecord_size=%d\nkdtree=%d\n"
	        "count=%llu\nemitted=%llu\nbbox=%.9g %.9g %.9g %.9g %.9g %.9g\n"
	        "light_hash=%016llx\ntime=%.17g\nseeds=%s\npm_version=%s\n",
	        PM_PHOTONS_VERSION, PM_PHOTON_BYTES, h->kdtree,
	        (unsigned long long)h->count, (unsigned long long)h->emitted,
	        bb[0], bb[1], bb[2], bb[3], bb[4], bb[5],
	        (unsigned long long)h->light_hash, h->time, h->seeds, PM_VERSION);
	for (s = h->history; s && *s;) {
		size_t n = strcspn(s, "\n");
		fprintf(f, "command=%.*s\n", (int)n, s);
		s += n;
		if (*s)
			s++;
	}
	putc('\n', f);
	buf = malloc((size_t)CHUNK * PM_PHOTON_BYTES);
	if (!buf)
		return pm_seterr(err, "%s: out of memory", fn);
	for (size_t i = 0; i < h->count; i += CHUNK) {
		size_t n = h->count - i < CHUNK ? (size_t)(h->count - i) : CHUNK;
		#pragma omp parallel for schedule(static)
		for (size_t j = 0; j < n; j++)
			pm_photon_encode(&ph->p[i + j], buf + j * PM_PHOTON_BYTES);
		if (fwrite(buf, PM_PHOTON_BYTES, n, f) != n) {
			int e = errno;
			free(buf);
			return pm_seterr(err, "cannot write %s: %s", fn, strerror(e ? e : EIO));
		}
	}
	free(buf);
	if (ferror(f))
		return pm_seterr(err, "cannot write %s: %s", fn, strerror(errno ? errno : EIO));
	return 0;
}

int
pm_photons_add_history(pm_photons *ph, const char *cmdline, pm_error *err)
{
	if (strchr(cmdline, '\n'))
		return pm_seterr(err, "command line contains a newline");
	if (strlen(cmdline) + 8 > MAX_LINE)
		return pm_seterr(err, "command line longer than %d bytes", MAX_LINE - 8);
	if (add_history(&ph->h.history, cmdline))
		return pm_seterr(err, "out of memory");
	return 0;
}

void
pm_photons_free(pm_photons *ph)
{
	free(ph->p);
	free(ph->h.history);
	ph->p = NULL;
	ph->h.history = NULL;
}
