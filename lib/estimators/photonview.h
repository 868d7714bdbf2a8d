/* photonview.h — pm-render -e photons: the photon map itself as seen from
 * the camera (paper figure 3c), for looking at where photons landed. */
#ifndef PM_PHOTONVIEW_H
#define PM_PHOTONVIEW_H

#include "estimators/estimators.h"

/* Splats every photon of in->map that projects into the image and that the
 * camera sees (the first hit along the ray to it lies at its distance) into
 * its pixel: R, G, B and indirect.* get
 *   f_r(x_p, psi_p, w_o) * (power_p / emitted) / A_pix(x_p),
 * A_pix the pixel's footprint on the surface at the photon, so a pixel's
 * expected value is the photon-carried (indirect) radiance over the pixel;
 * count gets the number of photons splatted. Other channels stay 0. No
 * random numbers are used: the image depends on the map only. img holds
 * pm_render's channels, zeroed. */
int pm_photonview_image(const pm_est_in *in, const pm_camera *cam, pm_image *img, pm_error *err);

#endif
