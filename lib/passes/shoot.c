/* shoot.c — the light pass (see shoot.h). */
#include "passes/shoot.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "optics/bsdf.h"
#include "base/ldseq.h"
#include "base/rng.h"

#define CHUNK 1024          /* paths per work item */
#define BATCH 64            /* work items per round */
#define SHOOT_DOMAIN 0x5348004f4f54ull

/* The photons of one chunk's paths, in path order, for one map. */
typedef struct stash {
	pm_photon *p;
	size_t n, cap;
	uint32_t count[CHUNK];  /* photons stored by each path of the chunk */
} stash;

typedef struct chunk {
	stash glob, caus, guide;
	int oom;
} chunk;

/* Appends ph to st as a photon of the chunk's path j. */
static void
push(chunk *c, stash *st, int j, const pm_photon *ph)
{
	if (st->n == st->cap) {
		size_t cap = st->cap ? 2 * st->cap : 256;
		pm_photon *p = realloc(st->p, cap * sizeof *p);
		if (!p) {
			c->oom = 1;
			return;
		}
		st->p = p;
		st->cap = cap;
	}
	st->p[st->n++] = *ph;
	st->count[j]++;
}

const char *
pm_light_paths_name(int lp)
{
	return lp == PM_PATHS_SOBOL ? "sobol" : lp == PM_PATHS_RANDOM ? "random" : "?";
}

int
pm_light_paths_parse(const char *name)
{
	if (strcmp(name, "random") == 0)
		return PM_PATHS_RANDOM;
	if (strcmp(name, "sobol") == 0)
		return PM_PATHS_SOBOL;
	return -1;
}

/* Pair numbers of a Sobol' path (shoot.h): 0 to 2 for the emission, then
 * two a bounce. */
enum { PAIR_LIGHT, PAIR_POINT, PAIR_DIR, PAIR_BOUNCE };

static void
trace_path(const pm_scene *s, const pm_accel *a, const pm_lights *L, const pm_shoot_opts *o,
           uint64_t idx, chunk *c, int j)
{
	pm_rng r = pm_rng_seed(o->seed ^ SHOOT_DOMAIN, idx);
	pm_vec3 org, d, n, power;
	int maxb = o->max_bounces > 0 ? o->max_bounces : 256;
	int specular_only = 1;  /* every hit so far strong: the path is L S* */
	int ld = o->light_paths == PM_PATHS_SOBOL;
	uint64_t lseed = o->seed ^ SHOOT_DOMAIN;
	pm_hit h;

	if (ld) {
		float u[6];
		pm_ld_pair(lseed, PAIR_LIGHT, idx, &u[0], &u[5]);
		pm_ld_pair(lseed, PAIR_POINT, idx, &u[1], &u[2]);
		pm_ld_pair(lseed, PAIR_DIR, idx, &u[3], &u[4]);
		pm_lights_emit_u(L, u, &org, &d, &n, &power);
	} else {
		pm_lights_emit(L, &r, &org, &d, &n, &power);
	}
	if (pm_dot(n, d) != 0)
		org = pm_accel_offset(a, org, n, d);
	for (int bounce = 0; bounce < maxb; bounce++) {
		const pm_material *m;
		pm_material mt;     /* m with its textures looked up, if it has any */
		pm_vec3 wo = pm_neg(d);
		pm_scatter sc;
		float q, u[4];

		if (!pm_accel_hit(a, org, d, 0.0f, FLT_MAX, &h))
			return;
		m = pm_hit_material(s, &h, &mt);
		/* After the first bounce a hit is kept: in the global (and the
		 * caustic) map where view paths end, in the guide map where they
		 * go on by sampling a lobe, not a delta (strong glossy; guide.h). */
		int ends = pm_mat_is_photon_surface(m);
		if (bounce > 0 && (ends || (o->guide && m->kind == PM_MAT_GLOSSY))) {
			pm_photon ph;
			pm_vec3 ns = pm_dot(h.ng, wo) >= 0 ? h.ng : pm_neg(h.ng);
			pm_photon_pack(&ph, h.p, wo, ns, power);
			push(c, ends ? &c->glob : &c->guide, j, &ph);
			if (ends && specular_only && o->caustic)
				push(c, &c->caus, j, &ph);
		}
		if (ends)
			specular_only = 0;
		/* Pseudo-random: the roulette's number follows the BSDF's three,
		 * drawn before the sample as it ends the path if that fails. */
		if (ld) {
			uint32_t pair = PAIR_BOUNCE + 2 * (uint32_t)bounce;
			pm_ld_pair(lseed, pair, idx, &u[0], &u[1]);
			pm_ld_pair(lseed, pair + 1, idx, &u[2], &u[3]);
		} else {
			for (int i = 0; i < 4; i++)
				u[i] = pm_rng_f(&r);
		}
		pm_vec3 ns = pm_hit_shading(s, &h);
		if (ns.x == h.ng.x && ns.y == h.ng.y && ns.z == h.ng.z) {
			if (pm_bsdf_sample_u(m, h.ng, wo, u[0], u[1], u[2], &sc) != 0)
				return;
		} else {
			/* About the shading normal, with the adjoint's correction
			 * (Veach 1997, eq. 5.19): flux arrives per unit of facet
			 * area, |wo.ng|, and leaves through it, |wi.ng|, while the
			 * BSDF's cosines are the shading normal's. */
			pm_vec3 n = pm_shading_side(h.ng, ns, wo);
			if (pm_bsdf_sample_n(m, h.ng, n, wo, u[0], u[1], u[2], &sc) != 0)
				return;
			float c = fabsf(pm_dot(wo, n)) * fabsf(pm_dot(sc.wi, h.ng))
			        / (fabsf(pm_dot(wo, h.ng)) * fabsf(pm_dot(sc.wi, n)));
			if (!(c < INFINITY))
				return;
			sc.weight = pm_scale(sc.weight, c);
		}
		/* Photons carry power: no eta^2 across a refraction. */
		if (sc.adjoint != 1.0f)
			sc.weight = pm_scale(sc.weight, sc.adjoint);
		q = fminf(1.0f, pm_maxc(sc.weight));
		if (!(q > 0) || u[3] >= q)
			return;
		power = pm_scale(pm_mul(power, sc.weight), 1.0f / q);
		org = pm_accel_offset(a, h.p, h.ng, sc.wi);
		d = sc.wi;
	}
}

