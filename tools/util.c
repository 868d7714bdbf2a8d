/* util.c — shared by every pm program (see util.h). */
#define _GNU_SOURCE
#include "util.h"

#include <dirent.h>
#include <errno.h>
#include <getopt.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <omp.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include "base/atomic.h"

const char *argv0 = "pm";

/* On SIGINT, SIGTERM or SIGHUP: removes the named temporary files this
 * process has open (lib/base/atomic.h: their names hold PM_TMP_MARK), then dies
 * of the same signal. It finds them through /proc/self/fd with raw system
 * calls only, all async-signal-safe, so it needs no record of pm_out
 * objects. An O_TMPFILE output has no name and vanishes by itself. */
static void
on_signal(int sig)
{
	char buf[4096], link[64], target[4096];
	int dfd = open("/proc/self/fd", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
	long n;

	while (dfd >= 0 && (n = syscall(SYS_getdents64, dfd, buf, sizeof buf)) > 0) {
		for (long off = 0; off < n;) {
			struct dirent64 *d = (struct dirent64 *)(buf + off);
			ssize_t len;
			off += d->d_reclen;
			if (d->d_name[0] < '0' || d->d_name[0] > '9')
				continue;
			/* "/proc/self/fd/" + name, without snprintf */
			size_t k = 0;
			for (const char *s = "/proc/self/fd/"; *s; s++)
				link[k++] = *s;
			for (const char *s = d->d_name; *s && k < sizeof link - 1; s++)
				link[k++] = *s;
			link[k] = 0;
			len = readlink(link, target, sizeof target - 1);
			if (len <= 0)
				continue;
			target[len] = 0;
			const char *base = strrchr(target, '/');
			if (base && base[1] == '.' && strstr(base, PM_TMP_MARK) && !strstr(base, " (deleted)"))
				unlink(target);
		}
	}
	if (dfd >= 0)
		close(dfd);
	signal(sig, SIG_DFL);
	raise(sig);
}

/* Set by die and usage_err: their message is the one to show. */
static int failing;

/* At exit: closing stdout is part of success (a full disk must not pass
 * silently, whatever wrote there: help text, statistics, a stream). */
static void
close_stdout(void)
{
	int bad = fflush(stdout) != 0 || ferror(stdout);
	int e = errno;

	if (fclose(stdout) != 0 && !bad) {
		bad = 1;
		e = errno;
	}
	if (bad && !failing) {
		fprintf(stderr, "%s: cannot write stdout: %s\n", argv0, strerror(e ? e : EIO));
		_exit(1);
	}
}

void
util_init(int argc, char **argv)
{
	static const int sigs[] = { SIGINT, SIGTERM, SIGHUP };

	atexit(close_stdout);

	for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
		struct sigaction sa;
		memset(&sa, 0, sizeof sa);
		sa.sa_handler = on_signal;
		sigemptyset(&sa.sa_mask);
		/* Left alone when ignored (nohup, a shell's background job). */
		struct sigaction old;
		if (sigaction(sigs[i], NULL, &old) == 0 && old.sa_handler != SIG_IGN)
			sigaction(sigs[i], &sa, NULL);
	}

	const char *slash = strrchr(argv[0], '/');

	argv0 = slash ? slash + 1 : argv[0];
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

	failing = 1;
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
	failing = 1;
	exit(2);
}

void
bad_option(const char *usage, int opt, char **argv)
{
	const char *word = argv[optind - 1];
	/* getopt has moved past a long option's word, and past a short one's
	 * only when its value is missing; an unknown letter may sit inside a
	 * cluster ("-qx"), so it is named by itself. */
	int islong = !strncmp(word, "--", 2) && (opt == ':' || !optopt || strchr(word, '='));
	size_t n = islong ? strcspn(word, "=") : 2;
	char shortname[3] = { '-', (char)optopt, 0 };

	if (!islong)
		word = shortname;
	if (opt == ':')
		usage_err(usage, "option '%.*s' needs a value", (int)n, word);
	if (optopt && islong)
		usage_err(usage, "option '%.*s' takes no value", (int)n, word);
	usage_err(usage, "unknown option '%.*s'", (int)n, word);
}

/* A whole number in decimal, also in exponent form ("1e6", "2.5e5"), read
 * exactly: *mag gets its magnitude, *neg its sign. Returns 0, or -1 if s is
 * no decimal number, -2 if it has a fraction ("1.5", "1e-3"), -3 if its
 * magnitude is 2^64 or more. */
static int
read_whole(const char *s, int *neg, unsigned long long *mag)
{
	const char *p = s, *first;
	long ndig = 0, nfrac = 0, e = 0, shift;
	int point = 0, eneg = 0;
	unsigned long long v = 0;

	*neg = *p == '-';
	if (*p == '+' || *p == '-')
		p++;
	for (first = p; (*p >= '0' && *p <= '9') || (*p == '.' && !point); p++) {
		if (*p == '.')
			point = 1;
		else
			ndig++, nfrac += point;
	}
	if (ndig == 0)
		return -1;
	if (*p == 'e' || *p == 'E') {
		p++;
		eneg = *p == '-';
		if (*p == '+' || *p == '-')
			p++;
		if (!(*p >= '0' && *p <= '9'))
			return -1;
		for (; *p >= '0' && *p <= '9'; p++)
			if (e < 100000)   /* beyond any 64-bit number either way */
				e = e * 10 + (*p - '0');
	}
	if (*p)
		return -1;
	/* The value is the digits as one integer times 10^shift. */
	shift = (eneg ? -e : e) - nfrac;
	long i = 0;
	for (p = first; i < ndig; p++) {
		if (*p == '.')
			continue;
		unsigned d = (unsigned)(*p - '0');
		if (shift < 0 && i >= ndig + shift) {
			if (d)
				return -2;
		} else if (v > (ULLONG_MAX - d) / 10) {
			return -3;
		} else {
			v = v * 10 + d;
		}
		i++;
	}
	for (; shift > 0 && v; shift--) {
		if (v > ULLONG_MAX / 10)
			return -3;
		v *= 10;
	}
	*mag = v;
	return 0;
}

