/* genscene — seeded random scenes of hard arrangements for the torture
 * harness (tests/torture/): a closed room (`box ... inward`) holding 1-4
 * items drawn from a grammar of the cases where photon estimates go wrong:
 * boxes and OBJ blocks resting on the floor, on rugs, on tables and on each
 * other (stacked, rotated, touching walls), open-bottom blocks (walls and
 * top, no bottom, as the published Cornell box blocks), tables with thin
 * tops on legs (as five boxes or as one OBJ of five boxes, a solid of
 * several parts), partitions with gaps under or beside them, rugs a fraction
 * of a millimetre to 5 mm above the floor or a table (sometimes with a block
 * on them), low overhanging slabs, pictures a hair in front of a wall,
 * spheres resting on surfaces; diffuse or soft-glossy floors, sometimes a
 * separate floor quad laid over the room's floor; point or area lights.
 * Later families, drawn from a stream of their own (fam_state) so that a
 * scene none of them touches is byte for byte what it was: rooms of six
 * separate quads (a polygon soup, not one closed box; half of them then
 * one OBJ wound outward, from a fourth stream), tables and boxes
 * written as polygon-soup OBJs (every face its own vertices), and curved
 * meshes as Blender's primitives export them (UV spheres 48 x 24, tori
 * 48 x 16, open 48-sided tubes, blobby heads), some as soups. A quarter of
 * the views, from a stream of their own too, look at the top of a wall
 * and the ceiling over it rather than at the items.
 *
 * Usage: genscene SEED OUTDIR [--furnace] [--size W H]
 *   Writes OUTDIR/scene.pms (and OUTDIR/meshN.obj for the OBJ blocks,
 *   referenced by relative names) and prints a one-line description.
 *   --furnace: the same geometry (same SEED gives the same polygons), every
 *   material `diffuse albedo 0.5 0.5 0.5 emit 1 1 1 twosided` and no point
 *   lights, so the exact radiance is 2 everywhere.
 *   --size W H: the camera's image size (default 96 72).
 *
 * Deterministic from SEED (splitmix64, its own state; no rand()). Every
 * coordinate is written on a 1e-5 grid with the same text wherever two
 * surfaces are meant to touch, and heights are written as absolute world y
 * (transforms are only `rotate 0 1 0` and a translate in x and z), so an
 * object resting on another has its bottom at exactly the float of the
 * other's top. Units: metres. */
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "splitmix.h"

#define PI 3.14159265358979323846

/* ---- random numbers: splitmix64 (splitmix.h) ---- */
/* Side streams: a choice added later draws from a stream of its own, so
 * that a scene it does not touch stays byte for byte what it was.
 * side_begin/side_end run the ordinary helpers (rnd, chance, ...) on one. */
static uint64_t side_keep;
static void side_begin(const uint64_t *st) { side_keep = rng_state; rng_state = *st; }
static void side_end(uint64_t *st) { *st = rng_state; rng_state = side_keep; }
static int
side_chance(uint64_t *st, double p)
{
	uint64_t keep = rng_state;
	rng_state = *st;
	int r = (double)(next64() >> 11) * 0x1.0p-53 < p;
	*st = rng_state;
	rng_state = keep;
	return r;
}
/* How an item is written (not where it is). */
static uint64_t form_state;
static int form_chance(double p) { return side_chance(&form_state, p); }
/* The families added later (rooms of six quads, polygon-soup furniture,
 * curved meshes). */
static uint64_t fam_state;
static void fam_begin(void) { side_begin(&fam_state); }
static void fam_end(void) { side_end(&fam_state); }
static int fam_chance(double p) { return side_chance(&fam_state, p); }
/* Whether a room of six quads is written instead as one OBJ facing out. */
static uint64_t shell_state;
/* Whether the camera looks at the top of a wall instead of the items. */
static uint64_t view_state;
static double rnd(double a, double b) { return a + (b - a) * unif(); }
static int irnd(int n) { return (int)(unif() * n); }
static int chance(double p) { return unif() < p; }

/* Every coordinate goes through q(): rounded to 1e-5, printed as %.5f, so
 * equal values print equal text. */
static double q(double v) { double r = round(v * 1e5) / 1e5; return r == 0 ? 0 : r; }

/* ---- output buffers ---- */
typedef struct { char *s; size_t n, cap; } sbuf;
static void
sb_printf(sbuf *b, const char *fmt, ...)
{
	va_list ap;
	for (;;) {
		size_t room = b->cap - b->n;
		va_start(ap, fmt);
		int k = vsnprintf(b->s ? b->s + b->n : NULL, b->s ? room : 0, fmt, ap);
		va_end(ap);
		if (k < 0) { perror("genscene: vsnprintf"); exit(1); }
		if (b->s && (size_t)k < room) { b->n += (size_t)k; return; }
		b->cap = b->cap * 2 + (size_t)k + 256;
		if (!(b->s = realloc(b->s, b->cap))) { perror("genscene"); exit(1); }
	}
}

static sbuf geo, desc;          /* object lines; the description */
static int furnace;

/* ---- materials ---- */
#define MAXMAT 64
static char mat_name[MAXMAT][16], mat_spec[MAXMAT][160];
static int nmat;
static const char *
material(const char *prefix, const char *fmt, ...)
{
	va_list ap;
	if (nmat >= MAXMAT) { fprintf(stderr, "genscene: too many materials\n"); exit(1); }
	snprintf(mat_name[nmat], sizeof mat_name[0], "%s%d", prefix, nmat);
	va_start(ap, fmt);
	vsnprintf(mat_spec[nmat], sizeof mat_spec[0], fmt, ap);
	va_end(ap);
	return mat_name[nmat++];
}
/* A random greyish or coloured diffuse albedo in [0.3, 0.8]. */
static const char *
diffuse_mat(const char *prefix)
{
	double g = rnd(0.3, 0.8), c[3];
	int coloured = chance(0.4);
	for (int i = 0; i < 3; i++)
		c[i] = coloured ? rnd(0.3, 0.8) : fmin(0.8, fmax(0.3, g + rnd(-0.04, 0.04)));
	return material(prefix, "diffuse albedo %.3f %.3f %.3f", c[0], c[1], c[2]);
}

/* ---- the scene being built ---- */
typedef struct { double lo[3], hi[3]; } aabb;
/* A horizontal rectangle things can rest on: centre, half sizes in its own
 * frame, its rotation about y (radians), its height. */
typedef struct { double cx, cz, hx, hz, ang, y; const char *what; } support;
#define MAXS 64
static aabb boxes[256];
static int nboxes;
static support sup[MAXS];
static int nsup;
static double W, H, D, floor_y;
static int coplanar_floor;  /* a floor quad lying exactly on the room's floor */
static double rx0, rx1, rz0, rz1;  /* focus region on the floor */
static int nmesh;
static const char *outdir;

/* A camera at e would sit within 5 cm of an item's box. */
static int
near_items(const double e[3])
{
	for (int i = 0; i < nboxes; i++) {
		int k;
		for (k = 0; k < 3; k++)
			if (!(e[k] > boxes[i].lo[k] - 0.05 && e[k] < boxes[i].hi[k] + 0.05))
				break;
		if (k == 3)
			return 1;
	}
	return 0;
}

static int
overlaps(const aabb *a)
{
	const double e = 2e-5;  /* coordinates are rounded to 1e-5 */
	if (a->lo[0] < -e || a->lo[2] < -e || a->hi[0] > W + e || a->hi[2] > D + e ||
	    a->hi[1] > H - 0.15)
		return 1;
	for (int i = 0; i < nboxes; i++) {
		const aabb *b = &boxes[i];
		int k;
		for (k = 0; k < 3; k++)
			if (!(a->lo[k] < b->hi[k] - e && b->lo[k] < a->hi[k] - e))
				break;
		if (k == 3)
			return 1;
	}
	return 0;
}
static void
add_aabb(const aabb *a)
{
	if (nboxes < 256)
		boxes[nboxes++] = *a;
}
static void
add_support(double cx, double cz, double hx, double hz, double ang, double y, const char *what)
{
	if (nsup < MAXS)
		sup[nsup++] = (support){ cx, cz, hx, hz, ang, y, what };
}

/* The world AABB of a rectangle of half sizes hx, hz rotated by ang about
 * (cx, cz), from y0 to y1. */
