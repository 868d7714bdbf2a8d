/* test_photon.c — the photon record codec (byte layout, power and direction
 * quantization, the grazing guarantee) and the photon file reader/writer,
 * including every refusal the reader promises. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "check.h"
#include "formats/photonfile.h"
#include "base/rng.h"

static pm_vec3
rand_dir(pm_rng *r)
{
	double z = 2.0 * pm_rng_f(r) - 1.0, a = 2 * PM_PI * pm_rng_f(r);
	double s = sqrt(fmax(0.0, 1 - z * z));
	return pm_norm(pm_v3((float)(s * cos(a)), (float)(s * sin(a)), (float)z));
}

static double
angle(pm_vec3 a, pm_vec3 b)
{
	/* atan2 of |a x b| and a . b stays accurate for tiny angles. */
	pm_dvec3 da = pm_dfromf(a), db = pm_dfromf(b);
	return atan2(pm_dlen(pm_dcross(da, db)), pm_ddot(da, db));
}

TEST(codec_round_trip)
{
	pm_rng r = pm_rng_seed(1, 1);
	int bad = 0;

	for (int t = 0; t < 100000; t++) {
		unsigned char b[PM_PHOTON_BYTES], b2[PM_PHOTON_BYTES];
		pm_photon p, q;
		for (int i = 0; i < PM_PHOTON_BYTES; i++)
			b[i] = (unsigned char)pm_rng_u32(&r);
		pm_photon_decode(&p, b);
		pm_photon_encode(&p, b2);
		pm_photon_decode(&q, b2);
		bad += memcmp(b, b2, sizeof b) != 0 || memcmp(&p, &q, sizeof p) != 0;
	}
	CHECKF(bad == 0, "%d of 100000 records changed in a round trip", bad);
}

TEST(byte_layout)
{
	/* Expected bytes worked out from formats/photons.md by hand: positions
	 * 1, -2, 0.5 as little-endian binary32; R=512 G=256 B=128 E=129
	 * (so power 1, 0.5, 0.25), u=0x123, v=0xabc, axis 1. */
	static const unsigned char want[PM_PHOTON_BYTES] = {
		0x00, 0x00, 0x80, 0x3f, 0x00, 0x00, 0x00, 0xc0, 0x00, 0x00, 0x00, 0x3f,
		0x00, 0x02, 0x04, 0x48, 0xe0, 0x48, 0xf0, 0x6a,
	};
	unsigned char got[PM_PHOTON_BYTES];
	pm_photon p, q;
	pm_vec3 pw;

	pm_photon_pack(&p, pm_v3(1, -2, 0.5f), pm_v3(0, 0, 1), pm_v3(0, 0, 1), pm_v3(1, 0.5f, 0.25f));
	CHECKF(p.bits[0] == 0x48040200u, "power word %08x", (unsigned)p.bits[0]);
	/* E = 129 = 0b10000001: bits 30-31 of the low word hold 01, the low 6
	 * bits of the high word hold 100000 */
	CHECKF((p.bits[1] & 0x3f) == 0x20, "exponent high bits %x", (unsigned)(p.bits[1] & 0x3f));
	CHECK(pm_photon_axis(&p) == PM_AXIS_NONE);
	/* replace the direction and axis with hand-picked codes */
	p.bits[1] = (p.bits[1] & 0x3f) | 0x123u << 6 | 0xabcu << 18;
	pm_photon_set_axis(&p, 1);
	pm_photon_encode(&p, got);
	for (int i = 0; i < PM_PHOTON_BYTES; i++)
		CHECKF(got[i] == want[i], "byte %d is 0x%02x, want 0x%02x", i, got[i], want[i]);
	pm_photon_decode(&q, want);
	pw = pm_photon_power(&q);
	CHECKF(pw.x == 1 && pw.y == 0.5f && pw.z == 0.25f, "power %g %g %g", pw.x, pw.y, pw.z);
	CHECK(q.pos[0] == 1 && q.pos[1] == -2 && q.pos[2] == 0.5f);
	CHECK(pm_photon_axis(&q) == 1);
	/* u = 0x123 = 291, v = 0xabc = 2748: p = (2c - 4095) / 4095 gives
	 * |px| + |py| > 1, the lower hemisphere, where the map folds. */
	{
		double px = (2.0 * 291 - 4095) / 4095, py = (2.0 * 2748 - 4095) / 4095;
		double pz = 1 - fabs(px) - fabs(py);
		CHECK(pz < 0);
		double fx = (1 - fabs(py)) * (px < 0 ? -1 : 1), fy = (1 - fabs(px)) * (py < 0 ? -1 : 1);
		px = fx;
		py = fy;
		double l = sqrt(px * px + py * py + pz * pz);
		pm_vec3 d = pm_photon_dir(&q);
		CHECKF(fabs(d.x - px / l) < 1e-6 && fabs(d.y - py / l) < 1e-6 && fabs(d.z - pz / l) < 1e-6,
		       "dir %g %g %g, want %g %g %g", d.x, d.y, d.z, px / l, py / l, pz / l);
	}
	pm_photon_set_axis(&q, 2);
	CHECK(pm_photon_axis(&q) == 2 && q.bits[0] == 0x48040200u && (q.bits[1] & 0x3fffffffu) == (0x6af048e0u & 0x3fffffffu));
}

