/* bsdf.c — diffuse, Blinn glossy, mirror and glass scattering (see bsdf.h).
 *
 * The glossy lobe is the normalized Blinn distribution
 *   f_s = ks (e + 8) / (8 pi) (n . h)^e,
 * an energy-conserving-enough approximation (Akenine-Moeller et al., Real-Time
 * Rendering, 3rd ed., §7.6) that is reciprocal because it depends on h only.
 * Its half vectors are sampled with density (e + 1)/(2 pi) cos^e theta_h,
 * so p(wi) = p(h) / (4 |wo . h|) (Walter et al. 2007, eq. 14). */
#include "optics/bsdf.h"

#include <math.h>

static inline pm_vec3
reflect(pm_vec3 w, pm_vec3 n)
{
	return pm_sub(pm_scale(n, 2.0f * pm_dot(w, n)), w);
}

pm_vec3
pm_sample_cosine(pm_vec3 n, float u1, float u2)
{
	pm_vec3 t, b;
	float r = sqrtf(u1), phi = 2.0f * (float)PM_PI * u2;
	float z = sqrtf(fmaxf(0.0f, 1.0f - u1));

	pm_basis(n, &t, &b);
	return pm_norm(pm_add(pm_add(pm_scale(t, r * cosf(phi)), pm_scale(b, r * sinf(phi))),
	                      pm_scale(n, z)));
}

pm_vec3
pm_sample_sphere(float u1, float u2)
{
	float z = 1.0f - 2.0f * u1, r = sqrtf(fmaxf(0.0f, 1.0f - z * z));
	float phi = 2.0f * (float)PM_PI * u2;

	return pm_v3(r * cosf(phi), r * sinf(phi), z);
}

static float
blinn_d(float e, float cos_h)
{
	return cos_h > 0 ? (e + 8.0f) / (8.0f * (float)PM_PI) * powf(cos_h, e) : 0.0f;
}

pm_vec3
pm_bsdf_eval(const pm_material *m, pm_vec3 n, pm_vec3 wi, pm_vec3 wo)
{
	float ci = pm_dot(wi, n), co = pm_dot(wo, n);
	pm_vec3 f;

	if (ci <= 0 || co <= 0)
		return pm_v3(0, 0, 0);
	switch (m->kind) {
	case PM_MAT_DIFFUSE:
		return pm_scale(m->kd, 1.0f / (float)PM_PI);
	case PM_MAT_GLOSSY:
		f = pm_scale(m->kd, 1.0f / (float)PM_PI);
		return pm_add(f, pm_scale(m->ks, blinn_d(m->exponent, pm_dot(pm_norm(pm_add(wi, wo)), n))));
	default:
		return pm_v3(0, 0, 0);
	}
}

float
pm_bsdf_diffuse_share(const pm_material *m)
{
	float d = pm_lum(m->kd), s = pm_lum(m->ks);

	return d + s > 0 ? d / (d + s) : 1.0f;
}

static float
glossy_pdf(const pm_material *m, pm_vec3 n, pm_vec3 wi, pm_vec3 wo)
{
	float pd = pm_bsdf_diffuse_share(m), ci = pm_dot(wi, n);
	pm_vec3 h = pm_norm(pm_add(wi, wo));
	float ch = pm_dot(h, n), oh = pm_dot(wo, h);
	float ps = 0;

	if (ch > 0 && oh > 0)
		ps = (m->exponent + 1.0f) / (2.0f * (float)PM_PI) * powf(ch, m->exponent) / (4.0f * oh);
	return pd * fmaxf(ci, 0.0f) / (float)PM_PI + (1.0f - pd) * ps;
}

/* Fresnel reflectance of a smooth dielectric for unpolarized light;
 * cos_i > 0 on the incident side, eta = eta_i / eta_t. *cos_t gets the
 * transmitted cosine (0 on total internal reflection, where F = 1). */
static float
fresnel(float cos_i, float eta, float *cos_t)
{
	float s2 = eta * eta * (1.0f - cos_i * cos_i);
	float ct, rs, rp;

	if (s2 >= 1.0f) {
		*cos_t = 0;
		return 1.0f;
	}
	ct = sqrtf(1.0f - s2);
	rs = (eta * cos_i - ct) / (eta * cos_i + ct);
	rp = (cos_i - eta * ct) / (cos_i + eta * ct);
	*cos_t = ct;
	return 0.5f * (rs * rs + rp * rp);
}

int
pm_bsdf_sample(const pm_material *m, pm_vec3 ng, pm_vec3 wo, pm_rng *r, pm_scatter *s)
{
	float u1 = pm_rng_f(r), u2 = pm_rng_f(r), u3 = pm_rng_f(r);

	return pm_bsdf_sample_u(m, ng, wo, u1, u2, u3, s);
}

int
pm_bsdf_sample_u(const pm_material *m, pm_vec3 ng, pm_vec3 wo, float u1, float u2, float u3,
                 pm_scatter *s)
{
	return pm_bsdf_sample_n(m, ng, pm_dot(wo, ng) >= 0 ? ng : pm_neg(ng), wo, u1, u2, u3, s);
}

int
pm_bsdf_sample_rn(const pm_material *m, pm_vec3 ng, pm_vec3 n, pm_vec3 wo, pm_rng *r, pm_scatter *s)
{
	float u1 = pm_rng_f(r), u2 = pm_rng_f(r), u3 = pm_rng_f(r);

	return pm_bsdf_sample_n(m, ng, n, wo, u1, u2, u3, s);
}

