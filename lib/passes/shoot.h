/* shoot.h — the light pass (paper §2): photons from the lights, traced with
 * Russian roulette, stored at every diffuse or soft-glossy hit after the
 * first bounce (direct light comes from shadow rays in the view pass).
 *
 * Light path i draws its random numbers from pm_rng_seed(seed', i) only, and
 * paths are kept in index order, so the photons are a function of the scene,
 * time, seed and count, never of the thread count.
 *
 * With PM_PATHS_SOBOL path i takes its numbers from point i of scrambled
 * Sobol' pairs (ldseq.h) instead: (light, side), emission point, emission
 * direction, then per bounce (direction) and (lobe, Russian roulette). The
 * scrambles come from the seed, which -P derives from the pass index, so a
 * pass's paths are one randomized low-discrepancy set and the passes are
 * independent of each other, as pseudo-random ones are: their average and
 * its spread (pm-average's error estimate) stay what they mean. */
#ifndef PM_SHOOT_H
#define PM_SHOOT_H

#include <stdint.h>

#include "scene/accel.h"
#include "base/err.h"
#include "optics/light.h"
#include "formats/photonfile.h"
#include "base/progress.h"
#include "scene/scene.h"

enum pm_light_paths { PM_PATHS_RANDOM, PM_PATHS_SOBOL };

/* "random" or "sobol" (the photon file's light_paths key), and back: -1 if
 * the name is unknown. */
const char *pm_light_paths_name(int lp);
int pm_light_paths_parse(const char *name);

typedef struct pm_shoot_opts {
	uint64_t nphotons;  /* photons to store */
	int light_paths;    /* enum pm_light_paths */
	uint64_t seed;
	float time;         /* shutter time the accel and lights were built at */
	int max_bounces;    /* hard cap on a path's length; 0 means 256 */
	uint64_t max_paths; /* give up after this many paths; 0 means 64 n + 2^20 */
	pm_progress_fn *progress;  /* if set, called with (photons stored, n) */
	void *progress_arg;
	pm_photons *caustic; /* if set, also receives the caustic map
	                      * (photonfile.h, PM_MAP_CAUSTIC) */
	uint64_t ncaustic;   /* caustic photons to store; 0: those of the global
	                      * map's light paths */
	pm_photons *guide;   /* if set, also receives the guide map
	                      * (photonfile.h, PM_MAP_GUIDE) of the global
	                      * map's light paths, with their emitted count */
} pm_shoot_opts;

/* Fills out (photons, header: count, emitted, light_hash, time, seed; the
 * bbox is left 0: pm_photons_write computes it from the records).
 * Stops after the path that stores the n-th photon; the photons it would
 * have stored later are dropped and every path begun is counted as emitted.
 * If max_paths is reached first the file holds fewer photons; that is not
 * an error (some scenes store few photons) and shows as count < n.
 * o->caustic, if set, gets the L S+ D photons the paths stored: with
 * ncaustic 0 those of the global map's paths (the n-th photon's path
 * included), with the same emitted count, so they are copies of photons of
 * the global map, which keeps them too (final gathering reads them there at
 * second bounces); else paths go on, numbered on from the same sequence,
 * until ncaustic of them are stored (same rule as for n, max_paths bounding
 * both), and the caustic map counts its own emitted paths. A scene without
 * mirror, glass or strong glossy materials gives an empty caustic map at
 * once. */
int pm_shoot(const pm_scene *s, const pm_accel *a, const pm_lights *L,
             const pm_shoot_opts *o, pm_photons *out, pm_error *err);

#endif
