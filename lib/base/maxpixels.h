/* maxpixels.h — the largest image pm accepts, width x height: a scene's
 * camera size (scene.h) and an image a reader trusts before allocating
 * (image.h), so that a typo in `size` (65535 65535) or a corrupt header
 * fails at once instead of allocating tens of gigabytes.
 *
 * PM_MAX_PIXELS (2^25 = 33554432, room for 8K UHD), unless the environment
 * variable PM_MAX_PIXELS holds a whole number >= 1 (which may raise or lower
 * it); a malformed value keeps the default rather than lifting it. */
#ifndef PM_MAXPIXELS_H
#define PM_MAXPIXELS_H

#include <errno.h>
#include <stdint.h>
#include <stdlib.h>

#define PM_MAX_PIXELS (1ull << 25)

static inline uint64_t
pm_max_pixels(void)
{
	const char *e = getenv("PM_MAX_PIXELS");
	char *end;
	unsigned long long v;

	if (!e || !*e)
		return PM_MAX_PIXELS;
	errno = 0;
	v = strtoull(e, &end, 10);
	if (errno || *end || e[0] == '-' || v < 1)
		return PM_MAX_PIXELS;
	return v;
}

#endif
