/* pm-shoot — the light pass: photons from a scene's lights to a photon file. */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/atomic.h"
#include "optics/frame.h"
#include "base/pass.h"
#include "formats/photonfile.h"
#include "scene/scene.h"
#include "passes/shoot.h"
#include "bar.h"
#include "options.h"
#include "util.h"

static const char usage[] =
	"pm-shoot SCENE [-n PHOTONS] [--light-paths random|sobol] [-P I/N] [-s SEED] [-t TIME] "
	"[-j THREADS] [-o FILE|-] [--caustic CFILE [--caustic-photons N]] [--guide GFILE] [-q]";

enum { MAX_PHOTONS = OPT_LONG, LIGHT_PATHS, CAUSTIC, CAUSTIC_PHOTONS, GUIDE };

static const opt opts[] = {
	{ 'n', "photons", "PHOTONS", "photons to store, 1e6 or 2.5e5 allowed", "200000", 0 },
	{ LIGHT_PATHS, "light-paths", "random|sobol", "the light paths' numbers: pseudo-random, or "
	  "from scrambled Sobol' pairs (a low-discrepancy sequence; see pm-shoot(1))", "random", 0 },
	{ MAX_PHOTONS, "max-photons", "N", "refuse -n above N, against typos", "100000000: 2 GB", 0 },
	{ 'o', "output", "FILE", "output file, - for stdout", "-", 0 },
	{ CAUSTIC, "caustic", "CFILE", "also write the caustic photons of the same light paths "
	  "(those that reached a diffuse surface through mirrors, glass and strong glossy "
	  "surfaces only) to CFILE, a photon file with map=caustic; they stay in FILE too",
	  "none", 0 },
	{ CAUSTIC_PHOTONS, "caustic-photons", "N", "with --caustic, go on shooting until "
	  "CFILE holds N photons (it then counts its own emitted paths); caustics are "
	  "sharp and take many photons", "0: those of FILE's paths", 0 },
	{ GUIDE, "guide", "GFILE", "also write the photons the same light paths brought to "
	  "strong glossy surfaces (after the first bounce; FILE has none there) to GFILE, "
	  "a photon file with map=guide, for pm-render --guide", "none", 0 },
	{ 'P', "pass", "I/N", "pass I of N: seed and time derived from I and N (see pm-shoot(1)); "
	  "-s and -t, if given, override them", "no pass", 0 },
	{ 'q', "quiet", NULL, "quiet: no warnings, no progress bar", NULL, 1 },
	{ 's', "seed", "SEED", "random seed", "0", 0 },
	{ 't', "time", "TIME", "shutter time in [0,1] for moving objects", "0", 0 },
	{ 'j', "threads", "THREADS", "threads, 0 for all cores; the output does not depend on it", "0", 1 },
	{ 0, NULL, NULL, NULL, NULL, 0 },
};

static const tool shoot = {
	usage,
	"Traces photons from the lights of SCENE and writes a photon file\n"
	"(formats/photons.md).",
	opts, NULL,
};

/* A map written beside the main output (--caustic, --guide). */
typedef struct side_out {
	const char *name;
	pm_photons *ph;
	pm_out o;
} side_out;

/* Drops the first n side outputs (opened, not committed) and dies. */
static void
abort_side(side_out *side, int n, pm_error *err)
{
	for (int i = 0; i < n; i++)
		pm_out_abort(&side[i].o);
	die_err(err);
}

