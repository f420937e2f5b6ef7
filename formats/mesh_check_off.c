/* mesh_check_off.c — a OFF file walked as OpenMesh 9 reads it (mesh_check.h). */
#include "mesh_reader.h"

/* ---- OFF (OpenMesh OFFReader) ----------------------------------------------- */

typedef struct off_header {
    int texcoords, colours, normals, binary;
} off_header;

/* The first line as OpenMesh's can_u_read takes it apart:
 * [ST][C][N][4][n]OFF, then BINARY one byte after OFF. */
static gb_result read_off_keyword(const reader *r, off_header *h, gb_error *error)
{
    const unsigned char *p = r->at, *newline = memchr(p, '\n', left(r));
    long remaining = (long)((newline ? newline : r->end) - p) + (newline != NULL);
    int other_dimension = 0;
    memset(h, 0, sizeof *h);
    if (remaining > 1 && p[0] == 'S' && p[1] == 'T')
        h->texcoords = 1, p += 2, remaining -= 2;
    if (remaining > 0 && p[0] == 'C')
        h->colours = 1, ++p, --remaining;
    if (remaining > 0 && p[0] == 'N')
        h->normals = 1, ++p, --remaining;
    if (remaining > 0 && p[0] == '4')
        other_dimension = 1, ++p, --remaining;
    if (remaining > 0 && p[0] == 'n')
        other_dimension = 1, ++p, --remaining;
    if (remaining < 3 || memcmp(p, "OFF", 3) != 0)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: not an OFF file (the first line does not "
                       "start with [ST][C][N]OFF)", r->path);
    if (other_dimension)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: 4OFF and nOFF (other than 3 "
                       "coordinates) are not supported", r->path);
    p += 4;
    remaining = remaining >= 4 ? remaining - 4 : 0;
    h->binary = remaining >= 6 && memcmp(p, "BINARY", 6) == 0;
    return GB_OK;
}

/* A token of an OFF body; OpenMesh has no comments there. */
static gb_result next_off_token(reader *r, token *t, const char *where, gb_error *error)
{
    if (!next_token(r, t))
        return truncated(r, where, error);
    if (*t->begin == '#')
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s:%d: a comment ('#') in the body of an "
                       "OFF file: OpenMesh would read it as a number", r->path, t->line);
    return GB_OK;
}

static gb_result walk_ascii_off(reader *r, const off_header *h, gb_mesh_counts *counts,
                                gb_error *error)
{
    static const char *const names[] = {"x", "y", "z", "nx", "ny", "nz"};
    static const char *const header_names[] = {"vertex count", "face count", "edge count"};
    unsigned long long n[3];
    char shown[48];
    token t;
    skip_line(r);
    for (int i = 0; i < 3; ++i) {
        gb_result result = next_off_token(r, &t, "the OFF header", error);
        if (result != GB_OK)
            return result;
        if (!count_token(t, &n[i]))
            return gb_fail(error, GB_ERROR_PARSE, "%s:%d: %s '%s' is not a count", r->path,
                           t.line, header_names[i], quoted(t, shown));
    }
    unsigned long long vertices = n[0], faces = n[1];
    int values = h->normals ? 6 : 3;
    if (vertices * 2 * values + faces * 2 > left(r) + 2)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: %llu vertices and %llu faces declared, "
                       "more than the file holds", r->path, vertices, faces);
    counts->vertices = (long long)vertices;
    counts->faces = (long long)faces;
    for (unsigned long long v = 0; v < vertices; ++v) {
        char where[64];
        snprintf(where, sizeof where, "vertex %llu", v);
        for (int k = 0; k < values; ++k) {
            gb_result result = next_off_token(r, &t, where, error);
            if (result == GB_OK)
                result = check_float_token(r, t, where, names[k], error);
            if (result != GB_OK)
                return result;
        }
        skip_line(r);   /* colours and texture coordinates, read from the line apart */
    }
    for (unsigned long long f = 0; f < faces; ++f) {
        char where[64];
        unsigned long long corners = 0;
        snprintf(where, sizeof where, "face %llu", f);
        gb_result result = next_off_token(r, &t, where, error);
        if (result == GB_OK)
            result = check_corners(r, t, where, &corners, error);
        counts->short_faces += result == GB_OK && corners < 3;
        for (unsigned long long c = 0; result == GB_OK && c < corners; ++c) {
            result = next_off_token(r, &t, where, error);
            if (result == GB_OK)
                result = check_index(r, t, where, vertices, error);
        }
        if (result != GB_OK)
            return result;
        if (h->colours)
            skip_line(r);
    }
    return GB_OK;
}

