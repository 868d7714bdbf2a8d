/* clip.c — area of a planar polygon inside a closed axis-aligned cube:
 * Sutherland–Hodgman reentrant clipping (CACM 17(1), 1974) streamed through
 * six stages, then the area by the cross-product (Newell) sum. See clip.h. */
#include "estimators/clip.h"

#include <math.h>

static double
coord(pm_dvec3 v, int a)
{
	return a == 0 ? v.x : a == 1 ? v.y : v.z;
}

/* Stage j keeps the half-space s * v[a] <= h with a = j / 2, s = +1 for even j
 * and -1 for odd j. Closed: a vertex on the plane is inside. */
static int
inside(const pm_clipper *c, int j, pm_dvec3 v)
{
	double t = coord(v, j >> 1);
	return ((j & 1) ? -t : t) <= c->h;
}

/* The crossing of the segment from an inside vertex to an outside one.
 * Always computed from the inside end, so an edge gives the same point in
 * whichever direction it is walked, and the crossing coordinate is set to the
 * plane exactly so that rounding never puts it outside. */
static pm_dvec3
crossing(const pm_clipper *c, int j, pm_dvec3 in, pm_dvec3 out)
{
	int a = j >> 1;
	double s = (j & 1) ? -1.0 : 1.0;
	double si = s * coord(in, a), so = s * coord(out, a);
	double t = (c->h - si) / (so - si);   /* so > h >= si: no division by 0 */
	pm_dvec3 r;

	if (!(t >= 0))
		t = 0;
	else if (t > 1)
		t = 1;
	r = pm_dadd(in, pm_dscale(pm_dsub(out, in), t));
	if (a == 0)
		r.x = s * c->h;
	else if (a == 1)
		r.y = s * c->h;
	else
		r.z = s * c->h;
	return r;
}

/* The area accumulator at the end of the pipeline: sum of (v_i - o) x
 * (v_{i+1} - o) over the output, taken relative to the first output vertex o
 * for precision. */
static void
emit(pm_clipper *c, pm_dvec3 v)
{
	if (c->nout == 0)
		c->o = v;
	else
		c->sum = pm_dadd(c->sum, pm_dcross(pm_dsub(c->prev, c->o), pm_dsub(v, c->o)));
	c->vsum = pm_dadd(c->vsum, v);
	c->prev = v;
	if (c->keep && c->nout < c->keepcap)
		c->keep[c->nout] = v;
	c->nout++;
}

static void
put(pm_clipper *c, int j, pm_dvec3 v)
{
	int in;

	if (j == 6) {
		emit(c, v);
		return;
	}
	in = inside(c, j, v);
	if (c->st[j].count == 0) {
		c->st[j].first = v;
		c->st[j].first_in = in;
	} else if (in != c->st[j].prev_in) {
		pm_dvec3 p = c->st[j].prev;
		put(c, c->next[j], in ? crossing(c, j, v, p) : crossing(c, j, p, v));
	}
	if (in)
		put(c, c->next[j], v);
	c->st[j].prev = v;
	c->st[j].prev_in = in;
	c->st[j].count++;
}

/* Closing edge of each stage, from its last vertex back to its first; the
 * stages are closed in order so that a later stage sees everything an earlier
 * one emits. */
static void
close_stage(pm_clipper *c, int j)
{
	if (j == 6)
		return;
	if (c->st[j].count > 0 && c->st[j].prev_in != c->st[j].first_in) {
		pm_dvec3 p = c->st[j].prev, f = c->st[j].first;
		put(c, c->next[j], c->st[j].prev_in ? crossing(c, j, p, f) : crossing(c, j, f, p));
	}
	close_stage(c, c->next[j]);
}

void
pm_clip_begin(pm_clipper *c, double h)
{
	for (int j = 0; j < 6; j++) {
		c->st[j].count = 0;
		c->next[j] = j + 1;
	}
	c->first = 0;
	c->h = h;
	c->off = !(h > 0) || !isfinite(h);
	c->nout = 0;
	c->sum = pm_dv3(0, 0, 0);
	c->vsum = pm_dv3(0, 0, 0);
	c->keep = NULL;
	c->keepcap = 0;
}

void
pm_clip_bounds(pm_clipper *c, const double lo[3], const double hi[3])
{
	int next = 6;

	/* A stage whose half-space holds the whole box passes every vertex on
	 * unchanged: the same test as inside(), on the box's extreme. */
	for (int j = 5; j >= 0; j--) {
		double t = (j & 1) ? -lo[j >> 1] : hi[j >> 1];
		c->next[j] = next;
		if (!(t <= c->h))
			next = j;
	}
	c->first = next;
}

void
pm_clip_keep(pm_clipper *c, pm_dvec3 *buf, int cap)
{
	c->keep = buf;
	c->keepcap = cap;
}

int
pm_clip_kept(const pm_clipper *c)
{
	return c->off ? 0 : c->nout <= c->keepcap ? c->nout : -1;
}

void
pm_clip_vertex(pm_clipper *c, pm_dvec3 v)
{
	if (!c->off)
		put(c, c->first, v);
}

