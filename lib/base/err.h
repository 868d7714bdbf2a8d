/* err.h — error reporting for libpm.
 *
 * Library code never prints and never exits. A function that can fail takes a
 * pm_error * as its last argument, returns 0 on success and -1 on failure, and
 * on failure leaves a one-line, lowercase message in err->msg (no trailing
 * newline, no program name: the tool adds "pm-NAME: "). Messages about a file
 * name it first, quoted or as FILE:LINE for text formats. Control bytes
 * (a newline in a quoted channel name, say) are replaced by '?'. */
#ifndef PM_ERR_H
#define PM_ERR_H

#include <stddef.h>

typedef struct pm_error {
	char msg[512];
} pm_error;

/* Formats a message into err (if err is non-NULL). Always returns -1 so that
 * "return pm_seterr(err, ...);" reads naturally. */
int pm_seterr(pm_error *err, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

/* Prepends "prefix: " to an existing message, e.g. a file name. Returns -1. */
int pm_preferr(pm_error *err, const char *fmt, ...)
	__attribute__((format(printf, 2, 3)));

#endif
