/* err.c — pm_error formatting (see err.h). */
#include "err.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int
pm_seterr(pm_error *err, const char *fmt, ...)
{
	va_list ap;

	if (!err)
		return -1;
	va_start(ap, fmt);
	vsnprintf(err->msg, sizeof err->msg, fmt, ap);
	va_end(ap);
	return -1;
}

int
pm_preferr(pm_error *err, const char *fmt, ...)
{
	char old[sizeof err->msg], pre[256];
	va_list ap;

	if (!err)
		return -1;
	memcpy(old, err->msg, sizeof old);
	va_start(ap, fmt);
	vsnprintf(pre, sizeof pre, fmt, ap);
	va_end(ap);
	/* Bounded so that prefix and message always fit in msg. */
	if (snprintf(err->msg, sizeof err->msg, "%s: %.*s", pre, (int)(sizeof err->msg - sizeof pre - 3), old) < 0)
		err->msg[0] = 0;
	return -1;
}