static aabb
rect_aabb(double cx, double cz, double hx, double hz, double ang, double y0, double y1)
{
	double c = fabs(cos(ang)), s = fabs(sin(ang));
	double ex = c * hx + s * hz, ez = s * hx + c * hz;
	return (aabb){ { cx - ex, y0, cz - ez }, { cx + ex, y1, cz + ez } };
}

/* A spot for a footprint of half sizes fx, fz on support s: sets the centre
 * and rotation. rel is the rotation relative to the support's frame. With
 * flush, the footprint is pushed against an edge of the support (for the
 * floor: a wall of the focus region, when it is one). Returns 0 if the
 * footprint does not fit. */
static int
spot(const support *s, double fx, double fz, double rel, int flush, double *cx, double *cz, double *ang)
{
	double c = fabs(cos(rel)), sn = fabs(sin(rel));
	double ex = c * fx + sn * fz, ez = sn * fx + c * fz;
	if (ex > s->hx || ez > s->hz)
		return 0;
	double u = rnd(-(s->hx - ex), s->hx - ex), v = rnd(-(s->hz - ez), s->hz - ez);
	if (flush) {
		if (chance(0.5)) u = chance(0.5) ? s->hx - ex : -(s->hx - ex);
		else v = chance(0.5) ? s->hz - ez : -(s->hz - ez);
	}
	double ca = cos(s->ang), sa = sin(s->ang);
	/* rotate (u, v) by the support's angle about y: x' = x cos + z sin,
	 * z' = -x sin + z cos (right-handed about +y, as `rotate 0 1 0`). */
	*cx = s->cx + u * ca + v * sa;
	*cz = s->cz - u * sa + v * ca;
	*ang = s->ang + rel;
	if (flush) {
		/* keep the flush edge exact: on the floor with no rotation the
		 * footprint's side lies on the support's edge. */
		*cx = q(*cx);
		*cz = q(*cz);
	}
	return 1;
}

/* Picks a support: the floor region or, with probability p_up, one of the
 * others (rugs, table tops, box tops, slabs). */
static const support *
pick_support(double p_up)
{
	if (nsup > 1 && chance(p_up))
		return &sup[1 + irnd(nsup - 1)];
	return &sup[0];
}

/* ---- primitives ---- */
/* A box of half sizes hx, hz from y0 to y1, rotated by ang (radians) about
 * y and centred at (cx, cz). */
static void
emit_box(const char *m, double cx, double cz, double hx, double hz, double ang, double y0, double y1)
{
	double deg = fmod(ang * 180 / PI, 360);
	if (fabs(deg) < 1e-9 || fabs(fabs(deg) - 180) < 1e-9) {
		/* axis-aligned: exact corners, no transform */
		sb_printf(&geo, "box %s %.5f %.5f %.5f  %.5f %.5f %.5f\n", m,
		          q(cx - hx), q(y0), q(cz - hz), q(cx + hx), q(y1), q(cz + hz));
	} else if (fabs(fabs(deg) - 90) < 1e-9 || fabs(fabs(deg) - 270) < 1e-9) {
		sb_printf(&geo, "box %s %.5f %.5f %.5f  %.5f %.5f %.5f\n", m,
		          q(cx - hz), q(y0), q(cz - hx), q(cx + hz), q(y1), q(cz + hx));
	} else {
		sb_printf(&geo, "box %s %.5f %.5f %.5f  %.5f %.5f %.5f  rotate 0 1 0 %.4f  translate %.5f 0 %.5f\n",
		          m, q(-hx), q(y0), q(-hz), q(hx), q(y1), q(hz), deg, q(cx), q(cz));
	}
}
/* A horizontal quad at height y, facing up (or down). */
static void
emit_hquad(const char *m, double cx, double cz, double hx, double hz, double ang, double y, int down)
{
	double ca = cos(ang), sa = sin(ang), u[4] = { -hx, -hx, hx, hx }, v[4] = { -hz, hz, hz, -hz };
	sb_printf(&geo, "quad %s", m);
	for (int j = 0; j < 4; j++) {
		int i = down ? 3 - j : j;
		sb_printf(&geo, "  %.5f %.5f %.5f", q(cx + u[i] * ca + v[i] * sa), q(y), q(cz - u[i] * sa + v[i] * ca));
	}
	sb_printf(&geo, "\n");
}
/* A quad with four world corners (counter-clockwise from the front). */
static void
emit_quad4(const char *m, const double p[4][3])
{
	sb_printf(&geo, "quad %s", m);
	for (int i = 0; i < 4; i++)
		sb_printf(&geo, "  %.5f %.5f %.5f", q(p[i][0]), q(p[i][1]), q(p[i][2]));
	sb_printf(&geo, "\n");
}

/* A prism standing on y0 up to y1 over the convex footprint (px, pz)[n]
 * (counter-clockwise seen from above). */
typedef struct { int n; double px[8], pz[8], y0, y1; } prism;

/* One face of an OBJ: corners idx[0..n-1] (1-based, into the shared
 * vertices); in a polygon soup each face gets its own copies of its
 * corners, as flat-shaded exports write them (no edge is shared, so the
 * mesh is an open sheet of loose faces). */
static void
obj_face(FILE *f, int soup, const double (*vt)[3], const int *idx, int n, int *nsoup)
{
	if (soup) {
		for (int i = 0; i < n; i++)
			fprintf(f, "v %.5f %.5f %.5f\n", q(vt[idx[i] - 1][0]), q(vt[idx[i] - 1][1]), q(vt[idx[i] - 1][2]));
		fprintf(f, "f");
		for (int i = 0; i < n; i++)
			fprintf(f, " %d", *nsoup + 1 + i);
		fprintf(f, "\n");
		*nsoup += n;
		return;
	}
	fprintf(f, "f");
	for (int i = 0; i < n; i++)
		fprintf(f, " %d", idx[i]);
	fprintf(f, "\n");
}

/* A mesh file of nv vertices and faces (face k: fv[fs[k] .. fs[k+1]-1],
 * 1-based), shared or as a polygon soup, added to the scene. */
static void
emit_obj(const char *m, const double (*vt)[3], int nv, const int *fv, const int *fs, int nf, int soup, const char *what)
{
	char name[64], path[4096];
	FILE *f;
	int nsoup = 0;
	snprintf(name, sizeof name, "mesh%d.obj", ++nmesh);
	snprintf(path, sizeof path, "%s/%s", outdir, name);
	if (!(f = fopen(path, "w"))) { fprintf(stderr, "genscene: cannot write '%s': %s\n", path, strerror(errno)); exit(1); }
	fprintf(f, "# %s: %s (genscene)\n", name, what);
	for (int i = 0; i < nv && !soup; i++)
		fprintf(f, "v %.5f %.5f %.5f\n", q(vt[i][0]), q(vt[i][1]), q(vt[i][2]));
	for (int k = 0; k < nf; k++)
		obj_face(f, soup, vt, fv + fs[k], fs[k + 1] - fs[k], &nsoup);
	if (fclose(f)) { fprintf(stderr, "genscene: cannot write '%s': %s\n", path, strerror(errno)); exit(1); }
	sb_printf(&geo, "mesh %s %s\n", name, m);
}

/* emit_prisms_obj's prisms as a polygon soup: every face its own
 * vertices, as flat-shaded exports write them (an open sheet of loose
 * faces, one object). */
static void
emit_prisms_soup(const char *m, const prism *pr, int np, int bottom, const char *what)
{
	static double vt[5 * 16][3];
	static int fv[5 * 64], fs[5 * 12];
	int nv = 0, nfv = 0, nf = 0;
	char w[160];
	for (int k = 0; k < np; k++) {
		const prism *P = &pr[k];
		int n = P->n, base = nv + 1;
		for (int i = 0; i < n; i++, nv++)
			vt[nv][0] = P->px[i], vt[nv][1] = P->y0, vt[nv][2] = P->pz[i];
		for (int i = 0; i < n; i++, nv++)
			vt[nv][0] = P->px[i], vt[nv][1] = P->y1, vt[nv][2] = P->pz[i];
		/* The top face must be counter-clockwise seen from +y: by
		 * Newell's normal, n_y = sum (z_i - z_j)(x_i + x_j) > 0 when
		 * the angle atan2(z, x) decreases along the corners; the caller
		 * gives that order. */
		fs[nf++] = nfv;
		for (int i = 0; i < n; i++)
			fv[nfv++] = base + n + i;
		for (int i = 0; i < n; i++) {
			int j = (i + 1) % n;
			/* side face: bottom i, bottom j, top j, top i is
			 * counter-clockwise seen from outside (normal outward) */
			fs[nf++] = nfv;
			fv[nfv++] = base + i;
			fv[nfv++] = base + j;
			fv[nfv++] = base + n + j;
			fv[nfv++] = base + n + i;
		}
		if (bottom) {
			fs[nf++] = nfv;
			for (int i = n - 1; i >= 0; i--)
				fv[nfv++] = base + i;
		}
	}
	fs[nf] = nfv;
	snprintf(w, sizeof w, "%s, %s, polygon soup", what, bottom ? "closed" : "open bottom");
	emit_obj(m, (const double (*)[3])vt, nv, fv, fs, nf, 1, w);
}

