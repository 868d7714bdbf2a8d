/* kdtree.h — the photon map: a left-balanced kd-tree in heap order (Jensen
 * 1996), stored in the photon array itself with the split axis in each
 * record's 2 axis bits, so it costs nothing beyond the 20-byte records.
 *
 * Heap order: node i has children 2i+1 and 2i+2 (0-based). */
#ifndef PM_KDTREE_H
#define PM_KDTREE_H

#include <stddef.h>

#include "base/err.h"
#include "formats/photon.h"

/* Reorders p[0..n-1] into a balanced kd-tree (median splits on the axis of
 * largest extent of each subset) and sets the axis bits. Deterministic.
 * Fails only on allocation failure. */
int pm_kd_build(pm_photon *p, size_t n, pm_error *err);

/* Depth of the tree (0 for n == 0). */
int pm_kd_depth(size_t n);

/* Checks the kd-tree invariant (every subtree on the right side of each split).
 * Returns 0 if valid, -1 with a message naming the first bad node. */
int pm_kd_validate(const pm_photon *p, size_t n, pm_error *err);

typedef struct pm_nn {
	uint32_t idx;       /* index into the photon array */
	float d;            /* distance: squared Euclidean (L2) or Chebyshev (Linf) */
} pm_nn;

enum pm_metric { PM_L2, PM_LINF };

/* The k nearest photons of x under the metric with distance < dmax (pass
 * INFINITY for no limit; for PM_L2 dmax is a squared distance). Writes up to
 * k neighbours to out (in no particular order) and returns how many; *dfar is
 * the largest distance found (squared for PM_L2; the cube half-size for
 * PM_LINF; 0 if none). Ties at the k-th distance are broken by index, so the
 * result is a function of the inputs alone. */
int pm_kd_knn(const pm_photon *p, size_t n, const float x[3], int k,
              enum pm_metric metric, float dmax, pm_nn *out, float *dfar);

#endif
