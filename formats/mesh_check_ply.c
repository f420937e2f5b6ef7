/* mesh_check_ply.c — a PLY file walked as OpenMesh 9 reads it (mesh_check.h). */
#include "mesh_reader.h"

/* ---- PLY (OpenMesh PLYReader) --------------------------------------------- */

enum ply_type { PLY_NONE, PLY_INT8, PLY_UINT8, PLY_INT16, PLY_UINT16, PLY_INT32, PLY_UINT32,
                PLY_FLOAT32, PLY_FLOAT64 };

/* In the order OpenMesh's get_property_type tries them. */
static const struct {
    const char *name;
    enum ply_type type;
} ply_types[] = {
    {"float32", PLY_FLOAT32}, {"float64", PLY_FLOAT64}, {"float", PLY_FLOAT32},
    {"double", PLY_FLOAT64},  {"int8", PLY_INT8},       {"uint8", PLY_UINT8},
    {"char", PLY_INT8},       {"uchar", PLY_UINT8},     {"int32", PLY_INT32},
    {"uint32", PLY_UINT32},   {"int", PLY_INT32},       {"uint", PLY_UINT32},
    {"int16", PLY_INT16},     {"uint16", PLY_UINT16},   {"short", PLY_INT16},
    {"ushort", PLY_UINT16},
};

static int ply_size(enum ply_type type)
{
    static const int sizes[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};
    return sizes[type];
}

static int is_signed(enum ply_type type)
{
    return type == PLY_INT8 || type == PLY_INT16 || type == PLY_INT32;
}

static enum ply_type ply_type_of(token t)
{
    for (size_t i = 0; i < sizeof ply_types / sizeof ply_types[0]; ++i)
        if (token_is(t, ply_types[i].name))
            return ply_types[i].type;
    return PLY_NONE;
}

/* What OpenMesh does with a property. */
enum ply_role { ROLE_SKIPPED, ROLE_COORDINATE, ROLE_FLOAT, ROLE_COLOUR, ROLE_CORNERS };

enum { PLY_MAX_ELEMENTS = 32, PLY_MAX_PROPERTIES = 64, PLY_NAME = 32 };

typedef struct ply_property {
    char name[PLY_NAME];
    enum ply_type type;         /* of the value, or of a list's entries */
    enum ply_type count_type;   /* PLY_NONE: not a list */
    enum ply_role role;
} ply_property;

typedef struct ply_element {
    char name[PLY_NAME];
    unsigned long long count;
    int property_count;
    ply_property properties[PLY_MAX_PROPERTIES];
} ply_element;

typedef struct ply_header {
    int binary, big_endian;
    int element_count;
    ply_element elements[PLY_MAX_ELEMENTS];
    const unsigned char *body;  /* where OpenMesh starts reading the body */
    int body_line;
    long long vertices, faces;  /* OpenMesh's vertexCount_, faceCount_ */
} ply_header;

static void copy_name(token t, char name[PLY_NAME])
{
    size_t n = (size_t)(t.end - t.begin);
    if (n >= PLY_NAME)
        n = PLY_NAME - 1;
    memcpy(name, t.begin, n);
    name[n] = '\0';
}

static enum ply_role vertex_role(const char *name, enum ply_type type)
{
    static const char *const floats[] = {"nx", "ny", "nz", "u", "s", "v", "t"};
    static const char *const colours[] = {"red", "green", "blue", "diffuse_red",
                                          "diffuse_green", "diffuse_blue", "alpha"};
    if (!strcmp(name, "x") || !strcmp(name, "y") || !strcmp(name, "z"))
        return ROLE_COORDINATE;
    for (size_t i = 0; i < sizeof floats / sizeof floats[0]; ++i)
        if (!strcmp(name, floats[i]))
            return ROLE_FLOAT;
    for (size_t i = 0; i < sizeof colours / sizeof colours[0]; ++i)
        if (!strcmp(name, colours[i]))
            return type == PLY_FLOAT32 ? ROLE_FLOAT : ROLE_COLOUR;
    return ROLE_SKIPPED;
}

static gb_result header_end(const reader *r, gb_error *error)
{
    return gb_fail(error, GB_ERROR_PARSE, "%s:%d: the PLY header has no end_header", r->path,
                   r->line);
}

