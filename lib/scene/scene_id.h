/* scene_id.h — a scene's identities, hashed from its parsed values
 * (formats/scene.md, "Scene identity"): what the light pass depends on, and
 * that plus the camera, what a view pass depends on. */
#ifndef PM_SCENE_ID_H
#define PM_SCENE_ID_H

#include "scene/scene.h"

/* Sets s->light_hash and s->view_hash from a fully loaded scene. Comments,
 * white space, number spellings and material names do not enter; every
 * parsed value the photons depend on does. */
void pm_scene_identify(pm_scene *s);

#endif
