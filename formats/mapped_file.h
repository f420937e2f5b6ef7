/* mapped_file.h — a whole regular file mapped read-only, for the readers
 * that walk a file's bytes (containers, the image, mesh and voxel checks).
 *
 *   gb_mapped_file file;
 *   if (gb_mapped_file_open(path, &file, &error) == GB_OK) {
 *       use(file.bytes, file.size);        // bytes is "" for an empty file
 *       gb_mapped_file_close(&file);
 *   }
 *
 * The caller owns the gb_mapped_file and closes it; a failed open leaves
 * nothing to close. Folders, devices and FIFOs are refused by name.
 */
#ifndef GB_MAPPED_FILE_H
#define GB_MAPPED_FILE_H

#include <stddef.h>

#include "result.h"

typedef struct gb_mapped_file {
    const void *bytes;          /* size bytes; "" (not mapped) when size is 0 */
    size_t size;
    void *mapping;              /* owned: NULL for an empty file */
} gb_mapped_file;

gb_result gb_mapped_file_open(const char *path, gb_mapped_file *file, gb_error *error);
void gb_mapped_file_close(gb_mapped_file *file);

#endif