static gb_result read_ply_element(reader *r, ply_header *h, gb_error *error)
{
    token name, count;
    char shown[48];
    if (!next_token(r, &name) || !next_token(r, &count))
        return header_end(r, error);
    if (h->element_count == PLY_MAX_ELEMENTS)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s:%d: more than %d PLY elements",
                       r->path, name.line, PLY_MAX_ELEMENTS);
    ply_element *e = &h->elements[h->element_count++];
    copy_name(name, e->name);
    if (!count_token(count, &e->count))
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: element %s: count '%s' is not a count",
                       r->path, count.line, e->name, quoted(count, shown));
    /* OpenMesh loops over its last vertex and face counts, whichever
     * element it reads: a second declaration would make it read the first
     * element with the second's count (past the body's end, a list of 2^32
     * corners) */
    long long *declared = !strcmp(e->name, "vertex") ? &h->vertices
                          : !strcmp(e->name, "face") ? &h->faces : NULL;
    if (declared && *declared >= 0)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s:%d: a second element %s", r->path,
                       name.line, e->name);
    if (declared)
        *declared = (long long)e->count;
    return GB_OK;
}

/* "property list COUNT ENTRY NAME" or "property TYPE NAME" (OpenMesh also
 * takes "NAME TYPE"). */
static gb_result read_ply_property(reader *r, ply_header *h, token keyword, gb_error *error)
{
    char shown[48];
    if (h->element_count == 0)
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: a property before any element", r->path,
                       keyword.line);
    ply_element *e = &h->elements[h->element_count - 1];
    if (e->property_count == PLY_MAX_PROPERTIES)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s:%d: element %s: more than %d properties",
                       r->path, keyword.line, e->name, PLY_MAX_PROPERTIES);
    ply_property *p = &e->properties[e->property_count];
    memset(p, 0, sizeof *p);
    token first, second;
    if (!next_token(r, &first) || !next_token(r, &second))
        return header_end(r, error);
    if (token_is(first, "list")) {
        token entry, name;
        if (!next_token(r, &entry) || !next_token(r, &name))
            return header_end(r, error);
        copy_name(name, p->name);
        if (!token_is(second, "uint8") && !token_is(second, "uint16") &&
            !token_is(second, "uchar") && !token_is(second, "int"))
            return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s:%d: property list %s: count type "
                           "'%s' is not uint8, uint16, uchar or int", r->path, second.line,
                           p->name, quoted(second, shown));
        p->count_type = ply_type_of(second);
        if (!(p->type = ply_type_of(entry)))
            return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s:%d: property list %s: unknown "
                           "entry type '%s'", r->path, entry.line, p->name,
                           quoted(entry, shown));
        if (!strcmp(e->name, "face") &&
            (!strcmp(p->name, "vertex_indices") || !strcmp(p->name, "vertex_index"))) {
            p->role = ROLE_CORNERS;
            if (e->property_count > 0)  /* OpenMesh forgets them, but they are in the file */
                return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s:%d: face properties before "
                               "%s are not supported", r->path, name.line, p->name);
        }
    } else {
        enum ply_type type = PLY_NONE;
        for (size_t i = 0; i < sizeof ply_types / sizeof ply_types[0] && !type; ++i)
            if (token_is(first, ply_types[i].name) || token_is(second, ply_types[i].name))
                type = ply_types[i].type;
        if (!type)
            return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s:%d: property '%s ...' has no "
                           "known type", r->path, first.line, quoted(first, shown));
        copy_name(ply_type_of(first) ? second : first, p->name);
        p->type = type;
        p->role = !strcmp(e->name, "vertex") ? vertex_role(p->name, type) : ROLE_SKIPPED;
    }
    ++e->property_count;
    return GB_OK;
}

/* Where OpenMesh starts a binary body: it seeks back to where the stream
 * was before it read "end_header" (after the header's last token, or at
 * the start of the line after a comment) and skips 12 bytes, 14 after a
 * CR LF: right only when end_header follows the last token's line end. */
static gb_result find_binary_body(const reader *r, ply_header *h, const unsigned char *before,
                                  token end_header, gb_error *error)
{
    const unsigned char *data = end_header.end;
    if (data < r->end && *data == '\r')
        ++data;
    int line_end = data < r->end && *data == '\n';
    size_t skip = r->end - before >= 2 && before[0] == '\r' && before[1] == '\n' ? 14 : 12;
    if (!line_end || (size_t)(r->end - before) < skip || before + skip != data + 1)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s:%d: binary PLY: end_header must be "
                       "alone on the line right after the header's last line (OpenMesh "
                       "would read the data from the wrong byte)", r->path, end_header.line);
    h->body = data + 1;
    return GB_OK;
}

