/* light.h — the scene's emitters at one shutter time: point, spot, distant
 * and environment lights and emitting triangles, chosen in proportion to
 * their power both for emitting photons (light pass) and for shadow rays
 * (view pass).
 *
 * Power of an emitting triangle of area A and radiance Le: pi Le A, twice
 * that if it emits on both sides. Power of a point light: as given; of a
 * spot light: its intensity integrated over its cone. Distant and
 * environment lights send their photons through a disk perpendicular to
 * their direction that covers the scene's bounding sphere (radius r):
 * power E pi r^2 and pi r^2 times the integral of the sky's radiance over
 * the sphere of directions (formats/scene.md). */
#ifndef PM_LIGHT_H
#define PM_LIGHT_H

#include "base/err.h"
#include "base/rng.h"
#include "scene/scene.h"
#include "base/vec.h"

enum pm_emitter { PM_EMIT_TRI, PM_EMIT_POINT, PM_EMIT_SPOT, PM_EMIT_DISTANT, PM_EMIT_ENV };

typedef struct pm_light {
	int kind;           /* enum pm_emitter */
	int tri;            /* emitting triangle, or -1 */
	pm_vec3 p0, e1, e2; /* triangle p0 + u e1 + v e2; point and spot light at p0 */
	pm_vec3 n;          /* triangle's unit front normal */
	float area;
	int twosided;
	/* triangle: radiance; point: power; spot: intensity on the axis;
	 * distant: irradiance; environment: radiance (constant) or scale 1 */
	pm_vec3 le;
	pm_vec3 power;      /* total emitted power, W per channel */
	pm_vec3 dir;        /* spot: unit axis; distant: unit direction of travel */
	float cos_outer, cos_inner, outer, inner;  /* spot: the cone (radians) */
	int falloff;        /* spot: enum pm_spot_falloff */
} pm_light;

typedef struct pm_lights {
	pm_light *l;
	int n;
	int ntri;           /* of them emitting triangles */
	float *cdf;         /* n + 1 entries, by mean power over the channels */
	int *tri_light;     /* per scene triangle: its light index, or -1 */
	pm_vec3 total;      /* sum of the lights' power */
	pm_vec3 center;     /* the scene's bounding sphere at this time */
	float radius;
	/* The environment light (index in l, or -1) and, for an image, its
	 * texels and the tables that sample it: row j's probability
	 * env_marg[j + 1] - env_marg[j], column i's within the row
	 * env_cond[j (w + 1) + i + 1] - env_cond[j (w + 1) + i]. */
	int env;
	const pm_pointlight *envsrc;
	double *env_marg, *env_cond;
	double env_int;     /* integral of the texels' mean over the sphere */
} pm_lights;

int pm_lights_build(pm_lights *L, const pm_scene *s, const pm_vec3 *verts, float t, pm_error *err);
void pm_lights_free(pm_lights *L);

/* Light pass: one photon's start. *power is the power it carries per emitted
 * path (the light's power divided by the probability of picking it). */
void pm_lights_emit(const pm_lights *L, pm_rng *r, pm_vec3 *o, pm_vec3 *d, pm_vec3 *n, pm_vec3 *power);

/* The same from given uniforms in [0, 1): u[0] picks the light, u[1], u[2]
 * the point, u[3], u[4] the direction, u[5] the side of a two-sided one. */
void pm_lights_emit_u(const pm_lights *L, const float u[6], pm_vec3 *o, pm_vec3 *d, pm_vec3 *n,
                      pm_vec3 *power);

/* View pass: a shadow-ray sample toward a light from point x. Fills the
 * unit direction *wi, the distance *dist to the light point (INFINITY for a
 * distant or environment light), and *li =
 * Le cos_l / (pdf_area d^2) (or I / d^2 for a point light) divided by the
 * pick probability: multiplied by f_r cos_x and visibility it is an unbiased
 * estimate of direct light. *pdf is the sample's solid-angle density, or 0
 * for a point light (a delta, which BSDF sampling can never hit). Returns 0
 * if the sample carries nothing. */
int pm_lights_sample(const pm_lights *L, pm_vec3 x, pm_rng *r, pm_vec3 *wi, float *dist,
                     pm_vec3 *li, float *pdf);

/* The same from given uniform numbers: u0 picks the light, (u1, u2) the
 * point on it, so a caller can stratify (u1, u2) over several samples.
 * pm_lights_sample draws u0, u1, u2 in that order. If cosl is not NULL it
 * gets the cosine between wi and the light's surface at the point (an area
 * light's), or 0 for a light without a surface. */
int pm_lights_sample_u(const pm_lights *L, pm_vec3 x, float u0, float u1, float u2, pm_vec3 *wi,
                       float *dist, pm_vec3 *li, float *pdf, float *cosl);

/* Solid-angle density with which pm_lights_sample, called at x, would pick
 * point p on scene triangle tri (0 if tri does not emit toward x). */
float pm_lights_pdf(const pm_lights *L, uint32_t tri, pm_vec3 x, pm_vec3 p);

/* The environment's radiance arriving along -d (from direction d) and, in
 * *pdf, the solid-angle density with which pm_lights_sample picks d; both 0
 * without an environment light. */
pm_vec3 pm_lights_env(const pm_lights *L, pm_vec3 d, float *pdf);

/* The nearest emitting triangle along the ray o + t d, t > 0 (either side),
 * found by testing each: *t and the light's index in L->l. Returns 1 if one
 * is hit, 0 if none, -1 if the scene has more than PM_LIGHTS_SCAN emitting
 * triangles (then the caller should trace the ray through the scene). The
 * view pass asks this before spending a full ray on a BSDF sample that can
 * only matter if it reaches an emitter. */
#define PM_LIGHTS_SCAN 64
int pm_lights_first(const pm_lights *L, pm_vec3 o, pm_vec3 d, float *t, int *light);

#endif
