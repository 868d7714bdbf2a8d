/* test_image.c — EXR round trips, the reader on bad and unusual files, and
 * the pass-merging math of average.h against directly computed statistics. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <openexr.h>

#include "passes/average.h"
#include "check.h"
#include "passes/compare.h"
#include "formats/image.h"

static int
contains(const char *s, const char *sub)
{
	return strstr(s, sub) != NULL;
}

/* Deterministic values that exercise float bits: signs, tiny, huge. */
static float
pattern(int c, int x, int y)
{
	static const float odd[] = { 0.0f, -0.0f, 1e-40f, -3.0e38f, 0.1f, 1.0f / 3.0f };
	int i = (c * 131 + y * 17 + x) % 9;
	return i < 6 ? odd[i] : (float)(c + 1) * (x - 2.5f) / (y + 1.25f);
}

TEST(round_trip_channels_attributes)
{
	const char *names[] = { "R", "G", "B", "direct.R", "count", "m2.B" };
	pm_image a, b;
	pm_error err = { "" };
	int ok = 1;

	CHECK(pm_image_init(&a, 7, 5, 6, names, &err) == 0);
	for (int c = 0; c < 6; c++)
		for (int y = 0; y < 5; y++)
			for (int x = 0; x < 7; x++)
				a.px[((size_t)c * 5 + y) * 7 + x] = pattern(c, x, y);
	CHECK(pm_image_set_attr(&a, "pm.seed", "7", &err) == 0);
	CHECK(pm_image_set_attr(&a, "pm.command", "pm-render -s 7 'a b.pms' -o x.exr", &err) == 0);
	CHECK(pm_image_set_attr(&a, "pm.seed", "8", &err) == 0);     /* replaces */
	CHECK(pm_image_set_attr(&a, "pm.a_key_longer_than_thirty_one_bytes", "long", &err) == 0);
	CHECK(pm_image_set_attr(&a, "pm.empty", "", &err) == 0);
	CHECKF(pm_image_write_exr(&a, "rt.exr", &err) == 0, "%s", err.msg);
	CHECKF(pm_image_read_exr(&b, "rt.exr", &err) == 0, "%s", err.msg);
	CHECK(b.width == 7 && b.height == 5 && b.nchan == 6);
	/* Memory order is the file's order, which EXR sorts by name. */
	CHECKF(b.nchan == 6 && strcmp(b.chan[0], "B") == 0 && strcmp(b.chan[3], "count") == 0 &&
	       strcmp(b.chan[5], "m2.B") == 0, "%s %s %s", b.chan[0], b.chan[3], b.chan[5]);
	for (int c = 0; c < 6 && b.nchan == 6; c++) {
		const float *pa = pm_image_chan(&a, names[c]), *pb = pm_image_chan(&b, names[c]);
		CHECKF(pb != NULL, "channel %s", names[c]);
		for (int i = 0; pb && i < 35; i++)
			if (memcmp(&pa[i], &pb[i], sizeof(float)) != 0)
				ok = 0;
	}
	CHECKF(ok, "pixels differ after a round trip");
	CHECK(pm_image_attr(&b, "pm.seed") && strcmp(pm_image_attr(&b, "pm.seed"), "8") == 0);
	CHECK(pm_image_attr(&b, "pm.command") &&
	      strcmp(pm_image_attr(&b, "pm.command"), "pm-render -s 7 'a b.pms' -o x.exr") == 0);
	CHECK(pm_image_attr(&b, "pm.a_key_longer_than_thirty_one_bytes") &&
	      strcmp(pm_image_attr(&b, "pm.a_key_longer_than_thirty_one_bytes"), "long") == 0);
	CHECK(pm_image_attr(&b, "pm.empty") && strcmp(pm_image_attr(&b, "pm.empty"), "") == 0);
	CHECK(pm_image_attr(&b, "pm.missing") == NULL);
	CHECK(pm_image_chan(&b, "direct.G") == NULL);
	pm_image_free(&a);
	pm_image_free(&b);
}

