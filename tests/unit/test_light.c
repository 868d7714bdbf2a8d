/* test_light.c — the lights that are not surfaces: the power their photons
 * carry against closed forms (spot cones of both falloffs, distant light,
 * constant and image skies), the sky's radiance and density seen by shadow
 * rays against those of its samples, and image files decoded as the scene
 * format says (sRGB 8-bit texels, PFM rows, NaN texels refused). Scenes and
 * images are written to a private temporary directory. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "base/ldseq.h"
#include "optics/light.h"
#include "scene/imagefile.h"
#include "scene/scene.h"

static char dir[64];

static const char *
put(const char *name, const void *data, size_t n)
{
	static char paths[8][256];
	static int k;
	char *path = paths[k++ % 8];
	snprintf(path, 256, "%s/%s", dir, name);
	FILE *f = fopen(path, "wb");
	if (!f) {
		perror(path);
		exit(1);
	}
	fwrite(data, 1, n, f);
	fclose(f);
	return path;
}

/* A floor of 4 x 4 around the origin at y = 0, with the lights given. */
static int
load(pm_scene *s, pm_lights *L, const char *lights, pm_error *err)
{
	char text[4096];
	snprintf(text, sizeof text,
	         "camera eye 0 1 5 look 0 0 0 up 0 1 0 fov 40 size 8 8\n"
	         "material white diffuse albedo 0.5 0.5 0.5\n"
	         "quad white -2 0 -2  -2 0 2  2 0 2  2 0 -2\n%s", lights);
	if (pm_scene_load(s, put("t.pms", text, strlen(text)), err))
		return -1;
	if (pm_lights_build(L, s, s->verts, 0, err)) {
		pm_scene_free(s);
		return -1;
	}
	return 0;
}

/* The mean power of n photons (scrambled Sobol' pairs, light pass style). */
static pm_vec3
photon_mean(const pm_lights *L, int n, pm_vec3 *dirsum)
{
	double acc[3] = {0, 0, 0}, ds[3] = {0, 0, 0};
	for (int i = 0; i < n; i++) {
		float u[6];
		pm_vec3 o, d, nn, p;
		pm_ld_pair(7, 0, (uint64_t)i, &u[0], &u[5]);
		pm_ld_pair(7, 1, (uint64_t)i, &u[1], &u[2]);
		pm_ld_pair(7, 2, (uint64_t)i, &u[3], &u[4]);
		pm_lights_emit_u(L, u, &o, &d, &nn, &p);
		acc[0] += p.x, acc[1] += p.y, acc[2] += p.z;
		ds[0] += d.x, ds[1] += d.y, ds[2] += d.z;
	}
	if (dirsum)
		*dirsum = pm_v3((float)(ds[0] / n), (float)(ds[1] / n), (float)(ds[2] / n));
	return pm_v3((float)(acc[0] / n), (float)(acc[1] / n), (float)(acc[2] / n));
}

static int
near(double a, double b, double rel)
{
	return fabs(a - b) <= rel * fabs(b);
}

TEST(spot_power_smooth)
{
	pm_scene s;
	pm_lights L;
	pm_error err;
	if (load(&s, &L, "spotlight 0 1 0 to 0 0 0 intensity 10 20 30 cone 30 20\n", &err)) {
		CHECKF(0, "%s", err.msg);
		return;
	}
	/* pbrt-v4: I 2 pi ((1 - cos inner) + (cos inner - cos outer) / 2) */
	double ci = cos(20 * PM_PI / 180), co = cos(30 * PM_PI / 180);
	double want = 10 * 2 * PM_PI * ((1 - ci) + (ci - co) / 2);
	pm_vec3 m = photon_mean(&L, 1 << 16, NULL);
	CHECKF(near(L.l[0].power.x, want, 1e-5), "power %g want %g", L.l[0].power.x, want);
	CHECKF(near(m.x, want, 0.002) && near(m.z, 3 * want, 0.002), "photons %g want %g", m.x, want);
	pm_lights_free(&L);
	pm_scene_free(&s);
}

