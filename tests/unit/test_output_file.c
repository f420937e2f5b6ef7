/* test_output_file.c — the one output writer (formats/output_file.h): new and
 * replaced files and their mode under two umasks, symlinks followed (relative,
 * chained, dangling), devices, FIFOs and standard output written through,
 * the by-name mode of the library adapters, the check before the work, write
 * errors (a full device, a file-size limit), and signals: SIGINT, SIGTERM and
 * SIGHUP remove the temporary, an ignored SIGINT is left ignored, SIGKILL
 * keeps the old file. Every signal is raised by the child itself at a known
 * point, so nothing depends on timing.
 */
#include "output_file.h"
#include "scratch.h"
#include "tap.h"
#include "tap_printf.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

/* Set once a FIFO was written through: only then is /dev/stdout tried (as
 * root, a writer that renames onto it would replace the system's link). */
static int fifo_written_through;

/* ---- helpers ---- */

/* Entries of sub (a folder under the test folder, "" for itself) whose name
 * contains ".tmp.". */
static int count_temporaries(const char *sub)
{
    DIR *dir = opendir(*sub ? scratch_path(sub) : scratch_folder);
    int count = 0;
    for (struct dirent *entry; dir && (entry = readdir(dir));)
        count += strstr(entry->d_name, ".tmp.") != NULL;
    if (dir)
        closedir(dir);
    return count;
}

static void remove_tree(const char *path)
{
    struct stat status;
    if (lstat(path, &status) != 0)
        return;
    if (S_ISDIR(status.st_mode)) {
        DIR *dir = opendir(path);
        for (struct dirent *entry; dir && (entry = readdir(dir));) {
            if (!strcmp(entry->d_name, ".") || !strcmp(entry->d_name, ".."))
                continue;
            char child[1024];
            snprintf(child, sizeof child, "%s/%s", path, entry->d_name);
            remove_tree(child);
        }
        if (dir)
            closedir(dir);
        rmdir(path);
    } else {
        unlink(path);
    }
}

/* The whole content of path as a NUL-terminated string ("" when missing). */
static const char *read_text(const char *path)
{
    static char text[4096];
    text[0] = '\0';
    FILE *file = fopen(path, "rb");
    if (!file)
        return text;
    size_t got = fread(text, 1, sizeof text - 1, file);
    text[got] = '\0';
    fclose(file);
    return text;
}

static unsigned file_mode(const char *path)
{
    struct stat status;
    return stat(path, &status) == 0 ? (unsigned)(status.st_mode & 07777) : 0u;
}

static int is_link(const char *path)
{
    struct stat status;
    return lstat(path, &status) == 0 && S_ISLNK(status.st_mode);
}

/* Opens, writes text and commits: the result of the commit (or the first
 * failure). */
static gb_result write_output(const char *path, const char *text, gb_error *error)
{
    gb_output_file *out;
    gb_result result = gb_output_file_open(path, GB_OUTPUT_FILE_STREAM, &out, error);
    if (result != GB_OK)
        return result;
    result = gb_output_file_write(out, text, strlen(text), error);
    if (result != GB_OK) {
        gb_output_file_abort(out);
        return result;
    }
    return gb_output_file_commit(out, error);
}

/* ---- regular files ---- */

static void test_new_and_replaced(void)
{
    gb_error error = {""};
    const char *path = scratch_path("new.txt");
    CHECK_EQ_INT(write_output(path, "first", &error), GB_OK, "a new file is written");
    CHECK(strcmp(read_text(path), "first") == 0, "... with its bytes");
    CHECK_EQ_INT(count_temporaries(""), 0, "... and no temporary left");

    gb_output_file *out;
    CHECK_EQ_INT(gb_output_file_open(path, GB_OUTPUT_FILE_STREAM, &out, &error), GB_OK,
                 "an existing file is opened for replacement");
    CHECK_EQ_INT(count_temporaries(""), 1, "... through one temporary beside it");
    gb_output_file_write(out, "second, longer", 14, &error);
    CHECK(strcmp(read_text(path), "first") == 0, "... the old file is untouched while writing");
    gb_output_file_abort(out);
    CHECK(strcmp(read_text(path), "first") == 0 && count_temporaries("") == 0,
          "abort: the old file is kept and the temporary removed");
    CHECK_EQ_INT(write_output(path, "second", &error), GB_OK, "commit replaces it");
    CHECK(strcmp(read_text(path), "second") == 0, "... with the new bytes");
    unlink(path);
}