TEST(add_channel_and_bad_init)
{
	const char *names[] = { "R", "R" };
	pm_image a;
	pm_error err = { "" };
	float *p;

	CHECK(pm_image_init(&a, 4, 4, 2, names, &err) == -1 && contains(err.msg, "duplicate channel 'R'"));
	CHECK(pm_image_init(&a, 0, 4, 1, names, &err) == -1 && contains(err.msg, "empty"));
	CHECK(pm_image_init(&a, 1 << 15, 1 << 14, 1, names, &err) == -1 && contains(err.msg, "exceeds"));
	CHECK(pm_image_init(&a, 3, 2, 1, names, &err) == 0);
	a.px[5] = 9;
	p = pm_image_add_chan(&a, "size", &err);
	CHECK(p && a.nchan == 2 && p[0] == 0 && p[5] == 0 && pm_image_chan(&a, "R")[5] == 9);
	CHECK(pm_image_add_chan(&a, "size", &err) == NULL && contains(err.msg, "duplicate"));
	CHECK(pm_image_add_chan(&a, "a.name.that.is.much.too.long.for.pm", &err) == NULL &&
	      contains(err.msg, "longer than 31"));
	pm_image_free(&a);
}

static void
write_bytes(const char *path, const void *p, size_t n)
{
	FILE *f = fopen(path, "wb");
	if (f) {
		fwrite(p, 1, n, f);
		fclose(f);
	}
}

static size_t
read_all(const char *path, unsigned char **buf)
{
	FILE *f = fopen(path, "rb");
	size_t n = 0, cap = 1 << 20;

	*buf = malloc(cap);
	if (f && *buf) {
		n = fread(*buf, 1, cap, f);
		fclose(f);
	}
	return n;
}

TEST(reader_refuses_bad_files)
{
	const char *names[] = { "R", "G", "B" };
	pm_image a, b;
	pm_error err = { "" };
	unsigned char *buf;
	size_t n;
	uint32_t s = 1;

	CHECK(pm_image_read_exr(&b, "missing.exr", &err) == -1);
	CHECKF(contains(err.msg, "'missing.exr'") && contains(err.msg, "No such file"), "%s", err.msg);
	write_bytes("empty.exr", "", 0);
	CHECK(pm_image_read_exr(&b, "empty.exr", &err) == -1);
	CHECKF(strcmp(err.msg, "'empty.exr': not an OpenEXR file") == 0, "%s", err.msg);
	write_bytes("text.exr", "P3\n1 1\n255\n0 0 0\n", 17);
	CHECK(pm_image_read_exr(&b, "text.exr", &err) == -1);
	CHECKF(strcmp(err.msg, "'text.exr': not an OpenEXR file") == 0, "%s", err.msg);

	/* Noise does not compress, so half the file is half the pixels. */
	CHECK(pm_image_init(&a, 64, 64, 3, names, &err) == 0);
	for (size_t i = 0; i < 3 * 64 * 64; i++) {
		s = s * 1664525u + 1013904223u;
		a.px[i] = (float)(s >> 8) / (1 << 24);
	}
	CHECKF(pm_image_write_exr(&a, "full.exr", &err) == 0, "%s", err.msg);
	n = read_all("full.exr", &buf);
	CHECK(n > 3 * 64 * 64 * 3);
	write_bytes("half.exr", buf, n / 2);
	CHECK(pm_image_read_exr(&b, "half.exr", &err) == -1);
	CHECKF(contains(err.msg, "'half.exr': truncated or corrupt"), "%s", err.msg);
	printf("# %s\n", err.msg);
	CHECK(b.px == NULL && b.nchan == 0);
	write_bytes("head.exr", buf, 40);
	CHECK(pm_image_read_exr(&b, "head.exr", &err) == -1);
	CHECKF(strncmp(err.msg, "'head.exr': ", 12) == 0 && !strchr(err.msg, '\n'), "%s", err.msg);
	printf("# %s\n", err.msg);
	free(buf);
	/* Writing into a directory that does not exist fails and names it. */
	CHECK(pm_image_write_exr(&a, "no/such/dir/x.exr", &err) == -1);
	CHECKF(contains(err.msg, "'no/such/dir/x.exr'"), "%s", err.msg);
	pm_image_free(&a);
}

/* Writes an EXR with the core API directly, to give the reader what pm
 * never writes: half and uint channels, tiles with partial edge tiles, a
 * data window off the origin. Channel "H" (half) = h[i], "U" (uint) = u[i]. */
