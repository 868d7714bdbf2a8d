/* scene_limits.h — the range of sizes pm resolves (formats/scene.md,
 * "Range"): a scene is refused, with the statement at fault, when a ray, the
 * kd-tree, the compensated estimate's clipping or the photon record could
 * not carry it in float. Every way into a scene (statements, mesh files,
 * transforms, move, imported scenes) passes through the builder, which calls
 * these; each returns 0, or -1 with a message that starts with the
 * statement (`what`), to which the parser puts "FILE:LINE: " before. */
#ifndef PM_SCENE_LIMITS_H
#define PM_SCENE_LIMITS_H

#include "base/err.h"
#include "scene/scene.h"

/* Largest coordinate magnitude of any position at any shutter time:
 * Embree refuses ray origins beyond 1.844e18 and its triangle test forms
 * products of a distance and two edges, (2 sqrt(3) 1e12)^3 = 4.2e37 < 3.4e38. */
#define PM_COORD_MAX 1e12
/* Smallest scene (bounding box of its geometry and point lights, largest
 * side): below it areas of photon-estimate discs and the light's distance
 * squared leave float's normal range (1.2e-38) for usual photon counts. */
#define PM_EXTENT_MIN 1e-9
/* Shortest look - eye and up: the camera squares and normalizes them in
 * float, 1e-24 and up still normal numbers. */
#define PM_DIRECTION_MIN 1e-12
/* Field of view in degrees: below, the whole image spans fewer than 30 float
 * spacings of the view direction (6e-8 rad); above, tan(fov / 2) in float
 * nears its pole, which 180 as a float passes (a negative tangent). */
#define PM_FOV_MIN 1e-4
#define PM_FOV_MAX 179.999
/* Emitted radiance (emit), a point light's power over the scene's extent
 * squared, and the scene's total power, per channel: far below float's
 * 3.4e38, so that photon powers, their sums over k photons and over
 * samples, and the radiance near lights and in caustics stay finite. */
#define PM_RADIANCE_MAX 1e30
#define PM_POWER_MAX 1e30

/* A vertex w (world space, t = 0) of an object moving by motion. */
int pm_limits_vertex(const double w[3], pm_vec3 motion, const char *what, pm_error *err);
int pm_limits_camera(const pm_camera_desc *c, pm_error *err);
int pm_limits_material(const pm_material *m, const char *what, pm_error *err);
int pm_limits_light(const pm_pointlight *l, pm_error *err);
/* The whole scene, once read: its extent, and power against it. */
int pm_limits_scene(const pm_scene *s, pm_error *err);

#endif
