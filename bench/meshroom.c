/* meshroom.c — writes a room of curved meshes as a modelling program's
 * primitives come out (a UV sphere on a shelf, a torus and an open tube on
 * the floor, a lumpy subdivided head), all triangulated, for the benchmark
 * of the compensated estimate's cost on dense meshes (bench/compcost.sh).
 *
 *   meshroom [-r RES] [-s SIZE] DIR
 *
 * RES scales every mesh's resolution (1: a 48 x 24 sphere, a 48 x 16 torus,
 * a 48-sided tube, a head of 20 480 triangles; about 25 000 triangles in
 * all). Writes DIR/meshroom.pms and its OBJ files; the camera is SIZE x SIZE
 * (default 256). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define PI 3.14159265358979323846

static void
die(const char *msg, const char *what)
{
	fprintf(stderr, "meshroom: %s '%s'\n", msg, what);
	exit(1);
}

static FILE *
create(const char *dir, const char *name)
{
	char path[4096];
	FILE *f;

	snprintf(path, sizeof path, "%s/%s", dir, name);
	f = fopen(path, "w");
	if (!f)
		die("cannot create", path);
	return f;
}

static void
done(FILE *f, const char *name)
{
	if (ferror(f) || fclose(f))
		die("cannot write", name);
}

/* A grid of nu x nv quads, each as two triangles, over vertices v(i, j);
 * wrapu/wrapv: the last row meets the first. Vertex numbers from 1. */
static void
grid(FILE *f, int nu, int nv, int wrapu, int wrapv, int rowlen)
{
	for (int i = 0; i < nu; i++)
		for (int j = 0; j < nv; j++) {
			int i1 = wrapu ? (i + 1) % nu : i + 1, j1 = wrapv ? (j + 1) % nv : j + 1;
			int a = 1 + i * rowlen + j, b = 1 + i1 * rowlen + j;
			int c = 1 + i1 * rowlen + j1, d = 1 + i * rowlen + j1;
			fprintf(f, "f %d %d %d\nf %d %d %d\n", a, b, c, a, c, d);
		}
}

/* UV sphere: nu segments, nv rings, poles as fans (closed). */
static void
uvsphere(FILE *f, int nu, int nv, double r)
{
	fprintf(f, "v 0 %.9g 0\n", r);
	for (int j = 1; j < nv; j++)
		for (int i = 0; i < nu; i++) {
			double th = PI * j / nv, ph = 2 * PI * i / nu;
			fprintf(f, "v %.9g %.9g %.9g\n", r * sin(th) * cos(ph), r * cos(th), -r * sin(th) * sin(ph));
		}
	fprintf(f, "v 0 %.9g 0\n", -r);
	int last = 2 + (nv - 1) * nu;
	for (int i = 0; i < nu; i++)
		fprintf(f, "f 1 %d %d\n", 2 + i, 2 + (i + 1) % nu);
	for (int j = 0; j < nv - 2; j++)
		for (int i = 0; i < nu; i++) {
			int a = 2 + j * nu + i, b = 2 + j * nu + (i + 1) % nu;
			int c = b + nu, d = a + nu;
			fprintf(f, "f %d %d %d\nf %d %d %d\n", a, d, c, a, c, b);
		}
	for (int i = 0; i < nu; i++)
		fprintf(f, "f %d %d %d\n", last, 2 + (nv - 2) * nu + (i + 1) % nu, 2 + (nv - 2) * nu + i);
}

/* Torus around y: nu segments around y, nv around the tube (closed). */
static void
torus(FILE *f, int nu, int nv, double R, double r)
{
	for (int i = 0; i < nu; i++)
		for (int j = 0; j < nv; j++) {
			double u = 2 * PI * i / nu, v = 2 * PI * j / nv;
			fprintf(f, "v %.9g %.9g %.9g\n", (R + r * cos(v)) * cos(u), r * sin(v), -(R + r * cos(v)) * sin(u));
		}
	grid(f, nu, nv, 1, 1, nv);
}

