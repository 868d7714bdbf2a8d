/* pm-average — averages pass images (or earlier averages) weighted by their
 * pass counts, keeping per-pixel M2 so averages of averages are exact and
 * the spread gives a standard error (lib/passes/average.h, formats/image.md).
 * Reads one input at a time: memory is O(image), not O(inputs), but for
 * the inputs' pass ids (16 bytes a pass), checked for repeats once all are
 * read (lib/formats/passid.h). */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "passes/average.h"
#include "formats/image.h"
#include "formats/passid.h"
#include "bar.h"
#include "options.h"
#include "util.h"

static const char usage[] = "pm-average [-fhqs] [-o OUT.exr] IMAGE...";

static const opt opts[] = {
	{ 'f', "force", NULL, "average despite differing pm.scene_hash, pm.estimator or "
	  "pm.consistent, or a pass given twice", "refuse", 0 },
	{ 'o', "output", "F", "write the average to the EXR file F, - for stdout", "none", 0 },
	{ 'q', "quiet", NULL, "no warnings, no progress bar", "warn about "
	  "dropped layers and forced mismatches; a progress bar "
	  "when stderr is a terminal", 1 },
	{ 's', "stats", NULL, "print passes, mean_stderr and mean to stdout", "off", 0 },
	{ 0, NULL, NULL, NULL, NULL, 0 },
};

static const tool average = {
	usage,
	"Averages pass images weighted by their pass counts (formats/image.md).",
	opts,
	"At least one of -o and -s is needed. An IMAGE - is an EXR read from stdin.\n",
};

/* Attributes copied to the output when every input has the same value (or
 * every input lacks it). */
static const char *const agreed[] = {
	"pm.scene_hash", "pm.estimator", "pm.k", "pm.spp", "pm.photons", "pm.time",
	"pm.light_samples", "pm.estimates", "pm.gather", "pm.consistent", "pm.light_paths",
	"pm.density", "pm.past_glossy",
};
enum { NAGREED = sizeof agreed / sizeof agreed[0] };

/* What --force overrode, recorded in pm.forced and inherited from inputs,
 * so that an average's provenance survives further averaging. */
static const char *const forced_word[] = { "scene_hash", "estimator", "duplicates", "consistent" };
enum { NFORCED = sizeof forced_word / sizeof forced_word[0] };

static int
same(const char *a, const char *b)
{
	return a == b || (a && b && strcmp(a, b) == 0);
}

static unsigned
forced_flags(const char *s)
{
	unsigned f = 0;

	for (int k = 0; s && k < NFORCED; k++) {
		size_t n = strlen(forced_word[k]);
		for (const char *p = strstr(s, forced_word[k]); p; p = strstr(p + 1, forced_word[k]))
			if ((p == s || p[-1] == ' ') && (p[n] == 0 || p[n] == ' '))
				f |= 1u << k;
	}
	return f;
}

static void
set_forced(pm_image *img, unsigned f)
{
	char buf[64] = "";
	pm_error err;

	for (int k = 0; k < NFORCED; k++)
		if (f & 1u << k)
			snprintf(buf + strlen(buf), sizeof buf - strlen(buf), "%s%s", *buf ? " " : "", forced_word[k]);
	if (*buf && pm_image_set_attr(img, "pm.forced", buf, &err))
		die_err(&err);
}

/* Refuses input path (a name as shown_name gives it) whose value v of an attribute that inputs must share
 * differs from rv, input ref's, unless forced: then warns (the first time)
 * and records the override as bit k of *overrode. */
static void
must_agree(int k, const char *what, const char *path, const char *v, const char *ref,
           const char *rv, int force, int quiet, unsigned *overrode)
{
	if (same(v, rv))
		return;
	if (!force)
		die("%s: %s %s differs from %s (%s)%s", path, what, v ? v : "(none)",
		    ref, rv ? rv : "(none)", k ? "; --force averages anyway" : "");
	if (!quiet && !(*overrode & 1u << k))
		warn("%s: %s %s differs from %s (%s); averaging anyway",
		     path, what, v ? v : "(none)", ref, rv ? rv : "(none)");
	*overrode |= 1u << k;
}

