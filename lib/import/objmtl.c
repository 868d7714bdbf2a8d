/* objmtl.c — the Wavefront OBJ reader (readers.h) with its MTL material
 * libraries: v, vt, f (v, v/t, v//n, v/t/n; negative indices count back
 * from the last vertex), o and g, usemtl, mtllib; newmtl, Kd, Ks, Ns, Ke,
 * Ni, d/Tr, Tf, illum, map_Kd. Each run of faces with one object/group and
 * one material becomes a shape; its front is the faces' counter-clockwise
 * side, as OBJ defines. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "import/readers.h"

typedef struct mtl {
	char name[64];
	int index;           /* d->mats */
	double ke[3];
} mtl;

typedef struct objr {
	pmi_desc *d;
	pm_error *err;
	char dir[4096];
	mtl *mtls; int nmtls;
	int cur;             /* mtls index, -1 for the default */
	int default_mat;
	float *v; size_t nv, capv;   /* nv counts floats: 3 per vertex */
	float *vt; size_t nvt, capvt;   /* 2 floats per texture vertex */
	float *vn; size_t nvn, capvn;   /* 3 floats per normal */
	/* the current run of faces, with indices into v, and per corner into
	 * vt and vn (UINT32_MAX for none) */
	uint32_t *fidx; size_t nidx, capidx;
	uint32_t *ftx, *fnx; size_t ntx, captx, nnx, capnx;
	uint32_t *fstart; size_t nface, capface;
	int run_line;
	int geometry_only;   /* materials ignored (Mitsuba's obj shapes) */
} objr;

static int
push(void **a, size_t *n, size_t *cap, size_t sz, const void *item)
{
	if (*n == *cap) {
		size_t nc = *cap ? 2 * *cap : 256;
		void *p = realloc(*a, nc * sz);
		if (!p)
			return -1;
		*a = p;
		*cap = nc;
	}
	memcpy((char *)*a + (*n)++ * sz, item, sz);
	return 0;
}

