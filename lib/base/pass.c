/* pass.c — pass index to seed and time (see pass.h). */
#include "base/pass.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/rng.h"

static int
whole(const char *s, const char *end, unsigned long long *v)
{
	char *e;

	if (s == end || *s < '0' || *s > '9')
		return -1;
	errno = 0;
	*v = strtoull(s, &e, 10);
	return errno || e != end ? -1 : 0;
}

int
pm_pass_parse(const char *s, uint32_t *i, uint32_t *n, pm_error *err)
{
	const char *slash = s;
	unsigned long long a, b;

	while (*slash && *slash != '/')
		slash++;
	if (!*slash)
		return pm_seterr(err, "'%s' is not I/N (pass I of N)", s);
	if (whole(s, slash, &a) != 0 || whole(slash + 1, slash + 1 + strlen(slash + 1), &b) != 0)
		return pm_seterr(err, "'%s' is not I/N with whole numbers I and N", s);
	if (b < 1 || b > UINT32_MAX)
		return pm_seterr(err, "'%s': N must be in [1, %u]", s, UINT32_MAX);
	if (a < 1 || a > b)
		return pm_seterr(err, "'%s': I must be in [1, N]", s);
	*i = (uint32_t)a;
	*n = (uint32_t)b;
	return 0;
}

void
pm_pass_derive(uint32_t i, uint32_t n, uint64_t *seed, float *time)
{
	uint64_t h = pm_mix64(((uint64_t)n << 32) | i);
	double u = (double)(pm_mix64(h) >> 40) / 16777216.0;
	float t = (float)(((double)i - 1.0 + u) / (double)n);

	/* Rounding to float may reach the stratum's top; 1 is still a time. */
	*seed = h;
	*time = t > 1.0f ? 1.0f : t;
}

double
pm_pass_shrink(uint32_t i, double alpha)
{
	return i <= 1 ? 1.0 : pow((double)i, 0.5 * (alpha - 1.0));
}

void
pm_pass_apply(uint32_t i, uint32_t n, uint64_t *seed, int *have_seed,
              float *time, int *have_time)
{
	uint64_t ps;
	float pt;

	if (n == 0)
		return;
	pm_pass_derive(i, n, &ps, &pt);
	if (!*have_seed)
		*seed = ps;
	if (!*have_time)
		*time = pt;
	*have_seed = *have_time = 1;
}
