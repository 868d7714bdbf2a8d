/* compensate.c — the compensated radiance estimate (Hey & Purgathofer 2001,
 * "Global Illumination with Photon Map Compensation", §3, eq. 1-4): photons
 * in the L-infinity cube around x, the photon-surface polygons clipped into
 * it, each photon's flux spread over its own target area A_p. The model that
 * decides what counts as target area is in compensate.h.
 *
 * Cost: one k-nearest search; one pass over the polygons that meet the cube
 * (typically 1-3), clipping each once; the polygons grouped into sheets
 * (groups()); pairwise tests between polygons of different groups to find
 * which can hide which, a group whose box is out of reach passed over whole,
 * and in a cube of many polygons only pairs that x' sees in one direction
 * (sight.h) tested (on a rough mesh, many groups, the pairs are the cost:
 * bench/compcost.sh). A polygon that many may hide stops its walk there
 * and keeps no list: what x' sees of it comes from segments through a tree
 * of the cube's polygons (boxtree.h, seen_cast()). In a cube of many
 * polygons (FATE_CAST_POLYS) there are no lists of what a backward ray may
 * meet either: the points' rays go through that tree, a few parallel ones
 * in one walk (cast_fates()).
 * Only polygons that something can hide (or, there, that are lit and
 * seen) get sample points, but not one that a single polygon hides whole
 * (x's own, or one on its list: hides_all()), which is unseen at once;
 * and only their samples cost work per photon; a photon on a sheet
 * nothing touches costs a slab test and a dot product. All geometry is
 * double and relative to x. */
#include "estimators/compensate.h"

#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/grow.h"
#include "optics/bsdf.h"
#include "estimators/boxtree.h"
#include "estimators/clip.h"
#include "estimators/overlap.h"
#include "estimators/sight.h"

/* A polygon whose unit normal is this close to +-n is taken as lying in the
 * plane of x (1 - cos of about 1.4 milliradians). */
#define PARALLEL_EPS 1e-6
#define MAX_K (1 << 24)
/* Sample points per polygon that something can hide: GRID x GRID cells of
 * its bounding rectangle, those inside it. */
#define GRID 8
/* fates_hit() keeps a polygon's dynamic samples in one 64-bit set, and
 * sample() packs a cell's column and row in a byte. */
_Static_assert(GRID * GRID <= 64 && GRID <= 16, "GRID too large for fates_hit()");
/* Convex polygons up to this many vertices find their cells inside row by row. */
#define ROW_MAX_VERTS 32
/* Two planes at most this far from perpendicular (|N_a . N_b| >= LAYER_COS)
 * are layers: one over the other, not walls meeting at an edge. */
#define LAYER_COS 0.5
/* x' = x + XOFF_REL h n: the point just off x's surface that looks. */
#define XOFF_REL 1e-3
/* Faces of x's own solid turned less than this from n (cos 30 degrees: the
 * facets of a tessellated curve) are seen through it; those across a
 * sharper convex edge are not: their light is their own. */
#define SMOOTH_COS 0.866
/* In a polygon's list of what its backward rays may meet: a solid that is
 * no layer over it, which matters only when met from behind. */
#define MATTER (1 << 30)
/* A smooth patch's polygons in the cube (scene/patch.h) whose sides that
 * count all lie within this of their mean (cos 45.6 degrees) are one
 * sheet: one surface at the cube's scale, many facets (a curved or scanned
 * mesh). A sheet hides none of itself from x', and a backward ray leaving
 * it does not meet it again, as holds exactly for a flat polygon and for
 * rays steeper than the sheet's slopes. (30 degrees, SMOOTH_COS, cost a
 * dense mesh 1.6 times as much for no measurable change in the torture
 * scenes with curved meshes: BENCHMARKS.md, "Sheets".) */
#define SHEET_COS 0.7
/* A patch that bends past SHEET_COS in the cube (a sphere, a torus's tube,
 * a head) is peeled into sheets (peel()): at most PEEL_TRIES directions
 * tried, each moved to the mean of what lies within SHEET_COS of it up to
 * PEEL_STEPS times. Four tries leave 2 303 of meshroom's 243 389 polygons
 * in cubes alone, sixteen 2 284; one try 28 372 (BENCHMARKS.md, "Bent
 * patches peeled into sheets"). */
#define PEEL_TRIES 4
#define PEEL_STEPS 4
/* From this many polygons in a cube of two groups or more, the fates of
 * P's points are found by rays through a tree of the cube's polygons
 * (cast_fates()), asking of each polygon met what P's list would have
 * said, rather than from lists: where two sheets of hundreds of facets
 * face each other, or a rough mesh's facets face every way, the lists hold
 * for each polygon most of the others, and the work grew with the square
 * of the facets. 32, 64 and 128 cost meshroom 3.08, 2.97 and 2.97 G
 * instructions, scanned 14.1, 14.3 and 15.0 G, dense 7.06 G each. */
#define FATE_CAST_POLYS 64
/* There, a polygon whose list would hold at most FRONT_MAX polygons that a
 * ray from it may meet, found among the first FRONT_SCAN whose boxes reach
 * its front, keeps them, and its rays try those alone (front_list()). */
#define FRONT_MAX 16
#define FRONT_SCAN 64
/* ... a polygon wholly in front of it. */
#define FRONT (1 << 29)
/* cast_closed()'s answers a polygon keeps: two bits a run. */
#define CLOSED_KEPT 32
/* From this many polygons in the cube, the candidates that may hide one
 * from x' come from a grid of where x' sees them (sight.h); below, from
 * every pair. Both apply the same test. */
#define SIGHT_MIN 32
/* From this many, a polygon x' sees across an edge of the cube of
 * directions gets a box on each face it reaches (pm_sight_box's across)
 * rather than every direction, which put it on every query's list and
 * every pair with it past the grid: a quarter of the polygons of
 * meshroom's cubes of 256 or more. Clipping it to the faces costs more
 * than that saves in smaller cubes (prims, cove: +1-2 % from 32 on). */
#define SIGHT_ACROSS 128
/* Up to this many groups in the cube (a smooth mesh is a few sheets), each
 * is asked once per polygon whether it can hide any of it; the grid is
 * queried only when those that can hold SIGHT_MIN polygons or more. A
 * query on a sheet of thousands of facets returns mostly the polygon's own
 * sheet, which is never on its list (dense: two thirds of an estimate). */
#define FEW_GROUPS 8
/* A polygon of a cube of SIGHT_MIN polygons or more that this many others
 * may hide (a rough mesh, where each facet has hundreds) keeps no list:
 * its pair walk stops at the CAST_AT-th, and what x' sees of it is found
 * by segments through a tree of the cube's polygons (seen_cast()), asking
 * of each polygon crossed what the walk would have: the same answer, with
 * work that grows with the points, not the pairs. */
#define CAST_AT 16
int pm_comp_cast_at = CAST_AT;
int pm_comp_fate_cast_from = FATE_CAST_POLYS;
int pm_comp_exact_overlap = 1;
int pm_comp_shadow_from = 6;
int pm_comp_fronts_wait = 1;
int pm_comp_hidden_whole = 1;
int pm_comp_sheet_nodes = 1;
int pm_comp_share_cells = 1;
int pm_comp_photon_grid = 1;
#define IDX(e) ((e) & (FRONT - 1))

typedef struct cpoly {
	uint32_t g;            /* scene polygon */
	int obj, solid;
	pm_dvec3 N, Ne;        /* unit normal; the side that counts (see .h) */
	double d, de;          /* N . v and Ne . v on its plane, v relative to x */
	double A;              /* area in the cube */
	int v0, nv;            /* clipped vertices sc->cv[v0 ..], sc->uv[2 v0 ..] */
	int ax;                /* axis N points most along (2-D inside test) */
	int convex;
	double nax;            /* |N| along it */
	double lo[3], hi[3];   /* bounding box of the clipped polygon */
	pm_dvec3 c;            /* ... its centre, and a radius about c */
	double rad;
	int xon;               /* x lies on it */
	int xpar;              /* parallel to n */
	int r0, nr;            /* polygons that may hide part of it from x' */
	int cast;              /* ... not listed: nr is CAST_AT, seen_cast() asks */
	int own;               /* x lies on its solid, as pair_lists() says */
	int f0, nf;            /* polygons a backward ray from it may meet ... */
	int nfc;               /* ... the first nfc lying on its plane */
	int s0, ns;            /* sample points kept: the ndyn first, then
	                          those covered for every direction */
	int ncell;             /* cells its area was shared among */
	int unseen;            /* not seen from x' at all: a solid's face turned
	                          away, or hidden whole by one polygon (hides_all()) */
	int lit;               /* faces some photon used: else nothing of it counts,
	                          and it needs no lists and no samples */
	double aopen;          /* area seen from x', not covered by a polygon on its plane */
	int ndyn;              /* samples whose fate depends on the direction */
	double adyn;           /* ... their area seen from x' */
	int grp;               /* its group (cgroup) */
	int fcast;             /* fates by rays (cast_fates()): no F list, every
	                          point it shows x' is dynamic */
	int gpos;              /* its place in sc->gp (list order, cast_fates()) */
	int share;             /* 1 + the facet whose point's backward rays
	                          stand for those of its cell's (share_cells()),
	                          itself included; 0: its own */
	int fl0, nfl;          /* fates by rays: what its list would hold that
	                          a ray from it may meet, sc->fl[fl0 ..], in
	                          list order, or nfl -1: too many, each ray
	                          goes through the tree (front_list()) */
	int orun;              /* its object's run in sc->oby (cast_fates()) */
	uint64_t closed;       /* cast_closed() for runs r < CLOSED_KEPT: bit
	                          2 r known, bit 2 r + 1 closed */
} cpoly;

/* The cube's polygons in groups: a sheet (see SHEET_COS), or one polygon.
 * Groups are numbered by their lowest polygon, and a group's polygons are
 * in ascending order, so walking groups and then their polygons visits the
 * polygons in their own order where every group is one polygon. */
typedef struct cgroup {
	uint32_t key;          /* smooth patch */
	int p0, np;            /* its polygons: sc->gp[p0 .. p0 + np) */
	int sheet;             /* a sheet of two polygons or more */
	int xsheet;            /* ... that x lies on */
	int simple;            /* every polygon seen whole with open fates, so
	                          no photon needs to know which one it is on */
	pm_dvec3 M;            /* the mean of the sides that count, unit */
	double cmin;           /* the least Ne . M, and sqrt(1 - cmin^2): */
	double sina;           /* Psi . M above it faces every polygon */
	double slo, shi;       /* M . v over its clipped vertices */
	pm_dvec3 c;            /* centre and radius of a sphere around it */
	double rad;
	double lo[3], hi[3];   /* its box */
	pm_dvec3 V;            /* sum of A Ne over polygons not parallel to n */
	double apar;           /* sum of A over those parallel, facing n */
	/* A sheet that is not simple: V and apar over its plain polygons
	 * (seen whole, open fates, like a simple sheet's), and the others,
	 * sc->gq[q0 .. q0 + nq), asked one by one. */
	pm_dvec3 Vp;
	double aparp;
	int q0, nq;
} cgroup;

/* A sampled polygon's grid, for fates_hit(): its plane_axes() t1 and t2,
 * the G columns' coordinate along t1 (v[0 .. G)) and the rows' along t2
 * (v[GRID .. GRID + G)), each as sample() worked it out for all of its
 * cells, and per column and row the set of its dynamic samples there (bit
 * s: sample s0 + s). A polygon whose cells all missed it has one sample,
 * its vertices' mean, as a grid of one. */
typedef struct sgrid {
	int G;
	pm_dvec3 t1, t2;
	double v[2 * GRID];
	uint64_t m[2 * GRID];
} sgrid;

struct pm_comp_scratch {
	int k;
	int *cellt, celltcap;  /* share_cells()'s table: cell key, facet */
	int *rayat, *rayhit;   /* a shared ray's answer (1: x's fate) along
	                          photon rayat - 1's direction */
	int rayatcap, rayhitcap;
	pm_nn *nn;
	pm_vec3 *pos, *dir;    /* photons found */
	double *w;             /* their weights */
	double *d;             /* their L-infinity distances from x */
	int *act;              /* photons used that arrive in front of n */
	pm_dvec3 *psi;         /* ... their unit directions */
	double *c;             /* ... Psi . n */
	int *own;              /* ... the polygon each lies on */
	int *fx;               /* ... the fate of x's backward ray along Psi */
	/* Grown as needed; a failed allocation leaves the estimate at 0. */
	cpoly *g;
	int ng, gcap;
	pm_dvec3 *cv;
	int ncv, cvcap;
	double *uv;            /* the clipped vertices in the plane across ax */
	int uvcap;
	int *bl;
	int nbl, blcap;
	pm_dvec3 *sp;          /* sample points */
	pm_dvec3 *ov;          /* pm_overlap_area's scratch */
	int ovcap;
	int *sf;               /* a covered sample's fate, the same for every
	                          direction (unused for dynamic ones) */
	unsigned char *scell;  /* a sample's column and row in its polygon's
	                          grid (16 column + row), while sample() works */
	sgrid *sgd;            /* per polygon: its samples' grid */
	int sgdcap;
	int *gapat;            /* per entry of sc->bl: where in gap its gaps
	                          are, or -1 before reach() first asks */
	double *gap;           /* B's d - N_B . v, for P's vertices v: the same
	                          for every photon (reach()) */
	int gapatcap, gapcap, ngap;
	int *shat;             /* per entry of sc->bl: where in sh its B's
	                          vertices are on P's plane_axes(), or -1 */
	double *sh;            /* N_P . q - d_P, q . t1, q . t2 for B's
	                          vertices q (fates_hit()) */
	int shatcap, shcap, nsh;
	int nsp, spcap;
	pm_dvec3 *pyr;         /* one polygon's pyramid from x' (pyramid()) */
	double *pl;            /* the polygons' planes, one array per number
	                          (N.x, N.y, N.z, d, N . x' - d), and ... */
	double *t;             /* the groups' keys while they are made */
	int plcap, tcap;
	int npyr, pyrcap;
	cgroup *gr;            /* groups, and past ng tentative ones */
	int ngr, grcap;
	int *gp;               /* polygons by group, then each one's tentative group */
	int gpcap;
	int *ht;               /* smooth patch -> tentative group */
	int htcap;
	int *gm;               /* groups that may hold one photon */
	int gmcap;
	int *held;             /* ... polygons whose planes and boxes hold it */
	int heldcap;
	int *pgc;              /* where many polygons: each cell's first in pgl
	                          (poly_grid()), GRID^3 + 1 of them */
	int pgccap;
	int *pgl;              /* the polygons whose boxes meet each cell */
	int pglcap;
	unsigned char *gmark;  /* 1 for the groups that may hold one photon */
	int gmarkcap;
	int *gq;               /* the polygons of sheets not plain (cgroup) */
	int gqcap;
	int *mark;             /* per polygon: on the list being closed, or found
	                          in the sight grid, if stamp */
	int markcap, marked, stamp;
	int *omark;            /* per scene object: a solid of the list being
	                          closed, if stamp */
	int omarkcap;
	pm_sight_grid grid;
	int *pgrp;             /* each polygon's group, for the grid's queries */
	int pgrpcap;
	int *cand;             /* polygons the grid gave for one P, then
	                          those off its plane in its F list */
	int candcap;
	pm_sight *sg;          /* every polygon's directions from x' (sight.h) */
	int sgcap;
	int *gmk, *gskip;      /* per group: gskip holds its test for P if gmk is stamp */
	int gmkcap;
	pm_boxtree tree;       /* the polygons' boxes, for seen_cast() ... */
	double (*bb)[3];       /* ... their boxes' lo, then hi */
	int bcap;
	int *btag;             /* ... tagged with their groups, which the
	                          walks from a polygon of a sheet pass over */
	int btagcap;
	int tree_built;        /* ... made once an estimate, when first asked */
	int fcast;             /* fates by rays in this cube (FATE_CAST_POLYS) */
	uint64_t *okey;        /* object and polygon, while runs are made */
	int okeycap;
	int *oby;              /* the polygons by object, and where each */
	int *orun0;            /* object's run starts (nrun + 1 entries) */
	int nrun, obycap, orun0cap;
	pm_dvec3 *onrm;        /* their normals in that order */
	int onrmcap;
	int *fl, *flk;         /* front_list()'s lists, and each entry's place
	                          in list order */
	int flcap, flkcap, nfl;
	int pyr_of;            /* the polygon whose pyramid sc->pyr holds, or -1 */
	int ob_last;           /* others_behind()'s last stopping group, or -1 */
	const unsigned char *cvx;
	int nwhole;            /* polygons pair_lists() found hidden whole */
	int oom;
	pm_comp_stats last;
};

/* P's group if it is a sheet, which the walks from P pass over, else -1. */
static inline int
sheet_of(const pm_comp_scratch *sc, const cpoly *P)
{
	return sc->gr[P->grp].sheet ? P->grp : -1;
}

pm_comp_scratch *
pm_comp_scratch_new(int k)
{
	pm_comp_scratch *sc;
	size_t n = (size_t)k;

	if (k < 1 || k > MAX_K)
		return NULL;
	sc = calloc(1, sizeof *sc);
	if (!sc)
		return NULL;
	sc->k = k;
	sc->nn = malloc(n * sizeof *sc->nn);
	sc->pos = malloc(n * sizeof *sc->pos);
	sc->dir = malloc(n * sizeof *sc->dir);
	sc->w = malloc(n * sizeof *sc->w);
	sc->d = malloc(n * sizeof *sc->d);
	sc->act = malloc(n * sizeof *sc->act);
	sc->psi = malloc(n * sizeof *sc->psi);
	sc->c = malloc(n * sizeof *sc->c);
	sc->own = malloc(n * sizeof *sc->own);
	sc->fx = malloc(n * sizeof *sc->fx);
	if (!sc->nn || !sc->pos || !sc->dir || !sc->w || !sc->d || !sc->act
	    || !sc->psi || !sc->c || !sc->own || !sc->fx) {
		pm_comp_scratch_free(sc);
		return NULL;
	}
	return sc;
}

void
pm_comp_scratch_free(pm_comp_scratch *sc)
{
	if (!sc)
		return;
	free(sc->nn);
	free(sc->pos);
	free(sc->dir);
	free(sc->w);
	free(sc->d);
	free(sc->act);
	free(sc->psi);
	free(sc->c);
	free(sc->own);
	free(sc->cellt);
	free(sc->rayat);
	free(sc->rayhit);
	free(sc->fx);
	free(sc->g);
	free(sc->cv);
	free(sc->uv);
	free(sc->bl);
	free(sc->sp);
	free(sc->sf);
	free(sc->scell);
	free(sc->sgd);
	free(sc->gapat);
	free(sc->shat);
	free(sc->sh);
	free(sc->gap);
	free(sc->ov);
	free(sc->pyr);
	free(sc->pl);
	free(sc->t);
	free(sc->gr);
	free(sc->gp);
	free(sc->ht);
	free(sc->gm);
	free(sc->held);
	free(sc->pgc);
	free(sc->pgl);
	free(sc->gmark);
	free(sc->gq);
	free(sc->mark);
	free(sc->pgrp);
	free(sc->omark);
	pm_sight_grid_free(&sc->grid);
	free(sc->cand);
	free(sc->gmk);
	free(sc->gskip);
	free(sc->sg);
	pm_boxtree_free(&sc->tree);
	free(sc->bb);
	free(sc->btag);
	free(sc->okey);
	free(sc->fl);
	free(sc->flk);
	free(sc->oby);
	free(sc->onrm);
	free(sc->orun0);
	free(sc);
}

const pm_comp_stats *
pm_comp_last(const pm_comp_scratch *sc)
{
	return &sc->last;
}

static int
grow_samples(pm_comp_scratch *sc, int need)
{
	int cap = sc->spcap;

	if (!pm_grow((void **)&sc->sp, &cap, sc->nsp, need, sizeof *sc->sp))
		return 0;
	cap = sc->spcap;
	if (!pm_grow((void **)&sc->sf, &cap, sc->nsp, need, sizeof *sc->sf))
		return 0;
	cap = sc->spcap;
	if (!pm_grow((void **)&sc->scell, &cap, sc->nsp, need, sizeof *sc->scell))
		return 0;
	sc->spcap = cap;
	return 1;
}

/* fmax and fmin, NaN ignored as theirs do, but inlined (libm's are calls
 * without -ffinite-math-only, and these sit in every inner loop). */
static inline double dmax(double a, double b) { return a > b || b != b ? a : b; }
static inline double dmin(double a, double b) { return a < b || b != b ? a : b; }

static double
comp(pm_dvec3 v, int a)
{
	return a == 0 ? v.x : a == 1 ? v.y : v.z;
}

/* Collects the polygons meeting the cube: clipped, with their areas. */
typedef struct visit_ctx {
	pm_comp_scratch *sc;
	const pm_polyindex *pi;
	pm_dvec3 x;
	double h, tau;
	int open;
} visit_ctx;

/* Polygons of up to this many vertices are clipped from an array. */
#define VISIT_MAX 16