static int
read_mtl(objr *R, const char *path, pmi_src from)
{
	FILE *f = fopen(path, "r");
	char line[4096];
	int ln = 0, file;
	pmi_material *m = NULL;
	mtl *cur = NULL;

	if (!f)
		return pmi_err(R->d, from, R->err, "mtllib: cannot open '%s': %s", path, strerror(errno));
	if ((file = pmi_file(R->d, path)) < 0) {
		fclose(f);
		return pm_seterr(R->err, "out of memory");
	}
	while (fgets(line, sizeof line, f)) {
		char key[32], rest[4000];
		double a, b, c;
		int k;
		ln++;
		pmi_src at = { file, ln };
		if (sscanf(line, "%31s", key) != 1 || key[0] == '#')
			continue;
		if (!strcmp(key, "newmtl")) {
			mtl *nm = realloc(R->mtls, (R->nmtls + 1) * sizeof *nm);
			if (!nm || !(m = pmi_add_material(R->d, at))) {
				fclose(f);
				if (nm)
					R->mtls = nm;
				return pm_seterr(R->err, "out of memory");
			}
			R->mtls = nm;
			cur = &nm[R->nmtls++];
			memset(cur, 0, sizeof *cur);
			if (sscanf(line, "%*s %63s", cur->name) != 1) {
				fclose(f);
				return pmi_err(R->d, at, R->err, "newmtl: no name");
			}
			cur->index = (int)R->d->nmats - 1;
			m->kind = PMI_MAT_PHONG;
			snprintf(m->name, sizeof m->name, "%s", cur->name);
			snprintf(m->type, sizeof m->type, "mtl");
			m->color[0] = m->color[1] = m->color[2] = 0.8;
			m->trans[0] = m->trans[1] = m->trans[2] = 1;
			m->exponent = 1;
			m->eta = 1.5;
			/* illum is kept in alpha until the end of the material. */
			m->alpha = -1;
			continue;
		}
		if (!m)
			continue;
		k = sscanf(line, "%*s %lf %lf %lf", &a, &b, &c);
		if (k == 1)
			b = c = a;
		double *dst = !strcmp(key, "Kd") ? m->color : !strcmp(key, "Ks") ? m->spec :
		              !strcmp(key, "Ke") ? cur->ke : !strcmp(key, "Tf") ? m->trans : NULL;
		if (dst) {
			if (k != 1 && k != 3) {
				fclose(f);
				return pmi_err(R->d, at, R->err, "%s: expected 1 or 3 numbers", key);
			}
			dst[0] = a; dst[1] = b; dst[2] = c;
		} else if (!strcmp(key, "Ns") && k >= 1)
			m->exponent = a;
		else if (!strcmp(key, "Ni") && k >= 1)
			m->eta = a > 0 ? a : 1.5;
		else if (!strcmp(key, "d") && k >= 1) {
			if (a < 1)
				m->kind = PMI_MAT_DIELECTRIC;
		}
		else if (!strcmp(key, "Tr") && k >= 1)
			m->kind = a > 0 ? PMI_MAT_DIELECTRIC : m->kind;
		else if (!strcmp(key, "illum") && k >= 1) {
			int il = (int)a;
			if (il == 4 || il == 6 || il == 7 || il == 9)
				m->kind = PMI_MAT_DIELECTRIC;
			else if (il == 3 || il == 5)
				m->alpha = -3;   /* mirror-like if it has no diffuse part */
		} else if (!strcmp(key, "map_Kd") && sscanf(line, "%*s %3999[^\r\n]", rest) == 1) {
			/* The file is the last word (options such as -s come first). */
			const char *fn = strrchr(rest, ' ');
			fn = fn ? fn + 1 : rest;
			snprintf(m->texture, sizeof m->texture, "%.255s", fn);
			if (rest[0] == '-')
				pmi_note_add(R->d, at, "map_Kd: options dropped (the image used as it is)");
			pmi_texture *t = pmi_add_texture(R->d, at);
			if (!t)
				return pm_seterr(R->err, "out of memory");
			t->kind = PMI_TEX_IMAGE;
			const char *sl = strrchr(path, '/');
			if (snprintf(t->file, sizeof t->file, "%.*s%s", fn[0] == '/' || !sl ? 0 : (int)(sl - path + 1), path, fn) >=
			    (int)sizeof t->file)
				return pmi_err(R->d, at, R->err, "map_Kd: file name too long");
			m = &R->d->mats[R->mtls[R->nmtls - 1].index];
			m->tex = (int)R->d->ntexs;
		} else if (!strncmp(key, "map_", 4) || !strcmp(key, "bump") || !strcmp(key, "disp") || !strcmp(key, "refl"))
			pmi_note_add(R->d, at, "%s: pm has no model for it, dropped", key);
	}
	fclose(f);
	/* Settle each material's kind now that all its lines are read. */
	for (int i = 0; i < R->nmtls; i++) {
		pmi_material *mm = &R->d->mats[R->mtls[i].index];
		if (mm->kind == PMI_MAT_PHONG && mm->alpha == -3 && mm->color[0] + mm->color[1] + mm->color[2] == 0 &&
		    mm->spec[0] + mm->spec[1] + mm->spec[2] > 0)
			mm->kind = PMI_MAT_CONDUCTOR;
		if (mm->kind == PMI_MAT_DIELECTRIC && mm->alpha == -1)
			pmi_note_add(R->d, mm->src, "material '%s' (mtl): transparency (d, Tr or illum) taken as smooth glass", mm->name);
		mm->alpha = 0;
	}
	return 0;
}

