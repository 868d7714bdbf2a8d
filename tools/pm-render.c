/* pm-render — the view pass: a scene and its photon map to an EXR image. */
#define _GNU_SOURCE
#include <getopt.h>
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "accel.h"
#include "estimate.h"
#include "image.h"
#include "light.h"
#include "pass.h"
#include "passid.h"
#include "photonfile.h"
#include "render.h"
#include "scene.h"
#include "progress.h"
#include "util.h"

static const char usage[] =
	"pm-render SCENE [MAP|-] [-e classical|compensated|path|photons] [-k K] [--classical-norm k|k-1] [-p SAMPLES] "
	"[-P I/N] [-s SEED] [-t TIME] [-j THREADS] [-q] [--force] -o OUT.exr";

_Noreturn static void
help(void)
{
	printf("usage: %s\n"
	       "Renders SCENE's view pass with photon map MAP (- for stdin) to an EXR (formats/image.md).\n"
	       "  -e EST      estimator: classical, compensated, path or photons (default\n"
	       "              compensated); path is an unbiased path tracer and needs no MAP;\n"
	       "              photons shows MAP's photons as seen from the camera\n"
	       "  -j THREADS  threads, 0 for all cores (default 0); the output does not depend on it\n"
	       "  -k K        nearest photons per estimate (default 50)\n"
	       "  --classical-norm k|k-1  the classical estimate's flux over pi r^2: of\n"
	       "              all k photons (k, Jensen's, the default) or scaled by (k-1)/k\n"
	       "              (k-1: unbiased on flat, evenly lit surfaces, where k reads\n"
	       "              bright by 1/(k-1)); k-1 needs -e classical and -k 2 or more\n"
	       "  -o OUT.exr  output image, - for stdout (to pipe into pm-tonemap - or\n"
	       "              pm-average -) (required)\n"
	       "  -p SAMPLES  camera samples per pixel (default 4)\n"
	       "  --max-samples N  refuse -p above N, against typos (default 65536)\n"
	       "  -P I/N      pass I of N: seed and time derived from I and N, as pm-shoot -P\n"
	       "              does (see pm-render(1)); -s and -t override them (default: no pass)\n"
	       "  -q          quiet: no progress bar\n"
	       "  -s SEED     random seed (default 0)\n"
	       "  -t TIME     shutter time in [0,1] (default: the map's time, else 0)\n"
	       "  --force     render even if MAP was made from another scene or time\n"
	       "  -h          this help\n", usage);
	exit(0);
}

