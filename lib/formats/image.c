/* image.c — pm_image in memory: channels, attributes, and the limits a
 * reader checks before it allocates (see image.h). exr.c reads and writes
 * it as OpenEXR. */
#include "formats/image.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/maxpixels.h"

/* The pixels a scene may ask for: PM_MAX_PIXELS, 2^25 unless the
 * environment says otherwise (maxpixels.h). */
#define MAX_PIXELS   ((int64_t)pm_max_pixels())
#define MAX_CHANNELS PM_IMAGE_MAX_CHANNELS
#define MAX_SAMPLES  PM_IMAGE_MAX_SAMPLES

int
pm_image_check_size(int64_t w, int64_t h, int64_t nchan, pm_error *err)
{
	if (w < 1 || h < 1)
		return pm_seterr(err, "image size %lldx%lld is empty", (long long)w, (long long)h);
	if (w > MAX_PIXELS || h > MAX_PIXELS || w * h > MAX_PIXELS)
		return pm_seterr(err, "image size %lldx%lld exceeds %lld pixels (PM_MAX_PIXELS)",
		                 (long long)w, (long long)h, (long long)MAX_PIXELS);
	if (nchan < 0 || nchan > MAX_CHANNELS)
		return pm_seterr(err, "%lld channels exceed the limit of %d",
		                 (long long)nchan, MAX_CHANNELS);
	if (w * h * nchan > MAX_SAMPLES)
		return pm_seterr(err, "%lldx%lld pixels with %lld channels exceed %lld samples",
		                 (long long)w, (long long)h, (long long)nchan, (long long)MAX_SAMPLES);
	return 0;
}

int
pm_image_check_name(const char *name, pm_error *err)
{
	size_t n = strlen(name);

	if (n == 0)
		return pm_seterr(err, "empty channel name");
	if (n >= PM_CHAN_NAME)
		return pm_seterr(err, "channel name '%s' longer than %d bytes", name, PM_CHAN_NAME - 1);
	return 0;
}

int
pm_image_init(pm_image *img, int w, int h, int nchan, const char *const *names,
              pm_error *err)
{
	memset(img, 0, sizeof *img);
	if (pm_image_check_size(w, h, nchan, err))
		return -1;
	for (int c = 0; c < nchan; c++) {
		if (pm_image_check_name(names[c], err))
			return -1;
		for (int d = 0; d < c; d++)
			if (strcmp(names[c], names[d]) == 0)
				return pm_seterr(err, "duplicate channel '%s'", names[c]);
	}
	size_t n = nchan > 0 ? (size_t)nchan : 1;
	img->chan = calloc(n, sizeof *img->chan);
	img->px = calloc(n * (size_t)w * (size_t)h, sizeof *img->px);
	if (!img->chan || !img->px) {
		pm_image_free(img);
		return pm_seterr(err, "out of memory for a %dx%d image with %d channels", w, h, nchan);
	}
	for (int c = 0; c < nchan; c++)
		snprintf(img->chan[c], PM_CHAN_NAME, "%s", names[c]);
	img->width = w;
	img->height = h;
	img->nchan = nchan;
	return 0;
}

void
pm_image_free(pm_image *img)
{
	for (int i = 0; i < img->nattr; i++) {
		free(img->attr[i].key);
		free(img->attr[i].value);
	}
	free(img->attr);
	free(img->chan);
	free(img->px);
	memset(img, 0, sizeof *img);
}

float *
pm_image_chan(const pm_image *img, const char *name)
{
	for (int c = 0; c < img->nchan; c++)
		if (strcmp(img->chan[c], name) == 0)
			return img->px + (size_t)c * img->width * img->height;
	return NULL;
}

float *
pm_image_add_chan(pm_image *img, const char *name, pm_error *err)
{
	size_t plane = (size_t)img->width * img->height;
	char (*chan)[PM_CHAN_NAME];
	float *px;

	if (pm_image_check_name(name, err))
		return NULL;
	if (pm_image_chan(img, name)) {
		pm_seterr(err, "duplicate channel '%s'", name);
		return NULL;
	}
	if (pm_image_check_size(img->width, img->height, (int64_t)img->nchan + 1, err))
		return NULL;
	chan = realloc(img->chan, (img->nchan + 1) * sizeof *chan);
	if (!chan) {
		pm_seterr(err, "out of memory adding channel '%s'", name);
		return NULL;
	}
	img->chan = chan;
	px = realloc(img->px, (img->nchan + 1) * plane * sizeof *px);
	if (!px) {
		pm_seterr(err, "out of memory adding channel '%s'", name);
		return NULL;
	}
	img->px = px;
	snprintf(img->chan[img->nchan], PM_CHAN_NAME, "%s", name);
	px += img->nchan * plane;
	memset(px, 0, plane * sizeof *px);
	img->nchan++;
	return px;
}

int
pm_image_set_attr(pm_image *img, const char *key, const char *value, pm_error *err)
{
	char *v;
	pm_attr *a;

	if (!*key || strlen(key) > 255)
		return pm_seterr(err, "attribute name '%.40s' is empty or longer than 255 bytes", key);
	v = strdup(value);
	if (!v)
		return pm_seterr(err, "out of memory for attribute '%s'", key);
	for (int i = 0; i < img->nattr; i++)
		if (strcmp(img->attr[i].key, key) == 0) {
			free(img->attr[i].value);
			img->attr[i].value = v;
			return 0;
		}
	a = realloc(img->attr, (img->nattr + 1) * sizeof *a);
	if (!a) {
		free(v);
		return pm_seterr(err, "out of memory for attribute '%s'", key);
	}
	img->attr = a;
	a[img->nattr].key = strdup(key);
	if (!a[img->nattr].key) {
		free(v);
		return pm_seterr(err, "out of memory for attribute '%s'", key);
	}
	a[img->nattr].value = v;
	img->nattr++;
	return 0;
}

const char *
pm_image_attr(const pm_image *img, const char *key)
{
	for (int i = 0; i < img->nattr; i++)
		if (strcmp(img->attr[i].key, key) == 0)
			return img->attr[i].value;
	return NULL;
}