TEST(power_error)
{
	pm_rng r = pm_rng_seed(2, 2);
	double worst_max = 0, worst_other = 0;
	int badmant = 0;

	for (int t = 0; t < 1000000; t++) {
		double mag = pow(10.0, -30 + 60 * pm_rng_f(&r));
		float v[3];
		pm_photon p;
		for (int c = 0; c < 3; c++) {
			float u = pm_rng_f(&r);
			v[c] = t % 7 == 0 && c == 1 ? 0.0f : (float)(mag * (t % 3 == 0 ? u * u * u : u));
		}
		v[t % 3] = (float)mag;      /* some channel is the largest */
		pm_photon_pack(&p, pm_v3(0, 0, 0), pm_v3(0, 0, 1), pm_v3(0, 0, 0), pm_v3(v[0], v[1], v[2]));
		pm_vec3 d = pm_photon_power(&p);
		float dv[3] = {d.x, d.y, d.z};
		double mx = fmax(v[0], fmax(v[1], v[2]));
		for (int c = 0; c < 3; c++) {
			double e = fabs((double)dv[c] - v[c]) / mx;
			if (v[c] == mx)
				worst_max = fmax(worst_max, e);
			else
				worst_other = fmax(worst_other, e);
		}
		/* the largest channel keeps a full 10-bit mantissa */
		int m = (int)(p.bits[0] >> (10 * (t % 3)) & 0x3ff);
		badmant += m < 512 || m > 1023;
	}
	printf("# power: worst error of the largest channel %.3g (relative), "
	       "of the others %.3g (relative to the largest)\n", worst_max, worst_other);
	CHECKF(worst_max <= ldexp(1, -10), "largest channel error %g > 2^-10", worst_max);
	CHECKF(worst_other <= ldexp(1, -10), "other channel error %g > 2^-10 of the largest", worst_other);
	CHECKF(badmant == 0, "%d largest mantissas outside [512, 1023]", badmant);
}

