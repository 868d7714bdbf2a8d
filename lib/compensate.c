/* compensate.c — the compensated radiance estimate (Hey & Purgathofer 2001,
 * "Global Illumination with Photon Map Compensation", §3, eq. 1-4): photons
 * in the L-infinity cube around x, the photon-surface polygons clipped into
 * it, each photon's flux spread over its own target area A_p, the projection
 * of that geometry across the photon's direction. The rules for the cases
 * the paper leaves open are in compensate.h.
 *
 * Cost per estimate: one k-nearest search, one pass over the polygons that
 * meet the cube (typically 1-6) clipping each once and adding its projected
 * area to every photon's A_p, and one f_r per photon, as in the classical
 * estimate. All geometry is double and relative to x. */
#include "compensate.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "bsdf.h"
#include "clip.h"
#include "overlap.h"

/* A polygon whose unit normal is this close to +-n is taken as lying in the
 * plane of x (1 - cos of about 1.4 milliradians). */
#define PARALLEL_EPS 1e-6
#define MAX_K (1 << 24)
/* Polygons remembered per cube for the parallel-layer correction. */
#define MAX_SEEN 32
/* Parallel layers closer than this (relative to h) count as touching
 * (opposite normals) or as one plane (same normals). */
#define CONTACT_REL 1e-3

struct pm_comp_scratch {
	int k;
	pm_nn *nn;
	pm_vec3 *pos, *dir;    /* photons found */
	double *w;             /* their weights */
	double *d;             /* their L-infinity distances from x */
	int *act;              /* photons used that arrive in front of n */
	pm_dvec3 *psi;         /* ... their unit directions */
	double *c;             /* ... Psi . n */
	double *ap;            /* ... target areas A_p */
	pm_comp_stats last;
};

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
	sc->ap = malloc(n * sizeof *sc->ap);
	if (!sc->nn || !sc->pos || !sc->dir || !sc->w || !sc->d || !sc->act
	    || !sc->psi || !sc->c || !sc->ap) {
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
	free(sc->ap);
	free(sc);
}

const pm_comp_stats *
pm_comp_last(const pm_comp_scratch *sc)
{
	return &sc->last;
}

/* What the polygon visitor needs: the cube, and the photons in front of n. */
typedef struct visit_ctx {
	const pm_polyindex *pi;
	pm_dvec3 x, n;
	double h, tau;
	int open;
	int na;
	const pm_dvec3 *psi;
	const double *c;
	double *ap;
	int polys;
	int nseen;                 /* polygons with area in the cube ... */
	uint32_t seen[MAX_SEEN];   /* ... their numbers */
	pm_dvec3 seen_n[MAX_SEEN]; /* ... unit normals */
	double seen_a[MAX_SEEN];   /* ... areas in the cube */
	double seen_d[MAX_SEEN];   /* ... plane offsets N . v relative to x */
	pm_dvec3 seen_m[MAX_SEEN]; /* ... a point of the clipped part */
} visit_ctx;

/* Polygon g's share of a photon's target area per unit of its area (the
 * factor of A_g in eq. 4), by the rules in compensate.h. */
static double
factor(const visit_ctx *q, int solid, pm_dvec3 N, int j)
{
	double sg = pm_ddot(N, q->n), t;

	if (fabs(sg) >= 1 - PARALLEL_EPS) {
		t = sg > 0 ? q->c[j] : -q->c[j];
		return solid ? fmax(0, t) : fabs(t);
	}
	t = pm_ddot(q->psi[j], N);
	return solid ? fmax(0, t) : fabs(t);
}

/* Eq. 4 for one polygon g: clip it into the cube (A_g) and add A_g (Psi_p .
 * N_g) to the target area of every photon it faces. */
