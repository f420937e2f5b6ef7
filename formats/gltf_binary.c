/* gltf_binary.c — the GLB container (gltf_binary.h). */
#include "gltf_binary.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "little_endian.h"
#include "output_file.h"

enum {
    GLB_MAGIC = 0x46546C67u,        /* "glTF" */
    GLB_VERSION = 2,
    GLB_CHUNK_JSON = 0x4E4F534Au,   /* "JSON" */
    GLB_CHUNK_BIN = 0x004E4942u,    /* "BIN\0" */
    GLB_MAX_SIZE = 0xFFFFFFFFu,     /* the header's length is a u32 */
};

static size_t padded(size_t size)
{
    return (size + 3) & ~(size_t)3;
}

/* A chunk's 8-byte header, its bytes and padding into out; returns the end. */
static uint8_t *put_chunk(uint8_t *out, uint32_t type, const void *bytes, size_t size,
                          uint8_t pad)
{
    gb_put_u32(out, (uint32_t)padded(size));
    gb_put_u32(out + 4, type);
    if (size)
        memcpy(out + 8, bytes, size);
    memset(out + 8 + size, pad, padded(size) - size);
    return out + 8 + padded(size);
}

gb_result gb_gltf_binary_write(const char *path, const char *json, size_t json_size,
                               const void *bin, size_t bin_size, gb_error *error)
{
    size_t total = 12 + 8 + padded(json_size) + (bin_size ? 8 + padded(bin_size) : 0);
    if (total > GLB_MAX_SIZE || json_size > GLB_MAX_SIZE || bin_size > GLB_MAX_SIZE)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: %zu bytes: a glTF binary holds at "
                       "most 4 GiB", path, total);
    uint8_t *bytes = malloc(total);
    if (!bytes)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    gb_put_u32(bytes, GLB_MAGIC);
    gb_put_u32(bytes + 4, GLB_VERSION);
    gb_put_u32(bytes + 8, (uint32_t)total);
    uint8_t *end = put_chunk(bytes + 12, GLB_CHUNK_JSON, json, json_size, ' ');
    if (bin_size)
        put_chunk(end, GLB_CHUNK_BIN, bin, bin_size, 0);
    gb_result result = gb_output_file_write_bytes(path, bytes, total, error);
    free(bytes);
    return result;
}