TEST(power_edges)
{
	pm_photon p;
	pm_vec3 d;

	pm_photon_pack(&p, pm_v3(0, 0, 0), pm_v3(0, 0, 1), pm_v3(0, 0, 1), pm_v3(0, 0, 0));
	d = pm_photon_power(&p);
	CHECK(d.x == 0 && d.y == 0 && d.z == 0 && (p.bits[0] >> 30) == 0 && (p.bits[1] & 0x3f) == 0);
	/* rounding up to 1024 moves to the next exponent: 1023.75 / 1024 */
	pm_photon_pack(&p, pm_v3(0, 0, 0), pm_v3(0, 0, 1), pm_v3(0, 0, 1), pm_v3(1023.75f / 1024, 0, 0));
	d = pm_photon_power(&p);
	CHECKF(d.x == 1 && (p.bits[0] & 0x3ff) == 512, "got %.9g, mantissa %u", d.x, (unsigned)(p.bits[0] & 0x3ff));
	/* saturation: the largest float clamps to 1023 * 2^117 */
	pm_photon_pack(&p, pm_v3(0, 0, 0), pm_v3(0, 0, 1), pm_v3(0, 0, 1), pm_v3(INFINITY, 3e38f, 1));
	d = pm_photon_power(&p);
	CHECKF(d.x == ldexpf(1023, 117) && d.y == ldexpf(1023, 117) && isfinite(d.z) && d.z >= 0,
	       "saturated to %g %g %g", d.x, d.y, d.z);
	/* gradual underflow below 2^-128, then zero */
	pm_photon_pack(&p, pm_v3(0, 0, 0), pm_v3(0, 0, 1), pm_v3(0, 0, 1), pm_v3(ldexpf(1, -130), 0, 0));
	d = pm_photon_power(&p);
	CHECKF(d.x == ldexpf(1, -130), "2^-130 decoded as %g", d.x);
	pm_photon_pack(&p, pm_v3(0, 0, 0), pm_v3(0, 0, 1), pm_v3(0, 0, 1), pm_v3(ldexpf(1, -140), 0, 0));
	d = pm_photon_power(&p);
	CHECKF(d.x == 0, "2^-140 decoded as %g", d.x);
	/* negative and NaN channels are stored as 0 */
	pm_photon_pack(&p, pm_v3(0, 0, 0), pm_v3(0, 0, 1), pm_v3(0, 0, 1), pm_v3(-1, NAN, 2));
	d = pm_photon_power(&p);
	CHECKF(d.x == 0 && d.y == 0 && d.z == 2, "got %g %g %g", d.x, d.y, d.z);
	/* every exponent decodes to m 2^(E - 138) exactly (formats/photons.md),
	 * the subnormal ones below E = 12 too, for the largest, the smallest
	 * and an odd mantissa; E = 0 is zero */
	int bad = 0;
	const uint32_t ms[3] = {0x3ff, 1, 0x2a5};
	for (uint32_t e = 0; e < 256; e++) {
		p.bits[0] = ms[0] | ms[1] << 10 | ms[2] << 20 | (e & 3) << 30;
		p.bits[1] = e >> 2;
		d = pm_photon_power(&p);
		float s = e == 0 ? 0 : ldexpf(1, (int)e - 138);
		int ok = pm_vfinite(d) && d.x == (float)ms[0] * s && d.y == (float)ms[1] * s &&
		         d.z == (float)ms[2] * s;
		if (!ok && bad++ == 0)
			printf("# E %u decoded as %g %g %g\n", (unsigned)e, d.x, d.y, d.z);
	}
	CHECK(bad == 0);
}

TEST(direction_error)
{
	pm_rng r = pm_rng_seed(3, 3);
	double worst = 0;
	int flips = 0;

	for (int t = 0; t < 1000000; t++) {
		pm_vec3 d = rand_dir(&r);
		if (t < 6)
			d = pm_v3(t / 2 == 0 ? (t & 1 ? -1 : 1) : 0, t / 2 == 1 ? (t & 1 ? -1 : 1) : 0,
			          t / 2 == 2 ? (t & 1 ? -1 : 1) : 0);
		pm_photon p;
		pm_photon_pack(&p, pm_v3(0, 0, 0), d, d, pm_v3(1, 1, 1));
		pm_vec3 q = pm_photon_dir(&p);
		worst = fmax(worst, angle(d, q));
		flips += fabsf(pm_len(q) - 1) > 1e-6f;
	}
	printf("# direction: worst angular error %.3g rad (%.4f degrees)\n", worst, worst * 180 / PM_PI);
	CHECKF(worst < 9e-4, "worst angular error %g rad", worst);
	CHECKF(flips == 0, "%d decoded directions not unit length", flips);
}

/* A grazing photon must stay on its side of the surface after quantization,
 * for arbitrary normals and for the axis-aligned ones of walls, where the
 * plane runs along the octahedral map's folds. */