static void test_modes(void)
{
    static const unsigned masks[2] = {022, 027};
    gb_error error;
    for (int i = 0; i < 2; ++i) {
        mode_t old = umask(masks[i]);
        const char *path = scratch_path("mode.txt");
        write_output(path, "x", &error);
        char label[96];
        snprintf(label, sizeof label, "umask %03o: a new file gets mode %03o", masks[i],
                 0666 & ~masks[i]);
        CHECK_EQ_INT(file_mode(path), 0666 & ~masks[i], label);
        chmod(path, 0600);
        write_output(path, "y", &error);
        snprintf(label, sizeof label, "umask %03o: a replaced 0600 file gets %03o too",
                 masks[i], 0666 & ~masks[i]);
        CHECK_EQ_INT(file_mode(path), 0666 & ~masks[i], label);
        unlink(path);
        umask(old);
    }
}

/* ---- symlinks ---- */

static void test_symlinks(void)
{
    gb_error error;
    mkdir(scratch_path("sub"), 0755);
    scratch_write_text(scratch_path("sub/target.txt"), "old");
    symlink("sub/target.txt", scratch_path("link.txt"));
    CHECK_EQ_INT(write_output(scratch_path("link.txt"), "through the link", &error), GB_OK,
                 "writing to a relative symlink succeeds");
    CHECK(is_link(scratch_path("link.txt")), "... the link stays a link");
    CHECK(strcmp(read_text(scratch_path("sub/target.txt")), "through the link") == 0,
          "... and its target has the bytes");
    CHECK(count_temporaries("") == 0 && count_temporaries("sub") == 0,
          "... no temporary left in either folder");

    /* a chain: chain.txt -> link.txt -> sub/target.txt */
    symlink("link.txt", scratch_path("chain.txt"));
    write_output(scratch_path("chain.txt"), "chained", &error);
    CHECK(is_link(scratch_path("chain.txt")) && is_link(scratch_path("link.txt")) &&
              strcmp(read_text(scratch_path("sub/target.txt")), "chained") == 0,
          "a chain of two links is followed to the end, both stay links");

    /* a link inside sub, relative to sub */
    symlink("target.txt", scratch_path("sub/inner.txt"));
    write_output(scratch_path("sub/inner.txt"), "inner", &error);
    CHECK(is_link(scratch_path("sub/inner.txt")) &&
              strcmp(read_text(scratch_path("sub/target.txt")), "inner") == 0,
          "a relative link is relative to its own folder");

    /* dangling: the target is created */
    symlink("sub/created.txt", scratch_path("dangling.txt"));
    CHECK_EQ_INT(write_output(scratch_path("dangling.txt"), "created", &error), GB_OK,
                 "writing to a dangling symlink succeeds");
    CHECK(is_link(scratch_path("dangling.txt")) &&
              strcmp(read_text(scratch_path("sub/created.txt")), "created") == 0,
          "... it creates the target and the link stays");

    /* absolute */
    char absolute[600];
    snprintf(absolute, sizeof absolute, "%s/sub/target.txt", scratch_folder);
    symlink(absolute, scratch_path("absolute.txt"));
    write_output(scratch_path("absolute.txt"), "absolute", &error);
    CHECK(is_link(scratch_path("absolute.txt")) &&
              strcmp(read_text(scratch_path("sub/target.txt")), "absolute") == 0,
          "an absolute link is followed");

    /* a loop */
    symlink("loop-b.txt", scratch_path("loop-a.txt"));
    symlink("loop-a.txt", scratch_path("loop-b.txt"));
    CHECK_EQ_INT(write_output(scratch_path("loop-a.txt"), "x", &error), GB_ERROR_IO,
                 "a symlink loop is an error");
    CHECK(strstr(error.message, "loop-a.txt: ") && strstr(error.message, "symbolic links"),
          "... saying so");
    remove_tree(scratch_path("sub"));
    unlink(scratch_path("link.txt"));
    unlink(scratch_path("chain.txt"));
    unlink(scratch_path("dangling.txt"));
    unlink(scratch_path("absolute.txt"));
    unlink(scratch_path("loop-a.txt"));
    unlink(scratch_path("loop-b.txt"));
}

