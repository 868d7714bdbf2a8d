/* replay.c — runs fuzz inputs through a target without libFuzzer: each
 * argument is a file, or a directory whose files are run in name order.
 * Prints "ok - TARGET: FILE" per input that returns normally; a crash or a
 * sanitizer report ends the process, which the test notices.
 * Usage: replay-TARGET FILE|DIR... */
#define _GNU_SOURCE
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fuzz.h"

static int
run_file(const char *target, const char *path)
{
	FILE *f = fopen(path, "rb");
	unsigned char *buf = NULL;
	size_t n = 0, cap = 0;

	if (!f) {
		printf("not ok - %s: cannot open %s\n", target, path);
		return 1;
	}
	for (;;) {
		if (n == cap) {
			cap = cap ? 2 * cap : 1 << 16;
			buf = realloc(buf, cap);
			if (!buf)
				abort();
		}
		size_t r = fread(buf + n, 1, cap - n, f);
		n += r;
		if (r == 0)
			break;
	}
	fclose(f);
	/* A copy of exactly n bytes, so reading past the input is caught. */
	unsigned char *in = malloc(n ? n : 1);
	if (!in)
		abort();
	memcpy(in, buf, n);
	free(buf);
	fflush(stdout);
	LLVMFuzzerTestOneInput(in, n);
	free(in);
	printf("ok - %s: %s\n", target, path);
	fflush(stdout);
	return 0;
}

static int
byname(const struct dirent **a, const struct dirent **b)
{
	return strcmp((*a)->d_name, (*b)->d_name);
}

int
main(int argc, char **argv)
{
	const char *target = strrchr(argv[0], '/') ? strrchr(argv[0], '/') + 1 : argv[0];
	int bad = 0;

	for (int i = 1; i < argc; i++) {
		struct stat st;
		if (stat(argv[i], &st) == 0 && S_ISDIR(st.st_mode)) {
			struct dirent **ents;
			int n = scandir(argv[i], &ents, NULL, byname);
			for (int j = 0; j < n; j++) {
				char p[8192];
				snprintf(p, sizeof p, "%s/%s", argv[i], ents[j]->d_name);
				if (ents[j]->d_name[0] != '.' && stat(p, &st) == 0 && S_ISREG(st.st_mode))
					bad |= run_file(target, p);
				free(ents[j]);
			}
			free(ents);
		} else {
			bad |= run_file(target, argv[i]);
		}
	}
	return bad;
}
