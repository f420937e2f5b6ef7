/* mesh_reader.h — reading mesh files the way OpenMesh 9's readers do, for
 * mesh_check.c's checkers: whitespace-separated tokens and the numbers
 * std::istream >> makes of them, the messages of a refused number, count
 * or index, and binary values of either byte order. Nothing is owned: a
 * reader walks the caller's bytes.
 *
 * The checkers of each format (mesh_check_ply.c, mesh_check_off.c,
 * mesh_check_stl.c) are declared at the end; gb_mesh_check picks one by
 * the file's suffix.
 */
#ifndef GB_MESH_READER_H
#define GB_MESH_READER_H

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh_check.h"

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

static inline int is_space(unsigned char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

static inline int next_token(reader *r, token *t)
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
static inline void skip_line(reader *r)
{
    const unsigned char *newline = memchr(r->at, '\n', (size_t)(r->end - r->at));
    r->at = newline ? newline + 1 : r->end;
    r->line += newline != NULL;
}

static inline size_t left(const reader *r)
{
    return (size_t)(r->end - r->at);
}

static inline int token_is(token t, const char *word)
{
    size_t n = strlen(word);
    return (size_t)(t.end - t.begin) == n && memcmp(t.begin, word, n) == 0;
}

/* The token as a C string for messages, cut at 40 bytes. */
static inline const char *quoted(token t, char out[48])
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
static inline int token_text(token t, char *text, size_t size)
{
    size_t n = (size_t)(t.end - t.begin);
    if (n >= size)
        return 0;
    memcpy(text, t.begin, n);
    text[n] = '\0';
    return 1;
}

static inline int is_digit(char c)
{
    return c >= '0' && c <= '9';
}

/* [+-] digits [. digits] [e [+-] digits], at least one digit before e. */
static inline int is_decimal(const char *s)
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
static inline enum number float_token(token t, float *value)
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
static inline int integer_token(token t, long long *value)
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
static inline int count_token(token t, unsigned long long *value)
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
static inline gb_result bad_number(const reader *r, token t, const char *where, const char *what,
                                   enum number kind, gb_error *error)
{
    char shown[48];
    if (kind == NOT_FINITE)
        return gb_fail(error, GB_ERROR_INVALID, "%s:%d: %s: %s '%s' is not finite", r->path,
                       t.line, where, what, quoted(t, shown));
    return gb_fail(error, GB_ERROR_PARSE, "%s:%d: %s: %s '%s' is not a number", r->path,
                   t.line, where, what, quoted(t, shown));
}

static inline gb_result check_float_token(const reader *r, token t, const char *where,
                                          const char *what, gb_error *error)
{
    float value;
    enum number kind = float_token(t, &value);
    return kind == NUMBER ? GB_OK : bad_number(r, t, where, what, kind, error);
}

static inline gb_result truncated(const reader *r, const char *where, gb_error *error)
{
    return gb_fail(error, GB_ERROR_PARSE, "%s:%d: the file ends in %s", r->path, r->line,
                   where);
}

/* A vertex index of a face: an integer in [0, vertices). */
static inline gb_result check_index(const reader *r, token t, const char *where,
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
static inline gb_result check_corners(const reader *r, token t, const char *where,
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

static inline gb_result binary_truncated(const char *path, const char *where,
                                         gb_error *error)
{
    return gb_fail(error, GB_ERROR_FORMAT, "%s: the file ends in %s", path, where);
}

static inline uint64_t get_uint(const unsigned char *p, int size, int big_endian)
{
    uint64_t value = 0;
    for (int i = 0; i < size; ++i)
        value |= (uint64_t)p[big_endian ? size - 1 - i : i] << (8 * i);
    return value;
}

static inline float get_f32(const unsigned char *p, int big_endian)
{
    uint32_t bits = (uint32_t)get_uint(p, 4, big_endian);
    float value;
    memcpy(&value, &bits, sizeof value);
    return value;
}

static inline double get_f64(const unsigned char *p, int big_endian)
{
    uint64_t bits = get_uint(p, 8, big_endian);
    double value;
    memcpy(&value, &bits, sizeof value);
    return value;
}

/* Whether a binary coordinate is a finite float (a double beyond the
 * float range becomes an infinity when OpenMesh stores it). */
static inline int finite_as_float(double value)
{
    return isfinite(value) && fabs(value) <= 3.4028234663852886e38;
}


/* ---- the checkers of each format ------------------------------------------ */

/* Each walks r from its start; counts as gb_mesh_check's (STL has none). */
gb_result gb_mesh_check_ply(reader *r, gb_mesh_counts *counts, gb_error *error);
gb_result gb_mesh_check_off(reader *r, gb_mesh_counts *counts, gb_error *error);
gb_result gb_mesh_check_stl(reader *r, gb_error *error);

#endif
