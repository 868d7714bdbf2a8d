/* test_boxtree.c — the tree of boxes for segment queries
 * (lib/estimators/boxtree.c) against a brute force of its own: a box that
 * some point of the segment lies in (found by walking the segment in fine
 * steps, grown as the tree grows it) must be reported, each box at most
 * once; a query stops where its callback says; a ray's search finds the
 * box it enters first, and so does each ray of a beam searched at once; a
 * half-space query reports every box beyond its plane. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/rng.h"
#include "check.h"
#include "estimators/boxtree.h"

#define MAXN 600
#define STEPS 4000

typedef struct seen_set {
	int count[MAXN];
	int calls, stop_at;
} seen_set;

static int
note(void *ctx, int i)
{
	seen_set *s = ctx;
	s->count[i]++;
	s->calls++;
	return s->calls == s->stop_at ? 7 : 0;
}

static double
u01(pm_rng *r)
{
	return (pm_rng_u32(r) + 0.5) / 4294967296.0;
}

/* n boxes in [-1, 1]^3, half-widths up to wmax; with flat, a fifth of
 * the widths 0 (a polygon in an axis plane). */
static void
random_boxes(pm_rng *r, int n, double wmax, int flat, double lo[][3], double hi[][3])
{
	for (int i = 0; i < n; i++)
		for (int k = 0; k < 3; k++) {
			double c = 2 * u01(r) - 1, w = flat && u01(r) < 0.2 ? 0 : wmax * u01(r);
			lo[i][k] = c - w;
			hi[i][k] = c + w;
		}
}

static pm_dvec3
random_point(pm_rng *r)
{
	double x = 2 * u01(r) - 1, y = 2 * u01(r) - 1;
	return pm_dv3(x, y, 2 * u01(r) - 1);
}

/* 1 if a + t (b - a) lies in box i grown by g for one of STEPS + 1 even t. */
static int
walk_meets(pm_dvec3 a, pm_dvec3 b, const double lo[3], const double hi[3], double g)
{
	for (int s = 0; s <= STEPS; s++) {
		double t = (double)s / STEPS, p[3] = {a.x + t * (b.x - a.x), a.y + t * (b.y - a.y), a.z + t * (b.z - a.z)};
		if (p[0] >= lo[0] - g && p[0] <= hi[0] + g && p[1] >= lo[1] - g && p[1] <= hi[1] + g &&
		    p[2] >= lo[2] - g && p[2] <= hi[2] + g)
			return 1;
	}
	return 0;
}

TEST(segments_find_every_box_they_meet)
{
	static double lo[MAXN][3], hi[MAXN][3];
	static seen_set s;
	pm_boxtree t = {0};
	pm_rng r = pm_rng_seed(5, 1);
	int missed = 0, twice = 0, met = 0, reported = 0, n = 0, asked = 0;

	for (int round = 0; round < 40; round++) {
		n = round == 0 ? 1 : 1 + (int)(u01(&r) * (MAXN - 1));
		/* Flat and thin boxes too (a polygon in an axis plane). */
		random_boxes(&r, n, 0.2, 1, lo, hi);
		double g = round % 2 ? 0.01 : 0;
		CHECK(pm_boxtree_build(&t, (const double (*)[3])lo, (const double (*)[3])hi, n, g));
		for (int q = 0; q < 25; q++) {
			pm_dvec3 a = random_point(&r), b = random_point(&r);
			/* Along an axis, and a point, now and then. */
			if (q % 5 == 1)
				b = pm_dv3(a.x, a.y, b.z);
			if (q % 5 == 2)
				b = a;
			memset(&s, 0, sizeof s);
			CHECK(pm_boxtree_segment(&t, a, b, note, &s) == 0);
			asked += n;
			for (int i = 0; i < n; i++) {
				int m = walk_meets(a, b, lo[i], hi[i], g);
				met += m;
				reported += s.count[i] > 0;
				missed += m && s.count[i] == 0;
				twice += s.count[i] > 1;
			}
		}
	}
	CHECKF(missed == 0 && twice == 0 && met > 500, "%d of %d boxes met missed, %d reported twice",
	       missed, met, twice);
	/* A tree that reported everything would pass the above: most boxes
	 * are far from a segment (a leaf's four come together). */
	CHECKF(reported < asked / 10, "%d reported of %d (%d met)", reported, asked, met);
	pm_boxtree_free(&t);
}