/* Appends photons from[at .. at+n-1] to a growing array; 0, or -1 out of
 * memory. */
static int
append(pm_photon **arr, size_t *len, size_t *cap, const pm_photon *from, size_t at, size_t n)
{
	if (n == 0)         /* arr and from may still be NULL */
		return 0;
	if (*len + n > *cap) {
		size_t c = *cap ? 2 * *cap : 4096;
		pm_photon *q;
		while (c < *len + n)
			c *= 2;
		if (!(q = realloc(*arr, c * sizeof *q)))
			return -1;
		*arr = q;
		*cap = c;
	}
	memcpy(*arr + *len, from + at, n * sizeof *from);
	*len += n;
	return 0;
}

/* 1 if some material continues paths (mirror, glass, strong glossy): without
 * one there are no caustic photons to wait for. */
static int
has_strong(const pm_scene *s)
{
	for (int i = 0; i < s->nmats; i++)
		if (!pm_mat_is_photon_surface(&s->mats[i]))
			return 1;
	return 0;
}

int
pm_shoot(const pm_scene *s, const pm_accel *a, const pm_lights *L,
         const pm_shoot_opts *o, pm_photons *out, pm_error *err)
{
	uint64_t want = o->nphotons, cwant = o->ncaustic, emitted = 0, cemitted = 0, next = 0;
	uint64_t most = want > cwant ? want : cwant;
	uint64_t maxp = o->max_paths ? o->max_paths : 64 * most + (1u << 20);
	chunk *ch = calloc(BATCH, sizeof *ch);
	pm_photon *all = NULL, *caus = NULL, *guide = NULL;
	size_t stored = 0, ncaus = 0, capcaus = 0, cap = 0, nguide = 0, capguide = 0;
	/* Each map is done after the path that stores its last photon; a
	 * caustic map without a count of its own takes the global map's paths. */
	int gdone = want == 0, cdone = !o->caustic || (cwant > 0 && !has_strong(s)), oom = 0;

	memset(out, 0, sizeof *out);
	if (o->caustic)
		memset(o->caustic, 0, sizeof *o->caustic);
	if (o->guide)
		memset(o->guide, 0, sizeof *o->guide);
	if (!ch)
		return pm_seterr(err, "out of memory");
	if (want > 0 && !(all = malloc(want * sizeof *all))) {
		free(ch);
		return pm_seterr(err, "out of memory for %llu photons", (unsigned long long)want);
	}
	cap = want;
	if (o->caustic && cwant == 0)
		cdone = gdone;
	while (!(gdone && cdone) && !oom && next < maxp) {
		uint64_t base = next;
		#pragma omp parallel for schedule(dynamic, 1)
		for (int ci = 0; ci < BATCH; ci++) {
			chunk *c = &ch[ci];
			c->glob.n = c->caus.n = c->guide.n = 0;
			memset(c->glob.count, 0, sizeof c->glob.count);
			memset(c->caus.count, 0, sizeof c->caus.count);
			memset(c->guide.count, 0, sizeof c->guide.count);
			for (int j = 0; j < CHUNK; j++)
				trace_path(s, a, L, o, base + (uint64_t)ci * CHUNK + j, c, j);
		}
		/* Keep paths in index order until each map's last photon is stored. */
		for (int ci = 0; ci < BATCH && !(gdone && cdone) && !oom; ci++) {
			chunk *c = &ch[ci];
			size_t at = 0, cat = 0, gat = 0;
			oom |= c->oom;
			for (int j = 0; j < CHUNK && !(gdone && cdone) && !oom; j++) {
				uint64_t take = c->glob.count[j], ctake = c->caus.count[j];
				int shared = cwant == 0 && !gdone;   /* a path of both maps */
				next++;
				if (!gdone) {
					emitted++;
					if (take > want - stored)
						take = want - stored;
					oom |= append(&all, &stored, &cap, c->glob.p, at, take);
					oom |= append(&guide, &nguide, &capguide, c->guide.p, gat, c->guide.count[j]);
					if (stored >= want || emitted >= maxp)
						gdone = 1;
				}
				if (!cdone) {
					cemitted++;
					if (cwant > 0 && ctake > cwant - ncaus)
						ctake = cwant - ncaus;
					oom |= append(&caus, &ncaus, &capcaus, c->caus.p, cat, ctake);
					if (shared ? gdone : ncaus >= cwant || cemitted >= maxp)
						cdone = 1;
				}
				at += c->glob.count[j];
				cat += c->caus.count[j];
				gat += c->guide.count[j];
			}
		}
		if (o->progress)
			o->progress(o->progress_arg, stored, want);
	}
	for (int ci = 0; ci < BATCH; ci++) {
		free(ch[ci].glob.p);
		free(ch[ci].caus.p);
		free(ch[ci].guide.p);
	}
	free(ch);
	if (oom) {
		free(all);
		free(caus);
		free(guide);
		return pm_seterr(err, "out of memory while shooting photons");
	}
	out->p = all;
	out->h.version = 1;
	out->h.kdtree = 0;
	out->h.count = stored;
	out->h.emitted = emitted;
	out->h.light_hash = s->light_hash;
	out->h.time = o->time;
	snprintf(out->h.seeds, sizeof out->h.seeds, "%llu", (unsigned long long)o->seed);
	snprintf(out->h.light_paths, sizeof out->h.light_paths, "%s", pm_light_paths_name(o->light_paths));
	if (o->caustic) {
		o->caustic->h = out->h;
		o->caustic->h.map = PM_MAP_CAUSTIC;
		o->caustic->h.version = 2;
		o->caustic->h.count = ncaus;
		o->caustic->h.emitted = cwant == 0 ? emitted : cemitted;
		o->caustic->p = caus;
	}
	if (o->guide) {
		o->guide->h = out->h;
		o->guide->h.map = PM_MAP_GUIDE;
		o->guide->h.version = 2;
		o->guide->h.count = nguide;
		o->guide->p = guide;
	} else {
		free(guide);
	}
	return 0;
}
