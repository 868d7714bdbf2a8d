/* atomic.c — whole-or-nothing output files (see atomic.h). */
#define _GNU_SOURCE
#include "base/atomic.h"

#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static void
dirof(const char *path, char *dir, size_t n)
{
	char buf[4096];

	snprintf(buf, sizeof buf, "%s", path);
	snprintf(dir, n, "%s", dirname(buf));
}

int
pm_out_open(pm_out *o, const char *path, pm_error *err)
{
	char dir[4096], base[4096];
	mode_t um;
	int fd;

	memset(o, 0, sizeof *o);
	o->fd = -1;
	if (strcmp(path, "-") == 0) {
		o->f = stdout;
		o->fd = 1;
		o->where = PM_OUT_STDOUT;
		snprintf(o->path, sizeof o->path, "stdout");
		return 0;
	}
	if (strlen(path) >= 2000)
		return pm_seterr(err, "'%s': path too long", path);
	snprintf(o->path, sizeof o->path, "%s", path);
	/* A device or a FIFO (/dev/null, /dev/stdout, a named pipe) is
	 * written in place: renaming a file over it would replace the
	 * device node, not write to it. Errors are still checked at commit. */
	/* Renaming over a directory would fail only at commit, with a
	 * message (ENOTDIR, EBUSY) that does not say what is wrong. */
	struct stat st;
	int found = stat(path, &st) == 0;
	if ((found && S_ISDIR(st.st_mode)) || (*path && path[strlen(path) - 1] == '/'))
		return pm_seterr(err, "cannot write '%s': that names a directory, not a file", path);
	if (found && !S_ISREG(st.st_mode)) {
		o->f = fopen(path, "wb");
		if (!o->f)
			return pm_seterr(err, "cannot open '%s': %s", path, strerror(errno));
		o->fd = fileno(o->f);
		o->where = PM_OUT_IN_PLACE;
		return 0;
	}
	dirof(path, dir, sizeof dir);
	/* PM_ATOMIC_NAMED=1 forces the named fallback, so that tests can
	 * reach it on file systems that have O_TMPFILE. */
	const char *named = getenv("PM_ATOMIC_NAMED");
	fd = named && strcmp(named, "1") == 0 ? -1
	   : open(dir, O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
	if (fd >= 0) {
		o->tmpfile_kind = 1;
	} else {
		snprintf(base, sizeof base, "%s", path);
		/* The path's length was checked above, so this fits. */
		if (snprintf(o->tmp, sizeof o->tmp, "%.2000s/.%.2000s" PM_TMP_MARK "XXXXXX", dir, basename(base)) < 0)
			return pm_seterr(err, "'%s': bad path", path);
		fd = mkostemp(o->tmp, O_CLOEXEC);
		if (fd < 0)
			return pm_seterr(err, "cannot create '%s': %s", path, strerror(errno));
		um = umask(0);
		umask(um);
		fchmod(fd, 0666 & ~um);
		o->tmpfile_kind = 2;
	}
	o->f = fdopen(fd, "wb");
	if (!o->f) {
		int e = errno;
		close(fd);
		if (o->tmpfile_kind == 2)
			unlink(o->tmp);
		return pm_seterr(err, "cannot create '%s': %s", path, strerror(e));
	}
	o->fd = fd;
	return 0;
}

int
pm_out_commit(pm_out *o, pm_error *err)
{
	char proc[64], tmp[4096 + 32];
	int e;

	if (!o->f)
		return pm_seterr(err, "'%s': output already closed", o->path);
	if (o->where != PM_OUT_RENAMED) {
		int bad = fflush(o->f) != 0 || ferror(o->f);
		e = errno;
		if (o->where == PM_OUT_IN_PLACE && fclose(o->f) != 0 && !bad) {
			bad = 1;
			e = errno;
		}
		o->f = NULL;
		if (bad)
			return pm_seterr(err, "cannot write %s%s%s: %s",
			                 o->where == PM_OUT_IN_PLACE ? "'" : "",
			                 o->path, o->where == PM_OUT_IN_PLACE ? "'" : "", strerror(e ? e : EIO));
		return 0;
	}
	if (fflush(o->f) != 0 || ferror(o->f) || fsync(o->fd) != 0) {
		e = errno ? errno : EIO;
		pm_out_abort(o);
		return pm_seterr(err, "cannot write '%s': %s", o->path, strerror(e));
	}
	if (o->tmpfile_kind == 1) {
		/* An unnamed file needs a name before it can be renamed over the
		 * target (linkat cannot replace an existing file). */
		snprintf(proc, sizeof proc, "/proc/self/fd/%d", o->fd);
		for (int i = 0;; i++) {
			char dir[4096];
			dirof(o->path, dir, sizeof dir);
			snprintf(tmp, sizeof tmp, "%s/" PM_TMP_MARK "%ld.%d", dir, (long)getpid(), i);
			if (linkat(AT_FDCWD, proc, AT_FDCWD, tmp, AT_SYMLINK_FOLLOW) == 0)
				break;
			if (errno != EEXIST || i > 100) {
				e = errno;
				pm_out_abort(o);
				return pm_seterr(err, "cannot write '%s': %s", o->path, strerror(e));
			}
		}
	} else {
		snprintf(tmp, sizeof tmp, "%s", o->tmp);
	}
	if (fclose(o->f) != 0) {
		e = errno;
		o->f = NULL;
		unlink(tmp);
		return pm_seterr(err, "cannot write '%s': %s", o->path, strerror(e));
	}
	o->f = NULL;
	if (rename(tmp, o->path) != 0) {
		e = errno;
		unlink(tmp);
		return pm_seterr(err, "cannot write '%s': %s", o->path, strerror(e));
	}
	return 0;
}

void
pm_out_abort(pm_out *o)
{
	if (!o->f)
		return;
	if (o->where == PM_OUT_IN_PLACE) {
		fclose(o->f);
	} else if (o->where == PM_OUT_RENAMED) {
		fclose(o->f);
		if (o->tmpfile_kind == 2)
			unlink(o->tmp);
	}
	o->f = NULL;
}
