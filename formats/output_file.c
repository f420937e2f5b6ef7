/* output_file.c — the one output writer (API and behaviour in
 * formats/output_file.h): temporary beside the target, fsync, rename, fsync
 * of the folder; straight through to devices and FIFOs; symlinks followed;
 * temporaries removed on SIGINT, SIGTERM, SIGHUP and SIGPIPE.
 *
 * Decided here:
 *   - The temporary is created with open(O_CREAT | O_EXCL, 0666), so the
 *     kernel applies the umask (and a folder's default ACL) exactly as for
 *     any new file: umask() is never called (it would change the mask, for a
 *     moment, for every thread) and /proc is not read.
 *   - Its name is the target's plus ".tmp." and six random letters or
 *     digits: visible beside the target, never matching the target's
 *     extension, so a `make` rule or a glob never picks up a stale one.
 *   - A temporary's name is registered before the open that creates it and
 *     forgotten after the rename or unlink that ends it, so no signal finds
 *     it on disk and unregistered (output.t caught one that came right
 *     after the open when the order was the other way). The price: a signal
 *     between the registration and an open that fails with EEXIST removes
 *     the file of that name, which can only be another NAME.tmp.XXXXXX.
 */
#include "output_file.h"

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <time.h>
#include <unistd.h>

enum {
    SLOT_COUNT = 32,     /* temporaries alive at once that a signal removes */
    NAME_TRIES = 100,    /* random names tried before giving up */
    MAX_LINKS = 40,      /* symlinks followed, as the kernel's ELOOP limit */
    SUFFIX_LETTERS = 6,
    COPY_CHUNK = 1 << 20,
};

static const char TEMPORARY_SUFFIX[] = ".tmp.";

/* ---- the registry of live temporaries and the signal handler ---- */

/* A slot is FREE, CLAIMED (being filled in), LIVE (a temporary on disk) or
 * REMOVED (unlinked by the signal handler; its owner still holds it). */
enum { SLOT_FREE, SLOT_CLAIMED, SLOT_LIVE, SLOT_REMOVED };

typedef struct slot {
    atomic_int state;
    atomic_int owner;       /* the thread that writes it (gettid) */
    char path[PATH_MAX];
} slot;

static slot slots[SLOT_COUNT];
static pthread_once_t handlers_once = PTHREAD_ONCE_INIT;
static const int caught_signals[] = {SIGINT, SIGTERM, SIGHUP, SIGPIPE};

static pid_t current_thread(void)
{
    return (pid_t)syscall(SYS_gettid);
}

/* Async-signal-safe: atomics, unlink, tgkill, sigaction and raise only.
 * A temporary is removed by the thread that writes it: the signal may have
 * been taken by another thread (the kernel gives a process's signal to any
 * thread that does not block it), and that thread removing the file under
 * the writer's feet would race with its rename. So a temporary of another
 * thread gets the signal sent on to that thread, and this one goes on; the
 * last thread with temporaries ends the process with the signal's default
 * action (the signal stays blocked while this runs, so the raise takes
 * effect as the handler returns). */
static void remove_temporaries(int signal_number)
{
    int saved = errno;
    pid_t self = current_thread(), process = getpid();
    int forwarded = 0;
    for (int i = 0; i < SLOT_COUNT; ++i) {
        if (atomic_load(&slots[i].state) != SLOT_LIVE)
            continue;
        pid_t owner = atomic_load(&slots[i].owner);
        if (owner != self && syscall(SYS_tgkill, process, owner, signal_number) == 0) {
            forwarded = 1;
            continue;
        }
        unlink(slots[i].path);
        int live = SLOT_LIVE;
        atomic_compare_exchange_strong(&slots[i].state, &live, SLOT_REMOVED);
    }
    if (!forwarded) {
        struct sigaction default_action;
        default_action.sa_handler = SIG_DFL;
        default_action.sa_flags = 0;
        sigemptyset(&default_action.sa_mask);
        sigaction(signal_number, &default_action, NULL);
        raise(signal_number);
    }
    errno = saved;
}