static void
visit(void *vctx, uint32_t g)
{
	visit_ctx *q = vctx;
	const pm_scene *s = q->pi->s;
	const pm_vec3 *verts = q->pi->verts;
	double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
	pm_clipper cl;
	pm_dvec3 N;
	double A, len, sg;

	pm_clip_begin(&cl, q->h);
	for (uint32_t v = s->poly_start[g]; v < s->poly_start[g + 1]; v++) {
		pm_dvec3 r = pm_dsub(pm_dfromf(verts[s->poly_vert[v]]), q->x);
		double rc[3] = {r.x, r.y, r.z};
		for (int a = 0; a < 3; a++) {
			lo[a] = rc[a] < lo[a] ? rc[a] : lo[a];
			hi[a] = rc[a] > hi[a] ? rc[a] : hi[a];
		}
		pm_clip_vertex(&cl, r);
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
	A = pm_clip_end(&cl, N);
	if (!(A > 0))
		return;
	q->polys++;
	if (q->nseen < MAX_SEEN) {
		q->seen[q->nseen] = g;
		q->seen_a[q->nseen] = A;
		q->seen_d[q->nseen] = pm_ddot(N, pm_dsub(pm_dfromf(verts[s->poly_vert[s->poly_start[g]]]), q->x));
		q->seen_m[q->nseen] = pm_clip_middle(&cl);
		q->seen_n[q->nseen++] = N;
	}

	int solid = s->objs[s->poly_obj[g]].solid;
	sg = pm_ddot(N, q->n);
	if (fabs(sg) >= 1 - PARALLEL_EPS) {
		/* The plane of x: Psi.N_g is Psi.n up to sign, exactly. */
		double sign = sg > 0 ? 1 : -1;
		for (int j = 0; j < q->na; j++) {
			double t = solid ? fmax(0, sign * q->c[j]) : q->c[j];
			q->ap[j] += A * t;
		}
		return;
	}
	for (int j = 0; j < q->na; j++) {
		double t = pm_ddot(q->psi[j], N);
		q->ap[j] += A * (solid ? fmax(0, t) : fabs(t));
	}
}

/* Polygon g clipped into the cube, relative to x; 0 vertices if it is too
 * large to clip here or not convex (then no correction is made for it). */
static int
clipped(const visit_ctx *q, uint32_t g, pm_dvec3 N, pm_dvec3 *out)
{
	const pm_scene *s = q->pi->s;
	pm_dvec3 v[64];
	int n = (int)(s->poly_start[g + 1] - s->poly_start[g]);

	if (n > 64)
		return 0;
	for (int i = 0; i < n; i++)
		v[i] = pm_dsub(pm_dfromf(q->pi->verts[s->poly_vert[s->poly_start[g] + (uint32_t)i]]), q->x);
	if (!pm_poly_convex(v, n, N))
		return 0;
	return pm_clip_poly(v, n, q->h, out);
}

/* The paper's eq. 4 assumes the front-facing polygons in the cube do not
 * overlap in a photon's projection. Parallel layers do (a picture in front
 * of a wall, a rug on a floor, a box resting on a table): light reaching the
 * back layer's covered part has to pass through the front one, so that part
 * is taken out of A_p (overlap.h). Layers with opposite normals that touch
 * seal the area between them off from every direction. */
static void
hide_overlaps(visit_ctx *q)
{
	const pm_scene *s = q->pi->s;
	pm_dvec3 va[64 + 6], vb[64 + 6], scratch[2 * (64 + 6) * 2 + 8];

	for (int a = 0; a < q->nseen; a++)
		for (int b = a + 1; b < q->nseen; b++) {
			pm_dvec3 Na = q->seen_n[a], Nb = q->seen_n[b];
			double cs = pm_ddot(Na, Nb), gap, oa, ob;
			int sa = s->objs[s->poly_obj[q->seen[a]]].solid;
			int sb = s->objs[s->poly_obj[q->seen[b]]].solid;
			int na, nb;
			if (fabs(cs) < 1 - PARALLEL_EPS)
				continue;
			na = clipped(q, q->seen[a], Na, va);
			nb = clipped(q, q->seen[b], Nb, vb);
			if (na < 3 || nb < 3)
				continue;
			oa = pm_ddot(va[0], Na);
			ob = pm_ddot(vb[0], Na);
			gap = ob - oa;             /* b's plane relative to a's, along Na */
			if (cs < 0) {
				/* Opposite normals: touching faces of two objects. */
				if (fabs(gap) > CONTACT_REL * q->h)
					continue;
				double O = pm_overlap_area(va, na, vb, nb, Nb, Nb, scratch);
				if (!(O > 0))
					continue;
				for (int j = 0; j < q->na; j++)
					q->ap[j] -= O * (factor(q, sa, Na, j) + factor(q, sb, Nb, j));
				continue;
			}
			/* Same normals: for each photon, the layer nearer to where it
			 * comes from hides part of the other. Nearly coplanar layers
			 * hide the same area for every direction. */
			double O0 = fabs(gap) <= CONTACT_REL * q->h ?
				pm_overlap_area(va, na, vb, nb, Nb, Nb, scratch) : -1;
			if (O0 == 0)
				continue;
			for (int j = 0; j < q->na; j++) {
				double fa = factor(q, sa, Na, j), fb = factor(q, sb, Nb, j);
				double dn = pm_ddot(q->psi[j], Na), O;
				int a_front;
				if (!(fa > 0) || !(fb > 0))
					continue;
				a_front = dn > 0 ? gap < 0 : gap > 0;
				if (O0 >= 0)
					O = O0;
				else if (a_front)
					O = pm_overlap_area(va, na, vb, nb, Nb, q->psi[j], scratch);
				else
					O = pm_overlap_area(vb, nb, va, na, Na, q->psi[j], scratch);
				q->ap[j] -= O * (a_front ? fb : fa);
			}
		}
	for (int j = 0; j < q->na; j++)
		if (q->ap[j] < 0)
			q->ap[j] = 0;
}

/* 1 if point p (in polygon g's plane, relative to x) is inside polygon g by
 * more than eps: crossing number in the coordinate plane the polygon
 * projects best to. Points within eps of an edge count as edge_in says. */
static int
inside(const visit_ctx *q, uint32_t g, pm_dvec3 N, pm_dvec3 p, double eps, int edge_in)
{
	const pm_scene *s = q->pi->s;
	int ax = fabs(N.x) > fabs(N.y) ? (fabs(N.x) > fabs(N.z) ? 0 : 2) : (fabs(N.y) > fabs(N.z) ? 1 : 2);
	int u = (ax + 1) % 3, v = (ax + 2) % 3, in = 0;
	double P[3] = {p.x, p.y, p.z};
	uint32_t a = s->poly_start[g], n = s->poly_start[g + 1] - a;

	for (uint32_t i = 0, j = n - 1; i < n; j = i++) {
		pm_dvec3 vi = pm_dsub(pm_dfromf(q->pi->verts[s->poly_vert[a + i]]), q->x);
		pm_dvec3 vj = pm_dsub(pm_dfromf(q->pi->verts[s->poly_vert[a + j]]), q->x);
		pm_dvec3 e = pm_dsub(vi, vj), r = pm_dsub(p, vj);
		double I[3] = {vi.x, vi.y, vi.z}, J[3] = {vj.x, vj.y, vj.z};
		double ee = pm_ddot(e, e), t = ee > 0 ? fmin(1, fmax(0, pm_ddot(r, e) / ee)) : 0;
		pm_dvec3 off = pm_dsub(r, pm_dscale(e, t));
		if (pm_ddot(off, off) <= eps * eps)
			return edge_in;
		if ((I[v] > P[v]) != (J[v] > P[v]) &&
		    P[u] < (J[u] - I[u]) * (P[v] - I[v]) / (J[v] - I[v]) + I[u])
			in = !in;
	}
	return in;
}

/* g's plane offset of point r (relative to x): > 0 on g's front side. */
static inline double
side(const visit_ctx *q, int gi, pm_dvec3 r)
{
	return pm_ddot(q->seen_n[gi], r) - q->seen_d[gi];
}

/* 1 if the segment from x to r crosses a polygon of the cube other than
 * those holding x or r. Crossing points within eps of an edge count: a
 * wall's edge is where it meets the next wall, and a segment along that
 * wall passes through it there. */
static int
crosses(const visit_ctx *q, pm_dvec3 r, double eps)
{
	for (int gi = 0; gi < q->nseen; gi++) {
		double sx = side(q, gi, pm_dv3(0, 0, 0)), sr = side(q, gi, r);
		if (fabs(sx) <= eps || fabs(sr) <= eps || (sx > 0) == (sr > 0))
			continue;
		if (inside(q, q->seen[gi], q->seen_n[gi], pm_dscale(r, sx / (sx - sr)), eps, 1))
			return 1;
	}
	return 0;
}

/* What x cannot see of the cube does not share x's light: photons and
 * target area behind a thin wall, under a rug, behind a picture, on the far
 * face of a thin solid. Eq. 4 spreads each photon over all the cube's
 * geometry facing it, which is right only for geometry lit by the same
 * field as x. So:
 *  - a photon is left out (w = 0) if the segment from x to it crosses
 *    another polygon of the cube; or if it lies on a two-sided sheet,
 *    having arrived on the side away from x; or if it lies right behind
 *    x's own surface (its foot point on the plane of x inside a polygon
 *    holding x);
 *  - a polygon whose middle x cannot see (the segment crosses another
 *    polygon) is no target area: its area leaves every A_p.
 * Photons and faces meeting x's surface at an edge, concave or convex, are
 * seen (the segment runs through free space or through the solid's inside
 * without crossing another face) and count, as the paper intends.
 * unseen_area runs before the weights, unseen_photons after; the latter
 * returns the number of photons left out. */
static void
unseen_area(visit_ctx *q, double eps)
{
	const pm_scene *s = q->pi->s;

	for (int gi = 0; gi < q->nseen; gi++) {
		if (fabs(q->seen_d[gi]) <= eps || !crosses(q, q->seen_m[gi], eps))
			continue;
		for (int j = 0; j < q->na; j++)
			q->ap[j] -= q->seen_a[gi] *
				factor(q, s->objs[s->poly_obj[q->seen[gi]]].solid, q->seen_n[gi], j);
	}
	for (int j = 0; j < q->na; j++)
		if (q->ap[j] < 0)
			q->ap[j] = 0;
}

static int
unseen_photons(const visit_ctx *q, const pm_vec3 *pos, const int *act, double *w, double eps)
{
	const pm_scene *s = q->pi->s;
	int hidden = 0;

	for (int j = 0; j < q->na; j++) {
		int i = act[j], out = 0;
		pm_dvec3 r = pm_dsub(pm_dfromf(pos[i]), q->x);
		if (!(w[i] > 0))
			continue;
		out = crosses(q, r, eps);
		for (int gi = 0; gi < q->nseen && !out; gi++) {
			uint32_t g = q->seen[gi];
			pm_dvec3 N = q->seen_n[gi];
			double sx = side(q, gi, pm_dv3(0, 0, 0)), sr = side(q, gi, r);
			pm_dvec3 foot;
			if (fabs(sx) <= eps) {
				/* g holds x: is the photon right behind it? */
				if (fabs(pm_ddot(N, q->n)) < 1 - PARALLEL_EPS || pm_ddot(q->n, r) >= -eps)
					continue;
				/* A foot point on an edge of a solid's face is a
				 * photon on the face below a convex edge: it stays.
				 * A sheet has no faces below its edges: there the
				 * photon is on the far side of a thin wall. */
				foot = pm_dsub(r, pm_dscale(N, sr));
				out = inside(q, g, N, foot, eps, !s->objs[s->poly_obj[g]].solid);
			} else if (fabs(sr) <= eps && !s->objs[s->poly_obj[g]].solid &&
			           (pm_ddot(q->psi[j], N) > 0) != (sx > 0)) {
				/* On a sheet, lit on the side away from x. */
				out = inside(q, g, N, pm_dsub(r, pm_dscale(N, sr)), eps, 1);
			}
		}
		if (out) {
			w[i] = 0;
			hidden++;
		}
	}
	return hidden;
}

void
pm_comp_weights(const pm_polyindex *pi, pm_vec3 x, pm_vec3 n,
                const pm_vec3 *pos, const pm_vec3 *dir, int m,
                int complete, pm_comp_scratch *sc, double *w,
                pm_comp_stats *st)
{
	pm_comp_stats z = {0};
	visit_ctx q = {0};
	pm_dvec3 xd = pm_dfromf(x), nd = pm_dfromf(n);
	double hk = 0, hs, tau, len = pm_dlen(nd);
	int valid = 0, inner = 0, na = 0;

	if (m > sc->k)
		m = sc->k;
	for (int i = 0; i < m; i++)
		w[i] = 0;
	z.found = m > 0 ? m : 0;
	if (m <= 0 || !pi || !pm_vfinite(x) || !(len > 0) || !isfinite(len))
		goto out;
	nd = pm_dscale(nd, 1 / len);

	/* L-infinity distances, exact in double (a difference of floats). */
	for (int i = 0; i < m; i++) {
		pm_dvec3 r = pm_dsub(pm_dfromf(pos[i]), xd);
		double d = fmax(fabs(r.x), fmax(fabs(r.y), fabs(r.z)));
		sc->d[i] = isfinite(d) ? d : -1;    /* -1: not used */
		if (d >= 0 && isfinite(d)) {
			hk = fmax(hk, d);
			valid++;
		}
	}
	if (valid == 0)
		goto out;

	/* The boundary shell: the photons at the largest distance, chained down
	 * through gaps of at most tau. Every photon nearer than the shell is
	 * certainly in the set; those in it may be only some of their kind. */
	tau = PM_COMP_TAU_REL * hk;
	hs = hk;
	if (!complete) {
		for (;;) {
			double lo = hs - tau, nm = hs;
			for (int i = 0; i < m; i++)
				if (sc->d[i] >= lo && sc->d[i] < nm)
					nm = sc->d[i];
			if (nm == hs)
				break;
			hs = nm;
		}
		for (int i = 0; i < m; i++)
			inner += sc->d[i] >= 0 && sc->d[i] < hs;
	}
	if (complete || inner == 0) {
		z.closed = 1;
		q.h = fmax(hk + tau, PM_COMP_HMIN_REL * pi->extent);
	} else {
		q.h = hs;
		z.shell = valid - inner;
	}
	z.h = q.h;
	if (!(q.h > 0) || !isfinite(q.h))
		goto out;

	/* Photons used that arrive in front of n; the others add nothing. */
	for (int i = 0; i < m; i++) {
		if (sc->d[i] < 0 || (!z.closed && sc->d[i] >= hs))
			continue;
		pm_dvec3 p = pm_dfromf(dir[i]);
		double l = pm_dlen(p);
		if (!(l > 0) || !isfinite(l))
			continue;
		p = pm_dscale(p, 1 / l);
		double c = pm_ddot(p, nd);
		if (!(c > 0))
			continue;
		sc->act[na] = i;
		sc->psi[na] = p;
		sc->c[na] = c;
		sc->ap[na] = 0;
		na++;
	}
	z.front = na;
	if (na == 0)
		goto out;

	q.pi = pi;
	q.x = xd;
	q.n = nd;
	q.tau = tau;
	q.open = !z.closed;
	q.na = na;
	q.psi = sc->psi;
	q.c = sc->c;
	q.ap = sc->ap;
	pm_polyindex_cube(pi, xd, q.h, visit, &q);
	z.polys = q.polys;
	/* Beyond float rounding of the vertices, which grows with |x|. */
	double mx = fmax(fabs(xd.x), fmax(fabs(xd.y), fabs(xd.z)));
	double eps = 1e-4 * q.h + 8 * FLT_EPSILON * mx;
	if (q.nseen > 1) {
		hide_overlaps(&q);
		unseen_area(&q, eps);
	}

	/* Eq. 2 and 3: Phi_p / A_p (Psi_p . N). A photon with no front-facing
	 * area cannot be spread: skip it. The threshold scales with Psi . n so
	 * that grazing photons on the plane of x (A_p ~ A_g (Psi . n)) pass. */
	double thr = PM_COMP_SKIP_REL * 4 * q.h * q.h;
	for (int j = 0; j < na; j++) {
		if (sc->ap[j] > thr * sc->c[j])
			w[sc->act[j]] = sc->c[j] / sc->ap[j];
		else
			z.skipped++;
	}
	if (q.nseen > 1)
		z.hidden = unseen_photons(&q, pos, sc->act, w, eps);
out:
	if (st)
		*st = z;
}

pm_vec3
pm_estimate_compensated(const pm_polyindex *pi, const pm_photons *map,
                        pm_vec3 x, pm_vec3 n, pm_vec3 wo,
                        const pm_material *m, int k,
                        pm_comp_scratch *sc, pm_estimate_info *info)
{
	pm_vec3 L = pm_v3(0, 0, 0);
	double sum[3] = {0, 0, 0}, inv;
	float q[3] = {x.x, x.y, x.z}, dfar = 0;
	int got, complete;

	info->size = 0;
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
	pm_comp_weights(pi, x, n, sc->pos, sc->dir, got, complete, sc, sc->w, &sc->last);
	for (int i = 0; i < got; i++) {
		if (!(sc->w[i] > 0))
			continue;
		pm_vec3 f = pm_bsdf_eval(m, n, sc->dir[i], wo);
		pm_vec3 P = pm_photon_power(&map->p[sc->nn[i].idx]);
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
	info->nphotons = got;
	return L;
}
