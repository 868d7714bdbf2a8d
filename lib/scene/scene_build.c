/* scene_build.c — the building half of the scene loader (scene_build.h):
 * objects' polygons transformed to world space, cleaned (repeated corners,
 * no area, not planar) and triangulated, into the scene's growing arrays. */
#include "scene/scene_build.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene_poly.h"

/* Bounds on what a scene may ask for; see formats/scene.md. */
#define MAX_MATS 65536
#define MAX_OBJS (1 << 24)
#define MAX_LIGHTS (1 << 20)
#define MAX_VERTS (1u << 28)
#define MAX_POLYS (1u << 28)
#define MAX_TRIS (1u << 28)
#define MAX_POLY_VERTS (1u << 30)   /* polygon corners in all */

/* Grows *arr to hold at least need elements of size elem. */
static int
grow(void *arrp, size_t *cap, size_t need, size_t elem, pm_error *err)
{
	void **arr = arrp;
	if (need <= *cap)
		return 0;
	size_t n = *cap ? *cap : 16;
	while (n < need)
		n = n > SIZE_MAX / 2 ? need : n * 2;
	if (n > SIZE_MAX / elem)
		return pm_seterr(err, "out of memory");
	void *q = realloc(*arr, n * elem);
	if (!q)
		return pm_seterr(err, "out of memory");
	*arr = q;
	*cap = n;
	return 0;
}

void
pm_xform_identity(pm_xform *x)
{
	memset(x, 0, sizeof *x);
	x->m[0][0] = x->m[1][1] = x->m[2][2] = 1;
}

void
pm_xform_then(pm_xform *x, const double a[3][4])
{
	pm_xform r;
	for (int i = 0; i < 3; i++) {
		for (int j = 0; j < 4; j++) {
			double v = j == 3 ? a[i][3] : 0;
			for (int k = 0; k < 3; k++)
				v += a[i][k] * x->m[k][j];
			r.m[i][j] = v;
		}
	}
	*x = r;
}