static void
setattr(pm_image *img, const char *k, const char *v)
{
	pm_error err;

	if (pm_image_set_attr(img, k, v, &err) != 0)
		die_err(&err);
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

int
main(int argc, char **argv)
{
	static const struct option longopts[] = {
		{"force", no_argument, NULL, 'F'},
		{"max-samples", required_argument, NULL, 'M'},
		{"classical-norm", required_argument, NULL, 'N'},
		{"help", no_argument, NULL, 'h'},
		{0, 0, 0, 0},
	};
	pm_render_opts o = {.estimator = PM_EST_COMPENSATED, .k = 50, .spp = 4};
	const char *out = NULL, *mapname = NULL;
	int c, threads = 0, force = 0, have_time = 0, have_seed = 0, quiet = 0, max_spp = 65536;
	uint32_t pass_i = 0, pass_n = 0;
	progress bar;
	float time = 0;
	pm_scene s;
	pm_photons map = {0};
	pm_vec3 *verts;
	pm_accel *a;
	pm_lights L;
	pm_polyindex *pi = NULL;
	pm_image img;
	pm_error err;
	char buf[64], *hist;

	util_init(argc, argv);
	opterr = 0;
	while ((c = getopt_long(argc, argv, "e:hj:k:o:p:P:qs:t:", longopts, NULL)) != -1) {
		switch (c) {
		case 'e':
			if ((o.estimator = pm_estimator_parse(optarg)) < 0)
				usage_err(usage, "-e: unknown estimator '%s'", optarg);
			break;
		case 'F': force = 1; break;
		case 'h': help();
		case 'j': threads = (int)parse_int(optarg, 0, 4096, "-j", usage); break;
		case 'k': o.k = (int)parse_int(optarg, 1, 100000, "-k", usage); break;
		case 'o': out = optarg; break;
		case 'N':
			if ((o.classical_norm = pm_classical_norm_parse(optarg)) < 0)
				usage_err(usage, "--classical-norm: unknown normalisation '%s' (k or k-1)", optarg);
			break;
		case 'M': max_spp = (int)parse_int(optarg, 1, 1 << 30, "--max-samples", usage); break;
		case 'p': o.spp = (int)parse_int(optarg, 1, 1 << 30, "-p", usage); break;
		case 'P':
			if (pm_pass_parse(optarg, &pass_i, &pass_n, &err) != 0)
				usage_err(usage, "-P: %s", err.msg);
			break;
		case 'q': quiet = 1; break;
		case 's': o.seed = parse_u64(optarg, "-s", usage); have_seed = 1; break;
		case 't': time = (float)parse_real(optarg, 0, 1, "-t", usage); have_time = 1; break;
		default: usage_err(usage, "unknown option '%s'", argv[optind - 1]);
		}
	}
	if (argc - optind < 1)
		usage_err(usage, "no scene given");
	if (argc - optind > 2)
		usage_err(usage, "too many arguments");
	if (argc - optind == 2)
		mapname = argv[optind + 1];
	if (!mapname && o.estimator != PM_EST_PATH)
		usage_err(usage, "the %s estimate needs a photon map (or use -e path)",
		          pm_estimator_name(o.estimator));
	if (!out)
		usage_err(usage, "no output given (-o OUT.exr)");
	if (o.classical_norm == PM_NORM_K1 && o.estimator != PM_EST_CLASSICAL)
		usage_err(usage, "--classical-norm k-1 is for -e classical, not %s",
		          pm_estimator_name(o.estimator));
	if (o.classical_norm == PM_NORM_K1 && o.k < 2)
		usage_err(usage, "--classical-norm k-1 needs -k 2 or more (one photon would give 0)");
	if (o.spp > max_spp)
		usage_err(usage, "-p: %d is more than %d samples per pixel (a typo? --max-samples raises the limit)",
		          o.spp, max_spp);
	check_output(usage, out, OUT_EXR, argv + optind, argc - optind);
	pm_pass_apply(pass_i, pass_n, &o.seed, &have_seed, &time, &have_time);
	set_threads(threads);

	if (pm_scene_load(&s, argv[optind], &err) != 0) {
		if (mapname && is_photon_file(argv[optind]))
			die("'%s': a photon file where the scene belongs: the order is SCENE MAP", argv[optind]);
		die_err(&err);
	}
	if (mapname) {
		FILE *f = strcmp(mapname, "-") == 0 ? stdin : fopen(mapname, "rb");
		if (!f)
			die("cannot open '%s': %m", mapname);
		if (pm_photons_read(&map, f, mapname, &err) != 0)
			die_err(&err);
		if (f != stdin)
			fclose(f);
		if (!map.h.kdtree)
			die("'%s': a photon file, not a photon map: run it through pm-build", mapname);
		if (map.h.light_hash != s.light_hash && !force)
			die("'%s': photon map of another scene (light_hash %016" PRIx64 ", '%s' has %016" PRIx64
			    ": its geometry, materials or lights differ); --force to use it",
			    mapname, map.h.light_hash, argv[optind], s.light_hash);
		if (have_time && map.h.time != time && !force)
			die("'%s': photon map is of time %g, not %g; --force to use it", mapname, map.h.time, time);
		if (!have_time)
			time = (float)map.h.time;
	}
	verts = malloc((s.nverts ? s.nverts : 1) * sizeof *verts);
	if (!verts)
		die("out of memory");
	pm_scene_verts_at(&s, time, verts);
	if (pm_accel_build(&a, &s, verts, &err) != 0 || pm_lights_build(&L, &s, verts, time, &err) != 0)
		die_err(&err);
	/* The index serves the compensated estimate and the edge layer. */
	if (mapname && o.estimator != PM_EST_PHOTONS && pm_polyindex_build(&pi, &s, verts, &err) != 0)
		die_err(&err);
	progress_start(&bar, "rows", (uint64_t)s.camera.height, quiet);
	o.progress = progress_hook;
	o.progress_arg = &bar;
	if (pm_render(&s, a, &L, mapname ? &map : NULL, pi, &o, &img, &err) != 0)
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
	snprintf(buf, sizeof buf, "%" PRIu64, map.h.count);
	setattr(&img, "pm.photons", buf);
	snprintf(buf, sizeof buf, "%" PRIu64, map.h.emitted);
	setattr(&img, "pm.emitted", buf);
	snprintf(buf, sizeof buf, "%016" PRIx64, s.view_hash);
	setattr(&img, "pm.scene_hash", buf);
	setattr(&img, "pm.estimator", pm_estimator_name(o.estimator));
	snprintf(buf, sizeof buf, "%d", o.k);
	setattr(&img, "pm.k", buf);
	snprintf(buf, sizeof buf, "%016" PRIx64, pm_pass_id(s.view_hash, pm_estimator_name(o.estimator),
	                                                     o.seed, time, map.h.seeds));
	setattr(&img, "pm.pass_ids", buf);
	if (pm_image_write_exr(&img, out, &err) != 0)
		die_err(&err);

	pm_image_free(&img);
	pm_polyindex_free(pi);
	pm_lights_free(&L);
	pm_accel_free(a);
	free(verts);
	pm_photons_free(&map);
	pm_scene_free(&s);
	return 0;
}
