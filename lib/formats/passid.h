/* passid.h — a pass's identity, so that pm-average can tell two renders of
 * the same random sample from two samples (formats/image.md, "Pass ids").
 *
 * A pass id is FNV-1a 64 (fnv.h) of the text
 *     SCENE_HASH " " ESTIMATOR " " SEED " " TIME " " MAP_SEEDS
 * with SCENE_HASH as 16 lowercase hex digits, ESTIMATOR its name, SEED the
 * view seed in decimal, TIME the shutter time as "%.9g" (the text of
 * pm.scene_hash, pm.estimator, pm.seed and pm.time) and MAP_SEEDS the photon
 * map's `seeds` header value (empty without a map). Two passes with the same
 * id drew the same random numbers: averaging them adds no information. An
 * image lists its passes' ids in pm.pass_ids, 16 lowercase hex digits each,
 * sorted, separated by single spaces. */
#ifndef PM_PASSID_H
#define PM_PASSID_H

#include <stddef.h>
#include <stdint.h>

#include "base/err.h"

uint64_t pm_pass_id(uint64_t scene_hash, const char *estimator, uint64_t seed,
                    float time, const char *map_seeds);

/* Pass ids gathered from several images; src says which image (its index
 * in the caller's input list). */
typedef struct pm_passid {
	uint64_t id;
	int src;
} pm_passid;

typedef struct pm_passids {
	pm_passid *v;
	size_t n, cap;
} pm_passids;

/* Zeroes l (no allocation). */
void pm_passids_init(pm_passids *l);
void pm_passids_free(pm_passids *l);

/* Appends the ids of a pm.pass_ids value, tagged src, and sets *added to
 * their number. Any text but ids of 16 lowercase hex digits separated by
 * single spaces fails, leaving l as it was. */
int pm_passids_add(pm_passids *l, const char *text, int src, size_t *added, pm_error *err);

/* Sorts l by id (then src) and looks for an id held twice. Returns 1 and
 * sets *id, *a <= *b (the two srcs, equal if one image holds it twice) for
 * the repeat whose later image comes first, then whose earlier one does;
 * returns 0 if every id is distinct. */
int pm_passids_dup(pm_passids *l, uint64_t *id, int *a, int *b);

/* The ids of l (sorted by pm_passids_dup) as a pm.pass_ids value, or NULL
 * if out of memory; the caller frees it. */
char *pm_passids_format(const pm_passids *l);

#endif
