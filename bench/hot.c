/* hot.c — the view pass's and light pass's hot parts on a real scene, one
 * thread, each against its anchor where there is one:
 *  - ray casting: our tracer (pm_accel_hit, Embree under our settings and
 *    bookkeeping) against raw Embree rtcIntersect1 on the same triangles and
 *    the same rays (camera rays, and diffuse bounce rays from their hits);
 *  - the light pass: pm_shoot's rays per second (every pm_accel_hit it makes
 *    is counted through the linker's --wrap) as a fraction of raw Embree's;
 *  - the photon map build per million photons (one thread, and all threads);
 *  - radiance estimates at the camera's first photon-surface hits, in image
 *    order: classical against compensated (and the compensated estimate's
 *    cube search alone), microseconds per estimate.
 * Not a test: it prints "name<TAB>value" lines, the summary last.
 *
 *   hot [-n PHOTONS] [-k K] [-r RUNS] SCENE */
#include <embree3/rtcore.h>
#include <float.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "scene/accel.h"
#include "optics/bsdf.h"
#include "scene/camera.h"
#include "estimators/compensate.h"
#include "estimators/estimate.h"
#include "optics/frame.h"
#include "formats/kdtree.h"
#include "optics/light.h"
#include "base/rng.h"
#include "scene/scene.h"
#include "passes/shoot.h"
#include "timing.h"

/* Every pm_accel_hit call from the library goes through here (-Wl,--wrap). */
int __real_pm_accel_hit(const pm_accel *a, pm_vec3 o, pm_vec3 d, float tmin, float tmax, pm_hit *h);
static unsigned long long nhits;
int
__wrap_pm_accel_hit(const pm_accel *a, pm_vec3 o, pm_vec3 d, float tmin, float tmax, pm_hit *h)
{
	nhits++;
	return __real_pm_accel_hit(a, o, d, tmin, tmax, h);
}


static void
die(const char *what, const char *msg)
{
	fprintf(stderr, "hot: %s: %s\n", what, msg);
	exit(1);
}

typedef struct ray { pm_vec3 o, d; } ray;

/* Raw Embree: the same triangles in a scene with Embree's defaults (the
 * device free to use its threads for the build, medium quality, no robust
 * flag), traced with plain rtcIntersect1. */
static RTCScene
raw_scene(RTCDevice dev, const pm_scene *s, const pm_vec3 *v)
{
	RTCScene scn = rtcNewScene(dev);
	RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
	float *vb = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
	                                    3 * sizeof(float), s->nverts);
	unsigned *ib = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
	                                       3 * sizeof(unsigned), s->ntris);
	for (uint32_t i = 0; i < s->nverts; i++) {
		vb[3 * i] = v[i].x;
		vb[3 * i + 1] = v[i].y;
		vb[3 * i + 2] = v[i].z;
	}
	memcpy(ib, s->tris, (size_t)s->ntris * 3 * sizeof(unsigned));
	rtcCommitGeometry(g);
	rtcAttachGeometry(scn, g);
	rtcReleaseGeometry(g);
	rtcCommitScene(scn);
	return scn;
}

static double
time_raw(RTCScene scn, const ray *r, long n, double *sink)
{
	struct RTCIntersectContext ctx;
	double t = now(), acc = 0;

	rtcInitIntersectContext(&ctx);
	for (long i = 0; i < n; i++) {
		struct RTCRayHit rh;
		rh.ray.org_x = r[i].o.x; rh.ray.org_y = r[i].o.y; rh.ray.org_z = r[i].o.z;
		rh.ray.dir_x = r[i].d.x; rh.ray.dir_y = r[i].d.y; rh.ray.dir_z = r[i].d.z;
		rh.ray.tnear = 0;
		rh.ray.tfar = FLT_MAX;
		rh.ray.time = 0;
		rh.ray.mask = (unsigned)-1;
		rh.ray.id = 0;
		rh.ray.flags = 0;
		rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
		rtcIntersect1(scn, &ctx, &rh);
		if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID)
			acc += rh.ray.tfar;
	}
	*sink += acc;
	return now() - t;
}

static double
time_ours(const pm_accel *a, const ray *r, long n, double *sink)
{
	double t = now(), acc = 0;
	pm_hit h;

	for (long i = 0; i < n; i++)
		if (pm_accel_hit(a, r[i].o, r[i].d, 0.0f, FLT_MAX, &h))
			acc += h.t;
	*sink += acc;
	return now() - t;
}