/* The current run of faces as a shape of its own vertices. */
static int
end_run(objr *R, int file)
{
	if (R->nface == 0)
		return 0;
	pmi_shape *s = pmi_add_shape(R->d, (pmi_src){ file, R->run_line });
	if (!s)
		return pm_seterr(R->err, "out of memory");
	size_t nall = R->nv / 3;
	uint32_t *map = malloc((nall ? nall : 1) * sizeof *map);
	if (!map || pmi_mesh_alloc(s, 0, R->nface, R->nidx, 0)) {
		free(map);
		return pm_seterr(R->err, "out of memory");
	}
	for (size_t i = 0; i < nall; i++)
		map[i] = UINT32_MAX;
	size_t nv = 0;
	for (size_t i = 0; i < R->nidx; i++) {
		uint32_t g = R->fidx[i];
		if (map[g] == UINT32_MAX)
			map[g] = (uint32_t)nv++;
		s->idx[i] = map[g];
	}
	free(s->v);
	if (!(s->v = malloc(nv * 3 * sizeof *s->v))) {
		free(map);
		return pm_seterr(R->err, "out of memory");
	}
	for (size_t i = 0; i < nall; i++)
		if (map[i] != UINT32_MAX)
			memcpy(s->v + 3 * (size_t)map[i], R->v + 3 * i, 3 * sizeof *s->v);
	s->nv = nv;
	memcpy(s->start, R->fstart, (R->nface + 1) * sizeof *s->start);
	free(map);
	/* Texture coordinates and normals belong to corners: where the run
	 * has them, every corner gets a vertex of its own (the writer welds
	 * those that agree). Normals are kept only if every corner has one. */
	int has_t = 0, has_n = 1;
	for (size_t i = 0; i < R->nidx; i++) {
		has_t |= R->ftx[i] != UINT32_MAX;
		has_n &= R->fnx[i] != UINT32_MAX;
	}
	if (has_t || has_n) {
		float *v = malloc((R->nidx ? R->nidx : 1) * 3 * sizeof *v);
		float *uv = has_t ? calloc((R->nidx ? R->nidx : 1) * 2, sizeof *uv) : NULL;
		float *n = has_n ? malloc((R->nidx ? R->nidx : 1) * 3 * sizeof *n) : NULL;
		if (!v || (has_t && !uv) || (has_n && !n)) {
			free(v); free(uv); free(n);
			return pm_seterr(R->err, "out of memory");
		}
		for (size_t i = 0; i < R->nidx; i++) {
			memcpy(v + 3 * i, R->v + 3 * (size_t)R->fidx[i], 3 * sizeof *v);
			if (has_t && R->ftx[i] != UINT32_MAX)
				memcpy(uv + 2 * i, R->vt + 2 * (size_t)R->ftx[i], 2 * sizeof *uv);
			if (has_n)
				memcpy(n + 3 * i, R->vn + 3 * (size_t)R->fnx[i], 3 * sizeof *n);
			s->idx[i] = (uint32_t)i;
		}
		free(s->v);
		free(s->uv);
		s->v = v;
		s->uv = uv;
		s->n = n;
		s->nv = R->nidx;
	}
	R->ntx = R->nnx = 0;
	if (R->cur >= 0) {
		s->mat = R->mtls[R->cur].index;
		memcpy(s->emit, R->mtls[R->cur].ke, sizeof s->emit);
	} else {
		if (R->default_mat < 0) {
			pmi_material *m = pmi_add_material(R->d, s->src);
			if (!m)
				return pm_seterr(R->err, "out of memory");
			m->kind = PMI_MAT_DIFFUSE;
			snprintf(m->type, sizeof m->type, "default");
			m->color[0] = m->color[1] = m->color[2] = 0.8;
			R->default_mat = (int)R->d->nmats - 1;
			if (!R->geometry_only)
				pmi_note_add(R->d, s->src, "faces without usemtl: grey diffuse 0.8");
		}
		s = &R->d->shapes[R->d->nshapes - 1];
		s->mat = R->default_mat;
	}
	R->nface = R->nidx = 0;
	R->fstart[0] = 0;
	return 0;
}

