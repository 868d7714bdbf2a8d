/* mkphotons.c — test helper: writes a photon file (kdtree=0, as pm-shoot
 * would) of N seeded random photons lying on axis-aligned planes, so the
 * photon tools can be tested without a light pass.
 *
 * Each photon: a plane chosen in turn from the -p list; position uniform in
 * [0,1)^2 on that plane; direction uniform over the hemisphere around the
 * plane's +axis normal; power per channel uniform in [0.5, 1.5). */
#define _GNU_SOURCE
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/atomic.h"
#include "formats/photonfile.h"
#include "base/rng.h"

static const char usage[] =
	"usage: mkphotons [-h] [-e EMITTED] [-H HASH] [-n N] [-o FILE] [-p AXIS=VALUE]... [-s SEED] [-t TIME]\n"
	"  -e EMITTED     emitted paths recorded in the header (default: N, at least 1)\n"
	"  -H HASH        light_hash, 16 hex digits (default: 00000000000000aa)\n"
	"  -n N           photons (default: 1000)\n"
	"  -o FILE        output, '-' for stdout (default: -)\n"
	"  -p AXIS=VALUE  a plane, e.g. y=0; repeatable (default: y=0)\n"
	"  -s SEED        random seed (default: 1)\n"
	"  -t TIME        shutter time (default: 0)\n";

static void
fail(const char *msg, const char *arg)
{
	fprintf(stderr, "mkphotons: %s '%s'\n%s", msg, arg, usage);
	exit(2);
}

static unsigned long long
num(const char *s, int base)
{
	char *end;
	unsigned long long v = strtoull(s, &end, base);
	if (end == s || *end || *s == '-')
		fail("bad number", s);
	return v;
}

int
main(int argc, char **argv)
{
	unsigned long long n = 1000, emitted = 0, seed = 1, hash = 0xaa;
	const char *out = "-";
	double t = 0;
	int axes[64], nplanes = 0, c;
	float vals[64];
	char cmd[4096];
	size_t cl = 0;
	pm_photons ph;
	pm_error err;
	pm_out o;

	while ((c = getopt(argc, argv, "e:H:hn:o:p:s:t:")) != -1) {
		switch (c) {
		case 'e': emitted = num(optarg, 10); break;
		case 'H': hash = num(optarg, 16); break;
		case 'h': fputs(usage, stdout); return 0;
		case 'n': n = num(optarg, 10); break;
		case 'o': out = optarg; break;
		case 'p': {
			char *end;
			if (nplanes == 64 || !strchr("xyz", optarg[0]) || optarg[0] == 0 || optarg[1] != '=')
				fail("bad plane", optarg);
			axes[nplanes] = optarg[0] - 'x';
			vals[nplanes] = strtof(optarg + 2, &end);
			if (end == optarg + 2 || *end)
				fail("bad plane", optarg);
			nplanes++;
			break;
		}
		case 's': seed = num(optarg, 10); break;
		case 't': {
			char *end;
			t = strtod(optarg, &end);
			if (end == optarg || *end)
				fail("bad time", optarg);
			break;
		}
		default: fputs(usage, stderr); return 2;
		}
	}
	if (optind != argc)
		fail("unexpected argument", argv[optind]);
	if (n > 100000000)
		fail("too many photons", "-n");
	if (nplanes == 0) {
		axes[0] = 1;
		vals[0] = 0;
		nplanes = 1;
	}
	for (int i = 0; i < argc && cl < sizeof cmd - 1; i++)
		cl += (size_t)snprintf(cmd + cl, sizeof cmd - cl, "%s%s", i ? " " : "", i ? argv[i] : "mkphotons");
	memset(&ph, 0, sizeof ph);
	ph.h.version = PM_PHOTONS_VERSION;
	ph.h.count = n;
	ph.h.emitted = emitted ? emitted : n ? n : 1;
	ph.h.light_hash = hash;
	ph.h.time = t;
	snprintf(ph.h.seeds, sizeof ph.h.seeds, "%llu", seed);
	ph.p = malloc((n ? n : 1) * sizeof *ph.p);
	if (!ph.p || pm_photons_add_history(&ph, cmd, &err)) {
		fprintf(stderr, "mkphotons: out of memory\n");
		return 1;
	}
	for (unsigned long long i = 0; i < n; i++) {
		pm_rng r = pm_rng_seed(seed, i);
		int a = axes[i % (unsigned)nplanes];
		float x[3], pw[3], u = pm_rng_f(&r), v = pm_rng_f(&r);
		x[a] = vals[i % (unsigned)nplanes];
		x[(a + 1) % 3] = u;
		x[(a + 2) % 3] = v;
		/* uniform hemisphere: cos theta uniform in (0, 1] */
		float ct = 1 - pm_rng_f(&r), phi = 6.2831853f * pm_rng_f(&r), st = sqrtf(1 - ct * ct);
		float d[3];
		d[a] = ct;
		d[(a + 1) % 3] = st * cosf(phi);
		d[(a + 2) % 3] = st * sinf(phi);
		for (int k = 0; k < 3; k++)
			pw[k] = 0.5f + pm_rng_f(&r);
		pm_vec3 nrm = pm_v3(a == 0, a == 1, a == 2);
		pm_photon_pack(&ph.p[i], pm_v3(x[0], x[1], x[2]), pm_norm(pm_v3(d[0], d[1], d[2])), nrm,
		               pm_v3(pw[0], pw[1], pw[2]));
	}
	if (pm_out_open(&o, out, &err) || pm_photons_write(&ph, o.f, out, &err)) {
		pm_out_abort(&o);
		fprintf(stderr, "mkphotons: %s\n", err.msg);
		return 1;
	}
	if (pm_out_commit(&o, &err)) {
		fprintf(stderr, "mkphotons: %s\n", err.msg);
		return 1;
	}
	pm_photons_free(&ph);
	return 0;
}