double
pm_clip_end(pm_clipper *c, pm_dvec3 normal)
{
	double a;

	if (c->off)
		return 0;
	close_stage(c, c->first);
	if (c->nout < 3)
		return 0;
	/* The closing term (v_last - o) x (o - o) is zero, so the sum is complete. */
	if (normal.x == 0 && normal.y == 0 && normal.z == 0)
		a = 0.5 * pm_dlen(c->sum);
	else
		a = 0.5 * fabs(pm_ddot(c->sum, normal));
	return isfinite(a) ? a : 0;
}

pm_dvec3
pm_clip_middle(const pm_clipper *c)
{
	return c->nout > 0 ? pm_dscale(c->vsum, 1.0 / c->nout) : pm_dv3(0, 0, 0);
}

double
pm_clip_area(const pm_dvec3 *v, size_t n, pm_dvec3 normal, double h)
{
	pm_clipper c;

	pm_clip_begin(&c, h);
	for (size_t i = 0; i < n; i++)
		pm_clip_vertex(&c, v[i]);
	return pm_clip_end(&c, normal);
}

/* One stage of pm_clip_array: put()'s rules for stage j over a whole
 * polygon, the closing edge last, as close_stage() takes it. -1 past cap. */
static int
stage(const pm_clipper *c, int j, const pm_dvec3 *in, int n, pm_dvec3 *out, int cap)
{
	int m = 0, first_in = 0, prev_in = 0;

	for (int i = 0; i < n; i++) {
		int in_i = inside(c, j, in[i]);
		if (i == 0)
			first_in = in_i;
		else if (in_i != prev_in) {
			if (m >= cap)
				return -1;
			out[m++] = in_i ? crossing(c, j, in[i], in[i - 1]) : crossing(c, j, in[i - 1], in[i]);
		}
		if (in_i) {
			if (m >= cap)
				return -1;
			out[m++] = in[i];
		}
		prev_in = in_i;
	}
	if (n > 0 && prev_in != first_in) {
		if (m >= cap)
			return -1;
		out[m++] = prev_in ? crossing(c, j, in[n - 1], in[0]) : crossing(c, j, in[0], in[n - 1]);
	}
	return m;
}

#define ARRAY_MAX 64

/* pm_clip_array where a buffer is too small: the streaming clipper, which
 * needs none and gives the same answer. */
static int
streamed(const pm_dvec3 *v, int n, double h, const double *lo, const double *hi,
         pm_dvec3 normal, pm_dvec3 *out, int cap, double *area, pm_dvec3 *middle)
{
	pm_clipper c;

	pm_clip_begin(&c, h);
	if (lo && hi)
		pm_clip_bounds(&c, lo, hi);
	pm_clip_keep(&c, out, cap);
	for (int i = 0; i < n; i++)
		pm_clip_vertex(&c, v[i]);
	*area = pm_clip_end(&c, normal);
	*middle = pm_clip_middle(&c);
	return pm_clip_kept(&c);
}

int
pm_clip_array(const pm_dvec3 *v, int n, double h, const double *lo, const double *hi,
              pm_dvec3 normal, pm_dvec3 *out, int cap, double *area, pm_dvec3 *middle)
{
	pm_clipper c;
	pm_dvec3 buf[2][ARRAY_MAX];
	const pm_dvec3 *src = v;
	int m = n, b = 0, last = -1;

	*area = 0;
	*middle = pm_dv3(0, 0, 0);
	pm_clip_begin(&c, h);
	if (c.off)
		return 0;
	if (lo && hi)
		pm_clip_bounds(&c, lo, hi);
	/* The stages that cut, in pipeline order; the last writes to out. */
	for (int j = c.first; j < 6; j = c.next[j])
		last = j;
	for (int j = c.first; j < 6 && m > 0; j = c.next[j]) {
		pm_dvec3 *dst = j == last ? out : buf[b];
		m = stage(&c, j, src, m, dst, j == last ? cap : ARRAY_MAX);
		if (m < 0)
			return streamed(v, n, h, lo, hi, normal, out, cap, area, middle);
		src = dst;
		b ^= 1;
	}
	if (src != out) {
		if (m > cap)
			return streamed(v, n, h, lo, hi, normal, out, cap, area, middle);
		for (int i = 0; i < m; i++)
			out[i] = src[i];
	}
	/* emit()'s sums, in its order. */
	pm_dvec3 sum = pm_dv3(0, 0, 0), vsum = pm_dv3(0, 0, 0);
	for (int i = 0; i < m; i++) {
		if (i > 0)
			sum = pm_dadd(sum, pm_dcross(pm_dsub(out[i - 1], out[0]), pm_dsub(out[i], out[0])));
		vsum = pm_dadd(vsum, out[i]);
	}
	if (m > 0)
		*middle = pm_dscale(vsum, 1.0 / m);
	if (m >= 3) {
		double a = normal.x == 0 && normal.y == 0 && normal.z == 0 ? 0.5 * pm_dlen(sum)
		                                                           : 0.5 * fabs(pm_ddot(sum, normal));
		*area = isfinite(a) ? a : 0;
	}
	return m;
}