static gb_result read_ply_header(reader *r, ply_header *h, gb_error *error)
{
    const unsigned char *newline = memchr(r->at, '\n', left(r));
    const unsigned char *first = r->at, *last = newline ? newline : r->end;
    while (first < last && is_space(*first))
        ++first;
    while (last > first && is_space(last[-1]))
        --last;
    if (!(last - first == 3 && (!memcmp(first, "ply", 3) || !memcmp(first, "PLY", 3))))
        return gb_fail(error, GB_ERROR_FORMAT, "%s: not a PLY file (no 'ply' line first)",
                       r->path);
    skip_line(r);
    token keyword, format, version;
    char shown[48];
    float number;
    if (!next_token(r, &keyword) || !next_token(r, &format) || !next_token(r, &version))
        return header_end(r, error);
    if (token_is(format, "binary_little_endian") || token_is(format, "binary_big_endian")) {
        h->binary = 1;
        h->big_endian = token_is(format, "binary_big_endian");
    } else if (!token_is(format, "ascii")) {
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s:%d: unknown PLY format '%s'", r->path,
                       format.line, quoted(format, shown));
    }
    if (float_token(version, &number) != NUMBER)
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: PLY version '%s' is not a number",
                       r->path, version.line, quoted(version, shown));
    const unsigned char *before = r->at;
    while (next_token(r, &keyword)) {
        gb_result result = GB_OK;
        if (token_is(keyword, "end_header")) {
            h->body_line = r->line;
            if (!h->binary) {
                h->body = r->at;
                return GB_OK;
            }
            return find_binary_body(r, h, before, keyword, error);
        }
        if (token_is(keyword, "comment"))
            skip_line(r);
        else if (token_is(keyword, "element"))
            result = read_ply_element(r, h, error);
        else if (token_is(keyword, "property"))
            result = read_ply_property(r, h, keyword, error);
        if (result != GB_OK)
            return result;
        before = r->at;     /* other words are ignored, one at a time, as OpenMesh does */
    }
    return header_end(r, error);
}

/* The elements OpenMesh reads: up to the first "face" one. */
static int ply_elements_read(const ply_header *h)
{
    for (int i = 0; i < h->element_count; ++i)
        if (!strcmp(h->elements[i].name, "face"))
            return i + 1;
    return h->element_count;
}

static int is_integer_type(enum ply_type type, int binary)
{
    /* OpenMesh's binary readInteger knows 8- and 32-bit integers only */
    return binary ? type == PLY_INT8 || type == PLY_UINT8 || type == PLY_INT32 ||
                        type == PLY_UINT32
                  : type != PLY_FLOAT32 && type != PLY_FLOAT64;
}

/* What OpenMesh cannot read right, and counts the body cannot hold. */
static gb_result check_ply_elements(const reader *r, const ply_header *h, gb_error *error)
{
    size_t body = (size_t)(r->end - h->body);
    int read = ply_elements_read(h);
    for (int i = 0; i < h->element_count; ++i) {
        const ply_element *e = &h->elements[i];
        unsigned long long item = 0;
        for (int k = 0; k < e->property_count; ++k) {
            const ply_property *p = &e->properties[k];
            item += h->binary ? (unsigned)ply_size(p->count_type ? p->count_type : p->type) : 2;
            if (i >= read)
                continue;
            int binary = h->binary;
            if (p->count_type && p->role != ROLE_CORNERS)
                return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: element %s: list property %s "
                               "is not supported (OpenMesh reads a face's vertex_indices as its "
                               "only list)", r->path, e->name, p->name);
            if (p->role == ROLE_CORNERS &&
                (!is_integer_type(p->type, binary) || (binary && p->count_type == PLY_UINT16)))
                return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: face %s: the types of its "
                               "count and entries must be %s", r->path, p->name,
                               binary ? "8- or 32-bit integers (uint16 counts neither)"
                                      : "integers");
            if (binary && (p->role == ROLE_COORDINATE || p->role == ROLE_FLOAT) &&
                p->type != PLY_FLOAT32 && p->type != PLY_FLOAT64)
                return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: binary PLY: vertex property "
                               "%s must be float or double", r->path, p->name);
            if (binary && p->role == ROLE_COLOUR && !is_integer_type(p->type, 1))
                return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: binary PLY: vertex property "
                               "%s must be float or an 8- or 32-bit integer", r->path, p->name);
        }
        if (e->count && item == 0)
            return gb_fail(error, GB_ERROR_FORMAT, "%s: element %s: %llu items without "
                           "properties", r->path, e->name, e->count);
        if (e->count > (body + !h->binary) / (item ? item : 1))
            return gb_fail(error, GB_ERROR_FORMAT, "%s: element %s declares %llu items, more "
                           "than the %zu bytes after the header hold", r->path, e->name,
                           e->count, body);
    }
    return GB_OK;
}

/* "vertex 3", "face 3" or "element edge, item 3" for messages. */
static const char *item_name(const ply_element *e, unsigned long long i, char out[64])
{
    if (!strcmp(e->name, "vertex") || !strcmp(e->name, "face"))
        snprintf(out, 64, "%s %llu", e->name, i);
    else
        snprintf(out, 64, "element %s, item %llu", e->name, i);
    return out;
}

