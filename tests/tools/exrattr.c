/* exrattr — prints an EXR's string attribute for tests; exits 1 if absent.
 * With no KEY, prints every attribute as "KEY=VALUE" and the channels as
 * "channel NAME" lines, in file order.
 * Usage: exrattr FILE.exr [KEY] */
#include <stdio.h>

#include "formats/image.h"

int
main(int argc, char **argv)
{
	pm_image img;
	pm_error err;
	const char *v;

	if (argc != 2 && argc != 3) {
		fprintf(stderr, "usage: exrattr FILE.exr [KEY]\n");
		return 2;
	}
	if (pm_image_read_exr(&img, argv[1], &err)) {
		fprintf(stderr, "exrattr: %s\n", err.msg);
		return 1;
	}
	if (argc == 3) {
		int found = (v = pm_image_attr(&img, argv[2])) != NULL;
		if (found)
			printf("%s\n", v);
		pm_image_free(&img);
		return !found;
	}
	for (int i = 0; i < img.nattr; i++)
		printf("%s=%s\n", img.attr[i].key, img.attr[i].value);
	for (int c = 0; c < img.nchan; c++)
		printf("channel %s\n", img.chan[c]);
	pm_image_free(&img);
	return 0;
}
