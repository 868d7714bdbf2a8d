/* pass.h — pass I of N: the seed and shutter time a pass pair derives from
 * its index, so that any scheduler (a shell loop, xargs, GNU parallel on many
 * hosts, make) can run any subset of passes in any order and get the same
 * images, and both halves of a pair (light pass, view pass) agree.
 *
 * With 1 <= I <= N < 2^32 and splitmix64 the finalizer of rng.h (pm_mix64):
 *   seed = splitmix64(N * 2^32 + I)
 *   u    = (splitmix64(seed) >> 40) / 2^24            (in [0, 1))
 *   time = (float)((I - 1 + u) / N)                   (in [0, 1))
 * so the N passes of a set stratify the shutter interval, one jittered time
 * in each of N equal strata (paper §4: each pass pair takes its own time),
 * and sets of different N (rounds of a progressive run) use different seeds.
 * README.md and the pm-shoot / pm-render man pages restate this. */
#ifndef PM_PASS_H
#define PM_PASS_H

#include <stdint.h>

#include "base/err.h"

/* Parses "I/N" (decimal, 1 <= I <= N <= 2^32 - 1). On failure err says what
 * is wrong (without naming an option). */
int pm_pass_parse(const char *s, uint32_t *i, uint32_t *n, pm_error *err);

/* The seed and time of pass i of n (see above); i and n as pm_pass_parse
 * accepts them. */
void pm_pass_derive(uint32_t i, uint32_t n, uint64_t *seed, float *time);

/* For pass i of n (n = 0: no pass): sets *seed and *time from
 * pm_pass_derive unless the user gave them (*have_seed, *have_time), and
 * marks them given. Both halves of a pair call it, so they agree. */
void pm_pass_apply(uint32_t i, uint32_t n, uint64_t *seed, int *have_seed,
                   float *time, int *have_time);

/* The consistent mode (pm-render --consistent ALPHA, 0 < ALPHA < 1): the
 * scale of pass i's estimate support, i^((ALPHA - 1) / 2), so that its
 * area (radius^2, the cube's face) falls as i^(ALPHA - 1) as in progressive
 * photon mapping (Hachisuka et al. 2008; Knaus & Zwicker 2011, who show
 * that the average of passes 1..N then converges: its bias falls with the
 * support and its variance as N^-ALPHA). A function of i alone: any pass
 * still runs alone, anywhere, and pass 1 is the fixed mode's. */
double pm_pass_shrink(uint32_t i, double alpha);

#endif
