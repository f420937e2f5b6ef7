/* result.h — the one result code every gibake function returns, and the
 * error message that goes with it.
 *
 * Every function that can fail returns a gb_result and, on failure, fills the
 * caller's gb_error with a message of the form "file:line: what is wrong"
 * (or "file: what is wrong" when there is no line). Library code never prints;
 * a tool's main() prints "tool: <message>" and exits non-zero.
 *
 * The caller owns the gb_error (usually on its stack); it may be NULL when
 * the caller does not want the message.
 */
#ifndef GB_RESULT_H
#define GB_RESULT_H

typedef enum gb_result {
    GB_OK = 0,
    GB_ERROR_IO,            /* a file could not be opened, read, written or renamed */
    GB_ERROR_PARSE,         /* a text input is malformed */
    GB_ERROR_FORMAT,        /* a binary input is malformed: magic, version, sizes */
    GB_ERROR_CHECKSUM,      /* a CRC-32 does not match */
    GB_ERROR_INVALID,       /* a value is out of range: NaN, bad index, empty mesh */
    GB_ERROR_STALE,         /* a baked file was made from another scene */
    GB_ERROR_OUT_OF_MEMORY,
    GB_ERROR_UNSUPPORTED,   /* valid input that gibake does not handle */
    GB_ERROR_ARGUMENT,      /* a caller passed a bad argument */
    GB_ERROR_INTERRUPTED,   /* a progress or interrupt callback asked to stop */
} gb_result;

typedef struct gb_error {
    char message[1024];
} gb_error;

/* Formats the message into error (if not NULL) and returns result, so that a
 * failure reads: return gb_fail(error, GB_ERROR_IO, "%s: %s", path, strerror(errno)); */
gb_result gb_fail(gb_error *error, gb_result result, const char *format, ...)
    __attribute__((format(printf, 3, 4)));

/* A short constant name for the result ("io", "parse", ...). */
const char *gb_result_name(gb_result result);

#endif
