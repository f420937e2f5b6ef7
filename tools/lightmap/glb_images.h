/* glb_images.h — the images the glTF export embeds (glb_export.h), each a
 * bufferView of the binary chunk:
 *
 *   the lightmap  8-bit sRGB PNG of lightmap / scale, scale its largest
 *                 value (1 for a black lightmap): a reader gets the
 *                 irradiance back as scale · srgb_to_linear(byte / 255).
 *                 sRGB spends the 8 bits evenly in relative terms, so the
 *                 dim parts of the map keep their precision; the PNG read
 *                 back is compared with the lightmap (relative MSE,
 *                 common/image_error.h) and that figure returned.
 *   a texture     a map_Kd file as it is when it is a PNG or a JPEG (by its
 *                 first bytes), else read and encoded as PNG (image.h).
 *
 * The caller owns the builder and the lightmap.
 */
#ifndef GB_GLB_IMAGES_H
#define GB_GLB_IMAGES_H

#include <stdint.h>

#include "glb_builder.h"
#include "image.h"
#include "result.h"

gb_result gb_glb_add_lightmap(gb_glb_builder *builder, const gb_image *lightmap,
                              uint32_t *view, float *scale, double *relative_mse,
                              gb_error *error);
/* *mime: "image/png" or "image/jpeg" (static). */
gb_result gb_glb_add_texture(gb_glb_builder *builder, const char *path, uint32_t *view,
                             const char **mime, gb_error *error);

#endif