/* ---- devices, FIFOs, standard output ---- */

static void test_devices(void)
{
    gb_error error;
    const char *null = scratch_path("null");
    const char *full = scratch_path("full");
    if (mknod(null, S_IFCHR | 0666, makedev(1, 3)) != 0 ||
        mknod(full, S_IFCHR | 0666, makedev(1, 7)) != 0) {
        for (int i = 0; i < 5; ++i)
            printf("ok %d # skip mknod: %s (needs root)\n", ++tap_count, strerror(errno));
        unlink(null);
        return;
    }
    struct stat status;
    CHECK_EQ_INT(write_output(null, "to the null device", &error), GB_OK,
                 "a null character device (mknod c 1 3) is written through");
    CHECK(stat(null, &status) == 0 && S_ISCHR(status.st_mode) &&
              status.st_rdev == makedev(1, 3) && count_temporaries("") == 0,
          "... it stays that device, no temporary beside it");
    CHECK_EQ_INT(write_output(full, "to the full device", &error), GB_ERROR_IO,
                 "a full device (mknod c 1 7) gives an error");
    CHECK(strstr(error.message, "full: cannot write: No space left on device") != NULL,
          "... 'cannot write: No space left on device'");
    CHECK(stat(full, &status) == 0 && S_ISCHR(status.st_mode),
          "... and stays a device");
    unlink(null);
    unlink(full);
}

static void test_fifo(void)
{
    gb_error error;
    const char *fifo = scratch_path("fifo");
    mkfifo(fifo, 0644);
    /* our own reader end, open before the writer's: the write then does not block */
    int reader = open(fifo, O_RDWR | O_NONBLOCK);
    CHECK_EQ_INT(write_output(fifo, "through the fifo", &error), GB_OK,
                 "a FIFO is written through");
    char got[64] = "";
    ssize_t n = read(reader, got, sizeof got - 1);
    got[n > 0 ? n : 0] = '\0';
    CHECK(strcmp(got, "through the fifo") == 0, "... the reader gets the bytes");
    struct stat status;
    fifo_written_through = CHECK(lstat(fifo, &status) == 0 && S_ISFIFO(status.st_mode) &&
                                     count_temporaries("") == 0,
                                 "... it stays a FIFO, no temporary beside it");

    /* by name (a library writing a path): through a temporary in $TMPDIR */
    gb_output_file *out;
    CHECK_EQ_INT(gb_output_file_open(fifo, GB_OUTPUT_FILE_BY_NAME, &out, &error), GB_OK,
                 "a FIFO opened by name");
    const char *name = gb_output_file_name(out);
    CHECK(name && strncmp(name, scratch_folder, strlen(scratch_folder)) == 0 &&
              strstr(name, "/gibake-fifo.tmp.") != NULL,
          "... is written as $TMPDIR/gibake-fifo.tmp.XXXXXX");
    scratch_write_text(name, "copied");
    CHECK_EQ_INT(gb_output_file_commit(out, &error), GB_OK, "... and committed");
    n = read(reader, got, sizeof got - 1);
    got[n > 0 ? n : 0] = '\0';
    CHECK(strcmp(got, "copied") == 0 && count_temporaries("") == 0,
          "... the FIFO gets the copy and the temporary is gone");
    close(reader);
    unlink(fifo);
}