static double
xform_det(const pm_xform *x)
{
	const double (*m)[4] = x->m;
	return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
		- m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
		+ m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* Appends one element to an array of *n. */
static int
append(void *arrp, size_t *cap, int *n, const void *item, size_t elem, pm_error *err)
{
	if (grow(arrp, cap, (size_t)*n + 1, elem, err))
		return -1;
	memcpy((char *)*(void **)arrp + (size_t)*n * elem, item, elem);
	++*n;
	return 0;
}

int
pm_build_material(pm_scene_build *b, const pm_material *m, pm_error *err)
{
	if (b->s->nmats >= MAX_MATS)
		return pm_seterr(err, "material: more than %d materials", MAX_MATS);
	return append(&b->s->mats, &b->cap_mats, &b->s->nmats, m, sizeof *m, err);
}

int
pm_build_light(pm_scene_build *b, const pm_pointlight *l, pm_error *err)
{
	if (b->s->nlights >= MAX_LIGHTS)
		return pm_seterr(err, "pointlight: more than %d point lights", MAX_LIGHTS);
	return append(&b->s->lights, &b->cap_lights, &b->s->nlights, l, sizeof *l, err);
}

static int
add_polygon(pm_scene_build *b, const uint32_t *idx, uint32_t n, pm_dvec3 nrm, uint32_t obj,
            const char *what, pm_error *err)
{
	pm_scene *s = b->s;
	if (s->npolys >= MAX_POLYS)
		return pm_seterr(err, "%s: more than %u polygons in the scene", what, MAX_POLYS);
	uint32_t first = s->npolys ? s->poly_start[s->npolys] : 0;
	if ((uint64_t)first + n > MAX_POLY_VERTS)
		return pm_seterr(err, "%s: more than %u polygon corners in the scene", what, MAX_POLY_VERTS);
	size_t need = (size_t)s->npolys + 2, c1 = b->cap_polys, c2 = b->cap_polys;
	if (grow(&s->poly_start, &b->cap_polys, need, sizeof *s->poly_start, err)
	    || grow(&s->poly_obj, &c1, need, sizeof *s->poly_obj, err)
	    || grow(&s->poly_normal, &c2, need, sizeof *s->poly_normal, err))
		return -1;
	if (grow(&s->poly_vert, &b->cap_pverts, (size_t)first + n, sizeof *s->poly_vert, err))
		return -1;
	memcpy(s->poly_vert + first, idx, n * sizeof *idx);
	double l = pm_dlen(nrm);
	s->poly_start[s->npolys] = first;
	s->poly_start[s->npolys + 1] = first + n;
	s->poly_obj[s->npolys] = obj;
	s->poly_normal[s->npolys] = pm_v3((float)(nrm.x / l), (float)(nrm.y / l), (float)(nrm.z / l));
	s->npolys++;
	return 0;
}

static int
add_triangle(pm_scene_build *b, const uint32_t t[3], const char *what, pm_error *err)
{
	pm_scene *s = b->s;
	if (s->ntris >= MAX_TRIS)
		return pm_seterr(err, "%s: more than %u triangles in the scene", what, MAX_TRIS);
	size_t c1 = b->cap_tris;
	if (grow(&s->tris, &b->cap_tris, (size_t)s->ntris + 1, sizeof *s->tris, err)
	    || grow(&s->tri_poly, &c1, (size_t)s->ntris + 1, sizeof *s->tri_poly, err))
		return -1;
	memcpy(s->tris[s->ntris], t, sizeof s->tris[0]);
	s->tri_poly[s->ntris] = s->npolys - 1;
	s->ntris++;
	return 0;
}

/* Adds one face (scene vertex indices, already in front winding): drops it
 * if it has no area, keeps it whole if planar, else splits it. */
static int
add_face(pm_scene_build *b, uint32_t *idx, uint32_t n, uint32_t obj, const char *what, pm_error *err)
{
	const pm_vec3 *v = b->s->verts;
	uint32_t m = 0;

	/* Repeated positions in a row (and around the end) would make zero
	 * length edges. */
	for (uint32_t i = 0; i < n; i++) {
		pm_vec3 a = v[idx[i]];
		if (m > 0) {
			pm_vec3 b = v[idx[m - 1]];
			if (a.x == b.x && a.y == b.y && a.z == b.z)
				continue;
		}
		idx[m++] = idx[i];
	}
	while (m > 1) {
		pm_vec3 a = v[idx[m - 1]], b = v[idx[0]];
		if (!(a.x == b.x && a.y == b.y && a.z == b.z))
			break;
		m--;
	}
	if (m < 3 || pm_poly_degenerate(v, idx, m))
		return 0;

	if (grow(&b->work, &b->work_size, PM_POLY_WORK_BYTES(m), 1, err)
	    || grow(&b->tribuf, &b->tribuf_n, m, sizeof *b->tribuf, err))
		return -1;
	pm_dvec3 nrm = pm_poly_newell(v, idx, m);
	uint32_t nt = pm_poly_triangulate(v, idx, m, nrm, b->tribuf, b->work);
	if (pm_poly_planar(v, idx, m, nrm)) {
		if (add_polygon(b, idx, m, nrm, obj, what, err))
			return -1;
		for (uint32_t i = 0; i < nt; i++)
			if (add_triangle(b, b->tribuf[i], what, err))
				return -1;
		return 0;
	}
	/* Not planar: every triangle becomes a polygon of its own. */
	for (uint32_t i = 0; i < nt; i++) {
		if (pm_poly_degenerate(v, b->tribuf[i], 3))
			continue;
		if (add_polygon(b, b->tribuf[i], 3, pm_poly_newell(v, b->tribuf[i], 3), obj, what, err)
		    || add_triangle(b, b->tribuf[i], what, err))
			return -1;
	}
	return 0;
}

/* The object o's texture coordinates into s->vuv, kept as s->vnormal is. */
static int
build_uv(pm_scene_build *b, const pm_build_obj *ob, pm_object *o, pm_error *err)
{
	pm_scene *s = b->s;
	int first = !s->vuv;

	if (!ob->shape->uv && !s->vuv)
		return 0;
	if (grow(&s->vuv, &b->cap_vuv, s->nverts, sizeof *s->vuv, err))
		return -1;
	if (first)
		memset(s->vuv, 0, o->first_vert * sizeof *s->vuv);
	for (uint32_t i = 0; i < o->nverts; i++) {
		const double *t = ob->shape->uv ? ob->shape->uv + 2 * (size_t)i : NULL;
		s->vuv[o->first_vert + i][0] = t && isfinite(t[0]) ? (float)t[0] : 0.0f;
		s->vuv[o->first_vert + i][1] = t && isfinite(t[1]) ? (float)t[1] : 0.0f;
	}
	o->has_uv = ob->shape->uv != NULL;
	return 0;
}

int
pm_build_texture(pm_scene_build *b, const pm_texture *t, pm_error *err)
{
	if (b->s->ntexs >= MAX_MATS)
		return pm_seterr(err, "texture: more than %d textures", MAX_MATS);
	return append(&b->s->texs, &b->cap_texs, &b->s->ntexs, t, sizeof *t, err);
}

/* The object o's shading normals (pm_build_obj.normals) into s->vnormal,
 * which exists from the first smooth object on and is kept as long as
 * s->verts, 0 where an object has none. */
static int
build_normals(pm_scene_build *b, const pm_build_obj *ob, pm_object *o, pm_error *err)
{
	pm_scene *s = b->s;
	size_t had = s->vnormal ? b->cap_vnormal : 0;

	if (ob->normals == PM_NORMALS_FLAT && !s->vnormal)
		return 0;
	if (!s->vnormal)
		had = 0;
	if (grow(&s->vnormal, &b->cap_vnormal, s->nverts, sizeof *s->vnormal, err))
		return -1;
	if (had == 0)
		memset(s->vnormal, 0, o->first_vert * sizeof *s->vnormal);
	pm_vec3 *vn = s->vnormal + o->first_vert;
	memset(vn, 0, o->nverts * sizeof *vn);
	if (ob->normals == PM_NORMALS_SHAPE) {
		/* Normals map by the inverse transpose: the cofactors, signed by
		 * the determinant; an inward object's front is the other side. */
		const double (*m)[4] = ob->xf.m;
		double c[3][3], sg = xform_det(&ob->xf) < 0 ? -1 : 1;
		for (int i = 0; i < 3; i++)
			for (int j = 0; j < 3; j++)
				c[i][j] = m[(i + 1) % 3][(j + 1) % 3] * m[(i + 2) % 3][(j + 2) % 3]
				        - m[(i + 1) % 3][(j + 2) % 3] * m[(i + 2) % 3][(j + 1) % 3];
		if (ob->flip)
			sg = -sg;
		for (uint32_t i = 0; i < o->nverts; i++) {
			const double *x = ob->shape->normals + 3 * (size_t)i;
			pm_dvec3 n = pm_dv3(c[0][0] * x[0] + c[0][1] * x[1] + c[0][2] * x[2],
			                    c[1][0] * x[0] + c[1][1] * x[1] + c[1][2] * x[2],
			                    c[2][0] * x[0] + c[2][1] * x[1] + c[2][2] * x[2]);
			double l = pm_dlen(n);
			if (l > 0 && isfinite(l))
				vn[i] = pm_v3((float)(sg * n.x / l), (float)(sg * n.y / l), (float)(sg * n.z / l));
		}
	} else if (ob->normals == PM_NORMALS_SMOOTH) {
		/* Each polygon's normal weighted by its angle at the vertex
		 * (Thuermer & Wuethrich 1998): independent of how the faces
		 * around a vertex are split. */
		pm_dvec3 *acc = calloc(o->nverts ? o->nverts : 1, sizeof *acc);
		if (!acc)
			return pm_seterr(err, "%s: out of memory", ob->what);
		for (uint32_t p = o->first_poly; p < o->first_poly + o->npolys; p++) {
			uint32_t a = s->poly_start[p], n = s->poly_start[p + 1] - a;
			pm_dvec3 pn = pm_dfromf(s->poly_normal[p]);
			for (uint32_t i = 0; i < n; i++) {
				uint32_t vi = s->poly_vert[a + i];
				pm_dvec3 x = pm_dfromf(s->verts[vi]);
				pm_dvec3 e0 = pm_dsub(pm_dfromf(s->verts[s->poly_vert[a + (i + n - 1) % n]]), x);
				pm_dvec3 e1 = pm_dsub(pm_dfromf(s->verts[s->poly_vert[a + (i + 1) % n]]), x);
				double ang = atan2(pm_dlen(pm_dcross(e0, e1)), pm_ddot(e0, e1));
				acc[vi - o->first_vert] = pm_dadd(acc[vi - o->first_vert], pm_dscale(pn, ang));
			}
		}
		for (uint32_t i = 0; i < o->nverts; i++) {
			double l = pm_dlen(acc[i]);
			if (l > 0 && isfinite(l))
				vn[i] = pm_v3((float)(acc[i].x / l), (float)(acc[i].y / l), (float)(acc[i].z / l));
		}
		free(acc);
	}
	o->smooth = ob->normals != PM_NORMALS_FLAT;
	return 0;
}

int
pm_build_object(pm_scene_build *b, const pm_build_obj *ob, pm_error *err)
{
	pm_scene *s = b->s;
	int flip = ob->flip;
	if (s->nobjs >= MAX_OBJS)
		return pm_seterr(err, "%s: more than %d objects", ob->what, MAX_OBJS);
	if ((uint64_t)s->nverts + ob->shape->nverts > MAX_VERTS)
		return pm_seterr(err, "%s: more than %u vertices in the scene", ob->what, MAX_VERTS);
	if (grow(&s->objs, &b->cap_objs, (size_t)s->nobjs + 1, sizeof *s->objs, err)
	    || grow(&s->verts, &b->cap_verts, (size_t)s->nverts + ob->shape->nverts, sizeof *s->verts, err))
		return -1;

	uint32_t base = s->nverts;
	const double (*m)[4] = ob->xf.m;
	for (uint32_t i = 0; i < ob->shape->nverts; i++) {
		const double *x = ob->shape->verts + 3 * (size_t)i;
		double w[3];
		for (int k = 0; k < 3; k++)
			w[k] = m[k][0] * x[0] + m[k][1] * x[1] + m[k][2] * x[2] + m[k][3];
		pm_vec3 f = pm_v3((float)w[0], (float)w[1], (float)w[2]);
		if (!pm_vfinite(f) || fabs(w[0]) > 3e38 || fabs(w[1]) > 3e38 || fabs(w[2]) > 3e38)
			return pm_seterr(err, "%s: vertex coordinates out of range", ob->what);
		s->verts[base + i] = f;
	}
	s->nverts += ob->shape->nverts;

	/* A mirroring transform turns counter-clockwise into clockwise:
	 * reverse the faces so normals still point the way they did. */
	if (xform_det(&ob->xf) < 0)
		flip = !flip;

	pm_object *o = &s->objs[s->nobjs];
	memset(o, 0, sizeof *o);
	o->material = ob->material;
	o->solid = ob->solid;
	o->motion = ob->motion;
	o->first_poly = s->npolys;
	o->first_tri = s->ntris;
	o->first_vert = base;
	o->nverts = ob->shape->nverts;
	o->line = ob->line;

	uint32_t *idx = NULL;
	size_t cap = 0;
	for (uint32_t f = 0; f < ob->shape->nfaces; f++) {
		uint32_t a = ob->shape->face_start[f], n = ob->shape->face_start[f + 1] - a;
		if (grow(&idx, &cap, n ? n : 1, sizeof *idx, err)) {
			free(idx);
			return -1;
		}
		for (uint32_t i = 0; i < n; i++)
			idx[i] = base + ob->shape->face_vert[a + (flip ? n - 1 - i : i)];
		if (add_face(b, idx, n, (uint32_t)s->nobjs, ob->what, err)) {
			free(idx);
			return -1;
		}
	}
	free(idx);
	o->npolys = s->npolys - o->first_poly;
	o->ntris = s->ntris - o->first_tri;
	if (o->npolys == 0)
		return pm_seterr(err, "%s: no polygon with nonzero area", ob->what);
	if (build_normals(b, ob, o, err) || build_uv(b, ob, o, err))
		return -1;
	s->nobjs++;
	return 0;
}

void
pm_build_free(pm_scene_build *b)
{
	free(b->work);
	free(b->tribuf);
	b->work = NULL;
	b->tribuf = NULL;
}
