/* exr.c — pm_image read and written as OpenEXR through OpenEXRCore's C
 * API (image.h, formats/image.md).
 *
 * Writing encodes into a memory buffer through a custom write_fn and then
 * copies that buffer to a pm_out, so the file appears atomically (and "-"
 * works, although EXR's offset table needs seeking). Reading goes through a
 * pread-based read_fn so that open errors carry errno and every library
 * message is caught by our handler instead of being printed; stdin or any
 * other input that cannot seek (a pipe) is read into memory first, for the
 * same reason writing goes through memory. */
#include "formats/image.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <openexr.h>

#include "base/atomic.h"
#include "base/version.h"

/* ---- OpenEXR glue ---- */

/* What a context's callbacks share: the stream and the first message the
 * library reported (the first is the most specific one). */
typedef struct stream {
	int fd;                 /* reading */
	unsigned char *buf;     /* writing: the whole file */
	size_t len, cap;
	int oom;
	char msg[256];
} stream;

static void
on_error(exr_const_context_t ctx, exr_result_t code, const char *msg)
{
	void *ud = NULL;
	stream *s;

	if (!ctx || exr_get_user_data(ctx, &ud) != EXR_ERR_SUCCESS || !ud)
		return;
	s = ud;
	if (!s->msg[0]) {
		snprintf(s->msg, sizeof s->msg, "%s", msg ? msg : exr_get_default_error_message(code));
		if (s->msg[0] >= 'A' && s->msg[0] <= 'Z' && !(s->msg[1] >= 'A' && s->msg[1] <= 'Z'))
			s->msg[0] += 'a' - 'A';
		for (char *p = s->msg; *p; p++)
			if (*p == '\n')
				*p = ' ';
	}
}

static const char *
exr_why(const stream *s, exr_result_t rv)
{
	return s->msg[0] ? s->msg : exr_get_default_error_message(rv);
}

static int64_t
mem_write(exr_const_context_t ctx, void *ud, const void *src, uint64_t sz,
          uint64_t off, exr_stream_error_func_ptr_t ecb)
{
	stream *s = ud;
	uint64_t end = off + sz;

	(void)ctx;
	(void)ecb;
	if (end < off || end > SIZE_MAX / 2) {
		s->oom = 1;
		return -1;
	}
	if (end > s->cap) {
		size_t cap = s->cap ? s->cap : 1 << 16;
		unsigned char *b;
		while (cap < end)
			cap *= 2;
		b = realloc(s->buf, cap);
		if (!b) {
			s->oom = 1;
			return -1;
		}
		memset(b + s->cap, 0, cap - s->cap);
		s->buf = b;
		s->cap = cap;
	}
	memcpy(s->buf + off, src, sz);
	if (end > s->len)
		s->len = end;
	return (int64_t)sz;
}

static int64_t
fd_read(exr_const_context_t ctx, void *ud, void *dst, uint64_t sz, uint64_t off,
        exr_stream_error_func_ptr_t ecb)
{
	stream *s = ud;
	uint64_t got = 0;

	while (got < sz) {
		ssize_t n = pread(s->fd, (char *)dst + got, sz - got, (off_t)(off + got));
		if (n < 0 && errno == EINTR)
			continue;
		if (n < 0) {
			if (ecb)
				ecb(ctx, EXR_ERR_READ_IO, "read error: %s", strerror(errno));
			return -1;
		}
		if (n == 0)
			break;
		got += (uint64_t)n;
	}
	return (int64_t)got;
}

/* A pipe cannot be read at offsets, so it is read whole first. */
static int64_t
mem_read(exr_const_context_t ctx, void *ud, void *dst, uint64_t sz, uint64_t off,
         exr_stream_error_func_ptr_t ecb)
{
	stream *s = ud;

	(void)ctx;
	(void)ecb;
	if (off >= s->len)
		return 0;
	if (sz > s->len - off)
		sz = s->len - off;
	memcpy(dst, s->buf + off, sz);
	return (int64_t)sz;
}

static int64_t
mem_size(exr_const_context_t ctx, void *ud)
{
	(void)ctx;
	return (int64_t)((stream *)ud)->len;
}

/* Reads all of s->fd into s->buf, up to a bound on what an image pm reads
 * can take: every sample as an uncompressed float, plus room for headers
 * and offset tables. */
