/* render.c — the view pass (see render.h). */
#include "passes/render.h"

#include <float.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "optics/bsdf.h"
#include "scene/camera.h"
#include "passes/direct.h"
#include "estimators/edge.h"
#include "base/rng.h"
#include "scene/patch.h"

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
	pm_direct dl;       /* the scene, accel and lights again, for direct.h */
	float pixel_angle;  /* a pixel's width in radians at the image centre */
	float sample_angle; /* the spacing of its camera samples: textures' filter */
	int light_samples;  /* o->light_samples, at least 1 */
	pm_gather gather;   /* used if o->gather */
	const uint32_t *patch;  /* each polygon's smooth patch (scene/patch.h) */
	int every;          /* past_glossy: estimates past a bounce that shares */
	float every_w;      /* nothing on samples 0, every, ...; their weight */
} ctx;

/* What a pixel's camera samples share. Its first-hit photon estimate on
 * each smooth patch it sees (up to PX_SLOTS of them), reused by its later
 * camera samples that land on the same patch (opts.estimate_once; a
 * polygon, or the facets of one curved surface, scene/patch.h): the
 * samples are each uniform over the pixel and exchangeable (pixel_order()),
 * so that, given where they all fall, the first one on a patch is any of
 * those on it with equal chance, and the pixel's expected value is
 * unchanged, provided that whether it is reused does not depend on that
 * point (the patches are fixed before any sample). Across an edge a pixel
 * sees several patches, in any order: keeping one estimate for the whole
 * pixel made every sample on another patch estimate anew, up to 8
 * estimates a pixel there (thin: 110 960 estimates for 65 536 pixels, the
 * expensive ones of several polygons).
 * Reuse pays where the estimate's support covers about the area of the
 * pixel's footprint: the square around a disc as large as the support
 * (2 info.disc across; the compensated cube counts as the disc of its
 * cross-section's area, so both estimates reuse alike: judged by the
 * cube's own side, the compensated pass took 42 % more estimates than the
 * classical one on the Cornell box, for 1 % less noise). The estimate
 * then barely varies within the pixel, while a support smaller than the
 * footprint (few photons per estimate, many per pass) would lose the
 * averaging of the samples' estimates, which are then nearly independent.
 * That test is made on the previous pixel of the row, on the same patch
 * (on a patch it did not see: a yes on any patch it did), or else on the
 * patch's first estimate in the pixel, which then is used once and the
 * next one there reused: made on the estimate it reuses, it
 * kept dim estimates (wide support) and diluted bright ones (narrow
 * support), and a caustic read 10 % dark. */
#define PX_SLOTS 4
/* A pixel's camera samples fall one to a cell of a ga x gb grid over it
 * (ga = floor(sqrt(spp)), gb = spp / ga; those past ga gb anywhere), which
 * takes the noise of what the pixel covers (a lamp's edge, a thin part's)
 * down faster than independent points. The cells are taken in an order
 * drawn afresh for each pixel, every order as likely, so the samples are
 * exchangeable: what sharing an estimate needs (above), as independent
 * samples are. In cells, taken in order, the first on a patch would favour
 * the top of the pixel. Up to PX_CELLS_MAX samples a pixel; past that they
 * are independent. */
#define PX_CELLS_MAX 4096
/* A path's specular bounces before the surface it takes an estimate on:
 * each a polygon and whether the path crossed it (refraction), if all of
 * them were mirrors or glass whose weights are untextured, so that every
 * camera sample along the same chain carries the same weight to that
 * surface. The pixel's samples along one chain then land on it as its
 * first hits land on a patch (independent, from one distribution), and
 * an estimate is shared among them as among first hits, with the same
 * expectation; through a strong glossy lobe the weights vary with the
 * direction, and nothing is shared (BENCHMARKS, compcost section). */
#define CHAIN_MAX 4
typedef struct chain {
	int n;                /* bounces so far; -1: past a bounce that shares nothing */
	uint32_t k[CHAIN_MAX];
} chain;

typedef struct pxslot {
	uint32_t key;         /* a patch number */
	chain ch;             /* for an estimate past specular bounces: */
	int seen;             /* ... how many of its samples have come */
	pm_vec3 p1;           /* ... the first one's point */
	int ok;               /* its estimates after the one that decided are reused */
	int first_ok;         /* the first one's word on the patch for the next pixel */
	int valid;            /* L and info hold one, to reuse */
	pm_vec3 L;
	pm_estimate_info info;
	int edge;             /* ... and whether its support reaches an edge */
} pxslot;