int
main(int argc, char **argv)
{
	pm_shoot_opts o = {.nphotons = 200000};
	uint64_t max_photons = 100000000;
	const char *out = "-", *cout = NULL, *gout = NULL;
	int c, threads = 0, quiet = 0, have_seed = 0, have_time = 0;
	uint32_t pass_i = 0, pass_n = 0;
	progress bar;
	pm_scene s;
	pm_frame fr;
	pm_photons ph, caus, guide;
	side_out side[2];
	int nside = 0;
	pm_out fo;
	pm_error err;

	opt_init(&shoot, argc, argv);
	while ((c = opt_next(&shoot, argc, argv)) != -1) {
		switch (c) {
		case 'j': threads = (int)parse_int(optarg, 0, 4096, "-j", usage); break;
		case LIGHT_PATHS:
			if ((o.light_paths = pm_light_paths_parse(optarg)) < 0)
				usage_err(usage, "--light-paths: unknown '%s' (random or sobol)", optarg);
			break;
		case MAX_PHOTONS: max_photons = (uint64_t)parse_int(optarg, 0, 4000000000LL, "--max-photons", usage); break;
		case 'n': o.nphotons = (uint64_t)parse_int(optarg, 0, 4000000000LL, "-n", usage); break;
		case 'o': out = optarg; break;
		case CAUSTIC: cout = optarg; break;
		case GUIDE: gout = optarg; break;
		case CAUSTIC_PHOTONS: o.ncaustic = (uint64_t)parse_int(optarg, 0, 4000000000LL, "--caustic-photons", usage); break;
		case 'P':
			if (pm_pass_parse(optarg, &pass_i, &pass_n, &err) != 0)
				usage_err(usage, "-P: %s", err.msg);
			break;
		case 'q': quiet = 1; break;
		case 's': o.seed = parse_u64(optarg, "-s", usage); have_seed = 1; break;
		case 't': o.time = (float)parse_real(optarg, 0, 1, "-t", usage); have_time = 1; break;
		}
	}
	if (argc - optind != 1)
		usage_err(usage, argc - optind == 0 ? "no scene given" : "too many arguments");
	if (o.nphotons > max_photons)
		usage_err(usage, "-n: %llu is more than %llu photons (a typo? --max-photons raises the limit)",
		          (unsigned long long)o.nphotons, (unsigned long long)max_photons);
	check_output(usage, out, OUT_PHOTONS, argv + optind, 1);
	if (o.ncaustic > 0 && !cout)
		usage_err(usage, "--caustic-photons needs --caustic CFILE");
	if (o.ncaustic > max_photons)
		usage_err(usage, "--caustic-photons: %llu is more than %llu photons (a typo? --max-photons raises the limit)",
		          (unsigned long long)o.ncaustic, (unsigned long long)max_photons);
	if (cout) {
		check_output(usage, cout, OUT_PHOTONS, argv + optind, 1);
		if (strcmp(cout, "-") == 0 || strcmp(cout, out) == 0)
			usage_err(usage, "--caustic: '%s' must be a file other than the output", cout);
		side[nside++] = (side_out){cout, &caus, {0}};
	}
	if (gout) {
		check_output(usage, gout, OUT_PHOTONS, argv + optind, 1);
		if (strcmp(gout, "-") == 0 || strcmp(gout, out) == 0 || (cout && strcmp(gout, cout) == 0))
			usage_err(usage, "--guide: '%s' must be a file other than the other outputs", gout);
		side[nside++] = (side_out){gout, &guide, {0}};
	}
	pm_pass_apply(pass_i, pass_n, &o.seed, &have_seed, &o.time, &have_time);
	set_threads(threads);

	if (pm_scene_load(&s, argv[optind], &err) != 0)
		die_err(&err);
	if (pm_frame_build(&fr, &s, o.time, 0, &err) != 0)
		die_err(&err);
	progress_start(&bar, "photons", o.nphotons, quiet);
	o.progress = progress_hook;
	o.progress_arg = &bar;
	o.caustic = cout ? &caus : NULL;
	o.guide = gout ? &guide : NULL;
	if (pm_shoot(&s, fr.accel, &fr.lights, &o, &ph, &err) != 0)
		die_err(&err);
	progress_end(&bar, ph.h.count);
	if (ph.h.count < o.nphotons && !quiet)
		warn("'%s': only %llu of %llu photons stored after %llu light paths",
		     argv[optind], (unsigned long long)ph.h.count,
		     (unsigned long long)o.nphotons, (unsigned long long)ph.h.emitted);
	if (pm_photons_add_history(&ph, cmdline(), &err) != 0)
		die_err(&err);
	/* All outputs are written whole before any appears. */
	for (int i = 0; i < nside; i++) {
		if (pm_photons_add_history(side[i].ph, cmdline(), &err) != 0 ||
		    pm_out_open(&side[i].o, side[i].name, &err) != 0)
			abort_side(side, i, &err);
		if (pm_photons_write(side[i].ph, side[i].o.f, side[i].o.path, &err) != 0)
			abort_side(side, i + 1, &err);
	}
	if (pm_out_open(&fo, out, &err) != 0)
		abort_side(side, nside, &err);
	if (pm_photons_write(&ph, fo.f, fo.path, &err) != 0) {
		pm_out_abort(&fo);
		abort_side(side, nside, &err);
	}
	for (int i = 0; i < nside; i++)
		if (pm_out_commit(&side[i].o, &err) != 0) {
			pm_out_abort(&fo);
			abort_side(side + i + 1, nside - i - 1, &err);
		}
	if (pm_out_commit(&fo, &err) != 0)
		die_err(&err);
	for (int i = 0; i < nside; i++)
		pm_photons_free(side[i].ph);
	pm_photons_free(&ph);
	pm_frame_free(&fr);
	pm_scene_free(&s);
	return 0;
}
