/* torturestat — the torture harness's numbers for one scene (tests/torture/):
 * how far the compensated and the classical photon estimates are from a
 * reference, overall, in the edge band and in single pixels.
 *
 * Usage: torturestat --comp C.exr --class K.exr (--ref R.exr | --exact V)
 *                    [--mask M.exr] [--halves CA CB KA KB [RA RB]] [--verdict]
 *   C, K   averages of the compensated and classical passes (pm-average)
 *   R      the path-traced reference, an average of passes (pm-average), so
 *          it has stderr.R/G/B (missing: taken as 0)
 *   V      the exact radiance everywhere (a furnace: 2), instead of R
 *   M      one compensated pass (pm-render): its `edge` channel > 0.5 marks
 *          the edge band, the pixels whose estimate's cube meets another
 *          surface; without it the edge numbers are nan
 *
 * Every number is about the per-pixel value v = (R + G + B) / 3, the mean of
 * the three beauty channels (not luminance: the channels weigh equally).
 * The reference's standard error is taken as (sR + sG + sB) / 3, the bound
 * for fully correlated channels (they come from the same paths).
 *
 * Prints key=value lines:
 *   pixels, mean_ref, mean_comp, mean_class
 *   rmse_comp, rmse_class      root mean square of v - ref over all pixels
 *   max_comp, max_class        max |v - ref|
 *   edge_pixels                pixels in the edge band
 *   edge_mae_comp, edge_mae_class  mean over the edge band of
 *                              |box5(v) / box5(ref) - 1|, box5 the 5x5 box
 *                              mean (clipped at the image's border); pixels
 *                              whose box5(ref) <= 1e-6 mean_ref are skipped
 *   edge_noise_comp, edge_noise_class  the edge MAE that noise alone would
 *                              give: mean over the same pixels of
 *                              sqrt(2/pi) sqrt(box5(se_est)^2 +
 *                              box5(se_ref)^2) / box5(ref), se the images'
 *                              stderr layers (nan if the estimate has none).
 *                              It takes neighbouring pixels' errors as
 *                              fully correlated (photon estimates of
 *                              neighbours share photons): an upper bound;
 *                              independent errors would give a fifth of it
 *   edge_bias_comp, edge_bias_class  (with --halves) the edge band's local
 *                              error with the noise taken out: the passes
 *                              split into two halves A and B (odd and even
 *                              passes: CA, CB, KA, KB; and the reference's
 *                              likewise, RA, RB, unless --exact), the local
 *                              errors eA = box5(vA) / box5(refA) - 1 and eB
 *                              have independent noise, so mean(eA eB) over
 *                              the band estimates the mean squared bias;
 *                              printed as its square root (0 if negative)
 *   fireflies_comp, fireflies_class  pixels with v > 3 ref + 5 stderr +
 *                              0.01 mean_ref
 *   ref_rel_stderr             mean stderr / mean ref (0 with --exact)
 *   with --exact: edge_mean_err_comp/class = mean over the edge band of
 *   v / V - 1; edge_max_err_comp/class = max over it of |v / V - 1|;
 *   mean_err_comp/class = mean_comp / V - 1 over all pixels.
 * With --verdict, also one line per bar (pass, fail, or na when its inputs
 * are nan) and the overall verdict (na counts as pass):
 *   bar_rmse       rmse_comp <= 1.05 rmse_class
 *   bar_max        max_comp <= 2 max_class
 *   bar_edge       edge_bias_comp <= 0.5 edge_bias_class (with --halves;
 *                  else edge_mae_comp <= 0.5 edge_mae_class)
 *   bar_fireflies  fireflies_comp == 0
 *   bar_furnace    (--exact only) |edge_mean_err_comp| <= 0.01
 *   verdict        pass if every bar passes
 * Exit status 0 whatever the verdict; 1 on unreadable input; 2 for a bad
 * command line. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "formats/image.h"

static void
usage(void)
{
	fprintf(stderr, "usage: torturestat --comp C.exr --class K.exr (--ref R.exr | --exact V) [--mask M.exr] [--halves CA CB KA KB [RA RB]] [--verdict]\n");
	exit(2);
}

static void
load(pm_image *img, const char *path)
{
	pm_error err;
	if (pm_image_read_exr(img, path, &err)) {
		fprintf(stderr, "torturestat: %s\n", err.msg);
		exit(1);
	}
}

/* v = (A + B + C) / 3 of the layer's channels (prefix "" or "stderr."), or
 * NULL if the image lacks them. */
