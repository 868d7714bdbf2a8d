/* render.c — the view pass (see render.h). */
#include "render.h"

#include <float.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "bsdf.h"
#include "camera.h"
#include "edge.h"
#include "rng.h"

#define RENDER_DOMAIN 0x52454e444552ull

const char *const pm_render_chans[PM_RENDER_NCHAN] = {
	"R", "G", "B",
	"direct.R", "direct.G", "direct.B",
	"indirect.R", "indirect.G", "indirect.B",
	"specular.R", "specular.G", "specular.B",
	"size", "count", "edge",
};

/* What one camera sample brought, by where it came from (formats/image.md):
 * direct = emission seen and shadow rays at a first-hit diffuse surface;
 * indirect = the photon estimate there (or, for path, everything after the
 * first bounce); specular = whatever arrived through a first hit that
 * continued the path (mirror, glass, strong glossy). */
typedef struct sample {
	pm_vec3 direct, indirect, specular;
	float size;
	int count, estimated, edge;
} sample;

typedef struct ctx {
	const pm_scene *s;
	const pm_accel *a;
	const pm_lights *L;
	const pm_render_opts *o;
	const pm_estimator *est;
	pm_est_in in;
	float pixel_angle;  /* a pixel's width in radians at the image centre */
	pm_gather gather;   /* used if o->gather */
} ctx;

/* Power heuristic (Veach 1997, §9.2.4) for two strategies, one sample each. */
static float
mis(float a, float b)
{
	return a > 0 ? a * a / (a * a + b * b) : 0.0f;
}

/* Direct light by nl shadow rays to light samples, their points stratified
 * over the light (a grid of strata in the unit square that maps onto each
 * triangle), weighted against one BSDF sample of the same light (multiple
 * importance sampling with sample counts, Veach 1997 §9.2.4): corners next
 * to an emitter, where light sampling alone has a heavy tail, are then
 * covered by the BSDF samples. */
