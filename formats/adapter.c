#include "adapter.h"

#include <dlfcn.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

gb_result gb_adapter_path(const char *name, char *path, size_t size, gb_error *error)
{
    char program[PATH_MAX];
    ssize_t length = readlink("/proc/self/exe", program, sizeof program - 1);
    if (length <= 0)
        return gb_fail(error, GB_ERROR_IO, "the %s adapter: cannot find the program's folder "
                       "(/proc/self/exe)", name);
    program[length] = '\0';
    char *slash = strrchr(program, '/');
    *(slash ? slash : program) = '\0';
    if (snprintf(path, size, "%s/../lib/gibake/gibake-%s.so", program, name) >= (int)size)
        return gb_fail(error, GB_ERROR_IO, "the %s adapter: path too long", name);
    return GB_OK;
}

void *gb_adapter_entry(const char *name, const char *entry, gb_error *error)
{
    char path[PATH_MAX + 64];
    if (gb_adapter_path(name, path, sizeof path, error) != GB_OK)
        return NULL;
    void *library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    void *function = library ? dlsym(library, entry) : NULL;
    if (!function) {
        const char *why = dlerror();
        gb_fail(error, GB_ERROR_IO, "cannot load the %s adapter %s: %s", name, path,
                why ? why : "no entry function");
    }
    return function;
}
