/* mesh_check_stl.c — a STL file walked as OpenMesh 9 reads it (mesh_check.h). */
#include "mesh_reader.h"

/* ---- STL (OpenMesh STLReader) ----------------------------------------------- */

/* Binary: 80 bytes, a u32 count, 50 bytes a facet (normal, 3 vertices, 2
 * bytes). OpenMesh takes a file as binary iff its size says so. */
static gb_result walk_binary_stl(const reader *r, uint64_t facets, gb_error *error)
{
    for (uint64_t f = 0; f < facets; ++f) {
        const unsigned char *facet = r->begin + 84 + 50 * f;
        for (int k = 0; k < 9; ++k) {
            float value = get_f32(facet + 12 + 4 * k, 0);
            if (!isfinite(value))
                return gb_fail(error, GB_ERROR_INVALID, "%s: facet %llu: vertex %d: %c is not "
                               "finite (%g)", r->path, (unsigned long long)f, k / 3,
                               "xyz"[k % 3], (double)value);
        }
    }
    return GB_OK;
}

/* ASCII: every line holding "outer" (or "OUTER") is followed by three
 * lines "word x y z", whatever else the file says. */
static gb_result walk_ascii_stl(reader *r, gb_error *error)
{
    unsigned long long facet = 0;
    while (r->at < r->end) {
        const unsigned char *line = r->at, *newline = memchr(line, '\n', left(r));
        size_t length = (size_t)((newline ? newline : r->end) - line);
        int outer = memmem(line, length, "outer", 5) || memmem(line, length, "OUTER", 5);
        skip_line(r);
        if (!outer)
            continue;
        for (int v = 0; v < 3; ++v) {
            char where[64];
            snprintf(where, sizeof where, "facet %llu: vertex %d", facet, v);
            if (r->at == r->end)
                return truncated(r, where, error);
            newline = memchr(r->at, '\n', left(r));
            reader in_line = *r;
            in_line.end = newline ? newline : r->end;
            token t;
            next_token(&in_line, &t);   /* "vertex", not checked by OpenMesh */
            for (int k = 0; k < 3; ++k) {
                char what[2] = {"xyz"[k], '\0'};
                gb_result result = next_token(&in_line, &t)
                    ? check_float_token(&in_line, t, where, what, error)
                    : gb_fail(error, GB_ERROR_PARSE, "%s:%d: %s: no %s coordinate", r->path,
                              r->line, where, what);
                if (result != GB_OK)
                    return result;
            }
            skip_line(r);
        }
        ++facet;
    }
    return GB_OK;
}

gb_result gb_mesh_check_stl(reader *r, gb_error *error)
{
    size_t size = (size_t)(r->end - r->begin);
    if (size >= 84) {
        uint64_t facets = get_uint(r->begin + 80, 4, 0);
        if (84 + 50 * facets == size)
            return walk_binary_stl(r, facets, error);
    }
    return walk_ascii_stl(r, error);
}