TEST(grazing)
{
	pm_rng r = pm_rng_seed(4, 4);
	int wrong = 0, tested = 0, unconstrained = 0;
	double worst = 0;

	for (int t = 0; t < 2000000; t++) {
		pm_vec3 n = rand_dir(&r), tb, bb, d;
		if (t % 2) {
			int a = (int)(pm_rng_u32(&r) % 3);
			float s = pm_rng_u32(&r) & 1 ? 1.0f : -1.0f;
			n = pm_v3(a == 0 ? s : 0, a == 1 ? s : 0, a == 2 ? s : 0);
		}
		pm_basis(n, &tb, &bb);
		double a = 2 * PM_PI * pm_rng_f(&r);
		double eps = pow(10.0, -9 + 7 * pm_rng_f(&r)) * (pm_rng_u32(&r) & 1 ? 1 : -1);
		d = pm_norm(pm_add(pm_add(pm_scale(tb, (float)cos(a)), pm_scale(bb, (float)sin(a))),
		                   pm_scale(n, (float)eps)));
		float side = pm_dot(d, n);
		if (side == 0)
			continue;
		pm_photon p;
		/* without the normal the nearest code often lands on the wrong side */
		pm_photon_pack(&p, pm_v3(0, 0, 0), d, pm_v3(0, 0, 0), pm_v3(1, 1, 1));
		float s = pm_dot(pm_photon_dir(&p), n);
		unconstrained += side > 0 ? !(s > 0) : !(s < 0);
		pm_photon_pack(&p, pm_v3(0, 0, 0), d, n, pm_v3(1, 1, 1));
		pm_vec3 q = pm_photon_dir(&p);
		s = pm_dot(q, n);
		wrong += side > 0 ? !(s > 0) : !(s < 0);
		worst = fmax(worst, angle(d, q));
		tested++;
	}
	printf("# grazing: %d pairs, worst angular error with the side constraint %.3g rad\n",
	       tested, worst);
	CHECKF(tested > 1900000, "only %d pairs tested", tested);
	CHECKF(unconstrained > tested / 10, "only %d would flip unconstrained: the test is too easy", unconstrained);
	CHECKF(wrong == 0, "%d of %d grazing photons flipped side", wrong, tested);
	CHECKF(worst < 2e-3, "side constraint cost %g rad", worst);
}

static pm_photons
sample(int n)
{
	pm_photons ph;
	pm_rng r = pm_rng_seed(5, 5);
	pm_error err;

	memset(&ph, 0, sizeof ph);
	ph.h.version = 1;
	ph.h.count = (uint64_t)n;
	ph.h.emitted = 1000;
	ph.h.light_hash = 0x0123456789abcdefull;
	ph.h.time = 0.1;
	snprintf(ph.h.seeds, sizeof ph.h.seeds, "7,8");
	ph.p = calloc((size_t)n + 1, sizeof *ph.p);
	for (int i = 0; i < n; i++)
		pm_photon_pack(&ph.p[i], pm_v3(pm_rng_f(&r) * 3 - 1, pm_rng_f(&r) / 3, -pm_rng_f(&r) * 1e-7f),
		               rand_dir(&r), pm_v3(0, 0, 0), pm_v3(pm_rng_f(&r), pm_rng_f(&r), 1e-20f));
	pm_photons_add_history(&ph, "pm-shoot -s 7 scene.pms", &err);
	pm_photons_add_history(&ph, "pm-shoot -s 8 'my scene.pms'", &err);
	return ph;
}

TEST(file_round_trip)
{
	pm_photons a = sample(1000), b;
	pm_error err = {""};
	FILE *f = tmpfile();
	int rc;

	CHECK(f != NULL);
	if (!f)
		return;
	rc = pm_photons_write(&a, f, "t.pm", &err);
	CHECKF(rc == 0, "write: %s", err.msg);
	rewind(f);
	rc = pm_photons_read(&b, f, "t.pm", &err);
	CHECKF(rc == 0, "read: %s", err.msg);
	if (rc == 0) {
		float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
		for (int i = 0; i < 1000; i++)
			for (int k = 0; k < 3; k++) {
				lo[k] = fminf(lo[k], a.p[i].pos[k]);
				hi[k] = fmaxf(hi[k], a.p[i].pos[k]);
			}
		CHECK(b.h.version == 1 && b.h.kdtree == 0 && b.h.count == 1000 && b.h.emitted == 1000);
		CHECK(b.h.light_hash == 0x0123456789abcdefull && b.h.time == 0.1);
		CHECKF(strcmp(b.h.seeds, "7,8") == 0, "seeds '%s'", b.h.seeds);
		CHECKF(strcmp(b.h.history, "pm-shoot -s 7 scene.pms\npm-shoot -s 8 'my scene.pms'") == 0,
		       "history '%s'", b.h.history);
		for (int k = 0; k < 3; k++)
			CHECKF(b.h.bbox[k] == lo[k] && b.h.bbox[3 + k] == hi[k], "bbox axis %d: %.9g %.9g, want %.9g %.9g",
			       k, b.h.bbox[k], b.h.bbox[3 + k], lo[k], hi[k]);
		CHECK(memcmp(a.p, b.p, 1000 * sizeof *a.p) == 0);
		pm_photons_free(&b);
	}
	/* an empty file round-trips too, bbox all zeros */
	rewind(f);
	CHECK(ftruncate(fileno(f), 0) == 0);
	a.h.count = 0;
	CHECK(pm_photons_write(&a, f, "t.pm", &err) == 0);
	rewind(f);
	rc = pm_photons_read(&b, f, "t.pm", &err);
	CHECKF(rc == 0 && b.h.count == 0 && b.h.bbox[0] == 0 && b.h.bbox[5] == 0, "%s", err.msg);
	if (rc == 0)
		pm_photons_free(&b);
	fclose(f);
	pm_photons_free(&a);
}