TEST(query_stops_where_asked)
{
	static double lo[MAXN][3], hi[MAXN][3];
	static seen_set s;
	pm_boxtree t = {0};

	/* 100 boxes in a row along x: a segment along the row meets them all. */
	for (int i = 0; i < 100; i++) {
		lo[i][0] = i;
		hi[i][0] = i + 0.5;
		lo[i][1] = lo[i][2] = -1;
		hi[i][1] = hi[i][2] = 1;
	}
	CHECK(pm_boxtree_build(&t, (const double (*)[3])lo, (const double (*)[3])hi, 100, 0));
	memset(&s, 0, sizeof s);
	s.stop_at = 30;
	int r = pm_boxtree_segment(&t, pm_dv3(-1, 0, 0), pm_dv3(101, 0, 0), note, &s);
	CHECKF(r == 7 && s.calls == 30, "returned %d after %d calls", r, s.calls);
	memset(&s, 0, sizeof s);
	r = pm_boxtree_segment(&t, pm_dv3(-1, 0, 0), pm_dv3(101, 0, 0), note, &s);
	CHECKF(r == 0 && s.calls == 100, "returned %d after %d calls", r, s.calls);
	/* No boxes: nothing to call. */
	CHECK(pm_boxtree_build(&t, (const double (*)[3])lo, (const double (*)[3])hi, 0, 0));
	memset(&s, 0, sizeof s);
	CHECK(pm_boxtree_segment(&t, pm_dv3(-1, 0, 0), pm_dv3(101, 0, 0), note, &s) == 0 && s.calls == 0);
	pm_boxtree_free(&t);
}

/* Where the segment a + s (b - a), s in [0, 1], enters box i grown by g,
 * by slabs; 2 if it misses. */
