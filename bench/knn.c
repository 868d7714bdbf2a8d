/* knn.c — the photon map's k-nearest search against its anchor, nanoflann,
 * side by side in one run: the same points (photons on the five walls of a
 * unit box, the shape of a Cornell-box photon map), the same queries (points
 * on those walls seen through a pinhole camera), in image order and shuffled,
 * for the sphere (L2, classical estimate) and the cube (L-infinity,
 * compensated estimate). One thread; each figure is the median of -r runs.
 * Also times both builds. Not a test: it prints numbers, the summary last.
 *
 *   knn [-n PHOTONS] [-q QUERIES] [-k K] [-r RUNS] [-l NANOFLANN_LEAF] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <omp.h>

#include "formats/kdtree.h"
#include "base/rng.h"
#include "timing.h"

void *nano_build(const float *xyz, size_t n, size_t stride, int leaf);
int nano_build_l2_only(const float *xyz, size_t n, size_t stride, int leaf);
int nano_knn(void *t, const float x[3], int k, int linf, uint32_t *idx, float *dist);
void nano_free(void *t);


/* A uniform point on one of the five walls (open at z = 1). */
static void
wall_point(pm_rng *r, float x[3])
{
	int w = (int)(pm_rng_u32(r) % 5);
	float u = pm_rng_f(r), v = pm_rng_f(r);
	switch (w) {
	case 0: x[0] = u; x[1] = 0; x[2] = v; break;    /* floor */
	case 1: x[0] = u; x[1] = 1; x[2] = v; break;    /* ceiling */
	case 2: x[0] = u; x[1] = v; x[2] = 0; break;    /* back */
	case 3: x[0] = 0; x[1] = u; x[2] = v; break;    /* left */
	default: x[0] = 1; x[1] = u; x[2] = v; break;   /* right */
	}
}

/* The wall point seen through pixel (i, j) of a side x side pinhole camera at
 * (0.5, 0.5, 2.5) looking down -z, whose frame is the box's open side. */
static void
camera_point(int i, int j, int side, float x[3])
{
	double o[3] = {0.5, 0.5, 2.5};
	double d[3] = {((i + 0.5) / side - 0.5) / 1.5, (0.5 - (j + 0.5) / side) / 1.5, -1};
	double best = INFINITY;
	/* planes: axis, value */
	static const int ax[5] = {1, 1, 2, 0, 0};
	static const double val[5] = {0, 1, 0, 0, 1};

	for (int w = 0; w < 5; w++) {
		if (d[ax[w]] == 0)
			continue;
		double t = (val[w] - o[ax[w]]) / d[ax[w]];
		if (!(t > 0) || t >= best)
			continue;
		int in = 1;
		for (int a = 0; a < 3; a++) {
			double c = o[a] + t * d[a];
			if (a != ax[w] && (c < 0 || c > 1))
				in = 0;
		}
		if (in)
			best = t;
	}
	for (int a = 0; a < 3; a++)
		x[a] = (float)(o[a] + best * d[a]);
}