/* ---- the reader's refusals, on hand-made files ------------------------ */

static unsigned char filebuf[1 << 17];

/* A valid 3-photon file with header line `key` replaced by `line` ("" drops
 * it; a key not present is appended), then `nrec` records and `extra` junk
 * bytes. Returns the length. */
static size_t
mkfile(const char *key, const char *line, int nrec, int extra, const pm_photon *recs)
{
	static const char *base[] = {
		"version=1", "endian=little", "record_size=20", "kdtree=0", "count=3",
		"emitted=10", "bbox=0 0 0 1 1 1", "light_hash=00000000000000ff",
		"time=0", "seeds=1", "command=mkphotons",
	};
	size_t n = 0;
	int used = 0;

	n += (size_t)sprintf((char *)filebuf + n, "PM-PHOTONS\n");
	for (size_t i = 0; i < sizeof base / sizeof *base; i++) {
		const char *l = base[i];
		if (key && strncmp(l, key, strlen(key)) == 0 && l[strlen(key)] == '=') {
			l = line;
			used = 1;
		}
		if (*l)
			n += (size_t)sprintf((char *)filebuf + n, "%s\n", l);
	}
	if (key && !used)
		n += (size_t)sprintf((char *)filebuf + n, "%s\n", line);
	filebuf[n++] = '\n';
	for (int i = 0; i < nrec; i++) {
		pm_photon p;
		if (recs)
			p = recs[i];
		else
			pm_photon_pack(&p, pm_v3(0.5f, 0.25f * (float)i, 1), pm_v3(0, 0, 1), pm_v3(0, 0, 1), pm_v3(1, 2, 3));
		pm_photon_encode(&p, filebuf + n);
		n += PM_PHOTON_BYTES;
	}
	for (int i = 0; i < extra; i++)
		filebuf[n++] = 'j';
	return n;
}

/* Reads filebuf[0..len) as `name`; returns the rc and leaves the message. */
static int
readbuf(size_t len, const char *name, pm_error *err)
{
	pm_photons ph;
	FILE *f = fmemopen(filebuf, len, "rb");
	int rc;

	if (!f)
		return -2;
	err->msg[0] = 0;
	rc = pm_photons_read(&ph, f, name, err);
	fclose(f);
	if (rc == 0)
		pm_photons_free(&ph);
	return rc;
}

#define REFUSE(len, name, want) do { \
	pm_error e_; int rc_ = readbuf((len), (name), &e_); \
	CHECKF(rc_ == -1 && strstr(e_.msg, (want)) != NULL, "rc %d, message '%s', want '%s'", rc_, e_.msg, (want)); \
	} while (0)

TEST(reader_accepts_base)
{
	pm_error e;
	int rc = readbuf(mkfile(NULL, NULL, 3, 0, NULL), "x.pm", &e);
	CHECKF(rc == 0, "%s", e.msg);
}

