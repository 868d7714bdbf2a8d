/* ldseq.c — hash-scrambled Sobol' pairs (see ldseq.h). */
#include "base/ldseq.h"

#include "base/rng.h"

static uint32_t
reverse(uint32_t x)
{
	x = (x << 16) | (x >> 16);
	x = ((x & 0x00ff00ffu) << 8) | ((x >> 8) & 0x00ff00ffu);
	x = ((x & 0x0f0f0f0fu) << 4) | ((x >> 4) & 0x0f0f0f0fu);
	x = ((x & 0x33333333u) << 2) | ((x >> 2) & 0x33333333u);
	return ((x & 0x55555555u) << 1) | ((x >> 1) & 0x55555555u);
}

/* Sobol's second dimension: the generator matrix of the primitive
 * polynomial x + 1, whose direction numbers follow v_k = v_{k-1} ^
 * (v_{k-1} >> 1) from v_0 = 2^31 (the first dimension is the bit reversal). */
static uint32_t
sobol1(uint32_t i)
{
	uint32_t v = 1u << 31, r = 0;

	for (; i; i >>= 1, v ^= v >> 1)
		if (i & 1)
			r ^= v;
	return r;
}

/* Nested uniform (Owen) scrambling of a 32-bit binary fraction: each bit is
 * flipped by a hash of the bits above it. In the reversed order the hash
 * need only let every bit depend on the lower ones, as Laine and Karras's
 * multiplications do; constants are Burley's. */
static uint32_t
owen(uint32_t x, uint32_t seed)
{
	x = reverse(x);
	x += seed;
	x ^= x * 0x6c50b47cu;
	x ^= x * 0xb82f1e52u;
	x ^= x * 0xc7afe638u;
	x ^= x * 0x8d22f6e6u;
	return reverse(x);
}

static float
unit(uint32_t x)
{
	return (float)(x >> 8) * (1.0f / 16777216.0f);
}

void
pm_ld_pair(uint64_t seed, uint32_t pair, uint64_t index, float *u0, float *u1)
{
	/* Beyond 2^32 points a block of them gets scrambles of its own. */
	uint64_t h = pm_mix64(seed ^ pm_mix64(((uint64_t)pair << 32) ^ (index >> 32)));
	uint64_t h2 = pm_mix64(h);
	/* Shuffling the index by an Owen scramble of its own keeps every
	 * prefix of 2^m points a net, and decorrelates the pairs. */
	uint32_t i = owen((uint32_t)index, (uint32_t)h);

	*u0 = unit(owen(reverse(i), (uint32_t)(h >> 32)));
	*u1 = unit(owen(sobol1(i), (uint32_t)h2));
}
