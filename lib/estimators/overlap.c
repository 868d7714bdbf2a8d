/* overlap.c — hidden area between parallel polygons (see overlap.h). */
#include "estimators/overlap.h"

#include <math.h>

/* One Sutherland-Hodgman pass: keep the side where s(v) = dot(v, p) - off
 * is <= 0 (with p a plane normal), writing to out. */
static int
clip_plane(const pm_dvec3 *in, int n, pm_dvec3 p, double off, pm_dvec3 *out)
{
	int m = 0;

	if (n <= 0)
		return 0;
	/* Each vertex's side once, as the start of one edge and the end of
	 * the one before. */
	double s0 = pm_ddot(in[0], p) - off, sa = s0;
	for (int i = 0; i < n; i++) {
		pm_dvec3 a = in[i], b = in[i + 1 < n ? i + 1 : 0];
		double sb = i + 1 < n ? pm_ddot(b, p) - off : s0;
		if (sa <= 0)
			out[m++] = a;
		if ((sa < 0 && sb > 0) || (sa > 0 && sb < 0)) {
			double t = sa / (sa - sb);
			out[m++] = pm_dadd(a, pm_dscale(pm_dsub(b, a), t));
		}
		sa = sb;
	}
	return m;
}

int
pm_clip_poly(const pm_dvec3 *in, int n, double h, pm_dvec3 *out)
{
	/* Ping-pong between out and a local buffer; the result ends in out. */
	pm_dvec3 tmp[64 + 6];
	const pm_dvec3 *src = in;
	int m = n;

	if (n < 3 || n > 64 || !(h > 0))
		return 0;
	for (int f = 0; f < 6 && m > 0; f++) {
		pm_dvec3 p = pm_dv3(f / 2 == 0, f / 2 == 1, f / 2 == 2);
		pm_dvec3 *dst = (f % 2 == 0) ? tmp : out;
		if (f % 2 == 1)
			p = pm_dscale(p, -1);
		m = clip_plane(src, m, p, h, dst);
		src = dst;
	}
	return m >= 3 ? m : 0;
}

int
pm_poly_convex(const pm_dvec3 *v, int n, pm_dvec3 N)
{
	for (int i = 0; i < n; i++) {
		pm_dvec3 e1 = pm_dsub(v[(i + 1) % n], v[i]), e2 = pm_dsub(v[(i + 2) % n], v[(i + 1) % n]);
		double s = pm_ddot(pm_dcross(e1, e2), N);
		double scale = pm_ddot(e1, e1) + pm_ddot(e2, e2);
		if (s < -1e-12 * scale)
			return 0;
	}
	return 1;
}

static double
area(const pm_dvec3 *v, int n, pm_dvec3 N)
{
	pm_dvec3 s = pm_dv3(0, 0, 0);

	for (int i = 1; i + 1 < n; i++)
		s = pm_dadd(s, pm_dcross(pm_dsub(v[i], v[0]), pm_dsub(v[i + 1], v[0])));
	return 0.5 * fabs(pm_ddot(s, N));
}

double
pm_overlap_area(const pm_dvec3 *a, int na, const pm_dvec3 *b, int nb,
                pm_dvec3 N, pm_dvec3 d, pm_dvec3 *scratch)
{
	pm_dvec3 *cur = scratch, *nxt = scratch + (na + nb + 4);
	double dn = pm_ddot(d, N), off = pm_ddot(b[0], N), orient = 0;
	int m = na;

	if (fabs(dn) < 1e-12 || na < 3 || nb < 3)
		return 0;
	/* a projected along d onto b's plane. */
	for (int i = 0; i < na; i++)
		cur[i] = pm_dsub(a[i], pm_dscale(d, (pm_ddot(a[i], N) - off) / dn));
	/* b's winding about N decides which side of each edge is inside. */
	for (int i = 1; i + 1 < nb; i++)
		orient += pm_ddot(pm_dcross(pm_dsub(b[i], b[0]), pm_dsub(b[i + 1], b[0])), N);
	if (orient == 0)
		return 0;
	for (int i = 0; i < nb && m > 0; i++) {
		pm_dvec3 e = pm_dsub(b[(i + 1) % nb], b[i]);
		/* Outward edge normal in the plane: e x N for counter-clockwise b. */
		pm_dvec3 p = pm_dcross(e, N);
		pm_dvec3 *t;
		if (orient < 0)
			p = pm_dscale(p, -1);
		m = clip_plane(cur, m, p, pm_ddot(b[i], p), nxt);
		t = cur;
		cur = nxt;
		nxt = t;
	}
	return m >= 3 ? area(cur, m, N) : 0;
}
