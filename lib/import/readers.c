/* readers.c — which reader a file wants (readers.h). */
#include <string.h>
#include <strings.h>

#include "import/readers.h"

pmi_reader
pmi_reader_for(const char *path)
{
	const char *dot = strrchr(path, '.'), *sl = strrchr(path, '/');

	if (!dot || (sl && dot < sl))
		return NULL;
	if (!strcasecmp(dot, ".pbrt"))
		return pmi_read_pbrt;
	if (!strcasecmp(dot, ".xml"))
		return pmi_read_mitsuba;
	if (!strcasecmp(dot, ".obj"))
		return pmi_read_obj;
	return NULL;
}
