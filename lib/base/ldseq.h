/* ldseq.h — scrambled low-discrepancy samples for light paths (pm-shoot
 * --light-paths sobol): the first two dimensions of Sobol's sequence, which
 * need no tables, Owen-scrambled by hashing and padded pair by pair with
 * independent scrambles (Burley 2020, "Practical Hash-based Owen
 * Scrambling", JCGT 9(4); Laine & Karras 2011 for the hash's form). Each
 * pair of a path's dimensions (emission position, emission direction, one
 * bounce's direction) is then a (0, 2)-sequence over the path indices:
 * the first 2^m paths of a pass stratify every such pair into 2^m cells.
 *
 * A sample is a function of (seed, pair, index) alone: no state, no
 * dependence on threads. Different seeds give independent scrambles, which
 * is what keeps passes independent (see shoot.h). */
#ifndef PM_LDSEQ_H
#define PM_LDSEQ_H

#include <stdint.h>

/* The two coordinates, in [0, 1) with 24 bits as pm_rng_f's, of point
 * index of the scrambled sequence of pair `pair` under seed. */
void pm_ld_pair(uint64_t seed, uint32_t pair, uint64_t index, float *u0, float *u1);

#endif