static void test_standard_output(void)
{
    gb_error error;
    const char *captured = scratch_path("stdout.txt");
    fflush(stdout);
    int saved = dup(STDOUT_FILENO);
    int file = open(captured, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    dup2(file, STDOUT_FILENO);
    close(file);
    gb_result stream = write_output("-", "dash, ", &error);
    gb_result check = gb_output_file_check("-", &error);
    gb_output_file *out;
    gb_result by_name = gb_output_file_open("-", GB_OUTPUT_FILE_BY_NAME, &out, &error);
    if (by_name == GB_OK) {
        scratch_write_text(gb_output_file_name(out), "by name, ");
        by_name = gb_output_file_commit(out, &error);
    }
    gb_result device = fifo_written_through ? write_output("/dev/stdout", "/dev/stdout", &error)
                                            : GB_ERROR_ARGUMENT;
    dup2(saved, STDOUT_FILENO);
    close(saved);
    CHECK_EQ_INT(stream, GB_OK, "\"-\" writes standard output");
    CHECK_EQ_INT(check, GB_OK, "... and passes the check when it is not a terminal");
    CHECK_EQ_INT(by_name, GB_OK, "\"-\" by name: copied to standard output");
    CHECK_EQ_INT(device, GB_OK, "/dev/stdout onto a regular file");
    CHECK(strcmp(read_text(captured), "dash, by name, /dev/stdout") == 0,
          "... all three land in standard output, in order");
    CHECK(is_link("/dev/stdout") || access("/dev/stdout", F_OK) != 0,
          "/dev/stdout is still a symlink");
    unlink(captured);
}

/* ---- by name ---- */

static void test_by_name(void)
{
    gb_error error;
    const char *path = scratch_path("library.bin");
    scratch_write_text(path, "old");
    gb_output_file *out;
    CHECK_EQ_INT(gb_output_file_open(path, GB_OUTPUT_FILE_BY_NAME, &out, &error), GB_OK,
                 "by-name mode opens");
    const char *name = gb_output_file_name(out);
    char prefix[600];
    snprintf(prefix, sizeof prefix, "%s.tmp.", path);
    CHECK(name && strncmp(name, prefix, strlen(prefix)) == 0 && strlen(name) == strlen(prefix) + 6,
          "... the library writes PATH.tmp.XXXXXX beside the target");
    CHECK_EQ_INT(gb_output_file_write(out, "x", 1, &error), GB_ERROR_ARGUMENT,
                 "... gb_output_file_write is refused in that mode");
    scratch_write_text(name, "written by the library");
    CHECK(strcmp(read_text(path), "old") == 0, "... the old file is there until commit");
    CHECK_EQ_INT(gb_output_file_commit(out, &error), GB_OK, "commit");
    CHECK(strcmp(read_text(path), "written by the library") == 0 && count_temporaries("") == 0,
          "... renames it into place");
    CHECK_EQ_INT(gb_output_file_name(NULL) == NULL, 1, "no name for no file");
    unlink(path);
}

/* ---- the check before the work ---- */

static void test_check(void)
{
    gb_error error = {""};
    CHECK_EQ_INT(gb_output_file_check(scratch_path("fine.bin"), &error), GB_OK,
                 "a new file in a writable folder passes");
    CHECK(count_temporaries("") == 0 && access(scratch_path("fine.bin"), F_OK) != 0,
          "... and the check leaves nothing behind");
    const char *missing = scratch_path("missing/x.bin");
    CHECK_EQ_INT(gb_output_file_check(missing, &error), GB_ERROR_IO, "a missing folder fails");
    char expected[700];
    snprintf(expected, sizeof expected,
             "%s: cannot write in folder '%s/missing': No such file or directory", missing,
             scratch_folder);
    CHECK(strcmp(error.message, expected) == 0, "... 'PATH: cannot write in folder ...: No such file'");
    scratch_write_text(scratch_path("plain"), "");
    CHECK_EQ_INT(gb_output_file_check(scratch_path("plain/x.bin"), &error), GB_ERROR_IO,
                 "a file as the folder fails");
    CHECK(strstr(error.message, "Not a directory") != NULL, "... 'Not a directory'");
    mkdir(scratch_path("a_folder"), 0755);
    CHECK_EQ_INT(gb_output_file_check(scratch_path("a_folder"), &error), GB_ERROR_IO,
                 "a folder as the output fails");
    CHECK(strstr(error.message, "a_folder: is a folder") != NULL, "... 'is a folder'");
    CHECK_EQ_INT(write_output(scratch_path("a_folder"), "x", &error), GB_ERROR_IO,
                 "opening a folder fails too");
    symlink("missing/y.bin", scratch_path("dangling"));
    CHECK_EQ_INT(gb_output_file_check(scratch_path("dangling"), &error), GB_ERROR_IO,
                 "a dangling link into a missing folder fails");
    CHECK_EQ_INT(gb_output_file_check("", &error), GB_ERROR_ARGUMENT, "an empty name fails");
    CHECK_EQ_INT(write_output(missing, "x", &error), GB_ERROR_IO,
                 "opening in a missing folder fails");
    CHECK(strncmp(error.message, missing, strlen(missing)) == 0 &&
              strstr(error.message, "No such file"),
          "... naming the path and the reason");
    char fine[600], second_missing[600];
    snprintf(fine, sizeof fine, "%s", scratch_path("fine.bin"));
    snprintf(second_missing, sizeof second_missing, "%s", scratch_path("missing/z.d"));
    CHECK_EQ_INT(gb_output_files_check((const char *[]){fine, NULL, fine}, 3, &error), GB_OK,
                 "several outputs: writable ones pass, a NULL one (not asked for) is skipped");
    CHECK(gb_output_files_check((const char *[]){fine, second_missing, missing}, 3, &error) ==
                  GB_ERROR_IO &&
              strncmp(error.message, second_missing, strlen(second_missing)) == 0,
          "several outputs: the first that cannot be written fails, by name");
    rmdir(scratch_path("a_folder"));
    unlink(scratch_path("plain"));
    unlink(scratch_path("dangling"));
}

/* path holding "old", stdout flushed, then fork(): 0 in the child, its pid
 * in the parent. */
static pid_t fork_over_old(const char *path)
{
    scratch_write_text(path, "old");
    fflush(stdout);
    return fork();
}

/* The old file at path as it was, and no temporary beside it. */
static int old_intact(const char *path)
{
    return strcmp(read_text(path), "old") == 0 && count_temporaries("") == 0;
}

/* ---- limits ---- */

/* In a child limited to 1 KiB files: writing 4 KiB fails with EFBIG (the
 * writer ignores SIGXFSZ), removes the temporary and keeps the old file. */
static void test_file_size_limit(void)
{
    const char *path = scratch_path("limited.bin");
    pid_t child = fork_over_old(path);
    if (child == 0) {
        struct rlimit limit = {1024, 1024};
        setrlimit(RLIMIT_FSIZE, &limit);
        static char big[4096];
        memset(big, 'x', sizeof big);
        big[sizeof big - 1] = '\0';
        gb_error error;
        gb_result result = write_output(path, big, &error);
        _exit(result == GB_ERROR_IO && strstr(error.message, "File too large") ? 0 : 1);
    }
    int status = 0;
    waitpid(child, &status, 0);
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0,
          "past a file-size limit: an error 'cannot write: File too large', no SIGXFSZ kill");
    CHECK(old_intact(path), "... the old file is kept and the temporary removed");
    unlink(path);
}

