/* container_kind.h — reading one kind of container file (skeleton,
 * segmentation, photon map, light octree, VPL set) in one place.
 *
 * Each format describes its kind once: the four letters, the newest format
 * version it reads, how a checked container becomes its object, and whether
 * the object keeps viewing the container (its arrays used in place) or copies
 * what it needs. gb_container_kind_read opens a file, gb_container_kind_parse
 * a caller's buffer; both check the kind and version, decode, and close the
 * container unless the object keeps it (the object's own free then closes
 * it). On failure the object is zeroed and nothing needs freeing.
 *
 *   static const gb_container_kind skeleton_kind = {
 *       "SKEL", GB_SKELETON_VERSION, sizeof(gb_skeleton), decode_skeleton, 0};
 *   gb_container_kind_read(path, &skeleton_kind, skeleton, &error);
 */
#ifndef GB_CONTAINER_KIND_H
#define GB_CONTAINER_KIND_H

#include <stddef.h>
#include <stdint.h>

#include "container.h"

typedef struct gb_container_kind {
    const char *name;          /* the four letters, e.g. "SKEL" */
    uint32_t newest_version;   /* the newest format version this program reads */
    size_t object_size;        /* bytes of the object decode fills */
    /* Fills the zeroed object from a container of this kind and version.
     * On failure it leaves nothing to free in the object (it frees what it
     * allocated) and never closes the container. */
    gb_result (*decode)(const gb_container *container, const char *path, void *object,
                        gb_error *error);
    /* Nonzero when, on success, decode has copied the container into the
     * object, whose arrays view it in place: the container is then not
     * closed here, and a parsed buffer must be 16-byte aligned. */
    int object_keeps_container;
} gb_container_kind;

/* The file at path, decoded into object (object_size bytes, zeroed first). */
gb_result gb_container_kind_read(const char *path, const gb_container_kind *kind, void *object,
                                 gb_error *error);
/* The same on bytes, which the caller keeps alive while the object lives
 * if the object keeps the container; path is used in messages. */
gb_result gb_container_kind_parse(const void *bytes, size_t size, const char *path,
                                  const gb_container_kind *kind, void *object, gb_error *error);

#endif
