#include "result.h"

#include <stdarg.h>
#include <stdio.h>

gb_result gb_fail(gb_error *error, gb_result result, const char *format, ...)
{
    if (error) {
        va_list arguments;
        va_start(arguments, format);
        vsnprintf(error->message, sizeof error->message, format, arguments);
        va_end(arguments);
    }
    return result;
}

const char *gb_result_name(gb_result result)
{
    switch (result) {
    case GB_OK: return "ok";
    case GB_ERROR_IO: return "io";
    case GB_ERROR_PARSE: return "parse";
    case GB_ERROR_FORMAT: return "format";
    case GB_ERROR_CHECKSUM: return "checksum";
    case GB_ERROR_INVALID: return "invalid";
    case GB_ERROR_STALE: return "stale";
    case GB_ERROR_OUT_OF_MEMORY: return "out of memory";
    case GB_ERROR_UNSUPPORTED: return "unsupported";
    case GB_ERROR_ARGUMENT: return "argument";
    case GB_ERROR_INTERRUPTED: return "interrupted";
    }
    return "unknown";
}
