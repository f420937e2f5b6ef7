/* image_check.c — the format, the PNG chunks and the declared size of an
 * image file, checked before OpenImageIO reads it (see image_check.h). */
#include "image_check.h"
#include "mapped_file.h"

#include <errno.h>
#include <stdint.h>
#include <string.h>
#include <unistd.h>

#include "text.h"

enum {
    VALUES_PER_BYTE = 4096,
    MIN_VALUE_LIMIT = 1 << 24,
    MAX_CHANNELS = 64,          /* as gb_image_allocate */
};

static int starts_with(const unsigned char *bytes, size_t size, const char *magic, size_t n)
{
    return size >= n && memcmp(bytes, magic, n) == 0;
}

static uint32_t big_endian_32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* Signature, then chunks (u32 length, 4-letter type, data, CRC) up to
 * IEND, each inside the file. libpng checks the CRCs and the contents. */
static gb_result check_png(const unsigned char *bytes, size_t size, const char *path,
                           gb_error *error)
{
    size_t at = 8;
    for (unsigned chunk = 0;; ++chunk) {
        if (size - at < 12)
            return gb_fail(error, GB_ERROR_FORMAT, "%s: truncated PNG: it ends in chunk %u, "
                           "before IEND", path, chunk);
        uint32_t length = big_endian_32(bytes + at);
        const unsigned char *type = bytes + at + 4;
        if (length > 0x7fffffffu || length > size - at - 12)
            return gb_fail(error, GB_ERROR_FORMAT, "%s: PNG chunk %u: %u bytes, beyond the "
                           "end of the file", path, chunk, length);
        for (int i = 0; i < 4; ++i)
            if (!((type[i] >= 'A' && type[i] <= 'Z') || (type[i] >= 'a' && type[i] <= 'z')))
                return gb_fail(error, GB_ERROR_FORMAT, "%s: PNG chunk %u: its type is not "
                               "four letters", path, chunk);
        if (chunk == 0 && (memcmp(type, "IHDR", 4) != 0 || length != 13))
            return gb_fail(error, GB_ERROR_FORMAT, "%s: PNG: the first chunk is not a "
                           "13-byte IHDR", path);
        if (memcmp(type, "IEND", 4) == 0)
            return GB_OK;
        at += 12 + (size_t)length;
    }
}

/* ---- OpenEXR: the header walked before the OpenEXR library allocates -------- */

/* OpenEXR allocates what an attribute's size field says, a preview's
 * width x height x 4, a string vector's lengths and an offset table of 8
 * bytes per chunk before it reads them; each must fit in the file. */

static uint32_t little_endian_32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* Lines in a chunk of a scanline image, by compression (ImfCompression.h). */
static unsigned long long exr_lines_per_chunk(int compression)
{
    static const unsigned char lines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 0};
    if (compression == 9)
        return 256;     /* DWAB */
    return compression >= 0 && compression < 9 ? lines[compression] : 0;
}

typedef struct exr_part {
    int has_window, has_tiles, has_chunk_count;
    long long channels;
    long long window[4];        /* xmin, ymin, xmax, ymax */
    unsigned long long tile[2];
    long long chunk_count;
    int compression;
} exr_part;

/* The value of a C string inside [at, end): its length, or -1. */
static long long string_length(const unsigned char *at, const unsigned char *end, size_t limit)
{
    const unsigned char *nul = memchr(at, '\0', (size_t)(end - at) < limit ? (size_t)(end - at)
                                                                            : limit);
    return nul ? (long long)(nul - at) : -1;
}

