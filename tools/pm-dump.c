/* pm-dump — inspects a photon file or map (formats/photons.md): its header,
 * statistics, the photons as TSV or a PLY point cloud, or the k nearest
 * photons of a point. Reads through the library's one photon reader; with
 * --header it also shows a pass image's provenance (formats/image.md). */
#define _GNU_SOURCE
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/atomic.h"
#include "formats/image.h"
#include "formats/kdtree.h"
#include "formats/photonfile.h"
#include "options.h"
#include "util.h"

static const char usage[] =
	"pm-dump [-h] [-k K] [--metric l2|linf] [-o FILE|-] "
	"--stats|--header|--tsv|--ply|--near X,Y,Z FILE|-";
enum { O_HEADER = OPT_LONG, O_METRIC, O_NEAR, O_PLY, O_STATS, O_TSV };

static const opt opts[] = {
	{ O_HEADER, "header", NULL, "the header lines as stored (reads only the header, so "
	  "it works on a truncated file); for an EXR image, its "
	  "size, channels and string attributes as key=value", NULL, 0 },
	{ O_NEAR, "near", "X,Y,Z", "the K nearest photons of the point, nearest first, with "
	  "their index and distance (photon maps only)", NULL, 0 },
	{ O_PLY, "ply", NULL, "an ASCII PLY point cloud: position, colour from the "
	  "flux (tone-mapped), normal = psi", NULL, 0 },
	{ O_STATS, "stats", NULL, "key: value statistics", NULL, 0 },
	{ O_TSV, "tsv", NULL, "one line per photon: x y z psi_x psi_y psi_z r g b (flux)", NULL, 0 },
	{ 'k', "neighbours", "K", "neighbours for --near", "10", 0 },
	{ O_METRIC, "metric", "M", "distance for --near: l2 (sphere) or linf (cube)", "l2", 0 },
	{ 'o', "output", "FILE", "write here, - for stdout", "-", 0 },
	{ 0, NULL, NULL, NULL, NULL, 0 },
};

static const tool dump = {
	usage,
	"Prints what a photon file or photon map holds: one of --header, --near,\n"
	"--ply, --stats and --tsv.",
	opts, NULL,
};

enum { M_NONE, M_HEADER, M_NEAR, M_PLY, M_STATS, M_TSV };

static void
print_header(FILE *o, const char *raw)
{
	/* everything before the blank line that ends the header */
	const char *end = strstr(raw, "\n\n");
	fwrite(raw, 1, end ? (size_t)(end - raw) + 1 : strlen(raw), o);
}

/* 1 if the named file begins with the OpenEXR magic number. */
static int
is_exr(const char *name)
{
	static const unsigned char magic[4] = {0x76, 0x2f, 0x31, 0x01};
	unsigned char b[4];
	FILE *f = strcmp(name, "-") == 0 ? NULL : fopen(name, "rb");
	int yes = f && fread(b, 1, 4, f) == 4 && memcmp(b, magic, 4) == 0;

	if (f)
		fclose(f);
	return yes;
}

/* An image's header as key=value lines: a value of several lines (the
 * command history) gives one line per line, as in a photon file. */
static void
print_exr_header(FILE *o, const pm_image *img)
{
	fprintf(o, "format=exr\nsize=%d %d\nchannels=", img->width, img->height);
	for (int c = 0; c < img->nchan; c++)
		fprintf(o, "%s%s", c ? " " : "", img->chan[c]);
	fputc('\n', o);
	for (int i = 0; i < img->nattr; i++) {
		const char *v = img->attr[i].value;
		do {
			size_t n = strcspn(v, "\n");
			fprintf(o, "%s=", img->attr[i].key);
			for (size_t j = 0; j < n; j++)
				fputc((unsigned char)v[j] < 0x20 ? '?' : v[j], o);
			fputc('\n', o);
			v += n + (v[n] == '\n');
		} while (*v);
	}
}

