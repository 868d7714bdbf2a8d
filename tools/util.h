/* util.h — what every pm program shares: messages, exits, checked number
 * parsing, output checks, threads.
 *
 * Exit codes: 0 success, 1 a failed run, 2 a bad command line. */
#ifndef PM_UTIL_H
#define PM_UTIL_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "base/err.h"

extern const char *argv0;     /* program name, set by util_init */

void util_init(int argc, char **argv);

/* "pm-NAME: message" on stderr and exit 1. */
_Noreturn void die(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
/* die() with a pm_error's message. */
_Noreturn void die_err(const pm_error *err);
/* "pm-NAME: message" plus the usage line, exit 2. */
_Noreturn void usage_err(const char *usage, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* For getopt_long run with opterr = 0 and optstring ":...": the usage error
 * for the option getopt just refused (unknown, or missing its argument),
 * in one line of our own instead of getopt's. Exits 2. */
_Noreturn void bad_option(const char *usage, int opt, char **argv);
void warn(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* Checked parsers: the whole string must be a number within [lo, hi], else
 * usage_err naming the option. Whole numbers may be written in exponent
 * form if their value is exact ("1e6", "2.5e5"; not "1.5" or "1e-3"). */
long long parse_int(const char *s, long long lo, long long hi, const char *opt, const char *usage);
uint64_t parse_u64(const char *s, const char *opt, const char *usage);
double parse_real(const char *s, double lo, double hi, const char *opt, const char *usage);

/* An input to read: stdin for "-", else the file opened for reading, or
 * die with the one "cannot open" message. */
FILE *open_input(const char *name);

/* A file name as messages show it: quoted, or stdin for "-". Returns buf. */
const char *shown_name(const char *name, char *buf, size_t n);

/* What an output file holds, for check_output. */
enum out_kind { OUT_PHOTONS, OUT_EXR, OUT_PNG, OUT_PLY, OUT_TEXT };

/* Refuses, before any work, an output that would hurt (usage_err, exit 2):
 * a name whose extension is another format's (out.png for an EXR, a .exr
 * or .pms for photons; names without a known extension pass), a name
 * that is one of the n inputs (the same file, or the same path when it does
 * not exist yet), and inputs that name stdin (-) more than once. A binary
 * output (photons, EXR, PNG) sent to stdout (-) when that is a terminal
 * dies (exit 1). */
void check_output(const char *usage, const char *out, enum out_kind kind,
                  char *const *inputs, int n);

/* Refuses (usage_err) inputs that name stdin (-) more than once. */
void check_stdin_once(const char *usage, char *const *inputs, int n);

/* Threads: n > 0 as given, 0 for all cores. Sets the OpenMP thread count. */
void set_threads(int n);

#endif