static int
slurp(stream *s, const char *name, pm_error *err)
{
	const size_t most = (size_t)PM_IMAGE_MAX_SAMPLES * 4 + ((size_t)1 << 26);

	for (;;) {
		ssize_t n;
		if (s->len > most)
			return pm_seterr(err, "%s: more than %zu bytes: too big for an image", name, most);
		if (s->len == s->cap) {
			size_t cap = s->cap ? s->cap * 2 : 1 << 16;
			unsigned char *b;
			if (cap > most + 1)
				cap = most + 1;
			if (!(b = realloc(s->buf, cap)))
				return pm_seterr(err, "%s: out of memory reading it", name);
			s->buf = b;
			s->cap = cap;
		}
		n = read(s->fd, s->buf + s->len, s->cap - s->len);
		if (n < 0 && errno == EINTR)
			continue;
		if (n < 0)
			return pm_seterr(err, "cannot read %s: %s", name, strerror(errno));
		if (n == 0)
			return 0;
		s->len += (size_t)n;
	}
}

static int64_t
fd_size(exr_const_context_t ctx, void *ud)
{
	stream *s = ud;
	struct stat st;

	(void)ctx;
	return fstat(s->fd, &st) == 0 ? (int64_t)st.st_size : -1;
}

static int
encode_rows(exr_context_t ctx, const pm_image *img, stream *s, pm_error *err)
{
	exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
	exr_result_t rv = EXR_ERR_SUCCESS;
	int32_t spc;
	int first = 1;

	if ((rv = exr_get_scanlines_per_chunk(ctx, 0, &spc)) != EXR_ERR_SUCCESS)
		return pm_seterr(err, "%s", exr_why(s, rv));
	for (int y = 0; y < img->height && rv == EXR_ERR_SUCCESS; y += spc) {
		exr_chunk_info_t ci;

		rv = exr_write_scanline_chunk_info(ctx, 0, y, &ci);
		if (rv != EXR_ERR_SUCCESS)
			break;
		rv = first ? exr_encoding_initialize(ctx, 0, &ci, &enc)
		           : exr_encoding_update(ctx, 0, &ci, &enc);
		if (rv != EXR_ERR_SUCCESS)
			break;
		for (int i = 0; i < enc.channel_count; i++) {
			exr_coding_channel_info_t *ch = &enc.channels[i];
			const float *plane = pm_image_chan(img, ch->channel_name);
			ch->user_pixel_stride = sizeof(float);
			ch->user_line_stride = (int32_t)(sizeof(float) * img->width);
			ch->user_data_type = EXR_PIXEL_FLOAT;
			ch->user_bytes_per_element = sizeof(float);
			ch->encode_from_ptr = (const uint8_t *)(plane + (size_t)ci.start_y * img->width);
		}
		if (first)
			rv = exr_encoding_choose_default_routines(ctx, 0, &enc);
		if (rv == EXR_ERR_SUCCESS)
			rv = exr_encoding_run(ctx, 0, &enc);
		first = 0;
	}
	if (!first)
		exr_encoding_destroy(ctx, &enc);
	if (rv != EXR_ERR_SUCCESS)
		return pm_seterr(err, "cannot encode: %s", exr_why(s, rv));
	return 0;
}

