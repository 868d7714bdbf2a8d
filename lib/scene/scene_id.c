/* scene_id.c — the scene identities of scene_id.h: FNV-1a over a canonical
 * little-endian encoding of the parsed scene, so that two files that parse
 * to the same values have the same identity however they are written. */
#include "scene/scene_id.h"

#include <string.h>

#include "base/fnv.h"

static uint64_t
put_u32(uint64_t h, uint32_t v)
{
	unsigned char b[4] = {(unsigned char)v, (unsigned char)(v >> 8), (unsigned char)(v >> 16),
	                      (unsigned char)(v >> 24)};
	return pm_fnv1a(h, b, sizeof b);
}

/* A float by its bits, with -0 taken as +0 (they compare equal and light
 * the same). */
static uint64_t
put_f32(uint64_t h, float f)
{
	uint32_t u;
	f += 0.0f;
	memcpy(&u, &f, sizeof u);
	return put_u32(h, u);
}

static uint64_t
put_vec(uint64_t h, pm_vec3 v)
{
	return put_f32(put_f32(put_f32(h, v.x), v.y), v.z);
}

static uint64_t
light_identity(const pm_scene *s)
{
	uint64_t h = PM_FNV_OFFSET;

	h = put_f32(h, s->glossy_threshold);
	h = put_u32(h, (uint32_t)s->nmats);
	for (int i = 0; i < s->nmats; i++) {
		const pm_material *m = &s->mats[i];
		h = put_u32(h, (uint32_t)m->kind);
		h = put_vec(put_vec(h, m->kd), m->ks);
		h = put_f32(put_f32(h, m->exponent), m->ior);
		h = put_vec(h, m->emit);
		h = put_u32(h, (uint32_t)m->emit_twosided);
	}
	h = put_u32(h, (uint32_t)s->nobjs);
	for (int i = 0; i < s->nobjs; i++) {
		const pm_object *o = &s->objs[i];
		h = put_u32(put_u32(h, (uint32_t)o->material), (uint32_t)o->solid);
		h = put_vec(h, o->motion);
		h = put_u32(put_u32(h, o->npolys), o->nverts);
	}
	h = put_u32(h, (uint32_t)s->nlights);
	for (int i = 0; i < s->nlights; i++) {
		const pm_pointlight *l = &s->lights[i];
		h = put_vec(put_vec(put_vec(h, l->pos), l->power), l->motion);
		if (l->kind == PM_LIGHT_POINT)
			continue;
		h = put_u32(put_vec(put_u32(h, (uint32_t)l->kind), l->dir), (uint32_t)l->falloff);
		h = put_f32(put_f32(h, l->outer), l->inner);
		if (!l->env)
			continue;
		h = put_u32(put_u32(h, (uint32_t)l->env_w), (uint32_t)l->env_h);
		for (int r = 0; r < 3; r++)
			for (int c = 0; c < 3; c++)
				h = put_f32(h, l->rot[r][c]);
		for (size_t k = 0; k < (size_t)l->env_w * l->env_h * 3; k++)
			h = put_f32(h, l->env[k]);
	}
	h = put_u32(h, s->nverts);
	for (uint32_t i = 0; i < s->nverts; i++)
		h = put_vec(h, s->verts[i]);
	/* Polygons as corner lists; their triangles and normals follow from
	 * these by fixed rules (formats/scene.md). */
	h = put_u32(h, s->npolys);
	for (uint32_t i = 0; i < s->npolys; i++) {
		h = put_u32(h, s->poly_start[i + 1] - s->poly_start[i]);
		for (uint32_t j = s->poly_start[i]; j < s->poly_start[i + 1]; j++)
			h = put_u32(h, s->poly_vert[j]);
	}
	/* Shading normals only where some object has them, so that the
	 * identities of scenes without stay what they were. */
	if (s->vnormal)
		for (uint32_t i = 0; i < s->nverts; i++)
			h = put_vec(h, s->vnormal[i]);
	/* Textures likewise: only in scenes that have them. */
	if (s->ntexs > 0) {
		h = put_u32(h, (uint32_t)s->ntexs);
		for (int i = 0; i < s->ntexs; i++) {
			const pm_texture *t = &s->texs[i];
			h = put_u32(put_u32(put_u32(h, (uint32_t)t->kind), (uint32_t)t->w), (uint32_t)t->h);
			for (size_t k = 0; k < (size_t)t->w * t->h * 3; k++)
				h = put_f32(h, t->px[k]);
			h = put_vec(put_vec(h, t->c1), t->c2);
			h = put_f32(put_f32(put_f32(put_f32(h, t->su), t->sv), t->ou), t->ov);
		}
		for (int i = 0; i < s->nmats; i++)
			h = put_u32(put_u32(put_u32(h, (uint32_t)s->mats[i].tkd), (uint32_t)s->mats[i].tks),
			            (uint32_t)s->mats[i].texp);
		for (uint32_t i = 0; s->vuv && i < s->nverts; i++)
			h = put_f32(put_f32(h, s->vuv[i][0]), s->vuv[i][1]);
	}
	return h;
}

void
pm_scene_identify(pm_scene *s)
{
	const pm_camera_desc *c = &s->camera;
	uint64_t h;

	s->light_hash = light_identity(s);
	h = put_u32(put_u32(PM_FNV_OFFSET, (uint32_t)s->light_hash), (uint32_t)(s->light_hash >> 32));
	h = put_vec(put_vec(put_vec(h, c->eye), c->look), c->up);
	h = put_f32(h, c->fov);
	s->view_hash = put_u32(put_u32(h, (uint32_t)c->width), (uint32_t)c->height);
}
