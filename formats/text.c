#include "text.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <zlib.h>

gb_text gb_text_start(const char *buffer, size_t size, const char *name)
{
    gb_text text = {buffer, buffer + size, name, 0};
    return text;
}

int gb_text_next_line(gb_text *text, gb_span *line)
{
    if (text->cursor >= text->end)
        return 0;
    const char *begin = text->cursor;
    const char *newline = memchr(begin, '\n', (size_t)(text->end - begin));
    const char *end = newline ? newline : text->end;
    text->cursor = newline ? newline + 1 : text->end;
    ++text->line;
    const char *comment = memchr(begin, '#', (size_t)(end - begin));
    if (comment)
        end = comment;
    else if (end > begin && end[-1] == '\r')
        --end;
    line->begin = begin;
    line->end = end;
    return 1;
}

static int is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r';
}

int gb_span_next_token(gb_span *line, gb_span *token)
{
    const char *p = line->begin;
    while (p < line->end && is_blank(*p))
        ++p;
    if (p == line->end) {
        line->begin = p;
        return 0;
    }
    token->begin = p;
    while (p < line->end && !is_blank(*p))
        ++p;
    token->end = p;
    line->begin = p;
    return 1;
}

gb_span gb_span_trim(gb_span line)
{
    while (line.begin < line.end && is_blank(*line.begin))
        ++line.begin;
    while (line.end > line.begin && is_blank(line.end[-1]))
        --line.end;
    return line;
}

size_t gb_span_length(gb_span span)
{
    return (size_t)(span.end - span.begin);
}

int gb_span_is(gb_span span, const char *word)
{
    size_t length = strlen(word);
    return gb_span_length(span) == length && memcmp(span.begin, word, length) == 0;
}

char *gb_span_dup(gb_span span)
{
    size_t length = gb_span_length(span);
    char *copy = malloc(length + 1);
    if (copy) {
        memcpy(copy, span.begin, length);
        copy[length] = '\0';
    }
    return copy;
}

/* The token as a printable, shortened string for messages. */
static void quote_token(gb_span token, char *out, size_t out_size)
{
    size_t n = 0;
    for (const char *p = token.begin; p < token.end && n + 4 < out_size; ++p)
        out[n++] = (*p >= 32 && *p < 127) ? *p : '?';
    if (gb_span_length(token) + 4 >= out_size && n >= 3)
        memcpy(out + n - 3, "...", 3);
    out[n] = '\0';
}

static gb_result bad_float(const gb_text *text, gb_span token, const char *what,
                           int finite, gb_error *error)
{
    char shown[48];
    quote_token(token, shown, sizeof shown);
    if (!finite)
        return gb_fail(error, GB_ERROR_INVALID, "%s:%d: %s '%s' is not finite", text->name,
                       text->line, what, shown);
    return gb_fail(error, GB_ERROR_PARSE, "%s:%d: %s '%s' is not a number", text->name,
                   text->line, what, shown);
}

gb_result gb_text_float(const gb_text *text, gb_span *line, const char *what,
                        float *value, gb_error *error)
{
    gb_span token;
    if (!gb_span_next_token(line, &token))
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: missing %s", text->name, text->line, what);
    char *stop;
    float parsed = strtof(token.begin, &stop);
    if (stop != token.end)
        return bad_float(text, token, what, 1, error);
    if (!isfinite(parsed))
        return bad_float(text, token, what, 0, error);
    *value = parsed;
    return GB_OK;
}

gb_result gb_text_floats(const gb_text *text, gb_span *line, const char *what,
                         float *values, int n, gb_error *error)
{
    static const char *const axes[] = {"x", "y", "z", "w"};
    for (int i = 0; i < n; ++i) {
        char name[96];
        if (n <= 4)
            snprintf(name, sizeof name, "%s %s", what, axes[i]);
        else
            snprintf(name, sizeof name, "%s %d", what, i + 1);
        gb_result result = gb_text_float(text, line, name, &values[i], error);
        if (result != GB_OK)
            return result;
    }
    return GB_OK;
}

