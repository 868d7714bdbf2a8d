/* test_kdtree.c — the photon kd-tree against brute force: k nearest under L2
 * and L-infinity for uniform, planar, duplicated and identical points, the
 * tie rule, the distance limit, validation, determinism and the edge cases
 * n = 0 and n = 1. */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "formats/kdtree.h"
#include "base/rng.h"

enum { UNIFORM, PLANES, DUPLICATES, IDENTICAL, NKINDS };
static const char *const kindname[NKINDS] = {"uniform", "planes", "duplicates", "identical"};

static pm_photon *
points(int kind, size_t n, uint64_t seed)
{
	pm_photon *p = malloc((n ? n : 1) * sizeof *p);
	pm_rng r = pm_rng_seed(seed, (uint64_t)kind);
	float pool[64][3];

	for (int i = 0; i < 64; i++)
		for (int a = 0; a < 3; a++)
			pool[i][a] = (float)(pm_rng_u32(&r) % 4) * 0.25f;   /* coarse: coordinates repeat too */
	for (size_t i = 0; i < n; i++) {
		float x[3];
		for (int a = 0; a < 3; a++)
			x[a] = pm_rng_f(&r) * 2 - 1;
		if (kind == PLANES)            /* the walls of a box: one coordinate exactly shared */
			x[i % 3] = (i / 3) % 2 ? 1.0f : -1.0f;
		if (kind == DUPLICATES)
			memcpy(x, pool[pm_rng_u32(&r) % 64], sizeof x);
		if (kind == IDENTICAL)
			x[0] = x[1] = x[2] = 0.5f;
		pm_photon_pack(&p[i], pm_v3(x[0], x[1], x[2]), pm_v3(0, 0, 1), pm_v3(0, 0, 1),
		               pm_v3((float)i, 1, 1));
	}
	return p;
}

/* The same float expressions as the tree, so ties compare equal. */
static float
dist(const float *a, const float *b, enum pm_metric m)
{
	float dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
	if (m == PM_LINF)
		return fmaxf(fabsf(dx), fmaxf(fabsf(dy), fabsf(dz)));
	return dx * dx + dy * dy + dz * dz;
}

static int
nncmp(const void *a, const void *b)
{
	const pm_nn *x = a, *y = b;
	if (x->d != y->d)
		return x->d < y->d ? -1 : 1;
	return x->idx < y->idx ? -1 : x->idx > y->idx;
}

/* Compares the tree's answer for (x, k, m, dmax) with a sorted brute-force
 * list all[0..n); returns 0 if equal, else reports and returns -1. */
static int
same_answer(const pm_photon *tree, size_t n, const float x[3], int k, enum pm_metric m,
            float dmax, const pm_nn *all, pm_nn *out, const char *what)
{
	float dfar = -1;
	size_t want = 0;
	int got = pm_kd_knn(tree, n, x, k, m, dmax, out, &dfar);

	while (want < n && want < (size_t)k && all[want].d < dmax)
		want++;
	if ((size_t)got != want) {
		CHECKF(0, "%s: k=%d metric %d: got %d neighbours, want %zu", what, k, m, got, want);
		return -1;
	}
	qsort(out, (size_t)got, sizeof *out, nncmp);
	for (int i = 0; i < got; i++)
		if (out[i].idx != all[i].idx || out[i].d != all[i].d) {
			CHECKF(0, "%s: k=%d metric %d: neighbour %d is %u (d %g), want %u (d %g)", what, k, m,
			       i, out[i].idx, out[i].d, all[i].idx, all[i].d);
			return -1;
		}
	if (dfar != (got ? all[got - 1].d : 0)) {
		CHECKF(0, "%s: dfar %g, want %g", what, dfar, got ? all[got - 1].d : 0);
		return -1;
	}
	return 0;
}

static void
against_brute_force(int kind, size_t n, int nq)
{
	pm_photon *p = points(kind, n, 11);
	pm_nn *all = malloc((n + 1) * sizeof *all), *out = malloc((n + 4) * sizeof *out);
	pm_rng r = pm_rng_seed(12, (uint64_t)kind);
	pm_error err = {""};
	int ks[4] = {1, 5, 50, (int)n + 3}, fails = 0;

	CHECKF(pm_kd_build(p, n, &err) == 0, "%s", err.msg);
	CHECKF(pm_kd_validate(p, n, &err) == 0, "%s: %s", kindname[kind], err.msg);
	for (int q = 0; q < nq && fails == 0; q++) {
		float x[3];
		for (int a = 0; a < 3; a++)
			x[a] = pm_rng_f(&r) * 3 - 1.5f;     /* some outside the points' box */
		if (q % 4 == 0 && n > 0)                 /* on a photon: distance-0 ties */
			memcpy(x, p[pm_rng_u32(&r) % n].pos, sizeof x);
		if (q % 8 == 1)                          /* on a coarse lattice: many equal distances */
			for (int a = 0; a < 3; a++)
				x[a] = (float)(pm_rng_u32(&r) % 9) * 0.25f - 1;
		for (int m = PM_L2; m <= PM_LINF; m++) {
			for (size_t i = 0; i < n; i++) {
				all[i].idx = (uint32_t)i;
				all[i].d = dist(x, p[i].pos, (enum pm_metric)m);
			}
			qsort(all, n, sizeof *all, nncmp);
			for (int j = 0; j < 4; j++)
				fails += same_answer(p, n, x, ks[j], (enum pm_metric)m, INFINITY, all, out,
				                     kindname[kind]) != 0;
			/* a distance limit, set to a distance that occurs, so "<" matters */
			if (n > 10) {
				float lim = all[n / 10].d;
				fails += same_answer(p, n, x, 50, (enum pm_metric)m, lim, all, out, kindname[kind]) != 0;
				fails += same_answer(p, n, x, (int)n, (enum pm_metric)m, lim, all, out, kindname[kind]) != 0;
			}
		}
	}
	free(p);
	free(all);
	free(out);
}