static pm_vec3
direct_light(const ctx *c, pm_vec3 x, pm_vec3 ng, pm_vec3 n, pm_vec3 wo,
             const pm_material *m, int nl, pm_rng *r)
{
	pm_vec3 sum = pm_v3(0, 0, 0);
	int ga = (int)sqrtf((float)nl), gb = nl / ga;

	for (int j = 0; j < nl; j++) {
		pm_vec3 wi, li, f;
		float dist, cosx, lpdf, w;
		float u0 = pm_rng_f(r), u1 = pm_rng_f(r), u2 = pm_rng_f(r);

		if (j < ga * gb && nl > 1) {
			u1 = fminf(((float)(j % ga) + u1) / (float)ga, 0x1.fffffep-1f);
			u2 = fminf(((float)(j / ga) + u2) / (float)gb, 0x1.fffffep-1f);
		}
		if (!pm_lights_sample_u(c->L, x, u0, u1, u2, &wi, &dist, &li, &lpdf))
			continue;
		cosx = pm_dot(wi, n);
		if (cosx <= 0)
			continue;
		f = pm_bsdf_eval(m, n, wi, wo);
		if (pm_maxc(f) <= 0)
			continue;
		pm_vec3 o = pm_accel_offset(c->a, x, ng, wi), lp = pm_add(x, pm_scale(wi, dist));
		/* Stop short of the light's own surface by more than the rounding
		 * of the light point, which grows with its distance from the origin. */
		float far = pm_len(pm_sub(lp, o)) - 2.0f * pm_accel_eps(c->a, lp);
		if (far > 0 && pm_accel_occluded(c->a, o, wi, 0.0f, far))
			continue;
		w = lpdf > 0 ? mis((float)nl * lpdf, pm_bsdf_pdf(m, n, wi, wo)) : 1.0f;
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
static pm_vec3
emitted_mis(const ctx *c, const pm_hit *h, pm_vec3 x, pm_vec3 d, float bpdf, int delta, int nl)
{
	const pm_material *m = &c->s->mats[c->s->objs[h->obj].material];
	pm_vec3 e = emitted(m, h->ng, pm_neg(d));

	if (delta || pm_maxc(e) <= 0)
		return e;
	return pm_scale(e, mis(bpdf, (float)nl * pm_lights_pdf(c->L, h->tri, x, h->p)));
}

/* What a BSDF sample from x along wi reaches, when only an emitter there
 * matters: with few emitting triangles, the nearest one on the ray and a
 * shadow ray to it, so that the many samples that miss every light cost no
 * ray through the scene. Returns 1 with *h the emitter's hit, else 0. */
static int
bsdf_light_hit(const ctx *c, pm_vec3 x, pm_vec3 ng, pm_vec3 wi, pm_hit *h)
{
	pm_vec3 o = pm_accel_offset(c->a, x, ng, wi), lp;
	const pm_light *l;
	float t, far;
	int i, k = pm_lights_first(c->L, o, wi, &t, &i);

	if (k < 0)
		return pm_accel_hit(c->a, o, wi, 0.0f, FLT_MAX, h);
	if (k == 0)
		return 0;
	l = &c->L->l[i];
	lp = pm_add(o, pm_scale(wi, t));
	far = t - 2.0f * pm_accel_eps(c->a, lp);
	if (far > 0 && pm_accel_occluded(c->a, o, wi, 0.0f, far))
		return 0;
	h->t = t;
	h->p = lp;
	h->ng = l->n;
	h->tri = (uint32_t)l->tri;
	h->poly = c->s->tri_poly[l->tri];
	h->obj = (int)c->s->poly_obj[h->poly];
	return 1;
}

/* A pixel's first-hit photon estimate, reused by its later camera samples
 * that land on the same polygon (opts.estimate_once): the first sample's
 * point is uniform over the pixel's footprint on that polygon, so the
 * pixel's expected value is unchanged. It is reused only when the
 * estimate's support (2 info.size across) covers at least the area of the
 * pixel's footprint there: then the estimate barely varies within the
 * pixel, while a support smaller than the footprint (few photons per
 * estimate, many per pass) would lose the averaging of the samples'
 * estimates, which are then nearly independent. */
typedef struct pxcache {
	int valid;
	uint32_t poly;
	pm_vec3 L;
	pm_estimate_info info;
} pxcache;

static pm_vec3
first_estimate(const ctx *c, void *sc, const pm_hit *h, pm_vec3 n, pm_vec3 wo,
               const pm_material *m, pxcache *pc, pm_estimate_info *info)
{
	pm_vec3 L;

	if (pc && pc->valid && pc->poly == h->poly) {
		*info = pc->info;
		return pc->L;
	}
	L = c->est->estimate(&c->in, sc, h->p, n, wo, m, info);
	if (pc) {
		/* The footprint's area: the pixel's angle at distance t,
		 * squared, stretched by the obliquity (capped, for grazing
		 * views); the support's: (2 size)^2, a cube's cross-section. */
		float cosv = fabsf(pm_dot(n, wo));
		float w = h->t * c->pixel_angle;
		pc->valid = w * w / (cosv > 0.05f ? cosv : 0.05f) <= 4.0f * info->size * info->size;
		pc->poly = h->poly;
		pc->L = L;
		pc->info = *info;
	}
	return L;
}

/* Follows a camera path from o along d, its vertex depth, its throughput
 * beta, from the scattering point prev (density bpdf of the BSDF sample that
 * led here, a delta or not, nlprev light samples taken there). bucket is
 * where contributions after the first hit go (set at depth 0). */
static void
walk(const ctx *c, void *sc, pm_vec3 o, pm_vec3 d, int depth, pm_vec3 beta, pm_vec3 prev,
     int delta, float bpdf, int nlprev, pm_vec3 *bucket, sample *out, pxcache *pc, pm_rng *r)
{
	int maxd = c->o->max_depth > 0 ? c->o->max_depth : 64;
	pm_hit h;

	for (; depth < maxd; depth++) {
		const pm_material *m;
		pm_vec3 wo = pm_neg(d), n;
		pm_vec3 *here;
		pm_scatter bs;
		int ends, nl;

		if (!pm_accel_hit(c->a, o, d, 0.0f, FLT_MAX, &h))
			return;
		m = &c->s->mats[c->s->objs[h.obj].material];
		n = pm_dot(h.ng, wo) >= 0 ? h.ng : pm_neg(h.ng);
		if (depth == 0)
			bucket = pm_mat_is_photon_surface(m) ? &out->indirect : &out->specular;
		here = depth == 0 ? (m->strong ? &out->specular : &out->direct) : bucket;
		*here = pm_add(*here, pm_mul(beta, emitted_mis(c, &h, prev, d, bpdf, delta, nlprev)));
		ends = pm_mat_is_photon_surface(m) && c->est->estimate;
		nl = depth == 0 || ends ? c->o->light_samples : 1;
		if (nl < 1)
			nl = 1;
		if (m->kind == PM_MAT_DIFFUSE || m->kind == PM_MAT_GLOSSY)
			*here = pm_add(*here, pm_mul(beta, direct_light(c, h.p, h.ng, n, wo, m, nl, r)));
		if (pm_bsdf_sample(m, h.ng, wo, r, &bs) != 0)
			bs.pdf = -1;
		if (ends) {
			pm_estimate_info info;
			pm_vec3 L;
			pm_hit lh;
			/* The BSDF-sampled half of the direct light. */
			if (bs.pdf > 0 && bsdf_light_hit(c, h.p, h.ng, bs.wi, &lh))
				*here = pm_add(*here, pm_mul(pm_mul(beta, bs.weight),
				                             emitted_mis(c, &lh, h.p, bs.wi, bs.pdf, 0, nl)));
			/* Gathering draws its own rays: one gather per camera sample. */
			L = c->o->gather ? pm_gather_radiance(&c->gather, sc, r, h.p, h.ng, n, wo, m, &info)
			                 : first_estimate(c, sc, &h, n, wo, m, depth == 0 ? pc : NULL, &info);
			*bucket = pm_add(*bucket, pm_mul(beta, L));
			if (depth == 0) {
				out->size = info.size;
				out->count = info.nphotons;
				out->estimated = 1;
				out->edge = pm_polyindex_near_edge(c->in.pi, h.p, info.size);
			}
			return;
		}
		if (bs.pdf < 0)
			return;
		beta = pm_mul(beta, bs.weight);
		delta = bs.delta;
		bpdf = bs.pdf;
		nlprev = nl;
		prev = h.p;
		if (depth >= 3) {
			float q = fminf(0.95f, pm_maxc(beta));
			if (!(q > 0) || pm_rng_f(r) >= q)
				return;
			beta = pm_scale(beta, 1.0f / q);
		}
		o = pm_accel_offset(c->a, h.p, h.ng, bs.wi);
		d = bs.wi;
	}
}

/* One camera sample; the camera counts as a delta, so emitters seen count. */
static void
trace(const ctx *c, void *sc, pm_vec3 o, pm_vec3 d, pm_rng *r, sample *out, pxcache *pc)
{
	memset(out, 0, sizeof *out);
	walk(c, sc, o, d, 0, pm_v3(1, 1, 1), o, 1, 0.0f, 1, NULL, out, pc, r);
}

static int
finite_sample(const sample *s)
{
	return pm_vfinite(s->direct) && pm_vfinite(s->indirect) && pm_vfinite(s->specular);
}

int
pm_render(const pm_frame *f, const pm_photons *map, const pm_render_opts *o,
          pm_image *img, pm_error *err)
{
	const pm_scene *s = f->s;
	const pm_estimator *est = o->estimator;
	ctx c = {s, f->accel, &f->lights, o, est,
	         {s, f->accel, map, f->pi, o->k, o->classical_norm, o->shrink}, 0.0f, {0}};
	pm_camera cam;
	int W, H, fail = 0;
	size_t npx;

	if ((est->needs & PM_NEEDS_MAP) && !map)
		return pm_seterr(err, "the %s estimate needs a photon map", est->name);
	if ((est->needs & PM_NEEDS_POLYINDEX) && !f->pi)
		return pm_seterr(err, "the %s estimate needs a polygon index", est->name);
	if (o->classical_norm != PM_NORM_K && o->classical_norm != PM_NORM_K1)
		return pm_seterr(err, "unknown classical normalisation %d", o->classical_norm);
	if (o->gather && !est->estimate)
		return pm_seterr(err, "gathering needs an estimate, not %s", est->name);
	if (o->gather)
		pm_gather_init(&c.gather, f, est, &c.in, o->gather);
	if (pm_camera_init(&cam, &s->camera, err) != 0)
		return pm_preferr(err, "%s", s->path);
	c.pixel_angle = 2.0f * cam.tan_half / (float)cam.height;
	W = cam.width;
	H = cam.height;
	npx = (size_t)W * H;
	if (pm_image_init(img, W, H, PM_RENDER_NCHAN, pm_render_chans, err) != 0)
		return -1;
	if (est->image) {
		if (est->image(&c.in, &cam, img, err) != 0) {
			pm_image_free(img);
			return -1;
		}
		if (o->progress)
			o->progress(o->progress_arg, (uint64_t)H, (uint64_t)H);
		return 0;
	}

	int rows_done = 0;
	#pragma omp parallel reduction(|:fail)
	{
		void *sc = est->scratch_new ? est->scratch_new(o->k) : NULL;
		if (est->scratch_new && !sc)
			fail = 1;
		#pragma omp for schedule(dynamic, 1)
		for (int y = 0; y < H; y++) {
			if (fail)
				continue;
			for (int x = 0; x < W; x++) {
				size_t i = (size_t)y * W + x;
				pm_rng r = pm_rng_seed(o->seed ^ RENDER_DOMAIN, i);
				pm_vec3 dsum = {0}, isum = {0}, ssum = {0};
				double size = 0;
				long count = 0;
				int nest = 0, nedge = 0;
				pxcache pc = {0};
				for (int k = 0; k < o->spp; k++) {
					sample smp;
					float sx = (float)x + pm_rng_f(&r), sy = (float)y + pm_rng_f(&r);
					trace(&c, sc, cam.eye, pm_camera_dir(&cam, sx, sy), &r, &smp,
					      o->estimate_once ? &pc : NULL);
					if (!finite_sample(&smp))
						continue;
					dsum = pm_add(dsum, smp.direct);
					isum = pm_add(isum, smp.indirect);
					ssum = pm_add(ssum, smp.specular);
					if (smp.estimated) {
						size += smp.size;
						count += smp.count;
						nedge += smp.edge;
						nest++;
					}
				}
				float inv = 1.0f / (float)o->spp;
				pm_vec3 tot = pm_scale(pm_add(dsum, pm_add(isum, ssum)), inv);
				float v[PM_RENDER_NCHAN] = {
					tot.x, tot.y, tot.z,
					dsum.x * inv, dsum.y * inv, dsum.z * inv,
					isum.x * inv, isum.y * inv, isum.z * inv,
					ssum.x * inv, ssum.y * inv, ssum.z * inv,
					nest ? (float)(size / nest) : 0.0f,
					nest ? (float)count / (float)nest : 0.0f,
					nest ? (float)nedge / (float)nest : 0.0f,
				};
				for (int ch = 0; ch < PM_RENDER_NCHAN; ch++)
					img->px[(size_t)ch * npx + i] = v[ch];
			}
			/* Progress from one thread only: the hook need not be
			 * thread-safe, and nothing it does reaches the image. */
			int done;
			#pragma omp atomic capture
			done = ++rows_done;
			if (o->progress && omp_get_thread_num() == 0)
				o->progress(o->progress_arg, (uint64_t)done, (uint64_t)H);
		}
		if (sc)
			est->scratch_free(sc);
	}
	if (fail) {
		pm_image_free(img);
		return pm_seterr(err, "out of memory");
	}
	if (o->progress)
		o->progress(o->progress_arg, (uint64_t)H, (uint64_t)H);
	return 0;
}
