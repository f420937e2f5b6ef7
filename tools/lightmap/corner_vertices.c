/* corner_vertices.c — identical corners welded through a hash table of
 * their bytes (corner_vertices.h). */
#include "corner_vertices.h"

#include <stdlib.h>
#include <string.h>

#define EMPTY 0xFFFFFFFFu

/* FNV-1a of a vertex's bytes. */
static uint64_t hash_vertex(const float *v)
{
    const unsigned char *p = (const unsigned char *)v;
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < GB_VERTEX_FLOATS * sizeof *v; ++i)
        h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

static size_t table_size(uint32_t corner_count)
{
    size_t size = 16;
    while (size < 2 * (size_t)corner_count)
        size *= 2;
    return size;
}

/* The vertex of corner, added when new. */
static uint32_t weld(gb_corner_vertices *out, uint32_t *table, size_t mask, const float *corner)
{
    size_t slot = (size_t)hash_vertex(corner) & mask;
    for (;; slot = (slot + 1) & mask) {
        uint32_t v = table[slot];
        if (v == EMPTY)
            break;
        if (!memcmp(out->vertices + (size_t)v * GB_VERTEX_FLOATS, corner,
                    GB_VERTEX_FLOATS * sizeof *corner))
            return v;
    }
    uint32_t v = out->count++;
    memcpy(out->vertices + (size_t)v * GB_VERTEX_FLOATS, corner,
           GB_VERTEX_FLOATS * sizeof *corner);
    table[slot] = v;
    return v;
}

gb_result gb_corner_vertices_make(const float *corners, uint32_t corner_count,
                                  gb_corner_vertices *out, gb_error *error)
{
    memset(out, 0, sizeof *out);
    size_t size = table_size(corner_count);
    uint32_t *table = malloc(size * sizeof *table);
    out->vertices = malloc(((size_t)corner_count + 1) * GB_VERTEX_FLOATS * sizeof(float));
    out->indices = malloc(((size_t)corner_count + 1) * sizeof *out->indices);
    if (!table || !out->vertices || !out->indices) {
        free(table);
        gb_corner_vertices_free(out);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "lightmap: out of memory (%u corners)",
                       corner_count);
    }
    memset(table, 0xFF, size * sizeof *table);
    for (uint32_t c = 0; c < corner_count; ++c)
        out->indices[c] = weld(out, table, size - 1, corners + (size_t)c * GB_VERTEX_FLOATS);
    free(table);
    return GB_OK;
}

void gb_corner_vertices_free(gb_corner_vertices *v)
{
    free(v->vertices);
    free(v->indices);
    memset(v, 0, sizeof *v);
}
