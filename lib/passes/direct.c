/* direct.c — direct light at a surface point (see direct.h): light
 * sampling, BSDF sampling that finds emitters, and their multiple
 * importance sampling weights. */
#include "passes/direct.h"

#include <float.h>
#include <math.h>

#include "optics/bsdf.h"

/* Power heuristic (Veach 1997, §9.2.4) for two strategies, one sample each. */
static float
mis(float a, float b)
{
	return a > 0 ? a * a / (a * a + b * b) : 0.0f;
}

/* 1 if something lies between o and the light point lp along the unit
 * direction wi. The ray stops short of the light's own surface by more than
 * the rounding of lp, which grows with its distance from the origin:
 * measured across the surface (cosl, the cosine there), as the offset of a
 * ray's origin is, not along the ray. Stopping 2 eps short along the ray
 * let light through a cover less than 2 eps above the emitter, wherever
 * the ray met it steeply (a furnace's floor quad 0.12 mm over its emitting
 * floor: the ceiling read 4.7 % bright). A light without a surface keeps
 * 2 eps along the ray; a grazing ray stops at most halfway. */
static int
light_blocked(const pm_direct *c, pm_vec3 o, pm_vec3 wi, float dist, pm_vec3 lp, float cosl)
{
	float eps = pm_accel_eps(c->a, lp);
	float far = dist - fminf(cosl > 0 ? eps / cosl : 2.0f * eps, 0.5f * dist);

	return far > 0 && pm_accel_occluded(c->a, o, wi, 0.0f, far);
}

/* Direct light by nl shadow rays to light samples, their points stratified
 * over the light (a grid of strata in the unit square that maps onto each
 * triangle), weighted against one BSDF sample of the same light (multiple
 * importance sampling with sample counts, Veach 1997 §9.2.4): corners next
 * to an emitter, where light sampling alone has a heavy tail, are then
 * covered by the BSDF samples. */
pm_vec3
pm_direct_light(const pm_direct *c, pm_vec3 x, pm_vec3 ng, pm_vec3 n, pm_vec3 wo,
                const pm_material *m, int nl, const pm_guide *gd, const pm_strata *st, pm_rng *r)
{
	pm_vec3 sum = pm_v3(0, 0, 0);
	int strata = st ? st->n : nl, ga, gb;
	/* The choice among the lights in its own strata, a multiple of the
	 * point's stratum (mod n: a prime's multiples run through them all),
	 * so that the two do not go in step. */
	uint32_t mul = st && st->n % 7919 != 0 ? 7919u : 1u, ns = st ? (uint32_t)st->n : 1;
	/* Ray j's two strata, stepped from ray to ray: the same numbers as
	 * (first + off + j) mod n and its multiple, without two divisions a ray. */
	uint32_t gs = st ? (uint32_t)(((uint64_t)st->first + st->off) % ns) : 0;
	uint32_t qs = (uint32_t)(((uint64_t)gs * mul + (st ? st->pick : 0)) % ns), step = mul % ns;

	pm_cells(strata, &ga, &gb);

	for (int j = 0; j < nl; j++) {
		pm_vec3 wi, li, f;
		float dist, cosx, lpdf, w, cosl;
		float u0 = pm_rng_f(r), u1 = pm_rng_f(r), u2 = pm_rng_f(r);
		int g = j;

		if (st) {
			g = (int)gs;
			u0 = fminf(((float)qs + u0) / (float)st->n, 0x1.fffffep-1f);
			gs = gs + 1 == ns ? 0 : gs + 1;
			qs = qs + step >= ns ? qs + step - ns : qs + step;
		}
		if (strata > 1)
			pm_cell_point(g, ga, gb, &u1, &u2);
		if (!pm_lights_sample_u(c->L, x, u0, u1, u2, &wi, &dist, &li, &lpdf, &cosl))
			continue;
		cosx = pm_dot(wi, n);
		/* Below the facet, whatever the shading normal says: the
		 * surface itself is in the way. */
		if (cosx <= 0 || pm_dot(wi, ng) * pm_dot(wo, ng) <= 0)
			continue;
		f = pm_bsdf_eval(m, n, wi, wo);
		if (pm_maxc(f) <= 0)
			continue;
		pm_vec3 o = pm_accel_offset(c->a, x, ng, wi);
		if (isinf(dist)) {
			if (pm_accel_occluded(c->a, o, wi, 0.0f, FLT_MAX))
				continue;
		} else {
			/* Aimed from the offset origin at the light point: along
			 * wi from o, a ray grazing the light's surface (the rim of
			 * a sphere lamp) met it short of the point and the sample
			 * counted as shadowed (a sphere lamp's floor read 2 %
			 * dark). */
			pm_vec3 lp = pm_add(x, pm_scale(wi, dist)), v = pm_sub(lp, o);
			float dl = pm_len(v);
			if (!(dl > 0) || light_blocked(c, o, pm_scale(v, 1.0f / dl), dl, lp, cosl))
				continue;
		}
		w = lpdf > 0 ? mis((float)nl * lpdf, pm_guide_mix_pdf(gd, m, n, wi, wo)) : 1.0f;
		sum = pm_add(sum, pm_scale(pm_mul(f, li), cosx * w));
	}
	return nl > 1 ? pm_scale(sum, 1.0f / (float)nl) : sum;
}