/* Open tube around y from y = 0 to h: n sides, rings rows high (a sheet). */
static void
tube(FILE *f, int n, int rings, double r, double h)
{
	for (int j = 0; j <= rings; j++)
		for (int i = 0; i < n; i++)
			fprintf(f, "v %.9g %.9g %.9g\n", r * cos(2 * PI * i / n), h * j / rings, -r * sin(2 * PI * i / n));
	for (int j = 0; j < rings; j++)
		for (int i = 0; i < n; i++) {
			int a = 1 + j * n + i, b = 1 + j * n + (i + 1) % n;
			fprintf(f, "f %d %d %d\nf %d %d %d\n", a, b, b + n, a, b + n, a + n);
		}
}

/* A lumpy head: an icosahedron subdivided `levels` times, pushed out to a
 * radius that varies smoothly, so its triangles differ in size and shape. */
typedef struct { double x, y, z; } v3;
static v3 *hv;
static int nhv, caphv;
static int (*ht)[3];
static int nht, capht;

static int
addv(v3 p)
{
	if (nhv == caphv) {
		caphv = caphv ? 2 * caphv : 256;
		hv = realloc(hv, (size_t)caphv * sizeof *hv);
		if (!hv)
			die("out of memory", "head");
	}
	hv[nhv] = p;
	return nhv++;
}

static void
addt(int a, int b, int c)
{
	if (nht == capht) {
		capht = capht ? 2 * capht : 256;
		ht = realloc(ht, (size_t)capht * sizeof *ht);
		if (!ht)
			die("out of memory", "head");
	}
	ht[nht][0] = a;
	ht[nht][1] = b;
	ht[nht][2] = c;
	nht++;
}

static v3
unit(v3 p)
{
	double l = sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
	return (v3){p.x / l, p.y / l, p.z / l};
}

/* Midpoint vertex of edge (a, b), shared with the neighbour through a small
 * hash of edges. */
static int *ekey_a, *ekey_b, *eval_;
static int ecap;

static int
mid(int a, int b)
{
	int lo = a < b ? a : b, hi = a < b ? b : a;
	unsigned hsh = ((unsigned)lo * 2654435761u ^ (unsigned)hi * 40503u) % (unsigned)ecap;
	while (ekey_a[hsh] >= 0) {
		if (ekey_a[hsh] == lo && ekey_b[hsh] == hi)
			return eval_[hsh];
		hsh = (hsh + 1) % (unsigned)ecap;
	}
	v3 p = unit((v3){hv[lo].x + hv[hi].x, hv[lo].y + hv[hi].y, hv[lo].z + hv[hi].z});
	ekey_a[hsh] = lo;
	ekey_b[hsh] = hi;
	eval_[hsh] = addv(p);
	return eval_[hsh];
}