pm_vec3
pm_shading_side(pm_vec3 ng, pm_vec3 ns, pm_vec3 wo)
{
	float co = pm_dot(wo, ng), c;
	pm_vec3 n = co >= 0 ? ns : pm_neg(ns);

	if (ns.x == ng.x && ns.y == ng.y && ns.z == ng.z)
		return n;
	/* wo at or below the shading hemisphere of a facet it sees from the
	 * front (a facet near the silhouette): bent toward wo until wo is
	 * just above it, so that the facet is not black there. */
	c = pm_dot(wo, n);
	if (c < PM_SHADING_MIN_COS)
		n = pm_norm(pm_add(n, pm_scale(wo, PM_SHADING_MIN_COS - c)));
	return n;
}

float
pm_shading_photon_weight(pm_vec3 n, pm_vec3 ns, pm_vec3 psi)
{
	float cg, cs;

	if (ns.x == n.x && ns.y == n.y && ns.z == n.z)
		return 1.0f;
	cg = fabsf(pm_dot(psi, n));
	cs = fabsf(pm_dot(psi, ns));
	return cs < PM_SHADING_MAX_RATIO * cg ? cs / cg : PM_SHADING_MAX_RATIO;
}

/* 1 if wi leaves on the side the sample must take: wo's for a reflection,
 * the other for a refraction, by the facet's normal. A shading normal can
 * send a sample through the facet; it is then absorbed. */
static int
geometric_side(pm_vec3 ng, pm_vec3 wo, pm_vec3 wi, int refracted)
{
	float a = pm_dot(wi, ng) * pm_dot(wo, ng);

	return refracted ? a < 0 : a > 0;
}

int
pm_bsdf_sample_n(const pm_material *m, pm_vec3 ng, pm_vec3 n, pm_vec3 wo, float u1, float u2,
                 float u3, pm_scatter *s)
{
	float co = pm_dot(wo, ng);
	/* Whether n is the facet's own normal: then the facet's side tests
	 * below are the shading normal's, and are skipped. */
	int shaded = !((n.x == ng.x && n.y == ng.y && n.z == ng.z) || (n.x == -ng.x && n.y == -ng.y && n.z == -ng.z));

	s->delta = 0;
	s->pdf = 0;
	s->adjoint = 1;
	switch (m->kind) {
	case PM_MAT_DIFFUSE:
		s->wi = pm_sample_cosine(n, u1, u2);
		if (pm_dot(s->wi, n) <= 0 || (shaded && !geometric_side(ng, wo, s->wi, 0)))
			return -1;
		s->weight = m->kd;     /* (kd/pi) cos / (cos/pi) */
		s->pdf = pm_dot(s->wi, n) / (float)PM_PI;
		return 0;
	case PM_MAT_GLOSSY: {
		float pd = pm_bsdf_diffuse_share(m), pdf, ci;
		if (u3 < pd) {
			s->wi = pm_sample_cosine(n, u1, u2);
		} else {
			pm_vec3 t, b, h;
			float ch = powf(u1, 1.0f / (m->exponent + 1.0f));
			float sh = sqrtf(fmaxf(0.0f, 1.0f - ch * ch)), phi = 2.0f * (float)PM_PI * u2;
			pm_basis(n, &t, &b);
			h = pm_add(pm_add(pm_scale(t, sh * cosf(phi)), pm_scale(b, sh * sinf(phi))), pm_scale(n, ch));
			s->wi = pm_norm(reflect(wo, h));
		}
		ci = pm_dot(s->wi, n);
		if (ci <= 0 || (shaded && !geometric_side(ng, wo, s->wi, 0)))
			return -1;
		pdf = glossy_pdf(m, n, s->wi, wo);
		if (!(pdf > 0))
			return -1;
		s->weight = pm_scale(pm_bsdf_eval(m, n, s->wi, wo), ci / pdf);
		s->pdf = pdf;
		return pm_vfinite(s->weight) ? 0 : -1;
	}
	case PM_MAT_MIRROR:
		s->wi = reflect(wo, n);
		s->weight = m->ks;
		s->delta = 1;
		return shaded && !geometric_side(ng, wo, s->wi, 0) ? -1 : 0;
	case PM_MAT_GLASS: {
		float ci = shaded ? fmaxf(pm_dot(wo, n), 0.0f) : fabsf(co), ct;
		float eta = co >= 0 ? 1.0f / m->ior : m->ior;   /* eta_i / eta_t */
		float F = fresnel(ci, eta, &ct);
		s->delta = 1;
		if (u1 < F) {
			s->wi = reflect(wo, n);
			s->weight = pm_v3(1, 1, 1);
		} else {
			/* Refraction: wi = -eta wo + (eta cos_i - cos_t) n; radiance
			 * crossing into wo's medium is scaled by eta^2, kept within
			 * float (an ior of 1e-30 or 3e38 is legal) so that weight x
			 * adjoint stays ks. */
			float e2 = fminf(fmaxf(eta * eta, 1e-30f), 1e30f);
			s->wi = pm_norm(pm_add(pm_scale(wo, -eta), pm_scale(n, eta * ci - ct)));
			s->weight = pm_scale(m->ks, e2);
			s->adjoint = 1.0f / e2;
		}
		return shaded && !geometric_side(ng, wo, s->wi, u1 >= F) ? -1 : 0;
	}
	}
	return -1;
}

float
pm_bsdf_pdf(const pm_material *m, pm_vec3 n, pm_vec3 wi, pm_vec3 wo)
{
	switch (m->kind) {
	case PM_MAT_DIFFUSE: return fmaxf(pm_dot(wi, n), 0.0f) / (float)PM_PI;
	case PM_MAT_GLOSSY: return pm_dot(wi, n) > 0 ? glossy_pdf(m, n, wi, wo) : 0.0f;
	default: return 0.0f;
	}
}