static gb_result exr_attribute_value(const char *path, const char *name, const char *type,
                                     const unsigned char *value, uint32_t size,
                                     exr_part *part, gb_error *error)
{
    if (!strcmp(type, "preview")) {
        if (size < 8 || (unsigned long long)little_endian_32(value) *
                            little_endian_32(value + 4) * 4 > size - 8)
            return gb_fail(error, GB_ERROR_FORMAT, "%s: OpenEXR preview '%s' is larger than "
                           "its attribute", path, name);
    } else if (!strcmp(type, "stringvector")) {
        for (uint32_t at = 0; at < size;) {
            if (size - at < 4 || little_endian_32(value + at) > size - at - 4)
                return gb_fail(error, GB_ERROR_FORMAT, "%s: OpenEXR attribute '%s': a string "
                               "longer than the attribute", path, name);
            at += 4 + little_endian_32(value + at);
        }
    } else if (!strcmp(type, "chlist")) {
        /* name, then 16 bytes (type, pLinear, reserved, x and y sampling) */
        for (uint32_t at = 0;; at += 16, ++part->channels) {
            long long length = string_length(value + at, value + size, 256);
            if (length < 0 || (length > 0 && size - at - (uint32_t)length - 1 < 16))
                return gb_fail(error, GB_ERROR_FORMAT, "%s: OpenEXR channel list '%s' is "
                               "truncated", path, name);
            at += (uint32_t)length + 1;
            if (length == 0)
                break;
        }
    } else if (!strcmp(name, "dataWindow") && !strcmp(type, "box2i") && size == 16) {
        part->has_window = 1;
        for (int i = 0; i < 4; ++i)
            part->window[i] = (int32_t)little_endian_32(value + 4 * i);
    } else if (!strcmp(name, "tiles") && !strcmp(type, "tiledesc") && size == 9) {
        part->has_tiles = 1;
        part->tile[0] = little_endian_32(value);
        part->tile[1] = little_endian_32(value + 4);
    } else if (!strcmp(name, "chunkCount") && !strcmp(type, "int") && size == 4) {
        part->has_chunk_count = 1;
        part->chunk_count = (int32_t)little_endian_32(value);
    } else if (!strcmp(name, "compression") && !strcmp(type, "compression") && size == 1) {
        part->compression = value[0];
    }
    return GB_OK;
}

/* The number of chunks (offset table entries) of a part, at least. */
static gb_result exr_check_part(const char *path, const exr_part *part, size_t file_size,
                                gb_error *error)
{
    if (!part->has_window)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: OpenEXR header without dataWindow", path);
    long long width = part->window[2] - part->window[0] + 1;
    long long height = part->window[3] - part->window[1] + 1;
    gb_image_file file = {"openexr", file_size};
    gb_result result = gb_image_check_size(path, &file, width, height, 1,
                                           part->channels ? part->channels : 1, error);
    if (result != GB_OK)
        return result;
    unsigned long long chunks;
    if (part->has_tiles) {
        if (part->tile[0] == 0 || part->tile[1] == 0)
            return gb_fail(error, GB_ERROR_FORMAT, "%s: OpenEXR tiles of size 0", path);
        chunks = ((unsigned long long)width + part->tile[0] - 1) / part->tile[0] *
                 (((unsigned long long)height + part->tile[1] - 1) / part->tile[1]);
    } else {
        unsigned long long lines = exr_lines_per_chunk(part->compression);
        if (!lines)
            return gb_fail(error, GB_ERROR_FORMAT, "%s: unknown OpenEXR compression %d", path,
                           part->compression);
        chunks = ((unsigned long long)height + lines - 1) / lines;
    }
    if (part->has_chunk_count)      /* multi-part files size their offset tables by it */
        chunks = part->chunk_count < 0 ? ~0ull
            : (unsigned long long)part->chunk_count > chunks
            ? (unsigned long long)part->chunk_count : chunks;
    if (chunks > file_size / 8)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: OpenEXR: %llu chunks, more offsets than "
                       "the file holds", path, chunks);
    return GB_OK;
}

/* magic, version (2, flags: 0x200 tiled, 0x400 long names, 0x800 deep,
 * 0x1000 multi-part), then headers of (name, type, size, value) attributes,
 * each ended by an empty name; a multi-part file ends them with one more. */
