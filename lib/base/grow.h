/* grow.h — arrays that grow as needed: scratch reused from call to call. */
#ifndef PM_GROW_H
#define PM_GROW_H

#include <stdlib.h>

/* Room for need more elements of size sz in *p (capacity *cap, n used),
 * doubling; 0 if the allocation failed (*p and *cap unchanged). */
static inline int
pm_grow(void **p, int *cap, int n, int need, size_t sz)
{
	int c = *cap;
	void *q;

	if (n + need <= c)
		return 1;
	while (c < n + need)
		c = c ? 2 * c : 64;
	q = realloc(*p, (size_t)c * sz);
	if (!q)
		return 0;
	*p = q;
	*cap = c;
	return 1;
}

#endif
