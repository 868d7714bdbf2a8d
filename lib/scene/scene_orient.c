/* scene_orient.c — which side of a closed surface is matter (scene_orient.h).
 *
 * Renderers that treat every surface as two-sided (pbrt-v4, Mitsuba 3 with
 * twosided BSDFs) let a room be modelled as a cube whose faces point out,
 * with the camera and lamps inside it. pm takes a closed surface for a
 * solid whose matter lies behind its faces, and the compensated estimate
 * counts on that, so such a room would have its air taken for matter. The
 * camera does not look out of matter, and every point pm estimates at is
 * seen from the air around the eye (directly, through mirrors and glass,
 * or by a gather ray), so a closed surface round the eye is the inside of a
 * room: it is turned over, as 'box ... inward' writes one.
 *
 * Lights would not do as the judge: a lamp shut inside a closed solid (by
 * mistake, or in a lantern) lights its inside while the camera sees its
 * outside, and a closed room in a scene with a sun has light on both
 * sides. */
#include "scene/scene_orient.h"

#include <math.h>

#include "base/vec.h"

/* The winding number of o's triangles about p: the sum of their signed
 * solid angles over 4 pi (Van Oosterom and Strackee 1983). 1 inside a
 * closed surface whose faces point out, -1 inside one whose faces point
 * in, 0 outside, in between only on the surface. */
static double
winding(const pm_scene *s, const pm_object *o, pm_dvec3 p)
{
	double sum = 0;
	for (uint32_t t = o->first_tri; t < o->first_tri + o->ntris; t++) {
		pm_dvec3 a = pm_dsub(pm_dfromf(s->verts[s->tris[t][0]]), p);
		pm_dvec3 b = pm_dsub(pm_dfromf(s->verts[s->tris[t][1]]), p);
		pm_dvec3 c = pm_dsub(pm_dfromf(s->verts[s->tris[t][2]]), p);
		double la = pm_dlen(a), lb = pm_dlen(b), lc = pm_dlen(c);
		double num = pm_ddot(a, pm_dcross(b, c));
		double den = la * lb * lc + pm_ddot(a, b) * lc + pm_ddot(a, c) * lb + pm_ddot(b, c) * la;
		sum += 2 * atan2(num, den);
	}
	return sum / (4 * PM_PI);
}

/* p inside o as wound: in its box, and clearly so (not on its surface). */
static int
holds(const pm_scene *s, const pm_object *o, pm_vec3 p)
{
	float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
	for (uint32_t v = o->first_vert; v < o->first_vert + o->nverts; v++)
		for (int k = 0; k < 3; k++) {
			lo[k] = fminf(lo[k], pm_vget(s->verts[v], k));
			hi[k] = fmaxf(hi[k], pm_vget(s->verts[v], k));
		}
	for (int k = 0; k < 3; k++)
		if (!(pm_vget(p, k) >= lo[k] && pm_vget(p, k) <= hi[k]))
			return 0;
	return winding(s, o, pm_dfromf(p)) > 0.75;
}

static void
turn_over(pm_scene *s, const pm_object *o)
{
	for (uint32_t g = o->first_poly; g < o->first_poly + o->npolys; g++) {
		uint32_t *c = s->poly_vert + s->poly_start[g];
		for (uint32_t i = 0, j = s->poly_start[g + 1] - s->poly_start[g] - 1; i < j; i++, j--) {
			uint32_t t = c[i];
			c[i] = c[j];
			c[j] = t;
		}
		s->poly_normal[g] = pm_neg(s->poly_normal[g]);
	}
	for (uint32_t t = o->first_tri; t < o->first_tri + o->ntris; t++) {
		uint32_t x = s->tris[t][1];
		s->tris[t][1] = s->tris[t][2];
		s->tris[t][2] = x;
	}
	if (s->vnormal && o->smooth)
		for (uint32_t v = o->first_vert; v < o->first_vert + o->nverts; v++)
			s->vnormal[v] = pm_neg(s->vnormal[v]);
}

void
pm_scene_orient_solids(pm_scene *s)
{
	for (int i = 0; i < s->nobjs; i++) {
		const pm_object *o = &s->objs[i];
		const pm_material *m = &s->mats[o->material];
		/* A one-sided emitter's front says where it shines; glass and
		 * mirrors have no photon estimate to mislead. Both stay as
		 * written. */
		if (!o->solid || !pm_mat_is_photon_surface(m) || (pm_maxc(m->emit) > 0 && !m->emit_twosided))
			continue;
		if (holds(s, o, s->camera.eye))
			turn_over(s, o);
	}
}
