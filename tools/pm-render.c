/* pm-render — the view pass: a scene and its photon map to an EXR image. */
#define _GNU_SOURCE
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "estimators/estimate.h"
#include "estimators/estimators.h"
#include "optics/frame.h"
#include "passes/gather.h"
#include "formats/image.h"
#include "estimators/irradiance.h"
#include "base/pass.h"
#include "formats/passid.h"
#include "formats/photonfile.h"
#include "passes/render.h"
#include "scene/scene.h"
#include "bar.h"
#include "options.h"
#include "util.h"

static const char est_default[] = "compensated";
static char usage[768], est_help[512];

/* The usage line and -e's help, with the estimators from their table. */
static void
make_usage(void)
{
	char names[256] = "";
	size_t n = 0;

	for (const pm_estimator *e = pm_estimators; e->name; e++) {
		int w = snprintf(names + n, sizeof names - n, "%s%s", n ? "|" : "", e->name);
		if (w < 0 || (size_t)w >= sizeof names - n)
			break;
		n += (size_t)w;
	}
	snprintf(usage, sizeof usage,
	         "pm-render SCENE [MAP|-] [-e %s] [-k K] [--classical-norm k|k-1] [-p SAMPLES] "
	         "[-l N] [--estimates pixel|sample] [--past-glossy N] [-g RAYS [--caustic CMAP] [--irradiance EVERY] [--guided]] [--guide GMAP] "
	         "[-P I/N] [--consistent ALPHA] [-s SEED] [-t TIME] [-j THREADS] [-q] [--force] -o OUT.exr",
	         names);
	n = (size_t)snprintf(est_help, sizeof est_help, "estimator:");
	for (const pm_estimator *e = pm_estimators; e->name && n < sizeof est_help; e++)
		n += (size_t)snprintf(est_help + n, sizeof est_help - n, " %s: %s;", e->name, e->help);
	if (n > 0 && n < sizeof est_help && est_help[n - 1] == ';')
		est_help[n - 1] = 0;
}

enum { FORCE = OPT_LONG, MAX_SAMPLES, CLASSICAL_NORM, ESTIMATES, CAUSTIC, IRRADIANCE, GUIDED,
       CONSISTENT, GUIDE, PAST_GLOSSY };