TEST(knn_uniform) { against_brute_force(UNIFORM, 3000, 200); }
TEST(knn_planes) { against_brute_force(PLANES, 3000, 200); }
TEST(knn_duplicates) { against_brute_force(DUPLICATES, 3000, 200); }
TEST(knn_identical) { against_brute_force(IDENTICAL, 500, 50); }
TEST(knn_small_sizes)
{
	/* every tree shape up to 70 nodes, complete or not */
	for (size_t n = 1; n <= 70; n++)
		against_brute_force((int)(n % NKINDS), n, 20);
}

static int
bytecmp(const void *a, const void *b)
{
	return memcmp(a, b, sizeof(pm_photon));
}

TEST(build_keeps_photons)
{
	size_t n = 5000;
	pm_photon *a = points(DUPLICATES, n, 13), *b = points(DUPLICATES, n, 13);
	pm_error err;
	int bad = 0;

	CHECK(pm_kd_build(b, n, &err) == 0);
	for (size_t i = 0; i < n; i++) {
		int ax = pm_photon_axis(&b[i]);
		bad += 2 * i + 1 < n ? ax > 2 : ax != PM_AXIS_NONE;
		pm_photon_set_axis(&a[i], 0);
		pm_photon_set_axis(&b[i], 0);
	}
	CHECKF(bad == 0, "%d nodes with a wrong axis", bad);
	/* the same multiset of records, only reordered */
	qsort(a, n, sizeof *a, bytecmp);
	qsort(b, n, sizeof *b, bytecmp);
	CHECK(memcmp(a, b, n * sizeof *a) == 0);
	free(a);
	free(b);
}

TEST(build_deterministic)
{
	/* large enough for the threaded build; results must not depend on the
	 * thread count or on the run */
	size_t n = 300000;
	pm_photon *a = points(PLANES, n, 14), *b = points(PLANES, n, 14);
	pm_error err;
	int t = omp_get_max_threads();

	omp_set_num_threads(1);
	CHECK(pm_kd_build(a, n, &err) == 0);
	omp_set_num_threads(4);
	CHECK(pm_kd_build(b, n, &err) == 0);
	omp_set_num_threads(t);
	CHECK(memcmp(a, b, n * sizeof *a) == 0);
	CHECKF(pm_kd_validate(a, n, &err) == 0, "%s", err.msg);
	free(a);
	free(b);
}

TEST(validate_catches)
{
	size_t n = 1000;
	pm_photon *p = points(UNIFORM, n, 15), t;
	pm_error err;

	CHECK(pm_kd_build(p, n, &err) == 0);
	t = p[1];                              /* swap the root's children */
	p[1] = p[2];
	p[2] = t;
	CHECK(pm_kd_validate(p, n, &err) == -1 && strstr(err.msg, "split at node 0"));
	t = p[1];
	p[1] = p[2];
	p[2] = t;
	CHECK(pm_kd_validate(p, n, &err) == 0);
	pm_photon_set_axis(&p[7], PM_AXIS_NONE);
	CHECKF(pm_kd_validate(p, n, &err) == -1 && strstr(err.msg, "node 7 has children but no split axis"),
	       "%s", err.msg);
	pm_photon_set_axis(&p[7], 0);
	/* a deep node moved across a split far above it */
	p[900].pos[pm_photon_axis(&p[0])] = p[0].pos[pm_photon_axis(&p[0])] + (900 % 2 ? 1 : -1) * 5.0f;
	CHECK(pm_kd_validate(p, n, &err) == -1);
	free(p);
}

TEST(empty_and_single)
{
	pm_photon p[1];
	pm_nn out[4];
	pm_error err;
	float x[3] = {0, 0, 0}, dfar = -1;

	CHECK(pm_kd_build(p, 0, &err) == 0);
	CHECK(pm_kd_validate(p, 0, &err) == 0);
	CHECK(pm_kd_knn(p, 0, x, 5, PM_L2, INFINITY, out, &dfar) == 0 && dfar == 0);
	CHECK(pm_kd_depth(0) == 0);
	pm_photon_pack(&p[0], pm_v3(1, 2, 2), pm_v3(0, 0, 1), pm_v3(0, 0, 1), pm_v3(1, 1, 1));
	CHECK(pm_kd_build(p, 1, &err) == 0 && pm_photon_axis(&p[0]) == PM_AXIS_NONE);
	CHECK(pm_kd_knn(p, 1, x, 5, PM_L2, INFINITY, out, &dfar) == 1 && out[0].idx == 0 && dfar == 9);
	CHECK(pm_kd_knn(p, 1, x, 5, PM_LINF, INFINITY, out, &dfar) == 1 && dfar == 2);
	CHECK(pm_kd_knn(p, 1, x, 5, PM_LINF, 2, out, &dfar) == 0 && dfar == 0);   /* d < dmax, strictly */
	CHECK(pm_kd_knn(p, 1, x, 0, PM_L2, INFINITY, out, &dfar) == 0);
	CHECK(pm_kd_depth(1) == 1 && pm_kd_depth(2) == 2 && pm_kd_depth(3) == 2 && pm_kd_depth(4) == 3);
	CHECK(pm_kd_depth(4294967295u) == 32);
}

int
main(void)
{
	RUN(knn_uniform);
	RUN(knn_planes);
	RUN(knn_duplicates);
	RUN(knn_identical);
	RUN(knn_small_sizes);
	RUN(build_keeps_photons);
	RUN(build_deterministic);
	RUN(validate_catches);
	RUN(empty_and_single);
	return check_done();
}