int
pm_image_write_exr(const pm_image *img, const char *path, pm_error *err)
{
	exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
	exr_context_t ctx = NULL;
	exr_result_t rv;
	stream s = { .fd = -1 };
	pm_out out;
	int part, longnames = 0;

	if (pm_image_check_size(img->width, img->height, img->nchan, err))
		return pm_preferr(err, "cannot write '%s'", path);
	if (img->nchan < 1)
		return pm_seterr(err, "cannot write '%s': image has no channels", path);
	for (int c = 0; c < img->nchan; c++)
		if (pm_image_check_name(img->chan[c], err))
			return pm_preferr(err, "cannot write '%s'", path);
	if (pm_out_open(&out, path, err))
		return -1;

	init.user_data = &s;
	init.write_fn = mem_write;
	init.error_handler_fn = on_error;
	rv = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init);
	if (rv == EXR_ERR_SUCCESS)
		rv = exr_add_part(ctx, NULL, EXR_STORAGE_SCANLINE, &part);
	if (rv == EXR_ERR_SUCCESS)
		rv = exr_initialize_required_attr_simple(ctx, 0, img->width, img->height,
		                                         EXR_COMPRESSION_ZIP);
	for (int c = 0; c < img->nchan && rv == EXR_ERR_SUCCESS; c++)
		rv = exr_add_channel(ctx, 0, img->chan[c], EXR_PIXEL_FLOAT,
		                     EXR_PERCEPTUALLY_LINEAR, 1, 1);
	for (int i = 0; i < img->nattr; i++)
		if (strlen(img->attr[i].key) > 31)
			longnames = 1;
	if (rv == EXR_ERR_SUCCESS && longnames)
		rv = exr_set_longname_support(ctx, 1);
	for (int i = 0; i < img->nattr && rv == EXR_ERR_SUCCESS; i++) {
		if (strcmp(img->attr[i].key, "type") == 0 || strcmp(img->attr[i].key, "name") == 0) {
			pm_seterr(err, "cannot write '%s': attribute name '%s' is reserved by OpenEXR",
			          path, img->attr[i].key);
			goto fail;
		}
		rv = exr_attr_set_string(ctx, 0, img->attr[i].key, img->attr[i].value);
		if (rv != EXR_ERR_SUCCESS) {
			pm_seterr(err, "cannot write '%s': attribute '%s': %s", path,
			          img->attr[i].key, exr_why(&s, rv));
			goto fail;
		}
	}
	/* Which pm wrote the file; a copied input's value is replaced. */
	if (rv == EXR_ERR_SUCCESS)
		rv = exr_attr_set_string(ctx, 0, "pm.version", PM_VERSION);
	if (rv == EXR_ERR_SUCCESS)
		rv = exr_write_header(ctx);
	if (rv != EXR_ERR_SUCCESS) {
		pm_seterr(err, "cannot write '%s': %s", path, exr_why(&s, rv));
		goto fail;
	}
	if (encode_rows(ctx, img, &s, err)) {
		pm_preferr(err, "cannot write '%s'", path);
		goto fail;
	}
	rv = exr_finish(&ctx);
	if (rv != EXR_ERR_SUCCESS || s.oom) {
		pm_seterr(err, "cannot write '%s': %s", path,
		          s.oom ? "out of memory" : exr_why(&s, rv));
		goto fail;
	}
	if (fwrite(s.buf, 1, s.len, out.f) != s.len) {
		pm_seterr(err, "cannot write '%s': %s", path, strerror(errno));
		goto fail;
	}
	free(s.buf);
	return pm_out_commit(&out, err);
fail:
	if (ctx)
		exr_finish(&ctx);
	free(s.buf);
	pm_out_abort(&out);
	return -1;
}

/* Decodes one chunk whose top-left pixel is (x, y) in image coordinates. */
static int
decode_chunk(exr_context_t ctx, exr_decode_pipeline_t *dec, int *first,
             const exr_chunk_info_t *ci, pm_image *img, int64_t x, int64_t y)
{
	exr_result_t rv;

	rv = *first ? exr_decoding_initialize(ctx, 0, ci, dec)
	            : exr_decoding_update(ctx, 0, ci, dec);
	if (rv != EXR_ERR_SUCCESS)
		return rv;
	*first = 0;
	for (int i = 0; i < dec->channel_count; i++) {
		exr_coding_channel_info_t *ch = &dec->channels[i];
		float *plane = pm_image_chan(img, ch->channel_name);
		ch->user_pixel_stride = sizeof(float);
		ch->user_line_stride = (int32_t)(sizeof(float) * img->width);
		ch->user_data_type = EXR_PIXEL_FLOAT;
		ch->user_bytes_per_element = sizeof(float);
		ch->decode_to_ptr = (uint8_t *)(plane + (size_t)y * img->width + (size_t)x);
	}
	rv = exr_decoding_choose_default_routines(ctx, 0, dec);
	if (rv == EXR_ERR_SUCCESS)
		rv = exr_decoding_run(ctx, 0, dec);
	return rv;
}

/* Checks that a chunk placed at pixel (x, y) lies inside the image, so a
 * corrupt chunk table cannot make the decoder write outside our planes. */
static int
chunk_inside(const exr_chunk_info_t *ci, int64_t x, int64_t y, const pm_image *img)
{
	return x >= 0 && y >= 0 && ci->width >= 0 && ci->height >= 0 &&
	       x + ci->width <= img->width && y + ci->height <= img->height;
}