static const opt opts[] = {
	{ 'e', "estimator", "EST", est_help, est_default, 0 },
	{ 'g', "gather", "RAYS", "final gathering with RAYS gather rays per pixel (shared among "
	  "the -p samples, each taking RAYS/SAMPLES rounded up): at the first diffuse or soft "
	  "glossy hit the rays sample the BSDF and read the estimate (-e) where they land, "
	  "instead of the estimate shown there; 0 shows the estimate", "0: off", 0 },
	{ CAUSTIC, "caustic", "CMAP", "with -g, the caustic map (pm-shoot --caustic, built), "
	  "shown directly; without it gather rays find caustics by themselves (noisier)",
	  "none", 0 },
	{ IRRADIANCE, "irradiance", "EVERY", "with -g, precompute the estimate at every "
	  "EVERY-th photon of MAP (Christensen 1999), so a gather ray landing on a diffuse "
	  "surface reads the nearest of those instead of estimating; 0 estimates at each",
	  "4", 0 },
	{ GUIDED, "guided", NULL, "with -g, draw half the gather rays from the incoming "
	  "directions of the photons near the point (Jensen 1995); the mean stays that of "
	  "BSDF sampling", "BSDF sampling only", 0 },
	{ GUIDE, "guide", "GMAP", "the guide map (pm-shoot --guide, built): camera paths go on "
	  "from strong glossy surfaces in directions drawn half from the incoming directions "
	  "of its photons near the point (Jensen 1995), half from the BSDF; the mean stays "
	  "that of BSDF sampling", "BSDF sampling only", 0 },
	{ 'j', "threads", "THREADS", "threads, 0 for all cores; the output does not depend on it", "0", 1 },
	{ 'k', "neighbours", "K", "nearest photons per estimate", "50", 0 },
	{ CLASSICAL_NORM, "classical-norm", "k|k-1", "the classical estimate's flux over pi r^2: of "
	  "all k photons (k, Jensen's) or scaled by (k-1)/k "
	  "(k-1: unbiased on flat, evenly lit surfaces, where k reads "
	  "bright by 1/(k-1)); k-1 needs -e classical and -k 2 or more", "k", 0 },
	{ 'o', "output", "OUT.exr", "output image, - for stdout (to pipe into pm-tonemap - or "
	  "pm-average -)", "none: required", 0 },
	{ 'p', "samples", "SAMPLES", "camera samples per pixel", "16", 0 },
	{ 'l', "light-samples", "N", "shadow rays per camera sample where its direct light is "
	  "taken first and where it meets the photon estimate; cheap next to the estimate, "
	  "they take the noise out of soft shadows", "4; 1 with -e path", 0 },
	{ ESTIMATES, "estimates", "pixel|sample", "the photon estimate at a first hit: once per "
	  "pixel and polygon seen (pixel; likewise past a chain of mirrors and glass), or at "
	  "every camera sample (sample, up to -p times the cost); the expected image is the "
	  "same", "pixel", 0 },
	{ PAST_GLOSSY, "past-glossy", "N", "with --estimates pixel, the photon estimate where a "
	  "camera path lands past a bounce that shares nothing (a strong glossy lobe, a "
	  "textured mirror): taken at one camera sample in N of each pixel, the others' "
	  "weight given to those taken; the expected image is the same; 1 takes it at every "
	  "sample; a gather (-g) is not affected", "4", 0 },
	{ MAX_SAMPLES, "max-samples", "N", "refuse -p above N, against typos", "65536", 0 },
	{ 'P', "pass", "I/N", "pass I of N: seed and time derived from I and N, as pm-shoot -P "
	  "does (see pm-render(1)); -s and -t override them", "no pass", 0 },
	{ CONSISTENT, "consistent", "ALPHA", "the consistent mode: pass I of -P I/N shrinks the "
	  "estimate's support (the classical disc's radius, the compensated cube's half-size) "
	  "found with K photons by I^((ALPHA-1)/2), 0 < ALPHA < 1 (2/3 is usual), so that "
	  "averages of passes 1..N converge to the exact image (see pm-render(1))", "off: fixed K", 0 },
	{ 'q', "quiet", NULL, "quiet: no progress bar", NULL, 1 },
	{ 's', "seed", "SEED", "random seed", "0", 0 },
	{ 't', "time", "TIME", "shutter time in [0,1]", "the map's time, else 0", 0 },
	{ FORCE, "force", NULL, "render even if MAP was made from another scene or time", NULL, 0 },
	{ 0, NULL, NULL, NULL, NULL, 0 },
};

static const tool render = {
	usage,
	"Renders SCENE's view pass with photon map MAP (- for stdin) to an EXR\n"
	"(formats/image.md).",
	opts, NULL,
};

static void
setattr(pm_image *img, const char *k, const char *v)
{
	pm_error err;

	if (pm_image_set_attr(img, k, v, &err) != 0)
		die_err(&err);
}

/* pm.consistent is what pm-average checks passes agree on; pm.shrink is
 * this pass's own scale. */
static void
consistent_attrs(pm_image *img, double alpha, double shrink)
{
	char buf[64];

	if (alpha > 0)
		snprintf(buf, sizeof buf, "alpha %.9g", alpha);
	setattr(img, "pm.consistent", alpha > 0 ? buf : "off");
	snprintf(buf, sizeof buf, "%.9g", alpha > 0 ? shrink : 1.0);
	setattr(img, "pm.shrink", buf);
}

/* 1 if path begins as a photon file does. */
static int
is_photon_file(const char *path)
{
	char b[sizeof PM_PHOTONS_MAGIC - 1];
	FILE *f = fopen(path, "rb");
	int yes = f && fread(b, 1, sizeof b, f) == sizeof b && !memcmp(b, PM_PHOTONS_MAGIC, sizeof b);

	if (f)
		fclose(f);
	return yes;
}

/* Reads a photon map (not a plain photon file) or dies. */
static void
read_map(const char *name, pm_photons *m)
{
	FILE *f = open_input(name);
	pm_error err;

	if (pm_photons_read(m, f, name, &err) != 0)
		die_err(&err);
	if (f != stdin)
		fclose(f);
	if (!m->h.kdtree)
		die("'%s': a photon file, not a photon map: run it through pm-build", name);
}

