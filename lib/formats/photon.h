/* photon.h — the 20-byte photon record (formats/photons.md, "Record");
 * the file around the records is photonfile.h.
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

#include "base/vec.h"

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

#endif