/* Only over the default action: a signal ignored (a background job's SIGINT)
 * or handled by the program stays as it is. */
static void install_handlers(void)
{
    struct sigaction action, old;
    memset(&action, 0, sizeof action);
    action.sa_handler = remove_temporaries;
    sigemptyset(&action.sa_mask);
    for (size_t i = 0; i < sizeof caught_signals / sizeof *caught_signals; ++i)
        sigaddset(&action.sa_mask, caught_signals[i]);
    for (size_t i = 0; i < sizeof caught_signals / sizeof *caught_signals; ++i)
        if (sigaction(caught_signals[i], NULL, &old) == 0 && !(old.sa_flags & SA_SIGINFO) &&
            old.sa_handler == SIG_DFL)
            sigaction(caught_signals[i], &action, NULL);
    /* Past `ulimit -f` a write then fails with EFBIG instead of killing. */
    if (sigaction(SIGXFSZ, NULL, &old) == 0 && !(old.sa_flags & SA_SIGINFO) &&
        old.sa_handler == SIG_DFL) {
        struct sigaction ignore;
        memset(&ignore, 0, sizeof ignore);
        ignore.sa_handler = SIG_IGN;
        sigemptyset(&ignore.sa_mask);
        sigaction(SIGXFSZ, &ignore, NULL);
    }
}

/* A slot for name, or -1 when every slot is taken (the temporary is then
 * still written and removed on failure, but not by a signal). */
static int register_temporary(const char *name)
{
    pthread_once(&handlers_once, install_handlers);
    if (strlen(name) >= PATH_MAX)
        return -1;
    for (int i = 0; i < SLOT_COUNT; ++i) {
        int expected = SLOT_FREE;
        if (atomic_compare_exchange_strong(&slots[i].state, &expected, SLOT_CLAIMED)) {
            strcpy(slots[i].path, name);
            atomic_store(&slots[i].owner, current_thread());
            atomic_store(&slots[i].state, SLOT_LIVE);
            return i;
        }
    }
    return -1;
}

static void forget_temporary(int index)
{
    if (index >= 0)
        atomic_store(&slots[index].state, SLOT_FREE);
}

/* ---- names ---- */

static char *concatenate(const char *a, const char *b, const char *c)
{
    size_t la = strlen(a), lb = strlen(b), lc = strlen(c);
    char *text = malloc(la + lb + lc + 1);
    if (text) {
        memcpy(text, a, la);
        memcpy(text + la, b, lb);
        memcpy(text + la + lb, c, lc + 1);
    }
    return text;
}

/* The folder part of path ("." when it has none), malloc'ed. */
static char *folder_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        return strdup(".");
    return strndup(path, slash == path ? 1 : (size_t)(slash - path));
}

/* The descriptor that "-", /dev/stdout, /dev/stderr, /dev/fd/N and
 * /proc/self/fd/N name, or -1. These are written through that descriptor,
 * as the shell does: renaming onto them would replace the file standard
 * output was opened on, and what else the program printed would be lost. */
static int descriptor_of(const char *path)
{
    static const char *const prefixes[] = {"/dev/fd/", "/proc/self/fd/"};
    if (strcmp(path, "-") == 0 || strcmp(path, "/dev/stdout") == 0)
        return STDOUT_FILENO;
    if (strcmp(path, "/dev/stderr") == 0)
        return STDERR_FILENO;
    for (int i = 0; i < 2; ++i) {
        size_t length = strlen(prefixes[i]);
        if (strncmp(path, prefixes[i], length) != 0 || !path[length])
            continue;
        char *end;
        long fd = strtol(path + length, &end, 10);
        if (*end == '\0' && fd >= 0 && fd <= INT_MAX && path[length] >= '0' &&
            path[length] <= '9')
            return (int)fd;
    }
    return -1;
}

/* The last component of path, "stdout" for a descriptor. */
static const char *base_of(const char *path)
{
    if (descriptor_of(path) >= 0)
        return "stdout";
    const char *slash = strrchr(path, '/');
    return slash && slash[1] ? slash + 1 : path;
}

