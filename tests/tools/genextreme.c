/* genextreme — seeded scenes with extreme but parseable values, for the
 * whole-pipeline drill of tests/fuzz/scenes.sh (issue 24): every number fits
 * a float and every statement parses, but lengths run from 1e-30 to 3e38,
 * fields of view come near 0 and 180 degrees, rooms are closed with albedo
 * 1, glossy exponents are 1e-30 or 1e30, indices of refraction 1e-30 or
 * 100 and lights 1e38 watts. pm must answer each with a clean image or a
 * one-line refusal naming the scene's file and line (formats/scene.md,
 * "Range").
 *
 * Usage: genextreme SEED OUTDIR
 *   Writes OUTDIR/scene.pms (and OUTDIR/m*.obj, m*.ply for its meshes) and
 *   prints a one-line description of what was drawn.
 *
 * Deterministic from SEED (splitmix64 of its own). Most draws pick an
 * ordinary value and sometimes an extreme one, so that a scene usually
 * holds one or two extremes among ordinary things, as a user's would; half
 * the scenes keep every extreme inside the range of formats/scene.md and
 * so must render (the description says "tame" or "wild"). */
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "splitmix.h"

static int chance(double p) { return unif() < p; }
static int pick(int n) { return (int)(unif() * n); }
#define PICK(a) (a[pick((int)(sizeof a / sizeof a[0]))])
/* Half the scenes are tame: their extremes lie inside the range pm
 * promises, so they must render; the wild half may pass it anywhere. */
static int wild;
#define DRAW(tame, wilder) (wild ? PICK(wilder) : PICK(tame))

static char desc[512];
static void
note(const char *what)
{
	size_t n = strlen(desc);
	snprintf(desc + n, sizeof desc - n, "%s%s", n ? ", " : "", what);
}

/* The length unit of the scene: the room is 2 of them across. */
static const double units_tame[] = {1e-8, 1e-7, 1e-3, 1, 1, 1, 1, 1e3, 1e9, 1e11};
static const double units_wild[] = {1e-30, 1e-20, 1e-10, 1e-8, 1e-3, 1, 1, 1, 1e12, 1e20, 1e30, 1e38};

static FILE *out;
static double U;        /* the unit, written into coordinates */
static int by_scale;    /* ... or given to each object as 'scale U' */

/* A coordinate in units. */
static void
co(double v)
{
	fprintf(out, " %.9g", by_scale ? v : v * U);
}

static void
tailw(int may_move)
{
	if (chance(0.15))
		fprintf(out, " rotate %.3g %.3g %.3g %.4g", unif() - 0.5, unif(), unif() - 0.5, 360 * unif());
	if (by_scale)
		fprintf(out, " scale %.9g", U);
	if (may_move && chance(0.15)) {
		static const double mv_tame[] = {0.1, 1, 1e-30};
		static const double mv_wild[] = {0.1, 1, 1e10, 1e30, 3e38};
		double m = DRAW(mv_tame, mv_wild);
		/* 'move' is in world units: a move of m units, or an absolute one */
		double w = !wild || chance(0.5) ? m * U : m;
		if (w > 3e38)
			w = 3e38;
		fprintf(out, " move %.9g 0 %.9g", w, -w / 2);
		note("move");
	}
}

static void
mesh_file(const char *dir, int i, int ply, double big)
{
	char path[600];
	snprintf(path, sizeof path, "%s/m%d.%s", dir, i, ply ? "ply" : "obj");
	FILE *f = fopen(path, "w");
	if (!f) {
		fprintf(stderr, "genextreme: cannot write '%s': %s\n", path, strerror(errno));
		exit(1);
	}
	/* a tetrahedron, one corner perhaps far out */
	double v[4][3] = {{0, 0, 0}, {0.5, 0, 0}, {0, 0.5, 0}, {0, 0, 0.5}};
	v[3][2] = big;
	if (ply) {
		fprintf(f, "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
		        "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n");
		for (int k = 0; k < 4; k++)
			fprintf(f, "%.9g %.9g %.9g\n", v[k][0], v[k][1], v[k][2]);
		fprintf(f, "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n");
	} else {
		for (int k = 0; k < 4; k++)
			fprintf(f, "v %.9g %.9g %.9g\n", v[k][0], v[k][1], v[k][2]);
		fprintf(f, "f 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n");
	}
	if (fclose(f)) {
		fprintf(stderr, "genextreme: cannot write '%s'\n", path);
		exit(1);
	}
}

