/* container_kind.c — see container_kind.h. */
#include "container_kind.h"

#include <string.h>

enum { IN_PLACE_ALIGNMENT = 16 };

/* Checks the version and decodes; closes the container unless the object
 * took it. */
static gb_result decode(gb_container *container, const char *path,
                        const gb_container_kind *kind, void *object, gb_error *error)
{
    gb_result result = gb_container_check_version(container, path, kind->newest_version, error);
    if (result == GB_OK)
        result = kind->decode(container, path, object, error);
    if (result != GB_OK)
        memset(object, 0, kind->object_size);
    if (result != GB_OK || !kind->object_keeps_container)
        gb_container_close(container);
    return result;
}

gb_result gb_container_kind_read(const char *path, const gb_container_kind *kind, void *object,
                                 gb_error *error)
{
    memset(object, 0, kind->object_size);
    gb_container container;
    gb_result result = gb_container_read(path, kind->name, &container, error);
    if (result != GB_OK)
        return result;
    return decode(&container, path, kind, object, error);
}

gb_result gb_container_kind_parse(const void *bytes, size_t size, const char *path,
                                  const gb_container_kind *kind, void *object, gb_error *error)
{
    memset(object, 0, kind->object_size);
    if (kind->object_keeps_container && (uintptr_t)bytes % IN_PLACE_ALIGNMENT)
        return gb_fail(error, GB_ERROR_ARGUMENT, "%s: buffer is not 16-byte aligned", path);
    gb_container container;
    gb_result result = gb_container_parse(bytes, size, path, kind->name, &container, error);
    if (result != GB_OK)
        return result;
    return decode(&container, path, kind, object, error);
}
