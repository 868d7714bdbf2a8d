/* pngpix — reads a PNG back for tests: prints "WIDTH HEIGHT" and, with X Y,
 * the pixel's "R G B" as 8-bit values (libpng's simplified reader).
 * Usage: pngpix FILE.png [X Y] */
#include <png.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int
main(int argc, char **argv)
{
	png_image im;
	unsigned char *buf;
	int x, y;

	if (argc != 2 && argc != 4) {
		fprintf(stderr, "usage: pngpix FILE.png [X Y]\n");
		return 2;
	}
	memset(&im, 0, sizeof im);
	im.version = PNG_IMAGE_VERSION;
	if (!png_image_begin_read_from_file(&im, argv[1])) {
		fprintf(stderr, "pngpix: '%s': %s\n", argv[1], im.message);
		return 1;
	}
	im.format = PNG_FORMAT_RGB;
	buf = malloc(PNG_IMAGE_SIZE(im));
	if (!buf || !png_image_finish_read(&im, NULL, buf, 0, NULL)) {
		fprintf(stderr, "pngpix: '%s': %s\n", argv[1], im.message);
		return 1;
	}
	printf("%u %u\n", im.width, im.height);
	if (argc == 4) {
		x = atoi(argv[2]);
		y = atoi(argv[3]);
		if (x < 0 || y < 0 || (unsigned)x >= im.width || (unsigned)y >= im.height) {
			free(buf);
			return 1;
		}
		printf("%d %d %d\n", buf[(y * im.width + x) * 3], buf[(y * im.width + x) * 3 + 1],
		       buf[(y * im.width + x) * 3 + 2]);
	}
	free(buf);
	return 0;
}