TEST(spot_power_linear)
{
	pm_scene s;
	pm_lights L;
	pm_error err;
	if (load(&s, &L, "spotlight 0 1 0 to 0 0 0 intensity 1 1 1 cone 40 10 falloff linear\n", &err)) {
		CHECKF(0, "%s", err.msg);
		return;
	}
	/* 2 pi times the integral of the factor times sin over the cone, by
	 * Simpson's rule in the angle. */
	double a = 10 * PM_PI / 180, b = 40 * PM_PI / 180, sum = 0;
	int n = 2000;
	for (int i = 0; i <= n; i++) {
		double th = a + (b - a) * i / n, f = (b - th) / (b - a) * sin(th);
		sum += f * (i == 0 || i == n ? 1 : i % 2 ? 4 : 2);
	}
	double want = 2 * PM_PI * ((1 - cos(a)) + sum * (b - a) / n / 3);
	pm_vec3 m = photon_mean(&L, 1 << 16, NULL);
	CHECKF(near(L.l[0].power.y, want, 1e-4), "power %g want %g", L.l[0].power.y, want);
	CHECKF(near(m.y, want, 0.003), "photons %g want %g", m.y, want);
	pm_lights_free(&L);
	pm_scene_free(&s);
}

TEST(spot_edge)
{
	pm_scene s;
	pm_lights L;
	pm_error err;
	if (load(&s, &L, "spotlight 0 1 0 to 0 0 0 intensity 4 4 4 cone 30 20\n", &err)) {
		CHECKF(0, "%s", err.msg);
		return;
	}
	/* Points on the floor at angles 19, 25 and 31 degrees off the axis. */
	float want[3] = {1, 0, 0};
	double c25 = cos(25 * PM_PI / 180), t = (c25 - cos(30 * PM_PI / 180)) / (cos(20 * PM_PI / 180) - cos(30 * PM_PI / 180));
	want[1] = (float)(t * t * (3 - 2 * t));
	int deg[3] = {19, 25, 31};
	for (int k = 0; k < 3; k++) {
		double th = deg[k] * PM_PI / 180;
		pm_vec3 x = pm_v3((float)tan(th), 0, 0), wi, li;
		float dist, pdf;
		int r = pm_lights_sample_u(&L, x, 0.5f, 0.5f, 0.5f, &wi, &dist, &li, &pdf, NULL);
		float got = r ? li.x * dist * dist / 4 : 0;
		CHECKF(fabsf(got - want[k]) < 1e-5f, "%d degrees: factor %g want %g", deg[k], got, want[k]);
	}
	pm_lights_free(&L);
	pm_scene_free(&s);
}

TEST(distant_power)
{
	pm_scene s;
	pm_lights L;
	pm_error err;
	if (load(&s, &L, "distantlight dir 1 -1 0 irradiance 3 3 3\n", &err)) {
		CHECKF(0, "%s", err.msg);
		return;
	}
	/* The floor's bounding sphere has radius 2 sqrt 2 (a little more). */
	double r = L.radius, want = 3 * PM_PI * r * r;
	pm_vec3 d, m = photon_mean(&L, 4096, &d);
	CHECKF(r >= 2 * sqrt(2) && r < 2 * sqrt(2) * 1.01, "radius %g", r);
	CHECKF(near(m.x, want, 1e-5), "photons %g want %g", m.x, want);
	CHECKF(fabsf(d.x - 0.70710678f) < 1e-5f && fabsf(d.y + 0.70710678f) < 1e-5f, "dir %g %g", d.x, d.y);
	pm_vec3 wi, li;
	float dist, pdf;
	CHECK(pm_lights_sample_u(&L, pm_v3(0, 0, 0), 0.3f, 0.2f, 0.1f, &wi, &dist, &li, &pdf, NULL));
	CHECKF(isinf(dist) && pdf == 0 && li.x == 3, "dist %g pdf %g li %g", dist, pdf, li.x);
	pm_lights_free(&L);
	pm_scene_free(&s);
}

/* What a shadow ray needs to stop short of a light's surface across it
 * (direct.c): the cosine at the light point, |wi . n| on either side of a
 * two-sided lamp; 0 for a light without a surface. */