typedef struct pxcache {
	pxslot s[PX_SLOTS];   /* the patches seen so far, in order */
	int ns;
	pxslot d[PX_SLOTS];   /* the same past specular chains */
	int nd;
	int nword;            /* the previous pixel's word: the patches it */
	uint32_t wkey[PX_SLOTS];   /* estimated on, and for each whether its */
	unsigned char wok[PX_SLOTS];  /* first estimate here is reused */
	/* The guide (opts.guide) at the pixel's first strong glossy hit,
	 * reused by its later samples on the same polygon: any histogram
	 * leaves the mean alone, and one a few millimetres away is as good. */
	int gvalid;
	uint32_t gpoly;
	pm_guide gd;
	int k;                /* the camera sample being traced */
	pm_strata st;         /* the shadow rays at its first hits (n 0: none) */
} pxcache;

static int
same_chain(const chain *a, const chain *b)
{
	if (a->n != b->n)
		return 0;
	for (int i = 0; i < a->n; i++)
		if (a->k[i] != b->k[i])
			return 0;
	return 1;
}

/* The estimate at h: a first hit's (ch NULL) or one past the specular
 * chain ch, shared in the pixel's cache pc if that is given. */
static pm_vec3
first_estimate(const ctx *c, void *sc, const pm_hit *h, pm_vec3 n, pm_vec3 ns, pm_vec3 wo,
               const pm_material *m, pxcache *pc, const chain *ch, pm_estimate_info *info, int *edge)
{
	pm_vec3 L;
	uint32_t key = c->patch ? c->patch[h->poly] : h->poly;
	pxslot *sl = NULL, *set = pc ? (ch ? pc->d : pc->s) : NULL;
	int *nset = pc ? (ch ? &pc->nd : &pc->ns) : NULL;

	for (int i = 0; pc && i < *nset && !sl; i++)
		sl = set[i].key == key && (!ch || same_chain(&set[i].ch, ch)) ? &set[i] : NULL;
	if (sl && sl->valid) {
		*info = sl->info;
		if (edge)
			*edge = sl->edge;
		return sl->L;
	}
	L = c->est->estimate(&c->in, sc, h->p, n, ns, wo, m, info);
	/* The edge band is about the support of the estimate a sample uses:
	 * a reused one's cube is around the point it was made at. Asked once
	 * an estimate, not once a sample (on a mesh, a query for each of 16
	 * samples a pixel cost 10-19 % of a view pass). */
	if (edge)
		*edge = pm_polyindex_near_edge(c->in.pi, h->p, info->size);
	if (!pc)
		return L;
	if (ch) {
		/* Past a chain the footprint can be anything (a ripple in
		 * water spreads a pixel's samples over the floor below), so
		 * the first two samples measure it: their points' distance
		 * against the second one's support. Neither estimate is
		 * reused, so the one that is (the third) does not depend on
		 * the points that chose it. */
		if (!sl) {
			if (*nset == PX_SLOTS)
				return L;
			sl = &set[(*nset)++];
			sl->key = key;
			sl->ch = *ch;
			sl->valid = sl->ok = 0;
			sl->seen = 1;
			sl->p1 = h->p;
		} else if (sl->seen++ == 1) {
			sl->ok = pm_len(pm_sub(h->p, sl->p1)) <= 0.5f * info->disc;
		} else if (sl->ok) {
			sl->valid = 1;
			sl->L = L;
			sl->info = *info;
			sl->edge = 0;
		}
		return L;
	}
	if (!sl) {
		/* The footprint's area: the pixel's angle at distance t,
		 * squared, stretched by the obliquity (capped, for grazing
		 * views); the support's: (2 disc)^2, the square around a disc
		 * as large as the support. */
		float cosv = fabsf(pm_dot(n, wo));
		float w = h->t * c->pixel_angle;
		int ok = w * w / (cosv > 0.05f ? cosv : 0.05f) <= 4.0f * info->disc * info->disc;
		/* Past PX_SLOTS patches, every sample estimates anew. */
		if (*nset == PX_SLOTS)
			return L;
		sl = &set[(*nset)++];
		sl->key = key;
		sl->valid = 0;
		sl->first_ok = ok;
		/* A patch the previous pixel did not see (an edge entering
		 * the row, a small patch) takes its word on those it did: the
		 * photons' spacing there is the same, and where it said yes
		 * on one (thin: 5 % fewer estimates, at edges, the dear ones).
		 * Every word is made before this pixel's samples, so the
		 * reused estimate's point is still uniform over the footprint. */
		int said = -1, any = 0;
		for (int i = 0; i < pc->nword; i++) {
			said = pc->wkey[i] == key ? pc->wok[i] : said;
			any |= pc->wok[i];
		}
		sl->ok = said >= 0 ? said : any;
		/* A no from the previous pixel, or none at all: this estimate
		 * decides for the next one here, which is reused, and is
		 * itself used once. */
		if (!sl->ok) {
			sl->ok = ok;
			return L;
		}
	}
	if (sl->ok) {
		sl->valid = 1;
		sl->L = L;
		sl->info = *info;
		sl->edge = edge ? *edge : 0;
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
	float eta_scale = 1;    /* the product of the refractions' adjoint factors */
	chain ch = {c->o->estimate_once ? 0 : -1, {0}};
	pm_hit h;

	for (; depth < maxd; depth++) {
		const pm_material *m;
		pm_material mt;     /* m with its textures looked up, if it has any */
		pm_vec3 wo = pm_neg(d), n, nf;
		pm_vec3 *here;
		pm_scatter bs;
		pm_guide gd;
		const pm_guide *g = NULL;
		int ends, nl;

		if (!pm_accel_hit(c->a, o, d, 0.0f, FLT_MAX, &h)) {
			pm_vec3 *sky = depth == 0 ? &out->direct : bucket;
			*sky = pm_add(*sky, pm_mul(beta, pm_direct_escaped(&c->dl, d, bpdf, delta, nlprev)));
			return;
		}
		if (depth == 0) {
			/* The camera ray's footprint filters textures (the
			 * light pass and later bounces point-sample). */
			pm_vec3 a1, a2;
			pm_pixel_footprint(&h, d, c->sample_angle, &a1, &a2);
			m = pm_hit_material_fp(c->s, &h, a1, a2, &mt);
		} else {
			m = pm_hit_material(c->s, &h, &mt);
		}
		/* nf: the facet's normal on wo's side, for the estimate's
		 * geometry (clipping, target areas, which photons count); n: the
		 * shading normal there, for direct light, the BSDF and the
		 * estimate's cosine (README). */
		nf = pm_dot(h.ng, wo) >= 0 ? h.ng : pm_neg(h.ng);
		n = pm_shading_side(h.ng, pm_hit_shading(c->s, &h), wo);
		if (depth == 0)
			bucket = pm_mat_is_photon_surface(m) ? &out->indirect : &out->specular;
		here = depth == 0 ? (m->strong ? &out->specular : &out->direct) : bucket;
		*here = pm_add(*here, pm_mul(beta, pm_direct_emitted(&c->dl, &h, prev, d, bpdf, delta, nlprev)));
		ends = pm_mat_is_photon_surface(m) && c->est->estimate;
		nl = depth == 0 || ends ? c->light_samples : 1;
		/* The guide is built before the light samples: their weights
		 * take the density the continuation is drawn with. */
		if (c->o->guide && m->kind == PM_MAT_GLOSSY && m->strong) {
			/* Only the diffuse lobe's light is spread out over the
			 * hemisphere; the glossy lobe keeps its own samples. */
			pm_guide *slot = depth == 0 ? &pc->gd : &gd;
			if (!(depth == 0 && pc->gvalid && pc->gpoly == h.poly)) {
				pm_guide_build(slot, c->o->guide, h.p, n);
				slot->share = 0.5f * pm_bsdf_diffuse_share(m);
				pc->gvalid |= depth == 0;
				pc->gpoly = depth == 0 ? h.poly : pc->gpoly;
			}
			g = slot;
		}
		if (m->kind == PM_MAT_DIFFUSE || m->kind == PM_MAT_GLOSSY) {
			const pm_strata *st = depth == 0 && pc && pc->st.n ? &pc->st : NULL;
			*here = pm_add(*here, pm_mul(beta, pm_direct_light(&c->dl, h.p, h.ng, n, wo, m, nl, g, st, r)));
		}
		if ((g ? pm_guide_mix(g, m, h.ng, n, wo, r, &bs) : pm_bsdf_sample_rn(m, h.ng, n, wo, r, &bs)) != 0)
			bs.pdf = -1;
		if (ends) {
			pm_estimate_info info;
			pm_vec3 L;
			int edge = 0;
			/* The BSDF-sampled half of the direct light. */
			*here = pm_add(*here, pm_mul(beta, pm_direct_bsdf_light(&c->dl, h.p, h.ng, &bs, nl)));
			/* A surface that reflects nothing gives 0 whatever the
			 * photons, and its cube can be huge: no photon lands near a
			 * lamp's face, so its k nearest are far (an imported sphere
			 * light: 8 304 polygons, 22 ms an estimate). No estimate,
			 * and the sample does not count in the size, count and
			 * edge layers. */
			if (pm_mat_is_black(m))
				return;
			/* Gathering draws its own rays: one gather per camera sample. */
			if (c->o->gather) {
				L = pm_gather_radiance(&c->gather, sc, r, h.p, h.ng, nf, n, wo, m, &info);
				if (depth == 0)
					edge = pm_polyindex_near_edge(c->in.pi, h.p, info.size);
			} else if (depth == 0) {
				L = first_estimate(c, sc, &h, nf, n, wo, m, c->o->estimate_once ? pc : NULL, NULL,
				                   &info, &edge);
			} else if (ch.n < 0 && pc && pc->k % c->every != 0) {
				/* Past a glossy lobe each sample's estimate is its
				 * own (its weight varies with the direction), and a
				 * pixel's 16 land close together, their photons
				 * largely the same: a quarter of them, chosen by
				 * index (the samples are independent and alike)
				 * and weighted up, keep the expected image for
				 * half the room's time (BENCHMARKS.md, "Estimates
				 * past a glossy floor on one sample in four"). */
				return;
			} else {
				L = first_estimate(c, sc, &h, nf, n, wo, m, ch.n >= 0 ? pc : NULL, &ch, &info, NULL);
				if (ch.n < 0 && pc)
					L = pm_scale(L, c->every_w);
			}
			*bucket = pm_add(*bucket, pm_mul(beta, L));
			if (depth == 0) {
				out->size = info.size;
				out->count = info.nphotons;
				out->estimated = 1;
				out->edge = edge;
			}
			return;
		}
		if (bs.pdf < 0)
			return;
		if (ch.n >= 0) {
			const pm_material *mo = &c->s->mats[c->s->objs[h.obj].material];
			if (!bs.delta || mo->tks || ch.n == CHAIN_MAX) {
				ch.n = -1;
			} else {
				int crossed = (pm_dot(bs.wi, h.ng) > 0) != (pm_dot(wo, h.ng) > 0);
				ch.k[ch.n++] = h.poly << 1 | (uint32_t)crossed;
			}
		}
		beta = pm_mul(beta, bs.weight);
		delta = bs.delta;
		bpdf = bs.pdf;
		nlprev = nl;
		prev = h.p;
		/* Roulette on the throughput without refraction's eta^2
		 * (Veach 1997, 5.2): inside glass it is not less light. */
		eta_scale *= bs.adjoint;
		if (depth >= 3) {
			float q = fminf(0.95f, pm_maxc(beta) * eta_scale);
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

/* A uniformly random order of a pixel's n cells (n <= PX_CELLS_MAX): the
 * inside-out shuffle (Durstenfeld 1964). */
static void
pixel_order(pm_rng *r, int n, int *order)
{
	for (int k = 0; k < n; k++) {
		int q = (int)pm_rng_below(r, (uint32_t)k + 1);
		if (q != k)
			order[k] = order[q];
		order[q] = k;
	}
}

/* Camera sample k's point in its pixel, in [0, 1)^2: in cell order[k] of
 * the pixel's ga x gb grid (pm_cells() of spp), or anywhere. */
static void
pixel_point(const int *order, int spp, int ga, int gb, int k, pm_rng *r, float *u, float *v)
{
	*u = pm_rng_f(r);
	*v = pm_rng_f(r);
	pm_cell_point(spp <= PX_CELLS_MAX ? order[k] : ga * gb, ga, gb, u, v);
}

/* 1 if f's vertices are the scene's at time 0: at time 0, or where no
 * object moves. */
static int
unmoved(const pm_frame *f)
{
	if (f->time == 0)
		return 1;
	for (int o = 0; o < f->s->nobjs; o++) {
		pm_vec3 m = f->s->objs[o].motion;
		if (m.x != 0 || m.y != 0 || m.z != 0)
			return 0;
	}
	return 1;
}

int
pm_render(const pm_frame *f, const pm_photons *map, const pm_render_opts *o,
          pm_image *img, pm_error *err)
{
	const pm_scene *s = f->s;
	const pm_estimator *est = o->estimator;
	ctx c = {s, f->accel, &f->lights, o, est,
	         {s, f->accel, map, f->pi, o->k, o->classical_norm, o->shrink},
	         {s, f->accel, &f->lights}, 0.0f, 0.0f,
	         o->light_samples > 1 ? o->light_samples : 1, {0}, NULL, 1, 1.0f};
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
	/* The pixel's samples already average its area: a texture needs
	 * filtering over their spacing only, a pixel over sqrt(spp), no finer
	 * than an eighth of a pixel (pbrt-v4's scale of its ray differentials,
	 * so that the two agree where squares meet a pixel's edge). */
	c.sample_angle = c.pixel_angle * fmaxf(0.125f, 1.0f / sqrtf((float)(o->spp > 0 ? o->spp : 1)));
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

	/* The patches of the scene at time 0. The frame's polygon index holds
	 * the same where nothing has moved (its positions are those, plus 0),
	 * and making them again cost a dense mesh's pass a tenth of a second. */
	uint32_t *patch = NULL;
	if (o->estimate_once && f->pi && unmoved(f))
		c.patch = f->pi->patch;
	else if (o->estimate_once && pm_scene_patches(s, &patch, err) != 0) {
		pm_image_free(img);
		return -1;
	} else
		c.patch = patch;
	c.every = o->estimate_once && o->past_glossy > 1 ? o->past_glossy : 1;
	c.every_w = (float)o->spp / (float)((o->spp + c.every - 1) / c.every);
	int rows_done = 0, cga, cgb;
	pm_cells(o->spp, &cga, &cgb);
	#pragma omp parallel reduction(|:fail)
	{
		void *sc = est->scratch_new ? est->scratch_new(o->k) : NULL;
		if (est->scratch_new && !sc)
			fail = 1;
		#pragma omp for schedule(dynamic, 1)
		for (int y = 0; y < H; y++) {
			int nword = 0, order[PX_CELLS_MAX];
			uint32_t wkey[PX_SLOTS] = {0};
			unsigned char wok[PX_SLOTS] = {0};
			if (fail)
				continue;
			for (int x = 0; x < W; x++) {
				size_t i = (size_t)y * W + x;
				pm_rng r = pm_rng_seed(o->seed ^ RENDER_DOMAIN, i);
				pm_vec3 dsum = {0}, isum = {0}, ssum = {0};
				double size = 0;
				long count = 0;
				int nest = 0, nedge = 0;
				/* Not zeroed whole: the guide's histogram is read
				 * only once built (gvalid). */
				pxcache pc;
				pc.ns = pc.nd = pc.gvalid = 0;
				pc.nword = nword;
				memcpy(pc.wkey, wkey, sizeof wkey);
				memcpy(pc.wok, wok, sizeof wok);
				pc.st.n = 0;
				if (o->spp <= PX_CELLS_MAX) {
					pixel_order(&r, o->spp, order);
					pc.st.n = o->spp * c.light_samples;
					pc.st.off = pm_rng_below(&r, (uint32_t)pc.st.n);
					pc.st.pick = pm_rng_below(&r, (uint32_t)pc.st.n);
				}
				for (int k = 0; k < o->spp; k++) {
					sample smp;
					float u, v;
					pc.k = k;
					pc.st.first = k * c.light_samples;
					pixel_point(order, o->spp, cga, cgb, k, &r, &u, &v);
					trace(&c, sc, cam.eye, pm_camera_dir(&cam, (float)x + u, (float)y + v), &r, &smp, &pc);
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
				/* Every patch the pixel saw gives its word, not
				 * only the first: along an edge each pixel sees
				 * the same two (thin: 4 % fewer estimates, the
				 * dear ones of several polygons). */
				nword = pc.ns;
				for (int j = 0; j < pc.ns; j++) {
					wkey[j] = pc.s[j].key;
					wok[j] = (unsigned char)pc.s[j].first_ok;
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
	free(patch);
	if (fail) {
		pm_image_free(img);
		return pm_seterr(err, "out of memory");
	}
	if (o->progress)
		o->progress(o->progress_arg, (uint64_t)H, (uint64_t)H);
	return 0;
}