static int
write_odd_exr(const char *path, int tiled, int w, int h, int x0, int y0,
              const uint16_t *hv, const uint32_t *uv)
{
	exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
	exr_context_t ctx;
	exr_encode_pipeline_t enc = EXR_ENCODE_PIPELINE_INITIALIZER;
	exr_attr_box2i_t dw;
	exr_result_t rv;
	int part, first = 1;
	int32_t spc = 1;
	const int tw = 4, th = 3;

	dw.min.x = x0;
	dw.min.y = y0;
	dw.max.x = x0 + w - 1;
	dw.max.y = y0 + h - 1;
	rv = exr_start_write(&ctx, path, EXR_WRITE_FILE_DIRECTLY, &init);
	if (rv)
		return rv;
	rv = exr_add_part(ctx, NULL, tiled ? EXR_STORAGE_TILED : EXR_STORAGE_SCANLINE, &part);
	if (!rv)
		rv = exr_initialize_required_attr_simple(ctx, 0, w, h, EXR_COMPRESSION_ZIPS);
	if (!rv)
		rv = exr_set_data_window(ctx, 0, &dw);
	if (!rv && tiled)
		rv = exr_set_tile_descriptor(ctx, 0, tw, th, EXR_TILE_ONE_LEVEL, EXR_TILE_ROUND_DOWN);
	if (!rv)
		rv = exr_add_channel(ctx, 0, "H", EXR_PIXEL_HALF, EXR_PERCEPTUALLY_LINEAR, 1, 1);
	if (!rv)
		rv = exr_add_channel(ctx, 0, "U", EXR_PIXEL_UINT, EXR_PERCEPTUALLY_LINEAR, 1, 1);
	if (!rv)
		rv = exr_attr_set_string(ctx, 0, "pm.note", "odd");
	if (!rv)
		rv = exr_write_header(ctx);
	if (!rv && !tiled)
		rv = exr_get_scanlines_per_chunk(ctx, 0, &spc);
	for (int ty = 0; !rv && ty * (tiled ? th : spc) < h; ty++)
		for (int tx = 0; !rv && tx * (tiled ? tw : w) < w; tx++) {
			exr_chunk_info_t ci;
			int px = tiled ? tx * tw : 0, py = ty * (tiled ? th : spc);
			rv = tiled ? exr_write_tile_chunk_info(ctx, 0, tx, ty, 0, 0, &ci)
			           : exr_write_scanline_chunk_info(ctx, 0, y0 + py, &ci);
			if (!rv)
				rv = first ? exr_encoding_initialize(ctx, 0, &ci, &enc)
				           : exr_encoding_update(ctx, 0, &ci, &enc);
			for (int i = 0; !rv && i < enc.channel_count; i++) {
				exr_coding_channel_info_t *ch = &enc.channels[i];
				int isu = strcmp(ch->channel_name, "U") == 0;
				ch->user_pixel_stride = isu ? 4 : 2;
				ch->user_line_stride = w * (isu ? 4 : 2);
				ch->user_bytes_per_element = isu ? 4 : 2;
				ch->user_data_type = isu ? EXR_PIXEL_UINT : EXR_PIXEL_HALF;
				ch->encode_from_ptr = isu ? (const uint8_t *)(uv + py * w + px)
				                          : (const uint8_t *)(hv + py * w + px);
			}
			if (!rv && first)
				rv = exr_encoding_choose_default_routines(ctx, 0, &enc);
			first = 0;
			if (!rv)
				rv = exr_encoding_run(ctx, 0, &enc);
		}
	if (!first)
		exr_encoding_destroy(ctx, &enc);
	return exr_finish(&ctx) || rv;
}

TEST(reader_half_uint_tiled_offset)
{
	enum { W = 10, H = 7 };
	/* Half bit patterns and the values they stand for. */
	static const uint16_t hbits[] = { 0x3c00, 0x3800, 0xc000, 0x7bff, 0x0001, 0x0000 };
	static const float hval[] = { 1.0f, 0.5f, -2.0f, 65504.0f, 5.9604645e-8f, 0.0f };
	uint16_t hv[W * H];
	uint32_t uv[W * H];
	pm_error err = { "" };
	pm_image b;

	for (int i = 0; i < W * H; i++) {
		hv[i] = hbits[i % 6];
		uv[i] = i == 5 ? 4000000000u : (uint32_t)i * 3;
	}
	for (int tiled = 0; tiled < 2; tiled++) {
		const char *path = tiled ? "tiled.exr" : "scan.exr";
		int bad = 0;
		CHECKF(write_odd_exr(path, tiled, W, H, 3, -2, hv, uv) == 0, "writing %s", path);
		CHECKF(pm_image_read_exr(&b, path, &err) == 0, "%s", err.msg);
		CHECKF(b.width == W && b.height == H && b.nchan == 2, "%dx%d %d", b.width, b.height, b.nchan);
		if (b.nchan != 2)
			continue;
		for (int i = 0; i < W * H; i++) {
			if (pm_image_chan(&b, "H")[i] != hval[i % 6])
				bad++;
			if (pm_image_chan(&b, "U")[i] != (float)uv[i])
				bad++;
		}
		CHECKF(bad == 0, "%s: %d wrong values", path, bad);
		CHECK(pm_image_attr(&b, "pm.note") && strcmp(pm_image_attr(&b, "pm.note"), "odd") == 0);
		pm_image_free(&b);
	}
}