/* np prisms written as one OBJ file (one object: a solid of several parts
 * when they are closed and touch, as a chair or table mesh is), with or
 * without their bottom faces; what says what it is. */
static void
emit_prisms_obj(const char *m, const prism *pr, int np, int bottom, const char *what)
{
	char name[64], path[4096];
	FILE *f;
	int base = 1;
	snprintf(name, sizeof name, "mesh%d.obj", ++nmesh);
	snprintf(path, sizeof path, "%s/%s", outdir, name);
	if (!(f = fopen(path, "w"))) { fprintf(stderr, "genscene: cannot write '%s': %s\n", path, strerror(errno)); exit(1); }
	fprintf(f, "# %s: %s, %s (genscene)\n", name, what, bottom ? "closed" : "open bottom");
	for (int k = 0; k < np; k++) {
		const prism *P = &pr[k];
		int n = P->n;
		for (int i = 0; i < n; i++)
			fprintf(f, "v %.5f %.5f %.5f\n", q(P->px[i]), q(P->y0), q(P->pz[i]));
		for (int i = 0; i < n; i++)
			fprintf(f, "v %.5f %.5f %.5f\n", q(P->px[i]), q(P->y1), q(P->pz[i]));
		/* The top face must be counter-clockwise seen from +y: by
		 * Newell's normal, n_y = sum (z_i - z_j)(x_i + x_j) > 0 when
		 * the angle atan2(z, x) decreases along the corners; the caller
		 * gives that order. */
		fprintf(f, "f");
		for (int i = 0; i < n; i++)
			fprintf(f, " %d", base + n + i);
		fprintf(f, "\n");
		for (int i = 0; i < n; i++) {
			int j = (i + 1) % n;
			/* side face: bottom i, bottom j, top j, top i is
			 * counter-clockwise seen from outside (normal outward) */
			fprintf(f, "f %d %d %d %d\n", base + i, base + j, base + n + j, base + n + i);
		}
		if (bottom) {
			fprintf(f, "f");
			for (int i = n - 1; i >= 0; i--)
				fprintf(f, " %d", base + i);
			fprintf(f, "\n");
		}
		base += 2 * n;
	}
	if (fclose(f)) { fprintf(stderr, "genscene: cannot write '%s': %s\n", path, strerror(errno)); exit(1); }
	sb_printf(&geo, "mesh %s %s\n", name, m);
}

static void
emit_prism_obj(const char *m, const double *px, const double *pz, int n, double y0, double y1, int bottom)
{
	prism P = { n, {0}, {0}, y0, y1 };
	char what[32];
	memcpy(P.px, px, (size_t)n * sizeof *px);
	memcpy(P.pz, pz, (size_t)n * sizeof *pz);
	snprintf(what, sizeof what, "a prism of %d sides", n);
	emit_prisms_obj(m, &P, 1, bottom, what);
}

/* The box of half sizes hx, hz about (cx, cz), rotated by ang, from y0 to
 * y1, as a prism (corners in emit_prisms_obj's order). */
static prism
box_prism(double cx, double cz, double hx, double hz, double ang, double y0, double y1)
{
	double ca = cos(ang), sa = sin(ang), u[4] = { -hx, hx, hx, -hx }, v[4] = { hz, hz, -hz, -hz };
	prism P = { 4, {0}, {0}, y0, y1 };
	for (int i = 0; i < 4; i++) {
		P.px[i] = cx + u[i] * ca + v[i] * sa;
		P.pz[i] = cz - u[i] * sa + v[i] * ca;
	}
	return P;
}

/* An open-bottom block of quads: four walls and a top (no bottom). */
static void
emit_open_box_quads(const char *m, double cx, double cz, double hx, double hz, double ang, double y0, double y1)
{
	double ca = cos(ang), sa = sin(ang), u[4] = { -hx, hx, hx, -hx }, v[4] = { hz, hz, -hz, -hz };
	double x[4], z[4];
	/* corners counter-clockwise seen from above (+y): see emit_hquad */
	for (int i = 0; i < 4; i++) {
		x[i] = cx + u[i] * ca + v[i] * sa;
		z[i] = cz - u[i] * sa + v[i] * ca;
	}
	for (int i = 0; i < 4; i++) {
		int j = (i + 1) % 4;
		double p[4][3] = { { x[i], y0, z[i] }, { x[j], y0, z[j] }, { x[j], y1, z[j] }, { x[i], y1, z[i] } };
		emit_quad4(m, p);
	}
	emit_hquad(m, cx, cz, hx, hz, ang, y1, 0);
}

static const char *
sup_name(const support *s)
{
	return s->what;
}

/* ---- items of the grammar; each returns 1 if placed ---- */

/* Boxes: one on a support, maybe rotated, maybe against a wall, with 0-2
 * more stacked on it. */
static int
item_boxes(void)
{
	const support *s = pick_support(0.5);
	double hx = rnd(0.05, 0.35), hz = rnd(0.05, 0.35), h = rnd(0.05, 0.7);
	int flush = s == &sup[0] ? chance(0.5) : chance(0.25);
	double rel = flush || chance(0.4) ? (chance(0.5) ? 0 : PI / 2) : rnd(0, PI / 2);
	double cx, cz, ang;
	if (!spot(s, hx, hz, rel, flush, &cx, &cz, &ang))
		return 0;
	aabb a = rect_aabb(cx, cz, hx, hz, ang, s->y, q(s->y + h));
	if (overlaps(&a))
		return 0;
	const char *m = diffuse_mat("m");
	double y1 = q(s->y + h);
	int soup = fam_chance(0.15);
	if (soup) {
		prism P = box_prism(cx, cz, hx, hz, ang, s->y, y1);
		emit_prisms_soup(m, &P, 1, 1, "a box");
	} else
		emit_box(m, cx, cz, hx, hz, ang, s->y, y1);
	add_aabb(&a);
	int nstack = irnd(3);
	int atwall = fabs(a.lo[0]) < 1e-4 || fabs(a.hi[0] - W) < 1e-4 || fabs(a.lo[2]) < 1e-4 || fabs(a.hi[2] - D) < 1e-4;
	sb_printf(&desc, "; box%s%s%s on %s", soup ? " (OBJ soup)" : "", atwall ? " against a wall" : flush ? " at an edge" : "", rel != 0 && rel != PI / 2 ? " rotated" : "", sup_name(s));
	support top = { cx, cz, hx, hz, ang, y1, "box" };
	int placed = 0;
	for (int k = 0; k < nstack; k++) {
		double sx = rnd(0.04, top.hx), sz = rnd(0.04, top.hz), sh = rnd(0.04, 0.4);
		double r2 = chance(0.5) ? 0 : rnd(-0.6, 0.6), ux, uz, ua;
		if (!spot(&top, sx, sz, r2, chance(0.3), &ux, &uz, &ua)) {
			if (!spot(&top, sx, sz, 0, 0, &ux, &uz, &ua))
				break;
		}
		aabb b = rect_aabb(ux, uz, sx, sz, ua, top.y, q(top.y + sh));
		if (overlaps(&b))
			break;
		const char *m2 = diffuse_mat("m");
		double t1 = q(top.y + sh);
		emit_box(m2, ux, uz, sx, sz, ua, top.y, t1);
		add_aabb(&b);
		top = (support){ ux, uz, sx, sz, ua, t1, "box" };
		placed++;
	}
	if (placed)
		sb_printf(&desc, " +%d stacked", placed);
	add_support(top.cx, top.cz, top.hx, top.hz, top.ang, top.y, "box");
	return 1;
}

/* A block as an OBJ prism (closed, or walls and top only) or as quads
 * (open bottom), resting on a support. */