TEST(reader_refusals)
{
	REFUSE(mkfile(NULL, NULL, 2, 5, NULL), "-", "stdin: truncated: 3 photons promised, 2 present");
	REFUSE(mkfile(NULL, NULL, 3, 1, NULL), "x.pm", "'x.pm': trailing data after 3 photons");
	{
		size_t n = mkfile(NULL, NULL, 3, 0, NULL);
		filebuf[9] = 'Z';
		REFUSE(n, "x.pm", "'x.pm': not a photon file");
	}
	{
		pm_photons ph;
		pm_error e;
		FILE *f = tmpfile();
		int rc = pm_photons_read(&ph, f, "x.pm", &e);
		CHECKF(rc == -1 && strstr(e.msg, "'x.pm': empty, not a photon file"), "%s", e.msg);
		fclose(f);
	}
	/* a newer version is named even when it brings keys this pm lacks */
	REFUSE(mkfile("version", "version=3\nfancy=yes", 3, 0, NULL), "x.pm",
	       "'x.pm': photon file version 3 is newer than this pm (2)");
	REFUSE(mkfile("version", "version=0", 3, 0, NULL), "x.pm", "bad version '0'");
	REFUSE(mkfile("record_size", "record_size=24", 3, 0, NULL), "x.pm",
	       "'x.pm': line 4: record_size=24 is not supported");
	REFUSE(mkfile("endian", "endian=big", 3, 0, NULL), "x.pm", "endian=big is not supported");
	REFUSE(mkfile("seeds", "", 3, 0, NULL), "x.pm", "'x.pm': missing key 'seeds'");
	REFUSE(mkfile("color", "color=red", 3, 0, NULL), "x.pm", "line 13: unknown key 'color'");
	REFUSE(mkfile("count2", "count=3", 3, 0, NULL), "x.pm", "duplicate key 'count'");
	REFUSE(mkfile("count", "count=3x", 3, 0, NULL), "x.pm", "bad count '3x'");
	REFUSE(mkfile("count", "count=-3", 3, 0, NULL), "x.pm", "bad count '-3'");
	REFUSE(mkfile("count", "count=4294967296", 3, 0, NULL), "x.pm", "count 4294967296 exceeds the limit");
	REFUSE(mkfile("count", "count=99999999999999999999999", 3, 0, NULL), "x.pm", "bad count");
	REFUSE(mkfile("emitted", "emitted=0", 3, 0, NULL), "x.pm", "3 photons but emitted=0");
	REFUSE(mkfile("bbox", "bbox=0 0 0 1 1", 3, 0, NULL), "x.pm", "bad bbox");
	REFUSE(mkfile("bbox", "bbox=0 0 0 1 1 inf", 3, 0, NULL), "x.pm", "is not finite");
	REFUSE(mkfile("bbox", "bbox=0 0 0 1 0.3 1", 3, 0, NULL), "x.pm", "photon 2 lies outside the header's bbox");
	REFUSE(mkfile("bbox", "bbox=0 0 0 1 1 -1", 3, 0, NULL), "x.pm", "bbox minimum exceeds maximum");
	REFUSE(mkfile("time", "time=nan", 3, 0, NULL), "x.pm", "time 'nan' is not finite");
	REFUSE(mkfile("light_hash", "light_hash=123", 3, 0, NULL), "x.pm", "bad light_hash '123'");
	/* a file of the pm before light_hash hashed the scene file's bytes */
	REFUSE(mkfile("light_hash", "scene_hash=00000000000000ff", 3, 0, NULL), "x.pm",
	       "'x.pm': photon file of an older pm (it records scene_hash, not light_hash): shoot it again");
	REFUSE(mkfile("kdtree", "kdtree=2", 3, 0, NULL), "x.pm", "bad kdtree '2'");
	REFUSE(mkfile("seeds", "seeds=1;rm", 3, 0, NULL), "x.pm", "bad seeds");
	REFUSE(mkfile("time", "time", 3, 0, NULL), "x.pm", "expected key=value");
	{
		size_t n = mkfile(NULL, NULL, 0, 0, NULL);
		REFUSE(n - 5, "x.pm", "'x.pm': truncated header");
	}
	{
		/* photons that are not in kd order, flagged as a tree */
		pm_photon r[3];
		pm_photon_pack(&r[0], pm_v3(0.5f, 0.5f, 0.5f), pm_v3(0, 0, 1), pm_v3(0, 0, 1), pm_v3(1, 1, 1));
		pm_photon_pack(&r[1], pm_v3(0.9f, 0.5f, 0.5f), pm_v3(0, 0, 1), pm_v3(0, 0, 1), pm_v3(1, 1, 1));
		pm_photon_pack(&r[2], pm_v3(0.1f, 0.5f, 0.5f), pm_v3(0, 0, 1), pm_v3(0, 0, 1), pm_v3(1, 1, 1));
		pm_photon_set_axis(&r[0], 0);
		REFUSE(mkfile("kdtree", "kdtree=1", 3, 0, r), "x.pm",
		       "'x.pm': not a valid kd-tree: node 1 lies right of the split at node 0");
		pm_photon_set_axis(&r[0], 3);
		REFUSE(mkfile("kdtree", "kdtree=1", 3, 0, r), "x.pm", "node 0 has children but no split axis");
		/* swap the children and it is a valid tree */
		pm_photon t = r[1]; r[1] = r[2]; r[2] = t;
		pm_photon_set_axis(&r[0], 0);
		pm_error e;
		int rc = readbuf(mkfile("kdtree", "kdtree=1", 3, 0, r), "x.pm", &e);
		CHECKF(rc == 0, "%s", e.msg);
	}
}