gb_result gb_text_int(const gb_text *text, gb_span *line, const char *what,
                      long minimum, long maximum, long *value, gb_error *error)
{
    gb_span token;
    if (!gb_span_next_token(line, &token))
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: missing %s", text->name, text->line, what);
    char shown[48];
    quote_token(token, shown, sizeof shown);
    char *stop;
    errno = 0;
    long parsed = strtol(token.begin, &stop, 10);
    if (stop != token.end)
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: %s '%s' is not an integer", text->name,
                       text->line, what, shown);
    if (errno == ERANGE || parsed < minimum || parsed > maximum)
        return gb_fail(error, GB_ERROR_INVALID, "%s:%d: %s %s is out of range (%ld to %ld)",
                       text->name, text->line, what, shown, minimum, maximum);
    *value = parsed;
    return GB_OK;
}

gb_result gb_text_expect_end(const gb_text *text, gb_span *line, gb_error *error)
{
    gb_span token;
    if (!gb_span_next_token(line, &token))
        return GB_OK;
    char shown[48];
    quote_token(token, shown, sizeof shown);
    return gb_fail(error, GB_ERROR_PARSE, "%s:%d: unexpected '%s'", text->name, text->line, shown);
}

gb_result gb_text_copy(const void *bytes, size_t size, char **buffer, gb_error *error)
{
    *buffer = malloc(size + 1);
    if (!*buffer)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (%zu bytes of text)", size);
    if (size)
        memcpy(*buffer, bytes, size);
    (*buffer)[size] = '\0';
    return GB_OK;
}

static gb_result read_all(gzFile file, const char *path, char **buffer, size_t *size,
                          gb_error *error)
{
    size_t capacity = 1 << 16, used = 0;
    char *data = malloc(capacity);
    for (;;) {
        if (!data)
            return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
        if (capacity - used < 2) {
            capacity *= 2;
            char *bigger = realloc(data, capacity);
            if (!bigger)
                free(data);
            data = bigger;
            continue;
        }
        unsigned chunk = (unsigned)((capacity - used - 1) > (1u << 30) ? (1u << 30)
                                                                       : capacity - used - 1);
        int n = gzread(file, data + used, chunk);
        if (n < 0) {
            int code;
            const char *message = gzerror(file, &code);
            free(data);
            return gb_fail(error, GB_ERROR_IO, "%s: %s", path,
                           code == Z_ERRNO ? strerror(errno) : message);
        }
        if (n == 0)
            break;
        used += (size_t)n;
    }
    data[used] = '\0';
    *buffer = data;
    *size = used;
    return GB_OK;
}

gb_result gb_text_load(const char *path, char **buffer, size_t *size, gb_error *error)
{
    *buffer = NULL;
    *size = 0;
    errno = 0;
    gzFile file = gzopen(path, "rb");
    if (!file)
        return gb_fail(error, GB_ERROR_IO, "%s: %s", path,
                       errno ? strerror(errno) : "cannot open");
    gb_result result = read_all(file, path, buffer, size, error);
    gzclose(file);
    return result;
}

char *gb_path_folder(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        return strdup(".");
    if (slash == path)
        return strdup("/");
    return strndup(path, (size_t)(slash - path));
}

char *gb_path_join(const char *folder, const char *name)
{
    size_t folder_length = strlen(folder), name_length = strlen(name);
    int absolute = name[0] == '/' || name[0] == '\\';
    char *joined = malloc(folder_length + name_length + 2);
    if (!joined)
        return NULL;
    size_t n = 0;
    if (!absolute && strcmp(folder, ".") != 0) {
        memcpy(joined, folder, folder_length);
        n = folder_length;
        if (n && joined[n - 1] != '/')
            joined[n++] = '/';
    }
    for (size_t i = 0; i < name_length; ++i)
        joined[n++] = name[i] == '\\' ? '/' : name[i];
    joined[n] = '\0';
    return joined;
}

int gb_path_has_suffix(const char *path, const char *suffix)
{
    size_t path_length = strlen(path), suffix_length = strlen(suffix);
    return path_length >= suffix_length
        && strcasecmp(path + path_length - suffix_length, suffix) == 0;
}
