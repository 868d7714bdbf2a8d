/* shoot.c — the light pass (see shoot.h). */
#include "shoot.h"

#include <float.h>
#include <stdlib.h>
#include <string.h>

#include "bsdf.h"
#include "ldseq.h"
#include "rng.h"

#define CHUNK 1024          /* paths per work item */
#define BATCH 64            /* work items per round */
#define SHOOT_DOMAIN 0x5348004f4f54ull

typedef struct chunk {
	pm_photon *p;
	size_t n, cap;
	uint32_t count[CHUNK];  /* photons stored by each path of the chunk */
	int oom;
} chunk;

static void
push(chunk *c, const pm_photon *ph)
{
	if (c->n == c->cap) {
		size_t cap = c->cap ? 2 * c->cap : 256;
		pm_photon *p = realloc(c->p, cap * sizeof *p);
		if (!p) {
			c->oom = 1;
			return;
		}
		c->p = p;
		c->cap = cap;
	}
	c->p[c->n++] = *ph;
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
           uint64_t idx, chunk *c, uint32_t *count)
{
	pm_rng r = pm_rng_seed(o->seed ^ SHOOT_DOMAIN, idx);
	pm_vec3 org, d, n, power;
	int maxb = o->max_bounces > 0 ? o->max_bounces : 256;
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
		pm_vec3 wo = pm_neg(d);
		pm_scatter sc;
		float q, u[4];

		if (!pm_accel_hit(a, org, d, 0.0f, FLT_MAX, &h))
			return;
		m = &s->mats[s->objs[h.obj].material];
		if (bounce > 0 && pm_mat_is_photon_surface(m)) {
			pm_photon ph;
			pm_vec3 ns = pm_dot(h.ng, wo) >= 0 ? h.ng : pm_neg(h.ng);
			pm_photon_pack(&ph, h.p, wo, ns, power);
			push(c, &ph);
			(*count)++;
		}
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
		if (pm_bsdf_sample_u(m, h.ng, wo, u[0], u[1], u[2], &sc) != 0)
			return;
		q = fminf(1.0f, pm_maxc(sc.weight));
		if (!(q > 0) || u[3] >= q)
			return;
		power = pm_scale(pm_mul(power, sc.weight), 1.0f / q);
		org = pm_accel_offset(a, h.p, h.ng, sc.wi);
		d = sc.wi;
	}
}

int
pm_shoot(const pm_scene *s, const pm_accel *a, const pm_lights *L,
         const pm_shoot_opts *o, pm_photons *out, pm_error *err)
{
	uint64_t want = o->nphotons, emitted = 0, stored = 0;
	uint64_t maxp = o->max_paths ? o->max_paths : 64 * want + (1u << 20);
	chunk *ch = calloc(BATCH, sizeof *ch);
	pm_photon *all = NULL;
	int done = 0, oom = 0;

	memset(out, 0, sizeof *out);
	if (!ch)
		return pm_seterr(err, "out of memory");
	if (want > 0 && !(all = malloc(want * sizeof *all))) {
		free(ch);
		return pm_seterr(err, "out of memory for %llu photons", (unsigned long long)want);
	}
	while (!done && stored < want && emitted < maxp) {
		uint64_t base = emitted;
		#pragma omp parallel for schedule(dynamic, 1)
		for (int ci = 0; ci < BATCH; ci++) {
			chunk *c = &ch[ci];
			c->n = 0;
			memset(c->count, 0, sizeof c->count);
			for (int j = 0; j < CHUNK; j++)
				trace_path(s, a, L, o, base + (uint64_t)ci * CHUNK + j, c, &c->count[j]);
		}
		/* Keep paths in index order until the n-th photon is stored. */
		for (int ci = 0; ci < BATCH && !done; ci++) {
			chunk *c = &ch[ci];
			size_t at = 0;
			oom |= c->oom;
			for (int j = 0; j < CHUNK && !done; j++) {
				uint64_t take = c->count[j];
				emitted++;
				if (take > want - stored)
					take = want - stored;
				memcpy(all + stored, c->p + at, take * sizeof *all);
				stored += take;
				at += c->count[j];
				if (stored >= want || emitted >= maxp)
					done = 1;
			}
		}
		if (o->progress)
			o->progress(o->progress_arg, stored, want);
	}
	for (int ci = 0; ci < BATCH; ci++)
		free(ch[ci].p);
	free(ch);
	if (oom) {
		free(all);
		return pm_seterr(err, "out of memory while shooting photons");
	}
	out->p = all;
	out->h.version = PM_PHOTONS_VERSION;
	out->h.kdtree = 0;
	out->h.count = stored;
	out->h.emitted = emitted;
	out->h.light_hash = s->light_hash;
	out->h.time = o->time;
	snprintf(out->h.seeds, sizeof out->h.seeds, "%llu", (unsigned long long)o->seed);
	snprintf(out->h.light_paths, sizeof out->h.light_paths, "%s", pm_light_paths_name(o->light_paths));
	return 0;
}