TEST(reader_nan_position)
{
	pm_photon r[3];
	for (int i = 0; i < 3; i++)
		pm_photon_pack(&r[i], pm_v3(0.5f, 0.5f, 0.5f), pm_v3(0, 0, 1), pm_v3(0, 0, 1), pm_v3(1, 1, 1));
	r[1].pos[2] = NAN;
	REFUSE(mkfile(NULL, NULL, 3, 0, r), "x.pm", "'x.pm': photon 1 has a non-finite position");
	r[1].pos[2] = -INFINITY;
	REFUSE(mkfile(NULL, NULL, 3, 0, r), "x.pm", "'x.pm': photon 1 has a non-finite position");
}

TEST(reader_huge_count)
{
	/* 4 billion promised, 3 present: the reader must notice without first
	 * allocating 80 GB (the test would fail or crawl if it did). */
	clock_t t0 = clock();
	REFUSE(mkfile("count", "count=4294967295", 3, 0, NULL), "-",
	       "stdin: truncated: 4294967295 photons promised, 3 present");
	CHECKF(clock() - t0 < CLOCKS_PER_SEC, "took %g s", (double)(clock() - t0) / CLOCKS_PER_SEC);
}

TEST(reader_long_lines)
{
	static char line[70000];
	memset(line, 'x', sizeof line - 1);
	memcpy(line, "command=", 8);
	line[sizeof line - 1] = 0;
	pm_error e;
	size_t n = mkfile("command", line, 3, 0, NULL);
	CHECK(n < sizeof filebuf);
	int rc = readbuf(n, "x.pm", &e);
	CHECKF(rc == -1 && strstr(e.msg, "line 12: header line longer than 65536 bytes"), "%s", e.msg);
}

TEST(writer_refusals)
{
	pm_photons a = sample(4);
	pm_error err;
	FILE *f = fopen("/dev/null", "wb");

	a.p[2].pos[0] = NAN;
	CHECK(pm_photons_write(&a, f, "-", &err) == -1 && strstr(err.msg, "stdout: photon 2 has a non-finite position"));
	a.p[2].pos[0] = 0;
	a.h.emitted = 0;
	CHECK(pm_photons_write(&a, f, "o.pm", &err) == -1 && strstr(err.msg, "'o.pm': 4 photons but emitted=0"));
	a.h.emitted = 1;
	CHECK(pm_photons_add_history(&a, "a\nb", &err) == -1);
	CHECK(pm_photons_write(&a, f, "o.pm", &err) == 0);
	fclose(f);
	pm_photons_free(&a);
}

int
main(void)
{
	RUN(codec_round_trip);
	RUN(byte_layout);
	RUN(power_error);
	RUN(power_edges);
	RUN(direction_error);
	RUN(grazing);
	RUN(file_round_trip);
	RUN(reader_accepts_base);
	RUN(reader_refusals);
	RUN(reader_nan_position);
	RUN(reader_huge_count);
	RUN(reader_long_lines);
	RUN(writer_refusals);
	return check_done();
}
