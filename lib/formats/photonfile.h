/* photonfile.h — the photon file (formats/photons.md): magic, a key=value
 * header (counts, seeds, scene and time, the producing command lines), then
 * the 20-byte records of photon.h. A photon map is the same file with the
 * records in kd-tree order (kdtree.h). */
#ifndef PM_PHOTONFILE_H
#define PM_PHOTONFILE_H

#include <stdint.h>
#include <stdio.h>

#include "base/err.h"
#include "formats/photon.h"

/* The newest version this pm reads. It writes version 1 for global maps, so
 * older readers still take them, and version 2 (which adds the map key) for
 * caustic and guide maps, so older readers refuse them instead of taking
 * them for global ones. */
#define PM_PHOTONS_VERSION 2
/* The first bytes of every photon file. */
#define PM_PHOTONS_MAGIC "PM-PHOTONS\n"

typedef struct pm_photon_header {
	int version;
	int kdtree;           /* 1: records are a balanced kd-tree in heap order */
	uint64_t count;       /* records that follow */
	uint64_t emitted;     /* light paths emitted, summed over merged inputs */
	float bbox[6];        /* min x y z, max x y z of the positions (0s if empty) */
	uint64_t light_hash;  /* the scene's light_hash (scene.h) */
	double time;          /* shutter time of the light pass */
	char seeds[256];      /* "7", or "1,2,3" after merging */
	char light_paths[8];  /* "random", "sobol" (shoot.h), "mixed" after merging */
	char density[48];     /* "off", "pixels C k K" (density.h), "mixed" after merging */
	char *history;        /* producing command lines, '\n' separated; owned */
	int map;              /* enum pm_map_kind: which photons the file holds */
} pm_photon_header;

/* Which photons a file holds (the header's map key): every photon stored
 * after the first bounce (global), or only those whose path from the light
 * went through mirrors, glass and strong glossy surfaces alone before the
 * diffuse hit, L S+ D (caustic, Jensen 1996), or the photons that met a
 * strong glossy surface after the first bounce, where the global map
 * stores none (guide: their incoming directions steer view paths that
 * continue there, guide.h). */
enum pm_map_kind { PM_MAP_GLOBAL = 0, PM_MAP_CAUSTIC = 1, PM_MAP_GUIDE = 2 };

/* "global", "caustic" or "guide". */
const char *pm_map_name(int map);

/* A photon file or map in memory. */
typedef struct pm_photons {
	pm_photon_header h;
	pm_photon *p;         /* h.count records; owned */
} pm_photons;

/* Reads a whole photon file from f; name is used in messages ("-" reads as
 * "stdin"). Checks magic, version, endianness, record size and every count
 * against the bytes actually present (a truncated stream is an error), and
 * rejects non-finite positions or powers. */
int pm_photons_read(pm_photons *out, FILE *f, const char *name, pm_error *err);

/* The two halves of pm_photons_read, for tools that look at the header alone
 * (pm-dump --header works on a truncated file) or need its text:
 * read_header checks and fills out->h (out->p = NULL; release with
 * pm_photons_free) and leaves f at the first record; if raw is non-NULL,
 * *raw receives the header bytes as read, blank line included, NUL-terminated
 * (caller frees). read_records then reads and checks ph->h.count records
 * and that nothing follows them. */
int pm_photons_read_header(pm_photons *out, FILE *f, const char *name, char **raw, pm_error *err);
int pm_photons_read_records(pm_photons *ph, FILE *f, const char *name, pm_error *err);

/* Writes header and records to f. Does not close f. The header's bbox is
 * computed from the records. */
int pm_photons_write(const pm_photons *ph, FILE *f, const char *name, pm_error *err);

/* Appends one command line to the history ("pm-shoot -s 7 scene.pms"). */
int pm_photons_add_history(pm_photons *ph, const char *cmdline, pm_error *err);

/* What pm_photons_differ finds different between two files' headers. */
enum { PM_DIFFER_LIGHTS = 1, PM_DIFFER_TIME = 2, PM_DIFFER_MAP = 4 };

/* The header fields (PM_DIFFER_*) in which b differs from a: merging such
 * files mixes photons of different lights or shutter times, or a caustic
 * map into a global one. */
unsigned pm_photons_differ(const pm_photons *a, const pm_photons *b);

/* Appends src to acc: records concatenated, emitted counts summed, seeds
 * joined (a list too long for the header ends in ",..."), histories joined.
 * acc keeps its other header fields. src's history moves to acc (src still
 * needs pm_photons_free). Fails, naming src_name, when the count or the
 * emitted count would overflow, or out of memory; acc is then unchanged. */
int pm_photons_merge(pm_photons *acc, pm_photons *src, const char *src_name, pm_error *err);

void pm_photons_free(pm_photons *ph);

#endif
