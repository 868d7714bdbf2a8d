/* bar.h — a one-line progress bar on stderr for people at a terminal:
 * "pm-render: rows [#####.....] 512/1024 50% 85.3/s 0:06 left". Shown only
 * when stderr is a terminal and the program is not quiet; otherwise every
 * call does nothing, so logs and pipes stay clean. Redrawn at most ten
 * times a second. Calls must come from one thread at a time. */
#ifndef PM_TOOLS_BAR_H
#define PM_TOOLS_BAR_H

#include <stdint.h>

typedef struct progress {
	const char *what;   /* "rows", "photons", "passes" */
	uint64_t total;
	double start, last; /* seconds, monotonic */
	int on, drawn;
} progress;

/* Starts a bar for `total` units of `what` (static string); off if quiet or
 * stderr is not a terminal. */
void progress_start(progress *p, const char *what, uint64_t total, int quiet);
void progress_update(progress *p, uint64_t done);
/* Draws the final state with the elapsed time and ends the line. */
void progress_end(progress *p, uint64_t done);
/* pm_progress_fn for library hooks: arg is a progress *. */
void progress_hook(void *arg, uint64_t done, uint64_t total);

#endif