int
main(int argc, char **argv)
{
	const char *outpath = NULL, *first = NULL, *est_ref = NULL, *cons_ref = NULL, *cons;
	char firstnm[300], est_refnm[300], cons_refnm[300];
	char *est = NULL, *cons_val = NULL;
	char *value[NAGREED] = { NULL };
	int agree[NAGREED];
	int force = 0, quiet = 0, stats = 0, opt, ndropped = 0, all_ids = 1, da, db;
	unsigned forced = 0, overrode = 0;
	uint64_t dup;
	pm_passids ids;
	char (*dropped)[PM_CHAN_NAME] = NULL;
	pm_error err;
	pm_avg avg;
	progress bar;
	pm_image img;

	opt_init(&average, argc, argv);
	while ((opt = opt_next(&average, argc, argv)) != -1) {
		switch (opt) {
		case 'f': force = 1; break;
		case 'o': outpath = optarg; break;
		case 'q': quiet = 1; break;
		case 's': stats = 1; break;
		}
	}
	if (optind >= argc)
		usage_err(usage, "no input images");
	if (!outpath && !stats)
		usage_err(usage, "nothing to do: give -o OUT.exr or --stats");

	if (outpath && stats && strcmp(outpath, "-") == 0)
		usage_err(usage, "-o - with --stats: both would go to stdout; give the average a file name");
	if (outpath)
		check_output(usage, outpath, OUT_EXR, argv + optind, argc - optind);
	else
		check_stdin_once(usage, argv + optind, argc - optind);
	pm_avg_init(&avg);
	pm_passids_init(&ids);
	progress_start(&bar, "images", (uint64_t)(argc - optind), quiet);
	for (int i = optind; i < argc; i++) {
		char nm[300];
		/* Messages show stdin for -, a quoted name otherwise. */
		const char *path = shown_name(argv[i], nm, sizeof nm);
		double passes;

		if (pm_image_read_exr(&img, argv[i], &err))
			die_err(&err);
		if (pm_image_passes(&img, &passes, &err))
			die("%s: %s", path, err.msg);
		if (pm_image_attr(&img, "pm.pass_ids")) {
			size_t n;
			if (pm_passids_add(&ids, pm_image_attr(&img, "pm.pass_ids"), i, &n, &err))
				die("%s: %s", path, err.msg);
			if ((double)n != passes)
				die("%s: pm.pass_ids has %zu ids but pm.passes is %.0f", path, n, passes);
		} else {
			all_ids = 0;    /* older files: accepted, but the list is incomplete */
		}
		forced |= forced_flags(pm_image_attr(&img, "pm.forced"));
		/* Fixed and consistent passes converge to different images; files
		 * from before the mode are fixed ones. */
		cons = pm_image_attr(&img, "pm.consistent") ? pm_image_attr(&img, "pm.consistent") : "off";
		if (!cons_ref) {
			cons_ref = strcpy(cons_refnm, path);
			if (!(cons_val = strdup(cons)))
				die("out of memory");
		} else {
			must_agree(3, "consistent mode", path, cons, cons_ref, cons_val, force, quiet, &overrode);
		}
		/* Inputs that name their estimator must name the same one;
		 * files that do not (older or foreign ones) are accepted. */
		if (pm_image_attr(&img, "pm.estimator") && !est_ref) {
			est_ref = strcpy(est_refnm, path);
			if (!(est = strdup(pm_image_attr(&img, "pm.estimator"))))
				die("out of memory");
		} else if (pm_image_attr(&img, "pm.estimator")) {
			must_agree(1, "estimator", path, pm_image_attr(&img, "pm.estimator"), est_ref, est,
			           force, quiet, &overrode);
		}
		if (!first) {
			first = strcpy(firstnm, path);
			/* Later inputs can only drop channels this one has. */
			if (!(dropped = calloc(img.nchan, sizeof *dropped)))
				die("out of memory");
			for (int k = 0; k < NAGREED; k++) {
				const char *v = pm_image_attr(&img, agreed[k]);
				value[k] = v ? strdup(v) : NULL;
				agree[k] = !v || value[k];
			}
		} else {
			if (img.width != avg.width || img.height != avg.height)
				die("%s: size %dx%d differs from %s (%dx%d)", path,
				    img.width, img.height, first, avg.width, avg.height);
			must_agree(0, "scene hash", path, pm_image_attr(&img, agreed[0]), first, value[0],
			           force, quiet, &overrode);
			for (int k = 0; k < NAGREED; k++)
				if (!same(pm_image_attr(&img, agreed[k]), value[k]))
					agree[k] = 0;
			for (int c = 0; c < avg.nchan; c++)
				if (!pm_image_chan(&img, avg.chan[c]))
					snprintf(dropped[ndropped++], PM_CHAN_NAME, "%s", avg.chan[c]);
		}
		if (pm_avg_add(&avg, &img, passes, &err))
			die("%s: %s", path, err.msg);
		for (int c = 0; c < ndropped && !quiet; c++)
			warn("%s: no channel '%s'; it is left out of the average", path, dropped[c]);
		ndropped = 0;
		pm_image_free(&img);
		progress_update(&bar, (uint64_t)(i - optind + 1));
	}
	progress_end(&bar, (uint64_t)(argc - optind));
	if (pm_passids_dup(&ids, &dup, &da, &db)) {
		char what[700], na[300], nb[300];
		const char *a = shown_name(argv[da], na, sizeof na), *b = shown_name(argv[db], nb, sizeof nb);
		if (da == db)
			snprintf(what, sizeof what, "%s holds pass %016" PRIx64 " twice", a, dup);
		else if (strcmp(argv[da], argv[db]) == 0)
			snprintf(what, sizeof what, "%s is given twice", a);
		else
			snprintf(what, sizeof what, "%s repeats pass %016" PRIx64 " of %s (the same scene, "
			         "estimator, seeds and time)", b, dup, a);
		if (!force)
			die("%s; --force averages anyway", what);
		if (!quiet)
			warn("%s; averaging anyway", what);
		overrode |= 1u << 2;    /* forced_word[2] */
	}

	if (outpath) {
		if (pm_avg_image(&avg, &img, &err) ||
		    pm_image_set_attr(&img, "pm.command", cmdline(), &err))
			die_err(&err);
		for (int k = 0; k < NAGREED; k++)
			if (agree[k] && value[k] && pm_image_set_attr(&img, agreed[k], value[k], &err))
				die_err(&err);
		if (all_ids) {
			char *list = pm_passids_format(&ids);
			if (!list || pm_image_set_attr(&img, "pm.pass_ids", list, &err))
				die("out of memory for pm.pass_ids");
			free(list);
		}
		/* Unlike a missing one, "mixed" differs from every estimator. */
		if ((overrode & 1u << 1) && pm_image_set_attr(&img, "pm.estimator", "mixed", &err))
			die_err(&err);
		if ((overrode & 1u << 3) && pm_image_set_attr(&img, "pm.consistent", "mixed", &err))
			die_err(&err);
		set_forced(&img, forced | overrode);
		if (pm_image_write_exr(&img, outpath, &err))
			die_err(&err);
		pm_image_free(&img);
	}
	if (stats) {
		double mean, mean_se;
		pm_avg_stats(&avg, &mean, &mean_se);
		printf("passes: %.0f\nmean_stderr: %.9g\nmean: %.9g\n", avg.n, mean_se, mean);
		if (fflush(stdout) != 0 || ferror(stdout))
			die("cannot write stdout");
	}
	for (int k = 0; k < NAGREED; k++)
		free(value[k]);
	free(dropped);
	free(est);
	free(cons_val);
	pm_avg_free(&avg);
	pm_passids_free(&ids);
	return 0;
}