static double *
mean3(const pm_image *img, const char *prefix, const char *path)
{
	char n[3][PM_CHAN_NAME];
	const float *p[3];
	for (int k = 0; k < 3; k++) {
		snprintf(n[k], sizeof n[k], "%s%c", prefix, "RGB"[k]);
		if (!(p[k] = pm_image_chan(img, n[k])))
			return NULL;
	}
	size_t np = (size_t)img->width * img->height;
	double *v = malloc(np * sizeof *v);
	if (!v) {
		fprintf(stderr, "torturestat: out of memory\n");
		exit(1);
	}
	for (size_t i = 0; i < np; i++) {
		v[i] = ((double)p[0][i] + p[1][i] + p[2][i]) / 3;
		if (!isfinite(v[i])) {
			fprintf(stderr, "torturestat: '%s': channel %s pixel (%zu, %zu) is not finite\n",
			        path, prefix[0] ? "stderr" : "R/G/B", i % img->width, i / img->width);
			exit(1);
		}
	}
	return v;
}

/* 5x5 box means, clipped at the border. */
static double *
box5(const double *v, int w, int h)
{
	double *b = malloc((size_t)w * h * sizeof *b);
	if (!b) {
		fprintf(stderr, "torturestat: out of memory\n");
		exit(1);
	}
	for (int y = 0; y < h; y++)
		for (int x = 0; x < w; x++) {
			double s = 0;
			int n = 0;
			for (int dy = -2; dy <= 2; dy++)
				for (int dx = -2; dx <= 2; dx++) {
					int xx = x + dx, yy = y + dy;
					if (xx < 0 || yy < 0 || xx >= w || yy >= h)
						continue;
					s += v[(size_t)yy * w + xx];
					n++;
				}
			b[(size_t)y * w + x] = s / n;
		}
	return b;
}

static const char *
bar(double lhs, double rhs)
{
	if (isnan(lhs) || isnan(rhs))
		return "na";
	return lhs <= rhs ? "pass" : "fail";
}