static int
item_block(void)
{
	const support *s = pick_support(0.5);
	int quads = chance(0.35), open = quads || chance(0.6);
	double h = rnd(0.08, 0.6), cx, cz, ang;
	if (quads) {
		double hx = rnd(0.06, 0.3), hz = rnd(0.06, 0.3), rel = chance(0.4) ? 0 : rnd(0, PI / 2);
		if (!spot(s, hx, hz, rel, chance(0.3), &cx, &cz, &ang))
			return 0;
		aabb a = rect_aabb(cx, cz, hx, hz, ang, s->y, q(s->y + h));
		if (overlaps(&a))
			return 0;
		emit_open_box_quads(diffuse_mat("m"), cx, cz, hx, hz, ang, s->y, q(s->y + h));
		add_aabb(&a);
		sb_printf(&desc, "; open-bottom block (quads) on %s", sup_name(s));
		return 1;
	}
	int n = 4 + irnd(3);
	double r = rnd(0.08, 0.3), px[8], pz[8], ph0 = rnd(0, 2 * PI);
	if (!spot(s, r, r, 0, 0, &cx, &cz, &ang))
		return 0;
	aabb a = { { cx - r, s->y, cz - r }, { cx + r, q(s->y + h), cz + r } };
	if (overlaps(&a))
		return 0;
	/* a convex polygon: n angles, decreasing (counter-clockwise seen
	 * from +y with x right and z down the page), radii 0.75r..r */
	for (int i = 0; i < n; i++) {
		double t = ph0 - 2 * PI * (i + rnd(-0.25, 0.25)) / n, rr = r * rnd(0.8, 1.0);
		px[i] = cx + rr * cos(t);
		pz[i] = cz + rr * sin(t);
	}
	emit_prism_obj(diffuse_mat("m"), px, pz, n, s->y, q(s->y + h), !open);
	add_aabb(&a);
	sb_printf(&desc, "; %s OBJ block (%d sides) on %s", open ? "open-bottom" : "closed", n, sup_name(s));
	return 1;
}

/* A table: a top 1-10 cm thick on four legs, standing on the floor or a
 * rug; its top is a support. */
static int
item_table(void)
{
	const support *s = pick_support(0.25);
	double hx = rnd(0.25, 0.7), hz = rnd(0.2, 0.55), t = rnd(0.01, 0.10), ht = rnd(0.3, 0.9);
	double leg = rnd(0.015, 0.04), inset = chance(0.4) ? 0 : rnd(0, 0.08);
	double rel = chance(0.5) ? 0 : rnd(0, PI), cx, cz, ang;
	if (s != &sup[0] && chance(0.5))
		hx *= 0.6, hz *= 0.6, ht *= 0.6;
	if (!spot(s, hx, hz, rel, 0, &cx, &cz, &ang))
		return 0;
	double y1 = q(s->y + ht), y0 = q(y1 - t);
	aabb a = rect_aabb(cx, cz, hx, hz, ang, s->y, y1);
	if (overlaps(&a))
		return 0;
	const char *m = diffuse_mat("m");
	/* Half the tables are one closed mesh of five boxes, as a modelled
	 * table is: a solid of several parts, not five solids. */
	int onemesh = form_chance(0.5), soup = fam_chance(0.25);
	prism part[5];
	part[0] = box_prism(cx, cz, hx, hz, ang, y0, y1);
	onemesh |= soup;
	if (!onemesh)
		emit_box(m, cx, cz, hx, hz, ang, y0, y1);
	double ca = cos(ang), sa = sin(ang);
	for (int i = 0; i < 4; i++) {
		double u = (i & 1 ? 1 : -1) * (hx - inset - leg), v = (i & 2 ? 1 : -1) * (hz - inset - leg);
		double lx = cx + u * ca + v * sa, lz = cz - u * sa + v * ca;
		part[1 + i] = box_prism(lx, lz, leg, leg, ang, s->y, y0);
		if (!onemesh)
			emit_box(m, lx, lz, leg, leg, ang, s->y, y0);
	}
	if (soup)
		emit_prisms_soup(m, part, 5, 1, "a table of five boxes");
	else if (onemesh)
		emit_prisms_obj(m, part, 5, 1, "a table of five boxes");
	add_aabb(&a);
	add_support(cx, cz, hx, hz, ang, y1, "table");
	sb_printf(&desc, "; table%s (top %.0f mm, %.0f cm high%s) on %s", soup ? " (OBJ soup)" : onemesh ? " (one OBJ)" : "",
	          t * 1000, ht * 100, inset == 0 ? ", flush legs" : "", sup_name(s));
	return 1;
}

/* A partition: a thin box (1-5 cm) or a single quad, perpendicular to a wall
 * of the region, with a gap under it and/or beside it. */
static int
item_partition(void)
{
	int quad = chance(0.4), along_x = chance(0.5);
	double th = quad ? 0 : rnd(0.01, 0.05), len = rnd(0.4, 1.6), ht = rnd(0.4, fmin(2.0, H - 0.4));
	double under = chance(0.6) ? rnd(0.01, 0.2) : 0, beside = chance(0.5) ? rnd(0.01, 0.2) : 0;
	double y0 = q(floor_y + under), y1 = q(y0 + ht);
	aabb a;
	/* the wall it starts from: the region's side nearer a room wall */
	if (along_x) {  /* runs along x from x = 0 or x = W, at some z */
		int from0 = rx0 < 1e-9 ? 1 : rx1 > W - 1e-9 ? 0 : chance(0.5);
		double z = rnd(rz0 + 0.2, rz1 - 0.2);
		double xa = from0 ? beside : W - beside - len, xb = xa + len;
		if (xa < 0 || xb > W)
			return 0;
		a = (aabb){ { q(xa), y0, q(z - th / 2) }, { q(xb), y1, q(z + th / 2) } };
	} else {
		int from0 = rz0 < 1e-9 ? 1 : rz1 > D - 1e-9 ? 0 : chance(0.5);
		double x = rnd(rx0 + 0.2, rx1 - 0.2);
		double za = from0 ? beside : D - beside - len, zb = za + len;
		if (za < 0 || zb > D)
			return 0;
		a = (aabb){ { q(x - th / 2), y0, q(za) }, { q(x + th / 2), y1, q(zb) } };
	}
	if (overlaps(&a))
		return 0;
	const char *m = diffuse_mat("m");
	if (quad) {
		double p[4][3];
		if (along_x) {
			double z = a.lo[2];
			double c[4][3] = { { a.lo[0], y0, z }, { a.hi[0], y0, z }, { a.hi[0], y1, z }, { a.lo[0], y1, z } };
			memcpy(p, c, sizeof p);
		} else {
			double x = a.lo[0];
			double c[4][3] = { { x, y0, a.hi[2] }, { x, y0, a.lo[2] }, { x, y1, a.lo[2] }, { x, y1, a.hi[2] } };
			memcpy(p, c, sizeof p);
		}
		emit_quad4(m, p);
	} else {
		sb_printf(&geo, "box %s %.5f %.5f %.5f  %.5f %.5f %.5f\n", m, a.lo[0], a.lo[1], a.lo[2], a.hi[0], a.hi[1], a.hi[2]);
	}
	add_aabb(&a);
	sb_printf(&desc, "; partition (%s", quad ? "quad" : "box");
	if (!quad) sb_printf(&desc, " %.0f mm", th * 1000);
	if (under > 0) sb_printf(&desc, ", %.0f mm gap under", under * 1000);
	if (beside > 0) sb_printf(&desc, ", %.0f mm gap at wall", beside * 1000);
	sb_printf(&desc, ")");
	return 1;
}

/* A block standing on the rug (or a hair above it). */
static void
block_on(const support *s, double hair)
{
	double hx = rnd(0.04, fmin(0.25, s->hx * 0.7)), hz = rnd(0.04, fmin(0.25, s->hz * 0.7));
	double h = rnd(0.1, 0.6), cx, cz, ang;
	if (!spot(s, hx, hz, chance(0.5) ? 0 : rnd(0, PI / 2), 0, &cx, &cz, &ang))
		return;
	double y0 = q(s->y + hair), y1 = q(y0 + h);
	aabb a = rect_aabb(cx, cz, hx, hz, ang, y0, y1);
	if (overlaps(&a))
		return;
	emit_box(diffuse_mat("m"), cx, cz, hx, hz, ang, y0, y1);
	add_aabb(&a);
	add_support(cx, cz, hx, hz, ang, y1, "box");
	if (hair > 0)
		sb_printf(&desc, " + block %.1f mm above it", hair * 1000);
	else
		sb_printf(&desc, " + block on it");
}

