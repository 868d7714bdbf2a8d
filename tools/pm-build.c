/* pm-build — merges photon files and builds the balanced kd-tree photon map
 * (formats/photons.md). Inputs are refused if they come from different
 * scenes or shutter times unless --force. */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/atomic.h"
#include "estimators/density.h"
#include "optics/frame.h"
#include "formats/kdtree.h"
#include "formats/photonfile.h"
#include "options.h"
#include "util.h"

static const char usage[] =
	"pm-build [-fhq] [--density SCENE [--density-pixels C] [--density-k K]] [-j THREADS] "
	"[-o FILE|-] [FILE ...|-]";

enum { DENSITY = OPT_LONG, DENSITY_PIXELS, DENSITY_K };

static const opt opts[] = {
	{ DENSITY, "density", "SCENE", "density control (Suykens & Willems 2000): thin the map where "
	  "it holds more than K photons in C pixel footprints of SCENE's camera, the dropped photons "
	  "handing their power to stored neighbours (see pm-build(1))", "off", 0 },
	{ DENSITY_PIXELS, "density-pixels", "C", "--density's smallest support, in pixel footprints", "2", 0 },
	{ DENSITY_K, "density-k", "K", "--density's photons per estimate (pm-render -k)", "50", 0 },
	{ 'f', "force", NULL, "merge inputs whose light_hash or time differ", "refuse", 0 },
	{ 'j', "threads", "THREADS", "threads, 0 for all cores; the output does not depend on it", "0", 1 },
	{ 'o', "output", "FILE", "the photon map to write, - for stdout", "-", 0 },
	{ 'q', "quiet", NULL, "no warnings", "warn on forced merges and empty maps", 1 },
	{ 0, NULL, NULL, NULL, NULL, 0 },
};

static const tool build = {
	usage,
	"Reads photon files (or maps) and writes one photon map: the records\n"
	"concatenated, emitted counts summed, then ordered as a balanced kd-tree.\n"
	"With no FILE, or FILE -, reads stdin.",
	opts, NULL,
};

/* --density: the scene posed at the map's time gives the camera. */
static void
control(pm_photons *map, const char *path, const pm_density_opts *o, int force)
{
	pm_scene s;
	pm_frame f;
	pm_error err;

	if (pm_scene_load(&s, path, &err))
		die_err(&err);
	if (s.light_hash != map->h.light_hash && !force)
		die("'%s': not the photons' scene (light_hash %016llx, the photons' %016llx); "
		    "--force uses it", path, (unsigned long long)s.light_hash,
		    (unsigned long long)map->h.light_hash);
	if (pm_frame_build(&f, &s, (float)map->h.time, 0, &err) ||
	    pm_density_control(&f, map, o, &err))
		die_err(&err);
	snprintf(map->h.density, sizeof map->h.density, "pixels %.6g k %d", o->pixels, o->k);
	pm_frame_free(&f);
	pm_scene_free(&s);
}

int
main(int argc, char **argv)
{
	static char *stdin_only[] = {"-"};
	const char *out = "-", *first = NULL;
	char **in, qa[600], qb[600];
	int force = 0, quiet = 0, nin, c;
	const char *dscene = NULL;
	int dgiven = 0;
	pm_density_opts dopt = {.k = 50, .pixels = 2};
	pm_photons acc;
	pm_error err;
	pm_out o;

	opt_init(&build, argc, argv);
	while ((c = opt_next(&build, argc, argv)) != -1) {
		switch (c) {
		case 'f': force = 1; break;
		case DENSITY: dscene = optarg; break;
		case DENSITY_PIXELS:
			dopt.pixels = parse_real(optarg, 1e-3, 1e6, "--density-pixels", usage);
			dgiven = 1;
			break;
		case DENSITY_K:
			dopt.k = (int)parse_int(optarg, 1, 100000, "--density-k", usage);
			dgiven = 1;
			break;
		case 'j': set_threads((int)parse_int(optarg, 0, 4096, "-j", usage)); break;
		case 'o': out = optarg; break;
		case 'q': quiet = 1; break;
		}
	}
	if (!dscene && dgiven)
		usage_err(usage, "--density-pixels and --density-k need --density SCENE");
	in = argv + optind;
	nin = argc - optind;
	if (nin == 0) {
		in = stdin_only;
		nin = 1;
	}
	check_output(usage, out, OUT_PHOTONS, in, nin);

	/* Read everything before opening the output, so a bad input leaves an
	 * existing output file untouched. */
	memset(&acc, 0, sizeof acc);
	for (int i = 0; i < nin; i++) {
		const char *name = in[i];
		FILE *f = open_input(name);
		pm_photons ph;
		unsigned differ;

		if (pm_photons_read(&ph, f, name, &err))
			die_err(&err);
		if (f != stdin)
			fclose(f);
		if (i == 0) {
			acc = ph;       /* takes the records and the history */
			first = name;
			continue;
		}
		differ = pm_photons_differ(&acc, &ph);
		/* Not even forced: a caustic map is a subset of a global one. */
		if (differ & PM_DIFFER_MAP)
			die("%s: a %s map, %s is a %s map: they cannot be merged",
			    shown_name(name, qa, sizeof qa), pm_map_name(ph.h.map),
			    shown_name(first, qb, sizeof qb), pm_map_name(acc.h.map));
		if (differ & PM_DIFFER_LIGHTS) {
			if (!force)
				die("%s: light_hash %016llx differs from %s (%016llx); --force merges anyway",
				    shown_name(name, qa, sizeof qa), (unsigned long long)ph.h.light_hash,
				    shown_name(first, qb, sizeof qb), (unsigned long long)acc.h.light_hash);
			if (!quiet)
				warn("%s: light_hash %016llx differs from %s; merging as forced",
				     shown_name(name, qa, sizeof qa), (unsigned long long)ph.h.light_hash,
				     shown_name(first, qb, sizeof qb));
		}
		if (differ & PM_DIFFER_TIME) {
			if (!force)
				die("%s: time %.9g differs from %s (%.9g); --force merges anyway",
				    shown_name(name, qa, sizeof qa), ph.h.time, shown_name(first, qb, sizeof qb), acc.h.time);
			if (!quiet)
				warn("%s: time %.9g differs from %s; the map keeps %.9g",
				     shown_name(name, qa, sizeof qa), ph.h.time, shown_name(first, qb, sizeof qb), acc.h.time);
		}
		if (pm_photons_merge(&acc, &ph, name, &err))
			die_err(&err);
		pm_photons_free(&ph);
	}
	if (acc.h.count == 0 && !quiet)
		warn("no photons: writing an empty photon map");
	if (pm_kd_build(acc.p, (size_t)acc.h.count, &err))
		die_err(&err);
	acc.h.kdtree = 1;
	if (dscene)
		control(&acc, dscene, &dopt, force);
	if (pm_photons_add_history(&acc, cmdline(), &err))
		die_err(&err);
	if (pm_out_open(&o, out, &err))
		die_err(&err);
	if (pm_photons_write(&acc, o.f, out, &err)) {
		pm_out_abort(&o);
		die_err(&err);
	}
	if (pm_out_commit(&o, &err))
		die_err(&err);
	pm_photons_free(&acc);
	return 0;
}