TEST(reader_bounds_size_before_allocating)
{
	const char *names[] = { "R" };
	pm_image a, b;
	pm_error err = { "" };
	unsigned char *buf, *dw = NULL;
	size_t n;
	int32_t big = 19999;

	/* A valid 2x2 file whose header then claims 20000 x 20000 pixels:
	 * "dataWindow\0box2i\0", size 16, then xmin ymin xmax ymax (LE). */
	CHECK(pm_image_init(&a, 2, 2, 1, names, &err) == 0);
	CHECK(pm_image_write_exr(&a, "small.exr", &err) == 0);
	pm_image_free(&a);
	n = read_all("small.exr", &buf);
	for (size_t i = 0; i + 40 < n && !dw; i++)
		if (memcmp(buf + i, "dataWindow\0box2i\0", 17) == 0)
			dw = buf + i + 17 + 4;
	CHECK(dw != NULL);
	if (dw) {
		for (int k = 0; k < 4; k++) {
			dw[8 + k] = (unsigned char)(big >> (8 * k));
			dw[12 + k] = (unsigned char)(big >> (8 * k));
		}
		write_bytes("huge.exr", buf, n);
		CHECK(pm_image_read_exr(&b, "huge.exr", &err) == -1);
		CHECKF(strcmp(err.msg, "'huge.exr': image size 20000x20000 exceeds 33554432 pixels (PM_MAX_PIXELS)") == 0,
		       "%s", err.msg);
	}
	free(buf);
}

/* ---- merging ---- */

enum { NP = 64, LEN = 5 };

static float
pass_value(int p, int i)
{
	uint32_t s = (uint32_t)(p * 7919 + i * 104729 + 12345);
	s ^= s << 13;
	s ^= s >> 17;
	s ^= s << 5;
	return 0.1f * (float)i + (float)(s % 100000) / 25000.0f;
}

static double
relerr(double a, double b)
{
	return fabs(a - b) / fmax(fabs(b), 1e-300);
}

TEST(chan_merge_any_grouping)
{
	double mean1[LEN] = { 0 }, m21[LEN] = { 0 };          /* one by one */
	double meanA[LEN] = { 0 }, m2A[LEN] = { 0 };          /* first half */
	double meanB[LEN] = { 0 }, m2B[LEN] = { 0 };          /* second half */
	double meanT[NP][LEN], m2T[NP][LEN];                  /* pairwise tree */
	float fm[LEN], fm2[LEN];
	int bad = 0;

	for (int p = 0; p < NP; p++) {
		float x[LEN];
		for (int i = 0; i < LEN; i++)
			x[i] = pass_value(p, i);
		pm_moments_merge(p, mean1, m21, 1, x, NULL, LEN);
		if (p < NP / 2)
			pm_moments_merge(p, meanA, m2A, 1, x, NULL, LEN);
		else
			pm_moments_merge(p - NP / 2, meanB, m2B, 1, x, NULL, LEN);
		for (int i = 0; i < LEN; i++)
			meanT[p][i] = x[i], m2T[p][i] = 0;
	}
	/* Halves merged as files would be: the second half's stats as float. */
	for (int i = 0; i < LEN; i++)
		fm[i] = (float)meanB[i], fm2[i] = (float)m2B[i];
	pm_moments_merge(NP / 2, meanA, m2A, NP / 2, fm, fm2, LEN);
	/* A balanced tree of merges, as averages of averages across machines. */
	for (int step = 1; step < NP; step *= 2)
		for (int p = 0; p + step < NP; p += 2 * step) {
			for (int i = 0; i < LEN; i++)
				fm[i] = (float)meanT[p + step][i], fm2[i] = (float)m2T[p + step][i];
			pm_moments_merge(step, meanT[p], m2T[p], step, fm, fm2, LEN);
		}
	for (int i = 0; i < LEN; i++) {
		double sum = 0, mean, ss = 0;
		for (int p = 0; p < NP; p++)
			sum += pass_value(p, i);
		mean = sum / NP;
		for (int p = 0; p < NP; p++)
			ss += (pass_value(p, i) - mean) * (pass_value(p, i) - mean);
		/* Sample variance, computed directly in double (two-pass). */
		if (relerr(mean1[i], mean) > 1e-6 || relerr(meanA[i], mean) > 1e-6 ||
		    relerr(meanT[0][i], mean) > 1e-6)
			bad++, printf("# mean %d: %.9g %.9g %.9g want %.9g\n", i, mean1[i], meanA[i], meanT[0][i], mean);
		if (relerr(m21[i] / (NP - 1), ss / (NP - 1)) > 1e-6 || relerr(m2A[i], ss) > 1e-6 ||
		    relerr(m2T[0][i], ss) > 1e-6)
			bad++, printf("# M2 %d: %.9g %.9g %.9g want %.9g\n", i, m21[i], m2A[i], m2T[0][i], ss);
	}
	CHECKF(bad == 0, "%d disagreements", bad);
	CHECK(pm_moments_stderr(1, 5) == 0 && pm_moments_stderr(0, 0) == 0);
	CHECKF(fabs(pm_moments_stderr(5, 8) - sqrt(8.0 / 4 / 5)) < 1e-15, "%g", pm_moments_stderr(5, 8));
}

