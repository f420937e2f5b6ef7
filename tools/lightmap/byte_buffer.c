/* byte_buffer.c — a growing buffer (byte_buffer.h). */
#include "byte_buffer.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "array_reserve.h"

/* Room for size more bytes and a NUL; 0 when out of memory. */
static int reserve(gb_byte_buffer *b, size_t size)
{
    if (b->failed)
        return 0;
    if (!gb_array_reserve(&b->data, &b->capacity, b->size + size + 1, 1))
        b->failed = 1;
    return !b->failed;
}

void gb_byte_buffer_append(gb_byte_buffer *b, const void *bytes, size_t size)
{
    if (!reserve(b, size))
        return;
    if (size)
        memcpy(b->data + b->size, bytes, size);
    b->size += size;
    b->data[b->size] = '\0';
}

void gb_byte_buffer_printf(gb_byte_buffer *b, const char *format, ...)
{
    va_list arguments;
    va_start(arguments, format);
    int length = vsnprintf(NULL, 0, format, arguments);
    va_end(arguments);
    if (length < 0 || !reserve(b, (size_t)length)) {
        b->failed = 1;
        return;
    }
    va_start(arguments, format);
    vsnprintf(b->data + b->size, (size_t)length + 1, format, arguments);
    va_end(arguments);
    b->size += (size_t)length;
}

void gb_byte_buffer_align(gb_byte_buffer *b, size_t alignment)
{
    static const char zeros[16] = {0};
    while (!b->failed && b->size % alignment)
        gb_byte_buffer_append(b, zeros, alignment - b->size % alignment > sizeof zeros
                                            ? sizeof zeros
                                            : alignment - b->size % alignment);
}

void gb_byte_buffer_free(gb_byte_buffer *b)
{
    free(b->data);
    memset(b, 0, sizeof *b);
}
