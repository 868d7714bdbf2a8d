/* gather.c — final gathering (see gather.h). */
#include "passes/gather.h"

#include <float.h>
#include <math.h>

#include "optics/bsdf.h"
#include "passes/direct.h"

#define GATHER_DEPTH 16     /* strong surfaces a gather ray may pass */

void
pm_gather_init(pm_gather *g, const pm_frame *f, const pm_estimator *est,
               const pm_est_in *in, const pm_gather_opts *o)
{
	g->s = f->s;
	g->a = f->accel;
	g->L = &f->lights;
	g->est = est;
	g->global = *in;
	g->caustic = *in;
	g->caustic.map = o->caustic;
	g->o = o;
}

/* Direct light at y: one shadow ray to a light sample and a BSDF sample
 * that may meet an emitter, combined as the view pass combines them
 * (direct.h). Light sampling alone has a heavy tail where a gather ray
 * lands beside an emitter (a ceiling around its lamp, every corner of a
 * furnace). */
static pm_vec3
direct_at(const pm_gather *g, const pm_hit *y, pm_vec3 n, pm_vec3 wo, const pm_material *m,
          pm_rng *r)
{
	pm_direct dl = {g->s, g->a, g->L};
	pm_vec3 sum = pm_direct_light(&dl, y->p, y->ng, n, wo, m, 1, NULL, NULL, r);
	pm_scatter bs;

	if (pm_bsdf_sample_rn(m, y->ng, n, wo, r, &bs) == 0)
		sum = pm_add(sum, pm_direct_bsdf_light(&dl, y->p, y->ng, &bs, 1));
	return sum;
}

/* What the surface y (a photon surface) reflects toward wo, emission aside:
 * its direct light plus the global map's estimate, or the precomputed value
 * where the surface is Lambertian and one is near. */
static pm_vec3
reflected(const pm_gather *g, void *sc, pm_rng *r, const pm_hit *h, pm_vec3 n, pm_vec3 wo,
          const pm_material *m)
{
	pm_vec3 ns = pm_shading_side(h->ng, pm_hit_shading(g->s, h), wo);
	pm_vec3 L = direct_at(g, h, ns, wo, m, r), E;
	pm_estimate_info info;

	if (g->o->irr && m->kind == PM_MAT_DIFFUSE && pm_irradiance_lookup(g->o->irr, h->p, n, &E))
		return pm_add(L, pm_mul(m->kd, E));
	return pm_add(L, g->est->estimate(&g->global, sc, h->p, n, ns, wo, m, &info));
}

/* One gather ray leaving x along s->wi with throughput s->weight: through
 * strong surfaces to the first photon surface, whose reflected light it
 * returns. An emitter it meets counts only after a strong surface and only
 * without a caustic map (that light is the caustic map's). */
static pm_vec3
gather_ray(const pm_gather *g, void *sc, pm_rng *r, pm_vec3 x, pm_vec3 ng, const pm_scatter *s)
{
	pm_vec3 beta = s->weight, d = s->wi, o = pm_accel_offset(g->a, x, ng, d);
	pm_vec3 acc = pm_v3(0, 0, 0);
	float eta_scale = s->adjoint;   /* the refractions' adjoint factors */

	for (int depth = 0; depth < GATHER_DEPTH; depth++) {
		const pm_material *m;
		pm_material mt;     /* m with its textures looked up, if it has any */
		pm_vec3 wo = pm_neg(d), n;
		pm_scatter bs;
		pm_hit h;

		if (!pm_accel_hit(g->a, o, d, 0.0f, FLT_MAX, &h)) {
			float pdf;
			if (depth > 0 && !g->o->caustic)     /* the sky, as an emitter */
				acc = pm_add(acc, pm_mul(beta, pm_lights_env(g->L, d, &pdf)));
			return acc;
		}
		m = pm_hit_material(g->s, &h, &mt);
		n = pm_dot(h.ng, wo) >= 0 ? h.ng : pm_neg(h.ng);
		if (depth > 0 && !g->o->caustic && pm_maxc(m->emit) > 0 &&
		    (pm_dot(h.ng, wo) > 0 || m->emit_twosided))
			acc = pm_add(acc, pm_mul(beta, m->emit));
		if (pm_mat_is_photon_surface(m))
			return pm_add(acc, pm_mul(beta, reflected(g, sc, r, &h, n, wo, m)));
		if (pm_bsdf_sample(m, h.ng, wo, r, &bs) != 0)
			return acc;
		beta = pm_mul(beta, bs.weight);
		/* Roulette on the throughput without refraction's eta^2
		 * (Veach 1997, 5.2): inside glass it is not less light. */
		eta_scale *= bs.adjoint;
		if (depth >= 3) {
			float q = fminf(0.95f, pm_maxc(beta) * eta_scale);
			if (!(q > 0) || pm_rng_f(r) >= q)
				return acc;
			beta = pm_scale(beta, 1.0f / q);
		}
		o = pm_accel_offset(g->a, h.p, h.ng, bs.wi);
		d = bs.wi;
	}
	return acc;
}

pm_vec3
pm_gather_radiance(const pm_gather *g, void *sc, pm_rng *r, pm_vec3 x, pm_vec3 ng,
                   pm_vec3 n, pm_vec3 ns, pm_vec3 wo, const pm_material *m,
                   pm_estimate_info *info)
{
	pm_vec3 L = pm_v3(0, 0, 0), sum = pm_v3(0, 0, 0);
	pm_guide gd;
	int nr = g->o->rays > 0 ? g->o->rays : 1;

	info->size = info->disc = 0;
	info->nphotons = 0;
	if (g->o->caustic)
		L = g->est->estimate(&g->caustic, sc, x, n, ns, wo, m, info);
	if (g->o->guided)
		pm_guide_build(&gd, g->global.map, x, ns);
	for (int i = 0; i < nr; i++) {
		pm_scatter s;
		if (pm_guide_mix(g->o->guided ? &gd : NULL, m, ng, ns, wo, r, &s) != 0)
			continue;
		sum = pm_add(sum, gather_ray(g, sc, r, x, ng, &s));
	}
	return pm_add(L, pm_scale(sum, 1.0f / (float)nr));
}