static void
print_stats(FILE *o, const pm_photons *ph, size_t header_bytes)
{
	const pm_photon_header *h = &ph->h;
	double sum[3] = {0, 0, 0}, e = h->emitted ? (double)h->emitted : 1;

	for (size_t i = 0; i < h->count; i++) {
		pm_vec3 p = pm_photon_power(&ph->p[i]);
		sum[0] += p.x;
		sum[1] += p.y;
		sum[2] += p.z;
	}
	for (int c = 0; c < 3; c++)
		sum[c] /= e;
	fprintf(o, "format: %s\n", h->kdtree ? "photonmap" : "photons");
	fprintf(o, "version: %d\n", h->version);
	fprintf(o, "map: %s\n", pm_map_name(h->map));
	fprintf(o, "photons: %llu\n", (unsigned long long)h->count);
	fprintf(o, "emitted: %llu\n", (unsigned long long)h->emitted);
	fprintf(o, "bytes_per_photon: %d\n", PM_PHOTON_BYTES);
	fprintf(o, "bbox: %.9g %.9g %.9g %.9g %.9g %.9g\n", h->bbox[0], h->bbox[1], h->bbox[2],
	        h->bbox[3], h->bbox[4], h->bbox[5]);
	fprintf(o, "total_power: %.9g %.9g %.9g\n", sum[0], sum[1], sum[2]);
	if (h->count)
		fprintf(o, "mean_power: %.9g %.9g %.9g\n", sum[0] / (double)h->count,
		        sum[1] / (double)h->count, sum[2] / (double)h->count);
	else
		fprintf(o, "mean_power: 0 0 0\n");
	fprintf(o, "light_hash: %016llx\n", (unsigned long long)h->light_hash);
	fprintf(o, "seeds: %s\n", h->seeds);
	fprintf(o, "light_paths: %s\n", h->light_paths);
	fprintf(o, "time: %.17g\n", h->time);
	if (h->kdtree)
		fprintf(o, "tree_depth: %d\n", pm_kd_depth((size_t)h->count));
	fprintf(o, "file_bytes: %llu\n",
	        (unsigned long long)(header_bytes + (size_t)h->count * PM_PHOTON_BYTES));
	for (const char *s = h->history; s && *s;) {
		size_t n = strcspn(s, "\n");
		fprintf(o, "command: %.*s\n", (int)n, s);
		s += n + (s[n] != 0);
	}
}

static void
print_photon(FILE *o, const pm_photon *p, double e)
{
	pm_vec3 d = pm_photon_dir(p), w = pm_photon_power(p);
	fprintf(o, "%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\t%.9g\n",
	        p->pos[0], p->pos[1], p->pos[2], d.x, d.y, d.z, w.x / e, w.y / e, w.z / e);
}

static const char tsv_head[] = "x\ty\tz\tpsi_x\tpsi_y\tpsi_z\tr\tg\tb\n";

static void
print_tsv(FILE *o, const pm_photons *ph)
{
	double e = ph->h.emitted ? (double)ph->h.emitted : 1;
	fputs(tsv_head, o);
	for (size_t i = 0; i < ph->h.count; i++)
		print_photon(o, &ph->p[i], e);
}

/* Colours scale the flux so that the mean photon's brightest channel sits
 * at half range, then apply a 1/2.2 display gamma. */
static void
print_ply(FILE *o, const pm_photons *ph, const char *name)
{
	double ref = 0;
	size_t n = (size_t)ph->h.count;

	for (size_t i = 0; i < n; i++)
		ref += pm_maxc(pm_photon_power(&ph->p[i]));
	ref = n && ref > 0 ? 2 * ref / (double)n : 1;
	fprintf(o, "ply\nformat ascii 1.0\ncomment pm-dump --ply of %s\n"
	        "element vertex %zu\nproperty float x\nproperty float y\nproperty float z\n"
	        "property uchar red\nproperty uchar green\nproperty uchar blue\n"
	        "property float nx\nproperty float ny\nproperty float nz\nend_header\n",
	        strcmp(name, "-") ? name : "stdin", n);
	for (size_t i = 0; i < n; i++) {
		const pm_photon *p = &ph->p[i];
		pm_vec3 d = pm_photon_dir(p), w = pm_photon_power(p);
		double c[3] = {w.x, w.y, w.z};
		int u[3];
		for (int k = 0; k < 3; k++)
			u[k] = (int)(255 * pow(fmin(1, c[k] / ref), 1 / 2.2) + 0.5);
		fprintf(o, "%.9g %.9g %.9g %d %d %d %.9g %.9g %.9g\n", p->pos[0], p->pos[1], p->pos[2],
		        u[0], u[1], u[2], d.x, d.y, d.z);
	}
}

static int
nncmp(const void *a, const void *b)
{
	const pm_nn *x = a, *y = b;
	if (x->d != y->d)
		return x->d < y->d ? -1 : 1;
	return x->idx < y->idx ? -1 : x->idx > y->idx;
}

static void
print_near(FILE *o, const pm_photons *ph, const float x[3], int k, enum pm_metric m)
{
	pm_nn *nn;

	if ((uint64_t)k > ph->h.count)      /* no more neighbours than photons */
		k = ph->h.count ? (int)ph->h.count : 1;
	nn = malloc((size_t)k * sizeof *nn);
	double e = ph->h.emitted ? (double)ph->h.emitted : 1;
	float dfar;
	int got;

	if (!nn)
		die("out of memory for %d neighbours", k);
	got = pm_kd_knn(ph->p, (size_t)ph->h.count, x, k, m, INFINITY, nn, &dfar);
	qsort(nn, (size_t)got, sizeof *nn, nncmp);
	fputs("index\tdistance\t", o);
	fputs(tsv_head, o);
	for (int i = 0; i < got; i++) {
		fprintf(o, "%u\t%.9g\t", nn[i].idx, m == PM_L2 ? sqrt(nn[i].d) : (double)nn[i].d);
		print_photon(o, &ph->p[nn[i].idx], e);
	}
	free(nn);
}