long long
parse_int(const char *s, long long lo, long long hi, const char *opt, const char *usage)
{
	unsigned long long m;
	int neg, r = read_whole(s, &neg, &m);

	if (r == -1 || r == -2)
		usage_err(usage, "%s: '%s' is not a whole number", opt, s);
	if (r == -3 || m > (neg ? (unsigned long long)LLONG_MAX + 1 : (unsigned long long)LLONG_MAX))
		usage_err(usage, "%s: %s is out of range [%lld, %lld]", opt, s, lo, hi);
	long long v = neg ? (long long)(0 - m) : (long long)m;
	if (v < lo || v > hi)
		usage_err(usage, "%s: %s is out of range [%lld, %lld]", opt, s, lo, hi);
	return v;
}

uint64_t
parse_u64(const char *s, const char *opt, const char *usage)
{
	unsigned long long m;
	int neg, r;

	if (*s == '-')
		usage_err(usage, "%s: '%s' must not be negative", opt, s);
	r = read_whole(s, &neg, &m);
	if (r)
		usage_err(usage, "%s: '%s' is not a whole number below 2^64", opt, s);
	return m;
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

FILE *
open_input(const char *name)
{
	FILE *f = strcmp(name, "-") == 0 ? stdin : fopen(name, "rb");

	if (!f)
		die("cannot open '%s': %s", name, strerror(errno));
	return f;
}

const char *
shown_name(const char *name, char *buf, size_t n)
{
	if (strcmp(name, "-") == 0)
		snprintf(buf, n, "stdin");
	else
		snprintf(buf, n, "'%s'", name);
	return buf;
}

/* File name extensions pm knows, and what they hold. Kinds past OUT_TEXT
 * are never written by pm: an output named so is always refused. */
enum { IN_SCENE = OUT_TEXT + 1, IN_MESH, IN_IMAGE };
static const struct {
	const char *ext;
	int kind;
} known_ext[] = {
	{ "pm", OUT_PHOTONS }, { "exr", OUT_EXR }, { "png", OUT_PNG }, { "ply", OUT_PLY },
	{ "txt", OUT_TEXT }, { "tsv", OUT_TEXT }, { "pms", IN_SCENE }, { "obj", IN_MESH },
	{ "off", IN_MESH }, { "stl", IN_MESH }, { "jpg", IN_IMAGE }, { "jpeg", IN_IMAGE },
	{ "hdr", IN_IMAGE }, { "tif", IN_IMAGE }, { "tiff", IN_IMAGE }, { "ppm", IN_IMAGE },
	{ "pfm", IN_IMAGE },
};
static const char *const kind_name[] = {
	"a photon file", "an OpenEXR image", "a PNG image", "a PLY point cloud", "text",
	"a scene", "a mesh", "an image format pm does not write",
};
static const char *const kind_ext[] = { ".pm", ".exr", ".png", ".ply", ".txt" };

void
check_stdin_once(const char *usage, char *const *inputs, int n)
{
	int nstdin = 0;

	for (int i = 0; i < n; i++)
		if (strcmp(inputs[i], "-") == 0 && nstdin++)
			usage_err(usage, "stdin (-) given as input more than once (it can be read once)");
}

void
check_output(const char *usage, const char *out, enum out_kind kind, char *const *inputs, int n)
{
	const char *dot = strrchr(out, '.'), *slash = strrchr(out, '/');
	struct stat so, si;
	int have_out;

	check_stdin_once(usage, inputs, n);
	if (strcmp(out, "-") == 0) {
		/* PLY is written as text. */
		if (kind != OUT_TEXT && kind != OUT_PLY && isatty(STDOUT_FILENO))
			die("refusing to write %s to a terminal: use -o FILE or a pipe", kind_name[kind]);
		return;
	}
	if (dot && (!slash || dot > slash + 1))
		for (size_t e = 0; e < sizeof known_ext / sizeof known_ext[0]; e++)
			if (strcasecmp(dot + 1, known_ext[e].ext) == 0 && known_ext[e].kind != (int)kind)
				usage_err(usage, "'%s' names %s, but %s writes %s: name it %s", out,
				          kind_name[known_ext[e].kind], argv0, kind_name[kind], kind_ext[kind]);
	have_out = stat(out, &so) == 0;
	for (int i = 0; i < n; i++) {
		/* stdin counts too when it is the output file redirected. */
		int in = strcmp(inputs[i], "-") == 0;
		if (have_out ? (in ? fstat(STDIN_FILENO, &si) : stat(inputs[i], &si)) == 0 &&
		               S_ISREG(si.st_mode) && si.st_dev == so.st_dev && si.st_ino == so.st_ino
		             : !in && strcmp(inputs[i], out) == 0)
			usage_err(usage, "'%s' is also an input%s: writing it would destroy it (choose another output)",
			          out, in ? " (as stdin)" : "");
	}
}

void
set_threads(int n)
{
	omp_set_num_threads(n > 0 ? n : omp_get_num_procs());
}
