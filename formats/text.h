/* text.h — lines, tokens and numbers of gibake's text inputs (OBJ, MTL,
 * scene files), with the file name and line number every message needs.
 *
 * A gb_text walks a NUL-terminated buffer that the caller owns (the NUL lets
 * strtof stop; gb_text_load and gb_text_copy make such buffers). Lines end at
 * LF, CRLF or the end of the buffer; a '#' starts a comment that runs to the
 * end of the line. Tokens are separated by spaces and tabs.
 *
 *   gb_text text = gb_text_start(buffer, size, "dir/a.obj");
 *   gb_span line, word;
 *   while (gb_text_next_line(&text, &line))
 *       if (gb_span_next_token(&line, &word) && gb_span_is(word, "v")) ...
 *
 * Numbers are parsed with strtof, which rounds correctly: "123456.7" gives the
 * same float as strtof("123456.7"). NaN, infinities and values beyond the
 * float range are refused.
 */
#ifndef GB_TEXT_H
#define GB_TEXT_H

#include <stddef.h>

#include "result.h"

typedef struct gb_span {
    const char *begin, *end;    /* [begin, end), not NUL-terminated */
} gb_span;

typedef struct gb_text {
    const char *cursor, *end;   /* what is left to read; *end == '\0' */
    const char *name;           /* the file, for messages */
    int line;                   /* number of the line last returned, from 1 */
} gb_text;

/* buffer[size] must be '\0'. */
gb_text gb_text_start(const char *buffer, size_t size, const char *name);

/* Next line without its end of line and comment; 0 at the end of the text. */
int gb_text_next_line(gb_text *text, gb_span *line);

/* Next token of line (advancing line->begin); 0 when none is left. */
int gb_span_next_token(gb_span *line, gb_span *token);
/* line without leading and trailing blanks (for names that may hold spaces). */
gb_span gb_span_trim(gb_span line);
int gb_span_is(gb_span span, const char *word);
size_t gb_span_length(gb_span span);
/* A malloc'ed NUL-terminated copy, NULL when out of memory. */
char *gb_span_dup(gb_span span);

/* Reads the next token of line as a finite float; what names the value in
 * the message ("file:line: missing x coordinate"). */
gb_result gb_text_float(const gb_text *text, gb_span *line, const char *what,
                        float *value, gb_error *error);
/* Same for n floats: "what" is followed by the index in messages. */
gb_result gb_text_floats(const gb_text *text, gb_span *line, const char *what,
                         float *values, int n, gb_error *error);
/* Reads the next token as a decimal integer in [minimum, maximum]. */
gb_result gb_text_int(const gb_text *text, gb_span *line, const char *what,
                      long minimum, long maximum, long *value, gb_error *error);
/* Fails with "file:line: unexpected 'token'" when line has a token left. */
gb_result gb_text_expect_end(const gb_text *text, gb_span *line, gb_error *error);

/* Reads a whole file, plain or gzip-compressed (zlib's gzread reads both),
 * into a malloc'ed NUL-terminated buffer. */
gb_result gb_text_load(const char *path, char **buffer, size_t *size, gb_error *error);
/* Copies bytes into a malloc'ed NUL-terminated buffer. */
gb_result gb_text_copy(const void *bytes, size_t size, char **buffer, gb_error *error);

/* The folder part of path, "." when it has none; malloc'ed. */
char *gb_path_folder(const char *path);
/* folder/name, or name alone when it is absolute; backslashes in name become
 * slashes; malloc'ed. */
char *gb_path_join(const char *folder, const char *name);
/* Whether path ends with suffix, ignoring ASCII case. */
int gb_path_has_suffix(const char *path, const char *suffix);

#endif