static void
parse_point(const char *s, float x[3])
{
	char buf[256], *parts[3], *save = NULL;
	int n = 0;

	if (strlen(s) >= sizeof buf)
		usage_err(usage, "--near: '%.40s...' is too long", s);
	strcpy(buf, s);
	for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
		if (n == 3)
			usage_err(usage, "--near: '%s' is not X,Y,Z", s);
		parts[n++] = t;
	}
	if (n != 3 || strstr(s, ",,") || s[0] == ',' || s[strlen(s) - 1] == ',')
		usage_err(usage, "--near: '%s' is not X,Y,Z", s);
	for (int i = 0; i < 3; i++)
		x[i] = (float)parse_real(parts[i], -3.4e38, 3.4e38, "--near", usage);
}

int
main(int argc, char **argv)
{
	const char *out = "-", *name;
	char *raw = NULL, fn[600];
	int mode = M_NONE, k = 10, kset = 0, mset = 0, c;
	enum pm_metric metric = PM_L2;
	float x[3] = {0, 0, 0};
	pm_photons ph;
	pm_error err;
	FILE *f;
	pm_out o;

	opt_init(&dump, argc, argv);
	while ((c = opt_next(&dump, argc, argv)) != -1) {
		int m = M_NONE;
		switch (c) {
		case 'k': k = (int)parse_int(optarg, 1, 10000000, "-k", usage); kset = 1; break;
		case 'o': out = optarg; break;
		case O_HEADER: m = M_HEADER; break;
		case O_METRIC:
			if (strcmp(optarg, "l2") == 0)
				metric = PM_L2;
			else if (strcmp(optarg, "linf") == 0)
				metric = PM_LINF;
			else
				usage_err(usage, "--metric: '%s' is not l2 or linf", optarg);
			mset = 1;
			break;
		case O_NEAR: m = M_NEAR; parse_point(optarg, x); break;
		case O_PLY: m = M_PLY; break;
		case O_STATS: m = M_STATS; break;
		case O_TSV: m = M_TSV; break;
		}
		if (m != M_NONE) {
			if (mode != M_NONE && mode != m)
				usage_err(usage, "give only one of --header, --near, --ply, --stats, --tsv");
			mode = m;
		}
	}
	if (mode == M_NONE)
		usage_err(usage, "give one of --header, --near, --ply, --stats, --tsv");
	if ((kset || mset) && mode != M_NEAR)
		usage_err(usage, "-k and --metric go with --near");
	if (argc - optind != 1)
		usage_err(usage, argc - optind ? "give exactly one FILE" : "no FILE given (- reads stdin)");
	name = argv[optind];
	shown_name(name, fn, sizeof fn);
	check_output(usage, out, mode == M_PLY ? OUT_PLY : OUT_TEXT, argv + optind, 1);

	if (is_exr(name)) {
		pm_image img;
		if (mode != M_HEADER)
			die("%s: an OpenEXR image: only --header reads images", fn);
		if (pm_image_read_exr(&img, name, &err) || pm_out_open(&o, out, &err))
			die_err(&err);
		print_exr_header(o.f, &img);
		if (pm_out_commit(&o, &err))
			die_err(&err);
		pm_image_free(&img);
		return 0;
	}
	f = open_input(name);
	if (pm_photons_read_header(&ph, f, name, &raw, &err))
		die_err(&err);
	if (mode != M_HEADER && pm_photons_read_records(&ph, f, name, &err))
		die_err(&err);
	if (f != stdin)
		fclose(f);
	if (mode == M_NEAR && !ph.h.kdtree)
		die("%s: a photon file, not a photon map (kdtree=0); run pm-build on it first", fn);

	if (pm_out_open(&o, out, &err))
		die_err(&err);
	switch (mode) {
	case M_HEADER: print_header(o.f, raw); break;
	case M_NEAR: print_near(o.f, &ph, x, k, metric); break;
	case M_PLY: print_ply(o.f, &ph, name); break;
	case M_STATS: print_stats(o.f, &ph, strlen(raw)); break;
	case M_TSV: print_tsv(o.f, &ph); break;
	}
	if (pm_out_commit(&o, &err))
		die_err(&err);
	free(raw);
	pm_photons_free(&ph);
	return 0;
}