static void
visit(void *vctx, uint32_t g)
{
	visit_ctx *q = vctx;
	pm_comp_scratch *sc = q->sc;
	const pm_scene *s = q->pi->s;
	const pm_vec3 *verts = q->pi->verts;
	double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
	uint32_t n = s->poly_start[g + 1] - s->poly_start[g];
	int cap = 2 * (int)n + 12, kept;
	pm_clipper cl;
	pm_dvec3 N, mid;
	double A, len;
	cpoly *P;

	if (sc->oom)
		return;
	if (!pm_grow((void **)&sc->cv, &sc->cvcap, sc->ncv, cap, sizeof *sc->cv) ||
	    !pm_grow((void **)&sc->uv, &sc->uvcap, 2 * sc->ncv, 2 * cap, sizeof *sc->uv) ||
	    !pm_grow((void **)&sc->g, &sc->gcap, sc->ng, 1, sizeof *sc->g)) {
		sc->oom = 1;
		return;
	}
	pm_dvec3 rv[VISIT_MAX];
	for (uint32_t v = s->poly_start[g], i = 0; v < s->poly_start[g + 1]; v++, i++) {
		pm_dvec3 r = pm_dsub(pm_dfromf(verts[s->poly_vert[v]]), q->x);
		if (i < VISIT_MAX)
			rv[i] = r;
		lo[0] = r.x < lo[0] ? r.x : lo[0];
		lo[1] = r.y < lo[1] ? r.y : lo[1];
		lo[2] = r.z < lo[2] ? r.z : lo[2];
		hi[0] = r.x > hi[0] ? r.x : hi[0];
		hi[1] = r.y > hi[1] ? r.y : hi[1];
		hi[2] = r.z > hi[2] ? r.z : hi[2];
	}
	/* Open cube: a polygon lying in (or beyond) a face plane is where the
	 * set-aside boundary photons are; it has no area inside. */
	if (q->open)
		for (int a = 0; a < 3; a++)
			if (lo[a] >= q->h - 0.5 * q->tau || hi[a] <= -q->h + 0.5 * q->tau)
				return;
	N = pm_dfromf(s->poly_normal[g]);
	len = pm_dlen(N);
	if (!(len > 0))
		return;
	N = pm_dscale(N, 1 / len);
	if (n <= VISIT_MAX)
		kept = pm_clip_array(rv, (int)n, q->h, lo, hi, N, sc->cv + sc->ncv, cap, &A, &mid);
	else {
		pm_clip_begin(&cl, q->h);
		pm_clip_bounds(&cl, lo, hi);
		pm_clip_keep(&cl, sc->cv + sc->ncv, cap);
		for (uint32_t v = s->poly_start[g]; v < s->poly_start[g + 1]; v++)
			pm_clip_vertex(&cl, pm_dsub(pm_dfromf(verts[s->poly_vert[v]]), q->x));
		A = pm_clip_end(&cl, N);
		kept = pm_clip_kept(&cl);
		mid = pm_clip_middle(&cl);
	}
	if (!(A > 0) || kept < 3)
		return;
	P = &sc->g[sc->ng++];
	*P = (cpoly){0};
	P->g = g;
	P->obj = (int)s->poly_obj[g];
	P->solid = s->objs[P->obj].solid;
	P->N = N;
	P->A = A;
	P->v0 = sc->ncv;
	P->nv = kept;
	sc->ncv += kept;
	P->d = pm_ddot(N, mid);
	P->ax = fabs(N.x) > fabs(N.y) ? (fabs(N.x) > fabs(N.z) ? 0 : 2) : (fabs(N.y) > fabs(N.z) ? 1 : 2);
	P->nax = fabs(comp(N, P->ax));
	int whole = 1, u = (P->ax + 1) % 3, w = (P->ax + 2) % 3;
	for (int a = 0; a < 3; a++) {
		whole &= lo[a] >= -q->h && hi[a] <= q->h;
		P->lo[a] = INFINITY;
		P->hi[a] = -INFINITY;
	}
	/* Not cut: its bounds are the polygon's own. */
	if (whole)
		for (int a = 0; a < 3; a++) {
			P->lo[a] = lo[a];
			P->hi[a] = hi[a];
		}
	for (int i = 0; i < kept; i++) {
		pm_dvec3 v = sc->cv[P->v0 + i];
		if (!whole)
			for (int a = 0; a < 3; a++) {
				P->lo[a] = dmin(P->lo[a], comp(v, a));
				P->hi[a] = dmax(P->hi[a], comp(v, a));
			}
		sc->uv[2 * (P->v0 + i)] = comp(v, u);
		sc->uv[2 * (P->v0 + i) + 1] = comp(v, w);
	}
	P->c = pm_dscale(pm_dadd(pm_dv3(P->lo[0], P->lo[1], P->lo[2]), pm_dv3(P->hi[0], P->hi[1], P->hi[2])), 0.5);
	P->rad = 0.5 * pm_dlen(pm_dv3(P->hi[0] - P->lo[0], P->hi[1] - P->lo[1], P->hi[2] - P->lo[2]));
}

/* 1 if p lies in B's box grown by tol: inside()'s first test, which the
 * fates of sample points make on their own, inlined (most of them miss). */
static inline int
in_box(const cpoly *B, pm_dvec3 p, double tol)
{
	return !(p.x < B->lo[0] - tol || p.x > B->hi[0] + tol || p.y < B->lo[1] - tol ||
	         p.y > B->hi[1] + tol || p.z < B->lo[2] - tol || p.z > B->hi[2] + tol);
}

/* 1 if point p (near P's plane) is inside P's clipped polygon; within tol
 * of its boundary, edge_in. Crossing number in the coordinate plane P
 * projects best to, where distances shrink by at most P->nax. */
static int
in_poly(const pm_comp_scratch *sc, const cpoly *P, pm_dvec3 p, double tol, int edge_in)
{
	const double *uv = sc->uv + 2 * P->v0;
	/* The two axes after ax, from a table: a division per call showed. */
	static const int next[3] = {1, 2, 0};
	int u = next[P->ax], w = next[u], in = 0;
	double pu = comp(p, u), pw = comp(p, w), tu = tol * P->nax, t2 = tu * tu;

	for (int i = 0, j = P->nv - 1; i < P->nv; j = i++) {
		double iu = uv[2 * i], iw = uv[2 * i + 1], ju = uv[2 * j], jw = uv[2 * j + 1];
		double eu = iu - ju, ew = iw - jw;
		if ((iw > pw) != (jw > pw) && pu < eu * (pw - iw) / ew + iu)
			in = !in;
		/* Within tu of the edge only inside its box grown by tu (the
		 * vertices are finite: plain min and max). */
		if (pu < (iu < ju ? iu : ju) - tu || pu > (iu > ju ? iu : ju) + tu ||
		    pw < (iw < jw ? iw : jw) - tu || pw > (iw > jw ? iw : jw) + tu)
			continue;
		double ru = pu - ju, rw = pw - jw, ee = eu * eu + ew * ew;
		double t = ee > 0 ? (ru * eu + rw * ew) / ee : 0;
		t = t < 0 ? 0 : t > 1 ? 1 : t;
		ru -= t * eu;
		rw -= t * ew;
		if (ru * ru + rw * rw <= t2)
			return edge_in;
	}
	return in;
}

/* in_poly() where p lies in P's box grown by tol, else 0. */
static inline int
inside(const pm_comp_scratch *sc, const cpoly *P, pm_dvec3 p, double tol, int edge_in)
{
	return in_box(P, p, tol) && in_poly(sc, P, p, tol, edge_in);
}

/* 1 if the segment from x' to y crosses polygon B, sx being N_B . x' - d_B.
 * Crossings within eps of a polygon's edge count: a wall's edge is where it
 * meets the floor, and the floor beyond runs under it. */
static inline int
crosses(const pm_comp_scratch *sc, const cpoly *B, pm_dvec3 xo, pm_dvec3 y, double sx, double eps)
{
	double sy = pm_ddot(B->N, y) - B->d;

	if (fabs(sx) <= eps || fabs(sy) <= eps || (sx > 0) == (sy > 0))
		return 0;
	return inside(sc, B, pm_dadd(xo, pm_dscale(pm_dsub(y, xo), sx / (sx - sy))), eps, 1);
}

static int seen_cast(pm_comp_scratch *sc, const cpoly *P, pm_dvec3 xo, pm_dvec3 y, double eps);

/* 1 if x' sees y: the segment between them crosses none of the polygons
 * that may hide part of P (y on P). */
static int
seen(pm_comp_scratch *sc, const cpoly *P, pm_dvec3 xo, pm_dvec3 y, double eps)
{
	if (P->cast)
		return seen_cast(sc, P, xo, y, eps);
	for (int i = 0; i < P->nr; i++) {
		const cpoly *B = &sc->g[sc->bl[P->r0 + i]];
		if (crosses(sc, B, xo, y, pm_ddot(B->N, xo) - B->d, eps))
			return 0;
	}
	return 1;
}

/* seen() for n points y on P at once, blocker by blocker (x's side of each
 * plane worked out once): vis[i] = 1 if x' sees y[i]. */
static void
seen_many(pm_comp_scratch *sc, const cpoly *P, pm_dvec3 xo, const pm_dvec3 *y, int n,
          double eps, unsigned char *vis)
{
	if (P->cast) {
		for (int s = 0; s < n; s++)
			vis[s] = seen_cast(sc, P, xo, y[s], eps);
		return;
	}
	for (int s = 0; s < n; s++)
		vis[s] = 1;
	for (int i = 0; i < P->nr; i++) {
		const cpoly *B = &sc->g[sc->bl[P->r0 + i]];
		double sx = pm_ddot(B->N, xo) - B->d;
		if (fabs(sx) <= eps)
			continue;
		for (int s = 0; s < n; s++)
			if (vis[s] && crosses(sc, B, xo, y[s], sx, eps))
				vis[s] = 0;
	}
}

/* The axes sample points are laid along on a plane of unit normal N. */
static inline void
plane_axes(pm_dvec3 N, pm_dvec3 *t1, pm_dvec3 *t2)
{
	pm_dvec3 t = fabs(N.x) < 0.9 ? pm_dv3(1, 0, 0) : pm_dv3(0, 1, 0);
	t = pm_dsub(t, pm_dscale(N, pm_ddot(t, N)));
	*t1 = pm_dscale(t, 1 / pm_dlen(t));
	*t2 = pm_dcross(N, *t1);
}

/* fate()'s test of one polygon B (d = N_B . psi, not near 0): 1 if the
 * backward ray from y along psi meets it nearer than best, at distance *t.
 * A hit at distance 0 (a face resting on y's surface) counts; a hit
 * within eps of the polygon's edge does not (the next polygon of a mesh). */
static inline int
meets(const pm_comp_scratch *sc, const cpoly *B, double d, pm_dvec3 y, pm_dvec3 psi, double eps,
      double best, double *t)
{
	double gap = B->d - pm_ddot(B->N, y), u;

	/* Behind y beyond eps: u < 0 for sure (gap and d differ in sign, and
	 * |gap| > eps keeps u from rounding to 0), with no division. */
	if ((gap < 0) != (d < 0) && fabs(gap) > eps)
		return 0;
	u = gap / d;
	if (u < 0) {
		if (fabs(gap) > eps)
			return 0;
		u = 0;
	}
	pm_dvec3 p = pm_dadd(y, pm_dscale(psi, u));
	if (u >= best || !inside(sc, B, p, eps, 0))
		return 0;
	*t = u;
	return 1;
}

/* The fate of a backward ray that meets list entry e (polygon B, d being
 * N_B . psi) first: which object and from which side; -1 for the front of
 * a solid added by close_matter(): the front of a wall across an edge is
 * where light comes from, as it is beyond the cube. */
static inline int
fate_at(int e, const cpoly *B, double d)
{
	return (e & MATTER) && d < 0 ? -1 : 2 * B->obj + (d > 0);
}

/* 1 if list entry le is the front of a solid met from behind as psi
 * meets it: its fate is -1, as if the ray left the cube, so it changes a
 * ray's fate only where it comes before something else the ray meets.
 * fates_hit() asks such entries only of points whose rays meet
 * something else (thin parts: two fifths of the candidates). */
static inline int
opens_later(const pm_comp_scratch *sc, int le, pm_dvec3 psi)
{
	return (le & MATTER) && pm_ddot(sc->g[IDX(le)].N, psi) < 0;
}

/* The fate of the backward ray from y toward psi through the cube: -1 if it
 * meets none of the polygons cand[0..nc-1] first but the front of a wall
 * across an edge (or leaves the cube), else which object it meets first and
 * from which side, by meets(). */
static int
fate(const pm_comp_scratch *sc, const int *cand, int nc, pm_dvec3 y, pm_dvec3 psi, double eps)
{
	double best = INFINITY, t;
	int f = -1;

	for (int i = 0; i < nc; i++) {
		const cpoly *B = &sc->g[IDX(cand[i])];
		double d = pm_ddot(B->N, psi);
		if (fabs(d) < 1e-9 || !meets(sc, B, d, y, psi, eps, best, &t))
			continue;
		best = t;
		f = fate_at(cand[i], B, d);
	}
	return f;
}

/* Of B's vertex q, what fates_hit() needs whatever the direction: its
 * height over P's plane, N_P . q - d_P, and its coordinates along P's
 * plane_axes() t1 and t2. */
static inline void
shadow_vert(const cpoly *P, pm_dvec3 q, pm_dvec3 t1, pm_dvec3 t2, double out[3])
{
	out[0] = pm_ddot(P->N, q) - P->d;
	out[1] = pm_ddot(q, t1);
	out[2] = pm_ddot(q, t2);
}

/* shadow_vert() for all of B's vertices, B being the entry e of sc->bl (on
 * P's list): worked out when first asked in an estimate, kept for its other
 * photons; NULL if there is no room. */
static const double *
shadow_verts(pm_comp_scratch *sc, const cpoly *P, const cpoly *B, int e, pm_dvec3 t1, pm_dvec3 t2)
{
	if (sc->shat[e] < 0) {
		if (!pm_grow((void **)&sc->sh, &sc->shcap, sc->nsh, 3 * B->nv, sizeof *sc->sh))
			return NULL;
		for (int v = 0; v < B->nv; v++)
			shadow_vert(P, sc->cv[B->v0 + v], t1, t2, sc->sh + sc->nsh + 3 * v);
		sc->shat[e] = sc->nsh;
		sc->nsh += 3 * B->nv;
	}
	return sc->sh + sc->shat[e];
}

static int may_meet(pm_comp_scratch *sc, const cpoly *P, int e, pm_dvec3 psi, double eps);

/* How many of P's dynamic sample points have fate fx along psi (-1 if
 * there is no room for what it keeps): fate()
 * for each, taken candidate by candidate over all the points (each point's
 * nearest hit so far kept as fate() keeps it, so the answers are fate()'s),
 * which keeps one plane in hand and lets neighbouring points' tests go the
 * same way. The candidates are entries of sc->bl (P's list), so that what
 * is worked out for one is kept for the estimate's other photons; the
 * fronts in dcand (opens_later()) are asked only of the points they met. */
static int
fates_hit(pm_comp_scratch *sc, const cpoly *P, const int *cand, int nc, const int *dcand, int ndc,
          pm_dvec3 psi, double eps, int fx, pm_comp_stats *z)
{
	/* best[s] and f[s] hold only for the points in touched: the others'
	 * nearest hit is none yet, and their fate -1. Few points meet
	 * anything, so none of the rest is written or read. */
	double best[GRID * GRID];
	int f[GRID * GRID], at[GRID * GRID], hit = 0, n = P->ndyn, nt = 0;
	uint64_t touched = 0;
	const pm_dvec3 *y = sc->sp + P->s0;
	const sgrid *S = &sc->sgd[P - sc->g];
	uint64_t all = n >= 64 ? ~(uint64_t)0 : ((uint64_t)1 << n) - 1;
	/* A point y meets B only inside B's shadow along psi on P's plane:
	 * the box (in P's plane_axes(), as sample() keeps the points) of B's
	 * vertices moved along psi onto that plane. meets() lets a hit lie off
	 * B's plane by up to eps (a point within sqrt(3) eps of B proper),
	 * which moves its shadow by that times 1 + 1 / |pn|; the box is grown
	 * by more than twice that, so it only passes over points meets() would
	 * refuse, and the answers stay the same. Worth its work from a few
	 * points on (pm_comp_shadow_from). A point lies in the box if its
	 * column and its row do (the same comparisons of the same numbers),
	 * so the box is asked of P's grid's columns and rows, not of each
	 * point. */
	double pn = pm_ddot(P->N, psi), grow = 4 * eps * (1 + 1 / fabs(pn));
	int cull = n >= pm_comp_shadow_from && fabs(pn) > 1e-3;
	double pa = pm_ddot(psi, S->t1), pb = pm_ddot(psi, S->t2);

	for (int i = 0; i < nc; i++) {
		int e = cand[i], ce = sc->bl[e];
		const cpoly *B = &sc->g[IDX(ce)];
		double d = pm_ddot(B->N, psi);
		uint64_t live = all;
		if (fabs(d) < 1e-9)
			continue;
		int fb = fate_at(ce, B, d);
		if (cull) {
			double alo = INFINITY, ahi = -INFINITY, blo = INFINITY, bhi = -INFINITY;
			uint64_t ca = 0, cb = 0;
			const double *q3 = shadow_verts(sc, P, B, e, S->t1, S->t2);
			if (!q3)
				return -1;
			for (int v = 0; v < B->nv; v++) {
				const double *qv = q3 + 3 * v;
				double t = qv[0] / pn;
				double qa = qv[1] - pa * t, qb = qv[2] - pb * t;
				alo = qa < alo ? qa : alo;
				ahi = qa > ahi ? qa : ahi;
				blo = qb < blo ? qb : blo;
				bhi = qb > bhi ? qb : bhi;
			}
			alo -= grow;
			ahi += grow;
			blo -= grow;
			bhi += grow;
			for (int c = 0; c < S->G; c++) {
				if (!(S->v[c] < alo || S->v[c] > ahi))
					ca |= S->m[c];
				if (!(S->v[GRID + c] < blo || S->v[GRID + c] > bhi))
					cb |= S->m[GRID + c];
			}
			live = ca & cb & all;
		}
		int tried = 0;
		for (; live; live &= live - 1, tried++) {
			int s = __builtin_ctzll(live);
			uint64_t bit = (uint64_t)1 << s;
			double t;
			if (meets(sc, B, d, y[s], psi, eps, touched & bit ? best[s] : INFINITY, &t)) {
				best[s] = t;
				f[s] = fb;
				at[s] = e;
				touched |= bit;
			}
		}
		if (cull)
			z->shadowed += n - tried;
	}
	/* The fronts that waited (opens_later()), in list order, of the
	 * points something met: one met first opens the point's ray; at an
	 * equal distance the entry first on the list wins, as in one pass. */
	for (int i = 0; i < ndc && touched; i++) {
		int e = dcand[i], k;
		const cpoly *B = &sc->g[IDX(sc->bl[e])];
		double d = pm_ddot(B->N, psi), t;
		if (fabs(d) < 1e-9)
			continue;
		/* Asked of those the candidates' own tests keep, as they were. */
		if ((k = may_meet(sc, P, e, psi, eps)) <= 0) {
			if (k < 0)
				return -1;
			continue;
		}
		for (uint64_t live = touched; live; live &= live - 1) {
			int s = __builtin_ctzll(live);
			if (f[s] == -1)
				continue;
			double lim = e < at[s] ? nextafter(best[s], INFINITY) : best[s];
			if (meets(sc, B, d, y[s], psi, eps, lim, &t)) {
				best[s] = t;
				f[s] = -1;
				at[s] = e;
			}
		}
	}
	for (; touched; touched &= touched - 1, nt++)
		hit += f[__builtin_ctzll(touched)] == fx;
	return hit + (fx == -1 ? n - nt : 0);
}

/* B->d - N_B . v for P's vertices v, B being the entry e of sc->bl (on P's
 * list): worked out when first asked in an estimate, kept for its other
 * photons; NULL if there is no room. */
static inline __attribute__((always_inline)) const double *
gaps(pm_comp_scratch *sc, const cpoly *P, const cpoly *B, int e)
{
	if (sc->gapat[e] < 0) {
		if (!pm_grow((void **)&sc->gap, &sc->gapcap, sc->ngap, P->nv, sizeof *sc->gap))
			return NULL;
		for (int i = 0; i < P->nv; i++)
			sc->gap[sc->ngap + i] = B->d - pm_ddot(B->N, sc->cv[P->v0 + i]);
		sc->gapat[e] = sc->ngap;
		sc->ngap += P->nv;
	}
	return sc->gap + sc->gapat[e];
}

/* 1 if a backward ray along psi from some point of P may meet B: the box
 * of where P's points meet B's plane along psi meets B's box (grown by
 * eps). A point in front of the plane meets it at the same mix of P's
 * vertices moved along psi onto it, those behind moved back; one within
 * eps behind meets it where it is, a mix of points on P's edges between
 * the plane and the vertices behind. So the box holds every vertex moved
 * onto the plane, and those behind where they are too. (Those behind
 * taken only where they are left out hits of a P lying across B's plane:
 * 215 sample points under test_compensate's clouds. The crossings of P's
 * edges with the plane give a box no smaller in practice, for 5 % more
 * instructions on thin.) */
