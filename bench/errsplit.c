/* errsplit.c — the error of an averaged image against a reference, split
 * into bias and noise by the spread between the passes it averages.
 *
 * For n passes with per-pixel pass variance s^2 the mean has variance s^2/n,
 * so MSE = bias^2 + s^2/n + (the reference's own variance). pm-average keeps
 * M2 (m2.R/G/B): s^2 = M2 / (n - 1). The reference's variance is its
 * stderr^2 when it is itself an average of passes (pm-average's stderr.*),
 * else 0; a constant reference (-c, for furnace scenes) is exact.
 * RMSE and relMSE are pm-diff's (lib/passes/compare.h): relMSE per channel is
 * (a-b)^2 / (b^2 + 0.01); the variances are scaled the same way.
 *
 * Prints one tab-separated line, no header:
 *   pixels mse rmse relmse passvar relpassvar refvar relrefvar
 * where passvar = mean s^2 (of one pass; divide by n for the mean's).
 *
 *   errsplit [-m MASK.exr -c CHANNEL|!CHANNEL] [-v VALUE] AVG.exr [REF.exr]
 *   errsplit -z CHANNEL IMG.exr     fraction of pixels whose CHANNEL > 0
 *   errsplit -s Z [-m MASK.exr -c [!]CHANNEL] AVG.exr REF.exr
 *       pixels (in the mask) where some channel is more than Z standard
 *       errors from the reference, |a - b| / sqrt(se_a^2 + se_b^2), se from
 *       each average's stderr layer: speckles, or a bias beyond the noise */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "passes/average.h"
#include "passes/compare.h"
#include "formats/image.h"

static void
die(const char *what, const char *msg)
{
	fprintf(stderr, "errsplit: %s: %s\n", what, msg);
	exit(1);
}

int
main(int argc, char **argv)
{
	const char *maskf = NULL, *maskc = "edge", *zc = NULL;
	double cval = NAN;
	int c;
	pm_image a, b, m;
	pm_error err;

	double zmax = NAN;

	while ((c = getopt(argc, argv, "c:m:s:v:z:")) != -1) {
		switch (c) {
		case 's': zmax = atof(optarg); break;
		case 'c': maskc = optarg; break;
		case 'm': maskf = optarg; break;
		case 'v': cval = atof(optarg); break;
		case 'z': zc = optarg; break;
		default:
			fprintf(stderr, "usage: errsplit [-m MASK.exr -c [!]CHANNEL] [-v VALUE] AVG.exr [REF.exr]\n");
			return 2;
		}
	}
	if (zc && argc - optind == 1) {
		if (pm_image_read_exr(&a, argv[optind], &err))
			die(argv[optind], err.msg);
		const float *z = pm_image_chan(&a, zc);
		size_t cnt = 0, np = (size_t)a.width * a.height;
		if (!z)
			die(argv[optind], "no such channel");
		for (size_t i = 0; i < np; i++)
			cnt += z[i] > 0;
		printf("%.6f\n", (double)cnt / (double)np);
		return 0;
	}
	if (argc - optind != (isnan(cval) ? 2 : 1)) {
		fprintf(stderr, "usage: errsplit [-m MASK.exr -c [!]CHANNEL] [-v VALUE] AVG.exr [REF.exr]\n");
		return 2;
	}
	const char *af = argv[optind];
	if (pm_image_read_exr(&a, af, &err))
		die(af, err.msg);
	int w = a.width, h = a.height;
	size_t np = (size_t)w * h;
	double n = 1;
	if (pm_image_passes(&a, &n, &err))
		die(af, err.msg);
	const float *pa[3], *pb[3], *am2[3] = {0}, *bse[3] = {0};
	float *cst = NULL;
	static const char *const rgb[3] = {"R", "G", "B"};
	if (pm_layer_planes(&a, NULL, pa, &err))
		die(af, err.msg);
	for (int k = 0; k < 3; k++) {
		char nm[16];
		snprintf(nm, sizeof nm, "m2.%s", rgb[k]);
		am2[k] = pm_image_chan(&a, nm);
	}
	if (isnan(cval)) {
		const char *bf = argv[optind + 1];
		if (pm_image_read_exr(&b, bf, &err))
			die(bf, err.msg);
		if (b.width != w || b.height != h)
			die(bf, "size differs");
		if (pm_layer_planes(&b, NULL, pb, &err))
			die(bf, err.msg);
		for (int k = 0; k < 3; k++) {
			char nm[16];
			snprintf(nm, sizeof nm, "stderr.%s", rgb[k]);
			bse[k] = pm_image_chan(&b, nm);
		}
	} else {
		cst = malloc(np * sizeof *cst);
		if (!cst)
			die("errsplit", "out of memory");
		for (size_t i = 0; i < np; i++)
			cst[i] = (float)cval;
		pb[0] = pb[1] = pb[2] = cst;
	}
	/* the mask: channel > 0.5, or with '!' <= 0.5 */
	float *mask = NULL;
	if (maskf) {
		int neg = maskc[0] == '!';
		if (pm_image_read_exr(&m, maskf, &err))
			die(maskf, err.msg);
		const float *mc = pm_image_chan(&m, maskc + neg);
		if (!mc || m.width != w || m.height != h)
			die(maskf, "no such mask channel, or size differs");
		mask = malloc(np * sizeof *mask);
		if (!mask)
			die("errsplit", "out of memory");
		for (size_t i = 0; i < np; i++)
			mask[i] = (mc[i] > 0.5f) != neg ? 1.0f : 0.0f;
	}
	if (!isnan(zmax)) {
		const float *ase[3];
		long long over = 0;
		for (int k = 0; k < 3; k++) {
			char nm[16];
			snprintf(nm, sizeof nm, "stderr.%s", rgb[k]);
			if (!(ase[k] = pm_image_chan(&a, nm)) || !bse[k])
				die(af, "-s needs both images' stderr layers (averages of passes)");
		}
		for (size_t i = 0; i < np; i++) {
			int hit = 0;
			if (mask && !(mask[i] > 0.5f))
				continue;
			for (int k = 0; k < 3; k++) {
				double s = sqrt((double)ase[k][i] * ase[k][i] + (double)bse[k][i] * bse[k][i]);
				double dd = fabs((double)pa[k][i] - pb[k][i]);
				hit |= s > 0 ? dd > zmax * s : dd > 0;
			}
			over += hit;
		}
		printf("%lld\n", over);
		return 0;
	}
	pm_diff d;
	if (pm_compare(pa, pb, mask, w, h, &d, &err)) {
		/* an empty mask: no pixels */
		printf("0\tnan\tnan\tnan\tnan\tnan\tnan\tnan\n");
		return 0;
	}
	double pv = 0, rpv = 0, rv = 0, rrv = 0;
	long long cnt = 0;
	for (size_t i = 0; i < np; i++) {
		if (mask && !(mask[i] > 0.5f))
			continue;
		cnt++;
		for (int k = 0; k < 3; k++) {
			double bb = pb[k][i], den = bb * bb + 0.01;
			double s2 = am2[k] && n > 1 ? am2[k][i] / (n - 1) : NAN;
			double r2 = bse[k] ? (double)bse[k][i] * bse[k][i] : 0;
			pv += s2;
			rpv += s2 / den;
			rv += r2;
			rrv += r2 / den;
		}
	}
	double q = 3.0 * (double)cnt;
	printf("%lld\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\t%.6g\n", d.pixels, d.rmse * d.rmse, d.rmse,
	       d.relmse, pv / q, rpv / q, rv / q, rrv / q);
	return 0;
}
