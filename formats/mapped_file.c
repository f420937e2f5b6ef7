/* mapped_file.c — gb_mapped_file_open and _close (mapped_file.h). */
#include "mapped_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

gb_result gb_mapped_file_open(const char *path, gb_mapped_file *file, gb_error *error)
{
    *file = (gb_mapped_file){.bytes = ""};
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return gb_fail(error, GB_ERROR_IO, "%s: %s", path, strerror(errno));
    struct stat status;
    gb_result result = GB_OK;
    if (fstat(fd, &status) != 0)
        result = gb_fail(error, GB_ERROR_IO, "%s: %s", path, strerror(errno));
    else if (S_ISDIR(status.st_mode))
        result = gb_fail(error, GB_ERROR_IO, "%s: is a folder, not a file", path);
    else if (!S_ISREG(status.st_mode))
        result = gb_fail(error, GB_ERROR_IO, "%s: not a regular file", path);
    else if ((uintmax_t)status.st_size > SIZE_MAX)
        result = gb_fail(error, GB_ERROR_IO, "%s: too large to map", path);
    size_t size = result == GB_OK ? (size_t)status.st_size : 0;
    if (result == GB_OK && size > 0) {
        void *address = mmap(NULL, size, PROT_READ, MAP_PRIVATE, fd, 0);
        if (address == MAP_FAILED)
            result = gb_fail(error, GB_ERROR_IO, "%s: cannot map: %s", path, strerror(errno));
        else
            *file = (gb_mapped_file){.bytes = address, .size = size, .mapping = address};
    }
    close(fd);
    return result;
}

void gb_mapped_file_close(gb_mapped_file *file)
{
    if (file->mapping)
        munmap(file->mapping, file->size);
    *file = (gb_mapped_file){.bytes = ""};
}