static inline __attribute__((always_inline)) int
reach(const pm_comp_scratch *sc, const cpoly *P, const cpoly *B, const double *gv, pm_dvec3 psi,
      double eps)
{
	double dn = pm_ddot(B->N, psi), lo[3] = {INFINITY, INFINITY, INFINITY};
	double hi[3] = {-INFINITY, -INFINITY, -INFINITY};
	int any = 0;

	if (fabs(dn) < 1e-9)
		return 0;
	/* Spelt out per axis (comp()'s branches cost more than the rest),
	 * plain min and max: the points are finite. */
#define REACH_ADD(p)                                            \
	do {                                                    \
		lo[0] = (p).x < lo[0] ? (p).x : lo[0];          \
		hi[0] = (p).x > hi[0] ? (p).x : hi[0];          \
		lo[1] = (p).y < lo[1] ? (p).y : lo[1];          \
		hi[1] = (p).y > hi[1] ? (p).y : hi[1];          \
		lo[2] = (p).z < lo[2] ? (p).z : lo[2];          \
		hi[2] = (p).z > hi[2] ? (p).z : hi[2];          \
	} while (0)
	for (int i = 0; i < P->nv; i++) {
		pm_dvec3 v = sc->cv[P->v0 + i], q;
		double t = gv[i] / dn;
		any |= t >= 0 || fabs(gv[i]) <= eps;
		q = pm_dadd(v, pm_dscale(psi, t));
		REACH_ADD(q);
		if (t < 0)
			REACH_ADD(v);
	}
#undef REACH_ADD
	if (!any)
		return 0;
	for (int a = 0; a < 3; a++)
		if (hi[a] < B->lo[a] - eps || lo[a] > B->hi[a] + eps)
			return 0;
	return 1;
}

/* 1 if no ray from P's sphere along psi meets B's (with fate()'s eps): B
 * cannot be hit, reach() not needed. Where reach()'s box kept such a B,
 * P's count now takes another path to its area (an exact overlap, not
 * samples), which moved 13 of 200 torture scenes by at most 5e-5 RMSE;
 * 4-11 % off an estimate on prims, soup and scanned. */
static inline __attribute__((always_inline)) int
apart(const cpoly *P, const cpoly *B, pm_dvec3 psi, double eps)
{
	pm_dvec3 wv = pm_dsub(B->c, P->c);
	double al = pm_ddot(wv, psi), rr = P->rad + B->rad + 2 * eps;
	return al < -rr || pm_ddot(wv, wv) - al * al > rr * rr;
}

/* The photons' loop's test of entry e of sc->bl (on P's list), for the
 * entries that wait: 1 if a backward ray from P along psi may meet it, 0
 * if none can, -1 if there is no room for gaps(). The loop spells the
 * same test out for the other entries: calling this there cost prims 2-4 %
 * more instructions, out of line or inlined at all three callers. */
static int
may_meet(pm_comp_scratch *sc, const cpoly *P, int e, pm_dvec3 psi, double eps)
{
	const cpoly *B = &sc->g[IDX(sc->bl[e])];
	if (apart(P, B, psi, eps))
		return 0;
	const double *gv = gaps(sc, P, B, e);
	if (!gv)
		return -1;
	return reach(sc, P, B, gv, psi, eps);
}

static void span_verts(const pm_comp_scratch *sc, const cpoly *Q, pm_dvec3 M, double m,
                       double *lo, double *hi);

/* Signed distances of Q's clipped vertices to the plane (M, m): the largest
 * and the smallest. */
static void
span(const pm_comp_scratch *sc, const cpoly *Q, pm_dvec3 M, double m, double *lo, double *hi)
{
	double c = pm_ddot(M, Q->c) - m;

	/* Far from the plane, the bounding sphere says enough. */
	if (fabs(c) > Q->rad) {
		*lo = c - Q->rad;
		*hi = c + Q->rad;
		return;
	}
	span_verts(sc, Q, M, m, lo, hi);
}

/* span() from the vertices alone. */
static void
span_verts(const pm_comp_scratch *sc, const cpoly *Q, pm_dvec3 M, double m, double *lo, double *hi)
{
	*lo = INFINITY;
	*hi = -INFINITY;
	for (int i = 0; i < Q->nv; i++) {
		double s = pm_ddot(M, sc->cv[Q->v0 + i]) - m;
		*lo = s < *lo ? s : *lo;
		*hi = s > *hi ? s : *hi;
	}
}

/* The pyramid from x' over P that between() tests against, worked out once
 * per P: the planes through x' and P's edges, each oriented so that a
 * point beyond it has t < -eps, up to the first edge where the pyramid test
 * gives up (P not convex as seen from x', or x' in an edge's plane): past
 * it every B counts as between. */
static int
pyramid(pm_comp_scratch *sc, const cpoly *P, pm_dvec3 xo, double eps)
{
	const pm_dvec3 *v = sc->cv + P->v0;
	pm_dvec3 c = pm_dv3(0, 0, 0);

	sc->npyr = 0;
	sc->pyr_of = -1;
	if (!pm_grow((void **)&sc->pyr, &sc->pyrcap, 0, P->nv, sizeof *sc->pyr))
		return 0;
	sc->pyr_of = (int)(P - sc->g);
	for (int i = 0; i < P->nv; i++)
		c = pm_dadd(c, v[i]);
	c = pm_dscale(c, 1.0 / P->nv);
	for (int i = 0, j = P->nv - 1; i < P->nv; j = i++) {
		pm_dvec3 m = pm_dcross(pm_dsub(v[i], xo), pm_dsub(v[j], xo));
		double ml = pm_dlen(m), sc0;
		if (!(ml > 0))
			continue;
		m = pm_dscale(m, 1 / ml);
		sc0 = pm_ddot(m, pm_dsub(c, xo));
		if (sc0 == 0)
			return 1;
		for (int k = 0; k < P->nv; k++)
			if ((pm_ddot(m, pm_dsub(v[k], xo)) > eps) != (sc0 > 0) &&
			    fabs(pm_ddot(m, pm_dsub(v[k], xo))) > eps)
				return 1;   /* not convex as seen from x' */
		/* Negation is exact: t < -eps for -m is t > eps for m. */
		sc->pyr[sc->npyr++] = sc0 > 0 ? m : pm_dscale(m, -1);
	}
	return 1;
}

/* 0 if B lies outside the pyramid from x' over P (pyramid() of P), so that
 * no segment from x' to P can cross it: behind P's plane, or beyond one of
 * the planes through x' and an edge of P (P convex; otherwise 1). u is
 * N_P . c_B - d_P (span()'s first step). */
static int
between(const pm_comp_scratch *sc, const cpoly *P, const cpoly *B, pm_dvec3 xo, double eps, double u)
{
	double sxo = pm_ddot(P->N, xo) - P->d, lo, hi;

	if (fabs(u) > B->rad)
		lo = u - B->rad, hi = u + B->rad;
	else
		span_verts(sc, B, P->N, P->d, &lo, &hi);
	if (sxo > 0 ? hi <= eps : lo >= -eps)
		return 0;
	for (int p = 0; p < sc->npyr; p++) {
		pm_dvec3 m = sc->pyr[p];
		/* B's bounding sphere decides unless it straddles -eps (the
		 * margin keeps rounding from deciding otherwise than the
		 * vertices would). */
		double tc = pm_ddot(m, pm_dsub(B->c, xo)), r = B->rad * (1 + 1e-9) + 1e-12 * fabs(tc);
		if (tc - r >= -eps)
			continue;
		if (tc + r < -eps)
			return 0;
		int out = 1;
		for (int k = 0; k < B->nv && out; k++)
			out = pm_ddot(m, pm_dsub(sc->cv[B->v0 + k], xo)) < -eps;
		if (out)
			return 0;
	}
	return 1;
}

/* Tentative groups by key through the hash table sc->ht (hn slots): each
 * polygon's in tg, their count, areas' sums of Ne in M, cones in cmin. */
static int
tentative(pm_comp_scratch *sc, const uint32_t *key, cgroup *tent, int *tg, int hn)
{
	int nt = 0;

	for (int i = 0; i < hn; i++)
		sc->ht[i] = -1;
	for (int a = 0; a < sc->ng; a++) {
		const cpoly *P = &sc->g[a];
		uint32_t hs = (key[a] * 2654435761u) & (uint32_t)(hn - 1);
		int t;
		for (;; hs = (hs + 1) & (uint32_t)(hn - 1)) {
			t = sc->ht[hs];
			if (t < 0) {
				t = sc->ht[hs] = nt++;
				tent[t] = (cgroup){.key = key[a], .p0 = -1};
				break;
			}
			if (tent[t].key == key[a])
				break;
		}
		tg[a] = t;
		tent[t].np++;
		tent[t].M = pm_dadd(tent[t].M, pm_dscale(P->Ne, P->A));
	}
	for (int t = 0; t < nt; t++) {
		double l = pm_dlen(tent[t].M);
		tent[t].M = l > 0 ? pm_dscale(tent[t].M, 1 / l) : pm_dv3(0, 0, 0);
		tent[t].cmin = l > 0 ? 1 : -1;
	}
	for (int a = 0; a < sc->ng; a++)
		tent[tg[a]].cmin = dmin(tent[tg[a]].cmin, pm_ddot(sc->g[a].Ne, tent[tg[a]].M));
	return nt;
}

/* The mean of the sides that count of sc->g[ord[lo .. hi)], unit, and
 * whether each of them lies within SHEET_COS of it. */
static pm_dvec3
cone_mean(const pm_comp_scratch *sc, const int *ord, int lo, int hi, int *ok)
{
	pm_dvec3 M = pm_dv3(0, 0, 0);
	for (int i = lo; i < hi; i++)
		M = pm_dadd(M, pm_dscale(sc->g[ord[i]].Ne, sc->g[ord[i]].A));
	double l = pm_dlen(M);
	M = l > 0 ? pm_dscale(M, 1 / l) : pm_dv3(0, 0, 0);
	*ok = l > 0;
	for (int i = lo; i < hi && *ok; i++)
		*ok = pm_ddot(sc->g[ord[i]].Ne, M) >= SHEET_COS;
	return M;
}

/* Moves the polygons of ord[lo .. hi) within SHEET_COS of M to its front;
 * returns where they end. */
static int
in_cone(const pm_comp_scratch *sc, int *ord, int lo, int hi, pm_dvec3 M)
{
	int k = lo;
	for (int i = lo; i < hi; i++)
		if (pm_ddot(sc->g[ord[i]].Ne, M) >= SHEET_COS) {
			int t = ord[k];
			ord[k++] = ord[i];
			ord[i] = t;
		}
	return k;
}

/* A smooth patch that bends past SHEET_COS in the cube, peeled into
 * sheets: from a direction (the patch's mean first, then the normal of the
 * largest polygon left), the polygons within SHEET_COS of it, then of
 * their mean, until they all lie within SHEET_COS of their own mean: they
 * are a sheet, and the rest go on. A try that finds none leaves its seed a
 * polygon of its own. The first step of the first try is what groups()
 * did before there were tries, so a patch it made a sheet of stays one.
 * Sorts sc->gp[0 .. ng) by tentative group on the way; sets the keys of
 * each sheet's polygons to 0x40000000 and its first polygon. */
static void
peel(pm_comp_scratch *sc, cgroup *tent, const int *tg, int nt, uint32_t *key)
{
	int *ord = sc->gp, ng = sc->ng;

	for (int t = 0, o = 0; t < nt; t++) {
		tent[t].p0 = o;
		o += tent[t].np;
	}
	for (int a = 0; a < ng; a++)
		ord[tent[tg[a]].p0++] = a;
	for (int t = 0; t < nt; t++) {
		cgroup *T = &tent[t];
		int hi = T->p0, lo = hi - T->np;
		if (T->np < 2 || T->cmin >= SHEET_COS)
			continue;
		pm_dvec3 M = T->M;
		for (int r = 0, seed = -1; r < PEEL_TRIES && hi - lo >= 2; r++) {
			if (r > 0) {
				int big = lo;
				for (int i = lo + 1; i < hi; i++)
					if (sc->g[ord[i]].A > sc->g[ord[big]].A)
						big = i;
				seed = ord[big];
				M = sc->g[seed].Ne;
			}
			int k = lo, ok = 0;
			for (int it = 0; it < PEEL_STEPS && !ok; it++) {
				k = in_cone(sc, ord, lo, hi, M);
				if (k - lo < 2)
					break;
				M = cone_mean(sc, ord, lo, k, &ok);
			}
			if (ok) {
				for (int i = lo; i < k; i++)
					key[ord[i]] = 0x40000000u | (uint32_t)ord[lo];
				lo = k;
			} else if (seed >= 0) {
				/* No sheet from the seed's direction: it stays alone. */
				for (int i = lo; i < hi; i++)
					if (ord[i] == seed) {
						ord[i] = ord[lo];
						ord[lo++] = seed;
						break;
					}
			}
		}
	}
}

/* Groups the cube's polygons (cgroup). A smooth patch's polygons in the
 * cube whose sides that count lie within SHEET_COS of their mean are one
 * sheet; where they do not (the patch bends or is rough at the cube's
 * scale), it is peeled into sheets (peel()), and what no sheet takes is a
 * group of its own, as is every polygon of no smooth patch. Needs every
 * polygon's Ne, A, xon and xpar. */
static int
groups(pm_comp_scratch *sc, const uint32_t *patch, pm_dvec3 n)
{
	int ng = sc->ng, hn = 16, nf = 0;

	while (hn < 2 * ng)
		hn *= 2;
	if (!pm_grow((void **)&sc->ht, &sc->htcap, 0, hn, sizeof *sc->ht) ||
	    !pm_grow((void **)&sc->gr, &sc->grcap, 0, 3 * ng, sizeof *sc->gr) ||
	    !pm_grow((void **)&sc->gp, &sc->gpcap, 0, 3 * ng, sizeof *sc->gp) ||
	    !pm_grow((void **)&sc->gm, &sc->gmcap, 0, ng, sizeof *sc->gm) ||
	    !pm_grow((void **)&sc->held, &sc->heldcap, 0, ng, sizeof *sc->held) ||
	    !pm_grow((void **)&sc->mark, &sc->markcap, 0, ng, sizeof *sc->mark) ||
	    !pm_grow((void **)&sc->t, &sc->tcap, 0, ng, sizeof *sc->t))
		return 0;
	/* New marks start unset; stamps start over before they could wrap. */
	for (int i = sc->marked; i < sc->markcap; i++)
		sc->mark[i] = 0;
	sc->marked = sc->markcap;
	if (sc->stamp > INT_MAX - 2 * ng - 4) {
		for (int i = 0; i < sc->markcap; i++)
			sc->mark[i] = 0;
		for (int i = 0; i < sc->omarkcap; i++)
			sc->omark[i] = 0;
		sc->stamp = 0;
	}
	cgroup *tent = sc->gr + ng, *sub = sc->gr + 2 * ng;
	int *tg = sc->gp + ng, *sg = sc->gp + 2 * ng;
	/* sc->t holds the keys while the table is built from them. */
	uint32_t *key = (uint32_t *)(void *)sc->t;
	/* A patch's facets that count on their fronts and those that count
	 * on their backs (x' behind their planes) are never one sheet: they
	 * are the near and the far side of a tube thinner than the cube, one
	 * over the other, whose sides that count point the same way. As one
	 * sheet, the near side hid none of the far one, whose inside then
	 * counted as target area: a thin tube under a parallel beam read 0.21
	 * of the exact (test_compensate, thin_tube_sides_apart). Patch
	 * numbers are polygon numbers, under 2^32 / 3 (poly_start counts 3 or
	 * more vertices a polygon in 32 bits), so the shift loses nothing. */
	for (int a = 0; a < ng; a++)
		key[a] = (patch ? patch[sc->g[a].g] : sc->g[a].g) << 1 | (pm_ddot(sc->g[a].Ne, sc->g[a].N) < 0);
	int nt = tentative(sc, key, tent, tg, hn);
	for (int a = 0; a < ng; a++)
		key[a] = tent[tg[a]].np > 1 && tent[tg[a]].cmin >= SHEET_COS ? (uint32_t)tg[a] : 0x80000000u | (uint32_t)a;
	peel(sc, tent, tg, nt, key);
	tentative(sc, key, sub, sg, hn);
	/* Final numbers in order of each group's lowest polygon. */
	for (int a = 0; a < ng; a++) {
		cgroup *T = &sub[sg[a]];
		int sheet = T->np > 1 && T->cmin >= SHEET_COS;
		if (!sheet || T->p0 < 0) {
			sc->gr[nf] = (cgroup){.key = T->key, .sheet = sheet, .M = T->M, .cmin = T->cmin};
			if (sheet)
				T->p0 = nf;
			sc->g[a].grp = nf++;
		} else
			sc->g[a].grp = T->p0;
		sc->gr[sc->g[a].grp].np++;
	}
	sc->ngr = nf;
	for (int G = 0, p0 = 0; G < nf; G++) {
		sc->gr[G].p0 = p0;
		p0 += sc->gr[G].np;
		sc->gr[G].np = 0;
	}
	for (int a = 0; a < ng; a++) {
		cgroup *G = &sc->gr[sc->g[a].grp];
		sc->gp[G->p0 + G->np++] = a;
	}
	for (int gi = 0; gi < nf; gi++) {
		cgroup *G = &sc->gr[gi];
		double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
		G->slo = INFINITY;
		G->shi = -INFINITY;
		G->sina = G->cmin > 0 ? sqrt(1 - G->cmin * G->cmin) : 2;
		for (int i = G->p0; i < G->p0 + G->np; i++) {
			const cpoly *P = &sc->g[sc->gp[i]];
			for (int a = 0; a < 3; a++) {
				lo[a] = dmin(lo[a], P->lo[a]);
				hi[a] = dmax(hi[a], P->hi[a]);
			}
			G->xsheet |= P->xon;
			if (P->xpar)
				G->apar += pm_ddot(P->Ne, n) > 0 ? P->A : 0;
			else
				G->V = pm_dadd(G->V, pm_dscale(P->Ne, P->A));
			for (int v = 0; v < P->nv && G->sheet; v++) {
				double m = pm_ddot(G->M, sc->cv[P->v0 + v]);
				G->slo = dmin(G->slo, m);
				G->shi = dmax(G->shi, m);
			}
		}
		G->xsheet &= G->sheet;
		for (int a = 0; a < 3; a++) {
			G->lo[a] = lo[a];
			G->hi[a] = hi[a];
		}
		G->c = pm_dscale(pm_dadd(pm_dv3(lo[0], lo[1], lo[2]), pm_dv3(hi[0], hi[1], hi[2])), 0.5);
		G->rad = 0.5 * pm_dlen(pm_dv3(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]));
	}
	return 1;
}

/* The largest and the smallest of M . v - m over group G's box, widened by
 * rounding's share. */
static void
box_span(const cgroup *G, pm_dvec3 M, double m, double *lo, double *hi)
{
	double c[3] = {M.x, M.y, M.z}, a = -m, b = -m, r = fabs(m);

	for (int k = 0; k < 3; k++) {
		double p = c[k] * G->lo[k], q = c[k] * G->hi[k];
		a += dmin(p, q);
		b += dmax(p, q);
		r += dmax(fabs(p), fabs(q));
	}
	*lo = a - 1e-12 * r;
	*hi = b + 1e-12 * r;
}

/* 1 if no polygon of group G can hide part of P from x': G's box wholly
 * behind P's plane as x' sees it, or beyond a plane of P's pyramid. */
static int
group_not_between(const pm_comp_scratch *sc, const cpoly *P, const cgroup *G, pm_dvec3 xo, double eps)
{
	double sxo = pm_ddot(P->N, xo) - P->d, lo, hi;

	box_span(G, P->N, P->d, &lo, &hi);
	if (sxo > 0 ? hi <= eps : lo >= -eps)
		return 1;
	for (int p = 0; p < sc->npyr; p++) {
		box_span(G, sc->pyr[p], pm_ddot(sc->pyr[p], xo), &lo, &hi);
		if (hi < -eps)
			return 1;
	}
	return 0;
}

/* Appends e to sc->bl; on a failed allocation sets sc->oom. */
static inline void
push(pm_comp_scratch *sc, int e)
{
	if (sc->nbl == sc->blcap && !pm_grow((void **)&sc->bl, &sc->blcap, sc->nbl, 1, sizeof *sc->bl)) {
		sc->oom = 1;
		return;
	}
	sc->bl[sc->nbl++] = e;
}

/* B lying on P's plane covers it: resting on it facing it, or the same
 * surface twice (the lower number wins). */
static inline int
plane_covers(const cpoly *P, const cpoly *B)
{
	return pm_ddot(B->Ne, P->Ne) < 0 || B->g < P->g;
}

/* A ray that meets the back of a solid has gone through its front first,
 * unless it started inside: so where a list holds a solid met from behind,
 * it holds the rest of that solid's polygons in the cube too (each again
 * counting only from behind), and a front met first ends the ray there as
 * open. The polygon the ray starts on is not among them (skip, or for x's
 * list those x lies on), nor its sheet (sgrp, or -1): a ray leaving a face's
 * front never meets that face, and in a solid of several parts (a chair's
 * seat, legs and back) x lies behind the planes of other parts' faces while
 * outside them all. Appends to sc->bl from f0. */
