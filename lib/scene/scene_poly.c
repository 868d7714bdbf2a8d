/* scene_poly.c — polygon plane geometry for the scene loader (scene_poly.h). */
#include "scene/scene_poly.h"

#include <math.h>

/* Relative tolerances, in units of the polygon's size (bounding box side)
 * and of the magnitude of its coordinates: a float vertex is only known to
 * about 6e-8 of its magnitude, so a rule finer than that would be noise. */
#define DEGEN_REL 1e-6  /* mean width below this: zero area */
#define FLAT_REL 1e-5   /* off-plane distance above this: not planar */
#define MAG_REL 1e-6

pm_dvec3
pm_poly_newell(const pm_vec3 *v, const uint32_t *idx, uint32_t n)
{
	/* Relative to the first vertex, so that a small polygon far from the
	 * origin does not lose its digits to cancellation. */
	pm_dvec3 o = pm_dfromf(v[idx[0]]), s = pm_dv3(0, 0, 0);
	for (uint32_t i = 1; i + 1 < n; i++) {
		pm_dvec3 a = pm_dsub(pm_dfromf(v[idx[i]]), o);
		pm_dvec3 b = pm_dsub(pm_dfromf(v[idx[i + 1]]), o);
		s = pm_dadd(s, pm_dcross(a, b));
	}
	return s;
}

/* Size measures used for relative tolerances: the longest side of the
 * bounding box, and the largest absolute coordinate. */
static void
poly_extent(const pm_vec3 *v, const uint32_t *idx, uint32_t n, double *size, double *mag)
{
	double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
	double m = 0, s = 0;
	for (uint32_t i = 0; i < n; i++)
		for (int k = 0; k < 3; k++) {
			double c = pm_vget(v[idx[i]], k);
			lo[k] = fmin(lo[k], c);
			hi[k] = fmax(hi[k], c);
			m = fmax(m, fabs(c));
		}
	for (int k = 0; k < 3; k++)
		s = fmax(s, hi[k] - lo[k]);
	*size = s;
	*mag = m;
}

int
pm_poly_degenerate(const pm_vec3 *v, const uint32_t *idx, uint32_t n)
{
	double size, mag;
	if (n < 3)
		return 1;
	poly_extent(v, idx, n, &size, &mag);
	if (!(size > 0))
		return 1;
	double area2 = pm_dlen(pm_poly_newell(v, idx, n));
	return area2 / size <= DEGEN_REL * size + MAG_REL * mag;
}

int
pm_poly_planar(const pm_vec3 *v, const uint32_t *idx, uint32_t n, pm_dvec3 nrm)
{
	double size, mag, far = 0;
	pm_dvec3 c = pm_dv3(0, 0, 0);
	if (n <= 3)
		return 1;
	poly_extent(v, idx, n, &size, &mag);
	pm_dvec3 u = pm_dscale(nrm, 1 / pm_dlen(nrm));
	for (uint32_t i = 0; i < n; i++)
		c = pm_dadd(c, pm_dfromf(v[idx[i]]));
	c = pm_dscale(c, 1.0 / n);
	for (uint32_t i = 0; i < n; i++)
		far = fmax(far, fabs(pm_ddot(pm_dsub(pm_dfromf(v[idx[i]]), c), u)));
	return far <= FLAT_REL * size + MAG_REL * mag;
}

static double
cross2(const double *a, const double *b, const double *c)
{
	return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

/* p inside triangle abc (counter-clockwise) or on its boundary. */
static int
in_tri(const double *a, const double *b, const double *c, const double *p)
{
	return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}

static int
same2(const double *a, const double *b)
{
	return a[0] == b[0] && a[1] == b[1];
}

uint32_t
pm_poly_triangulate(const pm_vec3 *v, const uint32_t *idx, uint32_t n, pm_dvec3 nrm,
	uint32_t (*tri)[3], void *work)
{
	double *p = work;                   /* 2 * n projected coordinates */
	uint32_t *rem = (uint32_t *)(p + 2 * (size_t)n); /* remaining corners */
	uint32_t m = n, ntri = 0, start = 0;
	double size, mag;

	if (n < 3)
		return 0;
	/* A basis (bu, bw) of the plane with bu x bw = nrm, so the polygon
	 * is counter-clockwise in the projection. */
	pm_dvec3 w = pm_dscale(nrm, 1 / pm_dlen(nrm));
	pm_dvec3 a = fabs(w.x) < 0.6 ? pm_dv3(1, 0, 0) : pm_dv3(0, 1, 0);
	pm_dvec3 bu = pm_dcross(a, w);
	bu = pm_dscale(bu, 1 / pm_dlen(bu));
	pm_dvec3 bw = pm_dcross(w, bu);
	pm_dvec3 o = pm_dfromf(v[idx[0]]);
	for (uint32_t i = 0; i < n; i++) {
		pm_dvec3 d = pm_dsub(pm_dfromf(v[idx[i]]), o);
		p[2 * i] = pm_ddot(d, bu);
		p[2 * i + 1] = pm_ddot(d, bw);
		rem[i] = i;
	}
	poly_extent(v, idx, n, &size, &mag);
	double eps = 1e-12 * size * size;

	while (m > 3) {
		uint32_t cut = m, best = 0;
		double bestcr = -INFINITY;
		int emit = 0;
		for (uint32_t k = 0; k < m && cut == m; k++) {
			uint32_t i = (start + k) % m;
			uint32_t ia = rem[(i + m - 1) % m], ib = rem[i], ic = rem[(i + 1) % m];
			const double *pa = p + 2 * ia, *pb = p + 2 * ib, *pc = p + 2 * ic;
			double cr = cross2(pa, pb, pc);
			if (cr > bestcr) {
				bestcr = cr;
				best = i;
			}
			if (fabs(cr) <= eps) {
				cut = i;  /* collinear: drop the corner, no triangle */
				break;
			}
			if (cr < 0)
				continue; /* reflex */
			int ear = 1;
			for (uint32_t j = 0; j < m && ear; j++) {
				const double *q = p + 2 * rem[j];
				if (rem[j] == ia || rem[j] == ib || rem[j] == ic)
					continue;
				if (same2(q, pa) || same2(q, pb) || same2(q, pc))
					continue;
				if (in_tri(pa, pb, pc, q))
					ear = 0;
			}
			if (ear) {
				cut = i;
				emit = 1;
			}
		}
		if (cut == m) {
			/* No ear: the polygon is not simple. Cut the most convex
			 * corner so the loop still ends. */
			cut = best;
			emit = bestcr > eps;
		}
		if (emit) {
			tri[ntri][0] = idx[rem[(cut + m - 1) % m]];
			tri[ntri][1] = idx[rem[cut]];
			tri[ntri][2] = idx[rem[(cut + 1) % m]];
			ntri++;
		}
		for (uint32_t j = cut; j + 1 < m; j++)
			rem[j] = rem[j + 1];
		m--;
		start = cut == 0 ? m - 1 : cut - 1;
	}
	if (cross2(p + 2 * rem[0], p + 2 * rem[1], p + 2 * rem[2]) > eps) {
		tri[ntri][0] = idx[rem[0]];
		tri[ntri][1] = idx[rem[1]];
		tri[ntri][2] = idx[rem[2]];
		ntri++;
	}
	return ntri;
}
