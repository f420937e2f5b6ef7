/* image_adapter.h — between formats/image.c and the OpenImageIO adapter
 * (formats/image_openimageio.cpp), a shared object loaded on the first
 * image read, written or checked (formats/adapter.h says why).
 *
 * The adapter's entry, gb_openimageio_adapter (a gb_adapter_entry), takes
 * a gb_image_host, the gibake functions it calls (which outlive it), and
 * returns its gb_image_adapter.
 */
#ifndef GB_IMAGE_ADAPTER_H
#define GB_IMAGE_ADAPTER_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#include "image.h"
#include "image_check.h"
#include "output_file.h"
#include "result.h"

typedef struct gb_image_host {
    gb_result (*fail)(gb_error *error, gb_result result, const char *format, ...)
        __attribute__((format(printf, 3, 4)));
    gb_result (*check_file)(const char *path, gb_image_file *file, gb_error *error);
    gb_result (*check_size)(const char *path, const gb_image_file *file, long long width,
                            long long height, long long depth, long long channels,
                            gb_error *error);
    gb_result (*allocate)(gb_image *image, int width, int height, int channels,
                          gb_error *error);
    void (*free)(gb_image *image);
    const gb_output_file_functions *output; /* the one output writer */
} gb_image_host;

/* What gb_image_read, gb_image_write and gb_image_check_output do. */
typedef struct gb_image_adapter {
    gb_result (*read)(const char *path, gb_image *image, gb_error *error);
    gb_result (*write)(const char *path, const gb_image *image, gb_error *error);
    gb_result (*check_output)(const char *path, gb_error *error);
} gb_image_adapter;


#ifdef __cplusplus
}
#endif

#endif
