/* scene_shape.c — built-in shapes of the scene format (scene_shape.h). */
#include "scene/scene_shape.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec.h"

static int
alloc(pm_shape *sh, uint32_t nv, uint32_t nf, uint32_t ncorners)
{
	memset(sh, 0, sizeof *sh);
	sh->verts = malloc(3 * (size_t)nv * sizeof *sh->verts);
	sh->face_start = malloc(((size_t)nf + 1) * sizeof *sh->face_start);
	sh->face_vert = malloc((size_t)ncorners * sizeof *sh->face_vert);
	if (!sh->verts || !sh->face_start || !sh->face_vert) {
		pm_shape_free(sh);
		return -1;
	}
	sh->nverts = nv;
	sh->nfaces = nf;
	sh->face_start[0] = 0;
	return 0;
}

static void
set_vert(pm_shape *sh, uint32_t i, double x, double y, double z)
{
	sh->verts[3 * (size_t)i] = x;
	sh->verts[3 * (size_t)i + 1] = y;
	sh->verts[3 * (size_t)i + 2] = z;
}

/* Appends face f with n corners given in v. */
static void
set_face(pm_shape *sh, uint32_t f, const uint32_t *v, uint32_t n)
{
	uint32_t a = sh->face_start[f];
	memcpy(sh->face_vert + a, v, n * sizeof *v);
	sh->face_start[f + 1] = a + n;
}

static pm_dvec3
corner(const double *c, int i)
{
	return pm_dv3(c[3 * i], c[3 * i + 1], c[3 * i + 2]);
}

/* Do segments ab and cd (2-D) cross or touch? */
static int
segments_meet(const double *a, const double *b, const double *c, const double *d)
{
	double d1 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
	double d2 = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
	double d3 = (d[0] - c[0]) * (a[1] - c[1]) - (d[1] - c[1]) * (a[0] - c[0]);
	double d4 = (d[0] - c[0]) * (b[1] - c[1]) - (d[1] - c[1]) * (b[0] - c[0]);
	return ((d1 <= 0 && d2 >= 0) || (d1 >= 0 && d2 <= 0))
		&& ((d3 <= 0 && d4 >= 0) || (d3 >= 0 && d4 <= 0));
}

int
pm_shape_quad_check(const double c[12])
{
	pm_dvec3 o = corner(c, 0), n = pm_dv3(0, 0, 0);
	double size = 0;
	for (int i = 1; i < 3; i++)
		n = pm_dadd(n, pm_dcross(pm_dsub(corner(c, i), o), pm_dsub(corner(c, i + 1), o)));
	for (int i = 0; i < 4; i++)
		for (int j = i + 1; j < 4; j++)
			size = fmax(size, pm_dlen(pm_dsub(corner(c, i), corner(c, j))));
	double len = pm_dlen(n);
	if (!(size > 0) || len / size <= 1e-9 * size)
		return 1;
	pm_dvec3 u = pm_dscale(n, 1 / len);
	pm_dvec3 m = pm_dv3(0, 0, 0);
	for (int i = 0; i < 4; i++)
		m = pm_dadd(m, pm_dscale(corner(c, i), 0.25));
	for (int i = 0; i < 4; i++)
		if (fabs(pm_ddot(pm_dsub(corner(c, i), m), u)) > 1e-5 * size)
			return 2;
	/* Project on the plane and look for crossing opposite edges. */
	pm_dvec3 a = fabs(u.x) < 0.6 ? pm_dv3(1, 0, 0) : pm_dv3(0, 1, 0);
	pm_dvec3 bu = pm_dcross(a, u);
	pm_dvec3 bw = pm_dcross(u, bu);
	double q[4][2];
	for (int i = 0; i < 4; i++) {
		pm_dvec3 d = pm_dsub(corner(c, i), o);
		q[i][0] = pm_ddot(d, bu);
		q[i][1] = pm_ddot(d, bw);
	}
	if (segments_meet(q[0], q[1], q[2], q[3]) || segments_meet(q[1], q[2], q[3], q[0]))
		return 3;
	return 0;
}

const char *
pm_shape_quad_problem(int code)
{
	switch (code) {
	case 1: return "zero area (corners coincide or lie on a line)";
	case 2: return "corners are not coplanar";
	case 3: return "edges cross (give the corners in order around the quad)";
	}
	return "bad quad";
}

int
pm_shape_polygon(pm_shape *sh, const double *c, uint32_t n)
{
	if (alloc(sh, n, 1, n))
		return -1;
	for (uint32_t i = 0; i < n; i++) {
		set_vert(sh, i, c[3 * i], c[3 * i + 1], c[3 * i + 2]);
		sh->face_vert[i] = i;
	}
	sh->face_start[1] = n;
	return 0;
}