static void
close_matter(pm_comp_scratch *sc, int f0, int skip, int sgrp)
{
	int n = sc->nbl, any = 0, st = ++sc->stamp;

	for (int i = f0; i < n; i++) {
		int o = sc->g[IDX(sc->bl[i])].obj;
		sc->mark[IDX(sc->bl[i])] = st;
		if (!(sc->bl[i] & MATTER))
			continue;
		if (o >= sc->omarkcap) {
			int cap = sc->omarkcap;
			if (!pm_grow((void **)&sc->omark, &cap, 0, o + 1, sizeof *sc->omark)) {
				sc->oom = 1;
				return;
			}
			for (int k = sc->omarkcap; k < cap; k++)
				sc->omark[k] = 0;
			sc->omarkcap = cap;
		}
		sc->omark[o] = st;
		any = 1;
	}
	/* Only the groups of those solids. */
	for (int G = 0; G < sc->ngr && any; G++) {
		const cgroup *Gr = &sc->gr[G];
		int o = sc->g[sc->gp[Gr->p0]].obj;
		if (G == sgrp || o >= sc->omarkcap || sc->omark[o] != st)
			continue;
		for (int gi = Gr->p0; gi < Gr->p0 + Gr->np; gi++) {
			int b = sc->gp[gi];
			if (b == skip || (skip < 0 && sc->g[b].xon) || sc->mark[b] == st)
				continue;
			push(sc, b | MATTER);
		}
	}
}

/* 1 if no polygon of group G is on or in front of plane (M, m) beyond eps. */
static int
group_behind(const cgroup *G, pm_dvec3 M, double m, double eps)
{
	double lo, hi;

	box_span(G, M, m, &lo, &hi);
	return hi < -eps;
}

/* 1 if some polygon of group G, not P's, is not behind P's plane: lies
 * in it, has part in front of it, or is more than eps over it (a
 * neighbour across an edge touches it within eps and is behind). A group
 * wholly behind is told by its box. */
static int
in_front(const pm_comp_scratch *sc, const cpoly *P, int G, double eps)
{
	const cgroup *Gr = &sc->gr[G];

	if (G == P->grp || group_behind(Gr, P->Ne, P->de, eps))
		return 0;
	for (int gi = Gr->p0; gi < Gr->p0 + Gr->np; gi++) {
		double lo, hi;
		span(sc, &sc->g[sc->gp[gi]], P->Ne, P->de, &lo, &hi);
		if (!(hi <= eps && lo < -eps))
			return 1;
	}
	return 0;
}

/* 1 if no group but P's is in front of P (in_front()): then P's list
 * (pair_lists()) would hold none of their polygons, as cover (in P's
 * plane), layer or solid (part in front of it) or solid closed (some
 * polygon of it in front), and no ray leaving P's front has a fate but
 * -1. A convex stretch of a mesh is such a sheet for the rest of it: a
 * sheet and the back of the same surface past its ridge (meshroom: 600 of
 * the 700 polygons in the dearest cubes). */
static int
others_behind(pm_comp_scratch *sc, const cpoly *P, double eps)
{
	/* The group that stopped the last walk first: a neighbour's is
	 * likely to stop this one (a rough mesh's lone facets). */
	if (sc->ob_last >= 0 && in_front(sc, P, sc->ob_last, eps))
		return 0;
	for (int G = 0; G < sc->ngr; G++)
		if (G != sc->ob_last && in_front(sc, P, G, eps)) {
			sc->ob_last = G;
			return 0;
		}
	return 1;
}

/* 1 if the model lets no polygon of group G hide part of P from x',
 * whatever the geometry: G is P's own sheet (sgrp), or the faces of one
 * convex solid, which never hide each other. */
static inline int
group_sees_through(const pm_comp_scratch *sc, const unsigned char *cvx, const cpoly *P, int G, int sgrp)
{
	return G == sgrp || (cvx[P->obj] && sc->g[sc->gp[sc->gr[G].p0]].obj == P->obj);
}

/* 1 if B is a polygon x lies on and P a nearly flat neighbour on x's own
 * solid (own, pair_lists()): x sees it through B. */
static inline int
own_neighbour(const cpoly *B, const cpoly *P, int own)
{
	return B->xon && B->solid && B->obj == P->obj && own;
}

/* 1 if no polygon of group G can hide part of P from x' (pair_lists): the
 * model's group_sees_through(), or a sheet out of reach. */
static int
skip_group(const pm_comp_scratch *sc, const unsigned char *cvx, const cpoly *P, int G, int sgrp,
           pm_dvec3 xo, double eps)
{
	const cgroup *Gr = &sc->gr[G];

	if (group_sees_through(sc, cvx, P, G, sgrp))
		return 1;
	return Gr->np > 1 && group_not_between(sc, P, Gr, xo, eps);
}

/* may_hide()'s first tests, the cheap ones: 1 if B cannot hide any of P
 * (x' on B's plane, their sight boxes apart, or P's sphere wholly on x''s
 * side of B's plane); else 0, with *t = N_B . (P's centre) - d_B. */
static inline int
cannot_hide(const pm_comp_scratch *sc, const cpoly *P, int a, int b, const double *plsx, double eps,
            double *t)
{
	const cpoly *B = &sc->g[b];
	double sx = plsx[b];

	if (fabs(sx) <= eps || b == a || !pm_sight_meet(&sc->sg[a], &sc->sg[b]))
		return 1;
	/* P's sphere wholly on the side of B's plane where x' is: P cannot
	 * cross it (span() would say the same). */
	*t = pm_ddot(B->N, P->c) - B->d;
	return fabs(*t) > P->rad && (sx > 0 ? *t - P->rad >= -eps : *t + P->rad <= eps);
}

/* may_hide() past cannot_hide(), t being what that gave. */
static int
may_hide_rest(const pm_comp_scratch *sc, const cpoly *P, int b, const double *plsx, pm_dvec3 xo,
              double eps, int own, double t)
{
	const cpoly *B = &sc->g[b];
	double sx = plsx[b], lo, hi, u;

	if (own_neighbour(B, P, own))
		return 0;
	if (fabs(t) > P->rad)
		lo = t - P->rad, hi = t + P->rad;
	else
		span_verts(sc, P, B->N, B->d, &lo, &hi);
	u = pm_ddot(P->N, B->c) - P->d;
	return (sx > 0 ? lo < -eps : hi > eps) && between(sc, P, B, xo, eps, u);
}

/* 1 if convex polygon B hides every point of P from x', and every photon
 * within eps of P, as crosses() finds: each of P's vertices lies more
 * than a margin m beyond B's plane from x', and the segment from x' to it
 * crosses B more than m inside B's edges. The segments to P's other
 * points cross B within the hull of those crossings (a projection from x'
 * keeps P convex and brings points nearer), so inside it too. m is
 * hide_margin()'s. */
static int
hides_all(const pm_comp_scratch *sc, const cpoly *B, const cpoly *P, pm_dvec3 xo, double m)
{
	double sx = pm_ddot(B->N, xo) - B->d;

	if (!B->convex || fabs(sx) <= m)
		return 0;
	for (int i = 0; i < P->nv; i++) {
		pm_dvec3 v = sc->cv[P->v0 + i];
		double sy = pm_ddot(B->N, v) - B->d;
		if ((sy > 0) == (sx > 0) || fabs(sy) <= m ||
		    !inside(sc, B, pm_dadd(xo, pm_dscale(pm_dsub(v, xo), sx / (sx - sy))), m, 0))
			return 0;
	}
	return 1;
}

/* hides_all()'s margin for P: 3 eps plus twice the largest distance of
 * P's vertices from P's plane. A polygon is planar only to 1e-5 of its
 * size (scene_poly.c), and its sample points lie on the plane, up to that
 * far off its hull. */
static double
hide_margin(const pm_comp_scratch *sc, const cpoly *P, double eps)
{
	double m = 0;

	for (int i = 0; i < P->nv; i++)
		m = dmax(m, fabs(pm_ddot(P->N, sc->cv[P->v0 + i]) - P->d));
	return 3 * eps + 2 * m;
}

/* 1 if x's own polygon (one of the nxp in xp) hides all of P
 * (hides_all(), margin m) and the model lets it hide any of P
 * (group_sees_through(), own_neighbour()).
 * Then P needs no lists and no samples, and nothing of it counts, as its
 * list (which would hold that polygon) would find cell by cell. On a
 * bookshelf these are the sides of the books next to x's spine: thin's
 * cubes of 9-32 polygons sampled 56 % of their polygons only to find
 * every cell hidden; on a rough mesh, the facets in a crevice behind x's. */
static int
behind_x(const pm_comp_scratch *sc, const cpoly *P, const int *xp, int nxp, pm_dvec3 xo, double m)
{
	for (int k = 0; k < nxp; k++) {
		const cpoly *X = &sc->g[xp[k]];
		if (!group_sees_through(sc, sc->cvx, P, X->grp, sheet_of(sc, P)) && !own_neighbour(X, P, P->own) &&
		    hides_all(sc, X, P, xo, m))
			return 1;
	}
	return 0;
}

/* 1 if polygon b (B) may hide part of polygon a (P) from x': some ray
 * from x' meets both (sight.h), B's plane between x' and part of P, and B
 * within P's pyramid from x' (between()). plsx holds each plane's
 * N . x' - d; own says x lies on P's solid. */
static int
may_hide(const pm_comp_scratch *sc, const cpoly *P, int a, int b, const double *plsx, pm_dvec3 xo,
         double eps, int own)
{
	double t;

	return !cannot_hide(sc, P, a, b, plsx, eps, &t) && may_hide_rest(sc, P, b, plsx, xo, eps, own, t);
}

typedef struct cast_ctx {
	pm_comp_scratch *sc;
	const cpoly *P;
	pm_dvec3 xo, y;
	double eps;
} cast_ctx;

/* The tree of the cube's polygons' boxes, grown by 2 eps (past inside()'s
 * eps), made once an estimate when first asked (seen_cast(), cast_fates()),
 * its nodes tagged with their polygons' group where they share one.
 * 0 if there is no room. */
static int
cube_tree(pm_comp_scratch *sc, double eps)
{
	int ng = sc->ng;

	if (sc->tree_built)
		return 1;
	if (!pm_grow((void **)&sc->bb, &sc->bcap, 0, 2 * ng, sizeof *sc->bb))
		return 0;
	for (int b = 0; b < ng; b++)
		for (int k = 0; k < 3; k++) {
			sc->bb[b][k] = sc->g[b].lo[k];
			sc->bb[ng + b][k] = sc->g[b].hi[k];
		}
	if (!pm_boxtree_build(&sc->tree, (const double (*)[3])sc->bb, (const double (*)[3])sc->bb + ng, ng,
	                      2 * eps) ||
	    !pm_grow((void **)&sc->btag, &sc->btagcap, 0, ng, sizeof *sc->btag))
		return 0;
	for (int b = 0; b < ng; b++)
		sc->btag[b] = sc->g[b].grp;
	pm_boxtree_tag(&sc->tree, sc->btag);
	sc->tree_built = 1;
	return 1;
}

/* pm_boxtree_segment's question for polygon b: 1 if it hides y from x',
 * with seen()'s test, and is one that pair_lists() would have listed for P
 * (asked only of the few the segment crosses). */
static int
hides(void *vq, int b)
{
	const cast_ctx *q = vq;
	const pm_comp_scratch *sc = q->sc;
	const cpoly *B = &sc->g[b], *P = q->P;
	double eps = q->eps;

	if (!crosses(sc, B, q->xo, q->y, pm_ddot(B->N, q->xo) - B->d, eps))
		return 0;
	return !skip_group(sc, sc->cvx, P, B->grp, sheet_of(sc, P), q->xo, eps) &&
	       may_hide(sc, P, (int)(P - sc->g), b, sc->pl, q->xo, eps, P->own);
}

/* seen() for a polygon with no list (CAST_AT): the polygons whose boxes
 * (grown by 2 eps, past inside()'s eps) the segment from x' to y passes
 * through, each asked hides(). P's pyramid is made again for
 * may_hide() if another's is in hand. */
static int
seen_cast(pm_comp_scratch *sc, const cpoly *P, pm_dvec3 xo, pm_dvec3 y, double eps)
{
	cast_ctx q = {sc, P, xo, y, eps};

	if (!cube_tree(sc, eps)) {
		sc->oom = 1;
		return 1;
	}
	if (sc->pyr_of != (int)(P - sc->g) && !pyramid(sc, P, xo, eps)) {
		sc->oom = 1;
		return 1;
	}
	return !pm_boxtree_segment(&sc->tree, xo, y, hides, &q);
}

static int
cmp_u64(const void *a, const void *b)
{
	uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
	return (x > y) - (x < y);
}

/* The objects a cube's polygons are counted into place by, past which
 * cast_prepare() sorts them. */
#define OBJS_FEW 16

/* In a cube whose fates go by rays: the cube's polygons by object (runs
 * in sc->oby, each polygon's run in orun), for cast_closed(), and each
 * polygon's place in sc->gp. 0 if there is no room. */
static int
cast_prepare(pm_comp_scratch *sc)
{
	int ng = sc->ng;

	if (!pm_grow((void **)&sc->oby, &sc->obycap, 0, ng, sizeof *sc->oby) ||
	    !pm_grow((void **)&sc->orun0, &sc->orun0cap, 0, ng + 1, sizeof *sc->orun0) ||
	    !pm_grow((void **)&sc->onrm, &sc->onrmcap, 0, ng, sizeof *sc->onrm))
		return 0;
	/* A cube holds polygons of few objects (objs, ascending): counted
	 * into place by object, in polygon order within one, the order a
	 * sort of (object, polygon) gives, and for less than a sort. */
	uint32_t objs[OBJS_FEW];
	int cnt[OBJS_FEW + 1] = {0}, no = 0;
	for (int i = 0; i < ng && no <= OBJS_FEW; i++) {
		uint32_t o = (uint32_t)sc->g[i].obj;
		int s = 0;
		while (s < no && objs[s] < o)
			s++;
		if (s < no && objs[s] == o)
			continue;
		if (no < OBJS_FEW) {
			memmove(objs + s + 1, objs + s, (size_t)(no - s) * sizeof *objs);
			objs[s] = o;
		}
		no++;
	}
	for (int i = 0; i < ng; i++)
		sc->g[sc->gp[i]].gpos = i;
	if (no > OBJS_FEW) {
		if (!pm_grow((void **)&sc->okey, &sc->okeycap, 0, ng, sizeof *sc->okey))
			return 0;
		for (int i = 0; i < ng; i++)
			sc->okey[i] = (uint64_t)(uint32_t)sc->g[i].obj << 32 | (uint32_t)i;
		qsort(sc->okey, (size_t)ng, sizeof *sc->okey, cmp_u64);
		for (int i = 0; i < ng; i++)
			sc->oby[i] = (int)(uint32_t)sc->okey[i];
	} else
		for (int pass = 0; pass < 2; pass++) {
			for (int i = 0; i < ng; i++) {
				int s = 0;
				while (objs[s] != (uint32_t)sc->g[i].obj)
					s++;
				if (pass == 0)
					cnt[s + 1]++;
				else
					sc->oby[cnt[s]++] = i;
			}
			for (int s = 0; s < no && pass == 0; s++)
				cnt[s + 1] += cnt[s];
		}
	sc->nrun = 0;
	for (int i = 0; i < ng; i++) {
		int b = sc->oby[i];
		if (i == 0 || sc->g[b].obj != sc->g[sc->oby[i - 1]].obj)
			sc->orun0[sc->nrun++] = i;
		sc->onrm[i] = sc->g[b].N;
		sc->g[b].orun = sc->nrun - 1;
	}
	sc->orun0[sc->nrun] = ng;
	return 1;
}

/* 1 if P's list would close B's solid (run r): some polygon of it, not P
 * nor of P's sheet sgrp, no layer over P, has part in front of P and P
 * lies partly behind its plane (pair_lists()'s MATTER entries, which
 * close_matter() closes). Kept in P for its first CLOSED_KEPT solids (the
 * photons' loop asks P after P), worked out again for the others (a cube
 * of so many objects holds few polygons of each). */
static int
cast_closed(pm_comp_scratch *sc, const cpoly *P, int r, int sgrp, double eps)
{
	cpoly *W = &sc->g[P - sc->g];
	int v = 0, kept = r < CLOSED_KEPT;

	if (kept && (W->closed >> 2 * r & 1))
		return (int)(W->closed >> (2 * r + 1) & 1);
	for (int i = sc->orun0[r]; i < sc->orun0[r + 1] && !v; i++) {
		const cpoly *C;
		double lo, hi, plo, phi;
		/* Most of a solid's polygons in the cube are layers over P (its
		 * own mesh, curving gently): told from the normals alone, kept
		 * together, before the polygon is looked at. */
		if (fabs(pm_ddot(sc->onrm[i], P->N)) >= LAYER_COS)
			continue;
		C = &sc->g[sc->oby[i]];
		if (C == P || C->grp == sgrp || !C->solid)
			continue;
		span(sc, C, P->Ne, P->de, &lo, &hi);
		if (!(hi > eps))
			continue;
		span(sc, P, C->N, C->d, &plo, &phi);
		v = plo < -eps;
	}
	if (kept)
		W->closed |= (uint64_t)(1 | v << 1) << 2 * r;
	return v;
}

/* What P's list (pair_lists()) would hold of B, neither P nor of P's sheet
 * sgrp, lo and hi being B's span over P's plane (span()): -1 nothing; 0 a
 * cover on P's plane; 1 a layer with part in front of P, or a solid P lies
 * partly behind (*matter); 2 another polygon of such a solid (*matter:
 * close_matter()). */
static int
cast_class_at(pm_comp_scratch *sc, const cpoly *P, const cpoly *B, double lo, double hi, int sgrp,
              double eps, int *matter)
{
	int layer = fabs(pm_ddot(B->N, P->N)) >= LAYER_COS;
	double plo, phi;

	*matter = 0;
	if (layer && hi <= eps && lo >= -eps) {
		if (plane_covers(P, B))
			return 0;
	} else if (layer && hi > eps)
		return 1;
	else if (B->solid && hi > eps) {
		span(sc, P, B->N, B->d, &plo, &phi);
		if (plo < -eps) {
			*matter = 1;
			return 1;
		}
	}
	if (B->solid && cast_closed(sc, P, B->orun, sgrp, eps)) {
		*matter = 1;
		return 2;
	}
	return -1;
}

/* cast_class_at() with B's span over P's plane worked out here. */
static int
cast_class(pm_comp_scratch *sc, const cpoly *P, const cpoly *B, int sgrp, double eps, int *matter)
{
	double lo, hi;

	span(sc, B, P->Ne, P->de, &lo, &hi);
	return cast_class_at(sc, P, B, lo, hi, sgrp, eps, matter);
}

/* Rays cast_fates() follows in one beam: at most four of a fate-cast
 * polygon's dynamic sample points, a row of its grid (at most 4 x 4,
 * sample()) or all of a 2 x 2 one. Beams of 8 or 16 met more polygons than
 * the walks they saved (scanned, meshroom); beams of 2 saved too few walks. */
#define BEAM_MAX 4

typedef struct fate_ctx {
	pm_comp_scratch *sc;
	const cpoly *P;
	const pm_dvec3 *y;
	pm_dvec3 psi;
	double eps, len, smax;
	int n, sgrp, covers;
	double best[BEAM_MAX];
	int key[BEAM_MAX], f[BEAM_MAX];
} fate_ctx;

/* pm_boxtree_beam's question for polygon b along the backward rays: for
 * each ray, if fate() over P's list would take b's entry before the best
 * so far (a nearer hit, or as near and earlier on the list), it becomes
 * that ray's best. Boxes entered beyond every ray's best (by more than
 * eps: a hit lies within eps of its polygon, whose box the tree grew by
 * 2 eps) need not be asked. What the list would hold of b is worked out
 * once, when some ray meets it. */
static void
fate_visit(void *vq, int b)
{
	fate_ctx *q = vq;
	pm_comp_scratch *sc = q->sc;
	const cpoly *B = &sc->g[b], *P = q->P;
	double d = pm_ddot(B->N, q->psi), t;
	int matter, cls = -2, key = 0, fb = 0, low = 0;

	if (B == P || B->grp == q->sgrp || fabs(d) < 1e-9)
		return;
	for (int i = 0; i < q->n; i++) {
		/* As near as the best counts too (the earlier entry wins):
		 * meets() asked for hits short of a hair past it, the test
		 * below sorts them. */
		double best = q->best[i];
		if (!meets(sc, B, d, q->y[i], q->psi, q->eps, best + 1e-12 * best + DBL_MIN, &t))
			continue;
		if (cls == -2) {
			cls = cast_class(sc, P, B, q->sgrp, q->eps, &matter);
			if (cls < 0 || (cls == 0 && !q->covers))
				return;
			/* List order: covers, then the rest of the walk, then
			 * what closing solids adds, each in the order of sc->gp. */
			key = cls * sc->ng + B->gpos;
			fb = fate_at(matter ? MATTER : 0, B, d);
		}
		if (t < best || (t == best && key < q->key[i])) {
			q->best[i] = t;
			q->key[i] = key;
			q->f[i] = fb;
			low = 1;
		}
	}
	if (low) {
		double smax = 0;
		for (int i = 0; i < q->n; i++)
			smax = dmax(smax, dmin(1, (q->best[i] + q->eps) / q->len));
		q->smax = smax;
	}
}

/* fate() of the backward rays from y[0 .. n) on P along psi (n <=
 * BEAM_MAX) over the list P would have (pair_lists()), into f[], by the
 * polygons whose boxes they pass through, in one walk of the tree: covers
 * on P's plane taken as any other entry (covers 1, a photon's own ray) or
 * left out (covers 0: sample points, which cast_cover() asked first). 0 if
 * there is no room (sc->oom set). */
