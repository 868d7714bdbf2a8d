/* timing.h — what every benchmark program measures time with: a monotonic
 * clock and the median of repeated runs. Header-only. */
#ifndef PM_BENCH_TIMING_H
#define PM_BENCH_TIMING_H

#include <stdlib.h>
#include <time.h>

static inline double
now(void)
{
	struct timespec t;
	clock_gettime(CLOCK_MONOTONIC, &t);
	return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static inline int
cmpd(const void *a, const void *b)
{
	double x = *(const double *)a, y = *(const double *)b;
	return x < y ? -1 : x > y;
}

static inline double
median(double *v, int n)
{
	qsort(v, (size_t)n, sizeof *v, cmpd);
	return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

#endif
