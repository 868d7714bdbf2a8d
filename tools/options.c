/* options.c — option tables to getopt_long, -h and the recorded command
 * (see options.h). */
#define _GNU_SOURCE
#include "options.h"

#include <getopt.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util.h"
#include "base/version.h"

enum { KEY_VERSION = OPT_LONG - 1, MAXOPT = 48 };

/* Every tool's table ends with these two; the tool never sees their keys. */
static const opt builtin[] = {
	{ 'h', "help", NULL, "print this help and exit", NULL, 1 },
	{ KEY_VERSION, "version", NULL, "print the version and exit", NULL, 1 },
};

static char cmdbuf[8192];
static size_t cmdlen;

static const opt *
nth(const tool *t, int i)
{
	int n = 0;

	while (t->opts[n].name)
		n++;
	if (i < n)
		return &t->opts[i];
	i -= n;
	return i < 2 ? &builtin[i] : NULL;
}

static const opt *
find_short(const tool *t, int c)
{
	const opt *o;

	for (int i = 0; (o = nth(t, i)); i++)
		if (o->key == c)
			return o;
	return NULL;
}

/* As getopt_long matches: the exact name, else the one name it begins. */
static const opt *
find_long(const tool *t, const char *s, size_t n)
{
	const opt *o, *hit = NULL;
	int nhit = 0;

	for (int i = 0; (o = nth(t, i)); i++) {
		if (strlen(o->name) == n && !strncmp(o->name, s, n))
			return o;
		if (!strncmp(o->name, s, n))
			hit = o, nhit++;
	}
	return nhit == 1 ? hit : NULL;
}

/* Appends one word of the command, shell-quoted where needed. */
static void
record(const char *a)
{
	char *b = cmdbuf;
	size_t n = cmdlen;
	int plain = *a != 0 && strspn(a, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./=,:+@%") == strlen(a);

	if (n >= sizeof cmdbuf - 8)
		return;
	if (n > 0)
		b[n++] = ' ';
	if (!plain)
		b[n++] = '\'';
	for (; *a && n < sizeof cmdbuf - 8; a++) {
		if (*a == '\n')
			b[n++] = ' ';
		else if (*a == '\'' && n < sizeof cmdbuf - 12) {
			memcpy(b + n, "'\\''", 4);
			n += 4;
		} else
			b[n++] = *a;
	}
	if (!plain)
		b[n++] = '\'';
	b[n] = 0;
	cmdlen = n;
}

/* A short-option word ("-fq", "-j4", "-o", "-qoFILE") without its inert
 * options; sets *next when its last option takes the next word as value
 * (*keep_next: and that value is recorded). */
static void
record_short(const tool *t, const char *a, int *next, int *keep_next)
{
	char *kept = malloc(strlen(a) + 1);
	size_t k = 1;

	if (!kept)
		die("out of memory");
	kept[0] = '-';
	for (const char *p = a + 1; *p; p++) {
		const opt *o = find_short(t, (unsigned char)*p);
		if (o && o->arg) {
			if (!o->inert) {
				strcpy(kept + k, p);
				k += strlen(p);
			}
			*next = p[1] == 0;
			*keep_next = !o->inert;
			break;
		}
		if (!o || !o->inert)
			kept[k++] = *p;
	}
	kept[k] = 0;
	if (k > 1)
		record(kept);
	free(kept);
}

void
opt_init(const tool *t, int argc, char **argv)
{
	util_init(argc, argv);
	record(argv0);
	for (int i = 1; i < argc; i++) {
		const char *a = argv[i];
		int next = 0, keep_next = 1;

		if (a[0] != '-' || a[1] == 0) {
			record(a);
			continue;
		}
		if (!strcmp(a, "--")) {
			/* Operands only from here. */
			while (i < argc)
				record(argv[i++]);
			break;
		}
		if (a[1] == '-') {
			const char *eq = strchr(a, '=');
			const opt *o = find_long(t, a + 2, eq ? (size_t)(eq - a - 2) : strlen(a + 2));
			next = o && o->arg && !eq;
			keep_next = !(o && o->inert);
			if (keep_next)
				record(a);
		} else {
			record_short(t, a, &next, &keep_next);
		}
		if (next && i + 1 < argc) {
			i++;
			if (keep_next)
				record(argv[i]);
		}
	}
}

const char *
cmdline(void)
{
	return cmdbuf;
}

/* "  -n, --photons N" as -h shows it; returns its length. */
static int
left_column(const opt *o, char *buf, size_t n)
{
	if (o->key < OPT_LONG && o->key != KEY_VERSION)
		return snprintf(buf, n, "  -%c, --%s%s%s", o->key, o->name, o->arg ? " " : "", o->arg ? o->arg : "");
	return snprintf(buf, n, "      --%s%s%s", o->name, o->arg ? " " : "", o->arg ? o->arg : "");
}

/* Prints the words of s from column col, wrapped before column 80 to
 * lines indented to indent; returns the column it ends in. */
static int
wrap(const char *s, int col, int indent)
{
	while (*s) {
		size_t n = strcspn(s, " \n");
		if (n > 0 && col > indent && col + 1 + (int)n > 79)
			col = printf("\n%*s", indent, "") - 1;
		else if (n > 0 && col > indent)
			col += printf(" ");
		col += printf("%.*s", (int)n, s);
		s += n;
		s += strspn(s, " \n");
	}
	return col;
}

_Noreturn static void
help(const tool *t)
{
	char left[128], def[160];
	const opt *o;
	int w = 0;

	for (int i = 0; (o = nth(t, i)); i++) {
		int n = left_column(o, left, sizeof left);
		if (n > w)
			w = n;
	}
	printf("usage: %s\n%s\n", t->usage, t->about);
	for (int i = 0; (o = nth(t, i)); i++) {
		left_column(o, left, sizeof left);
		int col = printf("%-*s  ", w, left);
		col = wrap(o->help, col, w + 2);
		if (o->def) {
			snprintf(def, sizeof def, "(default %s)", o->def);
			wrap(def, col, w + 2);
		}
		putchar('\n');
	}
	if (t->notes)
		fputs(t->notes, stdout);
	exit(0);
}

int
opt_next(const tool *t, int argc, char **argv)
{
	static struct option lopts[MAXOPT + 1];
	static char optstring[2 * MAXOPT + 2];
	static const tool *built;
	const opt *o;
	int c;

	if (built != t) {
		size_t k = 0, n = 0;
		optstring[k++] = ':';
		for (int i = 0; (o = nth(t, i)) && n < MAXOPT; i++, n++) {
			lopts[n] = (struct option){ o->name, o->arg ? required_argument : no_argument, NULL, o->key };
			if (o->key < OPT_LONG && o->key != KEY_VERSION) {
				optstring[k++] = (char)o->key;
				if (o->arg)
					optstring[k++] = ':';
			}
		}
		lopts[n] = (struct option){ 0, 0, 0, 0 };
		optstring[k] = 0;
		built = t;
		opterr = 0;
	}
	c = getopt_long(argc, argv, optstring, lopts, NULL);
	if (c == 'h')
		help(t);
	if (c == KEY_VERSION) {
		printf("%s %s\n", argv0, PM_VERSION);
		exit(0);
	}
	if (c == '?' || c == ':')
		bad_option(t->usage, c, argv);
	return c;
}