static void
pass_image(pm_image *img, int p, int w, int h)
{
	const char *names[] = { "R", "G", "B", "direct.R", "extra" };
	pm_error err;

	pm_image_init(img, w, h, p == 3 ? 4 : 5, names, &err);
	for (int c = 0; c < img->nchan; c++)
		for (int i = 0; i < w * h; i++)
			img->px[(size_t)c * w * h + i] = pass_value(p, c * 7 + i);
}

TEST(avg_images_equal_average_of_averages)
{
	enum { W = 3, H = 2 };
	pm_avg all, half[2], top;
	pm_image img, out[2], res_all, res_top;
	pm_error err = { "" };
	double n;
	int bad = 0;

	pm_avg_init(&all);
	pm_avg_init(&half[0]);
	pm_avg_init(&half[1]);
	pm_avg_init(&top);
	for (int p = 0; p < 10; p++) {
		pass_image(&img, p, W, H);
		CHECKF(pm_avg_add(&all, &img, 1, &err) == 0, "%s", err.msg);
		CHECKF(pm_avg_add(&half[p >= 4], &img, 1, &err) == 0, "%s", err.msg);
		pm_image_free(&img);
	}
	/* Pass 3 lacks "extra", so it is dropped from the halves holding it. */
	CHECK(all.nchan == 4 && half[0].nchan == 4 && half[1].nchan == 5);
	for (int k = 0; k < 2; k++) {
		CHECK(pm_avg_image(&half[k], &out[k], &err) == 0);
		CHECK(pm_image_passes(&out[k], &n, &err) == 0 && n == (k ? 6 : 4));
		CHECK(pm_avg_add(&top, &out[k], n, &err) == 0);
	}
	CHECK(top.n == 10 && top.nchan == 4);
	CHECK(pm_avg_image(&all, &res_all, &err) == 0 && pm_avg_image(&top, &res_top, &err) == 0);
	CHECK(res_all.nchan == 10 && res_top.nchan == 10);
	for (int c = 0; c < res_all.nchan && res_top.nchan == res_all.nchan; c++) {
		const float *a = res_all.px + (size_t)c * W * H, *b = pm_image_chan(&res_top, res_all.chan[c]);
		for (int i = 0; b && i < W * H; i++)
			if (fabs(a[i] - b[i]) > 1e-5 * fmax(fabs(a[i]), 1e-3))
				bad++;
	}
	CHECKF(bad == 0, "%d values differ", bad);
	/* stderr = sqrt(M2 / (n-1) / n) from the direct sample variance. */
	{
		double sum = 0, ss = 0, mean;
		for (int p = 0; p < 10; p++)
			sum += pass_value(p, 1 * 7 + 4);
		mean = sum / 10;
		for (int p = 0; p < 10; p++)
			ss += pow(pass_value(p, 1 * 7 + 4) - mean, 2);
		CHECKF(fabs(pm_image_chan(&res_all, "G")[4] - mean) < 1e-6, "%g %g", pm_image_chan(&res_all, "G")[4], mean);
		CHECKF(relerr(pm_image_chan(&res_all, "stderr.G")[4], sqrt(ss / 9 / 10)) < 1e-6, "%g %g",
		       pm_image_chan(&res_all, "stderr.G")[4], sqrt(ss / 9 / 10));
	}
	pm_image_free(&out[0]);
	pm_image_free(&out[1]);
	pm_image_free(&res_all);
	pm_image_free(&res_top);
	pm_avg_free(&all);
	pm_avg_free(&half[0]);
	pm_avg_free(&half[1]);
	pm_avg_free(&top);
}