/* A rug: a sheet 0.1-5 mm above the floor or a table, sometimes with a
 * block on it. */
static int
item_rug(void)
{
	const support *s = pick_support(0.35);
	double e = chance(0.5) ? rnd(0.0001, 0.001) : rnd(0.001, 0.005);
	double hx = rnd(0.15, 0.9), hz = rnd(0.15, 0.9), cx, cz, ang;
	double rel = chance(0.5) ? 0 : rnd(0, PI / 2);
	if (hx > s->hx * 0.95) hx = s->hx * 0.95;
	if (hz > s->hz * 0.95) hz = s->hz * 0.95;
	if (!spot(s, hx, hz, rel, 0, &cx, &cz, &ang))
		return 0;
	double y = q(s->y + e);
	aabb a = rect_aabb(cx, cz, hx, hz, ang, y, y);
	/* the rug must not cut through anything standing on its support */
	aabb a2 = a;
	a2.lo[1] = s->y;
	a2.hi[1] = y + 1e-3;
	if (overlaps(&a2))
		return 0;
	emit_hquad(diffuse_mat("m"), cx, cz, hx, hz, ang, y, 0);
	add_aabb(&a);
	sb_printf(&desc, "; rug %.2f mm above %s", e * 1000, sup_name(s));
	support r = { cx, cz, hx, hz, ang, y, "rug" };
	if (chance(0.6))
		block_on(&r, chance(0.3) ? 0.0001 : 0);
	add_support(cx, cz, hx, hz, ang, y, "rug");
	return 1;
}

/* An overhang: a slab 1-20 cm above the floor on a smaller base box, or a
 * low shelf from a wall, sticking out over the floor. */
static int
item_overhang(void)
{
	double gap = rnd(0.01, 0.2), t = rnd(0.02, 0.08), hx = rnd(0.2, 0.6), hz = rnd(0.15, 0.5);
	double y0 = q(floor_y + gap), y1 = q(y0 + t), cx, cz, ang;
	int shelf = chance(0.35);
	if (!spot(&sup[0], hx, hz, 0, shelf, &cx, &cz, &ang))
		return 0;
	aabb a = rect_aabb(cx, cz, hx, hz, ang, floor_y, y1);
	if (shelf) {
		/* a shelf must touch a wall */
		if (!(fabs(a.lo[0]) < 1e-6 || fabs(a.hi[0] - W) < 1e-6 || fabs(a.lo[2]) < 1e-6 || fabs(a.hi[2] - D) < 1e-6))
			return 0;
	}
	if (overlaps(&a))
		return 0;
	const char *m = diffuse_mat("m");
	emit_box(m, cx, cz, hx, hz, ang, y0, y1);
	if (!shelf) {
		/* the base: smaller, off-centre, so the slab overhangs */
		double bx = hx * rnd(0.3, 0.7), bz = hz * rnd(0.3, 0.7);
		double ox = rnd(-(hx - bx), hx - bx), oz = rnd(-(hz - bz), hz - bz);
		emit_box(m, cx + ox, cz + oz, bx, bz, 0, floor_y, y0);
	}
	add_aabb(&a);
	add_support(cx, cz, hx, hz, 0, y1, "slab");
	sb_printf(&desc, "; overhang (%s, slab %.0f mm over the floor)", shelf ? "wall shelf" : "slab on base", gap * 1000);
	return 1;
}

/* A picture: a quad a hair (0.1-5 mm) in front of a wall of the region. */
static int
item_picture(void)
{
	int walls[4], nw = 0;
	if (rx0 < 1e-9) walls[nw++] = 0;
	if (rx1 > W - 1e-9) walls[nw++] = 1;
	if (rz0 < 1e-9) walls[nw++] = 2;
	if (rz1 > D - 1e-9) walls[nw++] = 3;
	if (!nw)
		return 0;
	int w = walls[irnd(nw)];
	double d = chance(0.5) ? rnd(0.0001, 0.001) : rnd(0.001, 0.005);
	double hw = rnd(0.15, 0.6), hh = rnd(0.15, 0.45), yc = rnd(floor_y + hh + 0.05, fmin(1.8, H - hh - 0.2));
	double y0 = q(yc - hh), y1 = q(yc + hh), p[4][3];
	aabb a;
	if (w < 2) {
		double zc = rnd(rz0 + hw, rz1 - hw), x = w == 0 ? q(d) : q(W - d);
		if (rz1 - rz0 < 2 * hw) return 0;
		a = (aabb){ { x, y0, q(zc - hw) }, { x, y1, q(zc + hw) } };
		/* facing into the room: +x for wall 0, -x for wall 1 */
		double s = w == 0 ? 1 : -1;
		double c[4][3] = { { x, y0, zc + s * hw }, { x, y0, zc - s * hw }, { x, y1, zc - s * hw }, { x, y1, zc + s * hw } };
		memcpy(p, c, sizeof p);
	} else {
		double xc = rnd(rx0 + hw, rx1 - hw), z = w == 2 ? q(d) : q(D - d);
		if (rx1 - rx0 < 2 * hw) return 0;
		a = (aabb){ { q(xc - hw), y0, z }, { q(xc + hw), y1, z } };
		double s = w == 2 ? 1 : -1;
		double c[4][3] = { { xc - s * hw, y0, z }, { xc + s * hw, y0, z }, { xc + s * hw, y1, z }, { xc - s * hw, y1, z } };
		memcpy(p, c, sizeof p);
	}
	/* nothing may stand between the picture and its wall */
	aabb a2 = a;
	switch (w) {
	case 0: a2.lo[0] = 0; a2.hi[0] += 1e-3; break;
	case 1: a2.lo[0] -= 1e-3; a2.hi[0] = W; break;
	case 2: a2.lo[2] = 0; a2.hi[2] += 1e-3; break;
	default: a2.lo[2] -= 1e-3; a2.hi[2] = D; break;
	}
	if (overlaps(&a2))
		return 0;
	emit_quad4(diffuse_mat("m"), p);
	add_aabb(&a);
	sb_printf(&desc, "; picture %.2f mm off a wall", d * 1000);
	return 1;
}

/* A sphere resting on a support (its lowest vertex on it). */
static int
item_sphere(void)
{
	const support *s = pick_support(0.5);
	double r = rnd(0.05, 0.3), cx, cz, ang;
	if (s != &sup[0] && r > fmin(s->hx, s->hz)) r = fmin(s->hx, s->hz);
	if (!spot(s, r * 0.3, r * 0.3, 0, 0, &cx, &cz, &ang))
		return 0;
	aabb a = { { cx - r, s->y, cz - r }, { cx + r, s->y + 2 * r, cz + r } };
	if (overlaps(&a))
		return 0;
	int sub = 2 + irnd(3);  /* 128, 512 or 2048 polygons */
	sb_printf(&geo, "sphere %s %.5f %.5f %.5f %.5f subdiv %d\n", diffuse_mat("m"), q(cx), q(s->y + r), q(cz), q(r), sub);
	add_aabb(&a);
	sb_printf(&desc, "; sphere (subdiv %d) on %s", sub, sup_name(s));
	return 1;
}

