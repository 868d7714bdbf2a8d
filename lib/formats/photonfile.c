/* photonfile.c — the photon file around the records: magic, the key=value
 * header (counts, seeds, history), the checked reader, the writer, and
 * merging. The header keys are specified in formats/photons.md; keep the two
 * in step. */
#include "formats/photonfile.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "formats/kdtree.h"
#include "base/version.h"

#define MAX_COUNT 4294967295u   /* photon indices are uint32 */
#define MAX_LINE 65536
#define MAX_HEADER (1 << 20)

/* Message prefix: 'x.pm' quoted, stdin/stdout bare. */
static void
fname(char *buf, size_t n, const char *name, int out)
{
	if (strcmp(name, "-") == 0)
		snprintf(buf, n, "%s", out ? "stdout" : "stdin");
	else
		snprintf(buf, n, "'%s'", name);
}

/* A header value as the writer prints it: plain decimal digits, nothing
 * else (unlike the tools' option parser, which takes exponent forms). */
static int
header_u64(const char *s, uint64_t *v)
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
       K_HASH, K_TIME, K_SEEDS, K_COMMAND, K_PM_VERSION, K_MAP, K_PATHS, K_DENSITY, K_N };
static const char *const keynames[K_N] = {
	"version", "endian", "record_size", "kdtree", "count", "emitted", "bbox",
	"light_hash", "time", "seeds", "command", "pm_version", "map", "light_paths", "density",
};

const char *
pm_map_name(int map)
{
	return map == PM_MAP_CAUSTIC ? "caustic" : map == PM_MAP_GUIDE ? "guide" : "global";
}

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
		if (header_u64(val, &u) || u == 0 || u > INT_MAX)
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
		if (header_u64(val, &u))
			return pm_seterr(err, "bad count '%.40s'", val);
		if (u > MAX_COUNT)
			return pm_seterr(err, "count %llu exceeds the limit of %u photons",
			                 (unsigned long long)u, MAX_COUNT);
		h->count = u;
		return 0;
	case K_EMITTED:
		if (header_u64(val, &u))
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
	case K_MAP:
		if (strcmp(val, "global") == 0)
			h->map = PM_MAP_GLOBAL;
		else if (strcmp(val, "caustic") == 0)
			h->map = PM_MAP_CAUSTIC;
		else if (strcmp(val, "guide") == 0)
			h->map = PM_MAP_GUIDE;
		else
			return pm_seterr(err, "bad map '%.40s' (want global, caustic or guide)", val);
		return 0;
	case K_PM_VERSION:
		/* Which pm wrote the file, for people: nothing depends on it. */
		return 0;
	case K_PATHS:
		if (strcmp(val, "random") && strcmp(val, "sobol") && strcmp(val, "mixed"))
			return pm_seterr(err, "bad light_paths '%.40s' (want random, sobol or mixed)", val);
		snprintf(h->light_paths, sizeof h->light_paths, "%s", val);
		return 0;
	case K_DENSITY: {
		double c;
		int k, used = -1;
		if (strcmp(val, "off") && strcmp(val, "mixed") &&
		    (sscanf(val, "pixels %lf k %d%n", &c, &k, &used) != 2 || used != (int)strlen(val) ||
		     !(c > 0) || k < 1 || strlen(val) >= sizeof h->density))
			return pm_seterr(err, "bad density '%.40s' (want off, mixed or pixels C k K)", val);
		snprintf(h->density, sizeof h->density, "%s", val);
		return 0;
	}
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
	/* Files from before the key were all shot pseudo-randomly. */
	strcpy(h->light_paths, "random");
	strcpy(h->density, "off");
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
		if (!seen[k] && k != K_COMMAND && k != K_PM_VERSION && k != K_MAP && k != K_PATHS
		    && k != K_DENSITY) {
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
	if (h->map != PM_MAP_GLOBAL && h->map != PM_MAP_CAUSTIC && h->map != PM_MAP_GUIDE)
		return pm_seterr(err, "%s: unknown map kind %d", fn, h->map);
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
	        "light_hash=%016llx\ntime=%.17g\nseeds=%s\npm_version=%s\nlight_paths=%s\ndensity=%s\n",
	        h->map != PM_MAP_GLOBAL ? 2 : 1, PM_PHOTON_BYTES, h->kdtree,
	        (unsigned long long)h->count, (unsigned long long)h->emitted,
	        bb[0], bb[1], bb[2], bb[3], bb[4], bb[5],
	        (unsigned long long)h->light_hash, h->time, h->seeds, PM_VERSION,
	        h->light_paths[0] ? h->light_paths : "random", h->density[0] ? h->density : "off");
	if (h->map != PM_MAP_GLOBAL)
		fprintf(f, "map=%s\n", pm_map_name(h->map));
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

unsigned
pm_photons_differ(const pm_photons *a, const pm_photons *b)
{
	return (b->h.light_hash != a->h.light_hash ? PM_DIFFER_LIGHTS : 0) |
	       (b->h.time != a->h.time ? PM_DIFFER_TIME : 0) |
	       (b->h.map != a->h.map ? PM_DIFFER_MAP : 0);
}

/* Appends seeds to the merged list; a list that would not fit ends in
 * ",..." (the command history still names every input's seed). */
static void
join_seeds(char *acc, size_t cap, const char *add)
{
	size_t n = strlen(acc), m = strlen(add);
	char *cut;

	if (m == 0)
		return;
	if (n >= 4 && strcmp(acc + n - 4, ",...") == 0)
		return;
	if (n == 0 && m < cap) {
		memcpy(acc, add, m + 1);
		return;
	}
	if (n + 1 + m < cap) {
		acc[n] = ',';
		memcpy(acc + n + 1, add, m + 1);
		return;
	}
	while (strlen(acc) + 4 >= cap && (cut = strrchr(acc, ',')) != NULL)
		*cut = 0;
	if (strlen(acc) + 4 < cap)
		strcat(acc, ",...");
}

int
pm_photons_merge(pm_photons *acc, pm_photons *src, const char *src_name, pm_error *err)
{
	uint64_t n = acc->h.count + src->h.count;
	char fn[600];

	fname(fn, sizeof fn, src_name, 0);
	if (n > MAX_COUNT)
		return pm_seterr(err, "%s: merged maps would exceed %u photons", fn, MAX_COUNT);
	if (acc->h.emitted > UINT64_MAX - src->h.emitted)
		return pm_seterr(err, "%s: merged emitted count overflows", fn);
	if (src->h.count) {
		pm_photon *p = realloc(acc->p, (size_t)n * sizeof *p);
		if (!p)
			return pm_seterr(err, "out of memory for %llu photons", (unsigned long long)n);
		memcpy(p + acc->h.count, src->p, (size_t)src->h.count * sizeof *p);
		acc->p = p;
	}
	if (src->h.history && *src->h.history && add_history(&acc->h.history, src->h.history))
		return pm_seterr(err, "out of memory");
	acc->h.count = n;
	acc->h.emitted += src->h.emitted;
	join_seeds(acc->h.seeds, sizeof acc->h.seeds, src->h.seeds);
	if (strcmp(acc->h.light_paths, src->h.light_paths) != 0)
		strcpy(acc->h.light_paths, "mixed");
	if (strcmp(acc->h.density, src->h.density) != 0)
		strcpy(acc->h.density, "mixed");
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