static int
cast_fates(pm_comp_scratch *sc, const cpoly *P, const pm_dvec3 *y, int n, pm_dvec3 psi, double h, double eps,
           int covers, int *f)
{
	/* Every polygon lies in the cube, within 2 sqrt(3) h of y. */
	fate_ctx q = {sc, P, y, psi, eps, 4 * h, 1, n, sheet_of(sc, P), covers, {0}, {0}, {0}};
	pm_dvec3 lo = y[0], hi = y[0];

	if (!cube_tree(sc, eps)) {
		sc->oom = 1;
		return 0;
	}
	for (int i = 0; i < n; i++) {
		q.best[i] = INFINITY;
		q.key[i] = INT_MAX;
		q.f[i] = -1;
		lo = pm_dv3(dmin(lo.x, y[i].x), dmin(lo.y, y[i].y), dmin(lo.z, y[i].z));
		hi = pm_dv3(dmax(hi.x, y[i].x), dmax(hi.y, y[i].y), dmax(hi.z, y[i].z));
	}
	pm_boxtree_beam(&sc->tree, lo, hi, pm_dscale(psi, q.len), q.sgrp, &q.smax, fate_visit, &q);
	for (int i = 0; i < n; i++)
		f[i] = q.f[i];
	return 1;
}

/* cast_fates() of one ray: its fate, or -1 (sc->oom set) if there is no
 * room. */
static int
cast_fate(pm_comp_scratch *sc, const cpoly *P, pm_dvec3 y, pm_dvec3 psi, double h, double eps, int covers)
{
	int f = -1;

	cast_fates(sc, P, &y, 1, psi, h, eps, covers, &f);
	return f;
}

/* front_hits() by rays through the tree, in beams, where P has no front
 * list; sc->oom set if there is no room. */
static int
cast_hits(pm_comp_scratch *sc, const cpoly *P, pm_dvec3 psi, double h, double eps, int fx)
{
	int hit = 0, f[BEAM_MAX];

	for (int t = P->s0; t < P->s0 + P->ndyn; t += BEAM_MAX) {
		int n = P->s0 + P->ndyn - t < BEAM_MAX ? P->s0 + P->ndyn - t : BEAM_MAX;
		if (!cast_fates(sc, P, sc->sp + t, n, psi, h, eps, 0, f))
			return 0;
		for (int i = 0; i < n; i++)
			hit += f[i] == fx;
	}
	return hit;
}

typedef struct front_ctx {
	pm_comp_scratch *sc;
	cpoly *P;
	double eps;
	int sgrp, seen;
} front_ctx;

/* pm_boxtree_halfspace's question for polygon b, whose box reaches P's
 * front: if b reaches it (within 8 eps: a hit lies within a few eps of
 * its polygon, and may be behind y by eps) and P's list would hold it off
 * P's plane, it joins P's front list; 1 (stop) past FRONT_SCAN polygons
 * or FRONT_MAX entries. */
static int
front_visit(void *vq, int b)
{
	front_ctx *q = vq;
	pm_comp_scratch *sc = q->sc;
	const cpoly *B = &sc->g[b];
	cpoly *P = q->P;
	double lo, hi;
	int m, cls;

	if (B == P || B->grp == q->sgrp)
		return 0;
	span(sc, B, P->Ne, P->de, &lo, &hi);
	if (!(hi > -8 * q->eps))
		return 0;
	if (++q->seen > FRONT_SCAN)
		return 1;
	if ((cls = cast_class_at(sc, P, B, lo, hi, q->sgrp, q->eps, &m)) < 1)
		return 0;
	if (P->nfl == FRONT_MAX || !pm_grow((void **)&sc->fl, &sc->flcap, sc->nfl, 1, sizeof *sc->fl) ||
	    !pm_grow((void **)&sc->flk, &sc->flkcap, sc->nfl, 1, sizeof *sc->flk))
		return 1;
	/* In list order (fate() takes the first of equally near hits). */
	int k = cls * sc->ng + B->gpos, i = sc->nfl++;
	for (; i > P->fl0 && sc->flk[i - 1] > k; i--) {
		sc->fl[i] = sc->fl[i - 1];
		sc->flk[i] = sc->flk[i - 1];
	}
	sc->fl[i] = b | (m ? MATTER : 0);
	sc->flk[i] = k;
	P->nfl++;
	return 0;
}

/* P's front list: what its list (pair_lists()) would hold off its plane
 * that a backward ray from it may meet, or nfl -1 where that is more than
 * FRONT_MAX or the search passes FRONT_SCAN polygons. 0 if there is no room. */
static int
front_list(pm_comp_scratch *sc, cpoly *P, double eps)
{
	front_ctx q = {sc, P, eps, sheet_of(sc, P), 0};

	if (!cube_tree(sc, eps))
		return 0;
	P->fl0 = sc->nfl;
	P->nfl = 0;
	if (pm_boxtree_halfspace(&sc->tree, P->Ne, P->de - 8 * eps, q.sgrp, front_visit, &q)) {
		sc->nfl = P->fl0;
		P->nfl = -1;
	}
	return 1;
}

/* How many of P's dynamic sample points have fate fx along psi, from P's
 * front list (fate() over it, those no ray from P can meet left out). */
static int
front_hits(pm_comp_scratch *sc, const cpoly *P, pm_dvec3 psi, double eps, int fx)
{
	int cand[FRONT_MAX], nc = 0, hit = 0;
	double dn[FRONT_MAX];

	for (int i = 0; i < P->nfl; i++) {
		const cpoly *B = &sc->g[IDX(sc->fl[P->fl0 + i])];
		double d = pm_ddot(B->N, psi);
		if (fabs(d) < 1e-9 || apart(P, B, psi, eps))
			continue;
		dn[nc] = d;
		cand[nc++] = sc->fl[P->fl0 + i];
	}
	if (nc == 0)
		return fx == -1 ? P->ndyn : 0;
	for (int s = P->s0; s < P->s0 + P->ndyn; s++) {
		double best = INFINITY, t;
		int f = -1;
		for (int i = 0; i < nc; i++) {
			const cpoly *B = &sc->g[IDX(cand[i])];
			if (meets(sc, B, dn[i], sc->sp[s], psi, eps, best, &t)) {
				best = t;
				f = fate_at(cand[i] & MATTER, B, dn[i]);
			}
		}
		hit += f == fx;
	}
	return hit;
}

typedef struct cover_ctx {
	pm_comp_scratch *sc;
	const cpoly *P;
	pm_dvec3 y;
	double eps;
	int sgrp, best;
} cover_ctx;

static int
cover_visit(void *vq, int b)
{
	cover_ctx *q = vq;
	pm_comp_scratch *sc = q->sc;
	const cpoly *B = &sc->g[b];
	int matter;

	if (B == q->P || B->grp == q->sgrp || (q->best >= 0 && sc->g[q->best].gpos < B->gpos) ||
	    !inside(sc, B, q->y, q->eps, 0) || cast_class(sc, q->P, B, q->sgrp, q->eps, &matter) != 0)
		return 0;
	q->best = b;
	return 0;
}

/* sample()'s cover test for a point y of P whose fates go by rays: the
 * first cover on P's list (pair_lists()) holding y, as its list's nfc
 * entries are asked; -1 if none. sc->oom set if there is no room. */
static int
cast_cover(pm_comp_scratch *sc, const cpoly *P, pm_dvec3 y, double eps)
{
	cover_ctx q = {sc, P, y, eps, sheet_of(sc, P), -1};

	if (!cube_tree(sc, eps)) {
		sc->oom = 1;
		return -1;
	}
	pm_boxtree_segment(&sc->tree, y, y, cover_visit, &q);
	return q.best;
}

/* With few groups (FEW_GROUPS), asks each once whether it can hide part of
 * P (gskip, stamped st in gmk); if those that can hold fewer than
 * SIGHT_MIN polygons, lists them by may_hide() and returns 1, with no grid
 * query. 0: the caller queries the grid (the answers stay in gskip). */
static int
few_hiders(pm_comp_scratch *sc, const unsigned char *cvx, const cpoly *P, int a, int sgrp,
           const double *plsx, pm_dvec3 xo, double eps, int own, int st)
{
	int ngr = sc->ngr, nmay = 0;

	if (ngr > FEW_GROUPS)
		return 0;
	for (int G = 0; G < ngr; G++) {
		sc->gmk[G] = st;
		sc->gskip[G] = skip_group(sc, cvx, P, G, sgrp, xo, eps);
		nmay += sc->gskip[G] ? 0 : sc->gr[G].np;
	}
	if (nmay >= SIGHT_MIN)
		return 0;
	for (int G = 0; G < ngr; G++)
		for (int gi = sc->gr[G].p0; gi < sc->gr[G].p0 + sc->gr[G].np && !sc->gskip[G]; gi++)
			if (may_hide(sc, P, a, sc->gp[gi], plsx, xo, eps, own))
				push(sc, sc->gp[gi]);
	return 1;
}

static int
one_sheet(const pm_comp_scratch *sc)
{
	return sc->ngr == 1 && sc->gr[0].sheet;
}

/* For each polygon: which others may hide part of it from x' (R list), and
 * which a backward ray from it may meet so that its fate differs from the
 * open one (F list): layers over it (|N_b . N| >= LAYER_COS) with some part
 * in front of it or lying on it facing it; solids it lies partly behind.
 * Then the same F list for x itself (index ng). Polygons of one sheet are
 * never on each other's lists; a group wholly out of reach is passed over
 * whole. */
static int
pair_lists(pm_comp_scratch *sc, const unsigned char *cvx, pm_dvec3 xo, pm_dvec3 n, double eps,
           int *xf0, int *nxf)
{
	int ng = sc->ng, ngr = sc->ngr, follow = !sc->fcast, grid = ng >= SIGHT_MIN;
	/* In a cube for the grid, a walk that finds this many stops (CAST_AT). */
	int stop = !grid ? INT_MAX : pm_comp_cast_at < 9 ? 9 : pm_comp_cast_at;
	/* One sheet is all the cube holds: it hides none of itself, and a ray
	 * leaving it does not meet it again, so every polygon's lists are
	 * empty (x's too, where x lies on it). */
	int alone = one_sheet(sc);

	sc->nbl = 0;
	sc->nwhole = 0;
	sc->tree_built = 0;
	sc->pyr_of = -1;
	sc->ob_last = -1;
	sc->cvx = cvx;
	if (!pm_grow((void **)&sc->pl, &sc->plcap, 0, ng, sizeof *sc->pl))
		return 0;
	if (!pm_grow((void **)&sc->cand, &sc->candcap, 0, ng, sizeof *sc->cand))
		return 0;
	if (grid) {
		int gcap = sc->gmkcap;
		if (!pm_grow((void **)&sc->gmk, &sc->gmkcap, 0, ngr, sizeof *sc->gmk) ||
		    !pm_grow((void **)&sc->gskip, &gcap, 0, ngr, sizeof *sc->gskip))
			return 0;
		for (int G = 0; G < ngr; G++)
			sc->gmk[G] = 0;
	}
	int built = 0;
	int xobj[4], nxobj = 0, xp[4], nxp = 0;

	for (int b = 0; b < ng; b++)
		if (sc->g[b].xon && nxobj < 4) {
			xobj[nxobj++] = sc->g[b].obj;
			xp[nxp++] = b;
		}
	double *plsx = sc->pl;
	for (int b = 0; b < ng; b++)
		plsx[b] = pm_ddot(sc->g[b].N, xo) - sc->g[b].d;
	for (int a = 0; a < ng; a++) {
		cpoly *P = &sc->g[a];
		int own = nxobj == 4, sgrp = sheet_of(sc, P);
		P->r0 = sc->nbl;
		/* The back of a solid, seen from outside it, is hidden by the
		 * solid itself, unless x lies on that solid (a face across a
		 * convex edge). A face of x's own sheet turned away more than
		 * SMOOTH_COS is a back face too: the sheet's cone (SHEET_COS)
		 * says which facets hide none of each other, not which x sees
		 * (counted as seen, they read a sphere dark where it meets the
		 * floor: torture seed 185). */
		for (int b = 0; b < nxobj && !own; b++)
			own = xobj[b] == P->obj && pm_ddot(P->N, n) >= SMOOTH_COS;
		P->unseen = P->solid && !own && pm_ddot(P->N, xo) - P->d < -eps;
		P->own = own;
		P->cast = 0;
		if (alone) {
			P->nr = P->nfc = P->nf = 0;
			P->f0 = sc->nbl;
			continue;
		}
		double hm = !P->unseen && P->lit && pm_comp_hidden_whole ? hide_margin(sc, P, eps) : 0;
		if (hm > 0 && behind_x(sc, P, xp, nxp, xo, hm)) {
			P->unseen = 1;
			sc->nwhole++;
		}
		if (!P->unseen && P->lit && !pyramid(sc, P, xo, eps))
			return 0;
		if (P->unseen || !P->lit)
			;
		else if (!grid || sc->sg[a].face < 0) {
			for (int G = 0; G < ngr && sc->nbl - P->r0 < stop; G++) {
				const cgroup *Gr = &sc->gr[G];
				if (skip_group(sc, cvx, P, G, sgrp, xo, eps))
					continue;
				for (int gi = Gr->p0; gi < Gr->p0 + Gr->np && sc->nbl - P->r0 < stop; gi++)
					if (may_hide(sc, P, a, sc->gp[gi], plsx, xo, eps, own))
						push(sc, sc->gp[gi]);
			}
		} else if (!few_hiders(sc, cvx, P, a, sgrp, plsx, xo, eps, own, ++sc->stamp)) {
			int st = sc->stamp;
			if (!built) {
				/* The grid, and the groups its queries leave out by. */
				if (!pm_sight_grid_build(&sc->grid, sc->sg, ng) ||
				    !pm_grow((void **)&sc->pgrp, &sc->pgrpcap, 0, ng, sizeof *sc->pgrp))
					return 0;
				for (int b = 0; b < ng; b++)
					sc->pgrp[b] = sc->g[b].grp;
			}
			built = 1;
			/* Not P's own sheet, which skip_group() passes over, where
			 * it is an eighth of the cube or more (dense: two thirds of
			 * the candidates walked); a smaller one costs the query more
			 * to leave out than the walk to pass over (scanned). */
			int skip = sgrp >= 0 && 8 * sc->gr[sgrp].np >= ng ? sgrp : -1;
			int nc = pm_sight_grid_query(&sc->grid, ng, &sc->sg[a], sc->pgrp, skip, sc->cand, sc->mark, st);
			for (int k = 0; k < nc && sc->nbl - P->r0 < stop; k++) {
				int b = sc->cand[k], G = sc->g[b].grp;
				double t;
				/* may_hide()'s first tests before the group's, unless
				 * the group is known to be skipped: most candidates of
				 * a rough mesh fail them. */
				if ((sc->gmk[G] == st && sc->gskip[G]) || cannot_hide(sc, P, a, b, plsx, eps, &t))
					continue;
				if (sc->gmk[G] != st) {
					sc->gmk[G] = st;
					sc->gskip[G] = skip_group(sc, cvx, P, G, sgrp, xo, eps);
				}
				if (!sc->gskip[G] && may_hide_rest(sc, P, b, plsx, xo, eps, own, t))
					push(sc, b);
			}
		}
		P->nr = sc->nbl - P->r0;
		if (P->nr >= stop) {
			P->cast = 1;
			P->nr = stop;
			sc->nbl = P->r0;
		}
		/* One polygon on the list hiding all of P: seen() would say so of
		 * every cell and photon, so P is unseen, with no F list. Where
		 * the walk stopped (P->cast), one of those it found will do as
		 * well: seen_cast() would find it on every segment. */
		for (int i = 0; i < P->nr && !P->unseen && hm > 0; i++)
			if (hides_all(sc, &sc->g[sc->bl[P->r0 + i]], P, xo, hm)) {
				P->unseen = 1;
				P->cast = 0;
				P->nr = 0;
				sc->nbl = P->r0;
				sc->nwhole++;
			}
		P->f0 = sc->nbl;
		/* Where fates go by rays, no F list: cast_fates() asks what it
		 * would hold of the polygons a ray meets; nothing, where every
		 * other group lies behind P's plane, and P is then as plain as
		 * the lists would leave it. */
		P->fcast = !follow && P->lit && !P->unseen && !others_behind(sc, P, eps);
		/* Where they are, one walk: those on P's plane go first, the
		 * rest wait in sc->cand. */
		int noff = 0;
		for (int G = 0; G < ngr && follow && P->lit && !P->unseen; G++) {
			const cgroup *Gr = &sc->gr[G];
			if (G == sgrp || (Gr->np > 1 && group_behind(Gr, P->Ne, P->de, eps)))
				continue;
			for (int gi = Gr->p0; gi < Gr->p0 + Gr->np; gi++) {
				int b = sc->gp[gi];
				const cpoly *B = &sc->g[b];
				double lo, hi, plo, phi;
				int layer = fabs(pm_ddot(B->N, P->N)) >= LAYER_COS, cand = 0;
				if (b == a)
					continue;
				span(sc, B, P->Ne, P->de, &lo, &hi);
				if (layer && hi <= eps && lo >= -eps) {
					if (plane_covers(P, B))
						push(sc, b);
					continue;
				}
				if (layer && hi > eps)
					cand = 1;
				else if (B->solid && hi > eps) {
					span(sc, P, B->N, B->d, &plo, &phi);
					cand = plo < -eps ? 2 : 0;
				}
				if (cand)
					sc->cand[noff++] = (cand == 2 ? b | MATTER : b) | (lo >= -eps ? FRONT : 0);
			}
		}
		P->nfc = sc->nbl - P->f0;
		for (int k = 0; k < noff; k++)
			push(sc, sc->cand[k]);
		if (P->lit && !P->unseen && follow)
			close_matter(sc, P->f0 + P->nfc, a, sgrp);
		P->nf = sc->nbl - P->f0;
	}
	*xf0 = sc->nbl;
	for (int G = 0; G < ngr; G++) {
		const cgroup *Gr = &sc->gr[G];
		if (Gr->xsheet || (Gr->np > 1 && group_behind(Gr, n, 0, -eps)))
			continue;
		for (int gi = Gr->p0; gi < Gr->p0 + Gr->np; gi++) {
			const cpoly *B = &sc->g[sc->gp[gi]];
			double lo, hi;
			if (B->xon)
				continue;
			span(sc, B, n, 0, &lo, &hi);
			if (!(hi > eps))
				continue;
			if (fabs(pm_ddot(B->N, n)) >= LAYER_COS)
				push(sc, sc->gp[gi]);
			else if (B->solid && B->d > eps)
				push(sc, sc->gp[gi] | MATTER);
		}
	}
	int xs = -1;
	for (int G = 0; G < ngr && xs < 0; G++)
		xs = sc->gr[G].xsheet ? G : -1;
	close_matter(sc, *xf0, -1, xs);
	*nxf = sc->nbl - *xf0;
	/* Room for the candidates the photons' loop lists past the end, and
	 * those that wait. */
	if (!pm_grow((void **)&sc->bl, &sc->blcap, sc->nbl, 2 * (ng + 1), sizeof *sc->bl))
		sc->oom = 1;
	return !sc->oom;
}

/* Sample points of P: the centres of the G x G cells of its bounding
 * rectangle that lie inside it (G up to GRID, fewer for a polygon that
 * fills only a little of the cube), each carrying an equal share of its area;
 * and which of them x' sees. */