static gb_result check_exr(const unsigned char *bytes, size_t size, const char *path,
                           gb_error *error)
{
    if (size < 8)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: truncated OpenEXR header", path);
    uint32_t version = little_endian_32(bytes + 4);
    if ((version & 0xff) != 2)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: OpenEXR version %u", path,
                       version & 0xff);
    if (version & 0x800)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: deep OpenEXR images are not "
                       "supported", path);
    size_t name_limit = version & 0x400 ? 256 : 32;
    int multipart = (version & 0x1000) != 0;
    const unsigned char *at = bytes + 8, *end = bytes + size;
    for (int parts = 0;; ++parts) {
        if (at == end)
            return gb_fail(error, GB_ERROR_FORMAT, "%s: truncated OpenEXR header", path);
        if (*at == '\0' && (parts > 0 || !multipart)) {
            if (parts == 0)
                return gb_fail(error, GB_ERROR_FORMAT, "%s: empty OpenEXR header", path);
            return GB_OK;   /* the end of the headers of a multi-part file */
        }
        exr_part part = {0};
        for (;;) {
            long long name_length = string_length(at, end, name_limit);
            if (name_length < 0)
                return gb_fail(error, GB_ERROR_FORMAT, "%s: OpenEXR attribute name too long or "
                               "truncated", path);
            const char *name = (const char *)at;
            at += name_length + 1;
            if (name_length == 0)
                break;
            long long type_length = string_length(at, end, name_limit);
            if (type_length <= 0 || end - (at + type_length + 1) < 4)
                return gb_fail(error, GB_ERROR_FORMAT, "%s: OpenEXR attribute '%s': bad or "
                               "truncated type", path, name);
            const char *type = (const char *)at;
            at += type_length + 1;
            uint32_t value_size = little_endian_32(at);
            at += 4;
            if (value_size > 0x7fffffffu || value_size > (size_t)(end - at))
                return gb_fail(error, GB_ERROR_FORMAT, "%s: OpenEXR attribute '%s': %u bytes, "
                               "beyond the end of the file", path, name, value_size);
            gb_result result = exr_attribute_value(path, name, type, at, value_size, &part,
                                                   error);
            if (result != GB_OK)
                return result;
            at += value_size;
        }
        gb_result result = exr_check_part(path, &part, size, error);
        if (result != GB_OK || !multipart)
            return result;
    }
}

gb_result gb_image_check(const void *data, size_t size, const char *path,
                         gb_image_file *file, gb_error *error)
{
    const unsigned char *bytes = data;
    file->format = NULL;
    file->size = size;
    if (starts_with(bytes, size, "\x89PNG\r\n\x1a\n", 8)) {
        file->format = "png";
        return check_png(bytes, size, path, error);
    }
    if (starts_with(bytes, size, "\xff\xd8\xff", 3))
        file->format = "jpeg";
    else if (starts_with(bytes, size, "\x76\x2f\x31\x01", 4)) {
        file->format = "openexr";
        return check_exr(bytes, size, path, error);
    }
    else if (starts_with(bytes, size, "#?", 2))
        file->format = "hdr";
    else if (starts_with(bytes, size, "II*\0", 4) || starts_with(bytes, size, "MM\0*", 4) ||
             starts_with(bytes, size, "II+\0", 4) || starts_with(bytes, size, "MM\0+", 4))
        file->format = "tiff";
    else if (starts_with(bytes, size, "BM", 2))
        file->format = "bmp";
    else if (size >= 2 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '6')
        file->format = "pnm";   /* netpbm PBM/PGM/PPM, ASCII or binary: what a shell script writes */
    else if (gb_path_has_suffix(path, ".tga"))
        file->format = "targa";
    else
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: not an image gibake reads (PNG, "
                       "JPEG, OpenEXR, Radiance HDR, TIFF, BMP, PPM or a .tga file)", path);
    return GB_OK;
}

gb_result gb_image_check_file(const char *path, gb_image_file *file, gb_error *error)
{
    file->format = NULL;
    file->size = 0;
    gb_mapped_file mapped;
    gb_result result = gb_mapped_file_open(path, &mapped, error);
    if (result != GB_OK)
        return result;
    if (mapped.size == 0)
        result = gb_fail(error, GB_ERROR_FORMAT, "%s: empty file", path);
    else
        result = gb_image_check(mapped.bytes, mapped.size, path, file, error);
    gb_mapped_file_close(&mapped);
    return result;
}

gb_result gb_image_check_size(const char *path, const gb_image_file *file, long long width,
                              long long height, long long depth, long long channels,
                              gb_error *error)
{
    if (width <= 0 || height <= 0 || channels <= 0 || channels > MAX_CHANNELS ||
        width > INT32_MAX || height > INT32_MAX)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: bad image size %lld x %lld x %lld channels",
                       path, width, height, channels);
    if (depth != 1)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: a volume image (depth %lld)", path,
                       depth);
    unsigned long long values = (unsigned long long)width * (unsigned long long)height *
                                (unsigned long long)channels;
    unsigned long long limit = file->size > (unsigned long long)MIN_VALUE_LIMIT / VALUES_PER_BYTE
        ? file->size * VALUES_PER_BYTE : MIN_VALUE_LIMIT;
    if (values / (unsigned long long)channels / (unsigned long long)height
            != (unsigned long long)width || values > limit)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: %lld x %lld pixels x %lld channels: more "
                       "than a %llu-byte file can hold", path, width, height, channels,
                       file->size);
    return GB_OK;
}
