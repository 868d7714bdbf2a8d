/* photonview.c — the photon map itself as seen from the camera (see
 * photonview.h; paper figure 3c). */
#include "estimators/photonview.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "optics/bsdf.h"

/* Each photon's pixel and contribution are found in parallel, then summed
 * in photon order, so the image does not depend on the thread count. */
int
pm_photonview_image(const pm_est_in *in, const pm_camera *cam, pm_image *img, pm_error *err)
{
	const pm_scene *s = in->s;
	const pm_accel *a = in->a;
	const pm_photons *map = in->map;
	int W = cam->width, H = cam->height;
	size_t npx = (size_t)W * H, n = (size_t)map->h.count;
	double emitted = map->h.emitted ? (double)map->h.emitted : 1.0;
	/* Pixel side on the image plane at distance 1. */
	float pix = 2.0f * cam->tan_half / (float)H;
	float aspect = (float)W / (float)H;
	long *at = malloc((n ? n : 1) * sizeof *at);
	pm_vec3 *val = malloc((n ? n : 1) * sizeof *val);
	float *R = pm_image_chan(img, "R"), *G = pm_image_chan(img, "G"), *B = pm_image_chan(img, "B");
	float *IR = pm_image_chan(img, "indirect.R"), *IG = pm_image_chan(img, "indirect.G");
	float *IB = pm_image_chan(img, "indirect.B"), *cnt = pm_image_chan(img, "count");

	if (!at || !val) {
		free(at);
		free(val);
		return pm_seterr(err, "out of memory");
	}
	#pragma omp parallel for schedule(dynamic, 4096)
	for (size_t i = 0; i < n; i++) {
		pm_vec3 p = pm_photon_pos(&map->p[i]), v = pm_sub(p, cam->eye), d, wo, nrm;
		float z = pm_dot(v, cam->f), dist = pm_len(v), x, y, cosa, coso, area;
		const pm_material *m;
		pm_hit h;
		long px, py;

		at[i] = -1;
		if (!(z > 0) || !(dist > 0))
			continue;
		x = pm_dot(v, cam->r) / z;
		y = pm_dot(v, cam->u) / z;
		x = (x / (cam->tan_half * aspect) + 1.0f) * 0.5f * (float)W;
		y = (1.0f - y / cam->tan_half) * 0.5f * (float)H;
		if (!(x >= 0 && x < (float)W && y >= 0 && y < (float)H))
			continue;
		px = (long)x;
		py = (long)y;
		d = pm_scale(v, 1.0f / dist);
		/* Depth test: the camera sees the photon if the first surface
		 * along the ray to it is where the photon lies. */
		if (!pm_accel_hit(a, cam->eye, d, 0.0f, FLT_MAX, &h) ||
		    fabsf(h.t - dist) > 1e-3f * dist + 1e-6f)
			continue;
		m = &s->mats[s->objs[h.obj].material];
		wo = pm_neg(d);
		nrm = pm_dot(h.ng, wo) >= 0 ? h.ng : pm_neg(h.ng);
		cosa = z / dist;
		coso = pm_dot(nrm, wo);
		if (!(coso > 0))
			continue;
		/* Footprint: the pixel's solid angle pix^2 cos^3(a) at distance
		 * dist, spread over a surface tilted by the view angle. */
		area = dist * dist * pix * pix * cosa * cosa * cosa / coso;
		val[i] = pm_scale(pm_mul(pm_bsdf_eval(m, nrm, pm_photon_dir(&map->p[i]), wo),
		                         pm_photon_power(&map->p[i])),
		                  (float)(1.0 / emitted) / area);
		at[i] = py * W + px;
	}
	for (size_t i = 0; i < n; i++) {
		long k = at[i];
		if (k < 0 || !pm_vfinite(val[i]))
			continue;
		R[k] += val[i].x;
		G[k] += val[i].y;
		B[k] += val[i].z;
		cnt[k] += 1.0f;
	}
	for (size_t k = 0; k < npx; k++) {
		IR[k] = R[k];
		IG[k] = G[k];
		IB[k] = B[k];
	}
	free(at);
	free(val);
	return 0;
}