int
main(int argc, char **argv)
{
	long n = 1000000, nq = 1000000;
	int k = 50, runs = 3, leaf = 10, c;

	while ((c = getopt(argc, argv, "k:l:n:q:r:")) != -1) {
		switch (c) {
		case 'k': k = atoi(optarg); break;
		case 'l': leaf = atoi(optarg); break;
		case 'n': n = atol(optarg); break;
		case 'q': nq = atol(optarg); break;
		case 'r': runs = atoi(optarg); break;
		default:
			fprintf(stderr, "usage: knn [-n PHOTONS] [-q QUERIES] [-k K] [-r RUNS] [-l LEAF]\n");
			return 2;
		}
	}
	if (n < 1 || nq < 1 || k < 1 || runs < 1 || runs > 99 || leaf < 1) {
		fprintf(stderr, "knn: bad arguments\n");
		return 2;
	}
	int side = (int)sqrt((double)nq);
	nq = (long)side * side;
	/* one core for both: nanoflann builds and searches on one thread */
	omp_set_num_threads(1);
	pm_photon *p = malloc((size_t)n * sizeof *p);
	float *xyz = malloc((size_t)n * 3 * sizeof *xyz);
	float (*q)[3] = malloc((size_t)nq * sizeof *q), (*qs)[3] = malloc((size_t)nq * sizeof *qs);
	pm_nn *nn = malloc((size_t)k * sizeof *nn);
	uint32_t *ni = malloc((size_t)k * sizeof *ni);
	float *nd = malloc((size_t)k * sizeof *nd);
	float *kth = malloc((size_t)nq * sizeof *kth);
	pm_rng r = pm_rng_seed(1, 0);
	pm_error err;
	double t, tb[99];

	if (!p || !xyz || !q || !qs || !nn || !ni || !nd || !kth)
		return 1;
	for (long i = 0; i < n; i++) {
		float x[3];
		wall_point(&r, x);
		pm_photon_pack(&p[i], pm_v3(x[0], x[1], x[2]), pm_v3(0, 1, 0), pm_v3(0, 1, 0), pm_v3(1, 1, 1));
	}
	/* build times: ours from the same shuffled order every run */
	pm_photon *orig = malloc((size_t)n * sizeof *orig);
	if (!orig)
		return 1;
	memcpy(orig, p, (size_t)n * sizeof *p);
	for (int i = 0; i < runs; i++) {
		memcpy(p, orig, (size_t)n * sizeof *p);
		t = now();
		if (pm_kd_build(p, (size_t)n, &err)) {
			fprintf(stderr, "knn: %s\n", err.msg);
			return 1;
		}
		tb[i] = now() - t;
	}
	free(orig);
	double b_ours = median(tb, runs);
	for (long i = 0; i < n; i++)
		memcpy(xyz + 3 * i, p[i].pos, sizeof p[i].pos);
	for (int i = 0; i < runs; i++) {
		t = now();
		nano_build_l2_only(xyz, (size_t)n, 3, leaf);
		tb[i] = now() - t;
	}
	double b_nano = median(tb, runs);
	void *nt = nano_build(xyz, (size_t)n, 3, leaf);
	if (!nt) {
		fprintf(stderr, "knn: nanoflann build failed\n");
		return 1;
	}
	printf("photons\t%ld\nqueries\t%ld\nk\t%d\nruns\t%d\nnanoflann_leaf\t%d\n", n, nq, k, runs, leaf);
	printf("build_s_per_M_ours\t%.4f\nbuild_s_per_M_nanoflann\t%.4f\n",
	       b_ours * 1e6 / n, b_nano * 1e6 / n);

	/* queries: image order, and the same points shuffled */
	for (int j = 0; j < side; j++)
		for (int i = 0; i < side; i++)
			camera_point(i, j, side, q[(long)j * side + i]);
	memcpy(qs, q, (size_t)nq * sizeof *q);
	pm_rng sh = pm_rng_seed(3, 0);
	for (long i = nq - 1; i > 0; i--) {
		long j = (long)(((uint64_t)pm_rng_u32(&sh) * (uint64_t)(i + 1)) >> 32);
		float tmp[3];
		memcpy(tmp, qs[i], sizeof tmp);
		memcpy(qs[i], qs[j], sizeof tmp);
		memcpy(qs[j], tmp, sizeof tmp);
	}

	double ratio_prod = 1;
	int ncase = 0;
	for (int m = 0; m < 2; m++) {
		const char *mn = m ? "cube" : "sphere";
		for (int ord = 0; ord < 2; ord++) {
			float (*Q)[3] = ord ? qs : q;
			const char *on = ord ? "random" : "image";
			double to[99], tn[99], sum = 0;
			long differ = 0, closer = 0;
			for (int i = 0; i < runs; i++) {
				float dfar;
				t = now();
				for (long j = 0; j < nq; j++) {
					pm_kd_knn(p, (size_t)n, Q[j], k, m ? PM_LINF : PM_L2, INFINITY, nn, &dfar);
					kth[j] = dfar;
				}
				to[i] = now() - t;
				t = now();
				for (long j = 0; j < nq; j++) {
					int got = nano_knn(nt, Q[j], k, m, ni, nd);
					sum += got ? nd[got - 1] : 0;
					if (i == 0 && (got != k || nd[got - 1] != kth[j]))
						differ++;
					if (i == 0 && got == k && nd[got - 1] < kth[j])
						closer++;
				}
				tn[i] = now() - t;
			}
			double qo = nq / median(to, runs), qn = nq / median(tn, runs);
			printf("%s_%s_qps_ours\t%.0f\n%s_%s_qps_nanoflann\t%.0f\n%s_%s_ratio\t%.3f\n"
			       "%s_%s_kth_differs\t%ld\n%s_%s_nanoflann_closer\t%ld\n",
			       mn, on, qo, mn, on, qn, mn, on, qo / qn, mn, on, differ, mn, on, closer);
			fprintf(stderr, "checksum %g\n", sum);
			ratio_prod *= qo / qn;
			ncase++;
		}
	}
	nano_free(nt);
	printf("knn_speed_ours_over_nanoflann_geomean\t%.3f\n", pow(ratio_prod, 1.0 / ncase));
	free(p);
	free(xyz);
	free(q);
	free(qs);
	free(nn);
	free(ni);
	free(nd);
	free(kth);
	return 0;
}
