/* irradiance.c — precomputed irradiance at photon positions (see
 * irradiance.h). */
#include "estimators/irradiance.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "formats/kdtree.h"

/* The front normal of the surface photon p was stored on, found by casting
 * back along its direction from just in front of it; 0 if nothing is hit. */
static int
photon_normal(const pm_accel *a, const pm_photon *p, pm_vec3 *n)
{
	pm_vec3 x = pm_photon_pos(p), psi = pm_photon_dir(p);
	pm_vec3 o = pm_accel_offset(a, x, psi, psi);
	pm_hit h;

	if (!pm_accel_hit(a, o, pm_neg(psi), 0.0f, 4.0f * pm_accel_eps(a, x), &h))
		return 0;
	*n = pm_dot(h.ng, psi) >= 0 ? h.ng : pm_neg(h.ng);
	return 1;
}

int
pm_irradiance_build(pm_irradiance *irr, const pm_estimator *est, const pm_est_in *in,
                    int every, pm_error *err)
{
	const pm_photons *map = in->map;
	size_t n = every >= 1 ? (size_t)((map->h.count + (uint64_t)every - 1) / (uint64_t)every) : 0;
	pm_material white;
	pm_photon *pts;
	char *ok;
	int fail = 0;

	memset(irr, 0, sizeof *irr);
	if (every < 1)
		return pm_seterr(err, "precomputed irradiance: every must be >= 1");
	memset(&white, 0, sizeof white);
	white.kind = PM_MAT_DIFFUSE;
	white.kd = pm_v3(1, 1, 1);
	pts = malloc((n ? n : 1) * sizeof *pts);
	ok = calloc(n ? n : 1, 1);
	if (!pts || !ok) {
		free(pts);
		free(ok);
		return pm_seterr(err, "out of memory for %zu irradiance points", n);
	}
	#pragma omp parallel reduction(|:fail)
	{
		void *sc = est->scratch_new ? est->scratch_new(in->k) : NULL;
		if (est->scratch_new && !sc)
			fail = 1;
		#pragma omp for schedule(dynamic, 256)
		for (size_t i = 0; i < n; i++) {
			const pm_photon *p = &map->p[i * (size_t)every];
			pm_estimate_info info;
			pm_vec3 nrm, x = pm_photon_pos(p), L;
			if (fail || !photon_normal(in->a, p, &nrm))
				continue;
			/* Seen along the normal: the white surface reflects the same
			 * toward every direction. */
			L = est->estimate(in, sc, x, nrm, nrm, nrm, &white, &info);
			pm_photon_pack(&pts[i], x, nrm, nrm, pm_vfinite(L) ? L : pm_v3(0, 0, 0));
			ok[i] = 1;
		}
		if (sc)
			est->scratch_free(sc);
	}
	if (fail) {
		free(pts);
		free(ok);
		return pm_seterr(err, "out of memory");
	}
	size_t m = 0;
	for (size_t i = 0; i < n; i++)
		if (ok[i])
			pts[m++] = pts[i];
	free(ok);
	if (pm_kd_build(pts, m, err) != 0) {
		free(pts);
		return -1;
	}
	irr->pts.p = pts;
	irr->pts.h.count = m;
	irr->pts.h.emitted = 1;
	irr->pts.h.kdtree = 1;
	return 0;
}

int
pm_irradiance_lookup(const pm_irradiance *irr, pm_vec3 x, pm_vec3 n, pm_vec3 *L)
{
	float q[3] = {x.x, x.y, x.z}, dfar, best = INFINITY;
	pm_nn nn[PM_IRR_NEAR];
	int got, pick = -1;

	if (irr->pts.h.count == 0)
		return 0;
	got = pm_kd_knn(irr->pts.p, (size_t)irr->pts.h.count, q, PM_IRR_NEAR, PM_L2, INFINITY, nn, &dfar);
	for (int i = 0; i < got; i++) {
		const pm_photon *p = &irr->pts.p[nn[i].idx];
		/* Nearest first, ties by index, so the pick is a function of x. */
		if (pm_dot(pm_photon_dir(p), n) < PM_IRR_COS)
			continue;
		if (nn[i].d < best || (nn[i].d == best && (int)nn[i].idx < pick)) {
			best = nn[i].d;
			pick = (int)nn[i].idx;
		}
	}
	if (pick < 0)
		return 0;
	*L = pm_photon_power(&irr->pts.p[pick]);
	return 1;
}

void
pm_irradiance_free(pm_irradiance *irr)
{
	pm_photons_free(&irr->pts);
}
