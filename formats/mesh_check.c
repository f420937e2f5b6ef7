/* mesh_check.c — PLY, OFF and STL bytes checked before OpenMesh reads them
 * (see mesh_check.h for what is refused and why). Each reader below
 * follows the OpenMesh 9.0 reader of its format step by step, so that a
 * count, an index or a number is checked exactly where OpenMesh will use
 * it. */
#include "mesh_check.h"
#include "mapped_file.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "text.h"

/* ---- tokens and numbers, as std::istream >> reads them -------------------- */

typedef struct reader {
    const unsigned char *begin, *at, *end;
    const char *path;
    int line;                   /* line of at, from 1 */
} reader;

typedef struct token {
    const unsigned char *begin, *end;
    int line;
} token;

static int is_space(unsigned char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

static int next_token(reader *r, token *t)
{
    while (r->at < r->end && is_space(*r->at)) {
        r->line += *r->at == '\n';
        ++r->at;
    }
    if (r->at == r->end)
        return 0;
    t->begin = r->at;
    t->line = r->line;
    while (r->at < r->end && !is_space(*r->at))
        ++r->at;
    t->end = r->at;
    return 1;
}

/* Past the end of the current line, as std::getline. */
static void skip_line(reader *r)
{
    const unsigned char *newline = memchr(r->at, '\n', (size_t)(r->end - r->at));
    r->at = newline ? newline + 1 : r->end;
    r->line += newline != NULL;
}

static size_t left(const reader *r)
{
    return (size_t)(r->end - r->at);
}

static int token_is(token t, const char *word)
{
    size_t n = strlen(word);
    return (size_t)(t.end - t.begin) == n && memcmp(t.begin, word, n) == 0;
}

/* The token as a C string for messages, cut at 40 bytes. */
static const char *quoted(token t, char out[48])
{
    size_t n = (size_t)(t.end - t.begin), shown = n > 40 ? 37 : n;
    memcpy(out, t.begin, shown);
    strcpy(out + shown, n > 40 ? "..." : "");
    for (size_t i = 0; i < shown; ++i)
        if (out[i] < 0x20 || out[i] == 0x7f)
            out[i] = '?';
    return out;
}

/* Copies a token into text (NUL-terminated); 0 when too long. */
static int token_text(token t, char *text, size_t size)
{
    size_t n = (size_t)(t.end - t.begin);
    if (n >= size)
        return 0;
    memcpy(text, t.begin, n);
    text[n] = '\0';
    return 1;
}

static int is_digit(char c)
{
    return c >= '0' && c <= '9';
}

/* [+-] digits [. digits] [e [+-] digits], at least one digit before e. */
static int is_decimal(const char *s)
{
    s += *s == '+' || *s == '-';
    int digits = 0;
    for (; is_digit(*s); ++s)
        ++digits;
    if (*s == '.')
        for (++s; is_digit(*s); ++s)
            ++digits;
    if (!digits)
        return 0;
    if (*s == 'e' || *s == 'E') {
        ++s;
        s += *s == '+' || *s == '-';
        if (!is_digit(*s))
            return 0;
        while (is_digit(*s))
            ++s;
    }
    return *s == '\0';
}

enum number { NUMBER, NOT_FINITE, NOT_A_NUMBER };

/* What `stream >> float` makes of the token: a number, or a failure that
 * stops every later read; strtof rounds as libstdc++ does, and overflows
 * to an infinity where the stream fails. */
static enum number float_token(token t, float *value)
{
    char text[128];
    if (!token_text(t, text, sizeof text))
        return NOT_A_NUMBER;
    char *stop;
    float parsed = strtof(text, &stop);
    if (*stop != '\0' || stop == text)
        return NOT_A_NUMBER;
    if (!isfinite(parsed))
        return NOT_FINITE;  /* nan, inf, infinity, 1e39 */
    if (!is_decimal(text))
        return NOT_A_NUMBER;  /* hexadecimal: the stream reads "0" and stops */
    *value = parsed;
    return NUMBER;
}

/* [+-] digits into a long long; 0 when not that or out of range. */
static int integer_token(token t, long long *value)
{
    char text[32];
    if (!token_text(t, text, sizeof text))
        return 0;
    const char *s = text + (text[0] == '+' || text[0] == '-');
    if (!is_digit(*s))
        return 0;
    for (; *s; ++s)
        if (!is_digit(*s))
            return 0;
    errno = 0;
    char *stop;
    *value = strtoll(text, &stop, 10);
    return errno == 0;
}

/* A count: digits (an optional '+') up to 2^32 - 1, as an unsigned int. */
static int count_token(token t, unsigned long long *value)
{
    long long v;
    if (t.begin < t.end && *t.begin == '-')
        return 0;
    if (!integer_token(t, &v) || v > (long long)UINT32_MAX)
        return 0;
    *value = (unsigned long long)v;
    return 1;
}

/* "path:line: where: what 'token' is not finite / not a number". */
static gb_result bad_number(const reader *r, token t, const char *where, const char *what,
                            enum number kind, gb_error *error)
{
    char shown[48];
    if (kind == NOT_FINITE)
        return gb_fail(error, GB_ERROR_INVALID, "%s:%d: %s: %s '%s' is not finite", r->path,
                       t.line, where, what, quoted(t, shown));
    return gb_fail(error, GB_ERROR_PARSE, "%s:%d: %s: %s '%s' is not a number", r->path,
                   t.line, where, what, quoted(t, shown));
}

static gb_result check_float_token(const reader *r, token t, const char *where,
                                   const char *what, gb_error *error)
{
    float value;
    enum number kind = float_token(t, &value);
    return kind == NUMBER ? GB_OK : bad_number(r, t, where, what, kind, error);
}

static gb_result truncated(const reader *r, const char *where, gb_error *error)
{
    return gb_fail(error, GB_ERROR_PARSE, "%s:%d: the file ends in %s", r->path, r->line,
                   where);
}

/* A vertex index of a face: an integer in [0, vertices). */
static gb_result check_index(const reader *r, token t, const char *where,
                             unsigned long long vertices, gb_error *error)
{
    long long index;
    char shown[48];
    if (!integer_token(t, &index))
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: %s: vertex index '%s' is not an integer",
                       r->path, t.line, where, quoted(t, shown));
    if (index < 0 || (unsigned long long)index >= vertices)
        return gb_fail(error, GB_ERROR_INVALID,
                       "%s:%d: %s: vertex index %lld out of range (%llu vertices)", r->path,
                       t.line, where, index, vertices);
    return GB_OK;
}

