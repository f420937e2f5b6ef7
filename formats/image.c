/* image.c — the image front (image.h): pixels allocated and freed here,
 * reading, writing and format checks done by the OpenImageIO adapter, a
 * shared object loaded on first use (image_adapter.h, adapter.h). */
#include "image.h"

#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "adapter.h"
#include "image_adapter.h"

gb_result gb_image_allocate(gb_image *image, int width, int height, int channels,
                            gb_error *error)
{
    memset(image, 0, sizeof *image);
    if (width <= 0 || height <= 0 || channels <= 0 || channels > 64 ||
        (uint64_t)width * (uint64_t)height > ((uint64_t)1 << 32))
        return gb_fail(error, GB_ERROR_ARGUMENT, "bad image size %d x %d x %d", width, height,
                       channels);
    size_t values = (size_t)width * (size_t)height * (size_t)channels;
    image->pixels = calloc(values, sizeof(float));
    if (!image->pixels)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (%d x %d image)", width,
                       height);
    image->width = width;
    image->height = height;
    image->channels = channels;
    return GB_OK;
}

void gb_image_free(gb_image *image)
{
    free(image->pixels);
    memset(image, 0, sizeof *image);
}

static const gb_image_host host = {
    .fail = gb_fail,
    .check_file = gb_image_check_file,
    .check_size = gb_image_check_size,
    .allocate = gb_image_allocate,
    .free = gb_image_free,
    .output = &gb_output_file_table,
};

/* Defined only in programs that link the adapter in (adapter.h). */
extern gb_adapter_entry gb_openimageio_adapter __attribute__((weak));

static gb_adapter openimageio =
    GB_ADAPTER_INITIALIZER("openimageio", &host, gb_openimageio_adapter);

static const gb_image_adapter *image_adapter(gb_error *error)
{
    return gb_adapter_functions(&openimageio, error);
}

gb_result gb_image_read(const char *path, gb_image *image, gb_error *error)
{
    memset(image, 0, sizeof *image);
    const gb_image_adapter *adapter = image_adapter(error);
    return adapter ? adapter->read(path, image, error) : GB_ERROR_IO;
}

gb_result gb_image_write(const char *path, const gb_image *image, gb_error *error)
{
    const gb_image_adapter *adapter = image_adapter(error);
    return adapter ? adapter->write(path, image, error) : GB_ERROR_IO;
}

gb_result gb_image_check_output(const char *path, gb_error *error)
{
    const gb_image_adapter *adapter = image_adapter(error);
    return adapter ? adapter->check_output(path, error) : GB_ERROR_IO;
}