TEST(sample_cosine_at_the_light)
{
	pm_scene s;
	pm_lights L;
	pm_error err;
	if (load(&s, &L, "material lamp diffuse albedo 0 0 0 emit 1 1 1 twosided\n"
	                 "quad lamp -1 2 1  1 2 1  1 2 -1  -1 2 -1\n"
	                 "pointlight 0 1 0 power 25 25 25\n", &err)) {
		CHECKF(0, "%s", err.msg);
		return;
	}
	int area = 0, point = 0;
	for (int k = 0; k < 64; k++) {
		pm_vec3 x = k & 1 ? pm_v3(0.3f, 0.5f, -0.2f) : pm_v3(-0.4f, 3.5f, 0.1f), wi, li;
		float dist, pdf, cosl = -1;
		float u0 = (k + 0.5f) / 64, u1 = (float)((k * 0.618034) - floor(k * 0.618034)), u2 = (k % 8 + 0.5f) / 8;
		if (!pm_lights_sample_u(&L, x, u0, u1, u2, &wi, &dist, &li, &pdf, &cosl))
			continue;
		if (pdf > 0) {
			area++;
			CHECKF(fabsf(cosl - fabsf(wi.y)) < 1e-6f && cosl > 0, "sample %d: cosl %g, |wi.y| %g", k, cosl, fabsf(wi.y));
		} else {
			point++;
			CHECKF(cosl == 0, "sample %d: point light's cosl %g", k, cosl);
		}
	}
	CHECKF(area > 8 && point > 8, "%d area and %d point samples", area, point);
	pm_lights_free(&L);
	pm_scene_free(&s);
}

/* A w x h PFM (rows bottom to top) whose texel (i, j), j from the top,
 * holds f(i, j) in all three channels. */
static const char *
put_pfm(const char *name, int w, int h, float (*f)(int, int))
{
	size_t n = (size_t)w * h * 12 + 64;
	char *b = malloc(n);
	int o = snprintf(b, n, "PF\n%d %d\n-1.0\n", w, h);
	for (int j = h - 1; j >= 0; j--)
		for (int i = 0; i < w; i++)
			for (int c = 0; c < 3; c++) {
				float v = f(i, j);
				memcpy(b + o, &v, 4);
				o += 4;
			}
	const char *p = put(name, b, (size_t)o);
	free(b);
	return p;
}

static float
sky(int i, int j)
{
	return (float)(1 + i + 5 * (j == 0));   /* brighter to the east and the top row */
}

TEST(env_image)
{
	pm_scene s;
	pm_lights L;
	pm_error err;
	put_pfm("sky.pfm", 8, 4, sky);
	if (load(&s, &L, "envlight image sky.pfm scale 2\n", &err)) {
		CHECKF(0, "%s", err.msg);
		return;
	}
	/* pi r^2 times the integral of the radiance: texel by texel. */
	double r = L.radius, want = 0;
	for (int j = 0; j < 4; j++)
		for (int i = 0; i < 8; i++)
			want += 2 * sky(i, j) * (2 * PM_PI / 8) * (cos(PM_PI * j / 4) - cos(PM_PI * (j + 1) / 4));
	want *= PM_PI * r * r;
	pm_vec3 m = photon_mean(&L, 1 << 14, NULL);
	CHECKF(near(L.l[0].power.x, want, 1e-5), "power %g want %g", L.l[0].power.x, want);
	CHECKF(near(m.x, want, 1e-4), "photons %g want %g", m.x, want);
	/* Straight up is the top row, texel 0 of it (u = 0 is -z). */
	float pdf;
	pm_vec3 up = pm_lights_env(&L, pm_norm(pm_v3(0.01f, 1, -0.1f)), &pdf);
	CHECKF(up.x == 2 * 6, "up reads %g", up.x);
	/* Shadow-ray samples: their density is the one the sky reports, and
	 * li = Le / pdf. */
	for (int k = 0; k < 64; k++) {
		pm_vec3 wi, li, le;
		float dist, sp, ep;
		float u1 = (float)((k * 0.618034) - floor(k * 0.618034)), u2 = (k + 0.5f) / 64;
		if (!pm_lights_sample_u(&L, pm_v3(0, 0.5f, 0), 0.5f, u1, u2, &wi, &dist, &li, &sp, NULL))
			continue;
		le = pm_lights_env(&L, wi, &ep);
		CHECKF(near(sp, ep, 1e-3) && near(li.x, le.x / sp, 1e-3), "sample %d: pdf %g vs %g, li %g vs %g",
		       k, sp, ep, li.x, le.x / sp);
	}
	pm_lights_free(&L);
	pm_scene_free(&s);
}

TEST(env_constant)
{
	pm_scene s;
	pm_lights L;
	pm_error err;
	if (load(&s, &L, "envlight radiance 1 2 3\n", &err)) {
		CHECKF(0, "%s", err.msg);
		return;
	}
	double r = L.radius, want = 4 * PM_PI * PM_PI * r * r;
	pm_vec3 d, m = photon_mean(&L, 1 << 14, &d);
	CHECKF(near(m.x, want, 1e-5) && near(m.z, 3 * want, 1e-5), "photons %g want %g", m.x, want);
	CHECKF(pm_len(d) < 0.01f, "mean direction %g", pm_len(d));
	pm_lights_free(&L);
	pm_scene_free(&s);
}

