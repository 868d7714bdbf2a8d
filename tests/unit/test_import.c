/* test_import.c — the import layer's arithmetic (lib/import/desc.h): the
 * rotations pbrt and Mitsuba mean, inverses, mirroring transforms keeping a
 * face's front, disks facing +z with pbrt's area, and the notes' merging. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "base/vec.h"
#include "import/desc.h"

static int
near(double a, double b)
{
	return fabs(a - b) < 1e-9;
}

/* Newell normal of face f. */
static void
face_normal(const pmi_shape *s, size_t f, double n[3])
{
	uint32_t b = s->start[f], k = s->start[f + 1] - b;
	n[0] = n[1] = n[2] = 0;
	for (uint32_t i = 0; i < k; i++) {
		const float *p = s->v + 3 * (size_t)s->idx[b + i], *q = s->v + 3 * (size_t)s->idx[b + (i + 1) % k];
		n[0] += ((double)p[1] - q[1]) * ((double)p[2] + q[2]);
		n[1] += ((double)p[2] - q[2]) * ((double)p[0] + q[0]);
		n[2] += ((double)p[0] - q[0]) * ((double)p[1] + q[1]);
	}
}

TEST(rotate_is_right_handed)
{
	/* 90 degrees about +z takes +x to +y, about +x takes +y to +z. */
	double x[3] = { 1, 0, 0 }, y[3] = { 0, 1, 0 }, o[3];
	pmi_xform_vector(pmi_rotate(90, 0, 0, 1), x, o);
	CHECKF(near(o[0], 0) && near(o[1], 1) && near(o[2], 0), "%g %g %g", o[0], o[1], o[2]);
	pmi_xform_vector(pmi_rotate(90, 2, 0, 0), y, o);
	CHECKF(near(o[0], 0) && near(o[1], 0) && near(o[2], 1), "%g %g %g", o[0], o[1], o[2]);
}

TEST(product_order_and_inverse)
{
	/* a b applies b first: translate after scale moves the scaled point. */
	pmi_mat4 m = pmi_mul(pmi_translate(1, 2, 3), pmi_scale(2, 2, 2)), inv;
	double p[3] = { 1, 1, 1 }, q[3];
	pmi_xform_point(m, p, q);
	CHECKF(near(q[0], 3) && near(q[1], 4) && near(q[2], 5), "%g %g %g", q[0], q[1], q[2]);
	CHECK(pmi_invert(m, &inv) == 0);
	pmi_xform_point(inv, q, q);
	CHECKF(near(q[0], 1) && near(q[1], 1) && near(q[2], 1), "%g %g %g", q[0], q[1], q[2]);
	CHECK(near(pmi_det3(m), 8));
	CHECK(pmi_invert(pmi_scale(1, 0, 1), &inv) == -1);
}

TEST(mirror_keeps_the_front)
{
	pmi_shape s;
	double n[3];

	memset(&s, 0, sizeof s);
	CHECK(pmi_disk_mesh(&s, 1, 0, 0, 360) == 0);
	face_normal(&s, 0, n);
	CHECKF(n[2] > 0, "disk faces %g", n[2]);
	/* the full disk is one polygon of (nearly) pi r^2 */
	CHECKF(fabs(pmi_face_area(&s, 0) - PM_PI) < 0.002 * PM_PI, "area %g", pmi_face_area(&s, 0));
	/* Mirroring in z: the front stays on the side the normal carried as a
	 * normal points to, i.e. -z. */
	pmi_shape_xform(&s, pmi_scale(1, 1, -1), 0);
	face_normal(&s, 0, n);
	CHECKF(n[2] < 0, "mirrored disk faces %g", n[2]);
	/* flip (ReverseOrientation) turns it back. */
	pmi_shape_xform(&s, pmi_identity(), 1);
	face_normal(&s, 0, n);
	CHECKF(n[2] > 0, "flipped disk faces %g", n[2]);
	pmi_shape_free(&s);
}

TEST(annulus_and_partial_disk)
{
	pmi_shape s;
	double a = 0, n[3];

	memset(&s, 0, sizeof s);
	CHECK(pmi_disk_mesh(&s, 2, 1, 0.5, 180) == 0);
	for (size_t f = 0; f < s.nface; f++) {
		a += pmi_face_area(&s, f);
		face_normal(&s, f, n);
		CHECKF(n[2] > 0, "face %zu faces %g", f, n[2]);
	}
	/* half an annulus: pi (4 - 1) / 2, inscribed */
	CHECKF(fabs(a - 1.5 * PM_PI) < 0.003 * a, "area %g", a);
	CHECK(s.v[2] == 0.5f);
	pmi_shape_free(&s);
}

TEST(notes_merge)
{
	pmi_desc d;

	pmi_init(&d);
	CHECK(pmi_file(&d, "a.pbrt") == 0);
	CHECK(pmi_file(&d, "b.pbrt") == 1);
	CHECK(pmi_file(&d, "a.pbrt") == 0);
	pmi_note_add(&d, (pmi_src){ 0, 3 }, "x %d", 1);
	pmi_note_add(&d, (pmi_src){ 1, 9 }, "x %d", 1);
	pmi_note_add(&d, (pmi_src){ 1, 9 }, "y");
	CHECKF(d.nnotes == 2 && d.notes[0].count == 2 && d.notes[0].src.line == 3, "%zu notes", d.nnotes);
	char w[64];
	CHECK(!strcmp(pmi_where(&d, d.notes[1].src, w, sizeof w), "b.pbrt:9"));
	pmi_free(&d);
}

TEST(metals)
{
	double f[3];
	CHECK(pmi_metal_f0("Au", f) == 0 && f[0] > f[1] && f[1] > f[2]);
	CHECK(pmi_metal_f0("Ag", f) == 0 && f[2] > 0.9);
	CHECK(pmi_metal_f0("Xx", f) == -1);
}

int
main(void)
{
	RUN(rotate_is_right_handed);
	RUN(product_order_and_inverse);
	RUN(mirror_keeps_the_front);
	RUN(annulus_and_partial_disk);
	RUN(notes_merge);
	RUN(metals);
	return check_done();
}