static pm_vec3
emitted(const pm_material *m, pm_vec3 ng, pm_vec3 wo)
{
	if (!(pm_maxc(m->emit) > 0))
		return pm_v3(0, 0, 0);
	if (pm_dot(ng, wo) > 0 || m->emit_twosided)
		return m->emit;
	return pm_v3(0, 0, 0);
}

/* Emission found by a BSDF-sampled ray from x (density bpdf), weighted
 * against the nl light samples taken at x; all of it when the sample was a
 * delta. */
pm_vec3
pm_direct_emitted(const pm_direct *c, const pm_hit *h, pm_vec3 x, pm_vec3 d, float bpdf,
                  int delta, int nl)
{
	const pm_material *m = &c->s->mats[c->s->objs[h->obj].material];
	pm_vec3 e = emitted(m, h->ng, pm_neg(d));

	if (delta || pm_maxc(e) <= 0)
		return e;
	return pm_scale(e, mis(bpdf, (float)nl * pm_lights_pdf(c->L, h->tri, x, h->p)));
}

pm_vec3
pm_direct_escaped(const pm_direct *c, pm_vec3 d, float bpdf, int delta, int nl)
{
	float lpdf;
	pm_vec3 e = pm_lights_env(c->L, d, &lpdf);

	if (delta || pm_maxc(e) <= 0)
		return e;
	return pm_scale(e, mis(bpdf, (float)nl * lpdf));
}

pm_vec3
pm_direct_bsdf_light(const pm_direct *c, pm_vec3 x, pm_vec3 ng, const pm_scatter *bs, int nl)
{
	pm_hit h;

	if (!(bs->pdf > 0))
		return pm_v3(0, 0, 0);
	if (c->L->env >= 0) {
		/* A sky: what the sample misses matters too. */
		pm_vec3 o = pm_accel_offset(c->a, x, ng, bs->wi);
		if (!pm_accel_hit(c->a, o, bs->wi, 0.0f, FLT_MAX, &h))
			return pm_mul(bs->weight, pm_direct_escaped(c, bs->wi, bs->pdf, 0, nl));
	} else if (!pm_direct_bsdf_hit(c, x, ng, bs->wi, &h)) {
		return pm_v3(0, 0, 0);
	}
	return pm_mul(bs->weight, pm_direct_emitted(c, &h, x, bs->wi, bs->pdf, 0, nl));
}

/* What a BSDF sample from x along wi reaches, when only an emitter there
 * matters: with few emitting triangles, the nearest one on the ray and a
 * shadow ray to it, so that the many samples that miss every light cost no
 * ray through the scene. Returns 1 with *h the emitter's hit, else 0. */
int
pm_direct_bsdf_hit(const pm_direct *c, pm_vec3 x, pm_vec3 ng, pm_vec3 wi, pm_hit *h)
{
	pm_vec3 o = pm_accel_offset(c->a, x, ng, wi), lp;
	const pm_light *l;
	float t;
	int i, k = pm_lights_first(c->L, o, wi, &t, &i);

	if (k < 0)
		return pm_accel_hit(c->a, o, wi, 0.0f, FLT_MAX, h);
	if (k == 0)
		return 0;
	l = &c->L->l[i];
	lp = pm_add(o, pm_scale(wi, t));
	if (light_blocked(c, o, wi, t, lp, fabsf(pm_dot(wi, l->n))))
		return 0;
	h->t = t;
	h->p = lp;
	h->ng = l->n;
	h->tri = (uint32_t)l->tri;
	h->poly = c->s->tri_poly[l->tri];
	h->obj = (int)c->s->poly_obj[h->poly];
	return 1;
}
