/* scene_limits.c — the range of sizes pm resolves (scene_limits.h,
 * formats/scene.md "Range"). Checks are made in double on the values as
 * the scene will hold them (floats), so what passes here is what the ray
 * caster, the kd-tree and the estimates see. */
#include "scene/scene_limits.h"

#include <math.h>

/* x at most (at least) bound, as written in a scene: the float of a bound
 * may lie a rounding beyond it (1e30 as a float is 1.0000000150e30). */
static int
atmost(double x, double bound)
{
	return x <= bound * (1 + 1e-7);
}

static int
atleast(double x, double bound)
{
	return x >= bound * (1 - 1e-7);
}

static int
coord_ok(double c)
{
	return atmost(fabs(c), PM_COORD_MAX);
}

static int
vec_ok(pm_vec3 v)
{
	return coord_ok(v.x) && coord_ok(v.y) && coord_ok(v.z);
}

int
pm_limits_vertex(const double w[3], pm_vec3 motion, const char *what, pm_error *err)
{
	/* At t = 0 and t = 1 (positions in between lie on the segment). */
	for (int k = 0; k < 3; k++) {
		double m = k == 0 ? motion.x : k == 1 ? motion.y : motion.z;
		double a = (float)w[k];
		if (!coord_ok(w[k]) || !coord_ok(a + m))
			return pm_seterr(err, "%s: a vertex%s reaches %.3g, beyond the %g that pm resolves "
			                 "(formats/scene.md, \"Range\")",
			                 what, coord_ok(w[k]) ? " with 'move'" : "",
			                 coord_ok(w[k]) ? a + m : w[k], PM_COORD_MAX);
	}
	return 0;
}

static int
point_ok(pm_vec3 p, const char *stmt, const char *word, pm_error *err)
{
	if (vec_ok(p))
		return 0;
	return pm_seterr(err, "%s: %s (%.3g %.3g %.3g) is beyond the %g that pm resolves "
	                 "(formats/scene.md, \"Range\")", stmt, word, p.x, p.y, p.z, PM_COORD_MAX);
}

int
pm_limits_camera(const pm_camera_desc *c, pm_error *err)
{
	if (point_ok(c->eye, "camera", "eye", err) || point_ok(c->look, "camera", "look", err)
	    || point_ok(c->up, "camera", "up", err))
		return -1;
	pm_dvec3 f = pm_dsub(pm_dfromf(c->look), pm_dfromf(c->eye));
	double fl = pm_dlen(f), ul = pm_dlen(pm_dfromf(c->up));
	double mag = fmax(pm_dlen(pm_dfromf(c->eye)), pm_dlen(pm_dfromf(c->look)));
	/* The view direction is computed in float from look - eye. */
	if (fl > 0 && !(atleast(fl, PM_DIRECTION_MIN) && fl >= 1e-6 * mag))
		return pm_seterr(err, "camera: look is only %.3g from eye (at least %g, and 1e-6 of "
		                 "their magnitude; formats/scene.md, \"Range\")", fl, PM_DIRECTION_MIN);
	if (ul > 0 && !atleast(ul, PM_DIRECTION_MIN))
		return pm_seterr(err, "camera: up is %.3g long, shorter than %g "
		                 "(formats/scene.md, \"Range\")", ul, PM_DIRECTION_MIN);
	if (!(atleast(c->fov, PM_FOV_MIN) && atmost(c->fov, PM_FOV_MAX)))
		return pm_seterr(err, "camera: fov %.9g is outside %g to %g degrees "
		                 "(formats/scene.md, \"Range\")",
		                 c->fov, PM_FOV_MIN, PM_FOV_MAX);
	return 0;
}

int
pm_limits_material(const pm_material *m, const char *what, pm_error *err)
{
	if (!atmost(pm_maxc(m->emit), PM_RADIANCE_MAX))
		return pm_seterr(err, "%s: emit %.3g is more than the %g that pm carries in float "
		                 "(formats/scene.md, \"Range\")", what, pm_maxc(m->emit), PM_RADIANCE_MAX);
	return 0;
}

static const char *
light_name(int kind)
{
	return kind == PM_LIGHT_SPOT ? "spotlight" : kind == PM_LIGHT_DISTANT ? "distantlight"
	     : kind == PM_LIGHT_ENV ? "envlight" : "pointlight";
}

/* What a light's 'power' field holds, by kind: W, W/sr, W/m^2 or W/m^2/sr;
 * each is bounded by the same 1e30, and by its real power in the total. */
static const char *
light_unit(int kind)
{
	return kind == PM_LIGHT_SPOT ? "W/sr" : kind == PM_LIGHT_DISTANT ? "W/m^2"
	     : kind == PM_LIGHT_ENV ? "W/m^2/sr" : "W";
}

static const char *
light_quantity(int kind)
{
	return kind == PM_LIGHT_SPOT ? "intensity" : kind == PM_LIGHT_DISTANT ? "irradiance"
	     : kind == PM_LIGHT_ENV ? "radiance" : "power";
}

static int
positional(int kind)
{
	return kind == PM_LIGHT_POINT || kind == PM_LIGHT_SPOT;
}

