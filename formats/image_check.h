/* image_check.h — an image file looked at before the OpenImageIO adapter
 * (formats/image_openimageio.cpp) hands it to OpenImageIO.
 *
 * Given a file it does not recognise by its extension, OpenImageIO tries
 * every reader it has (DPX, FITS, PSD, ...), each of them a way for a
 * malformed file to reach code gibake never meant to run; its PNG reader
 * leaks memory when a file ends early (a string is skipped by libpng's
 * longjmp); and a header may declare any size. So:
 *
 *  - the format is found from the file's first bytes, and only PNG, JPEG,
 *    OpenEXR, Radiance HDR, TIFF, BMP and netpbm (P1-P6) are accepted (TGA,
 *    which has no magic, when the name ends in .tga); the adapter then opens
 *    the file with that one reader;
 *  - a PNG's chunks are walked up to IEND: each must lie inside the file;
 *  - an OpenEXR header is walked before the OpenEXR library allocates what
 *    it declares: every attribute (and a preview's or a string vector's
 *    inner sizes) inside the file, the offset table (8 bytes a chunk) too,
 *    the data window within the size bound below; deep images are refused;
 *  - gb_image_check_size refuses, once the header is read, an image whose
 *    values (pixels x channels) exceed 4096 per byte of the file and 2^24
 *    (no format gibake reads compresses more than about 1000:1, so only a
 *    lying header gets there), images of depth other than 1, and sizes
 *    gb_image cannot hold.
 *
 * Messages read "path: what is wrong".
 */
#ifndef GB_IMAGE_CHECK_H
#define GB_IMAGE_CHECK_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#include "result.h"

typedef struct gb_image_file {
    const char *format;         /* OpenImageIO's name: "png", "jpeg", "openexr", "hdr",
                                   "tiff", "bmp", "pnm" or "targa" (static strings) */
    unsigned long long size;    /* bytes */
} gb_image_file;

/* bytes of the file at path (path for the .tga rule and messages). */
gb_result gb_image_check(const void *bytes, size_t size, const char *path,
                         gb_image_file *file, gb_error *error);
/* The same on the file at path (mapped, not copied). */
gb_result gb_image_check_file(const char *path, gb_image_file *file, gb_error *error);
/* The header's size against the file's. */
gb_result gb_image_check_size(const char *path, const gb_image_file *file, long long width,
                              long long height, long long depth, long long channels,
                              gb_error *error);

#ifdef __cplusplus
}
#endif

#endif