static int
sample(pm_comp_scratch *sc, cpoly *P, pm_dvec3 xo, double h, double eps)
{
	pm_dvec3 t1, t2, base;
	double lo1 = INFINITY, hi1 = -INFINITY, lo2 = INFINITY, hi2 = -INFINITY;
	int kept = 0, G = (int)ceil(GRID * sqrt(P->A / (4 * h * h)));

	/* Cells of about the cube's face over GRID x GRID whatever the mesh: a
	 * polygon smaller than one gets one cell. A floor of two per side cost
	 * scanned 14 % and dense 11 % of an estimate's time, for areas finer
	 * than a large polygon's cells ever are, and cut the least target
	 * area of a photon on such a polygon (its cell) to a half or a
	 * quarter of the polygon: a photon alone on a sliver of its facet
	 * weighed up to four times as much (BENCHMARKS.md, "One cell for a
	 * polygon smaller than one"). */
	G = G < 1 ? 1 : G > GRID ? GRID : G;
	if ((P->nr + P->nf > 8 || P->fcast) && G > 4)
		G = 4;
	/* Twice G x G: the covered ones wait behind while the rest are sorted. */
	if (!grow_samples(sc, 2 * G * G) ||
	    !pm_grow((void **)&sc->sgd, &sc->sgdcap, 0, sc->ng, sizeof *sc->sgd))
		return 0;
	sgrid *S = &sc->sgd[P - sc->g];
	S->G = G;
	plane_axes(P->N, &t1, &t2);
	S->t1 = t1;
	S->t2 = t2;
	double va[ROW_MAX_VERTS], vb[ROW_MAX_VERTS];
	int rows = P->convex && P->nv <= ROW_MAX_VERTS;
	for (int i = 0; i < P->nv; i++) {
		double a = pm_ddot(sc->cv[P->v0 + i], t1), b = pm_ddot(sc->cv[P->v0 + i], t2);
		lo1 = dmin(lo1, a);
		hi1 = dmax(hi1, a);
		lo2 = dmin(lo2, b);
		hi2 = dmax(hi2, b);
		if (rows) {
			va[i] = a;
			vb[i] = b;
		}
	}
	base = pm_dscale(P->N, P->d);
	P->s0 = sc->nsp;
	for (int j = 0; j < G; j++)
		S->v[GRID + j] = lo2 + (hi2 - lo2) * (j + 0.5) / G;
	for (int i = 0; i < G; i++) {
		double a = lo1 + (hi1 - lo1) * (i + 0.5) / G, blo = INFINITY, bhi = -INFINITY;
		S->v[i] = a;
		/* A convex polygon meets the row in one interval. */
		for (int e = 0, f = P->nv - 1; rows && e < P->nv; f = e++)
			if ((va[e] - a) * (va[f] - a) <= 0 && va[e] != va[f]) {
				double b = vb[f] + (a - va[f]) * (vb[e] - vb[f]) / (va[e] - va[f]);
				blo = dmin(blo, b);
				bhi = dmax(bhi, b);
			}
		for (int j = 0; j < G; j++) {
			double b = S->v[GRID + j];
			pm_dvec3 p = pm_dadd(base, pm_dadd(pm_dscale(t1, a), pm_dscale(t2, b)));
			if (rows ? b >= blo && b <= bhi : inside(sc, P, p, 0, 1)) {
				sc->scell[P->s0 + kept] = (unsigned char)(16 * i + j);
				sc->sp[P->s0 + kept++] = p;
			}
		}
	}
	if (kept == 0) {
		pm_dvec3 m = pm_dv3(0, 0, 0);
		for (int i = 0; i < P->nv; i++)
			m = pm_dadd(m, sc->cv[P->v0 + i]);
		m = pm_dscale(m, 1.0 / P->nv);
		S->G = 1;
		S->v[0] = pm_ddot(m, t1);
		S->v[GRID] = pm_ddot(m, t2);
		sc->scell[P->s0] = 0;
		sc->sp[P->s0 + kept++] = m;
	}
	P->ncell = kept;
	P->ndyn = 0;
	/* Only samples whose fate is not "open for every direction" cost work
	 * per photon; they are kept, dynamic ones first. All cells weigh the
	 * same, so areas are counts times one cell. */
	double cell = P->A / kept;
	int nopen = 0, ncov = 0;
	unsigned char vis[GRID * GRID];
	seen_many(sc, P, xo, sc->sp + P->s0, kept, eps, vis);
	for (int i = P->s0; i < P->s0 + kept; i++) {
		int f = -1;
		if (!vis[i - P->s0])
			continue;
		/* Fates by rays: a point a cover holds is covered, the others
		 * are dynamic. */
		if (P->fcast) {
			int b = cast_cover(sc, P, sc->sp[i], eps);
			if (sc->oom)
				return 0;
			f = b < 0 ? -2 : 2 * sc->g[b].obj + (pm_ddot(sc->g[b].N, P->Ne) > 0);
		}
		/* Covered by a polygon on P's plane: a backward ray meets it at
		 * once, whatever its direction. */
		for (int b = 0; b < P->nfc && f < 0; b++) {
			const cpoly *B = &sc->g[sc->bl[P->f0 + b]];
			if (inside(sc, B, sc->sp[i], eps, 0))
				f = 2 * B->obj + (pm_ddot(B->N, P->Ne) > 0);
		}
		/* A layer off P's plane, or a solid P's point lies behind, can
		 * change the fate with the direction; the front of a solid
		 * across an edge alone cannot. */
		for (int b = P->nfc; b < P->nf && f == -1; b++) {
			int e = sc->bl[P->f0 + b];
			const cpoly *B = &sc->g[IDX(e)];
			if (!(e & MATTER) || pm_ddot(B->N, sc->sp[i]) - B->d < -eps)
				f = -2;
		}
		if (f == -1)
			nopen++;
		else if (f == -2) {
			sc->scell[P->s0 + P->ndyn] = sc->scell[i];
			sc->sp[P->s0 + P->ndyn++] = sc->sp[i];
		}
		else {
			sc->sf[P->s0 + G * G + ncov] = f;
			sc->sp[P->s0 + G * G + ncov++] = sc->sp[i];
		}
	}
	for (int i = 0; i < ncov; i++) {
		sc->sf[P->s0 + P->ndyn + i] = sc->sf[P->s0 + G * G + i];
		sc->sp[P->s0 + P->ndyn + i] = sc->sp[P->s0 + G * G + i];
	}
	for (int c = 0; c < 2 * GRID; c++)
		S->m[c] = 0;
	for (int k = 0; k < P->ndyn; k++) {
		int cl = sc->scell[P->s0 + k];
		S->m[cl >> 4] |= (uint64_t)1 << k;
		S->m[GRID + (cl & 15)] |= (uint64_t)1 << k;
	}
	P->ns = P->ndyn + ncov;
	sc->nsp += P->ns;
	P->aopen = cell * nopen;
	P->adyn = cell * P->ndyn;
	return 1;
}

/* Which of the cube's GRID cells along an axis holds coordinate v (from
 * x, the cube's half-size h), those outside the cube in the nearest: monotone
 * in v, so a box's cells hold the cells of every point in it. */
static inline int
cube_cell(double v, double h)
{
	double t = (v + h) * (GRID / (2 * h));
	return !(t >= 1) ? 0 : t >= GRID - 1 ? GRID - 1 : (int)t;
}

/* The cosine within which a facet's normal must lie of its cell's first
 * facet's to take its ray (10 degrees). Where the sheet bends inside a
 * cell (a bump's flank beside its top) the facets' fates part: there the
 * generated bumps test found its largest differences (127 % in one
 * estimate); with this rule 40 %, the mean 2.9 -> 2.1 %, while dense
 * keeps 99.8 % of its shared facets and meshroom 92 %. */
#define SHARE_COS 0.985

/* Where fates go by rays, a sheet of facets smaller than a sample cell
 * gets a point a facet (sample()), and each point a backward ray for
 * every photon: thousands in a cube of a dense mesh, where one polygon as
 * large as the sheet would get GRID^2 at most. Each facet keeps its own
 * point for what x' sees of it and for a fate that is the same for every
 * direction; those whose fate depends on the direction, of one sheet and
 * with their boxes' centres in one of the cube's GRID^3 cells and facing
 * within SHARE_COS of the first of them, take its ray. 0 if out of room. */
static int
share_cells(pm_comp_scratch *sc, double h, pm_comp_stats *z)
{
	double cell = 4 * h * h / (GRID * GRID);
	int cap = 16;

	if (sc->ngr >= INT_MAX / (GRID * GRID * GRID))
		return 1;       /* a key a cell would not fit: each its own */
	while (cap < 2 * sc->ng)
		cap <<= 1;
	if (!pm_grow((void **)&sc->cellt, &sc->celltcap, 0, 2 * cap, sizeof *sc->cellt))
		return 0;
	for (int i = 0; i < cap; i++)
		sc->cellt[2 * i] = -1;
	for (int a = 0; a < sc->ng; a++) {
		cpoly *P = &sc->g[a];
		if (!P->fcast || P->unseen || P->ndyn != 1 || P->ncell != 1 || !sc->gr[P->grp].sheet ||
		    !(P->A < cell))
			continue;
		int key = P->grp;
		for (int k = 0; k < 3; k++)
			key = key * GRID + cube_cell(comp(P->c, k), h);
		unsigned i = (unsigned)key * 2654435761u & (unsigned)(cap - 1);
		while (sc->cellt[2 * i] >= 0 && sc->cellt[2 * i] != key)
			i = (i + 1) & (unsigned)(cap - 1);
		if (sc->cellt[2 * i] < 0) {
			sc->cellt[2 * i] = key;
			sc->cellt[2 * i + 1] = a;
			continue;
		}
		int r = sc->cellt[2 * i + 1];
		if (pm_ddot(sc->g[r].N, P->N) < SHARE_COS)
			continue;
		sc->g[r].share = 1 + r;
		P->share = 1 + r;
		z->shared++;
	}
	return 1;
}

/* How many of P's dynamic points (fates by rays) have fate fx along psi:
 * their rays over P's front list, or through the tree in beams. */
static inline int
ray_hits(pm_comp_scratch *sc, const cpoly *P, pm_dvec3 psi, double h, double eps, int fx)
{
	return P->nfl >= 0 ? front_hits(sc, P, psi, eps, fx) : cast_hits(sc, P, psi, h, eps, fx);
}

/* The area of P (fates by rays) that x' sees and whose backward rays
 * along psi meet what x's does (fate fx): its open area where x's ray is
 * open, and its points of fate fx, a cell each. -1 if out of room. */
static double
cast_area(pm_comp_scratch *sc, const cpoly *P, pm_dvec3 psi, double h, double eps, int fx)
{
	/* The covered points' fates were found once (sample()). */
	int hit = ray_hits(sc, P, psi, h, eps, fx);
	if (sc->oom)
		return -1;
	for (int t = P->s0 + P->ndyn; t < P->s0 + P->ns; t++)
		hit += sc->sf[t] == fx;
	return (fx < 0 ? P->aopen : 0) + (hit > 0 ? hit * (P->A / P->ncell) : 0);
}

/* Psi . Ne for P, with Psi . n in its place on x's plane so that the cosine
 * cancels exactly against (Psi . n) in eq. 2. */
static inline __attribute__((always_inline)) double
facing(const cpoly *P, pm_dvec3 psi, double c, pm_dvec3 n)
{
	if (P->xpar)
		return pm_ddot(P->Ne, n) > 0 ? c : 0;
	double f = pm_ddot(psi, P->Ne);
	return f > 0 ? f : 0; /* 0 for a NaN, as dmax(0, f), in fewer instructions */
}

/* The weight c / A_p of a photon whose target area came to A, or 0 for one
 * with (next to) none (skipped); never spread over less than the floor
 * (compensate.h). thr and fl are SKIP_REL and FLOOR_REL times (2h)^2. The
 * one place both paths decide it. */
static inline double
spread(double A, double c, double thr, double fl, pm_comp_stats *z)
{
	if (!(A > thr * c)) {
		z->skipped++;
		return 0;
	}
	z->floored += A < fl * c;
	return c / dmax(A, fl * c);
}

/* The weights where the cube holds one polygon (most cubes: the middle of
 * a wall or a floor), the general path's answer without its groups, lists
 * and sight boxes, which have nothing to do there: a photon counts when it
 * lies on the polygon's plane on the side it faces (nothing can hide it or
 * change its fate), with the polygon's area as its target area. */
static void
one_polygon(pm_comp_scratch *sc, const pm_vec3 *pos, pm_dvec3 xd, pm_dvec3 nd, double h, double eps,
            double *w, pm_comp_stats *z)
{
	const cpoly *P = &sc->g[0];
	double thr = PM_COMP_SKIP_REL * 4 * h * h, fl = PM_COMP_FLOOR_REL * 4 * h * h;

	for (int j = 0; j < z->front; j++) {
		int i = sc->act[j];
		pm_dvec3 r = pm_dsub(pm_dfromf(pos[i]), xd), psi = sc->psi[j];
		double c = sc->c[j], f, A;
		if (fabs(pm_ddot(P->N, r) - P->d) > eps || !(pm_ddot(psi, P->Ne) > 0)) {
			z->hidden++;
			continue;
		}
		f = facing(P, psi, c, nd);
		A = f > 0 ? f * P->A : 0;
		/* The photon's own spot (an unsampled polygon's share of GRID^2
		 * cells), and the floor, as in the general path. */
		A = dmax(A, f * P->A / (GRID * GRID));
		w[i] = spread(A, c, thr, fl, z);
	}
}

/* The sides of P that the tests need, once it is found: the side that
 * counts (see compensate.h), lying on x's plane; with all, also whether x
 * lies on it, and the rest of what pair_lists() and sample() fill in
 * cleared. */
static void
sides(pm_comp_scratch *sc, cpoly *P, pm_dvec3 xo, pm_dvec3 n, double eps, int all)
{
	double sxo = pm_ddot(P->N, xo) - P->d;

	P->Ne = P->solid || sxo >= 0 ? P->N : pm_dscale(P->N, -1);
	P->de = pm_ddot(P->Ne, P->N) * P->d;
	P->xpar = fabs(pm_ddot(P->N, n)) >= 1 - PARALLEL_EPS && fabs(P->d) <= eps;
	P->aopen = P->A;
	if (!all)
		return;
	P->xon = fabs(P->d) <= eps && inside(sc, P, pm_dv3(0, 0, 0), eps, 1);
	P->unseen = 0;
	P->convex = 0;
	P->nfc = P->ndyn = 0;
	P->adyn = 0;
	P->lit = 0;
}

/* ---- A cube of one sheet, from the polygon index's nodes ----
 *
 * Where the cube holds one sheet that x lies on and x' sees whole (a
 * curved mesh's facets around x, hundreds of them where photons are
 * sparse), the general path's answer is a sum over the facets that face
 * each photon: nothing hides, no fate differs. An index node wholly
 * inside the cube adds its facets' sum of A N at once (pm_bvh_agg), and
 * only the facets the cube's faces cut, and those near x, are clipped
 * one by one. Each condition the general path would find polygon by
 * polygon is shown for a whole node by its box and its cone of normals,
 * with margins past rounding; where one cannot be shown, or the cube is
 * not one sheet, the general path runs. The answers are the general
 * path's up to rounding (sums in another order, areas from the absolute
 * vertices): test_compensate, sheet_nodes_as_polygons_say and
 * sheet_nodes_on_random_bumps. */

/* Nodes taken whole in one cube at most (a cube of a few thousand facets
 * takes tens). */
#define AGG_MAX 512

/* cos(a + t) and cos(a - t) for the angle a with cosine ca and the cone
 * angle t with cosine ct, both in [0, pi]. */
static inline void
cos_sum(double ca, double ct, double *plus, double *minus)
{
	ca = ca > 1 ? 1 : ca < -1 ? -1 : ca;
	ct = ct > 1 ? 1 : ct < -1 ? -1 : ct;
	double sa = sqrt(1 - ca * ca), st = sqrt(1 - ct * ct);
	/* a + t >= pi where cos a <= cos(pi - t); a <= t where cos a >= cos t. */
	*plus = ca <= -ct ? -1 : ca * ct - sa * st;
	*minus = ca >= ct ? 1 : ca * ct + sa * st;
}

/* Node box relative to x (lo xyz, hi xyz). */
static inline void
node_rel(const pm_bvh_node *nd, pm_dvec3 x, double b[6])
{
	double c[3] = {x.x, x.y, x.z};
	for (int k = 0; k < 3; k++) {
		b[k] = (double)nd->lo[k] - c[k];
		b[3 + k] = (double)nd->hi[k] - c[k];
	}
}

/* The least and the largest of M . v over box b. */
static inline void
box_dot(const double b[6], pm_dvec3 M, double *lo, double *hi)
{
	double m[3] = {M.x, M.y, M.z}, l = 0, u = 0;
	for (int k = 0; k < 3; k++) {
		double p = m[k] * b[k], q = m[k] * b[3 + k];
		l += p < q ? p : q;
		u += p > q ? p : q;
	}
	*lo = l;
	*hi = u;
}

/* 1 if every facet under the node (box b, cone A) has x' on its front by
 * more than m: N . (x' - v) for v in the box and N in the cone is at
 * least M . (x' - v) - |N - M| |x' - v|. */
static int
node_front(const double b[6], const pm_bvh_agg *A, pm_dvec3 xo, double m)
{
	double lo, hi, w2 = 0, o[3] = {xo.x, xo.y, xo.z};
	box_dot(b, A->M, &lo, &hi);
	for (int k = 0; k < 3; k++) {
		double p = o[k] - b[k], q = o[k] - b[3 + k];
		w2 += p * p > q * q ? p * p : q * q;
	}
	return pm_ddot(A->M, xo) - hi - sqrt(dmax(0, 2 - 2 * A->cmin)) * sqrt(w2) > m;
}

/* Whether node id can be taken whole in this cube: wholly inside it (and
 * off the open cube's face slabs: box in), away from x (no facet x lies
 * on: box near), one patch and one object, no facet parallel to n (x's
 * plane). in and near are float boxes rounded inward and outward, so the
 * tests on the node's float box are conservative. */
static int
node_whole(const pm_polyindex *pi, uint32_t id, const float in[6], const float near[6], pm_dvec3 n)
{
	const pm_bvh_node *nd = &pi->node[id];
	const pm_bvh_agg *A;
	double cp, cm;

	if (!(nd->lo[0] > in[0] && nd->lo[1] > in[1] && nd->lo[2] > in[2] &&
	      nd->hi[0] < in[3] && nd->hi[1] < in[4] && nd->hi[2] < in[5]) ||
	    pm_polyindex_overlaps(nd->lo, nd->hi, near))
		return 0;
	A = &pi->agg[id];
	if (A->patch == PM_AGG_MIXED || A->obj < 0 || A->count < 2 || A->cmin < -1)
		return 0;
	cos_sum(fabs(pm_ddot(A->M, n)), A->cmin, &cp, &cm);
	return cm < 1 - 2 * PARALLEL_EPS;
}

/* The float boxes node_whole() tests against: the cube less the open
 * cube's margin, rounded in, and x's neighbourhood of 2 eps, rounded out.
 * A move of 2^-22 of the value before rounding to float outweighs the
 * rounding (at most 2^-24 of it). */
static void
whole_boxes(const visit_ctx *q, double eps, float in[6], float near[6])
{
	double c[3] = {q->x.x, q->x.y, q->x.z}, m = q->h - (q->open ? 0.5 * q->tau : 0);

	for (int k = 0; k < 3; k++) {
		double a = c[k] - m, b = c[k] + m, u = c[k] - 2 * eps, v = c[k] + 2 * eps;
		in[k] = (float)(a + fabs(a) * 0x1p-22);
		in[3 + k] = (float)(b - fabs(b) * 0x1p-22);
		near[k] = (float)(u - fabs(u) * 0x1p-22);
		near[3 + k] = (float)(v + fabs(v) * 0x1p-22);
	}
}

/* Clips into sc->g the entries under node id0 that meet box, in the
 * order pm_polyindex_cube() visits them; -1 out of room. */
static int
clip_node(pm_comp_scratch *sc, visit_ctx *q, int id0, const float box[6])
{
	const pm_polyindex *pi = q->pi;
	uint32_t stack[80];
	int top = 0;

	if (pm_polyindex_overlaps(pi->node[id0].lo, pi->node[id0].hi, box))
		stack[top++] = (uint32_t)id0;
	while (top > 0) {
		const pm_bvh_node *nd = &pi->node[stack[--top]];
		if (nd->n > 0) {
			for (uint32_t i = nd->a; i < nd->a + nd->n; i++)
				if (pm_polyindex_overlaps(pi->box[i], pi->box[i] + 3, box))
					visit(q, pi->prim[i]);
			if (sc->oom)
				return -1;
			continue;
		}
		if (top + 2 > (int)(sizeof stack / sizeof *stack))
			return -1;
		uint32_t l = (uint32_t)(nd - pi->node) + 1;
		if (pm_polyindex_overlaps(pi->node[nd->a].lo, pi->node[nd->a].hi, box))
			stack[top++] = nd->a;
		if (pm_polyindex_overlaps(pi->node[l].lo, pi->node[l].hi, box))
			stack[top++] = l;
	}
	return 0;
}

/* 0 if the nodes agg[] and the entries ent[] together bend past
 * SHEET_COS from their mean normal (whole polygons' areas; sheet_nodes()
 * asks again of what the cube clips): the cube is then no one sheet,
 * known before anything is clipped. */
static int
one_cone(const pm_polyindex *pi, const int *agg, int nagg, const int *ent, int ne)
{
	pm_dvec3 M = pm_dv3(0, 0, 0);
	double l, cp, cm;

	for (int i = 0; i < nagg; i++)
		M = pm_dadd(M, pi->agg[agg[i]].V);
	for (int i = 0; i < ne; i++)
		M = pm_dadd(M, pm_dscale(pi->pn[ent[i]], pi->pa[ent[i]]));
	l = pm_dlen(M);
	if (!(l > 0) || !isfinite(l))
		return 0;
	M = pm_dscale(M, 1 / l);
	for (int i = 0; i < nagg; i++) {
		cos_sum(pm_ddot(M, pi->agg[agg[i]].M), pi->agg[agg[i]].cmin, &cp, &cm);
		if (cp < SHEET_COS)
			return 0;
	}
	for (int i = 0; i < ne; i++)
		if (pm_ddot(M, pi->pn[ent[i]]) < SHEET_COS)
			return 0;
	return 1;
}

/* The cube's polygons: nodes taken whole into agg[], the rest clipped
 * into sc->g by visit(), as long as they are of one patch. Where a second
 * patch shows, no more nodes are taken, and those taken are clipped too,
 * each where the walk met it (at[]), so that sc->g is what
 * pm_polyindex_cube() finds; so too where the patch bends too far
 * (one_cone()). The walk lists the entries to clip (in
 * sc->bl) before clipping any. 1 for one patch, 2 where no node is left
 * whole (sc->g is complete), 0 where there are too many nodes, -1 out of
 * room. */
