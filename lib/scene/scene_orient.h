/* scene_orient.h — which side of a closed surface is matter: not the one
 * the camera looks from (formats/scene.md, "Solids: which side is
 * matter"). */
#ifndef PM_SCENE_ORIENT_H
#define PM_SCENE_ORIENT_H

#include "scene/scene.h"

/* Turns over every closed photon-surface object (other than a one-sided
 * emitter) that has the camera's eye inside it as wound: its faces then
 * point into it, as those of a room seen from inside, and its outside
 * counts as matter. Needs the materials' strong flags and the camera.
 * The camera may be written after the objects, so this runs once the
 * whole file is read, on the built arrays (not through the build's flip,
 * which acts as each object is added). */
void pm_scene_orient_solids(pm_scene *s);

#endif