/* The file a chain of symlinks starting at path ends at (it need not exist),
 * malloc'ed; NULL with errno set on ELOOP or an unreadable link. A relative
 * link is relative to the folder the link is in. The chain stops at a name
 * of descriptor_of. */
static char *follow_links(const char *path)
{
    char *current = strdup(path);
    for (int hops = 0; current; ++hops) {
        struct stat status;
        if (descriptor_of(current) >= 0 || lstat(current, &status) != 0 ||
            !S_ISLNK(status.st_mode))
            return current;
        char target[PATH_MAX];
        ssize_t length = hops < MAX_LINKS ? readlink(current, target, sizeof target - 1) : -1;
        if (hops >= MAX_LINKS)
            errno = ELOOP;
        if (length < 0) {
            free(current);
            return NULL;
        }
        target[length] = '\0';
        char *next;
        if (target[0] == '/' || !strchr(current, '/')) {
            next = strdup(target);
        } else {
            char *folder = folder_of(current);
            next = folder ? concatenate(folder, "/", target) : NULL;
            free(folder);
        }
        free(current);
        current = next;
    }
    errno = ENOMEM;
    return NULL;
}

static void random_letters(char *out, int count)
{
    static const char letters[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
    static atomic_uint_fast64_t counter;
    uint64_t x = 0;
    if (getrandom(&x, sizeof x, GRND_NONBLOCK) != (ssize_t)sizeof x) {
        struct timespec now;
        clock_gettime(CLOCK_REALTIME, &now);
        x = (uint64_t)now.tv_nsec ^ ((uint64_t)now.tv_sec << 30) ^ ((uint64_t)getpid() << 12);
    }
    x += (uint64_t)atomic_fetch_add(&counter, 1) * 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    x ^= x >> 31;
    for (int i = 0; i < count; ++i, x /= 62)
        out[i] = letters[x % 62];
    out[count] = '\0';
}

/* Creates "<stem>.tmp.XXXXXX" (mode 0666 less the umask), registers it and
 * returns its descriptor, or -1 with errno set. *name is malloc'ed. */
static int create_temporary(const char *stem, char **name, int *slot_index)
{
    *name = NULL;
    *slot_index = -1;
    if (strlen(stem) + sizeof TEMPORARY_SUFFIX + SUFFIX_LETTERS >= PATH_MAX) {
        errno = ENAMETOOLONG;
        return -1;
    }
    for (int attempt = 0; attempt < NAME_TRIES; ++attempt) {
        char letters[SUFFIX_LETTERS + 1];
        random_letters(letters, SUFFIX_LETTERS);
        char *candidate = concatenate(stem, TEMPORARY_SUFFIX, letters);
        if (!candidate) {
            errno = ENOMEM;
            return -1;
        }
        int slot_index_now = register_temporary(candidate);
        int fd = open(candidate, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOCTTY, 0666);
        if (fd >= 0) {
            *slot_index = slot_index_now;
            *name = candidate;
            return fd;
        }
        int saved = errno;
        forget_temporary(slot_index_now);
        free(candidate);
        errno = saved;
        if (errno != EEXIST)
            return -1;
    }
    return -1;
}

static void remove_temporary(char **name, int *slot_index)
{
    if (*name)
        unlink(*name);
    forget_temporary(*slot_index);
    free(*name);
    *name = NULL;
    *slot_index = -1;
}

/* ---- the output file ---- */

typedef enum target_kind {
    TARGET_FILE,    /* a regular file or a new one: temporary and rename */
    TARGET_DEVICE,  /* anything else that exists: opened and written through */
    TARGET_DESCRIPTOR, /* "-", /dev/stdout, /dev/fd/N: that open descriptor */
} target_kind;

struct gb_output_file {
    char *path;          /* as the caller gave it, for messages */
    char *final;         /* TARGET_FILE: what the temporary is renamed to */
    char *temporary;     /* beside final, or in $TMPDIR for a device by name */
    int slot;            /* the registry slot of temporary, or -1 */
    int fd;              /* where gb_output_file_write writes, or -1 */
    int target_fd;       /* TARGET_DEVICE, TARGET_DESCRIPTOR: the target, or -1 */
    target_kind kind;
    gb_output_file_mode mode;
};

static void free_file(gb_output_file *file)
{
    if (file->fd >= 0 && file->fd != file->target_fd)
        close(file->fd);
    if (file->target_fd >= 0 && file->kind == TARGET_DEVICE)
        close(file->target_fd);
    remove_temporary(&file->temporary, &file->slot);
    free(file->path);
    free(file->final);
    free(file);
}

static gb_result write_all(int fd, const void *data, size_t size, const char *path,
                           gb_error *error)
{
    const unsigned char *bytes = data;
    while (size > 0) {
        size_t chunk = size > (1u << 30) ? (1u << 30) : size;
        ssize_t written = write(fd, bytes, chunk);
        if (written < 0 && errno == EINTR)
            continue;
        if (written <= 0)
            return gb_fail(error, GB_ERROR_IO, "%s: cannot write: %s", path,
                           written < 0 ? strerror(errno) : "no progress");
        bytes += written;
        size -= (size_t)written;
    }
    return GB_OK;
}

/* Where a library writes by name when the target is a device. */
static char *staging_stem(const char *path)
{
    const char *folder = getenv("TMPDIR");
    if (!folder || !*folder)
        folder = "/tmp";
    char *prefix = concatenate(folder, "/gibake-", "");
    char *stem = prefix ? concatenate(prefix, base_of(path), "") : NULL;
    free(prefix);
    return stem;
}

/* What is at path, symlinks followed: *final (malloc'ed) is the last name of
 * the chain; *descriptor >= 0 when it names an open descriptor; *status_of
 * is 0 when *final exists (with *status), else the errno of stat. */
static gb_result resolve(const char *path, char **final, int *descriptor,
                         struct stat *status, int *status_of, gb_error *error)
{
    *final = follow_links(path);
    if (!*final)
        return gb_fail(error, GB_ERROR_IO, "%s: %s", path, strerror(errno));
    *descriptor = descriptor_of(*final);
    *status_of = stat(*final, status) == 0 ? 0 : errno;
    if (*descriptor < 0 && *status_of == 0 && S_ISDIR(status->st_mode))
        return gb_fail(error, GB_ERROR_IO, "%s: is a folder", path);
    return GB_OK;
}

static gb_result open_target(gb_output_file *file, gb_error *error)
{
    const char *path = file->path;
    struct stat status;
    int descriptor, status_of;
    gb_result result = resolve(path, &file->final, &descriptor, &status, &status_of, error);
    if (result != GB_OK)
        return result;
    if (descriptor >= 0) {
        file->kind = TARGET_DESCRIPTOR;
        file->target_fd = descriptor;
        /* what the program printed there through stdio comes first */
        fflush(descriptor == STDOUT_FILENO ? stdout : descriptor == STDERR_FILENO ? stderr : NULL);
    } else if (status_of == 0 && !S_ISREG(status.st_mode)) {
        file->kind = TARGET_DEVICE;
        file->target_fd = open(file->final, O_WRONLY | O_CLOEXEC | O_NOCTTY);
        if (file->target_fd < 0)
            return gb_fail(error, GB_ERROR_IO, "%s: cannot open: %s", path, strerror(errno));
    } else {
        file->kind = TARGET_FILE;
    }
    return GB_OK;
}

gb_result gb_output_file_open(const char *path, gb_output_file_mode mode,
                              gb_output_file **out, gb_error *error)
{
    if (out)
        *out = NULL;
    if (!path || !*path || !out)
        return gb_fail(error, GB_ERROR_ARGUMENT, "gb_output_file_open: no path");
    gb_output_file *file = calloc(1, sizeof *file);
    if (!file || !(file->path = strdup(path))) {
        free(file);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    file->fd = file->target_fd = file->slot = -1;
    file->mode = mode;
    gb_result result = open_target(file, error);
    if (result == GB_OK && (file->kind == TARGET_FILE || mode == GB_OUTPUT_FILE_BY_NAME)) {
        char *stem = file->kind == TARGET_FILE ? strdup(file->final) : staging_stem(path);
        file->fd = stem ? create_temporary(stem, &file->temporary, &file->slot) : -1;
        if (!stem)
            errno = ENOMEM;
        if (file->fd < 0)
            result = gb_fail(error, GB_ERROR_IO, "%s: cannot create a temporary file %s: %s",
                             path, file->kind == TARGET_FILE ? "beside it" : "to copy from",
                             strerror(errno));
        free(stem);
        /* the library opens the temporary itself */
        if (result == GB_OK && mode == GB_OUTPUT_FILE_BY_NAME) {
            close(file->fd);
            file->fd = -1;
        }
    } else if (result == GB_OK) {
        file->fd = file->target_fd;
    }
    if (result != GB_OK) {
        free_file(file);
        return result;
    }
    *out = file;
    return GB_OK;
}

const char *gb_output_file_name(const gb_output_file *file)
{
    return file && file->mode == GB_OUTPUT_FILE_BY_NAME ? file->temporary : NULL;
}

gb_result gb_output_file_write(gb_output_file *file, const void *data, size_t size,
                               gb_error *error)
{
    if (!file || file->fd < 0 || (!data && size > 0))
        return gb_fail(error, GB_ERROR_ARGUMENT, "%s: not open for writing",
                       file ? file->path : "gb_output_file_write");
    return write_all(file->fd, data, size, file->path, error);
}

void gb_output_file_abort(gb_output_file *file)
{
    if (file)
        free_file(file);
}

/* Makes the rename durable. */
static gb_result sync_folder(const gb_output_file *file, gb_error *error)
{
    char *folder = folder_of(file->final);
    if (!folder)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", file->path);
    gb_result result = GB_OK;
    int fd = open(folder, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0 || (fsync(fd) != 0 && errno != EINVAL))
        result = gb_fail(error, GB_ERROR_IO, "%s: written, but cannot sync its folder: %s",
                         file->path, strerror(errno));
    if (fd >= 0)
        close(fd);
    free(folder);
    return result;
}

static gb_result commit_file(gb_output_file *file, gb_error *error)
{
    int fd = file->fd;
    file->fd = -1;
    if (fd < 0)
        fd = open(file->temporary, O_RDONLY | O_CLOEXEC);
    gb_result result = GB_OK;
    if (fd < 0)
        result = gb_fail(error, GB_ERROR_IO, "%s: cannot reopen %s: %s", file->path,
                         file->temporary, strerror(errno));
    else if (fsync(fd) != 0)
        result = gb_fail(error, GB_ERROR_IO, "%s: cannot sync: %s", file->path,
                         strerror(errno));
    if (fd >= 0 && close(fd) != 0 && result == GB_OK)
        result = gb_fail(error, GB_ERROR_IO, "%s: cannot close: %s", file->path,
                         strerror(errno));
    if (result == GB_OK && rename(file->temporary, file->final) != 0)
        result = gb_fail(error, GB_ERROR_IO, "%s: cannot rename %s into place: %s",
                         file->path, file->temporary, strerror(errno));
    if (result != GB_OK)
        return result;          /* free_file removes the temporary */
    forget_temporary(file->slot);
    file->slot = -1;
    free(file->temporary);
    file->temporary = NULL;
    return sync_folder(file, error);
}

/* A library wrote file->temporary: its bytes go to the device. */
static gb_result copy_to_target(gb_output_file *file, gb_error *error)
{
    int fd = open(file->temporary, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return gb_fail(error, GB_ERROR_IO, "%s: cannot reopen %s: %s", file->path,
                       file->temporary, strerror(errno));
    unsigned char *buffer = malloc(COPY_CHUNK);
    gb_result result = buffer ? GB_OK
                              : gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory",
                                        file->path);
    while (result == GB_OK) {
        ssize_t got = read(fd, buffer, COPY_CHUNK);
        if (got < 0 && errno == EINTR)
            continue;
        if (got < 0)
            result = gb_fail(error, GB_ERROR_IO, "%s: cannot read back %s: %s", file->path,
                             file->temporary, strerror(errno));
        if (got <= 0)
            break;
        result = write_all(file->target_fd, buffer, (size_t)got, file->path, error);
    }
    free(buffer);
    close(fd);
    return result;
}

gb_result gb_output_file_commit(gb_output_file *file, gb_error *error)
{
    if (!file)
        return gb_fail(error, GB_ERROR_ARGUMENT, "gb_output_file_commit: no file");
    gb_result result = GB_OK;
    if (file->kind == TARGET_FILE)
        result = commit_file(file, error);
    else if (file->mode == GB_OUTPUT_FILE_BY_NAME)
        result = copy_to_target(file, error);
    if (result == GB_OK && file->kind == TARGET_DEVICE) {
        int fd = file->target_fd;
        file->target_fd = file->fd = -1;
        if (close(fd) != 0 && errno != EINTR)
            result = gb_fail(error, GB_ERROR_IO, "%s: cannot close: %s", file->path,
                             strerror(errno));
    }
    free_file(file);
    return result;
}

/* ---- checking before the work ---- */

gb_result gb_output_file_check(const char *path, gb_error *error)
{
    if (!path || !*path)
        return gb_fail(error, GB_ERROR_ARGUMENT, "no output file name");
    char *final;
    struct stat status;
    int descriptor, status_of;
    gb_result result = resolve(path, &final, &descriptor, &status, &status_of, error);
    if (result != GB_OK) {
        free(final);
        return result;
    }
    if (descriptor >= 0) {
        int flags = fcntl(descriptor, F_GETFL);
        if (flags < 0 || (flags & O_ACCMODE) == O_RDONLY)
            result = gb_fail(error, GB_ERROR_IO, "%s: descriptor %d is not open for writing",
                             path, descriptor);
        else if (isatty(descriptor))
            result = gb_fail(error, GB_ERROR_IO,
                             "%s: is a terminal; redirect it to a file or a pipe", path);
    } else if (status_of == 0 && !S_ISREG(status.st_mode)) {
        if (S_ISSOCK(status.st_mode))
            result = gb_fail(error, GB_ERROR_IO, "%s: is a socket, which cannot be opened",
                             path);
        else if (access(final, W_OK) != 0)
            result = gb_fail(error, GB_ERROR_IO, "%s: cannot write: %s", path, strerror(errno));
    } else {
        /* tried for real (access() says yes to root on a read-only mount),
         * as "NAME.check.tmp.XXXXXX": never taken for the write's temporary */
        char *folder = folder_of(final);
        char *stem = concatenate(final, ".check", "");
        char *name = NULL;
        int slot_index = -1;
        int fd = folder && stem ? create_temporary(stem, &name, &slot_index) : -1;
        int saved = folder && stem ? errno : ENOMEM;
        free(stem);
        if (fd < 0)
            result = gb_fail(error, GB_ERROR_IO, "%s: cannot write in folder '%s': %s", path,
                             folder ? folder : "?", strerror(saved));
        else
            close(fd);
        remove_temporary(&name, &slot_index);
        free(folder);
    }
    free(final);
    return result;
}

gb_result gb_output_files_check(const char *const *paths, int count, gb_error *error)
{
    gb_result result = GB_OK;
    for (int n = 0; n < count && result == GB_OK; ++n)
        if (paths[n])
            result = gb_output_file_check(paths[n], error);
    return result;
}

const gb_output_file_functions gb_output_file_table = {
    .check = gb_output_file_check,
    .open = gb_output_file_open,
    .name = gb_output_file_name,
    .write = gb_output_file_write,
    .commit = gb_output_file_commit,
    .abort = gb_output_file_abort,
};

gb_result gb_output_file_write_bytes(const char *path, const void *data, size_t size,
                                     gb_error *error)
{
    gb_output_file *out;
    gb_result result = gb_output_file_open(path, GB_OUTPUT_FILE_STREAM, &out, error);
    if (result != GB_OK)
        return result;
    result = gb_output_file_write(out, data, size, error);
    if (result != GB_OK) {
        gb_output_file_abort(out);
        return result;
    }
    return gb_output_file_commit(out, error);
}