/* A face's corner count against what is left: each corner takes at least
 * 2 bytes in ASCII (a digit and a blank, the last one maybe none). */
static gb_result check_corners(const reader *r, token t, const char *where,
                               unsigned long long *corners, gb_error *error)
{
    char shown[48];
    if (!count_token(t, corners))
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: %s: corner count '%s' is not a count",
                       r->path, t.line, where, quoted(t, shown));
    if (*corners > (left(r) + 1) / 2)
        return gb_fail(error, GB_ERROR_FORMAT,
                       "%s:%d: %s: %llu corners, more than the rest of the file holds",
                       r->path, t.line, where, *corners);
    return GB_OK;
}

/* ---- binary values ---------------------------------------------------------- */

static uint64_t get_uint(const unsigned char *p, int size, int big_endian)
{
    uint64_t value = 0;
    for (int i = 0; i < size; ++i)
        value |= (uint64_t)p[big_endian ? size - 1 - i : i] << (8 * i);
    return value;
}

static float get_f32(const unsigned char *p, int big_endian)
{
    uint32_t bits = (uint32_t)get_uint(p, 4, big_endian);
    float value;
    memcpy(&value, &bits, sizeof value);
    return value;
}

static double get_f64(const unsigned char *p, int big_endian)
{
    uint64_t bits = get_uint(p, 8, big_endian);
    double value;
    memcpy(&value, &bits, sizeof value);
    return value;
}

/* Whether a binary coordinate is a finite float (a double beyond the
 * float range becomes an infinity when OpenMesh stores it). */
static int finite_as_float(double value)
{
    return isfinite(value) && fabs(value) <= 3.4028234663852886e38;
}

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
    if (!strcmp(e->name, "vertex"))
        h->vertices = (long long)e->count;
    else if (!strcmp(e->name, "face"))
        h->faces = (long long)e->count;
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
                unsigned long long corners;
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

static gb_result binary_truncated(const char *path, const char *where, gb_error *error)
{
    return gb_fail(error, GB_ERROR_FORMAT, "%s: the file ends in %s", path, where);
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

static gb_result check_ply(reader *r, gb_mesh_counts *counts, gb_error *error)
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
        unsigned long long corners;
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

static gb_result check_off(reader *r, gb_mesh_counts *counts, gb_error *error)
{
    off_header h;
    gb_result result = read_off_keyword(r, &h, error);
    if (result != GB_OK)
        return result;
    return h.binary ? walk_binary_off(r, &h, counts, error) : walk_ascii_off(r, &h, counts, error);
}

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

static gb_result check_stl(reader *r, gb_error *error)
{
    size_t size = (size_t)(r->end - r->begin);
    if (size >= 84) {
        uint64_t facets = get_uint(r->begin + 80, 4, 0);
        if (84 + 50 * facets == size)
            return walk_binary_stl(r, facets, error);
    }
    return walk_ascii_stl(r, error);
}

/* ---- entry points --------------------------------------------------------------- */

gb_result gb_mesh_check(const void *bytes, size_t size, const char *path,
                        gb_mesh_counts *counts, gb_error *error)
{
    reader r = {bytes, bytes, (const unsigned char *)bytes + size, path, 1};
    counts->vertices = counts->faces = -1;
    counts->short_faces = 0;
    if (gb_path_has_suffix(path, ".ply"))
        return check_ply(&r, counts, error);
    if (gb_path_has_suffix(path, ".off"))
        return check_off(&r, counts, error);
    if (gb_path_has_suffix(path, ".stl"))
        return check_stl(&r, error);
    return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: not a .ply, .off or .stl file", path);
}

gb_result gb_mesh_check_file(const char *path, gb_mesh_counts *counts, gb_error *error)
{
    counts->vertices = counts->faces = -1;
    counts->short_faces = 0;
    gb_mapped_file mapped;
    gb_result result = gb_mapped_file_open(path, &mapped, error);
    if (result != GB_OK)
        return result;
    result = gb_mesh_check(mapped.bytes, mapped.size, path, counts, error);
    gb_mapped_file_close(&mapped);
    return result;
}