int
pm_shape_disk(pm_shape *sh, pm_dvec3 c, pm_dvec3 n, double r)
{
	const uint32_t k = PM_DISK_CORNERS;
	/* A regular k-gon inscribed in radius R has area (k/2) R^2 sin(2 pi/k). */
	double R = r * sqrt(2 * PM_PI / (k * sin(2 * PM_PI / k)));
	pm_dvec3 w = pm_dscale(n, 1 / pm_dlen(n));
	pm_dvec3 a = fabs(w.x) > 0.5 ? pm_dv3(0, 1, 0) : pm_dv3(1, 0, 0);
	pm_dvec3 u = pm_dcross(a, w);
	u = pm_dscale(u, 1 / pm_dlen(u));
	pm_dvec3 v = pm_dcross(w, u);    /* u x v = w: counter-clockwise from the front */

	if (alloc(sh, k, 1, k))
		return -1;
	for (uint32_t i = 0; i < k; i++) {
		double t = 2 * PM_PI * i / k;
		pm_dvec3 p = pm_dadd(c, pm_dadd(pm_dscale(u, R * cos(t)), pm_dscale(v, R * sin(t))));
		set_vert(sh, i, p.x, p.y, p.z);
		sh->face_vert[i] = i;
	}
	sh->face_start[1] = k;
	return 0;
}

int
pm_shape_box(pm_shape *sh, const double c[6])
{
	/* Vertex i has x from bit 0, y from bit 1, z from bit 2. */
	static const uint32_t f[6][4] = {
		{0, 4, 6, 2}, {1, 3, 7, 5},  /* -x, +x */
		{0, 1, 5, 4}, {2, 6, 7, 3},  /* -y, +y */
		{0, 2, 3, 1}, {4, 5, 7, 6},  /* -z, +z */
	};
	if (alloc(sh, 8, 6, 24))
		return -1;
	for (uint32_t i = 0; i < 8; i++)
		set_vert(sh, i, c[(i & 1) ? 3 : 0], c[(i & 2) ? 4 : 1], c[(i & 4) ? 5 : 2]);
	for (uint32_t i = 0; i < 6; i++)
		set_face(sh, i, f[i], 4);
	return 0;
}

int
pm_shape_sphere(pm_shape *sh, const double c[4], int subdiv)
{
	uint32_t bands = 2u << subdiv, slices = 2 * bands;
	uint32_t rings = bands - 1;  /* rings of vertices between the poles */
	uint32_t nv = 2 + rings * slices;
	uint32_t nf = bands * slices;
	uint32_t ncorners = 2 * 3 * slices + 4 * (bands - 2) * slices;
	double r = c[3];
	uint32_t south = nv - 1;

	if (alloc(sh, nv, nf, ncorners))
		return -1;
	set_vert(sh, 0, c[0], c[1] + r, c[2]);
	set_vert(sh, south, c[0], c[1] - r, c[2]);
	for (uint32_t i = 0; i < rings; i++) {
		double th = PM_PI * (i + 1) / bands;
		for (uint32_t j = 0; j < slices; j++) {
			double ph = 2 * PM_PI * j / slices;
			/* -sin(ph) in z: longitude runs counter-clockwise seen
			 * from +y, which makes the faces below face outward. */
			set_vert(sh, 1 + i * slices + j, c[0] + r * sin(th) * cos(ph),
				c[1] + r * cos(th), c[2] - r * sin(th) * sin(ph));
		}
	}
	uint32_t f = 0;
	for (uint32_t j = 0; j < slices; j++) {
		uint32_t j1 = (j + 1) % slices;
		uint32_t top[3] = {0, 1 + j, 1 + j1};
		set_face(sh, f++, top, 3);
	}
	for (uint32_t i = 0; i + 1 < rings; i++)
		for (uint32_t j = 0; j < slices; j++) {
			uint32_t j1 = (j + 1) % slices;
			uint32_t up = 1 + i * slices, lo = up + slices;
			uint32_t q[4] = {up + j, lo + j, lo + j1, up + j1};
			set_face(sh, f++, q, 4);
		}
	for (uint32_t j = 0; j < slices; j++) {
		uint32_t j1 = (j + 1) % slices;
		uint32_t lo = 1 + (rings - 1) * slices;
		uint32_t bot[3] = {south, lo + j1, lo + j};
		set_face(sh, f++, bot, 3);
	}
	return 0;
}

void
pm_shape_free(pm_shape *sh)
{
	free(sh->normals);
	free(sh->uv);
	free(sh->verts);
	free(sh->face_start);
	free(sh->face_vert);
	memset(sh, 0, sizeof *sh);
}