static int
read_obj(const char *path, pmi_desc *d, pm_error *err, int geometry_only)
{
	objr R;
	FILE *f;
	char line[65536];
	int ln = 0, file, r = 0;
	uint32_t zero = 0;

	memset(&R, 0, sizeof R);
	R.d = d;
	R.err = err;
	R.cur = -1;
	R.default_mat = -1;
	R.geometry_only = geometry_only;
	const char *sl = strrchr(path, '/');
	if (sl)
		snprintf(R.dir, sizeof R.dir, "%.*s/", (int)(sl - path), path);
	if ((file = pmi_file(d, path)) < 0)
		return pm_seterr(err, "out of memory");
	if (!(f = fopen(path, "r")))
		return pm_seterr(err, "cannot open '%s': %s", path, strerror(errno));
	if (push((void **)&R.fstart, &R.nface, &R.capface, sizeof zero, &zero)) {
		fclose(f);
		return pm_seterr(err, "out of memory");
	}
	R.nface = 0;
	while (!r && fgets(line, sizeof line, f)) {
		char key[32];
		ln++;
		pmi_src at = { file, ln };
		if (!strchr(line, '\n') && !feof(f)) {
			r = pmi_err(d, at, err, "line longer than %zu bytes", sizeof line - 1);
			break;
		}
		if (sscanf(line, "%31s", key) != 1 || key[0] == '#')
			continue;
		if (!strcmp(key, "v")) {
			double x, y, z;
			if (sscanf(line, "%*s %lf %lf %lf", &x, &y, &z) != 3 || !isfinite(x) || !isfinite(y) || !isfinite(z)) {
				r = pmi_err(d, at, err, "v: expected 3 numbers");
				break;
			}
			float p[3] = { (float)x, (float)y, (float)z };
			for (int c = 0; c < 3 && !r; c++)
				if (push((void **)&R.v, &R.nv, &R.capv, sizeof p[0], &p[c]))
					r = pm_seterr(err, "out of memory");
		} else if (!strcmp(key, "f")) {
			size_t nverts = R.nv / 3, nc = 0;
			char *tok = line + 1, *save = NULL;
			if (R.nface == 0)
				R.run_line = ln;
			for (char *t = strtok_r(tok, " \t\r\n", &save); t; t = strtok_r(NULL, " \t\r\n", &save)) {
				char *end;
				long v = strtol(t, &end, 10), vt = 0, vn = 0;
				if (end == t || (*end && *end != '/')) {
					r = pmi_err(d, at, err, "f: bad vertex '%s'", t);
					break;
				}
				/* v/t, v//n, v/t/n */
				if (*end == '/' && end[1] != '/')
					vt = strtol(end + 1, &end, 10);
				if (*end == '/')
					vn = strtol(end + 1, &end, 10);
				long ti = vt < 0 ? (long)(R.nvt / 2) + vt : vt - 1, ni = vn < 0 ? (long)(R.nvn / 3) + vn : vn - 1;
				uint32_t tu = vt && ti >= 0 && ti < (long)(R.nvt / 2) ? (uint32_t)ti : UINT32_MAX;
				uint32_t nu = vn && ni >= 0 && ni < (long)(R.nvn / 3) ? (uint32_t)ni : UINT32_MAX;
				if ((vt && tu == UINT32_MAX) || (vn && nu == UINT32_MAX))
					pmi_note_add(d, at, "f: texture or normal index out of range: ignored");
				if (push((void **)&R.ftx, &R.ntx, &R.captx, sizeof tu, &tu) ||
				    push((void **)&R.fnx, &R.nnx, &R.capnx, sizeof nu, &nu)) {
					r = pm_seterr(err, "out of memory");
					break;
				}
				long idx = v < 0 ? (long)nverts + v : v - 1;
				if (v == 0 || idx < 0 || idx >= (long)nverts) {
					r = pmi_err(d, at, err, "f: vertex index %ld out of range (%zu vertices so far)", v, nverts);
					break;
				}
				uint32_t u = (uint32_t)idx;
				if (push((void **)&R.fidx, &R.nidx, &R.capidx, sizeof u, &u)) {
					r = pm_seterr(err, "out of memory");
					break;
				}
				nc++;
			}
			if (!r && nc < 3)
				r = pmi_err(d, at, err, "f: a face needs at least 3 vertices");
			if (!r) {
				/* fstart holds nface + 1 entries: its push counts them. */
				uint32_t e = (uint32_t)R.nidx;
				size_t n = R.nface + 1;
				if (push((void **)&R.fstart, &n, &R.capface, sizeof e, &e))
					r = pm_seterr(err, "out of memory");
				else
					R.nface++;
			}
		} else if (R.geometry_only && (!strcmp(key, "usemtl") || !strcmp(key, "mtllib"))) {
			;
		} else if (!strcmp(key, "usemtl")) {
			char name[64];
			int i;
			if (sscanf(line, "%*s %63s", name) != 1) {
				r = pmi_err(d, at, err, "usemtl: no name");
				break;
			}
			for (i = 0; i < R.nmtls; i++)
				if (!strcmp(R.mtls[i].name, name))
					break;
			if (i == R.nmtls) {
				r = pmi_err(d, at, err, "usemtl: unknown material '%s'", name);
				break;
			}
			if (i != R.cur) {
				r = end_run(&R, file);
				R.cur = i;
			}
		} else if (!strcmp(key, "o") || !strcmp(key, "g")) {
			r = end_run(&R, file);
		} else if (!strcmp(key, "mtllib")) {
			char *save = NULL, mpath[4200];
			strtok_r(line, " \t\r\n", &save);
			for (char *t = strtok_r(NULL, " \t\r\n", &save); t && !r; t = strtok_r(NULL, " \t\r\n", &save)) {
				snprintf(mpath, sizeof mpath, "%s%s", t[0] == '/' ? "" : R.dir, t);
				r = read_mtl(&R, mpath, at);
			}
		} else if (!strcmp(key, "vt") || !strcmp(key, "vn")) {
			double a[3] = { 0, 0, 0 };
			int k = sscanf(line, "%*s %lf %lf %lf", &a[0], &a[1], &a[2]), want = key[1] == 't' ? 2 : 3;
			if (k < (key[1] == 't' ? 1 : 3) || !isfinite(a[0]) || !isfinite(a[1]) || !isfinite(a[2])) {
				r = pmi_err(d, at, err, "%s: expected %d numbers", key, want);
				break;
			}
			for (int c = 0; c < want && !r; c++) {
				float x = (float)a[c];
				if (key[1] == 't' ? push((void **)&R.vt, &R.nvt, &R.capvt, sizeof x, &x)
				                  : push((void **)&R.vn, &R.nvn, &R.capvn, sizeof x, &x))
					r = pm_seterr(err, "out of memory");
			}
		} else if (!strcmp(key, "s") || !strcmp(key, "l") ||
		           !strcmp(key, "p") || !strcmp(key, "vp") || !strcmp(key, "usemap") || !strcmp(key, "maplib")) {
			;
		} else {
			r = pmi_err(d, at, err, "unknown statement '%s'", key);
		}
	}
	if (!r && ferror(f))
		r = pm_seterr(err, "'%s': read error", path);
	fclose(f);
	if (!r)
		r = end_run(&R, file);
	if (!r && d->nshapes == 0)
		r = pmi_err(d, (pmi_src){ file, 0 }, err, "no faces");
	free(R.mtls);
	free(R.v);
	free(R.vt);
	free(R.vn);
	free(R.ftx);
	free(R.fnx);
	free(R.fidx);
	free(R.fstart);
	return r;
}

