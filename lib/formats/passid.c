/* passid.c — pass ids and lists of them (see passid.h). */
#include "formats/passid.h"

#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/fnv.h"

#define ID_DIGITS 16

uint64_t
pm_pass_id(uint64_t scene_hash, const char *estimator, uint64_t seed,
           float time, const char *map_seeds)
{
	char head[128];
	int n = snprintf(head, sizeof head, "%016" PRIx64 " %s %" PRIu64 " %.9g ",
	                 scene_hash, estimator, seed, time);
	uint64_t h = pm_fnv1a(PM_FNV_OFFSET, head, (size_t)n);

	return pm_fnv1a(h, map_seeds, strlen(map_seeds));
}

void
pm_passids_init(pm_passids *l)
{
	memset(l, 0, sizeof *l);
}

void
pm_passids_free(pm_passids *l)
{
	free(l->v);
	memset(l, 0, sizeof *l);
}

static int
hexval(char c)
{
	if (c >= '0' && c <= '9')
		return c - '0';
	if (c >= 'a' && c <= 'f')
		return c - 'a' + 10;
	return -1;
}

int
pm_passids_add(pm_passids *l, const char *text, int src, size_t *added, pm_error *err)
{
	size_t len = strlen(text), n = (len + 1) / (ID_DIGITS + 1), start = l->n;

	*added = 0;
	if (len == 0 || (len + 1) % (ID_DIGITS + 1) != 0)
		return pm_seterr(err, "pm.pass_ids is not a list of 16-digit hex ids");
	if (l->n + n > l->cap) {
		size_t cap = l->cap ? l->cap : 64;
		pm_passid *v;
		while (cap < l->n + n)
			cap *= 2;
		if (!(v = realloc(l->v, cap * sizeof *v)))
			return pm_seterr(err, "out of memory for %zu pass ids", l->n + n);
		l->v = v;
		l->cap = cap;
	}
	for (size_t i = 0; i < n; i++) {
		const char *p = text + i * (ID_DIGITS + 1);
		uint64_t id = 0;
		for (int d = 0; d < ID_DIGITS; d++) {
			int h = hexval(p[d]);
			if (h < 0) {
				l->n = start;
				return pm_seterr(err, "pm.pass_ids is not a list of 16-digit hex ids");
			}
			id = id << 4 | (uint64_t)h;
		}
		if (i + 1 < n && p[ID_DIGITS] != ' ') {
			l->n = start;
			return pm_seterr(err, "pm.pass_ids is not a list of 16-digit hex ids");
		}
		l->v[l->n].id = id;
		l->v[l->n].src = src;
		l->n++;
	}
	*added = n;
	return 0;
}

static int
by_id(const void *pa, const void *pb)
{
	const pm_passid *a = pa, *b = pb;

	if (a->id != b->id)
		return a->id < b->id ? -1 : 1;
	return (a->src > b->src) - (a->src < b->src);
}

int
pm_passids_dup(pm_passids *l, uint64_t *id, int *a, int *b)
{
	int found = 0;

	if (l->n > 1)
		qsort(l->v, l->n, sizeof *l->v, by_id);
	for (size_t i = 1; i < l->n; i++) {
		const pm_passid *p = &l->v[i - 1], *q = &l->v[i];
		if (p->id != q->id || (i > 1 && l->v[i - 2].id == p->id))
			continue;    /* only the first two of a run of repeats */
		if (!found || q->src < *b || (q->src == *b && p->src < *a)) {
			*id = p->id;
			*a = p->src;
			*b = q->src;
			found = 1;
		}
	}
	return found;
}

char *
pm_passids_format(const pm_passids *l)
{
	char *s = malloc(l->n ? l->n * (ID_DIGITS + 1) : 1), *p = s;

	if (!s)
		return NULL;
	*s = 0;
	for (size_t i = 0; i < l->n; i++)
		p += sprintf(p, i ? " %016" PRIx64 : "%016" PRIx64, l->v[i].id);
	return s;
}
