/* fuzz_exr.c — fuzz target for the EXR reader (pm_image_read_exr in
 * lib/formats/image.c), the path every image tool reads through. Whatever the
 * bytes, it must return 0 or -1 with a one-line message; an image it
 * accepts must be writable and read back with the same size, channels and
 * bits. */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "formats/image.h"

static void
require(int cond, const char *what)
{
	if (!cond) {
		fprintf(stderr, "fuzz_exr: %s\n", what);
		abort();
	}
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	pm_image a, b;
	pm_error err = {""};
	const char *path = fuzz_file("in.exr", data, size);
	char again[8192];

	/* Images up to 2^20 pixels: a header may claim the maximum with a few
	 * bytes, and 2^25 pixels x 256 channels is more than a fuzzer's
	 * memory limit, though no more than a reader allows. */
	setenv("PM_MAX_PIXELS", "1048576", 0);
	if (pm_image_read_exr(&a, path, &err) != 0) {
		require(err.msg[0] && !strchr(err.msg, '\n'), "failure without a one-line message");
		return 0;
	}
	snprintf(again, sizeof again, "%s/again.exr", fuzz_dir());
	if (pm_image_write_exr(&a, again, &err) != 0) {
		/* Attribute names OpenEXR reserves, or one it cannot store,
		 * may be refused on writing: only with a message. */
		require(err.msg[0] && !strchr(err.msg, '\n'), "write failure without a message");
		pm_image_free(&a);
		return 0;
	}
	require(pm_image_read_exr(&b, again, &err) == 0, "a rewritten image is refused");
	require(a.width == b.width && a.height == b.height && a.nchan == b.nchan,
	        "size or channel count changed in a round trip");
	for (int c = 0; c < a.nchan; c++) {
		const float *pa = pm_image_chan(&a, a.chan[c]), *pb = pm_image_chan(&b, a.chan[c]);
		require(pb != NULL, "a channel was lost in a round trip");
		require(memcmp(pa, pb, (size_t)a.width * a.height * sizeof *pa) == 0,
		        "pixels changed in a round trip");
	}
	pm_image_free(&a);
	pm_image_free(&b);
	return 0;
}
