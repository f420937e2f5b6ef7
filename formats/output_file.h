/* output_file.h — the one way gibake writes an output file: every tool's -o,
 * the containers (container.h), the OpenVDB adapter and the OpenImageIO
 * adapter go through it.
 *
 * Where the bytes go depends on what is at the path, as with the shell's `>`:
 *   a regular file, or nothing yet: a temporary "NAME.tmp.XXXXXX" is created
 *       beside it (mode 0666 less the umask, as the kernel gives any new
 *       file), written, fsynced, renamed to NAME and the folder fsynced. The
 *       path holds the old file or the whole new one, never a part; any
 *       failure removes the temporary and leaves the old file untouched.
 *   a symlink: followed (to its final target, even when that does not exist
 *       yet); the temporary and the rename are beside the target, so the
 *       link stays a link.
 *   anything else (character or block device, FIFO, socket, /dev/stdout,
 *       /dev/null): written straight through (open O_WRONLY, no rename, no
 *       truncation); "-" is standard output. What was written before a
 *       failure stays written there: a device cannot be rolled back.
 *
 * Interruption: while a temporary exists it is in a small registry; SIGINT,
 * SIGTERM, SIGHUP and SIGPIPE remove every registered temporary and then end
 * the process with the signal's default action (installed once, at the first
 * check or open, and only over a signal's default action: a signal the
 * caller ignores or handles itself is left alone). Each temporary is removed
 * by the thread that writes it: a signal taken by another thread is sent on
 * to the writer, so that no rename races with the removal. SIGXFSZ, when at its default, is
 * ignored, so that a file-size limit (`ulimit -f`) is an EFBIG error that
 * removes the temporary rather than a kill. SIGKILL cannot be caught: the
 * path still holds the old file, and a stray NAME.tmp.XXXXXX may remain.
 *
 * Lifecycle (open → write or let a library write → commit, or abort):
 *   gb_output_file *out;
 *   if (gb_output_file_open(path, GB_OUTPUT_FILE_STREAM, &out, &error)) return ...;
 *   if (gb_output_file_write(out, bytes, size, &error)) { gb_output_file_abort(out); ... }
 *   return gb_output_file_commit(out, &error);      // frees out, whatever the result
 * A library that writes a file by name (OpenVDB, OpenImageIO without an IO
 * proxy) opens with GB_OUTPUT_FILE_BY_NAME and writes the file
 * gb_output_file_name(out) names: the temporary beside the target, or, when
 * the target is not a regular file, a temporary in $TMPDIR (else /tmp) whose
 * bytes commit copies to the target and then removes.
 *
 * The caller owns the gb_output_file from a successful open until commit or
 * abort, which free it. Messages read "path: what is wrong", path as the
 * caller gave it. Several threads may open and write different outputs.
 */
#ifndef GB_OUTPUT_FILE_H
#define GB_OUTPUT_FILE_H

#include <stddef.h>

#include "result.h"

typedef struct gb_output_file gb_output_file;

typedef enum gb_output_file_mode {
    GB_OUTPUT_FILE_STREAM,   /* the caller writes with gb_output_file_write */
    GB_OUTPUT_FILE_BY_NAME,  /* a library writes the file gb_output_file_name names */
} gb_output_file_mode;

/* Checks, before any work, that path can be written: "-" is standard output
 * (not a terminal); an existing device, FIFO or the like must be writable; a
 * folder is refused; otherwise the folder of path (of its target, for a
 * symlink) must exist and let a file be created in it — tried for real, by
 * creating and removing "NAME.check.tmp.XXXXXX" there, so that root on a
 * read-only mount or a missing folder is caught. Messages: "x/y.seg: cannot write in
 * folder 'x': No such file or directory", "d: is a folder", ... Formats whose
 * name matters (images) check their extension on top (image.h). */
gb_result gb_output_file_check(const char *path, gb_error *error);
/* gb_output_file_check of each of the count paths that is not NULL (a
 * tool's output and its optional ones, such as --depfile), in order, up to
 * the first that cannot be written. */
gb_result gb_output_files_check(const char *const *paths, int count, gb_error *error);

/* Opens path for writing as the top comment says; *file is NULL on failure. */
gb_result gb_output_file_open(const char *path, gb_output_file_mode mode,
                              gb_output_file **file, gb_error *error);

/* GB_OUTPUT_FILE_BY_NAME: the file the library writes (it may truncate and
 * rewrite it, and read it back). NULL in stream mode. */
const char *gb_output_file_name(const gb_output_file *file);

/* Stream mode: writes all of data (restarting after EINTR and short writes);
 * "path: cannot write: No space left on device" and the like. */
gb_result gb_output_file_write(gb_output_file *file, const void *data, size_t size,
                               gb_error *error);

/* Makes the output final: fsync, rename into place and fsync the folder (or,
 * for a device, copy the library's temporary to it). On failure the
 * temporary is removed and the old file kept — except when only the last
 * step, the folder's fsync, fails: the complete file is then in place and
 * the message says "written, but cannot sync its folder". Frees file. */
gb_result gb_output_file_commit(gb_output_file *file, gb_error *error);

/* Gives up: removes the temporary (the old file stays) and frees file.
 * NULL does nothing. */
void gb_output_file_abort(gb_output_file *file);

/* open, write, commit (or abort) of the size bytes of data: a whole small
 * file (a depfile, a hash) in one call. */
gb_result gb_output_file_write_bytes(const char *path, const void *data, size_t size,
                                     gb_error *error);

/* The functions above as a table, for the adapters (adapter.h), which link
 * no gibake code and reach the one writer through their host. */
typedef struct gb_output_file_functions {
    gb_result (*check)(const char *path, gb_error *error);
    gb_result (*open)(const char *path, gb_output_file_mode mode, gb_output_file **file,
                      gb_error *error);
    const char *(*name)(const gb_output_file *file);
    gb_result (*write)(gb_output_file *file, const void *data, size_t size, gb_error *error);
    gb_result (*commit)(gb_output_file *file, gb_error *error);
    void (*abort)(gb_output_file *file);
} gb_output_file_functions;

extern const gb_output_file_functions gb_output_file_table;

#endif
