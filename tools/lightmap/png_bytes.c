/* png_bytes.c — PNG in memory through a temporary file (png_bytes.h). */
#include "png_bytes.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mapped_file.h"

static gb_result copy_file(const char *path, void **bytes, size_t *size, gb_error *error)
{
    gb_mapped_file file;
    gb_result result = gb_mapped_file_open(path, &file, error);
    if (result != GB_OK)
        return result;
    *bytes = malloc(file.size ? file.size : 1);
    if (*bytes) {
        memcpy(*bytes, file.bytes, file.size);
        *size = file.size;
    } else {
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "lightmap: out of memory");
    }
    gb_mapped_file_close(&file);
    return result;
}

gb_result gb_png_bytes(const gb_image *image, void **bytes, size_t *size, gb_image *decoded,
                       gb_error *error)
{
    *bytes = NULL;
    *size = 0;
    if (decoded)
        memset(decoded, 0, sizeof *decoded);
    const char *tmp = getenv("TMPDIR");
    char folder[4096], path[4200];
    snprintf(folder, sizeof folder, "%s/gibake-png.XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(folder))
        return gb_fail(error, GB_ERROR_IO, "%s: cannot make a temporary folder", folder);
    snprintf(path, sizeof path, "%s/image.png", folder);
    gb_result result = gb_image_write(path, image, error);
    if (result == GB_OK)
        result = copy_file(path, bytes, size, error);
    if (result == GB_OK && decoded)
        result = gb_image_read(path, decoded, error);
    if (result != GB_OK) {
        free(*bytes);
        *bytes = NULL;
        *size = 0;
    }
    unlink(path);
    rmdir(folder);
    return result;
}