/* ---- signals ---- */

/* Over path holding "old", a child opens path, writes part of it, then
 * sends itself signal_number (ignored first when ignore); returns the
 * child's wait status. */
static int signalled_child(const char *path, int signal_number, int ignore)
{
    pid_t child = fork_over_old(path);
    if (child == 0) {
        if (ignore)
            signal(signal_number, SIG_IGN);
        gb_output_file *out;
        gb_error error;
        if (gb_output_file_open(path, GB_OUTPUT_FILE_STREAM, &out, &error) != GB_OK)
            _exit(3);
        gb_output_file_write(out, "partial", 7, &error);
        raise(signal_number);
        gb_output_file_write(out, " and the rest", 13, &error);
        _exit(gb_output_file_commit(out, &error) == GB_OK ? 0 : 4);
    }
    int status = 0;
    waitpid(child, &status, 0);
    return status;
}

static void test_signals(void)
{
    static const int signals[] = {SIGINT, SIGTERM, SIGHUP};
    static const char *names[] = {"SIGINT", "SIGTERM", "SIGHUP"};
    const char *path = scratch_path("signalled.bin");
    for (int i = 0; i < 3; ++i) {
        int status = signalled_child(path, signals[i], 0);
        CHECKF(WIFSIGNALED(status) && WTERMSIG(status) == signals[i],
               "%s while the temporary exists: the child dies by it", names[i]);
        CHECKF(old_intact(path), "%s: the old file is intact, the temporary removed", names[i]);
    }
    int status = signalled_child(path, SIGINT, 1);
    CHECK(WIFEXITED(status) && WEXITSTATUS(status) == 0,
          "an ignored SIGINT stays ignored (a background job): the write completes");
    CHECK(strcmp(read_text(path), "partial and the rest") == 0 && count_temporaries("") == 0,
          "... with the whole new file");
    status = signalled_child(path, SIGKILL, 0);
    CHECK(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL, "SIGKILL kills the child");
    CHECK(strcmp(read_text(path), "old") == 0,
          "... the old file is byte-identical (the rename never happened)");
    CHECK_EQ_INT(count_temporaries(""), 1,
                 "... and one stale signalled.bin.tmp.XXXXXX remains (SIGKILL cannot be caught)");
    DIR *dir = opendir(scratch_folder);
    for (struct dirent *entry; dir && (entry = readdir(dir));)
        if (strstr(entry->d_name, ".tmp."))
            unlink(scratch_path(entry->d_name));
    if (dir)
        closedir(dir);
    unlink(path);
}

