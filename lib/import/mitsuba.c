/* mitsuba.c — placeholder */
#include "import/readers.h"
int pmi_read_mitsuba(const char *path, pmi_desc *d, pm_error *err) { return pm_seterr(err, "'%s': not yet", path); }
