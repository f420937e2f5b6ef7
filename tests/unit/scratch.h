/* scratch.h — a unit test's scratch folder and its whole-file helpers, so
 * that each test reads and writes its files the same way.
 *
 *   scratch_create("skeleton");            // $TMPDIR/gibake-test-skeleton-XXXXXX
 *   const char *path = scratch_path("a.skel");
 *   scratch_write(path, bytes, size);      // exits 2 when it cannot
 *   unsigned char *back = scratch_read(path, &size);   // NULL if unreadable; free it
 *   scratch_remove();                      // every file in it, then the folder
 *
 * scratch_path returns one of eight buffers in turn: up to eight paths may
 * be held at once (scratch_path_into writes one into the caller's buffer). A failure to create or write is the test's own failure, so it
 * exits with status 2 (prove reports it) rather than returning.
 */
#ifndef GB_SCRATCH_H
#define GB_SCRATCH_H

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static char scratch_folder[256];

static inline void scratch_create(const char *test)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(scratch_folder, sizeof scratch_folder, "%s/gibake-test-%s-XXXXXX",
             tmp && *tmp ? tmp : "/tmp", test);
    if (!mkdtemp(scratch_folder)) {
        perror("mkdtemp");
        exit(2);
    }
}

static inline const char *scratch_path(const char *name)
{
    static char paths[8][512];
    static int next;
    char *path = paths[next++ % 8];
    snprintf(path, sizeof paths[0], "%s/%s", scratch_folder, name);
    return path;
}

/* The same path written into out (size bytes), for a path kept longer than
 * eight scratch_path calls. */
static inline const char *scratch_path_into(const char *name, char *out, size_t size)
{
    snprintf(out, size, "%s/%s", scratch_folder, name);
    return out;
}

/* The whole file at path, in a 16-byte aligned buffer (as the readers that
 * use arrays in place want) of *size bytes and at least 16 spare ones after
 * them (room to append); the caller frees it. NULL when it cannot be read. */
static inline unsigned char *scratch_read(const char *path, size_t *size)
{
    FILE *file = fopen(path, "rb");
    if (!file)
        return NULL;
    unsigned char *bytes = NULL;
    long length = fseek(file, 0, SEEK_END) == 0 ? ftell(file) : -1;
    if (length >= 0 && fseek(file, 0, SEEK_SET) == 0 &&
        (bytes = aligned_alloc(16, ((size_t)length + 31) & ~(size_t)15)) &&
        fread(bytes, 1, (size_t)length, file) != (size_t)length) {
        free(bytes);
        bytes = NULL;
    }
    fclose(file);
    if (bytes)
        *size = (size_t)length;
    return bytes;
}

static inline void scratch_write(const char *path, const void *bytes, size_t size)
{
    FILE *file = fopen(path, "wb");
    if (!file || fwrite(bytes, 1, size, file) != size || fclose(file) != 0) {
        perror(path);
        exit(2);
    }
}

static inline void scratch_write_text(const char *path, const char *text)
{
    scratch_write(path, text, strlen(text));
}

/* Removes every file in the folder (not sub-folders); returns how many. */
static inline int scratch_empty(void)
{
    DIR *dir = opendir(scratch_folder);
    int removed = 0;
    struct dirent *entry;
    while (dir && (entry = readdir(dir)))
        if (strcmp(entry->d_name, ".") && strcmp(entry->d_name, "..") &&
            unlink(scratch_path(entry->d_name)) == 0)
            ++removed;
    if (dir)
        closedir(dir);
    return removed;
}

static inline void scratch_remove(void)
{
    scratch_empty();
    rmdir(scratch_folder);
}

#endif
