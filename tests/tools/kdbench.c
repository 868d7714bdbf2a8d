/* kdbench.c — benchmark of the photon kd-tree: build time and k-nearest
 * queries per second for photons on the five walls of a unit box (the
 * shape of a Cornell-box photon map) and query points on those walls, the
 * way the view pass asks. Not a test: it prints numbers to compare.
 *
 *   kdbench [N [QUERIES [K]]]        defaults 1000000 1000000 50 */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "formats/kdtree.h"
#include "base/rng.h"

static double
now(void)
{
	struct timespec t;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void
wall_point(pm_rng *r, float x[3])
{
	int w = (int)(pm_rng_u32(r) % 5);      /* floor, ceiling, back, left, right */
	float u = pm_rng_f(r), v = pm_rng_f(r);
	int a = w < 2 ? 1 : w == 2 ? 2 : 0;
	x[a] = w == 1 ? 1.0f : 0.0f;
	if (w == 4)
		x[a] = 1.0f;
	x[(a + 1) % 3] = u;
	x[(a + 2) % 3] = v;
}

int
main(int argc, char **argv)
{
	size_t n = argc > 1 ? strtoull(argv[1], NULL, 10) : 1000000;
	long nq = argc > 2 ? strtol(argv[2], NULL, 10) : 1000000;
	int k = argc > 3 ? atoi(argv[3]) : 50;
	pm_photon *p = malloc(n * sizeof *p);
	pm_nn *nn = malloc((size_t)k * sizeof *nn);
	pm_rng r = pm_rng_seed(1, 0);
	pm_error err;
	double t, sum = 0;
	float dfar;

	if (!p || !nn || k < 1 || nq < 1)
		return 1;
	for (size_t i = 0; i < n; i++) {
		float x[3];
		wall_point(&r, x);
		pm_photon_pack(&p[i], pm_v3(x[0], x[1], x[2]), pm_v3(0, 1, 0), pm_v3(0, 1, 0), pm_v3(1, 1, 1));
	}
	t = now();
	if (pm_kd_build(p, n, &err)) {
		fprintf(stderr, "kdbench: %s\n", err.msg);
		return 1;
	}
	printf("build: %zu photons in %.3f s\n", n, now() - t);
	for (int m = PM_L2; m <= PM_LINF; m++) {
		pm_rng q = pm_rng_seed(2, 0);
		t = now();
		for (long i = 0; i < nq; i++) {
			float x[3];
			wall_point(&q, x);
			sum += pm_kd_knn(p, n, x, k, (enum pm_metric)m, INFINITY, nn, &dfar) + dfar;
		}
		t = now() - t;
		printf("knn %s k=%d: %ld queries in %.3f s, %.0f queries/s, %.2f us/query (one thread)\n",
		       m == PM_L2 ? "l2  " : "linf", k, nq, t, (double)nq / t, 1e6 * t / (double)nq);
	}
	fprintf(stderr, "checksum %g\n", sum);
	free(p);
	free(nn);
	return 0;
}