/* ---- curved meshes, as Blender's primitives are exported ---- */
typedef struct { double (*v)[3]; int nv, vcap; int *fv, nfv, fvcap; int *fs, nf, fcap; } meshbuf;
static int
mb_vert(meshbuf *M, double x, double y, double z)
{
	if (M->nv == M->vcap && !(M->v = realloc(M->v, (size_t)(M->vcap = 2 * M->vcap + 256) * sizeof *M->v))) { perror("genscene"); exit(1); }
	M->v[M->nv][0] = x, M->v[M->nv][1] = y, M->v[M->nv][2] = z;
	return ++M->nv;  /* 1-based, as OBJ */
}
static void
mb_face(meshbuf *M, int n, int a, int b, int c, int d)
{
	int idx[4] = { a, b, c, d };
	if (M->nf + 2 > M->fcap && !(M->fs = realloc(M->fs, (size_t)(M->fcap = 2 * M->fcap + 256) * sizeof *M->fs))) { perror("genscene"); exit(1); }
	if (M->nfv + 4 > M->fvcap && !(M->fv = realloc(M->fv, (size_t)(M->fvcap = 2 * M->fvcap + 1024) * sizeof *M->fv))) { perror("genscene"); exit(1); }
	M->fs[M->nf++] = M->nfv;
	for (int i = 0; i < n; i++)
		M->fv[M->nfv++] = idx[i];
	M->fs[M->nf] = M->nfv;
}
/* A UV sphere of nu segments and nv rings (quads, triangles at the poles). */
static void
mb_uvsphere(meshbuf *M, int nu, int nv, double r)
{
	int top = mb_vert(M, 0, r, 0), b0 = M->nv + 1, bot;
	for (int j = 1; j < nv; j++)
		for (int i = 0; i < nu; i++) {
			double th = PI * j / nv, ph = 2 * PI * i / nu;
			mb_vert(M, r * sin(th) * cos(ph), r * cos(th), -r * sin(th) * sin(ph));
		}
	bot = mb_vert(M, 0, -r, 0);
#define AT(j, i) (b0 + ((j) - 1) * nu + (i) % nu)
	for (int i = 0; i < nu; i++)
		mb_face(M, 3, top, AT(1, i), AT(1, i + 1), 0);
	for (int j = 1; j < nv - 1; j++)
		for (int i = 0; i < nu; i++)
			mb_face(M, 4, AT(j, i), AT(j + 1, i), AT(j + 1, i + 1), AT(j, i + 1));
	for (int i = 0; i < nu; i++)
		mb_face(M, 3, AT(nv - 1, i + 1), AT(nv - 1, i), bot, 0);
#undef AT
}
/* A torus about y: nu segments round the ring, nv round the tube. */
static void
mb_torus(meshbuf *M, int nu, int nv, double R, double r)
{
	int b0 = M->nv + 1;
	for (int i = 0; i < nu; i++)
		for (int j = 0; j < nv; j++) {
			double ph = 2 * PI * i / nu, th = 2 * PI * j / nv, d = R + r * cos(th);
			mb_vert(M, d * cos(ph), r * sin(th), -d * sin(ph));
		}
#define AT(i, j) (b0 + ((i) % nu) * nv + (j) % nv)
	for (int i = 0; i < nu; i++)
		for (int j = 0; j < nv; j++)
			mb_face(M, 4, AT(i, j), AT(i + 1, j), AT(i + 1, j + 1), AT(i, j + 1));
#undef AT
}
/* An open tube of n sides from y = 0 to h, no caps. */
static void
mb_tube(meshbuf *M, int n, double r, double h)
{
	int b0 = M->nv + 1;
	for (int k = 0; k < 2; k++)
		for (int i = 0; i < n; i++)
			mb_vert(M, r * cos(2 * PI * i / n), k * h, -r * sin(2 * PI * i / n));
	for (int i = 0; i < n; i++)
		mb_face(M, 4, b0 + i, b0 + (i + 1) % n, b0 + n + (i + 1) % n, b0 + n + i);
}
/* A blobby head: an octahedron subdivided level times onto the unit
 * sphere (8 * 4^level triangles), displaced by a few smooth random waves. */
static void
mb_blob(meshbuf *M, int level, double r)
{
	static const double o[6][3] = { { 1, 0, 0 }, { -1, 0, 0 }, { 0, 1, 0 }, { 0, -1, 0 }, { 0, 0, 1 }, { 0, 0, -1 } };
	static const int f8[8][3] = { { 0, 2, 4 }, { 4, 2, 1 }, { 1, 2, 5 }, { 5, 2, 0 }, { 4, 3, 0 }, { 1, 3, 4 }, { 5, 3, 1 }, { 0, 3, 5 } };
	double wv[5][4];
	int n = 1 << level;
	for (int w = 0; w < 5; w++)
		for (int k = 0; k < 4; k++)
			wv[w][k] = k < 3 ? rnd(-3, 3) : rnd(0, 2 * PI);
	/* each face of the octahedron as a triangular grid of n steps; edge
	 * vertices are repeated per face and merged by position below. */
	for (int t = 0; t < 8; t++) {
		const double *A = o[f8[t][0]], *B = o[f8[t][1]], *C = o[f8[t][2]];
		int row0 = M->nv + 1;
		for (int i = 0; i <= n; i++)
			for (int j = 0; j <= n - i; j++) {
				double p[3], l = 0, s = 0;
				for (int k = 0; k < 3; k++) {
					p[k] = (A[k] * (n - i - j) + B[k] * i + C[k] * j) / n;
					l += p[k] * p[k];
				}
				l = sqrt(l);
				for (int k = 0; k < 3; k++)
					p[k] /= l;
				for (int w = 0; w < 5; w++)
					s += sin(wv[w][0] * p[0] + wv[w][1] * p[1] + wv[w][2] * p[2] + wv[w][3]);
				s = r * (1 + 0.06 * s);
				mb_vert(M, p[0] * s, p[1] * s, p[2] * s);
			}
#define AT(i, j) (row0 + (i) * (n + 1) - (i) * ((i) - 1) / 2 + (j))
		for (int i = 0; i < n; i++)
			for (int j = 0; j < n - i; j++) {
				mb_face(M, 3, AT(i, j), AT(i + 1, j), AT(i, j + 1), 0);
				if (j < n - i - 1)
					mb_face(M, 3, AT(i + 1, j), AT(i + 1, j + 1), AT(i, j + 1), 0);
			}
#undef AT
	}
	/* merge repeated edge vertices (equal after rounding to the 1e-5 grid) */
	int *map = malloc((size_t)M->nv * sizeof *map);
	if (!map) { perror("genscene"); exit(1); }
	for (int i = 0; i < M->nv; i++) {
		map[i] = i;
		for (int k = 0; k < i && map[i] == i; k++)
			if (map[k] == k && q(M->v[k][0]) == q(M->v[i][0]) && q(M->v[k][1]) == q(M->v[i][1]) && q(M->v[k][2]) == q(M->v[i][2]))
				map[i] = k;
	}
	/* ... and the kept ones renumbered, so no vertex is left unused */
	int nk = 0;
	for (int i = 0; i < M->nv; i++)
		if (map[i] == i) {
			memcpy(M->v[nk], M->v[i], sizeof M->v[i]);
			map[i] = nk++;
		} else
			map[i] = map[map[i]];
	M->nv = nk;
	for (int i = 0; i < M->nfv; i++)
		M->fv[i] = map[M->fv[i] - 1] + 1;
	free(map);
}

/* A curved mesh (a UV sphere 48 x 24, a torus 48 x 16 lying flat, an open
 * 48-sided tube standing up, a blobby head of 2048 triangles) resting on
 * a support at its lowest vertices; a third of them written as polygon
 * soups. Drawn from the families' stream (fam_begin). */
static int
item_curved(void)
{
	static const char *kinds[] = { "UV sphere 48x24", "torus 48x16", "open tube (48 sides)", "blobby head (2048 triangles)" };
	const support *s = pick_support(0.4);
	int kind = irnd(4), soup = chance(0.3);
	double r = rnd(0.08, 0.3), cx, cz, ang;
	meshbuf M = { 0 };
	if (s != &sup[0] && r > fmin(s->hx, s->hz))
		r = fmin(s->hx, s->hz);
	if (!spot(s, r, r, 0, 0, &cx, &cz, &ang))
		return 0;
	if (kind == 0)
		mb_uvsphere(&M, 48, 24, r);
	else if (kind == 1)
		mb_torus(&M, 48, 16, r * 0.7, r * rnd(0.12, 0.3));
	else if (kind == 2)
		mb_tube(&M, 48, r, rnd(0.1, 0.5));
	else
		mb_blob(&M, 4, r * 0.9);
	double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
	for (int i = 0; i < M.nv; i++)
		for (int k = 0; k < 3; k++) {
			lo[k] = fmin(lo[k], M.v[i][k]);
			hi[k] = fmax(hi[k], M.v[i][k]);
		}
	/* the lowest vertices exactly on the support */
	for (int i = 0; i < M.nv; i++) {
		M.v[i][0] += cx;
		M.v[i][1] = q(s->y + q(M.v[i][1] - lo[1]));
		M.v[i][2] += cz;
	}
	aabb a = { { cx + lo[0], s->y, cz + lo[2] }, { cx + hi[0], s->y + hi[1] - lo[1], cz + hi[2] } };
	int ok = !overlaps(&a);
	if (ok) {
		char what[80];
		snprintf(what, sizeof what, "%s%s", kinds[kind], soup ? ", polygon soup" : "");
		emit_obj(diffuse_mat("m"), (const double (*)[3])M.v, M.nv, M.fv, M.fs, M.nf, soup, what);
		add_aabb(&a);
		sb_printf(&desc, "; %s%s on %s", kinds[kind], soup ? " (soup)" : "", sup_name(s));
	}
	free(M.v);
	free(M.fv);
	free(M.fs);
	return ok;
}

