/* pm-import — a pbrt-v4 scene, a Mitsuba 3 XML scene or an OBJ with its
 * MTL to a pm scene: the reader for the input's format fills a description
 * (lib/import/readers.h), the writer turns it into DIR/NAME.pms and the
 * meshes beside it (lib/import/write.h). What could only be approximated
 * or was dropped is printed here and kept as comments in the .pms. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "import/readers.h"
#include "import/write.h"
#include "options.h"
#include "util.h"

static const char usage[] = "pm-import [-h] [-q] [-f pbrt|mitsuba|obj] [-s W H] [-c CAMERA] [--fov DEG] "
                            "INPUT -o DIR/NAME.pms";

enum { OPT_FOV = OPT_LONG };

static const opt opts[] = {
	{ 'c', "camera", "CAMERA", "the camera, as a .pms camera statement's words: "
	  "'eye X Y Z look X Y Z up X Y Z fov DEG' (fov vertical; replaces the file's camera)",
	  "the file's; for OBJ, the framing of --fov", 0 },
	{ 'f', "format", "FORMAT", "read INPUT as pbrt, mitsuba or obj", "by extension: .pbrt, .xml, .obj", 0 },
	{ OPT_FOV, "fov", "DEG", "OBJ without --camera: the view along -z, +y up, that fits the "
	  "geometry's bounding sphere into DEG degrees of the shorter image axis", "40", 0 },
	{ 'o', "output", "DIR/NAME.pms", "the scene to write; its meshes go beside it as NAME-HASH.ply",
	  "none: required", 0 },
	{ 'q', "quiet", NULL, "do not print what was approximated or dropped (the .pms still says)",
	  "print it", 1 },
	{ 's', "size", "W H", "the image size in pixels (two values)", "the file's; 640 480 for OBJ", 0 },
	{ 0, NULL, NULL, NULL, NULL, 0 },
};

static const tool import = {
	usage,
	"Converts a pbrt-v4 scene (.pbrt), a Mitsuba 3 scene (.xml) or a Wavefront OBJ with its MTL\n"
	"(.obj) into a pm scene.",
	opts,
	"Every feature approximated or dropped is printed on stderr as FILE:LINE: note and kept as\n"
	"a comment in the .pms. Outputs appear whole or not at all.\n",
};

/* --camera's words into the description's camera (pm's conventions). */
static void
set_camera(pmi_desc *d, const char *spec)
{
	double eye[3], look[3], up[3], fov;
	char extra[2];

	if (sscanf(spec, " eye %lf %lf %lf look %lf %lf %lf up %lf %lf %lf fov %lf %1s", &eye[0], &eye[1], &eye[2],
	           &look[0], &look[1], &look[2], &up[0], &up[1], &up[2], &fov, extra) != 10)
		usage_err(usage, "--camera: want 'eye X Y Z look X Y Z up X Y Z fov DEG', got '%s'", spec);
	double f[3] = { look[0] - eye[0], look[1] - eye[1], look[2] - eye[2] };
	double r[3] = { f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0] };
	double rl = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
	if (!(rl > 0) || !(fov > 0 && fov < 180))
		usage_err(usage, "--camera: eye equals look, up is parallel to the view, or fov not in (0, 180)");
	pmi_camera *c = &d->cam;
	memcpy(c->pos, eye, sizeof eye);
	memcpy(c->fwd, f, sizeof f);
	memcpy(c->right, r, sizeof r);
	/* True up: right x forward. */
	c->up[0] = r[1] * f[2] - r[2] * f[1];
	c->up[1] = r[2] * f[0] - r[0] * f[2];
	c->up[2] = r[0] * f[1] - r[1] * f[0];
	c->fov = fov;
	c->fov_axis = PMI_FOV_Y;
	c->set = 1;
	c->src = (pmi_src){ 0, 0 };
}

int
main(int argc, char **argv)
{
	const char *out = NULL, *camera = NULL, *format = NULL;
	int quiet = 0, w = 0, h = 0, o;
	double fov = 40;
	pmi_desc d;
	pm_error err;

	opt_init(&import, argc, argv);
	while ((o = opt_next(&import, argc, argv)) != -1) {
		switch (o) {
		case 'c': camera = optarg; break;
		case 'f': format = optarg; break;
		case 'o': out = optarg; break;
		case 'q': quiet = 1; break;
		case 's':
			if (optind >= argc)
				usage_err(usage, "--size: want two numbers, W H");
			w = (int)parse_int(optarg, 1, 65535, "--size", usage);
			h = (int)parse_int(argv[optind++], 1, 65535, "--size", usage);
			break;
		case OPT_FOV: fov = parse_real(optarg, 1e-3, 179, "--fov", usage); break;
		}
	}
	if (argc - optind != 1)
		usage_err(usage, "want one INPUT, got %d", argc - optind);
	if (!out)
		usage_err(usage, "-o DIR/NAME.pms is required");
	const char *dot = strrchr(out, '.');
	if (!dot || strcasecmp(dot, ".pms") != 0 || strchr(dot, '/'))
		usage_err(usage, "'%s': the output is a scene: name it NAME.pms", out);
	if (strcmp(argv[optind], out) == 0)
		usage_err(usage, "'%s' is also the input", out);
	pmi_reader rd = NULL;
	if (format) {
		rd = !strcmp(format, "pbrt") ? pmi_read_pbrt : !strcmp(format, "mitsuba") ? pmi_read_mitsuba
		   : !strcmp(format, "obj") ? pmi_read_obj : NULL;
		if (!rd)
			usage_err(usage, "--format: '%s' is not pbrt, mitsuba or obj", format);
	} else if (!(rd = pmi_reader_for(argv[optind])))
		usage_err(usage, "'%s': unknown format (want .pbrt, .xml or .obj, or give --format)", argv[optind]);

	pmi_init(&d);
	if (rd(argv[optind], &d, &err))
		die_err(&err);
	if (camera)
		set_camera(&d, camera);
	else if (!d.cam.set && pmi_frame_camera(&d, fov, &err))
		die_err(&err);
	if (rd == pmi_read_obj && !d.cam.width) {
		d.cam.width = 640;
		d.cam.height = 480;
	}
	pmi_write_opts wo = { w, h, cmdline() };
	if (pmi_write(&d, out, &wo, &err))
		die_err(&err);
	if (!quiet)
		for (size_t i = 0; i < d.nnotes; i++) {
			char where[300];
			if (d.notes[i].count > 1)
				warn("%s: %s (%d times)", pmi_where(&d, d.notes[i].src, where, sizeof where), d.notes[i].msg,
				     d.notes[i].count);
			else
				warn("%s: %s", pmi_where(&d, d.notes[i].src, where, sizeof where), d.notes[i].msg);
		}
	pmi_free(&d);
	return 0;
}
