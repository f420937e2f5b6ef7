/* fuzz_reader.h — what the fuzz targets of gibake's readers share.
 *
 *   GB_FUZZ_READER(NAME, TYPE, PARSE, CHECK, FREE, USE, EMPTY)
 *       defines static void NAME(const unsigned char *bytes, size_t size), the
 *       whole assertion of a binary format's target: either
 *       PARSE(bytes, size, "fuzz", &value, &error) succeeds, CHECK(&value,
 *       "fuzz", &error) then passes, USE(&value) reads what the runtime would
 *       (its sum goes to a volatile sink, so that the reads stay) and
 *       FREE(&value) frees it; or it fails with a message "fuzz: ..." and
 *       EMPTY(&value) holds. Anything else traps.
 *   gb_fuzz_parse_aligned(data, size, parse, fix)
 *       the input copied into a 16-byte aligned buffer (as a mapped file is)
 *       and parsed; with fix, its container checksums then recomputed
 *       (fix_checksums.h) and parsed again, so that mutations reach the
 *       format's own checks instead of all stopping at the container's CRCs.
 *   gb_fuzz_parse_twice(data, size, parse)
 *       gb_fuzz_parse_aligned with fix: the whole test of a container-based
 *       format's target (.lot, .skel, .atlas, .phot).
 *   gb_fuzz_names(error, path)
 *       1 when the error's message starts with "PATH:", as every failure of
 *       a reader given a file name says.
 *   gb_fuzz_check_triangles(scene, areas)
 *       traps unless every triangle's vertex indices and material are in
 *       range and, with areas (after gb_scene_finish), its area positive.
 */
#ifndef GB_FUZZ_READER_H
#define GB_FUZZ_READER_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fix_checksums.h"
#include "scene.h"

static volatile double gb_fuzz_sink;

#define GB_FUZZ_READER(NAME, TYPE, PARSE, CHECK, FREE, USE, EMPTY)                        \
    static void NAME(const unsigned char *bytes, size_t size)                             \
    {                                                                                     \
        TYPE value;                                                                       \
        gb_error error;                                                                   \
        if (PARSE(bytes, size, "fuzz", &value, &error) == GB_OK) {                        \
            if (CHECK(&value, "fuzz", &error) != GB_OK)                                   \
                __builtin_trap(); /* what the reader accepts is valid */                  \
            gb_fuzz_sink += (double)USE(&value);                                          \
            FREE(&value);                                                                 \
        } else if (strncmp(error.message, "fuzz: ", 6) != 0 || !EMPTY(&value)) {          \
            __builtin_trap(); /* failures name the input and leave an empty result */     \
        }                                                                                 \
    }

static inline void gb_fuzz_parse_aligned(const uint8_t *data, size_t size,
                                         void (*parse)(const unsigned char *aligned,
                                                       size_t size),
                                         int fix)
{
    unsigned char *aligned = aligned_alloc(16, (size + 16) & ~(size_t)15);
    if (!aligned)
        return;
    memcpy(aligned, data, size);
    parse(aligned, size);
    if (fix) {
        gb_fuzz_fix_container_checksums(aligned, size);
        parse(aligned, size);
    }
    free(aligned);
}

static inline void gb_fuzz_parse_twice(const uint8_t *data, size_t size,
                                       void (*parse)(const unsigned char *aligned, size_t size))
{
    gb_fuzz_parse_aligned(data, size, parse, 1);
}

static inline int gb_fuzz_names(const gb_error *error, const char *path)
{
    size_t n = strlen(path);
    return strncmp(error->message, path, n) == 0 && error->message[n] == ':';
}

static inline void gb_fuzz_check_triangles(const gb_scene *scene, int areas)
{
    for (size_t i = 0; i < 3 * (size_t)scene->triangle_count; ++i)
        if (scene->indices[i] >= scene->vertex_count)
            __builtin_trap();
    for (uint32_t t = 0; t < scene->triangle_count; ++t)
        if (scene->triangle_material[t] >= scene->material_count ||
            (areas && !(gb_triangle_area(scene, t) > 0)))
            __builtin_trap();
}

#endif
