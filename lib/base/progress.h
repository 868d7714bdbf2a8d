/* progress.h — how long-running library work says how far it got without
 * printing (library code never prints): the caller passes a function that
 * libpm calls with the work done so far and the total, from one thread at a
 * time, and that must not change what the work computes. Tools turn the
 * calls into a terminal progress bar (tools/bar.h). */
#ifndef PM_PROGRESS_H
#define PM_PROGRESS_H

#include <stdint.h>

/* done <= total; the last call, if the work finishes, has done == total
 * (for pm_shoot, done == photons stored, which may stay below total). */
typedef void pm_progress_fn(void *arg, uint64_t done, uint64_t total);

#endif
