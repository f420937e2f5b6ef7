/* png_bytes.h — an image encoded as PNG in memory, for embedding in the
 * glTF binary (glb_export.h), through image.h (OpenImageIO: 8-bit sRGB,
 * clamped to [0, 1], as every PNG gibake writes). image.h encodes to files
 * only, so the PNG goes through a private temporary folder ($TMPDIR, else
 * /tmp), removed before the call returns.
 *
 * decoded, when not NULL, gets the PNG read back (linear, as image.h reads
 * 8-bit files), so that the caller can measure what the encoding lost.
 * The caller owns *bytes (free) and decoded (gb_image_free).
 */
#ifndef GB_PNG_BYTES_H
#define GB_PNG_BYTES_H

#include <stddef.h>

#include "image.h"
#include "result.h"

gb_result gb_png_bytes(const gb_image *image, void **bytes, size_t *size, gb_image *decoded,
                       gb_error *error);

#endif