/* A thread writes; the main thread takes the SIGINT (raised on itself). It
 * must not remove the writer's file under it: it sends the signal on to the
 * writer, which removes its temporary and ends the process. */
typedef struct holder {
    const char *path;
    int ready[2], never[2];
} holder;

static void *hold_output(void *argument)
{
    holder *h = argument;
    gb_output_file *out;
    gb_error error;
    if (gb_output_file_open(h->path, GB_OUTPUT_FILE_STREAM, &out, &error) != GB_OK)
        _exit(3);
    gb_output_file_write(out, "partial", 7, &error);
    char byte = 1;
    if (write(h->ready[1], &byte, 1) != 1)
        _exit(4);
    /* until the forwarded signal ends the process */
    if (read(h->never[0], &byte, 1) < 0 || 1)
        _exit(gb_output_file_commit(out, &error) == GB_OK ? 5 : 6);
    return NULL;
}

static void test_signal_to_another_thread(void)
{
    const char *path = scratch_path("threaded.bin");
    pid_t child = fork_over_old(path);
    if (child == 0) {
        alarm(20);   /* only a broken forward would wait that long: SIGALRM fails the check */
        holder h = {path, {-1, -1}, {-1, -1}};
        pthread_t writer;
        char byte;
        if (pipe(h.ready) != 0 || pipe(h.never) != 0 ||
            pthread_create(&writer, NULL, hold_output, &h) != 0 || read(h.ready[0], &byte, 1) != 1)
            _exit(2);
        raise(SIGINT);   /* to this thread, which holds no temporary */
        for (;;)
            pause();
    }
    int status = 0;
    waitpid(child, &status, 0);
    CHECK(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT,
          "SIGINT taken by a thread that writes nothing: sent on, the process dies by it");
    CHECK(old_intact(path),
          "... the writer thread removed its temporary, the old file is intact");
    unlink(path);
}

/* ---- threads ---- */

static void *write_in_thread(void *argument)
{
    const char *path = argument;
    gb_error error;
    for (int i = 0; i < 50; ++i)
        if (write_output(path, path, &error) != GB_OK)
            return (void *)1;
    return NULL;
}

static void test_threads(void)
{
    char paths[4][600];
    pthread_t threads[4];
    for (int i = 0; i < 4; ++i) {
        snprintf(paths[i], sizeof paths[i], "%s/thread-%d.bin", scratch_folder, i);
        pthread_create(&threads[i], NULL, write_in_thread, paths[i]);
    }
    int failed = 0, right = 1;
    for (int i = 0; i < 4; ++i) {
        void *result;
        pthread_join(threads[i], &result);
        failed += result != NULL;
        right &= strcmp(read_text(paths[i]), paths[i]) == 0;
        unlink(paths[i]);
    }
    CHECK(failed == 0 && right && count_temporaries("") == 0,
          "4 threads writing 50 outputs each: every file right, no temporary left");
}

int main(void)
{
    /* The signal checks expect a process whose signals are at their
     * defaults; run under nohup or as a background job (make test &), it
     * inherits SIGHUP or SIGINT ignored, which the writer rightly keeps. */
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    signal(SIGHUP, SIG_DFL);
    scratch_create("output");
    setenv("TMPDIR", scratch_folder, 1);   /* where a device's by-name temporary goes */
    umask(022);
    test_new_and_replaced();
    test_modes();
    test_symlinks();
    test_devices();
    test_fifo();
    test_standard_output();
    test_by_name();
    test_check();
    test_file_size_limit();
    test_signals();
    test_signal_to_another_thread();
    test_threads();
    remove_tree(scratch_folder);
    return tap_done();
}