int
pmi_read_obj(const char *path, pmi_desc *d, pm_error *err)
{
	return read_obj(path, d, err, 0);
}

int
pmi_read_obj_mesh(const char *path, pmi_shape *s, pm_error *err)
{
	pmi_desc tmp;
	int r;

	pmi_init(&tmp);
	memset(s, 0, sizeof *s);
	if ((r = read_obj(path, &tmp, err, 1)) == 0) {
		size_t nv = 0, nf = 0, nc = 0;
		for (size_t i = 0; i < tmp.nshapes; i++) {
			nv += tmp.shapes[i].nv;
			nf += tmp.shapes[i].nface;
			nc += tmp.shapes[i].start[tmp.shapes[i].nface];
		}
		/* uv and normals where every group has them (a group
		 * without would leave its vertices' undefined). */
		int has_uv = tmp.nshapes > 0, has_n = tmp.nshapes > 0;
		for (size_t i = 0; i < tmp.nshapes; i++) {
			has_uv &= tmp.shapes[i].uv != NULL;
			has_n &= tmp.shapes[i].n != NULL;
		}
		if (pmi_mesh_alloc(s, nv, nf, nc, has_uv) ||
		    (has_n && !(s->n = malloc((nv ? nv : 1) * 3 * sizeof *s->n)))) {
			pmi_shape_free(s);
			r = pm_seterr(err, "out of memory");
		} else {
			size_t ov = 0, of = 0, oc = 0;
			for (size_t i = 0; i < tmp.nshapes; i++) {
				const pmi_shape *t = &tmp.shapes[i];
				memcpy(s->v + 3 * ov, t->v, 3 * t->nv * sizeof *t->v);
				if (has_uv)
					memcpy(s->uv + 2 * ov, t->uv, 2 * t->nv * sizeof *t->uv);
				if (has_n)
					memcpy(s->n + 3 * ov, t->n, 3 * t->nv * sizeof *t->n);
				for (size_t f = 0; f < t->nface; f++)
					s->start[of + f + 1] = (uint32_t)(oc + t->start[f + 1]);
				for (size_t c = 0; c < t->start[t->nface]; c++)
					s->idx[oc + c] = (uint32_t)(ov + t->idx[c]);
				ov += t->nv;
				of += t->nface;
				oc += t->start[t->nface];
			}
		}
	}
	pmi_free(&tmp);
	return r;
}
