/* image.h — reading and writing images (EXR, PNG, JPEG, ...) through
 * OpenImageIO (adapter: formats/image_openimageio.cpp).
 *
 * Pixels are float, linear, interleaved, row 0 at the top. Reading an 8-bit
 * file (PNG, JPEG) converts sRGB to linear; writing an 8-bit file converts
 * linear to sRGB and clamps. The file type follows the extension. Writes go
 * through the one output writer (output_file.h): a temporary and a rename,
 * or straight through to a device or FIFO whose name has the extension;
 * "-" is refused (it names no format).
 *
 * The caller owns the gb_image and frees it with gb_image_free.
 */
#ifndef GB_IMAGE_H
#define GB_IMAGE_H

#include "result.h"

typedef struct gb_image {
    int width, height, channels;
    float *pixels;              /* width * height * channels */
} gb_image;

gb_result gb_image_allocate(gb_image *image, int width, int height, int channels,
                            gb_error *error);
gb_result gb_image_read(const char *path, gb_image *image, gb_error *error);
gb_result gb_image_write(const char *path, const gb_image *image, gb_error *error);
/* Before the work: path's extension names a format OpenImageIO writes
 * ("x.txt: unknown image format ...") and gb_output_file_check passes. */
gb_result gb_image_check_output(const char *path, gb_error *error);
void gb_image_free(gb_image *image);

#endif
