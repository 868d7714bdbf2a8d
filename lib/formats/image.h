/* image.h — float images with named channels and string attributes, read
 * and written as OpenEXR through its C API (formats/image.md).
 *
 * Channels are planar float32: channel c, row y (0 = top), column x is
 * px[((size_t)c * height + y) * width + x]. The beauty image is "R", "G",
 * "B"; other layers use "layer.R" etc. Attributes are key/value strings,
 * keys like "pm.seed"; formats/image.md lists the ones pm writes. */
#ifndef PM_IMAGE_H
#define PM_IMAGE_H

#include <stddef.h>
#include <stdint.h>

#include "base/err.h"

#define PM_CHAN_NAME 32

typedef struct pm_attr {
	char *key, *value;    /* owned */
} pm_attr;

typedef struct pm_image {
	int width, height, nchan;
	char (*chan)[PM_CHAN_NAME];
	float *px;
	int nattr;
	pm_attr *attr;
} pm_image;

/* Limits a reader trusts before allocating: 256 channels, 2^30 samples
 * (4 GiB of floats), and PM_MAX_PIXELS pixels (base/maxpixels.h). */
#define PM_IMAGE_MAX_CHANNELS 256
#define PM_IMAGE_MAX_SAMPLES  ((int64_t)1 << 30)
int pm_image_check_size(int64_t w, int64_t h, int64_t nchan, pm_error *err);
int pm_image_check_name(const char *name, pm_error *err);

/* Allocates a w x h image with the given channels, all zero. */
int pm_image_init(pm_image *img, int w, int h, int nchan,
                  const char *const *names, pm_error *err);
void pm_image_free(pm_image *img);

/* Channel plane by name, or NULL if the image has no such channel. */
float *pm_image_chan(const pm_image *img, const char *name);

/* Adds a channel (zeroed) and returns its plane, or NULL on failure. */
float *pm_image_add_chan(pm_image *img, const char *name, pm_error *err);

/* Sets (replacing) or gets an attribute; get returns NULL if absent. */
int pm_image_set_attr(pm_image *img, const char *key, const char *value, pm_error *err);
const char *pm_image_attr(const pm_image *img, const char *key);

/* Writes the image as an EXR (float32, ZIP compression) atomically: to a
 * temporary file in the target directory, renamed over path on success. */
int pm_image_write_exr(const pm_image *img, const char *path, pm_error *err);

/* Reads any scanline or tiled EXR with float/half/uint channels (converted
 * to float). Sizes are bounded before allocation. Path "-" reads stdin;
 * stdin, a FIFO or any input that is not a regular file is buffered whole
 * in memory (at most 4 GiB + 64 MiB) before it is decoded. Messages name
 * the file as 'path', or stdin. */
int pm_image_read_exr(pm_image *img, const char *path, pm_error *err);

#endif