/* OpenMesh reads binary OFF little-endian (the Geomview convention is
 * big-endian): nV, nF, nE, then per vertex 3 floats [3 normal floats]
 * [3 int32 colours] [2 texture floats], per face a count and its indices;
 * no face colours. */
static gb_result walk_binary_off(const reader *r, const off_header *h, gb_mesh_counts *counts,
                                 gb_error *error)
{
    const unsigned char *newline = memchr(r->at, '\n', left(r));
    const unsigned char *at = newline ? newline + 1 : r->end, *end = r->end;
    if (end - at < 12)
        return binary_truncated(r->path, "the OFF header", error);
    uint64_t vertices = get_uint(at, 4, 0), faces = get_uint(at + 4, 4, 0);
    uint64_t vertex_size = 12 + 12 * (uint64_t)h->normals + 12 * (uint64_t)h->colours +
                           8 * (uint64_t)h->texcoords;
    at += 12;
    uint64_t body = (uint64_t)(end - at);
    if (vertices * vertex_size + faces * 4 > body) {
        uint64_t v = get_uint(at - 12, 4, 1), f = get_uint(at - 8, 4, 1);
        if (v * vertex_size + f * 4 <= body)
            return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: binary OFF in big-endian byte "
                           "order: OpenMesh reads little-endian only", r->path);
        return gb_fail(error, GB_ERROR_FORMAT, "%s: %llu vertices and %llu faces declared, "
                       "more than the file holds", r->path, (unsigned long long)vertices,
                       (unsigned long long)faces);
    }
    counts->vertices = (long long)vertices;
    counts->faces = (long long)faces;
    for (uint64_t v = 0; v < vertices; ++v, at += vertex_size)
        for (int k = 0; k < 3; ++k) {
            float value = get_f32(at + 4 * k, 0);
            if (!isfinite(value))
                return gb_fail(error, GB_ERROR_INVALID, "%s: vertex %llu: %c is not finite (%g)",
                               r->path, (unsigned long long)v, "xyz"[k], (double)value);
        }
    for (uint64_t f = 0; f < faces; ++f) {
        if (end - at < 4)
            return gb_fail(error, GB_ERROR_FORMAT, "%s: the file ends in face %llu", r->path,
                           (unsigned long long)f);
        uint64_t corners = get_uint(at, 4, 0);
        at += 4;
        if (corners > (uint64_t)(end - at) / 4)
            return gb_fail(error, GB_ERROR_FORMAT, "%s: face %llu: %llu corners, more than the "
                           "rest of the file holds", r->path, (unsigned long long)f,
                           (unsigned long long)corners);
        counts->short_faces += corners < 3;
        for (uint64_t c = 0; c < corners; ++c, at += 4) {
            uint64_t index = get_uint(at, 4, 0);
            if (index >= vertices)
                return gb_fail(error, GB_ERROR_INVALID, "%s: face %llu: vertex index %llu out "
                               "of range (%llu vertices)", r->path, (unsigned long long)f,
                               (unsigned long long)index, (unsigned long long)vertices);
        }
    }
    return GB_OK;
}

gb_result gb_mesh_check_off(reader *r, gb_mesh_counts *counts, gb_error *error)
{
    off_header h;
    gb_result result = read_off_keyword(r, &h, error);
    if (result != GB_OK)
        return result;
    return h.binary ? walk_binary_off(r, &h, counts, error) : walk_ascii_off(r, &h, counts, error);
}