TEST(image_decoding)
{
	/* 8-bit texels are sRGB: 128 decodes to ((128/255 + 0.055)/1.055)^2.4. */
	static const char ppm[] = "P6\n2 1\n255\n\x80\x80\x80\xff\x00\x0a";
	pm_rgbimage im;
	pm_error err;
	if (pm_rgbimage_read(put("g.ppm", ppm, sizeof ppm - 1), &im, &err)) {
		CHECKF(0, "%s", err.msg);
		return;
	}
	double want = pow((128 / 255.0 + 0.055) / 1.055, 2.4);
	CHECKF(im.w == 2 && im.h == 1, "%dx%d", im.w, im.h);
	CHECKF(fabs(im.px[0] - want) < 1e-6 && fabs(im.px[2] - want) < 1e-6, "%g want %g", im.px[0], want);
	CHECKF(im.px[3] == 1 && im.px[4] == 0 && fabs(im.px[5] - 10 / 255.0 / 12.92) < 1e-7, "%g %g %g",
	       im.px[3], im.px[4], im.px[5]);
	pm_rgbimage_free(&im);
	/* Float images as they are, the top row first. */
	if (pm_rgbimage_read(put_pfm("s.pfm", 8, 4, sky), &im, &err)) {
		CHECKF(0, "%s", err.msg);
		return;
	}
	CHECKF(im.px[0] == 6 && im.px[3 * 8 * 3 + 3] == 2, "%g %g", im.px[0], im.px[3 * 8 * 3 + 3]);
	pm_rgbimage_free(&im);
}

static float
nan_texel(int i, int j)
{
	return i == 2 && j == 1 ? NAN : 1;
}

TEST(bad_images)
{
	pm_scene s;
	pm_lights L;
	pm_error err;
	put_pfm("nan.pfm", 4, 2, nan_texel);
	CHECK(load(&s, &L, "envlight image nan.pfm\n", &err) == -1);
	CHECKF(strstr(err.msg, "t.pms:4: envlight: ") && strstr(err.msg, "nan.pfm': texel (2, 1)"), "%s", err.msg);
	CHECK(load(&s, &L, "envlight image missing.exr\n", &err) == -1);
	CHECKF(strstr(err.msg, "t.pms:4: ") && strstr(err.msg, "missing.exr': cannot read image"), "%s", err.msg);
	put("empty.ppm", "P6\n0 0\n255\n", 11);
	CHECK(load(&s, &L, "envlight image empty.ppm\n", &err) == -1);
	CHECKF(strstr(err.msg, "t.pms:4: ") && strstr(err.msg, "empty.ppm'"), "%s", err.msg);
	CHECK(load(&s, &L, "distantlight dir 0 0 0 irradiance 1 1 1\n", &err) == -1);
	CHECKF(strstr(err.msg, "t.pms:4: distantlight: dir must not be zero"), "%s", err.msg);
	CHECK(load(&s, &L, "spotlight 0 1 0 to 0 1 0 intensity 1 1 1 cone 30 20\n", &err) == -1);
	CHECKF(strstr(err.msg, "t.pms:4: spotlight: 'to' is the light's own position"), "%s", err.msg);
	CHECK(load(&s, &L, "envlight radiance 1 1 1\nenvlight radiance 1 1 1\n", &err) == -1);
	CHECKF(strstr(err.msg, "t.pms:5: envlight: a second"), "%s", err.msg);
}

int
main(void)
{
	snprintf(dir, sizeof dir, "/tmp/pm-test-light-XXXXXX");
	if (!mkdtemp(dir)) {
		perror("mkdtemp");
		return 1;
	}
	RUN(spot_power_smooth);
	RUN(spot_power_linear);
	RUN(spot_edge);
	RUN(distant_power);
	RUN(sample_cosine_at_the_light);
	RUN(env_image);
	RUN(env_constant);
	RUN(image_decoding);
	RUN(bad_images);
	static const char *const files[] = {"t.pms", "sky.pfm", "s.pfm", "g.ppm", "nan.pfm", "empty.ppm"};
	char path[300];
	for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
		snprintf(path, sizeof path, "%s/%s", dir, files[i]);
		unlink(path);
	}
	rmdir(dir);
	return check_done();
}