static int
read_pixels(exr_context_t ctx, exr_storage_t storage, const exr_attr_box2i_t *dw,
            pm_image *img, stream *s, pm_error *err)
{
	exr_decode_pipeline_t dec = EXR_DECODE_PIPELINE_INITIALIZER;
	exr_result_t rv = EXR_ERR_SUCCESS;
	exr_chunk_info_t ci;
	int first = 1;
	int64_t x0 = dw->min.x, y0 = dw->min.y;
	char where[64] = "";

	if (storage == EXR_STORAGE_SCANLINE) {
		int32_t spc;
		if ((rv = exr_get_scanlines_per_chunk(ctx, 0, &spc)) == EXR_ERR_SUCCESS && spc < 1)
			rv = EXR_ERR_INVALID_ATTR;
		for (int64_t y = y0; y <= dw->max.y && rv == EXR_ERR_SUCCESS; y += spc) {
			snprintf(where, sizeof where, "scanline %lld", (long long)(y - y0));
			rv = exr_read_scanline_chunk_info(ctx, 0, (int)y, &ci);
			if (rv == EXR_ERR_SUCCESS &&
			    !chunk_inside(&ci, (int64_t)ci.start_x - x0, (int64_t)ci.start_y - y0, img))
				rv = EXR_ERR_CORRUPT_CHUNK;
			if (rv == EXR_ERR_SUCCESS)
				rv = decode_chunk(ctx, &dec, &first, &ci, img,
				                  (int64_t)ci.start_x - x0, (int64_t)ci.start_y - y0);
		}
	} else {
		uint32_t tw, th;
		exr_tile_level_mode_t lm;
		exr_tile_round_mode_t rm;
		rv = exr_get_tile_descriptor(ctx, 0, &tw, &th, &lm, &rm);
		if (rv == EXR_ERR_SUCCESS && (tw < 1 || th < 1))
			rv = EXR_ERR_INVALID_ATTR;
		/* Level (0, 0) of a mip- or ripmap is the full-resolution image. */
		for (int64_t ty = 0; rv == EXR_ERR_SUCCESS && ty * th < img->height; ty++)
			for (int64_t tx = 0; rv == EXR_ERR_SUCCESS && tx * tw < img->width; tx++) {
				snprintf(where, sizeof where, "tile (%lld, %lld)", (long long)tx, (long long)ty);
				rv = exr_read_tile_chunk_info(ctx, 0, (int)tx, (int)ty, 0, 0, &ci);
				/* A tile's chunk info holds tile indices, not pixels. */
				if (rv == EXR_ERR_SUCCESS && !chunk_inside(&ci, tx * tw, ty * th, img))
					rv = EXR_ERR_CORRUPT_CHUNK;
				if (rv == EXR_ERR_SUCCESS)
					rv = decode_chunk(ctx, &dec, &first, &ci, img, tx * tw, ty * th);
			}
	}
	if (!first)
		exr_decoding_destroy(ctx, &dec);
	if (rv != EXR_ERR_SUCCESS)
		return pm_seterr(err, "truncated or corrupt OpenEXR file (%s: %s)", where,
		                 exr_why(s, rv));
	return 0;
}

static int
read_attrs(exr_context_t ctx, pm_image *img, pm_error *err)
{
	int32_t n;

	if (exr_get_attribute_count(ctx, 0, &n) != EXR_ERR_SUCCESS)
		return 0;
	for (int32_t i = 0; i < n; i++) {
		const exr_attribute_t *a;
		const char *v, *nul;
		char *val;
		int r;

		if (exr_get_attribute_by_index(ctx, 0, EXR_ATTR_LIST_FILE_ORDER, i, &a) != EXR_ERR_SUCCESS ||
		    a->type != EXR_ATTR_STRING || !a->string || a->string->length < 0)
			continue;
		/* "type" and "name" describe the file's structure (the library
		 * writes them), not the image. */
		if (strcmp(a->name, "type") == 0 || strcmp(a->name, "name") == 0)
			continue;
		v = a->string->str ? a->string->str : "";
		nul = memchr(v, 0, (size_t)a->string->length);
		val = strndup(v, nul ? (size_t)(nul - v) : (size_t)a->string->length);
		if (!val)
			return pm_seterr(err, "out of memory for attribute '%s'", a->name);
		r = pm_image_set_attr(img, a->name, val, err);
		free(val);
		if (r)
			return -1;
	}
	return 0;
}

static const char *
type_name(exr_pixel_type_t t)
{
	return t == EXR_PIXEL_UINT ? "uint" : t == EXR_PIXEL_HALF ? "half" :
	       t == EXR_PIXEL_FLOAT ? "float" : "unknown";
}

