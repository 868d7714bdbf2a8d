/* fuzz.h — what the fuzz targets share: the libFuzzer entry point they each
 * define, and a private scratch directory for readers that want a path.
 *
 * Each target file defines LLVMFuzzerTestOneInput for one reader. Built with
 * clang -fsanitize=fuzzer it is a libFuzzer binary (make fuzz); linked with
 * replay.c instead it runs given files once each (make check replays the
 * corpus and every regression input that way, without clang). */
#ifndef PM_FUZZ_H
#define PM_FUZZ_H

#include <stddef.h>
#include <stdint.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* A directory of this process's own, created on first use (under $TMPDIR or
 * /tmp) and removed at exit. */
const char *fuzz_dir(void);
/* Writes data to DIR/name, replacing it; aborts if that fails (the target
 * cannot test anything then). Returns the path (static storage per call). */
const char *fuzz_file(const char *name, const uint8_t *data, size_t size);

#endif