int
main(int argc, char **argv)
{
	long nph = 200000;
	int k = 50, runs = 3, c;
	pm_scene s;
	pm_frame fr;
	pm_camera cam;
	pm_error err;
	double sink = 0, tv[99], tw[99];

	while ((c = getopt(argc, argv, "k:n:r:")) != -1) {
		switch (c) {
		case 'k': k = atoi(optarg); break;
		case 'n': nph = atol(optarg); break;
		case 'r': runs = atoi(optarg); break;
		default:
			fprintf(stderr, "usage: hot [-n PHOTONS] [-k K] [-r RUNS] SCENE\n");
			return 2;
		}
	}
	if (argc - optind != 1 || nph < 1 || k < 1 || runs < 1 || runs > 99) {
		fprintf(stderr, "usage: hot [-n PHOTONS] [-k K] [-r RUNS] SCENE\n");
		return 2;
	}
	const char *path = argv[optind];
	int ncpu = omp_get_max_threads();
	omp_set_num_threads(1);
	if (pm_scene_load(&s, path, &err))
		die(path, err.msg);
	if (pm_frame_build(&fr, &s, 0, PM_NEEDS_POLYINDEX, &err) || pm_camera_init(&cam, &s.camera, &err))
		die(path, err.msg);
	const pm_accel *a = fr.accel;
	printf("scene\t%s\ntriangles\t%u\n", path, s.ntris);

	/* Rays: one camera ray per pixel centre, and from each hit a cosine
	 * bounce ray (the light pass's and the path tracer's kind of ray). */
	long np = (long)cam.width * cam.height, nb = 0;
	ray *cr = malloc((size_t)np * sizeof *cr), *br = malloc((size_t)np * sizeof *br);
	pm_vec3 *hx = malloc((size_t)np * sizeof *hx), *hn = malloc((size_t)np * sizeof *hn);
	pm_vec3 *hw = malloc((size_t)np * sizeof *hw);
	const pm_material **hm = malloc((size_t)np * sizeof *hm);
	long ne = 0;
	if (!cr || !br || !hx || !hn || !hw || !hm)
		die(path, "out of memory");
	pm_rng r = pm_rng_seed(9, 0);
	for (int y = 0; y < cam.height; y++)
		for (int x = 0; x < cam.width; x++) {
			long i = (long)y * cam.width + x;
			pm_hit h;
			cr[i].o = cam.eye;
			cr[i].d = pm_camera_dir(&cam, x + 0.5f, y + 0.5f);
			if (!pm_accel_hit(a, cr[i].o, cr[i].d, 0, FLT_MAX, &h))
				continue;
			pm_vec3 wo = pm_neg(cr[i].d);
			pm_vec3 n = pm_dot(h.ng, wo) >= 0 ? h.ng : pm_neg(h.ng);
			pm_vec3 d = pm_sample_cosine(n, pm_rng_f(&r), pm_rng_f(&r));
			br[nb].o = pm_accel_offset(a, h.p, h.ng, d);
			br[nb++].d = d;
			const pm_material *m = &s.mats[s.objs[h.obj].material];
			if (pm_mat_is_photon_surface(m)) {
				hx[ne] = h.p;
				hn[ne] = n;
				hw[ne] = wo;
				hm[ne++] = m;
			}
		}

	RTCDevice dev = rtcNewDevice("verbose=0");
	RTCScene raw = raw_scene(dev, &s, fr.verts);
	const char *kind[2] = {"camera", "bounce"};
	const ray *rs[2] = {cr, br};
	long rn[2] = {np, nb};
	double raw_rps = 0;
	for (int j = 0; j < 2; j++) {
		for (int i = 0; i < runs; i++) {
			tv[i] = time_raw(raw, rs[j], rn[j], &sink);
			tw[i] = time_ours(a, rs[j], rn[j], &sink);
		}
		double rr = rn[j] / median(tv, runs), ro = rn[j] / median(tw, runs);
		printf("rays_%s_per_s_embree\t%.0f\nrays_%s_per_s_ours\t%.0f\nrays_%s_fraction\t%.3f\n",
		       kind[j], rr, kind[j], ro, kind[j], ro / rr);
		if (j == 1)
			raw_rps = rr;
	}

	/* The light pass, one thread: rays per second including everything it
	 * does per ray (sampling, BSDF, storing photons). */
	pm_shoot_opts so = {.nphotons = (uint64_t)nph, .seed = 1};
	pm_photons ph;
	for (int i = 0; i < runs; i++) {
		nhits = 0;
		double t = now();
		if (pm_shoot(&s, a, &fr.lights, &so, &ph, &err))
			die(path, err.msg);
		tv[i] = now() - t;
		if (i + 1 < runs)
			pm_photons_free(&ph);
	}
	double tshoot = median(tv, runs);
	printf("shoot_photons\t%llu\nshoot_paths\t%llu\nshoot_rays\t%llu\nshoot_s\t%.4f\n"
	       "shoot_rays_per_s\t%.0f\nshoot_fraction_of_embree\t%.3f\n",
	       (unsigned long long)ph.h.count, (unsigned long long)ph.h.emitted, nhits, tshoot,
	       nhits / tshoot, nhits / tshoot / raw_rps);

	/* The photon map build, per million photons. */
	pm_photon *orig = malloc((size_t)ph.h.count * sizeof *orig);
	if (!orig)
		die(path, "out of memory");
	memcpy(orig, ph.p, (size_t)ph.h.count * sizeof *orig);
	for (int th = 0; th < 2; th++) {
		omp_set_num_threads(th ? ncpu : 1);
		for (int i = 0; i < runs; i++) {
			memcpy(ph.p, orig, (size_t)ph.h.count * sizeof *orig);
			double t = now();
			if (pm_kd_build(ph.p, (size_t)ph.h.count, &err))
				die(path, err.msg);
			tv[i] = now() - t;
		}
		printf("build_s_per_M_%s\t%.4f\n", th ? "all_threads" : "1_thread",
		       median(tv, runs) * 1e6 / (double)ph.h.count);
	}
	omp_set_num_threads(1);
	free(orig);
	ph.h.kdtree = 1;

	/* Estimates at the first photon-surface hits, in image order. */
	const pm_polyindex *pi = fr.pi;
	pm_nn *nn = malloc((size_t)k * sizeof *nn);
	pm_comp_scratch *sc = pm_comp_scratch_new(k);
	double tc[99], tq[99];
	long multi = 0, sampled = 0, npolys = 0;
	if (!nn || !sc)
		die(path, "out of memory");
	for (int i = 0; i < runs; i++) {
		pm_estimate_info info;
		float dfar;
		double t = now();
		for (long j = 0; j < ne; j++)
			sink += pm_estimate_classical(&ph, hx[j], hn[j], hw[j], hm[j], k, nn, &info).x;
		tv[i] = now() - t;
		t = now();
		for (long j = 0; j < ne; j++)
			sink += pm_estimate_compensated(pi, &ph, hx[j], hn[j], hw[j], hm[j], k, sc, &info).x;
		tc[i] = now() - t;
		if (i == 0)
			for (long j = 0; j < ne; j++) {
				const pm_comp_stats *cs;
				sink += pm_estimate_compensated(pi, &ph, hx[j], hn[j], hw[j], hm[j], k, sc, &info).x;
				cs = pm_comp_last(sc);
				multi += cs->polys > 1;
				sampled += cs->sampled > 0;
				npolys += cs->polys;
			}
		t = now();
		for (long j = 0; j < ne; j++) {
			float q[3] = {hx[j].x, hx[j].y, hx[j].z};
			sink += pm_kd_knn(ph.p, (size_t)ph.h.count, q, k, PM_LINF, INFINITY, nn, &dfar);
		}
		tq[i] = now() - t;
		t = now();
		for (long j = 0; j < ne; j++) {
			float q[3] = {hx[j].x, hx[j].y, hx[j].z};
			sink += pm_kd_knn(ph.p, (size_t)ph.h.count, q, k, PM_L2, INFINITY, nn, &dfar);
		}
		tw[i] = now() - t;
	}
	double ucl = 1e6 * median(tv, runs) / ne, uco = 1e6 * median(tc, runs) / ne;
	double ucq = 1e6 * median(tq, runs) / ne, usq = 1e6 * median(tw, runs) / ne;
	printf("pixels\t%ld\nestimates\t%ld\nk\t%d\nphotons_in_map\t%llu\n", np, ne, k, (unsigned long long)ph.h.count);
	printf("us_classical\t%.3f\nus_classical_search\t%.3f\nus_compensated\t%.3f\n"
	       "us_compensated_search\t%.3f\n", ucl, usq, uco, ucq);
	fprintf(stderr, "checksum %g\n", sink);
	printf("compensated_over_classical\t%.3f\n", uco / ucl);
	/* How often the cube holds more than one polygon, and how often one of
	 * them can hide part of another (sample points needed). */
	printf("comp_multi_polygon\t%.4f\ncomp_sampled\t%.4f\ncomp_mean_polygons\t%.2f\n",
	       (double)multi / ne, (double)sampled / ne, (double)npolys / ne);

	pm_comp_scratch_free(sc);
	free(nn);
	rtcReleaseScene(raw);
	rtcReleaseDevice(dev);
	pm_photons_free(&ph);
	pm_frame_free(&fr);
	free(cr);
	free(br);
	free(hx);
	free(hn);
	free(hw);
	free(hm);
	pm_scene_free(&s);
	return 0;
}
