/* fuzz_photons.c — fuzz target for the photon file and photon map reader
 * (lib/formats/photonfile.c, formats/photons.md). Whatever the bytes, the reader must
 * return 0 or -1 with a message; a file it accepts must survive a write and
 * a second read unchanged (same header fields, same records). */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz.h"
#include "formats/photonfile.h"

static FILE *
open_input(const uint8_t *data, size_t size)
{
	/* glibc's fmemopen refuses a zero-length buffer. */
	return size ? fmemopen((void *)data, size, "rb") : fopen("/dev/null", "rb");
}

static void
require(int cond, const char *what)
{
	if (!cond) {
		fprintf(stderr, "fuzz_photons: %s\n", what);
		abort();
	}
}

int
LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
	pm_photons a, b;
	pm_error err = {""};
	char *raw = NULL, *out = NULL;
	size_t outlen = 0;
	FILE *f;

	/* The header half alone, as pm-dump --header uses it. */
	f = open_input(data, size);
	require(f != NULL, "cannot open the input");
	if (pm_photons_read_header(&a, f, "fuzz.pm", &raw, &err) == 0) {
		require(raw != NULL && strncmp(raw, "PM-PHOTONS\n", 11) == 0, "raw header lost its magic");
		pm_photons_free(&a);
		free(raw);
	} else {
		require(err.msg[0] && !strchr(err.msg, '\n'), "failure without a one-line message");
	}
	fclose(f);

	f = open_input(data, size);
	require(f != NULL, "cannot open the input");
	if (pm_photons_read(&a, f, "fuzz.pm", &err) != 0) {
		require(err.msg[0] && !strchr(err.msg, '\n'), "failure without a one-line message");
		fclose(f);
		return 0;
	}
	fclose(f);

	f = open_memstream(&out, &outlen);
	require(f != NULL, "open_memstream");
	require(pm_photons_write(&a, f, "fuzz.pm", &err) == 0, "an accepted file cannot be written");
	require(fclose(f) == 0, "memstream close");
	f = fmemopen(out, outlen, "rb");
	require(f != NULL, "fmemopen of the rewrite");
	require(pm_photons_read(&b, f, "again.pm", &err) == 0, "a rewritten file is refused");
	fclose(f);
	require(a.h.count == b.h.count && a.h.emitted == b.h.emitted &&
	        a.h.kdtree == b.h.kdtree && a.h.light_hash == b.h.light_hash &&
	        memcmp(&a.h.time, &b.h.time, sizeof a.h.time) == 0 &&
	        strcmp(a.h.seeds, b.h.seeds) == 0, "header changed in a round trip");
	require(!a.h.history == !b.h.history &&
	        (!a.h.history || strcmp(a.h.history, b.h.history) == 0), "history changed in a round trip");
	require(a.h.count == 0 || memcmp(a.p, b.p, (size_t)a.h.count * sizeof *a.p) == 0,
	        "records changed in a round trip");
	pm_photons_free(&a);
	pm_photons_free(&b);
	free(out);
	return 0;
}
