/* compcost.c — what one compensated estimate costs against the classical
 * one, and how that grows with the polygons meeting its cube (issue 21's
 * "no cliff"): estimates at the camera's first photon-surface hits (pixel
 * centres), one thread, each timed alone (thread CPU time).
 *
 *   compcost [-c CAST_AT] [-f POLYS] [-n PHOTONS] [-k K] [-r RUNS] [-o FILE] [-p LO,HI[,GROUPS]] [-S] SCENE
 *   compcost -t SCENE      (prints the scene's triangles and stops)
 *
 * Prints "name<TAB>value" lines: the median over RUNS of the mean time per
 * estimate, classical and compensated, their ratio, a checksum of the
 * compensated estimates (the same for any change that computes the same
 * thing), the photons whose target area the floor raised (compensate.h,
 * PM_COMP_FLOOR_REL) and in how many estimates, the polygons given sample
 * points and those found hidden from x' whole without (pm_comp_stats
 * sampled, whole), and per bin of polygons in the cube (1, 2, 3-4, 5-8,
 * ...) the estimates there, their mean time (and the classical one's at
 * the same points), and the bin's share of the time the compensated
 * estimates take over the classical ones. -o
 * writes one line per estimate: polygons in its cube, those sampled,
 * microseconds (compensated, classical), the compensated RGB, the groups
 * (sheets and lone polygons) and the polygons whose fates went by rays
 * (pm_comp_stats), for plots and for comparing two builds estimate by
 * estimate. -c sets the compensated estimate's CAST_AT (pm_comp_cast_at,
 * compensate.h), which changes its time, not its answers. -S has each
 * facet cast its own rays (pm_comp_share_cells 0). -p runs the
 * compensated estimates whose cubes hold LO to HI polygons (and, with
 * GROUPS, that many groups) five times more in profile_range(), for a
 * profiler to count those alone:
 *   valgrind --tool=callgrind --collect-atstart=no \
 *       --toggle-collect=profile_range compcost -r 1 -p 32,100000 SCENE */
#include <float.h>
#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "scene/accel.h"
#include "scene/camera.h"
#include "estimators/compensate.h"
#include "estimators/estimate.h"
#include "optics/frame.h"
#include "formats/kdtree.h"
#include "scene/scene.h"
#include "passes/shoot.h"
#include "timing.h"

#define NBIN 16

/* This thread's CPU time: the machine may be shared, and an estimate that
 * waited for a core did not cost more. */