static gb_result walk_ascii_ply(reader *r, const ply_header *h, gb_mesh_counts *counts,
                                gb_error *error)
{
    unsigned long long vertices = h->vertices > 0 ? (unsigned long long)h->vertices : 0;
    for (int i = 0, read = ply_elements_read(h); i < read; ++i) {
        const ply_element *e = &h->elements[i];
        for (unsigned long long n = 0; n < e->count; ++n) {
            char where[64], shown[48];
            item_name(e, n, where);
            for (int k = 0; k < e->property_count; ++k) {
                const ply_property *p = &e->properties[k];
                token t;
                long long integer;
                unsigned long long corners = 0;
                gb_result result = GB_OK;
                if (!next_token(r, &t))
                    return truncated(r, where, error);
                switch (p->role) {
                case ROLE_COORDINATE:
                case ROLE_FLOAT:
                    result = check_float_token(r, t, where, p->name, error);
                    break;
                case ROLE_COLOUR:
                    if (!integer_token(t, &integer) || integer < INT32_MIN || integer > INT32_MAX)
                        result = gb_fail(error, GB_ERROR_PARSE, "%s:%d: %s: %s '%s' is not an "
                                         "integer", r->path, t.line, where, p->name,
                                         quoted(t, shown));
                    break;
                case ROLE_CORNERS:
                    result = check_corners(r, t, where, &corners, error);
                    counts->short_faces += result == GB_OK && corners < 3;
                    for (unsigned long long c = 0; result == GB_OK && c < corners; ++c)
                        result = next_token(r, &t) ? check_index(r, t, where, vertices, error)
                                                   : truncated(r, where, error);
                    break;
                case ROLE_SKIPPED:
                    break;  /* OpenMesh reads it as a word and drops it */
                }
                if (result != GB_OK)
                    return result;
            }
        }
    }
    return GB_OK;
}

static gb_result walk_binary_ply(const reader *r, const ply_header *h, gb_mesh_counts *counts,
                                 gb_error *error)
{
    unsigned long long vertices = h->vertices > 0 ? (unsigned long long)h->vertices : 0;
    const unsigned char *at = h->body, *end = r->end;
    int be = h->big_endian;
    for (int i = 0, read = ply_elements_read(h); i < read; ++i) {
        const ply_element *e = &h->elements[i];
        for (unsigned long long n = 0; n < e->count; ++n) {
            char where[64];
            item_name(e, n, where);
            for (int k = 0; k < e->property_count; ++k) {
                const ply_property *p = &e->properties[k];
                int size = ply_size(p->count_type ? p->count_type : p->type);
                if ((size_t)(end - at) < (size_t)size)
                    return binary_truncated(r->path, where, error);
                if (p->role == ROLE_CORNERS) {
                    uint64_t corners = get_uint(at, size, be);
                    if (is_signed(p->count_type))   /* an int read into an unsigned */
                        corners = (uint32_t)(int32_t)corners;
                    at += size;
                    int entry = ply_size(p->type);
                    if (corners > (uint64_t)(end - at) / (uint64_t)entry)
                        return gb_fail(error, GB_ERROR_FORMAT, "%s: %s: %llu corners, more "
                                       "than the rest of the file holds", r->path, where,
                                       (unsigned long long)corners);
                    counts->short_faces += corners < 3;
                    for (uint64_t c = 0; c < corners; ++c, at += entry) {
                        uint64_t bits = get_uint(at, entry, be);
                        long long index = is_signed(p->type)
                            ? (entry == 1 ? (int8_t)bits : (int32_t)bits) : (long long)bits;
                        if (index < 0 || (unsigned long long)index >= vertices)
                            return gb_fail(error, GB_ERROR_INVALID, "%s: %s: vertex index %lld "
                                           "out of range (%llu vertices)", r->path, where, index,
                                           vertices);
                    }
                    continue;
                }
                if (p->role == ROLE_COORDINATE) {
                    double value = size == 4 ? get_f32(at, be) : get_f64(at, be);
                    if (!finite_as_float(value))
                        return gb_fail(error, GB_ERROR_INVALID, "%s: %s: %s is not finite (%g)",
                                       r->path, where, p->name, value);
                }
                at += size;
            }
        }
    }
    return GB_OK;
}

gb_result gb_mesh_check_ply(reader *r, gb_mesh_counts *counts, gb_error *error)
{
    ply_header *h = calloc(1, sizeof *h);
    if (!h)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", r->path);
    h->vertices = h->faces = -1;
    gb_result result = read_ply_header(r, h, error);
    if (result == GB_OK)
        result = check_ply_elements(r, h, error);
    if (result == GB_OK && h->binary) {
        result = walk_binary_ply(r, h, counts, error);
    } else if (result == GB_OK) {
        r->at = h->body;
        r->line = h->body_line;
        result = walk_ascii_ply(r, h, counts, error);
    }
    counts->vertices = h->vertices;
    counts->faces = h->faces;
    free(h);
    return result;
}

