/* bsdf.h — the materials' scattering: Lambertian diffuse, Blinn glossy
 * (normalized, (e+8)/(8 pi) cos^e theta_h), perfect mirror, smooth dielectric
 * with exact Fresnel. Directions are unit vectors pointing away from the
 * surface; n is the unit shading normal on the side the light leaves toward
 * (wo's side) unless said otherwise. RGB throughout, channels independent. */
#ifndef PM_BSDF_H
#define PM_BSDF_H

#include "base/rng.h"
#include "scene/scene.h"
#include "base/vec.h"

/* f_r(wi -> wo) for diffuse and glossy materials (0 for mirror and glass,
 * whose BSDFs are deltas). n must be on wo's side; returns 0 if wi is below
 * n. Reciprocal: eval(wi, wo) == eval(wo, wi). */
pm_vec3 pm_bsdf_eval(const pm_material *m, pm_vec3 n, pm_vec3 wi, pm_vec3 wo);

typedef struct pm_scatter {
	pm_vec3 wi;         /* sampled direction */
	pm_vec3 weight;     /* f cos / pdf (the throughput factor) */
	float pdf;          /* solid-angle density of wi (0 for a delta) */
	int delta;          /* 1 if sampled from a delta (mirror, glass) */
	float adjoint;      /* what turns weight from radiance's into power's:
	                     * (eta on wi's side / eta on wo's side)^2 after a
	                     * refraction, 1 otherwise */
} pm_scatter;

/* Samples wi given wo. ng is the geometric front normal of the surface (not
 * flipped): glass uses it to tell entering from leaving. Returns 0 and sets
 * *s, or -1 if the sample is absorbed (direction below the surface).
 * The weight carries radiance from wi to wo (camera paths): a refraction
 * scales it by (eta_wo / eta_wi)^2, radiance being compressed into the
 * denser medium. A photon (power, arriving along wo and leaving along wi)
 * takes weight x adjoint instead (Veach 1997, ch. 5: refraction's BSDF is
 * not symmetric). */
int pm_bsdf_sample(const pm_material *m, pm_vec3 ng, pm_vec3 wo, pm_rng *r,
                   pm_scatter *s);

/* The same from given uniforms in [0, 1): u1, u2 the direction, u3 the
 * lobe (glossy); glass takes its choice from u1. */
int pm_bsdf_sample_u(const pm_material *m, pm_vec3 ng, pm_vec3 wo, float u1, float u2,
                     float u3, pm_scatter *s);

/* The same about the shading normal n, on wo's side (pm_shading_side): a
 * sample that n sends through the facet (ng) is absorbed (returns -1). With
 * n the facet's own normal, exactly pm_bsdf_sample_u. */
int pm_bsdf_sample_n(const pm_material *m, pm_vec3 ng, pm_vec3 n, pm_vec3 wo, float u1, float u2,
                     float u3, pm_scatter *s);
/* pm_bsdf_sample_n drawing u1, u2, u3 from r in that order. */
int pm_bsdf_sample_rn(const pm_material *m, pm_vec3 ng, pm_vec3 n, pm_vec3 wo, pm_rng *r,
                      pm_scatter *s);

/* The shading normal to use at a point seen (or left) along wo: ns (the
 * front shading normal, pm_hit_shading) turned to wo's side of the facet
 * (front normal ng), and, where wo lies below it although above the
 * facet, bent toward wo so that wo is PM_SHADING_MIN_COS above it. ns equal
 * to ng gives ng on wo's side, unbent. */
#define PM_SHADING_MIN_COS 0.01f
pm_vec3 pm_shading_side(pm_vec3 ng, pm_vec3 ns, pm_vec3 wo);

/* What a photon arriving along psi (toward where it came from) counts for in
 * a radiance estimate at a point whose facet normal is n and shading normal
 * ns (both on the seen side): photons land per unit of facet area, |psi.n|,
 * while the reflected radiance integrates the shading cosine |psi.ns|, so
 * the ratio of the two, capped at PM_SHADING_MAX_RATIO near grazing facets
 * (where its variance grows without bound; README). Exactly 1 if ns is n. */
#define PM_SHADING_MAX_RATIO 10.0f
float pm_shading_photon_weight(pm_vec3 n, pm_vec3 ns, pm_vec3 psi);

/* Solid-angle density with which pm_bsdf_sample picks wi given wo, for
 * multiple importance sampling (0 for mirror and glass). n on wo's side. */
float pm_bsdf_pdf(const pm_material *m, pm_vec3 n, pm_vec3 wi, pm_vec3 wo);

/* The probability with which pm_bsdf_sample picks a glossy material's
 * diffuse lobe (by the lobes' albedos). */
float pm_bsdf_diffuse_share(const pm_material *m);

/* Sampling helpers. */
pm_vec3 pm_sample_cosine(pm_vec3 n, float u1, float u2);
pm_vec3 pm_sample_sphere(float u1, float u2);

#endif