int
main(int argc, char **argv)
{
	const char *cpath = NULL, *kpath = NULL, *rpath = NULL, *mpath = NULL, *hpath[6] = {0};
	double exact = NAN;
	int verdict = 0, nh = 0;
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i];
		if (!strcmp(a, "--verdict")) { verdict = 1; continue; }
		if (!strcmp(a, "--halves")) {
			while (nh < 6 && i + 1 < argc && strncmp(argv[i + 1], "--", 2) != 0)
				hpath[nh++] = argv[++i];
			if (nh != 4 && nh != 6) usage();
			continue;
		}
		if (i + 1 >= argc) usage();
		if (!strcmp(a, "--comp")) cpath = argv[++i];
		else if (!strcmp(a, "--class")) kpath = argv[++i];
		else if (!strcmp(a, "--ref")) rpath = argv[++i];
		else if (!strcmp(a, "--mask")) mpath = argv[++i];
		else if (!strcmp(a, "--exact")) {
			char *end;
			exact = strtod(argv[++i], &end);
			if (*end || !(exact > 0) || !isfinite(exact)) usage();
		} else usage();
	}
	if (!cpath || !kpath || (!rpath == isnan(exact)))
		usage();

	pm_image ci, ki, ri, mi;
	load(&ci, cpath);
	load(&ki, kpath);
	int w = ci.width, h = ci.height;
	size_t np = (size_t)w * h;
	if (ki.width != w || ki.height != h) {
		fprintf(stderr, "torturestat: '%s': size %dx%d differs from '%s' (%dx%d)\n", kpath, ki.width, ki.height, cpath, w, h);
		return 1;
	}
	double *c = mean3(&ci, "", cpath), *k = mean3(&ki, "", kpath), *r, *se;
	double *sec = mean3(&ci, "stderr.", cpath), *sek = mean3(&ki, "stderr.", kpath);
	if (!c || !k) {
		fprintf(stderr, "torturestat: '%s': no R, G, B channels\n", !c ? cpath : kpath);
		return 1;
	}
	if (rpath) {
		load(&ri, rpath);
		if (ri.width != w || ri.height != h) {
			fprintf(stderr, "torturestat: '%s': size %dx%d differs from '%s' (%dx%d)\n", rpath, ri.width, ri.height, cpath, w, h);
			return 1;
		}
		if (!(r = mean3(&ri, "", rpath))) {
			fprintf(stderr, "torturestat: '%s': no R, G, B channels\n", rpath);
			return 1;
		}
		if (!(se = mean3(&ri, "stderr.", rpath))) {
			fprintf(stderr, "torturestat: '%s': no stderr.R/G/B (one pass?): taken as 0\n", rpath);
			se = calloc(np, sizeof *se);
		}
		pm_image_free(&ri);
	} else {
		r = malloc(np * sizeof *r);
		se = calloc(np, sizeof *se);
		if (r)
			for (size_t i = 0; i < np; i++)
				r[i] = exact;
	}
	if (!r || !se) {
		fprintf(stderr, "torturestat: out of memory\n");
		return 1;
	}
	unsigned char *edge = calloc(np, 1);
	if (!edge) {
		fprintf(stderr, "torturestat: out of memory\n");
		return 1;
	}
	if (mpath) {
		load(&mi, mpath);
		const float *e = pm_image_chan(&mi, "edge");
		if (!e) {
			fprintf(stderr, "torturestat: '%s': no edge channel (not a compensated pass?)\n", mpath);
			return 1;
		}
		if (mi.width != w || mi.height != h) {
			fprintf(stderr, "torturestat: '%s': size %dx%d differs from '%s' (%dx%d)\n", mpath, mi.width, mi.height, cpath, w, h);
			return 1;
		}
		for (size_t i = 0; i < np; i++)
			edge[i] = e[i] > 0.5f;
		pm_image_free(&mi);
	}

	double mean_r = 0, mean_c = 0, mean_k = 0, mean_se = 0;
	for (size_t i = 0; i < np; i++) {
		mean_r += r[i]; mean_c += c[i]; mean_k += k[i]; mean_se += se[i];
	}
	mean_r /= np; mean_c /= np; mean_k /= np; mean_se /= np;
	double floor_ = 0.01 * mean_r;

	double sc = 0, sk = 0, mc = 0, mk = 0;
	long fc = 0, fk = 0;
	for (size_t i = 0; i < np; i++) {
		double dc = c[i] - r[i], dk = k[i] - r[i], lim = 3 * r[i] + 5 * se[i] + floor_;
		sc += dc * dc; sk += dk * dk;
		if (fabs(dc) > mc) mc = fabs(dc);
		if (fabs(dk) > mk) mk = fabs(dk);
		fc += c[i] > lim;
		fk += k[i] > lim;
	}
	double *bc = box5(c, w, h), *bk = box5(k, w, h), *br = box5(r, w, h), *bsr = box5(se, w, h);
	double *bsc = sec ? box5(sec, w, h) : NULL, *bsk = sek ? box5(sek, w, h) : NULL;
	long ne = 0, nused = 0;
	double maec = 0, maek = 0, emc = 0, emk = 0, exc = 0, exk = 0, nzc = 0, nzk = 0;
	const double sq2pi = sqrt(2 / 3.14159265358979323846);
	for (size_t i = 0; i < np; i++) {
		if (!edge[i])
			continue;
		ne++;
		if (!isnan(exact)) {
			double ec = c[i] / exact - 1, ek = k[i] / exact - 1;
			emc += ec; emk += ek;
			if (fabs(ec) > exc) exc = fabs(ec);
			if (fabs(ek) > exk) exk = fabs(ek);
		}
		if (!(br[i] > 1e-6 * mean_r))
			continue;
		nused++;
		maec += fabs(bc[i] / br[i] - 1);
		maek += fabs(bk[i] / br[i] - 1);
		if (bsc) nzc += sq2pi * sqrt(bsc[i] * bsc[i] + bsr[i] * bsr[i]) / br[i];
		if (bsk) nzk += sq2pi * sqrt(bsk[i] * bsk[i] + bsr[i] * bsr[i]) / br[i];
	}
	nzc = nused && bsc ? nzc / nused : NAN;
	nzk = nused && bsk ? nzk / nused : NAN;
	maec = nused ? maec / nused : NAN;
	maek = nused ? maek / nused : NAN;

	/* The split-half bias (see the top). */
	double biasc = NAN, biask = NAN;
	if (nh) {
		double *hv[6], *hb[6];
		for (int j = 0; j < 6; j++) {
			pm_image hi;
			if (j >= nh) {
				hv[j] = r;     /* --exact: the exact value for both halves */
				hb[j] = box5(r, w, h);
				continue;
			}
			load(&hi, hpath[j]);
			if (hi.width != w || hi.height != h) {
				fprintf(stderr, "torturestat: '%s': size %dx%d differs from '%s' (%dx%d)\n", hpath[j], hi.width, hi.height, cpath, w, h);
				return 1;
			}
			if (!(hv[j] = mean3(&hi, "", hpath[j]))) {
				fprintf(stderr, "torturestat: '%s': no R, G, B channels\n", hpath[j]);
				return 1;
			}
			hb[j] = box5(hv[j], w, h);
			pm_image_free(&hi);
		}
		double pc = 0, pk = 0;
		long nb = 0;
		for (size_t i = 0; i < np; i++) {
			if (!edge[i] || !(hb[4][i] > 1e-6 * mean_r) || !(hb[5][i] > 1e-6 * mean_r))
				continue;
			pc += (hb[0][i] / hb[4][i] - 1) * (hb[1][i] / hb[5][i] - 1);
			pk += (hb[2][i] / hb[4][i] - 1) * (hb[3][i] / hb[5][i] - 1);
			nb++;
		}
		if (nb) {
			biasc = sqrt(fmax(0, pc / nb));
			biask = sqrt(fmax(0, pk / nb));
		}
		for (int j = 0; j < 6; j++) {
			if (hv[j] != r)
				free(hv[j]);
			free(hb[j]);
		}
	}

	printf("pixels=%zu\n", np);
	printf("mean_ref=%.6g\nmean_comp=%.6g\nmean_class=%.6g\n", mean_r, mean_c, mean_k);
	printf("rmse_comp=%.6g\nrmse_class=%.6g\n", sqrt(sc / np), sqrt(sk / np));
	printf("max_comp=%.6g\nmax_class=%.6g\n", mc, mk);
	printf("edge_pixels=%ld\n", ne);
	printf("edge_mae_comp=%.6g\nedge_mae_class=%.6g\n", maec, maek);
	printf("edge_noise_comp=%.6g\nedge_noise_class=%.6g\n", nzc, nzk);
	if (nh)
		printf("edge_bias_comp=%.6g\nedge_bias_class=%.6g\n", biasc, biask);
	printf("fireflies_comp=%ld\nfireflies_class=%ld\n", fc, fk);
	printf("ref_rel_stderr=%.6g\n", mean_r > 0 ? mean_se / mean_r : 0.0);
	double emean_c = ne ? emc / ne : NAN;
	if (!isnan(exact)) {
		printf("exact=%.6g\n", exact);
		printf("mean_err_comp=%.6g\nmean_err_class=%.6g\n", mean_c / exact - 1, mean_k / exact - 1);
		printf("edge_mean_err_comp=%.6g\nedge_mean_err_class=%.6g\n", emean_c, ne ? emk / ne : NAN);
		printf("edge_max_err_comp=%.6g\nedge_max_err_class=%.6g\n", ne ? exc : NAN, ne ? exk : NAN);
	}
	if (verdict) {
		const char *b[5];
		int nb = 0, fail = 0;
		printf("bar_rmse=%s\n", b[nb++] = bar(sqrt(sc / np), 1.05 * sqrt(sk / np)));
		printf("bar_max=%s\n", b[nb++] = bar(mc, 2 * mk));
		printf("bar_edge=%s\n", b[nb++] = nh ? bar(biasc, 0.5 * biask) : bar(maec, 0.5 * maek));
		printf("bar_fireflies=%s\n", b[nb++] = fc == 0 ? "pass" : "fail");
		if (!isnan(exact))
			printf("bar_furnace=%s\n", b[nb++] = bar(fabs(emean_c), 0.01));
		for (int i = 0; i < nb; i++)
			fail |= !strcmp(b[i], "fail");
		printf("verdict=%s\n", fail ? "fail" : "pass");
	}
	free(c); free(k); free(r); free(se); free(edge); free(bc); free(bk); free(br); free(bsr);
	free(sec); free(sek); free(bsc); free(bsk);
	pm_image_free(&ci);
	pm_image_free(&ki);
	return 0;
}
