/* edge.h — is a point within one cube of an edge or corner of the
 * photon-surface geometry? */
#ifndef PM_EDGE_H
#define PM_EDGE_H

#include "scene/polyindex.h"

/* 1 if the closed cube of half-size h centred at x meets, with nonzero
 * area, a photon-surface polygon whose plane does not pass through x: x is
 * within one cube of an edge or corner of the geometry. pm-render's `edge`
 * layer, the mask for error measured near edges. */
int pm_polyindex_near_edge(const pm_polyindex *pi, pm_vec3 x, double h);

#endif