static double
entry_of(pm_dvec3 a, pm_dvec3 b, const double lo[3], const double hi[3], double g)
{
	double pa[3] = {a.x, a.y, a.z}, d[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, s0 = 0, s1 = 1;
	for (int k = 0; k < 3; k++) {
		if (d[k] == 0) {
			if (pa[k] < lo[k] - g || pa[k] > hi[k] + g)
				return 2;
			continue;
		}
		double u = (lo[k] - g - pa[k]) / d[k], v = (hi[k] + g - pa[k]) / d[k];
		s0 = fmax(s0, fmin(u, v));
		s1 = fmin(s1, fmax(u, v));
	}
	return s0 <= s1 ? s0 : 2;
}

typedef struct nearest {
	const double (*lo)[3], (*hi)[3];
	pm_dvec3 a, b;
	double g, best, *smax;
	int calls;
} nearest;

/* A search for the box the segment enters first, as a ray's first hit is
 * searched: each box asked lowers the bound to where the segment enters it. */
static void
nearer(void *ctx, int i)
{
	nearest *q = ctx;
	double e = entry_of(q->a, q->b, q->lo[i], q->hi[i], q->g);
	q->calls++;
	if (e < q->best) {
		q->best = e;
		*q->smax = e;
	}
}

/* pm_boxtree_beam of one segment, with a callback that lowers the bound as it goes: it must
 * find the box the segment enters first (against every box tried), and ask
 * far fewer boxes than a full walk, among boxes crowded enough that a
 * segment meets many. */
TEST(rays_find_the_nearest_box)
{
	static double lo[MAXN][3], hi[MAXN][3];
	static seen_set s;
	pm_boxtree t = {0};
	pm_rng r = pm_rng_seed(6, 1);
	int wrong = 0, rays = 0;
	long asked = 0, walked = 0;

	for (int round = 0; round < 40; round++) {
		int n = 1 + (int)(u01(&r) * (MAXN - 1));
		random_boxes(&r, n, 0.3, 1, lo, hi);
		double g = round % 2 ? 0.01 : 0;
		CHECK(pm_boxtree_build(&t, (const double (*)[3])lo, (const double (*)[3])hi, n, g));
		for (int q = 0; q < 25; q++, rays++) {
			pm_dvec3 a = random_point(&r), b = random_point(&r);
			if (q % 5 == 1)
				b = pm_dv3(a.x, a.y, b.z);
			double smax = 1, truth = 2;
			nearest nq = {(const double (*)[3])lo, (const double (*)[3])hi, a, b, g, 2, &smax, 0};
			pm_boxtree_beam(&t, a, a, pm_dsub(b, a), -1, &smax, nearer, &nq);
			for (int i = 0; i < n; i++)
				truth = fmin(truth, entry_of(a, b, lo[i], hi[i], g));
			wrong += nq.best != truth;
			asked += nq.calls;
			memset(&s, 0, sizeof s);
			pm_boxtree_segment(&t, a, b, note, &s);
			walked += s.calls;
		}
	}
	CHECKF(wrong == 0, "%d of %d rays missed the nearest box", wrong, rays);
	CHECKF(2 * asked < walked, "asked %ld boxes, a full walk %ld", asked, walked);
	pm_boxtree_free(&t);
}

#define BEAM 9

typedef struct beam_q {
	const double (*lo)[3], (*hi)[3];
	const int *tag;
	pm_dvec3 a[BEAM], d;
	double g, best[BEAM], *smax;
	int n, skip, full, calls, count[MAXN];
} beam_q;

/* Each ray of the beam keeps the box it enters first, of those not tagged
 * skip; the bound is the furthest any ray still needs (or, with full, the
 * whole way). */
static void
nearer_each(void *ctx, int i)
{
	beam_q *q = ctx;
	double m = 0;

	q->calls++;
	q->count[i]++;
	if (q->tag[i] == q->skip)
		return;
	for (int j = 0; j < q->n; j++) {
		double e = entry_of(q->a[j], pm_dadd(q->a[j], q->d), q->lo[i], q->hi[i], q->g);
		q->best[j] = fmin(q->best[j], e);
		m = fmax(m, fmin(q->best[j], 1));
	}
	*q->smax = q->full ? 1 : m;
}

/* Tags: 0 for boxes centred at x < 0 (a region, as a sheet is), 1 or 2
 * for the others (mixed). */
static void
tag_boxes(int n, const double lo[][3], const double hi[][3], int *tag)
{
	for (int i = 0; i < n; i++)
		tag[i] = lo[i][0] + hi[i][0] < 0 ? 0 : 1 + i % 2;
}

/* pm_boxtree_beam: parallel segments from origins scattered in a small box
 * (some along an axis, where the origins differ in the coordinates the
 * direction lacks), in one walk, in half the rounds passing over boxes
 * tagged 0 (and then walking the whole way). Each must find the box it
 * enters first of those not passed over, no box may be asked twice, the
 * walk must ask fewer boxes than the rays' own walks together, and most
 * boxes tagged 0 that the segments enter must be passed over. */
TEST(beams_find_each_rays_nearest_box)
{
	static double lo[MAXN][3], hi[MAXN][3];
	static beam_q q;
	static int tag[MAXN];
	pm_boxtree t = {0};
	pm_rng r = pm_rng_seed(8, 1);
	int wrong = 0, twice = 0, rays = 0, skipped = 0, skippable = 0;
	long asked = 0, alone = 0;

	for (int round = 0; round < 40; round++) {
		int n = 1 + (int)(u01(&r) * (MAXN - 1)), skip = round % 4 < 2 ? 0 : -1;
		random_boxes(&r, n, 0.3, 1, lo, hi);
		double g = round % 2 ? 0.01 : 0;
		CHECK(pm_boxtree_build(&t, (const double (*)[3])lo, (const double (*)[3])hi, n, g));
		tag_boxes(n, (const double (*)[3])lo, (const double (*)[3])hi, tag);
		pm_boxtree_tag(&t, tag);
		for (int k = 0; k < 25; k++) {
			pm_dvec3 c = random_point(&r), b = random_point(&r), blo, bhi;
			double w = 0.05 * u01(&r);
			if (k % 5 == 1)
				b = pm_dv3(c.x, c.y, b.z);
			memset(&q, 0, sizeof q);
			q.lo = (const double (*)[3])lo;
			q.hi = (const double (*)[3])hi;
			q.tag = tag;
			q.skip = skip;
			q.full = skip == 0;
			q.d = pm_dsub(b, c);
			q.g = g;
			q.n = 1 + (int)(u01(&r) * BEAM);
			blo = bhi = c;
			for (int j = 0; j < q.n; j++) {
				q.a[j] = pm_dadd(c, pm_dv3(w * (2 * u01(&r) - 1), w * (2 * u01(&r) - 1),
				                          k % 5 == 1 ? 0 : w * (2 * u01(&r) - 1)));
				q.best[j] = 2;
				blo = pm_dv3(fmin(blo.x, q.a[j].x), fmin(blo.y, q.a[j].y), fmin(blo.z, q.a[j].z));
				bhi = pm_dv3(fmax(bhi.x, q.a[j].x), fmax(bhi.y, q.a[j].y), fmax(bhi.z, q.a[j].z));
			}
			double smax = 1;
			q.smax = &smax;
			pm_boxtree_beam(&t, blo, bhi, q.d, skip, &smax, nearer_each, &q);
			asked += q.calls;
			for (int i = 0; i < n; i++) {
				twice += q.count[i] > 1;
				int enters = 0;
				for (int j = 0; j < q.n && skip == 0 && tag[i] == 0; j++)
					enters |= entry_of(q.a[j], pm_dadd(q.a[j], q.d), lo[i], hi[i], g) <= 1;
				skippable += enters;
				skipped += enters && q.count[i] == 0;
			}
			for (int j = 0; j < q.n; j++, rays++) {
				double truth = 2, sm = 1;
				nearest nq = {(const double (*)[3])lo, (const double (*)[3])hi, q.a[j],
				              pm_dadd(q.a[j], q.d), g, 2, &sm, 0};
				for (int i = 0; i < n; i++)
					if (tag[i] != skip)
						truth = fmin(truth, entry_of(q.a[j], pm_dadd(q.a[j], q.d), lo[i], hi[i], g));
				wrong += q.best[j] != truth;
				pm_boxtree_beam(&t, q.a[j], q.a[j], q.d, -1, &sm, nearer, &nq);
				alone += nq.calls;
			}
		}
	}
	CHECKF(wrong == 0, "%d of %d rays missed the nearest box", wrong, rays);
	CHECKF(twice == 0, "%d boxes asked twice by one beam", twice);
	CHECKF(asked < alone, "the beams asked %ld boxes, their rays alone %ld", asked, alone);
	CHECKF(skippable > 1000 && skipped > skippable * 3 / 4, "%d of %d boxes tagged 0 entered passed over",
	       skipped, skippable);
	pm_boxtree_free(&t);
}

typedef struct beyond {
	int count[MAXN];
} beyond;

static int
mark_beyond(void *ctx, int i)
{
	((beyond *)ctx)->count[i]++;
	return 0;
}

/* pm_boxtree_halfspace must report every box with a corner beyond the
 * plane, each once, and leave most of the others out; told to skip the
 * boxes tagged 0 (in half the rounds), it must still report every other,
 * and leave most of those out. */
TEST(halfspace_finds_every_box_beyond)
{
	static double lo[MAXN][3], hi[MAXN][3];
	static beyond bs;
	static int tag[MAXN];
	pm_boxtree t = {0};
	pm_rng r = pm_rng_seed(7, 1);
	int missed = 0, twice = 0, due = 0, others = 0, extra = 0, tagged = 0, untold = 0;

	for (int round = 0; round < 40; round++) {
		int n = 1 + (int)(u01(&r) * (MAXN - 1)), skip = round % 2 ? 0 : -1;
		random_boxes(&r, n, 0.1, 0, lo, hi);
		CHECK(pm_boxtree_build(&t, (const double (*)[3])lo, (const double (*)[3])hi, n, 0));
		tag_boxes(n, (const double (*)[3])lo, (const double (*)[3])hi, tag);
		pm_boxtree_tag(&t, tag);
		for (int q = 0; q < 25; q++) {
			pm_dvec3 N = pm_dv3(2 * u01(&r) - 1, 2 * u01(&r) - 1, 2 * u01(&r) - 1);
			/* Planes that leave a tenth to most of the boxes beyond. */
			double d = 0.4 + 0.6 * u01(&r);
			memset(&bs, 0, sizeof bs);
			CHECK(pm_boxtree_halfspace(&t, N, d, skip, mark_beyond, &bs) == 0);
			for (int i = 0; i < n; i++) {
				int in = 0;
				for (int c = 0; c < 8; c++)
					in |= (c & 1 ? hi : lo)[i][0] * N.x + (c & 2 ? hi : lo)[i][1] * N.y +
					      (c & 4 ? hi : lo)[i][2] * N.z > d;
				if (tag[i] == skip) {
					tagged += in;
					untold += in && bs.count[i] > 0;
					twice += bs.count[i] > 1;
					continue;
				}
				due += in;
				others += !in;
				missed += in && bs.count[i] == 0;
				twice += bs.count[i] > 1;
				extra += !in && bs.count[i] > 0;
			}
		}
	}
	CHECKF(missed == 0 && twice == 0 && due > 1000, "%d of %d boxes beyond missed, %d reported twice",
	       missed, due, twice);
	CHECKF(extra < others / 4, "%d of %d boxes not beyond reported", extra, others);
	CHECKF(tagged > 1000 && untold < tagged / 10, "%d of %d boxes beyond tagged 0 reported", untold, tagged);
	pm_boxtree_free(&t);
}

int
main(void)
{
	RUN(segments_find_every_box_they_meet);
	RUN(query_stops_where_asked);
	RUN(rays_find_the_nearest_box);
	RUN(beams_find_each_rays_nearest_box);
	RUN(halfspace_finds_every_box_beyond);
	return check_done();
}
