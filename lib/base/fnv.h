/* fnv.h — FNV-1a, 64-bit (Fowler, Noll, Vo): the hash behind a scene's
 * identity (formats/scene.md) and a pass's (formats/image.md). */
#ifndef PM_FNV_H
#define PM_FNV_H

#include <stddef.h>
#include <stdint.h>

#define PM_FNV_OFFSET 14695981039346656037ull
#define PM_FNV_PRIME 1099511628211ull

/* Continues hash h over n bytes at b; start from PM_FNV_OFFSET. */
static inline uint64_t
pm_fnv1a(uint64_t h, const void *b, size_t n)
{
	const unsigned char *p = b;

	for (size_t i = 0; i < n; i++) {
		h ^= p[i];
		h *= PM_FNV_PRIME;
	}
	return h;
}

#endif