static int
sheet_walk(pm_comp_scratch *sc, visit_ctx *q, pm_dvec3 n, double eps, int *agg, int *nagg)
{
	const pm_polyindex *pi = q->pi;
	uint32_t stack[80], patch = PM_AGG_MIXED;
	int top = 0, mixed = 0, ne = 0, at[AGG_MAX];
	float box[6], in[6], near[6];

	*nagg = 0;
	pm_polyindex_query_box(q->x, q->h, box);
	whole_boxes(q, eps, in, near);
	if (!pm_polyindex_overlaps(pi->node[0].lo, pi->node[0].hi, box))
		return 2;
	/* Children are tested before they are pushed, left before right, as
	 * pm_polyindex_cube() does. */
	stack[top++] = 0;
	while (top > 0) {
		uint32_t id = stack[--top];
		for (;;) {
			const pm_bvh_node *nd = &pi->node[id];
			if (!mixed && node_whole(pi, id, in, near, n)) {
				uint32_t p = pi->agg[id].patch;
				mixed = patch != PM_AGG_MIXED && p != patch;
				if (!mixed) {
					if (*nagg == AGG_MAX)
						return 0;
					patch = p;
					at[*nagg] = ne;
					agg[(*nagg)++] = (int)id;
					break;
				}
			}
			if (nd->n > 0) {
				if (!pm_grow((void **)&sc->bl, &sc->blcap, ne, (int)nd->n, sizeof *sc->bl))
					return -1;
				for (uint32_t i = nd->a; i < nd->a + nd->n; i++) {
					if (!pm_polyindex_overlaps(pi->box[i], pi->box[i] + 3, box))
						continue;
					sc->bl[ne++] = (int)i;
					uint32_t p = pi->patch[pi->prim[i]];
					mixed |= patch != PM_AGG_MIXED && p != patch;
					patch = p;
				}
				break;
			}
			int hl = pm_polyindex_overlaps(nd[1].lo, nd[1].hi, box),
			    hr = pm_polyindex_overlaps(pi->node[nd->a].lo, pi->node[nd->a].hi, box);
			if (hl && hr) {
				if (top + 1 > (int)(sizeof stack / sizeof *stack))
					return -1;
				stack[top++] = nd->a;
			}
			if (hl)
				id = id + 1;
			else if (hr)
				id = nd->a;
			else
				break;
		}
	}
	mixed |= *nagg > 0 && !one_cone(pi, agg, *nagg, sc->bl, ne);
	for (int k = 0, a = 0; k <= ne; k++) {
		for (; mixed && a < *nagg && at[a] == k; a++)
			if (clip_node(sc, q, agg[a], box) < 0)
				return -1;
		if (k < ne)
			visit(q, pi->prim[sc->bl[k]]);
		if (sc->oom)
			return -1;
	}
	if (mixed)
		*nagg = 0;
	return *nagg == 0 ? 2 : 1;
}

/* Sum of max(0, psi . N) A over the facets under node id: a node whose
 * cone faces psi whole adds its V, one turned away nothing. */
static double
facing_nodes(const pm_polyindex *pi, int id0, pm_dvec3 psi)
{
	uint32_t stack[80];
	int top = 0;
	double A = 0;

	stack[top++] = (uint32_t)id0;
	while (top > 0) {
		uint32_t id = stack[--top];
		const pm_bvh_node *nd = &pi->node[id];
		const pm_bvh_agg *G = &pi->agg[id];
		double cp, cm;
		cos_sum(pm_ddot(psi, G->M), G->cmin, &cp, &cm);
		if (G->cmin >= -1 && cp > 1e-12) {
			A += pm_ddot(psi, G->V);
			continue;
		}
		if (G->cmin >= -1 && cm < -1e-12)
			continue;
		if (nd->n > 0) {
			for (uint32_t i = nd->a; i < nd->a + nd->n; i++)
				A += dmax(0, pm_ddot(psi, pi->pn[i])) * pi->pa[i];
			continue;
		}
		if (top + 2 > (int)(sizeof stack / sizeof *stack))
			break;
		stack[top++] = nd->a;
		stack[top++] = id + 1;
	}
	return A;
}

/* Clips into sc->g the facets under node id0 whose boxes meet box (a
 * photon's, grown by the tolerance of its planes), unseen as their node;
 * -1 out of room. */
static int
nodes_at(pm_comp_scratch *sc, visit_ctx *q, int id0, int unseen, const float box[6])
{
	int ng = sc->ng;

	if (clip_node(sc, q, id0, box) < 0)
		return -1;
	for (int a = ng; a < sc->ng; a++)
		sc->g[a].unseen = unseen;
	return 0;
}

/* A node taken whole: what x' sees of its facets, as pair_lists() would
 * say facet by facet (a solid's back is hidden unless x lies on the solid
 * and the facet turns less than SMOOTH_COS from n; a facet of another
 * body's back counts on its back): NODE_SEEN, NODE_UNSEEN, NODE_SPLIT
 * where its box and cone cannot tell, NODE_FLIPPED where every facet
 * counts on its back (the cube is then not one sheet). */
enum { NODE_SEEN, NODE_UNSEEN, NODE_SPLIT, NODE_FLIPPED };

static int
node_sight(const pm_polyindex *pi, int id, const visit_ctx *q, pm_dvec3 n, pm_dvec3 xo, double eps,
           const int *xobj, int nxobj)
{
	const pm_bvh_agg *A = &pi->agg[id];
	int solid = pi->s->objs[A->obj].solid, ownall = nxobj == 4, ownnone = 1;
	double b[6], cp, cm, m = 1e-10 * q->h;

	node_rel(&pi->node[id], q->x, b);
	cos_sum(pm_ddot(A->M, n), A->cmin, &cp, &cm);
	for (int k = 0; k < nxobj && !ownall; k++)
		if (xobj[k] == A->obj) {
			ownall = cp >= SMOOTH_COS + 1e-12;
			ownnone = cm < SMOOTH_COS - 1e-12;
		}
	if (!solid) {
		if (node_front(b, A, xo, m))
			return NODE_SEEN;
		pm_bvh_agg back = *A;
		back.M = pm_dscale(A->M, -1);
		return node_front(b, &back, xo, m) ? NODE_FLIPPED : NODE_SPLIT;
	}
	if (ownall || node_front(b, A, xo, m - eps))
		return NODE_SEEN;
	/* Every facet behind x' by more than eps: N . (x' - v) <= M . (x' -
	 * v) + |N - M| |x' - v| < -eps, i.e. -N in the flipped cone fronts
	 * x' by more than eps. */
	pm_bvh_agg back = *A;
	back.M = pm_dscale(A->M, -1);
	if (ownnone && node_front(b, &back, xo, eps + m))
		return NODE_UNSEEN;
	return NODE_SPLIT;
}

/* The weights where the cube is one sheet that x lies on, from index
 * nodes where it can be shown (see above): 1 if done (w written, or left
 * at 0 out of room); else the general path must run, 2 with sc->g
 * holding the cube's polygons as pm_polyindex_cube() would have found
 * them, 0 with a part of them. */
static int
sheet_nodes(pm_comp_scratch *sc, visit_ctx *q, const pm_vec3 *pos, pm_dvec3 n, pm_dvec3 xo, double eps,
            double *w, pm_comp_stats *z)
{
	const pm_polyindex *pi = q->pi;
	int agg[AGG_MAX], nagg, unseen[AGG_MAX], xobj[4], nxobj = 0, np = 0, r, simple = 1;
	double h = q->h;

	/* 2, no node whole: sc->g holds every polygon of the cube, in the
	 * order pm_polyindex_cube() gives them (left before right, entries in
	 * order), for the general path. */
	if ((r = sheet_walk(sc, q, n, eps, agg, &nagg)) != 1)
		return r < 0 ? 1 : r;
	/* x lies on one of the polygons clipped one by one (nodes near x are
	 * not taken whole). */
	for (int a = 0; a < sc->ng; a++) {
		cpoly *P = &sc->g[a];
		sides(sc, P, xo, n, eps, 1);
		if (P->xon && nxobj < 4)
			xobj[nxobj++] = P->obj;
	}
	if (nxobj == 0)
		return 0;
	/* What x' sees of each node; a node that cannot tell gives way to its
	 * children, or its facets one by one. */
	for (int i = 0; i < nagg;) {
		int id = agg[i], v = node_sight(pi, id, q, n, xo, eps, xobj, nxobj);
		const pm_bvh_node *nd = &pi->node[id];
		if (v == NODE_FLIPPED)
			return 0;
		if (v != NODE_SPLIT) {
			unseen[i++] = v == NODE_UNSEEN;
			continue;
		}
		agg[i] = agg[--nagg];
		if (nd->n > 0) {
			for (uint32_t e = nd->a; e < nd->a + nd->n; e++) {
				int ng = sc->ng;
				visit(q, pi->prim[e]);
				if (sc->oom)
					return 1;
				if (sc->ng > ng)
					sides(sc, &sc->g[ng], xo, n, eps, 1);
			}
			continue;
		}
		if (nagg + 2 > AGG_MAX)
			return 0;
		agg[nagg++] = (int)nd->a;
		agg[nagg++] = id + 1;
	}
	/* The polygons one by one: on their fronts' side (a patch's facets
	 * that count on their backs are another group), hidden as
	 * pair_lists() says for one sheet. */
	for (int a = 0; a < sc->ng; a++) {
		cpoly *P = &sc->g[a];
		int own = nxobj == 4;
		if (pm_ddot(P->Ne, P->N) < 0)
			return 0;
		for (int b = 0; b < nxobj && !own; b++)
			own = xobj[b] == P->obj && pm_ddot(P->N, n) >= SMOOTH_COS;
		P->unseen = P->solid && !own && pm_ddot(P->N, xo) - P->d < -eps;
		simple &= !P->unseen;
	}
	/* Sums over what x' sees (V, apar) and over all (M: groups() takes
	 * the mean over every polygon). */
	pm_dvec3 V = pm_dv3(0, 0, 0), M = pm_dv3(0, 0, 0);
	double apar = 0, slo = INFINITY, shi = -INFINITY, cmin = 1, b[6];
	for (int i = 0; i < nagg; i++) {
		const pm_bvh_agg *A = &pi->agg[agg[i]];
		if (!unseen[i])
			V = pm_dadd(V, A->V);
		M = pm_dadd(M, A->V);
		simple &= !unseen[i];
		np += (int)A->count;
	}
	for (int a = 0; a < sc->ng; a++) {
		const cpoly *P = &sc->g[a];
		pm_dvec3 s = pm_dscale(P->Ne, P->A);
		M = pm_dadd(M, s);
		if (P->unseen)
			;
		else if (P->xpar)
			apar += pm_ddot(P->Ne, n) > 0 ? P->A : 0;
		else
			V = pm_dadd(V, s);
	}
	np += sc->ng;
	double l = pm_dlen(M);
	if (!(l > 0) || !isfinite(l) || np < 2)
		return 0;
	M = pm_dscale(M, 1 / l);
	/* A cone around M that holds every facet, and the sheet's slab. */
	for (int i = 0; i < nagg; i++) {
		const pm_bvh_agg *A = &pi->agg[agg[i]];
		double cp, cm, lo, hi;
		cos_sum(pm_ddot(M, A->M), A->cmin, &cp, &cm);
		cmin = dmin(cmin, cp - 1e-12);
		node_rel(&pi->node[agg[i]], q->x, b);
		box_dot(b, M, &lo, &hi);
		slo = dmin(slo, lo);
		shi = dmax(shi, hi);
	}
	for (int a = 0; a < sc->ng; a++) {
		const cpoly *P = &sc->g[a];
		cmin = dmin(cmin, pm_ddot(P->Ne, M) - 1e-12);
		for (int v = 0; v < P->nv; v++) {
			double m = pm_ddot(M, sc->cv[P->v0 + v]);
			slo = dmin(slo, m);
			shi = dmax(shi, m);
		}
	}
	if (!(cmin >= SHEET_COS))
		return 0;

	/* Each photon as the general path takes it on one sheet: at once
	 * where the sheet is simple and faces it whole, else on the facet
	 * that holds it (none, or one x' does not see: not counted). */
	double sina = sqrt(1 - cmin * cmin);
	double thr = PM_COMP_SKIP_REL * 4 * h * h, fl = PM_COMP_FLOOR_REL * 4 * h * h;
	int nind = sc->ng, ncv = sc->ncv;
	z->polys = np;
	z->groups = 1;
	z->nodes = nagg;
	for (int j = 0; j < z->front; j++) {
		int i = sc->act[j], own = -1, nplane = 0, whole;
		pm_dvec3 r = pm_dsub(pm_dfromf(pos[i]), q->x), psi = sc->psi[j];
		double c = sc->c[j], A, m = pm_ddot(M, r);
		if (m < slo - eps || m > shi + eps) {
			z->hidden++;
			continue;
		}
		whole = pm_ddot(psi, M) > sina + 1e-9;
		if (simple && whole) {
			w[i] = spread(c * apar + pm_ddot(psi, V), c, thr, fl, z);
			continue;
		}
		/* The planes and boxes that hold it: of the polygons clipped,
		 * and of the facets of the nodes whose boxes hold it, clipped
		 * for it. */
		float box[6];
		pm_polyindex_query_box(pm_dadd(q->x, r), eps, box); /* once: it costs a hundred instructions */
		for (int k = 0; k < nagg; k++)
			if (nodes_at(sc, q, agg[k], unseen[k], box) < 0)
				return 1;
		if (!pm_grow((void **)&sc->held, &sc->heldcap, 0, sc->ng, sizeof *sc->held))
			return 1;
		for (int a = 0; a < sc->ng; a++) {
			cpoly *P = &sc->g[a];
			if (a >= nind)
				sides(sc, P, xo, n, eps, 0);
			if (fabs(pm_ddot(P->N, r) - P->d) <= eps && in_box(P, r, eps))
				sc->held[nplane++] = a;
		}
		if (nplane == 1)
			own = pm_ddot(psi, sc->g[sc->held[0]].Ne) > 0 ? sc->held[0] : -1;
		for (int t = 0; nplane > 1 && t < nplane; t++) {
			const cpoly *P = &sc->g[sc->held[t]];
			if (pm_ddot(psi, P->Ne) > 0 && (own < 0 || P->g < sc->g[own].g) && inside(sc, P, r, eps, 1))
				own = sc->held[t];
		}
		if (own < 0 || sc->g[own].unseen) {
			z->hidden++;
			sc->ng = nind;
			sc->ncv = ncv;
			continue;
		}
		if (whole)
			A = c * apar + pm_ddot(psi, V);
		else {
			A = 0;
			for (int a = 0; a < nind; a++) {
				double f = facing(&sc->g[a], psi, c, n);
				A += f > 0 && !sc->g[a].unseen ? f * sc->g[a].A : 0;
			}
			for (int k = 0; k < nagg; k++)
				A += unseen[k] ? 0 : facing_nodes(pi, agg[k], psi);
		}
		const cpoly *O = &sc->g[own];
		A = dmax(A, facing(O, psi, c, n) * O->A / (GRID * GRID));
		w[i] = spread(A, c, thr, fl, z);
		sc->ng = nind;
		sc->ncv = ncv;
	}
	return 1;
}

/* Past this many polygons the photons' loop finds a photon's polygons
 * among those of its cell of the cube's GRID^3 cells (cube_cell()), not among all
 * the planes of its groups (each photon testing every one cost meshroom
 * 1.3 % more instructions, grid built included). */
#define PGRID_FROM 48
#define PGRID_PER 16

/* sc->pgc and sc->pgl: the polygons by cell, each box grown by eps (the
 * tolerance of in_box()). 1 if built; 0 where the polygons are so large
 * that the lists would pass PGRID_PER entries a polygon (the loop then
 * tests every plane); -1 out of room. */
static int
poly_grid(pm_comp_scratch *sc, double h, double eps)
{
	int lo[3], hi[3], n = 0, *c;

	if (!pm_grow((void **)&sc->pgc, &sc->pgccap, 0, GRID * GRID * GRID + 1, sizeof *sc->pgc))
		return -1;
	c = sc->pgc;
	for (int i = 0; i <= GRID * GRID * GRID; i++)
		c[i] = 0;
	for (int pass = 0; pass < 2; pass++) {
		for (int a = 0; a < sc->ng; a++) {
			const cpoly *P = &sc->g[a];
			for (int k = 0; k < 3; k++) {
				lo[k] = cube_cell(P->lo[k] - eps, h);
				hi[k] = cube_cell(P->hi[k] + eps, h);
			}
			for (int i = lo[0]; i <= hi[0]; i++)
				for (int j = lo[1]; j <= hi[1]; j++)
					for (int k = lo[2]; k <= hi[2]; k++) {
						int cell = (i * GRID + j) * GRID + k;
						if (pass == 0)
							c[cell + 1]++;
						else
							sc->pgl[c[cell]++] = a;
					}
		}
		if (pass == 0) {
			for (int i = 0; i < GRID * GRID * GRID; i++)
				c[i + 1] += c[i];
			n = c[GRID * GRID * GRID];
			if (n > PGRID_PER * sc->ng)
				return 0;
			if (!pm_grow((void **)&sc->pgl, &sc->pglcap, 0, n, sizeof *sc->pgl))
				return -1;
		}
	}
	/* The fill moved each cell's start to the next one's: back by one. */
	for (int i = GRID * GRID * GRID; i > 0; i--)
		c[i] = c[i - 1];
	c[0] = 0;
	return 1;
}

/* pm_comp_weights, or with hfix > 0 (pm_comp_weights_cube) the open cube
 * of that half-size. */