static double
cpu_now(void)
{
	struct timespec t;
	clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void
die(const char *what, const char *msg)
{
	fprintf(stderr, "compcost: %s: %s\n", what, msg);
	exit(1);
}

static int
bin_of(int polys)
{
	int b = 0;
	while (b < NBIN - 1 && (1 << b) < polys)
		b++;
	return b;
}

static int
usage(void)
{
	fprintf(stderr, "usage: compcost [-c CAST_AT] [-f POLYS] [-n PHOTONS] [-k K] [-r RUNS] [-o FILE] [-p LO,HI[,GROUPS]] [-S] SCENE\n");
	return 2;
}

/* The compensated estimates sel[0 .. nsel), five times: a function of its
 * own for a profiler's toggle (-p). */
__attribute__((noinline)) static double
profile_range(const pm_polyindex *pi, const pm_photons *ph, const long *sel, long nsel,
              const pm_vec3 *hx, const pm_vec3 *hn, const pm_vec3 *hw, const pm_material **hm,
              int k, pm_comp_scratch *sc)
{
	pm_estimate_info info;
	double sink = 0;
	for (int r = 0; r < 5; r++)
		for (long i = 0; i < nsel; i++) {
			long j = sel[i];
			sink += pm_estimate_compensated(pi, ph, hx[j], hn[j], hw[j], hm[j], k, sc, &info).x;
		}
	return sink;
}

int
main(int argc, char **argv)
{
	long nph = 200000;
	int k = 50, runs = 3, c, tris_only = 0;
	const char *out = NULL;
	int plo = -1, phi = -1, pgr = 0;
	pm_scene s;
	pm_frame fr;
	pm_camera cam;
	pm_error err;

	while ((c = getopt(argc, argv, "c:f:k:n:o:p:r:St")) != -1) {
		switch (c) {
		case 'c': pm_comp_cast_at = atoi(optarg); break;
		case 'f': pm_comp_fate_cast_from = atoi(optarg); break;
		case 'k': k = atoi(optarg); break;
		case 'n': nph = atol(optarg); break;
		case 'o': out = optarg; break;
		case 'p':
			if (sscanf(optarg, "%d,%d,%d", &plo, &phi, &pgr) < 2 || plo < 1 || phi < plo || pgr < 0) {
				fprintf(stderr, "compcost: -p wants LO,HI[,GROUPS]: polygons 1 <= LO <= HI, and groups (0: any)\n");
				return 2;
			}
			break;
		case 'r': runs = atoi(optarg); break;
		case 't': tris_only = 1; break;
		case 'S': pm_comp_share_cells = 0; break;
		default:
			return usage();
		}
	}
	if (argc - optind != 1 || nph < 1 || k < 1 || runs < 1 || runs > 99) {
		return usage();
	}
	const char *path = argv[optind];
	omp_set_num_threads(1);
	if (pm_scene_load(&s, path, &err))
		die(path, err.msg);
	if (tris_only) {
		printf("triangles\t%u\n", s.ntris);
		return 0;
	}
	if (pm_frame_build(&fr, &s, 0, PM_NEEDS_POLYINDEX, &err) || pm_camera_init(&cam, &s.camera, &err))
		die(path, err.msg);

	long np = (long)cam.width * cam.height, ne = 0;
	pm_vec3 *hx = malloc((size_t)np * sizeof *hx), *hn = malloc((size_t)np * sizeof *hn);
	pm_vec3 *hw = malloc((size_t)np * sizeof *hw);
	const pm_material **hm = malloc((size_t)np * sizeof *hm);
	if (!hx || !hn || !hw || !hm)
		die(path, "out of memory");
	for (int y = 0; y < cam.height; y++)
		for (int x = 0; x < cam.width; x++) {
			pm_vec3 d = pm_camera_dir(&cam, x + 0.5f, y + 0.5f);
			pm_hit h;
			if (!pm_accel_hit(fr.accel, cam.eye, d, 0, FLT_MAX, &h))
				continue;
			const pm_material *m = &s.mats[s.objs[h.obj].material];
			if (!pm_mat_is_photon_surface(m))
				continue;
			hx[ne] = h.p;
			hw[ne] = pm_neg(d);
			hn[ne] = pm_dot(h.ng, hw[ne]) >= 0 ? h.ng : pm_neg(h.ng);
			hm[ne++] = m;
		}
	if (ne == 0)
		die(path, "the camera sees no photon surface");

	pm_shoot_opts so = {.nphotons = (uint64_t)nph, .seed = 1};
	pm_photons ph;
	if (pm_shoot(&s, fr.accel, &fr.lights, &so, &ph, &err) || pm_kd_build(ph.p, (size_t)ph.h.count, &err))
		die(path, err.msg);
	ph.h.kdtree = 1;

	pm_nn *nn = malloc((size_t)k * sizeof *nn);
	pm_comp_scratch *sc = pm_comp_scratch_new(k);
	double *tcl = malloc((size_t)ne * sizeof *tcl), *tco = malloc((size_t)ne * sizeof *tco);
	int *polys = malloc((size_t)ne * sizeof *polys), *nsam = malloc((size_t)ne * sizeof *nsam);
	int *ngrp = malloc((size_t)ne * sizeof *ngrp), *nfc = malloc((size_t)ne * sizeof *nfc);
	pm_vec3 *L = malloc((size_t)ne * sizeof *L);
	double tv[99], tw[99], sink = 0;
	long nfl = 0, efl = 0, nwh = 0, nsm = 0, nsn = 0, esn = 0, nsh = 0;
	if (!nn || !sc || !tcl || !tco || !polys || !nsam || !ngrp || !nfc || !L)
		die(path, "out of memory");
	for (long j = 0; j < ne; j++)
		tcl[j] = tco[j] = INFINITY;
	for (int i = 0; i < runs; i++) {
		pm_estimate_info info;
		double t0 = cpu_now(), t;
		for (long j = 0; j < ne; j++) {
			t = cpu_now();
			sink += pm_estimate_classical(&ph, hx[j], hn[j], hw[j], hm[j], k, nn, &info).x;
			t = cpu_now() - t;
			tcl[j] = t < tcl[j] ? t : tcl[j];
		}
		tv[i] = cpu_now() - t0;
		t0 = cpu_now();
		for (long j = 0; j < ne; j++) {
			t = cpu_now();
			L[j] = pm_estimate_compensated(fr.pi, &ph, hx[j], hn[j], hw[j], hm[j], k, sc, &info);
			t = cpu_now() - t;
			tco[j] = t < tco[j] ? t : tco[j];
			polys[j] = pm_comp_last(sc)->polys;
			nsam[j] = pm_comp_last(sc)->sampled;
			ngrp[j] = pm_comp_last(sc)->groups;
			nfc[j] = pm_comp_last(sc)->fcast;
			if (i == 0) {
				nfl += pm_comp_last(sc)->floored;
				efl += pm_comp_last(sc)->floored > 0;
				nwh += pm_comp_last(sc)->whole;
				nsm += pm_comp_last(sc)->sampled;
				nsn += pm_comp_last(sc)->nodes;
				esn += pm_comp_last(sc)->nodes > 0;
				nsh += pm_comp_last(sc)->shared;
			}
		}
		tw[i] = cpu_now() - t0;
	}
	if (plo > 0) {
		long *sel = malloc((size_t)ne * sizeof *sel), nsel = 0;
		if (!sel)
			die(path, "out of memory");
		for (long j = 0; j < ne; j++)
			if (polys[j] >= plo && polys[j] <= phi && (pgr == 0 || ngrp[j] == pgr))
				sel[nsel++] = j;
		fprintf(stderr, "compcost: profile_range: %ld estimates of %d to %d polygons, 5 times\n", nsel, plo, phi);
		sink += profile_range(fr.pi, &ph, sel, nsel, hx, hn, hw, hm, k, sc);
		free(sel);
	}
	/* FNV-1a over the estimates' bits. */
	uint64_t hsh = 1469598103934665603ull;
	for (long j = 0; j < ne; j++) {
		unsigned char b[12];
		memcpy(b, &L[j], 12);
		for (int i = 0; i < 12; i++)
			hsh = (hsh ^ b[i]) * 1099511628211ull;
	}
	double ucl = 1e6 * median(tv, runs) / ne, uco = 1e6 * median(tw, runs) / ne;
	printf("scene\t%s\ntriangles\t%u\nestimates\t%ld\nk\t%d\nphotons_in_map\t%llu\n", path, s.ntris, ne, k,
	       (unsigned long long)ph.h.count);
	printf("us_classical\t%.3f\nus_compensated\t%.3f\ncompensated_over_classical\t%.3f\n",
	       ucl, uco, uco / ucl);
	printf("checksum\t%016llx\n", (unsigned long long)hsh);
	printf("floored\t%ld photons in %ld estimates\n", nfl, efl);
	printf("sampled\t%ld polygons; %ld more hidden whole, unsampled\n", nsm, nwh);
	printf("sheet_nodes\t%ld estimates of one sheet from %ld index nodes\n", esn, nsn);
	printf("shared\t%ld facets took their cell's rays\n", nsh);
	/* Per bin also the classical estimates' mean at the same points, and
	 * the bin's share of what the compensated ones cost over them: where
	 * the price comes from, which the means alone hide (many cheap
	 * estimates can outweigh a few dear ones). */
	long cnt[NBIN] = {0};
	double sum[NBIN] = {0}, mx[NBIN] = {0}, scl[NBIN] = {0}, extra = 0;
	for (long j = 0; j < ne; j++) {
		int b = bin_of(polys[j]);
		cnt[b]++;
		sum[b] += tco[j];
		scl[b] += tcl[j];
		extra += tco[j] - tcl[j];
		mx[b] = tco[j] > mx[b] ? tco[j] : mx[b];
	}
	for (int b = 0; b < NBIN; b++)
		if (cnt[b])
			printf("polys_le_%d\t%ld estimates, mean %.2f us (classical %.2f), max %.1f us, "
			       "%.1f %% of the extra\n", 1 << b, cnt[b], 1e6 * sum[b] / cnt[b],
			       1e6 * scl[b] / cnt[b], 1e6 * mx[b], extra > 0 ? 100 * (sum[b] - scl[b]) / extra : 0);
	if (out) {
		FILE *f = fopen(out, "w");
		if (!f)
			die(out, "cannot create");
		for (long j = 0; j < ne; j++)
			fprintf(f, "%d\t%d\t%.3f\t%.3f\t%.9g\t%.9g\t%.9g\t%d\t%d\n", polys[j], nsam[j], 1e6 * tco[j],
			        1e6 * tcl[j], L[j].x, L[j].y, L[j].z, ngrp[j], nfc[j]);
		if (ferror(f) | fclose(f))
			die(out, "cannot write");
	}
	fprintf(stderr, "sink %g\n", sink);
	return 0;
}
