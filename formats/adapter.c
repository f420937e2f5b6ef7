/* adapter.c — finding, loading and entering an adapter (adapter.h). */
#include "adapter.h"

#include <dlfcn.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

/* The path of adapter NAME: the program's folder, then ../lib/gibake/
 * gibake-NAME.so, into path (size bytes). */
static gb_result adapter_path(const char *name, char *path, size_t size, gb_error *error)
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

/* The entry function of the shared object, or NULL with error set. */
static gb_adapter_entry *load_entry(const gb_adapter *adapter, gb_error *error)
{
    char path[PATH_MAX + 64];
    if (adapter_path(adapter->name, path, sizeof path, error) != GB_OK)
        return NULL;
    void *library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    gb_adapter_entry *entry = library ? (gb_adapter_entry *)dlsym(library, adapter->entry_name)
                                      : NULL;
    if (!entry) {
        const char *why = dlerror();
        gb_fail(error, GB_ERROR_IO, "cannot load the %s adapter %s: %s", adapter->name, path,
                why ? why : "no entry function");
    }
    return entry;
}

const void *gb_adapter_functions(gb_adapter *adapter, gb_error *error)
{
    pthread_mutex_lock(&adapter->lock);
    if (!adapter->functions) {
        gb_adapter_entry *entry = adapter->linked_in ? adapter->linked_in
                                                     : load_entry(adapter, error);
        adapter->functions = entry ? entry(adapter->host) : NULL;
    }
    const void *functions = adapter->functions;
    pthread_mutex_unlock(&adapter->lock);
    return functions;
}
