/* splitmix.h — the random numbers of the scene generators (genscene,
 * genextreme): splitmix64 over one global state, so that a seed gives the
 * same scene on every machine. */
#ifndef PM_TESTS_SPLITMIX_H
#define PM_TESTS_SPLITMIX_H

#include <stdint.h>

static uint64_t rng_state;

static uint64_t
next64(void)
{
	uint64_t z = (rng_state += 0x9e3779b97f4a7c15ull);
	z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
	z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
	return z ^ (z >> 31);
}

/* Uniform in [0, 1), 53 bits. */
static double unif(void) { return (double)(next64() >> 11) * 0x1.0p-53; }

#endif
