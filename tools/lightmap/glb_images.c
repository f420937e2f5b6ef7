/* glb_images.c — the lightmap and the textures as embedded images
 * (glb_images.h). */
#include "glb_images.h"

#include <math.h>
#include <string.h>
#include <stdlib.h>

#include "image_error.h"
#include "mapped_file.h"
#include "png_bytes.h"

static float largest_value(const gb_image *image)
{
    size_t n = (size_t)image->width * image->height * image->channels;
    float largest = 0.0f;
    for (size_t i = 0; i < n; ++i)
        largest = fmaxf(largest, image->pixels[i]);
    return largest;
}

/* The PNG read back, times scale, against the lightmap. */
static gb_result measure(const gb_image *lightmap, gb_image *decoded, float scale,
                         double *relative_mse, gb_error *error)
{
    size_t n = (size_t)decoded->width * decoded->height * decoded->channels;
    for (size_t i = 0; i < n; ++i)
        decoded->pixels[i] *= scale;
    gb_image_error measured;
    gb_result result = gb_image_error_compute(decoded, lightmap, NULL, &measured, error);
    *relative_mse = result == GB_OK ? measured.relative_mse : NAN;
    return result;
}

gb_result gb_glb_add_lightmap(gb_glb_builder *builder, const gb_image *lightmap,
                              uint32_t *view, float *scale, double *relative_mse,
                              gb_error *error)
{
    float largest = largest_value(lightmap);
    *scale = largest > 0.0f ? largest : 1.0f;
    gb_image scaled;
    gb_result result = gb_image_allocate(&scaled, lightmap->width, lightmap->height,
                                         lightmap->channels, error);
    if (result != GB_OK)
        return result;
    size_t n = (size_t)lightmap->width * lightmap->height * lightmap->channels;
    for (size_t i = 0; i < n; ++i)
        scaled.pixels[i] = lightmap->pixels[i] / *scale;
    void *bytes = NULL;
    size_t size = 0;
    gb_image decoded = {0};
    result = gb_png_bytes(&scaled, &bytes, &size, &decoded, error);
    gb_image_free(&scaled);
    if (result == GB_OK)
        result = measure(lightmap, &decoded, *scale, relative_mse, error);
    if (result == GB_OK)
        *view = gb_glb_add_view(builder, bytes, size, 0);
    gb_image_free(&decoded);
    free(bytes);
    return result;
}

static const char *mime_of(const void *bytes, size_t size)
{
    static const unsigned char png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    static const unsigned char jpeg[3] = {0xFF, 0xD8, 0xFF};
    if (size >= sizeof png && !memcmp(bytes, png, sizeof png))
        return "image/png";
    if (size >= sizeof jpeg && !memcmp(bytes, jpeg, sizeof jpeg))
        return "image/jpeg";
    return NULL;
}

/* A texture of another format, read and encoded as PNG. */
static gb_result add_reencoded(gb_glb_builder *builder, const char *path, uint32_t *view,
                               gb_error *error)
{
    gb_image image;
    void *bytes = NULL;
    size_t size = 0;
    gb_result result = gb_image_read(path, &image, error);
    if (result == GB_OK)
        result = gb_png_bytes(&image, &bytes, &size, NULL, error);
    if (result == GB_OK)
        *view = gb_glb_add_view(builder, bytes, size, 0);
    free(bytes);
    gb_image_free(&image);
    return result;
}

gb_result gb_glb_add_texture(gb_glb_builder *builder, const char *path, uint32_t *view,
                             const char **mime, gb_error *error)
{
    gb_mapped_file file;
    gb_result result = gb_mapped_file_open(path, &file, error);
    if (result != GB_OK)
        return result;
    *mime = mime_of(file.bytes, file.size);
    if (*mime)
        *view = gb_glb_add_view(builder, file.bytes, file.size, 0);
    gb_mapped_file_close(&file);
    if (*mime)
        return GB_OK;
    *mime = "image/png";
    return add_reencoded(builder, path, view, error);
}