int
pm_limits_light(const pm_pointlight *l, pm_error *err)
{
	const char *what = light_name(l->kind);

	if (positional(l->kind) && point_ok(l->pos, what, "the position", err))
		return -1;
	if (!atmost(pm_maxc(l->power), PM_POWER_MAX))
		return pm_seterr(err, "%s: %s %.3g %s is more than the %g that pm carries "
		                 "in float (formats/scene.md, \"Range\")", what,
		                 light_quantity(l->kind), pm_maxc(l->power),
		                 light_unit(l->kind), PM_POWER_MAX);
	if (positional(l->kind) && (!vec_ok(pm_add(l->pos, l->motion)) || !vec_ok(l->motion)))
		return pm_seterr(err, "%s: 'move' takes it beyond the %g that pm resolves "
		                 "(formats/scene.md, \"Range\")", what, PM_COORD_MAX);
	return 0;
}

/* The largest texel of an environment image (1 for a constant sky). */
static double
env_peak(const pm_pointlight *l)
{
	double m = 1;

	if (l->env) {
		m = 0;
		for (size_t i = 0; i < (size_t)l->env_w * l->env_h * 3; i++)
			m = fmax(m, l->env[i]);
	}
	return m;
}

static void
grow_box(double lo[3], double hi[3], pm_vec3 p)
{
	for (int k = 0; k < 3; k++) {
		double c = pm_vget(p, k);
		lo[k] = fmin(lo[k], c);
		hi[k] = fmax(hi[k], c);
	}
}

int
pm_limits_scene(const pm_scene *s, pm_error *err)
{
	double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
	for (int o = 0; o < s->nobjs; o++) {
		const pm_object *ob = &s->objs[o];
		for (uint32_t i = ob->first_vert; i < ob->first_vert + ob->nverts; i++) {
			grow_box(lo, hi, s->verts[i]);
			grow_box(lo, hi, pm_add(s->verts[i], ob->motion));
		}
	}
	for (int i = 0; i < s->nlights; i++) {
		if (!positional(s->lights[i].kind))
			continue;
		grow_box(lo, hi, s->lights[i].pos);
		grow_box(lo, hi, pm_add(s->lights[i].pos, s->lights[i].motion));
	}
	double d = 0;
	for (int k = 0; k < 3; k++)
		d = fmax(d, hi[k] - lo[k]);
	if (s->nverts > 0 && !atleast(d, PM_EXTENT_MIN))
		return pm_seterr(err, "the scene is %.3g across, less than the %g that pm resolves "
		                 "(scale it up; formats/scene.md, \"Range\")", d, PM_EXTENT_MIN);
	/* Power against the extent: a point or spot light's, and the whole
	 * scene's. A spot light emits at most 4 pi times its intensity; the sun
	 * and the sky reach the scene through a disk of its bounding sphere's
	 * radius r: E pi r^2 and L pi^2 r^2 (times the image's largest texel). */
	double d2 = d * d, r2 = 0.75 * d2, total[3] = {0, 0, 0};
	for (int i = 0; i < s->nlights; i++) {
		const pm_pointlight *l = &s->lights[i];
		double f = l->kind == PM_LIGHT_SPOT ? 4 * PM_PI
		         : l->kind == PM_LIGHT_DISTANT ? PM_PI * r2
		         : l->kind == PM_LIGHT_ENV ? PM_PI * PM_PI * r2 * env_peak(l) : 1;
		pm_vec3 pw = l->power;
		/* (with no geometry, nothing is lit) */
		if (positional(l->kind) && s->nverts > 0 && !atmost(f * pm_maxc(pw), PM_RADIANCE_MAX * d2))
			return pm_seterr(err, "%s %d of the file: power %.3g is more than %g times "
			                 "the scene's extent squared (%.3g across; formats/scene.md, \"Range\")",
			                 light_name(l->kind), i + 1, f * pm_maxc(pw), PM_RADIANCE_MAX, d);
		total[0] += f * pw.x, total[1] += f * pw.y, total[2] += f * pw.z;
	}
	for (uint32_t t = 0; t < s->ntris; t++) {
		const pm_material *m = &s->mats[s->objs[s->poly_obj[s->tri_poly[t]]].material];
		if (!(pm_maxc(m->emit) > 0))
			continue;
		pm_dvec3 a = pm_dfromf(s->verts[s->tris[t][0]]);
		double area = 0.5 * pm_dlen(pm_dcross(pm_dsub(pm_dfromf(s->verts[s->tris[t][1]]), a),
		                                      pm_dsub(pm_dfromf(s->verts[s->tris[t][2]]), a)));
		double w = PM_PI * area * (m->emit_twosided ? 2 : 1);
		total[0] += w * m->emit.x, total[1] += w * m->emit.y, total[2] += w * m->emit.z;
	}
	double tmax = fmax(total[0], fmax(total[1], total[2]));
	if (!atmost(tmax, PM_POWER_MAX))
		return pm_seterr(err, "the lights emit %.3g W in all, more than the %g that pm carries "
		                 "in float (formats/scene.md, \"Range\")", tmax, PM_POWER_MAX);
	return 0;
}
