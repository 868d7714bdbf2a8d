/* version.h — pm's version, defined here only: --version prints it and
 * every file pm writes records it (photon files' "version" key is the
 * format's, this is the program's). */
#ifndef PM_VERSION_H
#define PM_VERSION_H

#define PM_VERSION "0.15"

#endif
