/* rng.h — seeded random numbers that do not depend on thread scheduling.
 *
 * PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient
 * Statistically Good Algorithms for Random Number Generation"), XSH-RR output,
 * 64-bit state, with the stream selected by a 64-bit key. Every unit of work
 * (one photon path, one pixel sample) gets its own generator from
 * pm_rng_seed(seed, key), so the numbers it sees depend only on the seed and its
 * key, never on which thread ran it or in what order. */
#ifndef PM_RNG_H
#define PM_RNG_H

#include <math.h>
#include <stdint.h>

typedef struct { uint64_t state, inc; } pm_rng;

/* splitmix64 finalizer: a bijective 64-bit mix used to derive keys. */
static inline uint64_t pm_mix64(uint64_t z)
{
	z += 0x9e3779b97f4a7c15ull;
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
	return z ^ (z >> 31);
}

static inline uint32_t pm_rng_u32(pm_rng *r)
{
	uint64_t old = r->state;
	r->state = old * 6364136223846793005ull + r->inc;
	uint32_t xs = (uint32_t)(((old >> 18) ^ old) >> 27);
	uint32_t rot = (uint32_t)(old >> 59);
	return (xs >> rot) | (xs << ((-rot) & 31));
}

static inline pm_rng pm_rng_seed(uint64_t seed, uint64_t key)
{
	pm_rng r;
	r.state = 0;
	r.inc = (pm_mix64(seed ^ pm_mix64(key)) << 1) | 1u;
	pm_rng_u32(&r);
	r.state += pm_mix64(key + 0x632be59bd9b4e019ull * (seed + 1));
	pm_rng_u32(&r);
	return r;
}

/* Uniform on 0 .. n - 1 (n > 0), exactly: Lemire's multiply-and-shift,
 * drawing again in the few cases that would favour some values
 * (Lemire 2019, "Fast random integer generation in an interval"). */
static inline uint32_t pm_rng_below(pm_rng *r, uint32_t n)
{
	uint64_t m = (uint64_t)pm_rng_u32(r) * n;
	uint32_t lo = (uint32_t)m;

	if (lo < n) {
		uint32_t t = (0u - n) % n;
		while (lo < t) {
			m = (uint64_t)pm_rng_u32(r) * n;
			lo = (uint32_t)m;
		}
	}
	return (uint32_t)(m >> 32);
}

/* Uniform in [0, 1): 24 random bits, so the result is exactly representable
 * and never rounds up to 1. */
static inline float pm_rng_f(pm_rng *r)
{
	return (float)(pm_rng_u32(r) >> 8) * (1.0f / 16777216.0f);
}

/* Stratified sampling over [0, 1)^2 in n cells: a grid of ga = floor(sqrt n)
 * columns and gb = n / ga rows (any of the n past ga gb are not cells). */
static inline void pm_cells(int n, int *ga, int *gb)
{
	*ga = n > 0 ? (int)sqrtf((float)n) : 1;
	*gb = n / *ga;
}

/* (u, v), uniform in [0, 1)^2, moved into cell c of the ga x gb grid
 * (column c % ga, row c / ga), uniform there; a c past the grid leaves them
 * where they are. */
static inline void pm_cell_point(int c, int ga, int gb, float *u, float *v)
{
	if (c >= 0 && c < ga * gb) {
		*u = fminf(((float)(c % ga) + *u) / (float)ga, 0x1.fffffep-1f);
		*v = fminf(((float)(c / ga) + *v) / (float)gb, 0x1.fffffep-1f);
	}
}

#endif
