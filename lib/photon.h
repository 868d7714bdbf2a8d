/* photon.h — the 20-byte photon record and the photon file (formats/photons.md).
 *
 * A photon is a position (3 x float32), a power (three 10-bit mantissas with
 * a shared 8-bit exponent) and an incoming direction (octahedral, 2 x 12 bits)
 * plus 2 bits for the kd-tree split axis, packed into 20 bytes. The in-memory
 * struct is those same 20 bytes (alignment 4); the file encodes them as
 * explicit little-endian fields.
 *
 * Conventions: the direction psi points from the surface back toward where
 * the photon came from (so psi . N > 0 for a photon arriving on the front of a
 * surface with normal N). The stored power is per emitted light path: the
 * photon's flux is power / emitted, where emitted is the header's count. That
 * makes merging files a concatenation with the emitted counts summed. */
#ifndef PM_PHOTON_H
#define PM_PHOTON_H

#include <stdint.h>
#include <stdio.h>

#include "err.h"
#include "vec.h"

#define PM_PHOTON_BYTES 20
#define PM_AXIS_NONE 3

typedef struct pm_photon {
	float pos[3];
	uint32_t bits[2];   /* power, direction, axis; see formats/photons.md */
} pm_photon;

/* Packs a photon. dir must be unit length; n is the normal of the surface it
 * was stored on: among the nearest direction codes the packer picks one whose
 * decoded direction is on the same side of n as dir, so quantization never
 * turns a grazing photon around. power channels must be finite and >= 0.
 * The axis is set to PM_AXIS_NONE. */
void pm_photon_pack(pm_photon *p, pm_vec3 pos, pm_vec3 dir, pm_vec3 n, pm_vec3 power);
pm_vec3 pm_photon_pos(const pm_photon *p);
pm_vec3 pm_photon_dir(const pm_photon *p);
pm_vec3 pm_photon_power(const pm_photon *p);
int pm_photon_axis(const pm_photon *p);
void pm_photon_set_axis(pm_photon *p, int axis);

/* Explicit little-endian codec of one record (20 bytes). */
void pm_photon_encode(const pm_photon *p, unsigned char out[PM_PHOTON_BYTES]);
void pm_photon_decode(pm_photon *p, const unsigned char in[PM_PHOTON_BYTES]);

#define PM_PHOTONS_VERSION 1
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
	char *history;        /* producing command lines, '\n' separated; owned */
} pm_photon_header;

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

void pm_photons_free(pm_photons *ph);

#endif