int
main(int argc, char **argv)
{
	pm_render_opts o = {.estimator = pm_estimator_find(est_default), .k = 50, .spp = 16,
	                    .estimate_once = 1, .past_glossy = 4};
	const char *out = NULL, *mapname = NULL, *cname = NULL, *gname = NULL;
	int gather_rays = 0, irr_every = 4, guided = 0;
	pm_gather_opts go = {0};
	pm_photons cmap = {0}, gmap = {0};
	pm_irradiance irr = {0};
	int c, threads = 0, force = 0, have_time = 0, have_seed = 0, quiet = 0, max_spp = 65536;
	uint32_t pass_i = 0, pass_n = 0;
	progress bar;
	float time = 0;
	double alpha = 0;
	pm_scene s;
	pm_photons map = {0};
	pm_frame fr;
	pm_image img;
	pm_error err;
	char buf[64], *hist;

	make_usage();
	opt_init(&render, argc, argv);
	while ((c = opt_next(&render, argc, argv)) != -1) {
		switch (c) {
		case 'e':
			if (!(o.estimator = pm_estimator_find(optarg)))
				usage_err(usage, "-e: unknown estimator '%s'", optarg);
			break;
		case FORCE: force = 1; break;
		case 'g': gather_rays = (int)parse_int(optarg, 0, 1 << 20, "-g", usage); break;
		case CAUSTIC: cname = optarg; break;
		case IRRADIANCE: irr_every = (int)parse_int(optarg, 0, 1 << 20, "--irradiance", usage); break;
		case GUIDED: guided = 1; break;
		case GUIDE: gname = optarg; break;
		case CONSISTENT:
			alpha = parse_real(optarg, 0, 1, "--consistent", usage);
			if (!(alpha > 0 && alpha < 1))
				usage_err(usage, "--consistent: ALPHA must be between 0 and 1, not %s", optarg);
			break;
		case 'j': threads = (int)parse_int(optarg, 0, 4096, "-j", usage); break;
		case 'k': o.k = (int)parse_int(optarg, 1, 100000, "-k", usage); break;
		case 'o': out = optarg; break;
		case CLASSICAL_NORM:
			if ((o.classical_norm = pm_classical_norm_parse(optarg)) < 0)
				usage_err(usage, "--classical-norm: unknown normalisation '%s' (k or k-1)", optarg);
			break;
		case MAX_SAMPLES: max_spp = (int)parse_int(optarg, 1, 1 << 30, "--max-samples", usage); break;
		case 'l': o.light_samples = (int)parse_int(optarg, 1, 4096, "-l", usage); break;
		case ESTIMATES:
			if (!strcmp(optarg, "pixel") || !strcmp(optarg, "sample"))
				o.estimate_once = !strcmp(optarg, "pixel");
			else
				usage_err(usage, "--estimates: '%s' is neither pixel nor sample", optarg);
			break;
		case PAST_GLOSSY: o.past_glossy = (int)parse_int(optarg, 1, 1 << 30, "--past-glossy", usage); break;
		case 'p': o.spp = (int)parse_int(optarg, 1, 1 << 30, "-p", usage); break;
		case 'P':
			if (pm_pass_parse(optarg, &pass_i, &pass_n, &err) != 0)
				usage_err(usage, "-P: %s", err.msg);
			break;
		case 'q': quiet = 1; break;
		case 's': o.seed = parse_u64(optarg, "-s", usage); have_seed = 1; break;
		case 't': time = (float)parse_real(optarg, 0, 1, "-t", usage); have_time = 1; break;
		}
	}
	if (argc - optind < 1)
		usage_err(usage, "no scene given");
	if (argc - optind > 2)
		usage_err(usage, "too many arguments");
	if (argc - optind == 2)
		mapname = argv[optind + 1];
	if (!mapname && (o.estimator->needs & PM_NEEDS_MAP))
		usage_err(usage, "the %s estimate needs a photon map (or use -e path)",
		          o.estimator->name);
	if (!out)
		usage_err(usage, "no output given (-o OUT.exr)");
	if (o.classical_norm == PM_NORM_K1 && !(o.estimator->needs & PM_TAKES_NORM))
		usage_err(usage, "--classical-norm k-1 is for -e classical, not %s",
		          o.estimator->name);
	if (o.classical_norm == PM_NORM_K1 && o.k < 2)
		usage_err(usage, "--classical-norm k-1 needs -k 2 or more (one photon would give 0)");
	if (gather_rays > 0 && !o.estimator->estimate)
		usage_err(usage, "-g gathers with a photon estimate (-e classical or compensated), not %s",
		          o.estimator->name);
	if (cname && gather_rays == 0)
		usage_err(usage, "--caustic is shown only when gathering (-g RAYS)");
	if (guided && gather_rays == 0)
		usage_err(usage, "--guided steers gather rays: give -g RAYS");
	if (o.spp > max_spp)
		usage_err(usage, "-p: %d is more than %d samples per pixel (a typo? --max-samples raises the limit)",
		          o.spp, max_spp);
	if (alpha > 0 && pass_n == 0)
		usage_err(usage, "--consistent needs -P I/N: the pass index sets the support");
	if (alpha > 0 && (!o.estimator->estimate || !(o.estimator->needs & PM_NEEDS_MAP)))
		usage_err(usage, "--consistent is for estimates from a photon map, not -e %s",
		          o.estimator->name);
	if (alpha > 0)
		o.shrink = pm_pass_shrink(pass_i, alpha);
	/* Measured (BENCHMARKS.md, "Levers"): next to a photon estimate four
	 * shadow rays pay for themselves; in the path tracer, whose every
	 * camera sample already costs a whole path, one does. */
	if (!o.light_samples)
		o.light_samples = o.estimator->estimate && (o.estimator->needs & PM_NEEDS_MAP) ? 4 : 1;
	check_output(usage, out, OUT_EXR, argv + optind, argc - optind);
	if (cname || gname) {
		char *ins[3] = {(char *)mapname, (char *)cname, (char *)gname};
		int nin = 0;
		for (int i = 0; i < 3; i++)
			if (ins[i])
				ins[nin++] = ins[i];
		check_output(usage, out, OUT_EXR, ins + (mapname != NULL), nin - (mapname != NULL));
		check_stdin_once(usage, ins, nin);
	}
	pm_pass_apply(pass_i, pass_n, &o.seed, &have_seed, &time, &have_time);
	set_threads(threads);

	if (pm_scene_load(&s, argv[optind], &err) != 0) {
		if (mapname && is_photon_file(argv[optind]))
			die("'%s': a photon file where the scene belongs: the order is SCENE MAP", argv[optind]);
		die_err(&err);
	}
	if (mapname) {
		read_map(mapname, &map);
		if (map.h.light_hash != s.light_hash && !force)
			die("'%s': photon map of another scene (light_hash %016" PRIx64 ", '%s' has %016" PRIx64
			    ": its geometry, materials or lights differ); --force to use it",
			    mapname, map.h.light_hash, argv[optind], s.light_hash);
		if (have_time && map.h.time != time && !force)
			die("'%s': photon map is of time %g, not %g; --force to use it", mapname, map.h.time, time);
		if (!have_time)
			time = (float)map.h.time;
	}
	if (cname) {
		read_map(cname, &cmap);
		if (cmap.h.map != PM_MAP_CAUSTIC)
			die("'%s': a %s map where the caustic map belongs (pm-shoot --caustic makes one)",
			    cname, pm_map_name(cmap.h.map));
		if (pm_photons_differ(&map, &cmap) & (PM_DIFFER_LIGHTS | PM_DIFFER_TIME) && !force)
			die("'%s': caustic map of another scene or time than '%s'; --force to use it", cname, mapname);
	}
	if (mapname && map.h.map != PM_MAP_GLOBAL)
		die("'%s': a %s map where the global map belongs: give it as --%s", mapname,
		    pm_map_name(map.h.map), pm_map_name(map.h.map));
	if (gname) {
		read_map(gname, &gmap);
		if (gmap.h.map != PM_MAP_GUIDE)
			die("'%s': a %s map where the guide map belongs (pm-shoot --guide makes one)",
			    gname, pm_map_name(gmap.h.map));
		if ((gmap.h.light_hash != s.light_hash || gmap.h.time != time) && !force)
			die("'%s': guide map of another scene or time than '%s'; --force to use it",
			    gname, argv[optind]);
		o.guide = &gmap;
	}
	if (pm_frame_build(&fr, &s, time, o.estimator->needs, &err) != 0)
		die_err(&err);
	if (gather_rays > 0) {
		go.rays = (gather_rays + o.spp - 1) / o.spp;
		go.caustic = cname ? &cmap : NULL;
		go.guided = guided;
		if (irr_every > 0) {
			pm_est_in in = {&s, fr.accel, &map, fr.pi, o.k, o.classical_norm, o.shrink};
			if (pm_irradiance_build(&irr, o.estimator, &in, irr_every, &err) != 0)
				die_err(&err);
			go.irr = &irr;
		}
		o.gather = &go;
	}
	progress_start(&bar, "rows", (uint64_t)s.camera.height, quiet);
	o.progress = progress_hook;
	o.progress_arg = &bar;
	if (pm_render(&fr, mapname ? &map : NULL, &o, &img, &err) != 0)
		die_err(&err);
	progress_end(&bar, (uint64_t)s.camera.height);

	hist = malloc((map.h.history ? strlen(map.h.history) : 0) + strlen(cmdline()) + 2);
	if (!hist)
		die("out of memory");
	sprintf(hist, "%s%s%s", map.h.history ? map.h.history : "",
	        map.h.history && *map.h.history ? "\n" : "", cmdline());
	setattr(&img, "pm.command", hist);
	free(hist);
	snprintf(buf, sizeof buf, "%" PRIu64, o.seed);
	setattr(&img, "pm.seed", buf);
	snprintf(buf, sizeof buf, "%.9g", time);
	setattr(&img, "pm.time", buf);
	setattr(&img, "pm.passes", "1");
	snprintf(buf, sizeof buf, "%d", o.spp);
	setattr(&img, "pm.spp", buf);
	snprintf(buf, sizeof buf, "%d", o.light_samples);
	setattr(&img, "pm.light_samples", buf);
	setattr(&img, "pm.estimates", o.estimate_once ? "pixel" : "sample");
	snprintf(buf, sizeof buf, "%d", o.estimate_once && o.estimator->estimate ? o.past_glossy : 1);
	setattr(&img, "pm.past_glossy", buf);
	snprintf(buf, sizeof buf, "%" PRIu64, map.h.count);
	setattr(&img, "pm.photons", buf);
	snprintf(buf, sizeof buf, "%" PRIu64, map.h.emitted);
	setattr(&img, "pm.emitted", buf);
	snprintf(buf, sizeof buf, "%016" PRIx64, s.view_hash);
	setattr(&img, "pm.scene_hash", buf);
	setattr(&img, "pm.estimator", o.estimator->name);
	setattr(&img, "pm.light_paths", mapname ? map.h.light_paths : "none");
	setattr(&img, "pm.density", mapname ? map.h.density : "none");
	snprintf(buf, sizeof buf, "%d", o.k);
	setattr(&img, "pm.k", buf);
	if (gather_rays > 0) {
		char g[160];
		snprintf(g, sizeof g, "%d rays per sample, caustic map %s, irradiance %s%.0d, %s",
		         go.rays, cname ? "yes" : "no", irr_every ? "every " : "off", irr_every,
		         guided ? "guided" : "BSDF sampling");
		setattr(&img, "pm.gather", g);
		snprintf(buf, sizeof buf, "%" PRIu64, cmap.h.count);
		setattr(&img, "pm.caustic_photons", buf);
	}
	if (gname) {
		snprintf(buf, sizeof buf, "%" PRIu64, gmap.h.count);
		setattr(&img, "pm.guide_photons", buf);
	}
	consistent_attrs(&img, alpha, o.shrink);
	snprintf(buf, sizeof buf, "%016" PRIx64, pm_pass_id(s.view_hash, o.estimator->name,
	                                                     o.seed, time, map.h.seeds));
	setattr(&img, "pm.pass_ids", buf);
	if (pm_image_write_exr(&img, out, &err) != 0)
		die_err(&err);

	pm_image_free(&img);
	pm_frame_free(&fr);
	pm_photons_free(&map);
	pm_photons_free(&cmap);
	pm_photons_free(&gmap);
	pm_irradiance_free(&irr);
	pm_scene_free(&s);
	return 0;
}
