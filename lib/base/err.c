/* err.c — pm_error formatting (see err.h). */
#include "base/err.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

/* Messages quote what files hold (names, values); a newline or another
 * control byte there would break the one-line contract or play with the
 * terminal, so each becomes '?'. */
static void
one_line(char *s)
{
	for (; *s; s++)
		if ((unsigned char)*s < 0x20 || *s == 0x7f)
			*s = '?';
}

int
pm_seterr(pm_error *err, const char *fmt, ...)
{
	va_list ap;

	if (!err)
		return -1;
	va_start(ap, fmt);
	vsnprintf(err->msg, sizeof err->msg, fmt, ap);
	va_end(ap);
	one_line(err->msg);
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
	one_line(err->msg);
	return -1;
}