TEST(avg_refusals)
{
	pm_avg a;
	pm_image img, small;
	pm_error err = { "" };
	const char *gb[] = { "G", "B" };
	double n;

	pm_avg_init(&a);
	pass_image(&img, 0, 4, 3);
	CHECK(pm_avg_add(&a, &img, 2, &err) == 0);
	pass_image(&small, 0, 3, 3);
	CHECK(pm_avg_add(&a, &small, 1, &err) == -1 && strcmp(err.msg, "size 3x3 differs from 4x3") == 0);
	pm_image_free(&small);
	pm_image_chan(&img, "B")[2 * 4 + 1] = NAN;
	CHECK(pm_avg_add(&a, &img, 1, &err) == -1);
	CHECKF(strcmp(err.msg, "channel 'B' pixel (1, 2) is nan") == 0, "%s", err.msg);
	pm_image_chan(&img, "B")[2 * 4 + 1] = 0;
	pm_image_chan(&img, "extra")[3] = -INFINITY;
	CHECK(pm_avg_add(&a, &img, 1, &err) == -1 && strcmp(err.msg, "channel 'extra' pixel (3, 0) is inf") == 0);
	CHECK(a.n == 2);
	pm_image_free(&img);
	CHECK(pm_image_init(&img, 4, 3, 2, gb, &err) == 0);
	CHECK(pm_avg_add(&a, &img, 1, &err) == -1 && strcmp(err.msg, "no channel 'R'") == 0);
	CHECK(pm_image_passes(&img, &n, &err) == 0 && n == 1);
	pm_image_set_attr(&img, "pm.passes", "3x", &err);
	CHECK(pm_image_passes(&img, &n, &err) == -1 && contains(err.msg, "'3x'"));
	pm_image_set_attr(&img, "pm.passes", "0", &err);
	CHECK(pm_image_passes(&img, &n, &err) == -1);
	pm_image_set_attr(&img, "pm.passes", "-1", &err);
	CHECK(pm_image_passes(&img, &n, &err) == -1);
	pm_image_set_attr(&img, "pm.passes", "12", &err);
	CHECK(pm_image_passes(&img, &n, &err) == 0 && n == 12);
	pm_image_free(&img);
	pm_avg_free(&a);
}

TEST(compare_metrics)
{
	float a0[4] = { 1, 1, 1, 1 }, b0[4] = { 1.5f, 1.5f, 1.5f, 0 }, z[4] = { 0, 0, 0, 0 };
	float mask[4] = { 1, 0, 0.6f, 0.5f };
	const float *a[3] = { a0, a0, a0 }, *b[3] = { b0, b0, b0 };
	pm_diff d;
	pm_error err = { "" };

	CHECK(pm_compare(a, b, NULL, 2, 2, &d, &err) == 0);
	CHECK(d.pixels == 4);
	CHECKF(fabs(d.rmse - sqrt((3 * 0.25 + 1) / 4)) < 1e-12, "%g", d.rmse);
	CHECKF(fabs(d.mae - (3 * 0.5 + 1) / 4) < 1e-12, "%g", d.mae);
	CHECKF(fabs(d.relmse - (3 * 0.25 / 2.26 + 1 / 0.01) / 4) < 1e-9, "%g", d.relmse);
	CHECK(d.max_abs == 1 && d.mean_a == 1 && fabs(d.mean_b - 4.5 / 4) < 1e-12);
	CHECK(pm_compare(a, b, mask, 2, 2, &d, &err) == 0);
	CHECK(d.pixels == 2 && fabs(d.rmse - 0.5) < 1e-12 && d.max_abs == 0.5);
	CHECK(pm_compare(a, b, z, 2, 2, &d, &err) == -1 && strcmp(err.msg, "mask selects no pixels") == 0);
}

int
main(void)
{
	RUN(round_trip_channels_attributes);
	RUN(add_channel_and_bad_init);
	RUN(reader_refuses_bad_files);
	RUN(reader_half_uint_tiled_offset);
	RUN(reader_bounds_size_before_allocating);
	RUN(chan_merge_any_grouping);
	RUN(avg_images_equal_average_of_averages);
	RUN(avg_refusals);
	RUN(compare_metrics);
	return check_done();
}
