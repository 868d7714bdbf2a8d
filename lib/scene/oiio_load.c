/* oiio_load.c — finds and loads pm-oiio.so once (oiio.h). */
#include "scene/oiio.h"

#include <dlfcn.h>
#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* The build tree's module directory, for programs run from it (the
 * Makefile defines it; tests and their tools live deeper than bin/). */
#ifndef PM_BUILD_PLUGINS
#define PM_BUILD_PLUGINS ""
#endif

static pthread_once_t once = PTHREAD_ONCE_INIT;
static const pm_oiio_api *api;
static char fail[400];

typedef const pm_oiio_api *(*get_fn)(void);

/* 1 if DIR's module loads; a module there that does not is the failure. */
static int
try_dir(const char *dir)
{
	char path[PATH_MAX];
	void *h;
	get_fn get;

	if (snprintf(path, sizeof path, "%s/%s", dir, PM_OIIO_FILE) >= (int)sizeof path)
		return 0;
	if (access(path, F_OK) != 0)
		return 0;
	h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
	if (!h) {
		snprintf(fail, sizeof fail, "OpenImageIO module: %s", dlerror());
		return 0;
	}
	get = (get_fn)dlsym(h, PM_OIIO_SYMBOL);
	if (!get || !(api = get())) {
		snprintf(fail, sizeof fail, "OpenImageIO module %.300s: no %s in it", path, PM_OIIO_SYMBOL);
		dlclose(h);
		return 0;
	}
	return 1;
}

static void
load(void)
{
	const char *env = getenv("PM_PLUGIN_DIR");
	char exe[PATH_MAX], *slash;
	ssize_t n;

	if (env && *env) {
		if (!try_dir(env) && !fail[0])
			snprintf(fail, sizeof fail, "OpenImageIO module %s not in PM_PLUGIN_DIR (%.300s)",
			         PM_OIIO_FILE, env);
		return;
	}
	n = readlink("/proc/self/exe", exe, sizeof exe - 16);
	if (n > 0) {
		exe[n] = '\0';
		if ((slash = strrchr(exe, '/'))) {
			strcpy(slash, "/../lib/pm");
			if (try_dir(exe) || fail[0])
				return;
		}
	}
	if (PM_BUILD_PLUGINS[0] && (try_dir(PM_BUILD_PLUGINS) || fail[0]))
		return;
	snprintf(fail, sizeof fail, "OpenImageIO module %s not found in ../lib/pm beside the program%s%s "
	         "(PM_PLUGIN_DIR names its directory)", PM_OIIO_FILE,
	         PM_BUILD_PLUGINS[0] ? " nor in " : "", PM_BUILD_PLUGINS);
}

const pm_oiio_api *
pm_oiio(char *why, size_t n)
{
	pthread_once(&once, load);
	if (!api && why && n > 0)
		snprintf(why, n, "%s", fail);
	return api;
}
