/* util.c — shared by every pm program (see util.h). */
#define _GNU_SOURCE
#include "util.h"

#include <errno.h>
#include <math.h>
#include <omp.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

const char *argv0 = "pm";
static char cmdbuf[8192];

void
util_init(int argc, char **argv)
{
	const char *slash = strrchr(argv[0], '/');
	size_t n = 0;

	argv0 = slash ? slash + 1 : argv[0];
	for (int i = 0; i < argc && n < sizeof cmdbuf - 8; i++) {
		const char *a = i == 0 ? argv0 : argv[i];
		int plain;

		/* The thread count and quietness do not change what a program
		 * writes, so they are left out of the recorded command: outputs
		 * stay byte-identical whatever -j says. */
		if (i > 0 && (!strcmp(a, "-q") || !strncmp(a, "-j", 2))) {
			i += !strcmp(a, "-j");
			continue;
		}
		plain = *a != 0 && strspn(a, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./=,:+@%") == strlen(a);
		if (i > 0)
			cmdbuf[n++] = ' ';
		if (!plain)
			cmdbuf[n++] = '\'';
		for (; *a && n < sizeof cmdbuf - 8; a++) {
			if (*a == '\n')
				cmdbuf[n++] = ' ';
			else if (*a == '\'' && n < sizeof cmdbuf - 12) {
				memcpy(cmdbuf + n, "'\\''", 4);
				n += 4;
			} else
				cmdbuf[n++] = *a;
		}
		if (!plain)
			cmdbuf[n++] = '\'';
	}
	cmdbuf[n] = 0;
}

static void
vmsg(const char *fmt, va_list ap)
{
	fprintf(stderr, "%s: ", argv0);
	vfprintf(stderr, fmt, ap);
	fputc('\n', stderr);
}

void
die(const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	vmsg(fmt, ap);
	va_end(ap);
	exit(1);
}

void
die_err(const pm_error *err)
{
	die("%s", err->msg);
}

void
warn(const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	vmsg(fmt, ap);
	va_end(ap);
}

void
usage_err(const char *usage, const char *fmt, ...)
{
	va_list ap;

	va_start(ap, fmt);
	vmsg(fmt, ap);
	va_end(ap);
	fprintf(stderr, "usage: %s\n", usage);
	exit(2);
}

long long
parse_int(const char *s, long long lo, long long hi, const char *opt, const char *usage)
{
	char *end;
	long long v;

	errno = 0;
	v = strtoll(s, &end, 10);
	if (errno || end == s || *end)
		usage_err(usage, "%s: '%s' is not a whole number", opt, s);
	if (v < lo || v > hi)
		usage_err(usage, "%s: %s is out of range [%lld, %lld]", opt, s, lo, hi);
	return v;
}

uint64_t
parse_u64(const char *s, const char *opt, const char *usage)
{
	char *end;
	unsigned long long v;

	errno = 0;
	if (*s == '-')
		usage_err(usage, "%s: '%s' must not be negative", opt, s);
	v = strtoull(s, &end, 10);
	if (errno || end == s || *end)
		usage_err(usage, "%s: '%s' is not a whole number below 2^64", opt, s);
	return v;
}

double
parse_real(const char *s, double lo, double hi, const char *opt, const char *usage)
{
	char *end;
	double v;

	errno = 0;
	v = strtod(s, &end);
	if (errno || end == s || *end || !isfinite(v))
		usage_err(usage, "%s: '%s' is not a number", opt, s);
	if (v < lo || v > hi)
		usage_err(usage, "%s: %s is out of range [%g, %g]", opt, s, lo, hi);
	return v;
}

const char *
cmdline(void)
{
	return cmdbuf;
}

void
set_threads(int n)
{
	omp_set_num_threads(n > 0 ? n : omp_get_num_procs());
}
