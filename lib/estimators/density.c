/* density.c — density control as a map filter (see density.h). */
#include "estimators/density.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/camera.h"
#include "formats/kdtree.h"
#include "base/rng.h"

#define DENSITY_DOMAIN 0x44454e534954ull
/* A photon not stored looks for stored ones among its k, 4k, 16k nearest:
 * where few are kept (f k < 1) the k nearest often hold none. */
#define REACH 16

/* The points the camera sees, as photon records (kd-tree searches) whose
 * power's first channel holds the target radius C a_j (to 2^-10). */
static pm_photon *
seen_points(const pm_frame *f, double pixels, size_t *n, pm_error *err)
{
	const pm_scene *s = f->s;
	pm_camera cam;
	pm_photon *pts;
	size_t m = 0;

	if (pm_camera_init(&cam, &s->camera, err) != 0)
		return NULL;
	pts = malloc((size_t)cam.width * cam.height * sizeof *pts);
	if (!pts) {
		pm_seterr(err, "out of memory");
		return NULL;
	}
	float a = 2.0f * cam.tan_half / (float)cam.height;
	for (int y = 0; y < cam.height; y++)
		for (int x = 0; x < cam.width; x++) {
			pm_vec3 d = pm_camera_dir(&cam, (float)x + 0.5f, (float)y + 0.5f);
			pm_hit h;
			if (!pm_accel_hit(f->accel, cam.eye, d, 0.0f, FLT_MAX, &h))
				continue;
			pm_photon_pack(&pts[m++], h.p, d, d, pm_v3((float)(pixels * h.t * a), 0, 0));
		}
	*n = m;
	return pts;
}

int
pm_density_control(const pm_frame *f, pm_photons *map, const pm_density_opts *o,
                   pm_error *err)
{
	size_t n = (size_t)map->h.count, nseen = 0, kept = 0;
	int k = o->k, oom = 0;
	pm_photon *seen, *out;
	pm_nn *nn;
	unsigned char *keep;
	double *extra;

	if (n == 0 || k < 1)
		return 0;
	if (!(seen = seen_points(f, o->pixels, &nseen, err)))
		return -1;
	if (nseen == 0) {
		free(seen);
		return 0;       /* the camera sees nothing: no importance to go by */
	}
	if (pm_kd_build(seen, nseen, err) != 0) {
		free(seen);
		return -1;
	}
	keep = malloc(n);
	extra = calloc(3 * n, sizeof *extra);
	nn = malloc((size_t)(REACH * k + 1) * sizeof *nn);
	if (!keep || !extra || !nn) {
		free(keep);
		free(extra);
		free(nn);
		free(seen);
		return pm_seterr(err, "out of memory");
	}

	/* Which photons stay: f = min(1, (r_k / r)^2) against a hash of the
	 * index. */
	#pragma omp parallel reduction(|:oom)
	{
		pm_nn *loc = malloc((size_t)(k + 1) * sizeof *loc);
		oom |= !loc;
		#pragma omp for schedule(dynamic, 1024)
		for (size_t i = 0; i < n; i++) {
			pm_nn one;
			float q[3] = {map->p[i].pos[0], map->p[i].pos[1], map->p[i].pos[2]}, d2 = 0, rk2 = 0;
			keep[i] = 1;
			if (!loc || pm_kd_knn(seen, nseen, q, 1, PM_L2, INFINITY, &one, &d2) < 1)
				continue;
			double r = fmax(pm_photon_power(&seen[one.idx]).x, sqrt(d2));
			int got = pm_kd_knn(map->p, n, q, k, PM_L2, INFINITY, loc, &rk2);
			if (got < k || !(r > 0))
				continue;
			pm_rng g = pm_rng_seed(DENSITY_DOMAIN, i);
			keep[i] = pm_rng_f(&g) < rk2 / (r * r);
		}
		free(loc);
	}
	if (oom) {
		free(keep);
		free(extra);
		free(nn);
		free(seen);
		return pm_seterr(err, "out of memory");
	}
	/* A photon without a stored neighbour keeps its power by staying. Only
	 * photons not stored turn stored here, so no other's neighbours lose
	 * one. */
	for (size_t i = 0; i < n; i++) {
		float q[3] = {map->p[i].pos[0], map->p[i].pos[1], map->p[i].pos[2]}, rk2;
		int got, to = 0;
		if (keep[i] == 1)
			continue;
		for (int kk = k; to == 0 && kk <= REACH * k; kk *= 4) {
			got = pm_kd_knn(map->p, n, q, kk, PM_L2, INFINITY, nn, &rk2);
			for (int j = 0; j < got; j++)
				to += keep[nn[j].idx] == 1;
			if (got < kk)
				break;
		}
		if (to == 0) {
			keep[i] = 2;    /* stored, but gives nothing to others' lists */
			continue;
		}
		pm_vec3 P = pm_photon_power(&map->p[i]);
		for (int j = 0; j < got; j++)
			if (keep[nn[j].idx] == 1) {
				double *e = extra + 3 * (size_t)nn[j].idx;
				e[0] += (double)P.x / to;
				e[1] += (double)P.y / to;
				e[2] += (double)P.z / to;
			}
	}
	out = map->p;
	for (size_t i = 0; i < n; i++) {
		if (!keep[i])
			continue;
		pm_photon p = map->p[i];
		if (extra[3 * i] > 0 || extra[3 * i + 1] > 0 || extra[3 * i + 2] > 0) {
			/* New power bits (0-37), the direction's and axis's kept. */
			pm_vec3 P = pm_photon_power(&p), d = pm_photon_dir(&p);
			pm_photon t;
			pm_photon_pack(&t, pm_photon_pos(&p), d, d,
			               pm_v3((float)(P.x + extra[3 * i]), (float)(P.y + extra[3 * i + 1]),
			                     (float)(P.z + extra[3 * i + 2])));
			p.bits[0] = t.bits[0];
			p.bits[1] = (p.bits[1] & ~0x3fu) | (t.bits[1] & 0x3fu);
		}
		out[kept++] = p;
	}
	free(keep);
	free(extra);
	free(nn);
	free(seen);
	map->h.count = kept;
	return pm_kd_build(map->p, kept, err);
}
