#include "screenshot_path.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

/* The extension's dot in the file name of path, or its end. */
static size_t extension_start(const char *path)
{
    const char *name = strrchr(path, '/');
    name = name ? name + 1 : path;
    const char *dot = strrchr(name, '.');
    return (size_t)((dot && dot != name ? dot : name + strlen(name)) - path);
}

gb_result gb_screenshot_path(const char *base, unsigned *next, char *path, size_t size,
                             gb_error *error)
{
    size_t stem = extension_start(base);
    for (unsigned n = *next; n <= GB_SCREENSHOT_MAX_NUMBER; ++n) {
        int length = snprintf(path, size, "%.*s-%03u%s", (int)stem, base, n, base + stem);
        if (length < 0 || (size_t)length >= size)
            return gb_fail(error, GB_ERROR_ARGUMENT, "%s: the screenshot's name is too long",
                           base);
        if (access(path, F_OK) != 0) {
            *next = n + 1;
            return GB_OK;
        }
    }
    return gb_fail(error, GB_ERROR_IO, "%s: every screenshot number up to %d is taken", base,
                   GB_SCREENSHOT_MAX_NUMBER);
}