static void
usage(void)
{
	fprintf(stderr, "usage: genscene SEED OUTDIR [--furnace] [--size W H]\n");
	exit(2);
}

int
main(int argc, char **argv)
{
	int iw = 96, ih = 72;
	char *end;
	if (argc < 3)
		usage();
	errno = 0;
	unsigned long long seed = strtoull(argv[1], &end, 10);
	if (errno || end == argv[1] || *end)
		usage();
	outdir = argv[2];
	for (int i = 3; i < argc; i++) {
		if (!strcmp(argv[i], "--furnace"))
			furnace = 1;
		else if (!strcmp(argv[i], "--size") && i + 2 < argc) {
			iw = atoi(argv[i + 1]);
			ih = atoi(argv[i + 2]);
			i += 2;
			if (iw < 1 || ih < 1 || iw > 65535 || ih > 65535)
				usage();
		} else
			usage();
	}
	if (mkdir(outdir, 0777) && errno != EEXIST) {
		fprintf(stderr, "genscene: cannot create '%s': %s\n", outdir, strerror(errno));
		return 1;
	}
	rng_state = seed * 0x2545f4914f6cdd1dull + 0x1234567;
	form_state = seed * 0x9e3779b97f4a7c15ull + 0x7654321;
	fam_state = seed * 0xd1342543de82ef95ull + 0x2468ace;
	shell_state = seed * 0xbf58476d1ce4e5b9ull + 0x13579bd;
	view_state = seed * 0x94d049bb133111ebull + 0x2c1b3c6d;
	next64();

	/* the room */
	W = q(rnd(3, 6)); D = q(rnd(3, 6)); H = q(rnd(2.4, 3.2));
	W = round(W * 100) / 100; D = round(D * 100) / 100; H = round(H * 100) / 100;
	const char *wall = diffuse_mat("wall");
	/* A fifth of the rooms are six separate quads facing in (a polygon
	 * soup of walls, as modelling tools export a room), not one closed box. */
	if (fam_chance(0.2)) {
		double c[6][4][3] = {
			{ { 0, 0, 0 }, { 0, 0, D }, { W, 0, D }, { W, 0, 0 } },
			{ { 0, H, 0 }, { W, H, 0 }, { W, H, D }, { 0, H, D } },
			{ { 0, 0, 0 }, { W, 0, 0 }, { W, H, 0 }, { 0, H, 0 } },
			{ { 0, 0, D }, { 0, H, D }, { W, H, D }, { W, 0, D } },
			{ { 0, 0, 0 }, { 0, H, 0 }, { 0, H, D }, { 0, 0, D } },
			{ { W, 0, 0 }, { W, 0, D }, { W, H, D }, { W, H, 0 } } };
		/* Half of them are one OBJ of the six faces wound outward, as a
		 * modelling program exports a scaled cube (shared corners, or a
		 * soup of loose faces that pm welds shut): a closed surface
		 * round the eye, which pm turns over (formats/scene.md). */
		if (side_chance(&shell_state, 0.5)) {
			int soup = side_chance(&shell_state, 0.5), fv[24], fs[7];
			double vt[8][3];
			for (int i = 0; i < 6; i++) {
				fs[i] = 4 * i;
				for (int j = 0; j < 4; j++) {
					const double *p = c[i][3 - j];
					int k = (p[0] > 0) | (p[1] > 0) << 1 | (p[2] > 0) << 2;
					memcpy(vt[k], p, sizeof vt[0]);
					fv[4 * i + j] = k + 1;
				}
			}
			fs[6] = 24;
			emit_obj(wall, (const double (*)[3])vt, 8, fv, fs, 6, soup,
			         soup ? "a room: six faces wound outward, loose" : "a room: six faces wound outward");
			sb_printf(&desc, "room as one OBJ facing out%s %.1fx%.1fx%.1f", soup ? " (soup)" : "", W, D, H);
		} else {
			for (int i = 0; i < 6; i++)
				emit_quad4(wall, (const double (*)[3])c[i]);
			sb_printf(&desc, "room of six quads %.1fx%.1fx%.1f", W, D, H);
		}
	} else {
		sb_printf(&geo, "box %s 0 0 0  %.2f %.2f %.2f inward\n", wall, W, H, D);
		sb_printf(&desc, "room %.1fx%.1fx%.1f", W, D, H);
	}
	/* the floor: the room's own, or a quad laid over it */
	floor_y = 0;
	if (chance(0.5)) {
		double f = chance(0.3) ? 0 : chance(0.5) ? 0.0005 : rnd(0.0001, 0.002);
		const char *fm;
		int glossy = chance(0.6);
		if (glossy) {
			double kd = rnd(0.3, 0.6), ks = rnd(0.1, fmin(0.4, 0.95 - kd));
			fm = material("floor", "glossy kd %.3f %.3f %.3f ks %.3f %.3f %.3f exponent %.1f",
			              kd, kd * rnd(0.7, 1), kd * rnd(0.5, 1), ks, ks, ks, rnd(2, 60));
		} else
			fm = diffuse_mat("floor");
		floor_y = q(f);
		coplanar_floor = floor_y == 0;
		emit_hquad(fm, W / 2, D / 2, W / 2, D / 2, 0, floor_y, 0);
		sb_printf(&desc, ", %s floor quad %.2f mm over the floor", glossy ? "soft-glossy" : "diffuse", f * 1000);
	}

	/* the focus region: a corner, the middle of a wall, or the middle */
	double F = rnd(1.4, 2.4);
	int where = irnd(10);
	if (where < 6) {
		int cxr = chance(0.5), czr = chance(0.5);
		rx0 = cxr ? W - fmin(F, W - 0.5) : 0; rx1 = cxr ? W : fmin(F, W - 0.5);
		rz0 = czr ? D - fmin(F, D - 0.5) : 0; rz1 = czr ? D : fmin(F, D - 0.5);
		sb_printf(&desc, ", in a corner");
	} else if (where < 9) {
		double hw = fmin(F, W - 0.4) / 2;
		rx0 = W / 2 - hw; rx1 = W / 2 + hw;
		int far = chance(0.5);
		rz0 = far ? D - fmin(F, D - 0.5) : 0; rz1 = far ? D : fmin(F, D - 0.5);
		sb_printf(&desc, ", at a wall");
	} else {
		rx0 = W / 2 - fmin(F, W - 0.6) / 2; rx1 = W / 2 + fmin(F, W - 0.6) / 2;
		rz0 = D / 2 - fmin(F, D - 0.6) / 2; rz1 = D / 2 + fmin(F, D - 0.6) / 2;
		sb_printf(&desc, ", mid-room");
	}
	rx0 = q(rx0); rx1 = q(rx1); rz0 = q(rz0); rz1 = q(rz1);
	add_support((rx0 + rx1) / 2, (rz0 + rz1) / 2, (rx1 - rx0) / 2, (rz1 - rz0) / 2, 0, floor_y, "floor");
	sb_printf(&desc, ":");

	/* the items */
	int n = 1 + irnd(4), placed = 0;
	for (int it = 0; it < n; it++) {
		for (int tries = 0; tries < 40; tries++) {
			/* weights: boxes 3, blocks 2, table 2, partition 1, rug 2,
			 * overhang 1, picture 1, sphere 2 */
			int k = irnd(14), ok;
			size_t g0 = geo.n, d0 = desc.n;
			int nm0 = nmat, nb0 = nboxes, ns0 = nsup, nmesh0 = nmesh;
			if (k < 3) ok = item_boxes();
			else if (k < 5) ok = item_block();
			else if (k < 7) ok = item_table();
			else if (k < 8) ok = item_partition();
			else if (k < 10) ok = item_rug();
			else if (k < 11) ok = item_overhang();
			else if (k < 12) ok = item_picture();
			else ok = item_sphere();
			if (ok) { placed++; break; }
			/* undo a partial item */
			geo.n = g0; desc.n = d0; nmat = nm0; nboxes = nb0; nsup = ns0;
			if (nmesh != nmesh0) nmesh = nmesh0;  /* its file is overwritten later or left unused */
			if (geo.s) geo.s[geo.n] = 0;
			if (desc.s) desc.s[desc.n] = 0;
		}
	}
	/* A curved mesh besides, from the families' stream. */
	if (fam_chance(0.25)) {
		fam_begin();
		for (int tries = 0; tries < 20; tries++) {
			int nm0 = nmat;
			if (item_curved()) {
				placed++;
				break;
			}
			nmat = nm0;
		}
		fam_end();
	}
	if (!placed) {  /* cannot happen in practice: a sphere always fits */
		const char *m = diffuse_mat("m");
		double r = 0.2, cx = (rx0 + rx1) / 2, cz = (rz0 + rz1) / 2;
		sb_printf(&geo, "sphere %s %.5f %.5f %.5f %.5f\n", m, q(cx), q(floor_y + r), q(cz), r);
		boxes[nboxes++] = (aabb){ { cx - r, floor_y, cz - r }, { cx + r, floor_y + 2 * r, cz + r } };
		sb_printf(&desc, "; sphere on floor");
	}

	/* the camera: looking from the room side at the bounds of all the
	 * items or (half the time, so that contacts fill the frame) of one
	 * object */
	aabb u = boxes[0];
	if (chance(0.5))
		u = boxes[irnd(nboxes)];
	else
		for (int i = 1; i < nboxes; i++)
			for (int k = 0; k < 3; k++) {
				u.lo[k] = fmin(u.lo[k], boxes[i].lo[k]);
				u.hi[k] = fmax(u.hi[k], boxes[i].hi[k]);
			}
	double look[3] = { (u.lo[0] + u.hi[0]) / 2, u.lo[1] + 0.4 * (u.hi[1] - u.lo[1]), (u.lo[2] + u.hi[2]) / 2 };
	double rad = 0.5 * sqrt((u.hi[0] - u.lo[0]) * (u.hi[0] - u.lo[0]) + (u.hi[1] - u.lo[1]) * (u.hi[1] - u.lo[1]) +
	                        (u.hi[2] - u.lo[2]) * (u.hi[2] - u.lo[2]));
	rad = fmax(rad, 0.25);
	double fov = rnd(35, 60), eye[3] = { W / 2, H * 0.6, D / 2 };
	double base = atan2(D / 2 - look[2], W / 2 - look[0]);
	if (fabs(D / 2 - look[2]) + fabs(W / 2 - look[0]) < 0.3)
		base = rnd(0, 2 * PI);
	double want = rad / tan(fov * PI / 360) * rnd(0.8, 1.05);
	for (int tries = 0; tries < 40; tries++) {
		double az = base + rnd(-0.6, 0.6), el = rnd(10, 45) * PI / 180;
		double dir[3] = { cos(el) * cos(az), sin(el), cos(el) * sin(az) }, t = want;
		/* stay inside the room, 5 cm from its walls */
		for (int k = 0; k < 3; k++) {
			double lo = 0.05, hi = (k == 0 ? W : k == 1 ? H : D) - 0.05;
			if (dir[k] > 1e-9) t = fmin(t, (hi - look[k]) / dir[k]);
			if (dir[k] < -1e-9) t = fmin(t, (lo - look[k]) / dir[k]);
		}
		if (t < 0.3)
			continue;
		double e[3] = { look[0] + t * dir[0], look[1] + t * dir[1], look[2] + t * dir[2] };
		if (near_items(e))
			continue;
		memcpy(eye, e, sizeof eye);
		break;
	}

	/* the lights */
	int kind = irnd(10);  /* 0-4 point, 5-8 area, 9 both */
	double P = rnd(30, 80) * W * D / 16;
	int npoint = 0;
	if (kind <= 4 || kind == 9) {
		for (int tries = 0; tries < 100; tries++) {
			double p[3] = { rnd(0.3, W - 0.3), rnd(0.6 * H, H - 0.15), rnd(0.3, D - 0.3) };
			aabb a = { { p[0] - 0.05, p[1] - 0.05, p[2] - 0.05 }, { p[0] + 0.05, p[1] + 0.05, p[2] + 0.05 } };
			if (overlaps(&a) && tries < 99)
				continue;
			double tg = rnd(0.85, 1), tb = rnd(0.7, 1);  /* drawn in both modes */
			if (!furnace)
				sb_printf(&geo, "pointlight %.5f %.5f %.5f power %.3f %.3f %.3f\n",
				          q(p[0]), q(p[1]), q(p[2]), P, P * tg, P * tb);
			npoint++;
			break;
		}
	}
	if (kind >= 5 || !npoint) {
		double sx = rnd(0.15, 0.4), sz = rnd(0.15, 0.4), gap = rnd(0.0005, 0.002);
		double cx = fmin(fmax((look[0] + W / 2) / 2, sx + 0.05), W - sx - 0.05);
		double cz = fmin(fmax((look[2] + D / 2) / 2, sz + 0.05), D - sz - 0.05);
		double L = P / (PI * 4 * sx * sz);
		const char *lamp = material("lamp", "diffuse albedo 0.5 0.5 0.5 emit %.3f %.3f %.3f", L, L * rnd(0.85, 1), L * rnd(0.7, 1));
		emit_hquad(lamp, cx, cz, sx, sz, 0, H - gap, 1);
		sb_printf(&desc, "; area light %.1f mm under the ceiling", gap * 1000);
	}
	if (npoint)
		sb_printf(&desc, "; point light");

	/* A quarter of the views look instead at the top of a wall, where it
	 * meets the ceiling (the camera above sees the items, and so almost
	 * never that corner). Drawn after everything else, from a stream of
	 * its own, so the rest of the scene is what it was. */
	if (side_chance(&view_state, 0.25)) {
		side_begin(&view_state);
		int wall = irnd(4);
		double a = rnd(0.25, 0.75), drop = rnd(0.15, 0.6), across = rnd(0.55, 0.9);
		double ey = rnd(0.9, 1.7), side = rnd(-0.2, 0.2), vf = rnd(35, 60);
		side_end(&view_state);
		/* wall 0, 1: x = 0, W; 2, 3: z = 0, D */
		double L = wall < 2 ? D : W, A = wall < 2 ? W : D;
		double on = a * L, off = fmin(fmax(across * A, 0.3), A - 0.05);
		double lk[3], e[3];
		lk[1] = H - drop;
		e[1] = fmin(ey, H - 0.05);
		double lw = wall == 0 || wall == 2 ? 0 : A, ew = wall == 0 || wall == 2 ? off : A - off;
		double eo = fmin(fmax(on + side * L, 0.05), L - 0.05);
		if (wall < 2) {
			lk[0] = lw; lk[2] = on; e[0] = ew; e[2] = eo;
		} else {
			lk[2] = lw; lk[0] = on; e[2] = ew; e[0] = eo;
		}
		if (!near_items(e)) {
			memcpy(eye, e, sizeof eye);
			memcpy(look, lk, sizeof look);
			fov = vf;
			sb_printf(&desc, "; view of a wall's top");
		}
	}

	/* the file */
	char path[4096];
	FILE *f;
	snprintf(path, sizeof path, "%s/scene.pms", outdir);
	if (!(f = fopen(path, "w"))) {
		fprintf(stderr, "genscene: cannot write '%s': %s\n", path, strerror(errno));
		return 1;
	}
	for (char *c; (c = strstr(desc.s, ":; "));)
		memmove(c + 1, c + 2, strlen(c + 2) + 1);
	fprintf(f, "# genscene %llu%s: %s\n", seed, furnace ? " --furnace (exact radiance 2)" : "", desc.s);
	if (furnace)
		fprintf(f, "# torture: exact 2\n");
	/* Two coplanar two-sided emitters emit into a gap of no thickness:
	 * no renderer reads 2 there (the path tracer neither). */
	if (furnace && coplanar_floor)
		fprintf(f, "# torture: no furnace twin\n");
	fprintf(f, "camera eye %.5f %.5f %.5f  look %.5f %.5f %.5f  up 0 1 0  fov %.1f  size %d %d\n",
	        q(eye[0]), q(eye[1]), q(eye[2]), q(look[0]), q(look[1]), q(look[2]), fov, iw, ih);
	fprintf(f, "glossy_threshold 100\n");
	for (int i = 0; i < nmat; i++)
		fprintf(f, "material %s %s\n", mat_name[i],
		        furnace ? "diffuse albedo 0.5 0.5 0.5 emit 1 1 1 twosided" : mat_spec[i]);
	fputs(geo.s, f);
	if (fclose(f)) {
		fprintf(stderr, "genscene: cannot write '%s': %s\n", path, strerror(errno));
		return 1;
	}
	printf("%s\n", desc.s);
	return 0;
}