int
main(int argc, char **argv)
{
	if (argc != 3) {
		fprintf(stderr, "usage: genextreme SEED OUTDIR\n");
		return 2;
	}
	rng_state = strtoull(argv[1], NULL, 10) * 0x2545f4914f6cdd1dull + 24;
	const char *dir = argv[2];
	mkdir(dir, 0777);
	char path[600];
	snprintf(path, sizeof path, "%s/scene.pms", dir);
	out = fopen(path, "w");
	if (!out) {
		fprintf(stderr, "genextreme: cannot write '%s': %s\n", path, strerror(errno));
		return 1;
	}

	wild = chance(0.5);
	note(wild ? "wild" : "tame");
	U = DRAW(units_tame, units_wild);
	by_scale = chance(0.3);
	char b[64];
	snprintf(b, sizeof b, "unit %g%s", U, by_scale ? " by scale" : "");
	note(b);
	/* Coordinates (and the camera, which has no transform) are written up
	 * to 5 units: keep them floats. */
	if (U > 3e38 / 5)
		U = 3e38 / 5;

	/* camera */
	static const double fovs_tame[] = {60, 60, 60, 60, 1e-4, 0.01, 179.9, 179.999};
	static const double fovs_wild[] = {60, 60, 1e-6, 1e-30, 1e-45, 179.999999, 180 - 1e-5};
	double fov = DRAW(fovs_tame, fovs_wild);
	fprintf(out, "camera eye");
	if (wild && chance(0.1)) {
		fprintf(out, " 1e30 1 5");
		note("eye 1e30 away");
	} else {
		/* inside the room, near its front wall */
		fprintf(out, " 0 %.9g %.9g", U, 0.95 * U);
	}
	fprintf(out, "  look 0 %.9g 0  up 0 1 0  fov %.9g  size 8 6\n", U, fov);
	if (fov != 45 && fov != 60) {
		snprintf(b, sizeof b, "fov %g", fov);
		note(b);
	}
	if (chance(0.1)) {
		static const double th[] = {1e-30, 3e38, 1};
		fprintf(out, "glossy_threshold %g\n", PICK(th));
		note("glossy_threshold");
	}

	/* materials: the walls, and one of each kind for the items */
	int white = chance(0.25);
	fprintf(out, "material wall diffuse albedo %s\n", white ? "1 1 1" : "0.7 0.6 0.5");
	if (white)
		note("albedo 1");
	static const double expo[] = {1e-30, 1e-30, 1e30, 1e30, 3e38, 20, 1000};
	double e = PICK(expo);
	/* kd + ks at most 1: all specular (1 of it) or a mix */
	fprintf(out, "material gl glossy %s exponent %.9g\n",
	        chance(0.5) ? "kd 0 0 0 ks 1 1 1" : "kd 0.3 0.3 0.3 ks 0.7 0.7 0.7", e);
	snprintf(b, sizeof b, "exponent %g", e);
	note(b);
	static const double iors[] = {1e-30, 100, 1.5, 1e-30, 100, 3e38};
	double ior = PICK(iors);
	fprintf(out, "material gs glass ior %.9g\n", ior);
	snprintf(b, sizeof b, "ior %g", ior);
	note(b);
	fprintf(out, "material mi mirror reflect 1 1 1\n");
	static const double emits_tame[] = {1, 10, 1e10, 1e20, 1e29};
	static const double emits_wild[] = {1, 10, 1e31, 1e38, 3e38};
	double em = DRAW(emits_tame, emits_wild);
	/* tame: all lights together stay under 1e30 W */
	if (!wild && em * U * U > 1e28)
		em = 1e28 / (U * U);
	fprintf(out, "material lamp diffuse albedo %s emit %.9g %.9g %.9g%s\n",
	        white ? "1 1 1" : "0.5 0.5 0.5", em, em, em, chance(0.3) ? " twosided" : "");

	/* the room: closed (inward box) or a floor alone */
	if (chance(0.8)) {
		fprintf(out, "box wall");
		co(-1); co(0); co(-1); co(1); co(2); co(1);
		fprintf(out, " inward");
		tailw(0);
		fprintf(out, "\n");
	} else {
		fprintf(out, "quad wall");
		double q[12] = {-3, 0, 3, 3, 0, 3, 3, 0, -3, -3, 0, -3};
		for (int k = 0; k < 12; k++)
			co(q[k]);
		tailw(0);
		fprintf(out, "\n");
		note("open");
	}

	/* items */
	static const char *const mats[] = {"wall", "gl", "gs", "mi", "wall", "gl"};
	int nitems = pick(4);
	for (int i = 0; i < nitems; i++) {
		const char *m = PICK(mats);
		switch (pick(5)) {
		case 0:
			fprintf(out, "box %s", m);
			co(-0.3); co(0); co(-0.3); co(0.3); co(0.6); co(0.3);
			break;
		case 1:
			fprintf(out, "sphere %s", m);
			co(0.4); co(0.4); co(0.2); co(0.3);
			fprintf(out, " subdiv 1");
			break;
		case 2:
			fprintf(out, "quad %s", m);
			{
				double q[12] = {-0.5, 0.5, -0.9, 0.5, 0.5, -0.9, 0.5, 1.5, -0.9, -0.5, 1.5, -0.9};
				for (int k = 0; k < 12; k++)
					co(q[k]);
			}
			break;
		case 3:
			fprintf(out, "triangle %s", m);
			co(-0.8); co(0.01); co(0.5); co(0.2); co(0.01); co(0.6); co(-0.3); co(0.01); co(-0.2);
			break;
		default: {
			static const double far_tame[] = {0.5, 0.5, 0.5, 1e-30};
			static const double far_wild[] = {0.5, 1e30, 3e38, 1e-30};
			double big = DRAW(far_tame, far_wild);
			int ply = chance(0.5);
			mesh_file(dir, i, ply, big);
			fprintf(out, "mesh m%d.%s %s", i, ply ? "ply" : "obj", m);
			if (big != 0.5) {
				snprintf(b, sizeof b, "mesh vertex %g", big);
				note(b);
			}
			if (!by_scale)
				fprintf(out, " scale %.9g", U);
			break;
		}
		}
		tailw(1);
		fprintf(out, "\n");
	}

	/* one of the shapes, now and then */
	if (!wild && chance(0.15)) {
		/* in range, though the room is then far below the scene's detail */
		fprintf(out, "box wall -1e12 -1e12 -1e12 1e12 -1e11 1e12\n");
		note("slab 1e12");
	} else if (wild && chance(0.25)) {
		switch (pick(4)) {
		case 0:
			fprintf(out, "box wall -1e30 -1e30 -1e30 1e30 -1e29 1e30\n");
			note("slab 1e30");
			break;
		case 1:
			fprintf(out, "box wall -3e38 0.1 -0.2 1.19 0.3 0.2\n");
			note("box from -3e38");
			break;
		case 2:
			fprintf(out, "box gs -0.1 0.1 -0.1 0.1 0.3 0.1 scale 1e20\n");
			note("glass scale 1e20");
			break;
		default:
			fprintf(out, "sphere wall 0 0.5 0 0.1 subdiv 1 scale 1e-30\n");
			note("sphere scale 1e-30");
			break;
		}
	}

	/* lights */
	static const double powers_tame[] = {10, 10, 100, 1e20, 1e29};
	static const double powers_wild[] = {10, 1e20, 1e31, 1e38, 3e38};
	int npl = chance(0.7) ? 1 + pick(3) : 0;
	for (int i = 0; i < npl; i++) {
		double pw = DRAW(powers_tame, powers_wild);
		/* tame: in watts per unit squared, all lights under 1e30 W */
		if (!wild)
			pw = fmin(pw * U * U, 1e29);
		fprintf(out, "pointlight");
		co(0.3 * i - 0.3); co(1.9); co(0);
		fprintf(out, " power %.9g %.9g %.9g", pw, pw, pw);
		if (chance(0.1))
			fprintf(out, " move %.9g 0 0", wild && chance(0.5) ? 1e30 : 0.1 * U);
		fprintf(out, "\n");
		if (pw > 1e3) {
			snprintf(b, sizeof b, "power %g", pw);
			note(b);
		}
	}
	if (npl == 0 || chance(0.3)) {
		fprintf(out, "quad lamp");
		double q[12] = {-0.3, 1.99, -0.3, -0.3, 1.99, 0.3, 0.3, 1.99, 0.3, 0.3, 1.99, -0.3};
		for (int k = 0; k < 12; k++)
			co(q[k]);
		tailw(0);
		fprintf(out, "\n");
		snprintf(b, sizeof b, "emit %g", em);
		note(b);
	}
	if (fclose(out)) {
		fprintf(stderr, "genextreme: cannot write '%s'\n", path);
		return 1;
	}
	printf("%s\n", desc);
	return 0;
}