int
pm_image_read_exr(pm_image *img, const char *path, pm_error *err)
{
	static const unsigned char magic[4] = { 0x76, 0x2f, 0x31, 0x01 };
	exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
	exr_context_t ctx = NULL;
	exr_result_t rv;
	exr_storage_t storage;
	exr_attr_box2i_t dw;
	const exr_attr_chlist_t *cl;
	const char *names[PM_IMAGE_MAX_CHANNELS];
	unsigned char head[4];
	stream s = { .fd = -1 };
	int64_t w, h;
	int nparts, piped;
	struct stat st;
	char nm[300];

	memset(img, 0, sizeof *img);
	if (strcmp(path, "-") == 0) {
		snprintf(nm, sizeof nm, "stdin");
		s.fd = STDIN_FILENO;
	} else {
		snprintf(nm, sizeof nm, "'%.280s'", path);
		s.fd = open(path, O_RDONLY | O_CLOEXEC);
	}
	if (s.fd < 0)
		return pm_seterr(err, "cannot open %s: %s", nm, strerror(errno));
	/* stdin, a FIFO, <(...): anything but a file is read whole first. */
	piped = fstat(s.fd, &st) != 0 || !S_ISREG(st.st_mode);
	if (piped && slurp(&s, nm, err))
		goto fail;
	if ((piped ? mem_read : fd_read)(NULL, &s, head, 4, 0, NULL) != 4 || memcmp(head, magic, 4) != 0) {
		pm_seterr(err, "%s: not an OpenEXR file", nm);
		goto fail;
	}
	init.user_data = &s;
	init.read_fn = piped ? mem_read : fd_read;
	init.size_fn = piped ? mem_size : fd_size;
	init.error_handler_fn = on_error;
	init.flags = EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
	rv = exr_start_read(&ctx, path, &init);
	if (rv != EXR_ERR_SUCCESS) {
		pm_seterr(err, "%s: bad OpenEXR header: %s", nm, exr_why(&s, rv));
		goto fail;
	}
	if (exr_get_count(ctx, &nparts) != EXR_ERR_SUCCESS || nparts < 1 ||
	    exr_get_storage(ctx, 0, &storage) != EXR_ERR_SUCCESS ||
	    exr_get_data_window(ctx, 0, &dw) != EXR_ERR_SUCCESS ||
	    exr_get_channels(ctx, 0, &cl) != EXR_ERR_SUCCESS || !cl) {
		pm_seterr(err, "%s: bad OpenEXR header: %s", nm, exr_why(&s, EXR_ERR_MISSING_REQ_ATTR));
		goto fail;
	}
	if (storage != EXR_STORAGE_SCANLINE && storage != EXR_STORAGE_TILED) {
		pm_seterr(err, "%s: deep OpenEXR images are not supported", nm);
		goto fail;
	}
	w = (int64_t)dw.max.x - dw.min.x + 1;
	h = (int64_t)dw.max.y - dw.min.y + 1;
	if (cl->num_channels < 1) {
		pm_seterr(err, "%s: image has no channels", nm);
		goto fail;
	}
	if (pm_image_check_size(w, h, cl->num_channels, err)) {
		pm_preferr(err, "%s", nm);
		goto fail;
	}
	for (int c = 0; c < cl->num_channels; c++) {
		const exr_attr_chlist_entry_t *e = &cl->entries[c];
		names[c] = e->name.str;
		if (pm_image_check_name(e->name.str, err)) {
			pm_preferr(err, "%s", nm);
			goto fail;
		}
		if (e->x_sampling != 1 || e->y_sampling != 1) {
			pm_seterr(err, "%s: channel '%s' is subsampled (%dx%d), which is not supported",
			          nm, e->name.str, e->x_sampling, e->y_sampling);
			goto fail;
		}
		if (e->pixel_type != EXR_PIXEL_UINT && e->pixel_type != EXR_PIXEL_HALF &&
		    e->pixel_type != EXR_PIXEL_FLOAT) {
			pm_seterr(err, "%s: channel '%s' has %s pixels", nm, e->name.str,
			          type_name(e->pixel_type));
			goto fail;
		}
	}
	if (pm_image_init(img, (int)w, (int)h, cl->num_channels, names, err)) {
		pm_preferr(err, "%s", nm);
		goto fail;
	}
	if (read_attrs(ctx, img, err) || read_pixels(ctx, storage, &dw, img, &s, err)) {
		pm_preferr(err, "%s", nm);
		goto fail;
	}
	exr_finish(&ctx);
	if (s.fd != STDIN_FILENO)
		close(s.fd);
	free(s.buf);
	return 0;
fail:
	if (ctx)
		exr_finish(&ctx);
	if (s.fd != STDIN_FILENO)
		close(s.fd);
	free(s.buf);
	pm_image_free(img);
	return -1;
}