static void
head(FILE *f, int levels, double r)
{
	double t = (1 + sqrt(5)) / 2;
	static const int ico[20][3] = {
		{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
		{11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
		{3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
	v3 iv[12] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
	             {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};

	for (int i = 0; i < 12; i++)
		addv(unit(iv[i]));
	for (int i = 0; i < 20; i++)
		addt(ico[i][0], ico[i][1], ico[i][2]);
	for (int l = 0; l < levels; l++) {
		int n = nht;
		ecap = 4 * (nhv + 3 * n) + 1;
		ekey_a = malloc((size_t)ecap * sizeof *ekey_a);
		ekey_b = malloc((size_t)ecap * sizeof *ekey_b);
		eval_ = malloc((size_t)ecap * sizeof *eval_);
		if (!ekey_a || !ekey_b || !eval_)
			die("out of memory", "head");
		memset(ekey_a, 0xff, (size_t)ecap * sizeof *ekey_a);
		int (*old)[3] = malloc((size_t)n * sizeof *old);
		if (!old)
			die("out of memory", "head");
		memcpy(old, ht, (size_t)n * sizeof *old);
		nht = 0;
		for (int i = 0; i < n; i++) {
			int a = old[i][0], b = old[i][1], c = old[i][2];
			int ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
			addt(a, ab, ca);
			addt(b, bc, ab);
			addt(c, ca, bc);
			addt(ab, bc, ca);
		}
		free(old);
		free(ekey_a);
		free(ekey_b);
		free(eval_);
	}
	double ymin = 0;
	for (int pass = 0; pass < 2; pass++)
		for (int i = 0; i < nhv; i++) {
			v3 p = hv[i];
			/* two ears' and a brow's worth of bumps */
			double s = 1 + 0.18 * sin(3 * p.x + 1) * cos(2 * p.y) + 0.12 * cos(5 * p.z + 2 * p.x)
			           + 0.25 * exp(-8 * ((p.x - 0.8) * (p.x - 0.8) + p.y * p.y))
			           + 0.25 * exp(-8 * ((p.x + 0.8) * (p.x + 0.8) + p.y * p.y));
			if (pass == 0)
				ymin = r * s * p.y < ymin ? r * s * p.y : ymin;
			else	/* resting on y = 0 */
				fprintf(f, "v %.9g %.9g %.9g\n", r * s * p.x, r * s * p.y - ymin, r * s * p.z);
		}
	for (int i = 0; i < nht; i++)
		fprintf(f, "f %d %d %d\n", ht[i][0] + 1, ht[i][1] + 1, ht[i][2] + 1);
}

int
main(int argc, char **argv)
{
	double res = 1;
	int size = 256, c;
	char *end;

	while ((c = getopt(argc, argv, "r:s:")) != -1)
		switch (c) {
		case 'r':
			res = strtod(optarg, &end);
			if (*end || !(res > 0 && res <= 16))
				die("bad resolution", optarg);
			break;
		case 's':
			size = (int)strtol(optarg, &end, 10);
			if (*end || size < 1 || size > 8192)
				die("bad size", optarg);
			break;
		default:
			fprintf(stderr, "usage: meshroom [-r RES] [-s SIZE] DIR\n");
			return 2;
		}
	if (optind != argc - 1) {
		fprintf(stderr, "usage: meshroom [-r RES] [-s SIZE] DIR\n");
		return 2;
	}
	const char *dir = argv[optind];
	int n48 = (int)lround(48 * res), n24 = (int)lround(24 * res), n16 = (int)lround(16 * res);
	int levels = res >= 1.5 ? 6 : res >= 0.75 ? 5 : res >= 0.375 ? 4 : 3;
	FILE *f;

	f = create(dir, "sphere.obj");
	fprintf(f, "# UV sphere, %d segments, %d rings\n", n48, n24);
	uvsphere(f, n48, n24, 0.25);
	done(f, "sphere.obj");
	f = create(dir, "torus.obj");
	fprintf(f, "# torus, %d x %d\n", n48, n16);
	torus(f, n48, n16, 0.35, 0.1);
	done(f, "torus.obj");
	f = create(dir, "tube.obj");
	fprintf(f, "# open tube, %d sides\n", n48);
	tube(f, n48, 1, 0.22, 0.7);
	done(f, "tube.obj");
	f = create(dir, "head.obj");
	fprintf(f, "# lumpy subdivided head, %d levels\n", levels);
	head(f, levels, 0.22);
	done(f, "head.obj");

	f = create(dir, "meshroom.pms");
	fprintf(f,
	        "# meshroom.pms — a room of curved primitive meshes (bench/meshroom.c)\n"
	        "camera eye 2 1.4 0.3  look 2 0.6 3  up 0 1 0  fov 55  size %d %d\n"
	        "material wall  diffuse albedo 0.75 0.75 0.72\n"
	        "material floor diffuse albedo 0.55 0.45 0.35\n"
	        "material red   diffuse albedo 0.7 0.2 0.15\n"
	        "material blue  diffuse albedo 0.2 0.3 0.7\n"
	        "material green diffuse albedo 0.25 0.6 0.25\n"
	        "material grey  glossy kd 0.5 0.5 0.5 ks 0.1 0.1 0.1 exponent 10\n"
	        "material lamp  diffuse albedo 0.8 0.8 0.8 emit 12 12 11\n"
	        "box wall 0 0 0  4 2.6 4 inward\n"
	        "quad lamp 1.5 2.59 1.5  2.5 2.59 1.5  2.5 2.59 2.5  1.5 2.59 2.5\n"
	        "# a shelf against the far wall, the sphere resting on it\n"
	        "box grey 2.3 0.8 3.5  3.5 0.84 4\n"
	        "mesh sphere.obj blue translate 2.9 1.09 3.72\n"
	        "# on the floor: the torus lying flat, the tube standing, the head\n"
	        "mesh torus.obj red translate 1.2 0.1 2.6\n"
	        "mesh tube.obj green translate 2.2 0 2.7\n"
	        "mesh head.obj grey translate 1.5 0 3.4\n",
	        size, size);
	done(f, "meshroom.pms");
	return 0;
}