static void
weights(const pm_polyindex *pi, pm_vec3 x, pm_vec3 n,
        const pm_vec3 *pos, const pm_vec3 *dir, int m,
        int complete, double hfix, pm_comp_scratch *sc, double *w,
        pm_comp_stats *st)
{
	pm_comp_stats z = {0};
	visit_ctx q = {0};
	pm_dvec3 xd = pm_dfromf(x), nd = pm_dfromf(n), xo;
	double hk = 0, hs, h, tau, len = pm_dlen(nd), eps, mx;
	int valid = 0, inner = 0, na = 0, xf0 = 0, nxf = 0;

	if (m > sc->k)
		m = sc->k;
	for (int i = 0; i < m; i++)
		w[i] = 0;
	z.found = m > 0 ? m : 0;
	if (m <= 0 || !pi || !pm_vfinite(x) || !(len > 0) || !isfinite(len))
		goto out;
	nd = pm_dscale(nd, 1 / len);

	/* L-infinity distances, exact in double (a difference of floats). The
	 * loop has no branches: which axis is largest is a coin toss per
	 * photon, and as branches these maxima were a fifth of this function's
	 * time on the room. The sum is finite exactly where every axis is: a
	 * photon with a coordinate not finite is not used (dmax() passed over
	 * a NaN axis; no map holds one: photonfile.c refuses it). */
	for (int i = 0; i < m; i++) {
		double ax = fabs((double)pos[i].x - xd.x), ay = fabs((double)pos[i].y - xd.y),
		       az = fabs((double)pos[i].z - xd.z);
		double d = ax > ay ? ax : ay;
		int ok = isfinite(ax + ay + az);
		d = d > az ? d : az;
		d = ok ? d : -1;                    /* -1: not used */
		sc->d[i] = d;
		hk = hk > d ? hk : d;
		valid += ok;
	}
	if (valid == 0)
		goto out;

	/* The boundary shell: the photons at the largest distance, chained down
	 * through gaps of at most tau. Every photon nearer than the shell is
	 * certainly in the set; those in it may be only some of their kind. */
	tau = PM_COMP_TAU_REL * (hfix > 0 ? hfix : hk);
	hs = hfix > 0 ? hfix : hk;
	if (hfix > 0) {
		for (int i = 0; i < m; i++)
			inner += sc->d[i] >= 0 && sc->d[i] < hs;
	} else if (!complete) {
		for (;;) {
			double lo = hs - tau, nm = hs;
			for (int i = 0; i < m; i++) {
				double d = sc->d[i] >= lo ? sc->d[i] : hs;
				nm = d < nm ? d : nm;
			}
			if (nm == hs)
				break;
			hs = nm;
		}
		for (int i = 0; i < m; i++)
			inner += sc->d[i] >= 0 && sc->d[i] < hs;
	}
	if (hfix <= 0 && (complete || inner == 0)) {
		z.closed = 1;
		h = dmax(hk + tau, PM_COMP_HMIN_REL * pi->extent);
	} else {
		h = hs;
		z.shell = valid - inner;
	}
	z.h = h;
	if (!(h > 0) || !isfinite(h))
		goto out;

	/* Photons used that arrive in front of n; the others add nothing. Each
	 * is written to the next slot and kept by counting it (no branch on
	 * which way it arrives: near a corner that is a coin toss too). A
	 * zero or infinite direction makes NaNs here, in a slot not kept. */
	for (int i = 0; i < m; i++) {
		pm_dvec3 p = pm_dfromf(dir[i]);
		double l = pm_dlen(p);
		p = pm_dscale(p, 1 / l);
		double c = pm_ddot(p, nd);
		int use = (sc->d[i] >= 0) & (z.closed | (sc->d[i] < hs)) & (l > 0) & (l <= DBL_MAX) & (c > 0);
		sc->act[na] = i;
		sc->psi[na] = p;
		sc->c[na] = c;
		na += use;
	}
	z.front = na;
	if (na == 0)
		goto out;

	/* Beyond float rounding of the vertices, which grows with |x|. */
	mx = dmax(fabs(xd.x), dmax(fabs(xd.y), fabs(xd.z)));
	eps = 1e-4 * h + 8 * FLT_EPSILON * mx;
	xo = pm_dscale(nd, dmax(XOFF_REL * h, 4 * eps));

	/* The polygons in the cube: where they are one sheet, from the
	 * index's nodes (sheet_nodes()), else one by one. */
	sc->ng = sc->ncv = sc->nsp = sc->nbl = sc->nfl = 0;
	sc->oom = 0;
	q.sc = sc;
	q.pi = pi;
	q.x = xd;
	q.h = h;
	q.tau = tau;
	q.open = !z.closed;
	int found = 0;
	if (pm_comp_sheet_nodes && pi->agg) {
		found = sheet_nodes(sc, &q, pos, nd, xo, eps, w, &z);
		if (found == 1)
			goto out;
		if (found == 0)
			sc->ng = sc->ncv = 0;
	}
	if (!found)
		pm_polyindex_cube(pi, xd, h, visit, &q);
	z.polys = sc->ng;
	if (sc->oom)
		goto out;
	if (!pm_grow((void **)&sc->sg, &sc->sgcap, 0, sc->ng, sizeof *sc->sg))
		goto out;

	for (int a = 0; a < sc->ng; a++)
		sides(sc, &sc->g[a], xo, nd, eps, sc->ng > 1);
	z.groups = sc->ng;
	if (sc->ng == 1) {
		one_polygon(sc, pos, xd, nd, h, eps, w, &z);
		goto out;
	}
	if (!groups(sc, pi->patch, nd))
		goto out;
	z.groups = sc->ngr;
	sc->fcast = sc->ngr >= 2 && sc->ng >= pm_comp_fate_cast_from;
	if (sc->fcast && !cast_prepare(sc))
		goto out;
	/* What the pair tests need (none, where one sheet is all there is). */
	for (int a = 0; a < sc->ng && !one_sheet(sc); a++) {
		cpoly *P = &sc->g[a];
		P->convex = pm_poly_convex(sc->cv + P->v0, P->nv, P->N);
		/* 2 eps: a crossing within eps of B counts (seen()), and a
		 * photon lies within eps of its polygon. */
		pm_sight_box(sc->cv + P->v0, P->nv, xo, 2 * eps, sc->ng >= SIGHT_ACROSS, &sc->sg[a]);
		for (int j = 0; j < na && !P->lit; j++)
			P->lit = facing(P, sc->psi[j], sc->c[j], nd) > 0;
	}
	if (sc->ng > 1) {
		if (!pair_lists(sc, pi->convex, xo, nd, eps, &xf0, &nxf))
			goto out;
		z.whole = sc->nwhole;
		for (int a = 0; a < sc->ng; a++)
			if (sc->g[a].unseen)
				sc->g[a].aopen = 0;
			else if (sc->g[a].nr > 0 || sc->g[a].nf > 0 || sc->g[a].fcast) {
				if (!sample(sc, &sc->g[a], xo, h, eps))
					goto out;
				z.sampled++;
				z.cells += sc->g[a].ncell;
				z.cast += sc->g[a].cast;
				z.fcast += sc->g[a].fcast;
			}
		if (sc->fcast && pm_comp_share_cells && !share_cells(sc, h, &z))
			goto out;
		/* A front list serves rays from P's points whose fate depends on
		 * the direction: none without such points, or where they take
		 * another facet's rays. */
		for (int a = 0; a < sc->ng; a++) {
			cpoly *P = &sc->g[a];
			if (P->fcast && !P->unseen && P->ndyn > 0 && (P->share == 0 || P->share - 1 == a) &&
			    !front_list(sc, P, eps))
				goto out;
		}
	}
	if (!pm_grow((void **)&sc->gq, &sc->gqcap, 0, sc->ng, sizeof *sc->gq) ||
	    !pm_grow((void **)&sc->gapat, &sc->gapatcap, 0, sc->nbl, sizeof *sc->gapat) ||
	    !pm_grow((void **)&sc->shat, &sc->shatcap, 0, sc->nbl, sizeof *sc->shat))
		goto out;
	for (int e = 0; e < sc->nbl; e++)
		sc->gapat[e] = sc->shat[e] = -1;
	sc->ngap = sc->nsh = 0;
	for (int G = 0, nq = 0; G < sc->ngr; G++) {
		cgroup *Gr = &sc->gr[G];
		Gr->simple = Gr->sheet;
		for (int gi = Gr->p0; gi < Gr->p0 + Gr->np && Gr->simple; gi++) {
			const cpoly *P = &sc->g[sc->gp[gi]];
			Gr->simple = !P->unseen && P->nr == 0 && P->nf == 0 && !P->fcast;
		}
		Gr->Vp = pm_dv3(0, 0, 0);
		Gr->aparp = 0;
		Gr->q0 = nq;
		for (int gi = Gr->p0; gi < Gr->p0 + Gr->np && Gr->sheet && !Gr->simple; gi++) {
			const cpoly *P = &sc->g[sc->gp[gi]];
			if (P->unseen || P->nr > 0 || P->nf > 0 || P->fcast)
				sc->gq[nq++] = sc->gp[gi];
			else if (P->xpar)
				Gr->aparp += pm_ddot(P->Ne, nd) > 0 ? P->A : 0;
			else
				Gr->Vp = pm_dadd(Gr->Vp, pm_dscale(P->Ne, P->A));
		}
		Gr->nq = nq - Gr->q0;
	}

	/* Which photons count: each lies on a polygon of the cube, on the side
	 * that faces its light and x', where x' sees it, and its backward ray
	 * meets what x's does. */
	int pgrid = pm_comp_photon_grid && sc->ng >= PGRID_FROM ? poly_grid(sc, h, eps) : 0;
	if (pgrid < 0)
		goto out;
	if (pgrid) {
		if (!pm_grow((void **)&sc->gmark, &sc->gmarkcap, 0, sc->ngr, 1))
			goto out;
		for (int G = 0; G < sc->ngr; G++)
			sc->gmark[G] = 0;
	}
	for (int j = 0; j < na; j++) {
		int i = sc->act[j], own = -1, fy, nm = 0;
		pm_dvec3 r = pm_dsub(pm_dfromf(pos[i]), xd), psi = sc->psi[j];
		sc->own[j] = -1;
		/* The groups that may hold it: a sheet by its slab, a polygon by
		 * its plane. */
		for (int G = 0; G < sc->ngr; G++) {
			const cgroup *Gr = &sc->gr[G];
			if (Gr->sheet) {
				double m = pm_ddot(Gr->M, r);
				if (m < Gr->slo - eps || m > Gr->shi + eps)
					continue;
			} else {
				const cpoly *P = &sc->g[sc->gp[Gr->p0]];
				if (fabs(pm_ddot(P->N, r) - P->d) > eps)
					continue;
			}
			sc->gm[nm++] = G;
		}
		/* On one sheet whose every polygon is seen whole with open
		 * fates, facing all of them: which one holds it does not matter. */
		if (nm == 1 && sc->gr[sc->gm[0]].simple &&
		    pm_ddot(psi, sc->gr[sc->gm[0]].M) > sc->gr[sc->gm[0]].sina + 1e-9) {
			sc->fx[j] = fate(sc, sc->bl + xf0, nxf, pm_dv3(0, 0, 0), psi, eps);
			if (sc->fx[j] != -1)
				z.hidden++;
			else
				sc->own[j] = -2 - sc->gm[0];
			continue;
		}
		/* A photon in the cube lies on one of its polygons: of those
		 * whose planes and boxes hold it, where only one does, that one
		 * (no inside test needed). Where there is a grid, they are
		 * among its cell's. */
		int nplane = 0, *held = sc->held;
		if (pgrid) {
			int cell = (cube_cell(r.x, h) * GRID + cube_cell(r.y, h)) * GRID + cube_cell(r.z, h);
			for (int k = 0; k < nm; k++)
				sc->gmark[sc->gm[k]] = 1;
			for (int t = sc->pgc[cell]; t < sc->pgc[cell + 1]; t++) {
				const cpoly *P = &sc->g[sc->pgl[t]];
				if (sc->gmark[P->grp] && fabs(pm_ddot(P->N, r) - P->d) <= eps && in_box(P, r, eps))
					held[nplane++] = sc->pgl[t];
			}
			for (int k = 0; k < nm; k++)
				sc->gmark[sc->gm[k]] = 0;
		} else
			for (int k = 0; k < nm; k++) {
				const cgroup *Gr = &sc->gr[sc->gm[k]];
				for (int gi = Gr->p0; gi < Gr->p0 + Gr->np; gi++) {
					const cpoly *P = &sc->g[sc->gp[gi]];
					if (fabs(pm_ddot(P->N, r) - P->d) > eps || !in_box(P, r, eps))
						continue;
					held[nplane++] = sc->gp[gi];
				}
			}
		if (nplane == 1)
			own = pm_ddot(psi, sc->g[held[0]].Ne) > 0 ? held[0] : -1;
		/* Where several do (an edge; the same surface twice; the two
		 * triangles of a mesh's quad), the lowest polygon number that
		 * faces it and holds it: the one the target area keeps of a
		 * surface given twice. Those are all among the planes found,
		 * whose test is not asked again. */
		for (int t = 0; nplane > 1 && t < nplane; t++) {
			const cpoly *P = &sc->g[held[t]];
			if (pm_ddot(psi, P->Ne) > 0 && (own < 0 || P->g < sc->g[own].g) && inside(sc, P, r, eps, 1))
				own = held[t];
		}
		if (own < 0) {
			z.hidden++;
			continue;
		}
		const cpoly *P = &sc->g[own];
		if (P->unseen) {
			z.hidden++;
			continue;
		}
		sc->fx[j] = fate(sc, sc->bl + xf0, nxf, pm_dv3(0, 0, 0), psi, eps);
		fy = P->fcast ? cast_fate(sc, P, r, psi, h, eps, 1) : fate(sc, sc->bl + P->f0, P->nf, r, psi, eps);
		if (sc->oom)
			goto out;
		if (fy != sc->fx[j] || (P->nr > 0 && !seen(sc, P, xo, r, eps))) {
			z.hidden++;
			continue;
		}
		sc->own[j] = own;
	}

	if (z.shared > 0) {
		if (!pm_grow((void **)&sc->rayat, &sc->rayatcap, 0, sc->ng, sizeof *sc->rayat) ||
		    !pm_grow((void **)&sc->rayhit, &sc->rayhitcap, 0, sc->ng, sizeof *sc->rayhit))
			goto out;
		for (int a = 0; a < sc->ng; a++)
			sc->rayat[a] = 0;
	}
	/* Eq. 4 over what counts, eq. 2 and 3: Phi_p / A_p (Psi_p . N). */
	double thr = PM_COMP_SKIP_REL * 4 * h * h, fl = PM_COMP_FLOOR_REL * 4 * h * h;
	int *cand = sc->bl + sc->nbl, *dcand = cand + sc->ng + 1, wait = pm_comp_fronts_wait;
	for (int j = 0; j < na; j++) {
		int own = sc->own[j];
		double A = 0, c = sc->c[j];
		pm_dvec3 psi = sc->psi[j];
		if (own == -1)
			continue;
		for (int G = 0; G < sc->ngr; G++) {
			const cgroup *Gr = &sc->gr[G];
			if (Gr->simple) {
				/* Seen whole, open fates: all of it or nothing. */
				if (sc->fx[j] >= 0)
					continue;
				if (pm_ddot(psi, Gr->M) > Gr->sina + 1e-9) {
					A += c * Gr->apar + pm_ddot(psi, Gr->V);
					continue;
				}
				for (int gi = Gr->p0; gi < Gr->p0 + Gr->np; gi++) {
					const cpoly *P = &sc->g[sc->gp[gi]];
					double f = facing(P, psi, c, nd);
					A += f > 0 ? f * P->A : 0;
				}
				continue;
			}
			/* A sheet facing psi whole: its plain polygons at once (as a
			 * simple sheet's; nothing where x's ray is not open), the
			 * rest one by one. */
			const int *gl = sc->gp + Gr->p0;
			int gn = Gr->np;
			if (Gr->sheet && pm_ddot(psi, Gr->M) > Gr->sina + 1e-9) {
				if (sc->fx[j] < 0)
					A += c * Gr->aparp + pm_ddot(psi, Gr->Vp);
				gl = sc->gq + Gr->q0;
				gn = Gr->nq;
			}
			for (int gi = 0; gi < gn; gi++) {
				const cpoly *P = &sc->g[gl[gi]];
				double f = facing(P, psi, c, nd), s = 0;
				if (!(f > 0) || P->unseen)
					continue;
				if (P->share) {
					/* Its one point's fate along psi (share_cells()): its
					 * cell's first facet's ray, cast once a photon. */
					int r = P->share - 1;
					if (!(pm_ddot(psi, sc->g[r].Ne) > 0) || gl[gi] == own) {
						/* Its cell's first facet turned from psi, or the
						 * photon's own facet: its own ray, through the
						 * tree (a member builds no front list). */
						int hit = cast_hits(sc, P, psi, h, eps, sc->fx[j]);
						if (sc->oom)
							goto out;
						A += f * hit * P->A;
						continue;
					}
					if (sc->rayat[r] != j + 1) {
						sc->rayhit[r] = ray_hits(sc, &sc->g[r], psi, h, eps, sc->fx[j]);
						if (sc->oom)
							goto out;
						sc->rayat[r] = j + 1;
					}
					A += f * sc->rayhit[r] * P->A;
					continue;
				}
				if (P->fcast) {
					if ((s = cast_area(sc, P, psi, h, eps, sc->fx[j])) < 0)
						goto out;
					A += f * s;
					continue;
				}
				/* The polygons off P's plane that a backward ray from P may
				 * meet along psi; the fronts of solids met from behind
				 * wait in dcand (opens_later()). */
				int nc = 0, ndc = 0, k;
				for (int b = P->nfc; b < P->nf && P->ndyn > 0; b++) {
					int e = P->f0 + b, le = sc->bl[e];
					if (wait && opens_later(sc, le, psi)) {
						dcand[ndc++] = e;
						continue;
					}
					const cpoly *B = &sc->g[IDX(le)];
					if (apart(P, B, psi, eps))
						continue;
					const double *gv = gaps(sc, P, B, e);
					if (!gv)
						goto out;
					if (reach(sc, P, B, gv, psi, eps))
						cand[nc++] = e;
				}
				z.waited += ndc;
				/* The exact overlap below takes one candidate, whichever
				 * kind: count the waiting ones where that can matter. */
				int ntot = nc, one = nc == 1 ? cand[0] : -1;
				if (ndc > 0 && nc <= 1 && P->nr == 0 && P->nfc == 0 && P->convex)
					for (int i = 0; i < ndc && ntot <= 1; i++) {
						if ((k = may_meet(sc, P, dcand[i], psi, eps)) < 0)
							goto out;
						if (k && ntot++ == 0)
							one = dcand[i];
					}
				if (ntot == 0 && sc->fx[j] < 0) {
					A += f * (P->aopen + P->adyn);
					continue;
				}
				if (ntot == 1 && P->nr == 0 && P->nfc == 0 && P->convex && (sc->bl[one] & FRONT) &&
				    pm_comp_exact_overlap) {
					/* One polygon in front of P, all of P seen: what it
					 * covers of P along psi, exactly. */
					int c0 = sc->bl[one];
					const cpoly *B = &sc->g[IDX(c0)];
					double dn = pm_ddot(B->N, psi), ov = 0;
					int fb = fate_at(c0, B, dn);
					if (fb >= 0) {
						if (!pm_grow((void **)&sc->ov, &sc->ovcap, 0, 2 * (B->nv + P->nv) + 8, sizeof *sc->ov))
							goto out;
						ov = pm_overlap_area(sc->cv + B->v0, B->nv, sc->cv + P->v0, P->nv, P->N, psi, sc->ov);
					}
					s = sc->fx[j] < 0 ? P->A - ov : sc->fx[j] == fb ? ov : 0;
					A += f * dmax(0, s);
					continue;
				}
				/* Only the fronts waiting (fate -1 wherever they are met):
				 * as if nothing were met. */
				int hit = nc > 0 ? fates_hit(sc, P, cand, nc, dcand, ndc, psi, eps, sc->fx[j], &z) : 0;
				if (hit < 0)
					goto out;
				for (int t = P->s0 + P->ndyn; t < P->s0 + P->ns; t++)
					hit += sc->sf[t] == sc->fx[j];
				/* An unsampled polygon has no cells (ncell 0): hit is 0 there,
				 * and 0 * (A / 0) would be NaN. */
				s = (sc->fx[j] < 0 ? P->aopen + (nc > 0 ? 0 : P->adyn) : 0) +
				    (hit > 0 ? hit * (P->A / P->ncell) : 0);
				A += f * s;
			}
		}
		/* The photon's own spot is exposed: never less than its cell (a
		 * photon on a simple sheet has all of the sheet). */
		if (own >= 0) {
			const cpoly *O = &sc->g[own];
			A = dmax(A, facing(O, psi, c, nd) * O->A / (O->ncell > 0 ? O->ncell : GRID * GRID));
		}
		w[sc->act[j]] = spread(A, c, thr, fl, &z);
	}
out:
	if (st)
		*st = z;
}

void
pm_comp_weights(const pm_polyindex *pi, pm_vec3 x, pm_vec3 n,
                const pm_vec3 *pos, const pm_vec3 *dir, int m,
                int complete, pm_comp_scratch *sc, double *w,
                pm_comp_stats *st)
{
	weights(pi, x, n, pos, dir, m, complete, 0, sc, w, st);
}

void
pm_comp_weights_cube(const pm_polyindex *pi, pm_vec3 x, pm_vec3 n,
                     const pm_vec3 *pos, const pm_vec3 *dir, int m, double h,
                     pm_comp_scratch *sc, double *w, pm_comp_stats *st)
{
	if (!(h > 0) || !isfinite(h)) {
		for (int i = 0; i < (m < sc->k ? m : sc->k); i++)
			w[i] = 0;
		if (st)
			*st = (pm_comp_stats){.found = m > 0 ? m : 0};
		return;
	}
	weights(pi, x, n, pos, dir, m, 0, h, sc, w, st);
}

pm_vec3
pm_estimate_compensated(const pm_polyindex *pi, const pm_photons *map,
                        pm_vec3 x, pm_vec3 n, pm_vec3 wo,
                        const pm_material *m, int k,
                        pm_comp_scratch *sc, pm_estimate_info *info)
{
	return pm_estimate_compensated_shrink(pi, map, x, n, n, wo, m, k, 1, sc, info);
}

pm_vec3
pm_estimate_compensated_shrink(const pm_polyindex *pi, const pm_photons *map,
                               pm_vec3 x, pm_vec3 n, pm_vec3 ns, pm_vec3 wo,
                               const pm_material *m, int k, double shrink,
                               pm_comp_scratch *sc, pm_estimate_info *info)
{
	pm_vec3 L = pm_v3(0, 0, 0);
	double sum[3] = {0, 0, 0}, inv;
	float q[3] = {x.x, x.y, x.z}, dfar = 0;
	int got, complete;

	info->size = info->disc = 0;
	info->nphotons = 0;
	if (!sc)
		return L;
	sc->last = (pm_comp_stats){0};
	if (!pi || !map || !m || k < 1 || map->h.count == 0 || map->h.emitted == 0
	    || !pm_vfinite(x))
		return L;
	if (k > sc->k)
		k = sc->k;
	got = pm_kd_knn(map->p, (size_t)map->h.count, q, k, PM_LINF, INFINITY, sc->nn, &dfar);
	if (got <= 0)
		return L;
	for (int i = 0; i < got; i++) {
		const pm_photon *p = &map->p[sc->nn[i].idx];
		sc->pos[i] = pm_photon_pos(p);
		sc->dir[i] = pm_photon_dir(p);
	}
	complete = got < k || (uint64_t)got == map->h.count;
	int shading = ns.x != n.x || ns.y != n.y || ns.z != n.z;
	if (shrink > 0 && shrink < 1 && dfar > 0)
		pm_comp_weights_cube(pi, x, n, sc->pos, sc->dir, got, shrink * dfar, sc, sc->w, &sc->last);
	else
		pm_comp_weights(pi, x, n, sc->pos, sc->dir, got, complete, sc, sc->w, &sc->last);
	for (int i = 0; i < got; i++) {
		if (!(sc->w[i] > 0))
			continue;
		pm_vec3 f = pm_bsdf_eval(m, ns, sc->dir[i], wo);
		pm_vec3 P = pm_photon_power(&map->p[sc->nn[i].idx]);
		if (shading)
			f = pm_scale(f, pm_shading_photon_weight(n, ns, sc->dir[i]));
		sum[0] += sc->w[i] * P.x * f.x;
		sum[1] += sc->w[i] * P.y * f.y;
		sum[2] += sc->w[i] * P.z * f.z;
	}
	inv = 1.0 / (double)map->h.emitted;
	for (int c = 0; c < 3; c++) {
		double v = sum[c] * inv;
		sum[c] = !(v > 0) ? 0 : v > FLT_MAX ? FLT_MAX : v;
	}
	L = pm_v3((float)sum[0], (float)sum[1], (float)sum[2]);
	info->size = (float)sc->last.h;
	info->disc = (float)(2 * sc->last.h / sqrt(PM_PI));
	info->nphotons = got;
	return L;
}
