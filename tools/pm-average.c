/* pm-average — averages pass images (or earlier averages) weighted by their
 * pass counts, keeping per-pixel M2 so averages of averages are exact and
 * the spread gives a standard error (lib/average.h, formats/image.md).
 * Reads one input at a time: memory is O(image), not O(inputs). */
#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "average.h"
#include "image.h"
#include "progress.h"
#include "util.h"

static const char usage[] = "pm-average [-fhqs] [-o OUT.exr] IMAGE...";

static void
help(void)
{
	printf("usage: %s\n"
	       "  -f, --force     average despite differing pm.scene_hash (default: refuse)\n"
	       "  -h, --help      print this help and exit\n"
	       "  -o, --output F  write the average to the EXR file F, - for stdout\n"
	       "                  (default: none)\n"
	       "  -q, --quiet     no warnings, no progress bar (default: warn about\n"
	       "                  dropped layers and forced mismatches; a progress bar\n"
	       "                  when stderr is a terminal)\n"
	       "  -s, --stats     print passes, mean_stderr and mean to stdout (default: off)\n"
	       "At least one of -o and -s is needed. An IMAGE - is an EXR read from stdin.\n", usage);
}

/* Attributes copied to the output when every input has the same value (or
 * every input lacks it). */
static const char *const agreed[] = {
	"pm.scene_hash", "pm.estimator", "pm.k", "pm.spp", "pm.photons", "pm.time",
};
enum { NAGREED = sizeof agreed / sizeof agreed[0] };

static int
same(const char *a, const char *b)
{
	return a == b || (a && b && strcmp(a, b) == 0);
}

int
main(int argc, char **argv)
{
	static const struct option longopts[] = {
		{ "force", no_argument, NULL, 'f' },
		{ "help", no_argument, NULL, 'h' },
		{ "output", required_argument, NULL, 'o' },
		{ "quiet", no_argument, NULL, 'q' },
		{ "stats", no_argument, NULL, 's' },
		{ NULL, 0, NULL, 0 },
	};
	const char *outpath = NULL, *first = NULL;
	char firstnm[300];
	char *value[NAGREED] = { NULL };
	int agree[NAGREED];
	int force = 0, quiet = 0, stats = 0, opt, ndropped = 0;
	char (*dropped)[PM_CHAN_NAME] = NULL;
	pm_error err;
	pm_avg avg;
	progress bar;
	pm_image img;

	util_init(argc, argv);
	while ((opt = getopt_long(argc, argv, ":fho:qs", longopts, NULL)) != -1) {
		switch (opt) {
		case 'f': force = 1; break;
		case 'h': help(); return 0;
		case 'o': outpath = optarg; break;
		case 'q': quiet = 1; break;
		case 's': stats = 1; break;
		default: bad_option(usage, opt, argv);
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
			const char *hash = pm_image_attr(&img, "pm.scene_hash");
			if (img.width != avg.width || img.height != avg.height)
				die("%s: size %dx%d differs from %s (%dx%d)", path,
				    img.width, img.height, first, avg.width, avg.height);
			if (!same(hash, value[0])) {
				if (!force)
					die("%s: scene hash %s differs from %s (%s)", path,
					    hash ? hash : "(none)", first, value[0] ? value[0] : "(none)");
				if (!quiet && agree[0])
					warn("%s: scene hash %s differs from %s (%s); averaging anyway",
					     path, hash ? hash : "(none)", first, value[0] ? value[0] : "(none)");
			}
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

	if (outpath) {
		if (pm_avg_image(&avg, &img, &err) ||
		    pm_image_set_attr(&img, "pm.command", cmdline(), &err))
			die_err(&err);
		for (int k = 0; k < NAGREED; k++)
			if (agree[k] && value[k] && pm_image_set_attr(&img, agreed[k], value[k], &err))
				die_err(&err);
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
	pm_avg_free(&avg);
	return 0;
}
