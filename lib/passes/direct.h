/* direct.h — direct light at a surface point, for the view pass and for
 * final gathering's gather-ray hits: shadow rays to light samples, a BSDF
 * sample that may find an emitter, and the multiple importance sampling
 * weights (Veach 1997, power heuristic with sample counts) that combine
 * them, so that corners next to an emitter, where light sampling alone has
 * a heavy tail, are covered by the BSDF samples. */
#ifndef PM_DIRECT_H
#define PM_DIRECT_H

#include "scene/accel.h"
#include "optics/bsdf.h"
#include "estimators/guide.h"
#include "optics/light.h"
#include "base/rng.h"
#include "scene/scene.h"
#include "base/vec.h"

typedef struct pm_direct {
	const pm_scene *s;
	const pm_accel *a;
	const pm_lights *L;
} pm_direct;

/* A pixel's shadow rays at its camera samples' first hits, stratified
 * together: n strata of the lights' two point coordinates (a grid of
 * floor(sqrt(n)) columns, the rest anywhere) and n of the choice among the
 * lights, sample k's j-th ray in stratum first + j (first = k nl), both
 * shifted by the pixel's random off and pick, so that each ray is uniform
 * over the lights as an unstratified one is. */
typedef struct pm_strata {
	int first, n;
	uint32_t off, pick;
} pm_strata;

/* The light-sampled part at x (geometric normal ng, shading normal n on
 * wo's side, material m): nl shadow rays, their points stratified over the
 * lights (in st's strata, or among the nl alone if st is NULL), each
 * weighted against one BSDF sample of the same light, drawn by
 * pm_guide_mix with gd (BSDF alone if gd is NULL). */
pm_vec3 pm_direct_light(const pm_direct *c, pm_vec3 x, pm_vec3 ng, pm_vec3 n, pm_vec3 wo,
                        const pm_material *m, int nl, const pm_guide *gd, const pm_strata *st,
                        pm_rng *r);

/* What a BSDF sample from x along wi reaches when only an emitter there
 * matters: 1 with *h the emitter's hit, else 0. With few emitting
 * triangles they are tested one by one and only a shadow ray is cast. */
int pm_direct_bsdf_hit(const pm_direct *c, pm_vec3 x, pm_vec3 ng, pm_vec3 wi, pm_hit *h);

/* The emission of h toward the ray that found it (from x along d, a BSDF
 * sample of density bpdf), weighted against the nl light samples taken at
 * x; all of it when the sample was a delta. */
pm_vec3 pm_direct_emitted(const pm_direct *c, const pm_hit *h, pm_vec3 x, pm_vec3 d, float bpdf,
                          int delta, int nl);

/* The sky's radiance along a ray from a scattering point that left the
 * scene along d (a BSDF sample of density bpdf), weighted against the nl
 * light samples taken there; all of it after a delta (or the camera). */
pm_vec3 pm_direct_escaped(const pm_direct *c, pm_vec3 d, float bpdf, int delta, int nl);

/* The BSDF-sampled half of direct light at x: bs's weight times what its
 * ray finds (an emitter, or the sky if it leaves the scene), weighted
 * against the nl light samples taken at x. 0 if bs was absorbed (pdf <= 0). */
pm_vec3 pm_direct_bsdf_light(const pm_direct *c, pm_vec3 x, pm_vec3 ng, const pm_scatter *bs, int nl);

#endif
