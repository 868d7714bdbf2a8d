/* atomic.h — output files that appear whole or not at all.
 *
 * pm_out_open creates an unnamed file in the target's directory (O_TMPFILE,
 * or a hidden temporary name where that is unsupported); pm_out_commit
 * flushes, fsyncs, checks every write error and then links/renames it over
 * the target. Until commit the target is untouched; a process killed before
 * commit leaves no partial file (with O_TMPFILE not even a temporary one).
 * Path "-" means stdout: written directly, errors still checked at commit.
 * So is a path naming an existing device or FIFO (/dev/null, /dev/full, a
 * named pipe): renaming over it would replace the device node. A path
 * naming a directory (or ending in '/') is refused at open.
 *
 * Every temporary name contains PM_TMP_MARK (".NAME.pm-tmp-XXXXXX", or
 * ".pm-tmp-PID.N" for the moment between naming an O_TMPFILE and renaming
 * it), so a signal handler can find and remove them (tools/util.c does, for
 * SIGINT, SIGTERM and SIGHUP); only SIGKILL during the named fallback can
 * leave one behind. PM_ATOMIC_NAMED=1 in the environment forces the named
 * fallback (for tests). */
#ifndef PM_ATOMIC_H
#define PM_ATOMIC_H

#define PM_TMP_MARK ".pm-tmp-"

#include <stdio.h>

#include "base/err.h"

/* Where a pm_out writes: a temporary renamed over the target at commit;
 * stdout; or in place, for a device or FIFO (renaming over /dev/null or a
 * named pipe would replace the node, not write to it). */
enum pm_out_where { PM_OUT_RENAMED, PM_OUT_STDOUT, PM_OUT_IN_PLACE };

typedef struct pm_out {
	FILE *f;            /* write here */
	int fd;             /* fileno(f) */
	enum pm_out_where where;
	int tmpfile_kind;   /* 0 stdout, 1 O_TMPFILE, 2 named temporary */
	char path[4096];    /* target */
	char tmp[4096];     /* named temporary, if tmpfile_kind == 2 */
} pm_out;

int pm_out_open(pm_out *o, const char *path, pm_error *err);
int pm_out_commit(pm_out *o, pm_error *err);
/* Discards the output; the target is left as it was. Safe to call twice. */
void pm_out_abort(pm_out *o);

#endif
