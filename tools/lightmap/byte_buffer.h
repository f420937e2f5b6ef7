/* byte_buffer.h — bytes appended to a growing buffer: the glTF export's
 * JSON text and its binary chunk (glb_export.h).
 *
 *   gb_byte_buffer b = {0};
 *   gb_byte_buffer_printf(&b, "{\"asset\":%d}", 2);
 *   gb_byte_buffer_append(&b, floats, n * sizeof *floats);
 *   if (b.failed) ... out of memory, nothing else went wrong
 *   gb_byte_buffer_free(&b);
 *
 * A failed allocation sets `failed` and makes every later call do nothing,
 * so a caller checks once at the end. The text is kept NUL-terminated
 * (the NUL not counted in size). The caller owns the buffer.
 */
#ifndef GB_BYTE_BUFFER_H
#define GB_BYTE_BUFFER_H

#include <stddef.h>

typedef struct gb_byte_buffer {
    char *data;
    size_t size, capacity;
    int failed;
} gb_byte_buffer;

void gb_byte_buffer_append(gb_byte_buffer *buffer, const void *bytes, size_t size);
void gb_byte_buffer_printf(gb_byte_buffer *buffer, const char *format, ...)
    __attribute__((format(printf, 2, 3)));
/* Zero bytes up to a multiple of alignment. */
void gb_byte_buffer_align(gb_byte_buffer *buffer, size_t alignment);
void gb_byte_buffer_free(gb_byte_buffer *buffer);

#endif
