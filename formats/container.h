/* container.h — the one binary container every gibake file uses.
 *
 * A container is a magic, a file kind (four ASCII letters such as "SKEL"),
 * the kind's format version, a table of named sections and their payloads,
 * each with a CRC-32. formats/FORMATS.md documents every byte.
 *
 * Writing: create → add sections → commit → destroy.
 *   gb_container_writer *w = gb_container_writer_create("SKEL", 1);
 *   gb_container_add(w, "nodes", nodes, node_bytes);   // w keeps the pointer:
 *                                                      // data must live until commit
 *   gb_container_commit(w, "out.skel", &error);        // through output_file.h
 *   gb_container_writer_destroy(w);
 * The file is written by the one output writer (formats/output_file.h): a
 * failed commit leaves nothing at the final path (and an existing file there
 * untouched); SIGINT or SIGTERM during a commit removes its temporary; a
 * process killed by SIGKILL may leave a stray "<path>.tmp.XXXXXX" beside it,
 * never a partial file at the path. A device, FIFO or "-" (standard output)
 * is written straight through; a symlink is followed.
 *
 * Reading: gb_container_read maps the whole file and checks the magic, the
 * kind, every size, offset and checksum before returning; sections are then
 * views into the mapping (16-byte aligned, so arrays can be used in place)
 * and live until gb_container_close. gb_container_parse does the same on a
 * caller's buffer (which the caller keeps alive), for tests and fuzzing; its
 * views are 16-byte aligned relative to the buffer's start, so absolutely
 * only when the buffer is. Neither trusts a byte: any input gives either a
 * valid container or an error ("path: what is wrong"), never a crash.
 *
 * The container checks its own version; the kind's format version is the
 * caller's to check, with gb_container_check_version for a uniform message.
 */
#ifndef GB_CONTAINER_H
#define GB_CONTAINER_H

#include <stddef.h>
#include <stdint.h>

#include "result.h"

enum { GB_SECTION_NAME_SIZE = 24 };

typedef struct gb_section {
    char name[GB_SECTION_NAME_SIZE]; /* NUL-terminated */
    const void *data;
    uint64_t size;
} gb_section;

typedef struct gb_container {
    char kind[5];              /* NUL-terminated copy of the four letters */
    uint32_t version;          /* the kind's format version */
    uint32_t section_count;
    gb_section *sections;      /* owned by the container */
    void *mapping;             /* owned: the mapped file, or NULL for parse */
    size_t mapping_size;
} gb_container;

typedef struct gb_container_writer gb_container_writer;

/* kind: four ASCII letters or digits; version: the kind's format version,
 * at least 1. Returns NULL only when out of memory; a bad kind or version is
 * reported by gb_container_commit. */
gb_container_writer *gb_container_writer_create(const char *kind, uint32_t version);
/* Adds a section; name is 1 to 23 printable ASCII bytes and unique. data is
 * not copied (it may be NULL when size is 0). Sections are written in the
 * order they are added. */
gb_result gb_container_add(gb_container_writer *writer, const char *name,
                           const void *data, uint64_t size, gb_error *error);
/* Cancellation, in the OpenVDB habit: commit calls interrupt(user) before
 * writing each section's payload and once more before renaming the file into
 * place; a nonzero return cancels the commit, which removes its temporary
 * file and returns GB_ERROR_INTERRUPTED ("path: interrupted, nothing written"). The
 * callback may also report progress. NULL (the default) never interrupts. */
void gb_container_writer_set_interrupt(gb_container_writer *writer,
                                       int (*interrupt)(void *user), void *user);
/* Writes the container to path with gb_output_file (output_file.h):
 * "<path>.tmp.XXXXXX" in path's folder, fsynced, renamed to path, the folder
 * fsynced. On failure the temporary is removed, path is as it was, and the
 * message is "path: what is wrong" (one exception: when only the last step,
 * the folder's fsync, fails, the complete file is in place and the message
 * says "written, but cannot sync its folder"). The writer may commit
 * again. */
gb_result gb_container_commit(gb_container_writer *writer, const char *path,
                              gb_error *error);
void gb_container_writer_destroy(gb_container_writer *writer);

/* One section seen as an array: its name and its items' count and size.
 * data is the payload to write or, after gb_container_find_arrays, the
 * payload found (NULL where it stopped). */
typedef struct gb_container_array {
    const char *name;
    uint64_t count, item_size;
    const void *data;
} gb_container_array;

/* Creates a writer of kind and version, adds the arrays in order and commits
 * them to path: the whole write of a file in one call. */
gb_result gb_container_write_arrays(const char *path, const char *kind, uint32_t version,
                                    const gb_container_array *arrays, int count,
                                    gb_error *error);

/* expected_kind may be NULL to accept any kind; on success *out holds the
 * container, on failure *out is zeroed and nothing needs closing. path is used
 * in messages. */
gb_result gb_container_read(const char *path, const char *expected_kind,
                            gb_container *out, gb_error *error);
gb_result gb_container_parse(const void *bytes, size_t size, const char *path,
                             const char *expected_kind, gb_container *out,
                             gb_error *error);
/* Fails with "path: format version 3 is newer than this program (2)" when the
 * container's kind version is above newest, or when it is 0. */
gb_result gb_container_check_version(const gb_container *container, const char *path,
                                     uint32_t newest, gb_error *error);
/* NULL when the container has no section of that name. */
const gb_section *gb_container_find(const gb_container *container, const char *name);
/* The section `name` as an array of count elements of element_size bytes,
 * in *out. Fails (GB_ERROR_FORMAT) with "path: no "name" section" or
 * "path: "name" section has N bytes, C x S = M expected"; with alignment
 * above 1 (16 for a caller that uses the array in place), also when the
 * section's data is not that aligned in memory (GB_ERROR_ARGUMENT: a
 * gb_container_parse buffer that was not). */
gb_result gb_container_find_array(const gb_container *container, const char *name,
                                  uint64_t count, uint64_t element_size, unsigned alignment,
                                  const char *path, const gb_section **out, gb_error *error);
/* gb_container_find_array for each of the arrays in order, setting its data
 * to the section's payload; stops at the first that fails. */
gb_result gb_container_find_arrays(const gb_container *container, gb_container_array *arrays,
                                   int count, unsigned alignment, const char *path,
                                   gb_error *error);
void gb_container_close(gb_container *container);

#endif
