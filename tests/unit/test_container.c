/* test_container.c — unit tests of formats/container.[ch]: the byte layout of
 * a round trip, rejection of every corrupted byte, every truncation and
 * hostile tables, and the writer's atomicity (cancelled or killed commits
 * leave nothing at the final path, an existing file survives).
 */
#include "container.h"
#include "scratch.h"
#include "tap.h"

#include <dirent.h>
#include <signal.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

/* ---- helpers ---- */

/* Number of entries in the scratch folder; *first gets the first name seen. */
static int count_files(char *first, size_t first_size)
{
    DIR *dir = opendir(scratch_folder);
    int count = 0;
    struct dirent *entry;
    while (dir && (entry = readdir(dir)))
        if (strcmp(entry->d_name, ".") && strcmp(entry->d_name, "..")) {
            if (count++ == 0 && first)
                snprintf(first, first_size, "%s", entry->d_name);
        }
    if (dir)
        closedir(dir);
    return count;
}

static int exists(const char *path)
{
    struct stat status;
    return stat(path, &status) == 0;
}

static int starts_with(const char *text, const char *prefix)
{
    return strncmp(text, prefix, strlen(prefix)) == 0;
}

static uint32_t get_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
           (uint32_t)p[3] << 24;
}

static void put_u32(unsigned char *p, uint32_t value)
{
    for (int i = 0; i < 4; ++i)
        p[i] = (unsigned char)(value >> (8 * i));
}

static void put_u64(unsigned char *p, uint64_t value)
{
    put_u32(p, (uint32_t)value);
    put_u32(p + 4, (uint32_t)(value >> 32));
}

/* Recomputes the header CRC after a test edits the header or the table, so
 * that the reader's later checks are reached (a table larger than the file
 * is cut at its end: the reader rejects it before it looks at the CRC). */
static void reseal(unsigned char *bytes, size_t size)
{
    uint64_t table = (uint64_t)get_u32(bytes + 24) * 48u;
    if (table > size - 32)
        table = size - 32;
    uLong crc = crc32(0L, Z_NULL, 0);
    crc = crc32(crc, bytes, 28);
    crc = crc32(crc, bytes + 32, (uInt)table);
    put_u32(bytes + 28, (uint32_t)crc);
}

/* Parses a copy of exactly size bytes (so ASan sees any over-read). */
static gb_result parse_copy(const unsigned char *bytes, size_t size, const char *kind,
                            gb_error *error)
{
    unsigned char *copy = malloc(size ? size : 1);
    memcpy(copy, bytes, size);
    gb_container container;
    gb_result result = gb_container_parse(copy, size, "x.test", kind, &container, error);
    gb_container_close(&container);
    free(copy);
    return result;
}

/* Payloads of the round trip: sizes 100, 0, 33, 32 and 1. */
static unsigned char positions[100], indices[33], aligned[32], one[1] = {0x5A};

static void fill_payloads(void)
{
    for (int i = 0; i < 100; ++i)
        positions[i] = (unsigned char)(i * 7 + 1);
    for (int i = 0; i < 33; ++i)
        indices[i] = (unsigned char)(255 - i);
    for (int i = 0; i < 32; ++i)
        aligned[i] = (unsigned char)(i ^ 0x3C);
}

static gb_container_writer *sample_writer(void)
{
    gb_container_writer *writer = gb_container_writer_create("TEST", 2);
    gb_error error;
    gb_container_add(writer, "positions", positions, sizeof positions, &error);
    gb_container_add(writer, "empty", NULL, 0, &error);
    gb_container_add(writer, "indices", indices, sizeof indices, &error);
    gb_container_add(writer, "aligned", aligned, sizeof aligned, &error);
    gb_container_add(writer, "one", one, sizeof one, &error);
    return writer;
}

/* A small file of three sections (5, 0, 17 bytes): 209 bytes in all. */
static unsigned char *small_file(size_t *size)
{
    gb_container_writer *writer = gb_container_writer_create("TEST", 1);
    gb_error error;
    gb_container_add(writer, "a", "hello", 5, &error);
    gb_container_add(writer, "bb", NULL, 0, &error);
    gb_container_add(writer, "ccc", "seventeen bytes!!", 17, &error);
    const char *path = scratch_path("small.test");
    gb_container_commit(writer, path, &error);
    gb_container_writer_destroy(writer);
    unsigned char *bytes = scratch_read(path, size);
    unlink(path);
    return bytes;
}

/* ---- round trip ---- */

static void check_sample_sections(const gb_container *container, const void *base,
                                  const char *what)
{
    static const char *names[5] = {"positions", "empty", "indices", "aligned", "one"};
    static const void *datas[5] = {positions, NULL, indices, aligned, one};
    static const uint64_t sizes[5] = {100, 0, 33, 32, 1};
    static const long offsets[5] = {272, 384, 384, 432, 464};
    char label[160];
    for (int i = 0; i < 5; ++i) {
        const gb_section *section = &container->sections[i];
        snprintf(label, sizeof label, "%s: section %d is '%s' of %llu bytes at offset %ld",
                 what, i, names[i], (unsigned long long)sizes[i], offsets[i]);
        CHECK(strcmp(section->name, names[i]) == 0 && section->size == sizes[i] &&
                  (const unsigned char *)section->data - (const unsigned char *)base ==
                      offsets[i] &&
                  (sizes[i] == 0 || memcmp(section->data, datas[i], sizes[i]) == 0),
              label);
        snprintf(label, sizeof label, "%s: '%s' data is 16-byte aligned from the start",
                 what, names[i]);
        CHECK(((const unsigned char *)section->data - (const unsigned char *)base) % 16 == 0,
              label);
    }
}

static void test_round_trip(void)
{
    gb_container_writer *writer = sample_writer();
    gb_error error = {""};
    const char *path = scratch_path("sample.test");
    CHECK_EQ_INT(gb_container_commit(writer, path, &error), GB_OK, "commit succeeds");
    gb_container_writer_destroy(writer);
    CHECK_EQ_INT(count_files(NULL, 0), 1, "commit leaves only the final file");

    struct stat status;
    stat(path, &status);
    CHECK_EQ_INT(status.st_size, 465, "file ends at the end of the last payload (465 bytes)");
    CHECK_EQ_INT(status.st_mode & 0777, 0644, "file mode is 0666 less the umask 022");

    size_t size;
    unsigned char *bytes = scratch_read(path, &size);
    static const unsigned char magic[8] = {0xAB, 'G', 'B', 'K', 0x0D, 0x0A, 0x1A, 0x0A};
    CHECK(memcmp(bytes, magic, 8) == 0, "bytes 0..7 are the magic");
    CHECK(memcmp(bytes + 8, "TEST", 4) == 0, "bytes 8..11 are the kind");
    CHECK_EQ_INT(get_u32(bytes + 12), 2, "bytes 12..15 are the kind's version");
    CHECK_EQ_INT(get_u32(bytes + 16), 1, "bytes 16..19 are the container version 1");
    CHECK(bytes[20] == 4 && bytes[21] == 3 && bytes[22] == 2 && bytes[23] == 1,
          "bytes 20..23 are 0x01020304 little-endian");
    CHECK_EQ_INT(get_u32(bytes + 24), 5, "bytes 24..27 are the section count");
    CHECK_EQ_INT(get_u32(bytes + 32 + 40), crc32(0, positions, sizeof positions),
                 "entry 0 holds the zlib CRC-32 of its payload");

    gb_container container;
    CHECK_EQ_INT(gb_container_read(path, "TEST", &container, &error), GB_OK,
                 "read succeeds");
    CHECK(strcmp(container.kind, "TEST") == 0, "read: kind is TEST");
    CHECK_EQ_INT(container.version, 2, "read: version is 2");
    CHECK_EQ_INT(container.section_count, 5, "read: five sections");
    CHECK_EQ_INT(container.mapping_size, 465, "read: the whole file is mapped");
    check_sample_sections(&container, container.mapping, "read");
    int absolute = 1;
    for (uint32_t i = 0; i < container.section_count; ++i)
        absolute &= (uintptr_t)container.sections[i].data % 16 == 0;
    CHECK(absolute, "read: every data pointer is 16-byte aligned in memory");
    const gb_section *found = gb_container_find(&container, "indices");
    CHECK(found == &container.sections[2], "find returns the named section");
    CHECK(gb_container_find(&container, "missing") == NULL, "find of a missing name is NULL");
    CHECK(gb_container_check_version(&container, path, 2, &error) == GB_OK,
          "check_version accepts version 2 when 2 is the newest");
    gb_container_close(&container);
    CHECK(container.sections == NULL && container.mapping == NULL,
          "close zeroes the container");

    CHECK_EQ_INT(gb_container_parse(bytes, size, "buffer", "TEST", &container, &error),
                 GB_OK, "parse of the same bytes succeeds");
    CHECK(container.mapping == NULL, "parse maps nothing");
    check_sample_sections(&container, bytes, "parse");
    gb_container_close(&container);
    free(bytes);
    unlink(path);
}

static void test_empty_container(void)
{
    gb_container_writer *writer = gb_container_writer_create("NONE", 1);
    gb_error error;
    const char *path = scratch_path("none.test");
    CHECK_EQ_INT(gb_container_commit(writer, path, &error), GB_OK,
                 "commit of a container without sections");
    gb_container_writer_destroy(writer);
    gb_container container;
    CHECK_EQ_INT(gb_container_read(path, NULL, &container, &error), GB_OK,
                 "read of a container without sections (any kind)");
    CHECK(container.section_count == 0 && container.mapping_size == 32,
          "a container without sections is the 32-byte header");
    gb_container_close(&container);
    unlink(path);
}

static void test_deterministic(void)
{
    gb_container_writer *writer = sample_writer();
    gb_error error;
    const char *first = scratch_path("first.test"), *second = scratch_path("second.test");
    gb_container_commit(writer, first, &error);
    gb_container_commit(writer, second, &error);
    gb_container_writer_destroy(writer);
    size_t first_size = 0, second_size = 1;
    unsigned char *a = scratch_read(first, &first_size), *b = scratch_read(second, &second_size);
    CHECK(a && b && first_size == second_size && memcmp(a, b, first_size) == 0,
          "two commits of the same sections are byte-identical");
    free(a);
    free(b);
    unlink(first);
    unlink(second);
}

static void test_check_version(void)
{
    gb_container container = {.version = 3};
    gb_error error;
    CHECK_EQ_INT(gb_container_check_version(&container, "x.skel", 2, &error),
                 GB_ERROR_UNSUPPORTED, "a newer kind version is unsupported");
    CHECK(strcmp(error.message, "x.skel: format version 3 is newer than this program (2)") == 0,
          "newer kind version message");
    container.version = 0;
    CHECK_EQ_INT(gb_container_check_version(&container, "x.skel", 2, &error), GB_ERROR_FORMAT,
                 "kind version 0 is rejected");
}

/* ---- corrupted input ---- */

static void test_every_byte_flip(void)
{
    size_t size;
    unsigned char *bytes = small_file(&size);
    CHECK_EQ_INT(size, 209, "the small file is 209 bytes");
    gb_error error;
    CHECK_EQ_INT(parse_copy(bytes, size, NULL, &error), GB_OK, "the small file parses");
    long accepted = 0, without_message = 0, tries = 0;
    for (size_t i = 0; i < size; ++i)
        for (int flip = 1; flip < 256; ++flip) {
            bytes[i] ^= (unsigned char)flip;
            error.message[0] = 0;
            gb_result result = parse_copy(bytes, size, NULL, &error);
            accepted += result == GB_OK;
            without_message += !starts_with(error.message, "x.test: ");
            ++tries;
            bytes[i] ^= (unsigned char)flip;
        }
    CHECK_EQ_INT(tries, 209 * 255, "every byte changed to each of its 255 other values");
    CHECK_EQ_INT(accepted, 0, "no changed byte is accepted");
    CHECK_EQ_INT(without_message, 0, "every rejection has a 'path: ...' message");

    struct { size_t at; gb_result result; const char *message; } cases[] = {
        {0, GB_ERROR_FORMAT, "x.test: not a gibake file (bad magic)"},
        {9, GB_ERROR_CHECKSUM, "x.test: header checksum mismatch"},
        {29, GB_ERROR_CHECKSUM, "x.test: header checksum mismatch"},
        {180, GB_ERROR_CHECKSUM, "x.test: section 'a' checksum mismatch"},
        {185, GB_ERROR_FORMAT, "x.test: padding byte 185 before section 'bb' is not zero"},
        {208, GB_ERROR_CHECKSUM, "x.test: section 'ccc' checksum mismatch"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        bytes[cases[c].at] ^= 0x10;
        gb_result result = parse_copy(bytes, size, NULL, &error);
        bytes[cases[c].at] ^= 0x10;
        CHECK(result == cases[c].result && strcmp(error.message, cases[c].message) == 0,
              cases[c].message);
        if (strcmp(error.message, cases[c].message) != 0)
            printf("#   got '%s'\n", error.message);
    }
    free(bytes);
}

static void test_truncations_and_trailing(void)
{
    size_t size;
    unsigned char *bytes = small_file(&size);
    gb_error error;
    long accepted = 0, without_message = 0;
    for (size_t length = 0; length < size; ++length) {
        error.message[0] = 0;
        accepted += parse_copy(bytes, length, NULL, &error) == GB_OK;
        without_message += !starts_with(error.message, "x.test: ");
    }
    CHECK_EQ_INT(accepted, 0, "every truncation (0..208 bytes) is rejected");
    CHECK_EQ_INT(without_message, 0, "every truncation has a message");
    parse_copy(bytes, 0, NULL, &error);
    CHECK(strcmp(error.message, "x.test: empty file, not a gibake file") == 0,
          "empty input message");
    parse_copy(bytes, 20, NULL, &error);
    CHECK(strcmp(error.message, "x.test: truncated header (20 bytes, the header has 32)") == 0,
          "truncated header message");

    unsigned char *longer = malloc(size + 1);
    memcpy(longer, bytes, size);
    longer[size] = 0;
    CHECK_EQ_INT(parse_copy(longer, size + 1, NULL, &error), GB_ERROR_FORMAT,
                 "an appended byte is rejected");
    CHECK(strcmp(error.message, "x.test: 1 trailing bytes after the last section") == 0,
          "trailing byte message");
    free(longer);
    free(bytes);
}

static void test_wrong_kind(void)
{
    size_t size;
    unsigned char *bytes = small_file(&size);
    gb_error error;
    CHECK_EQ_INT(parse_copy(bytes, size, "PHOT", &error), GB_ERROR_FORMAT,
                 "a TEST file is rejected where PHOT is expected");
    CHECK(strcmp(error.message, "x.test: is a TEST file, expected PHOT") == 0,
          "wrong kind message");
    CHECK_EQ_INT(parse_copy(bytes, size, "TOOLONG", &error), GB_ERROR_ARGUMENT,
                 "an expected kind of 7 letters is a bad argument");
    free(bytes);
}

/* What text-mode copies do to the magic is named in the message. */
static void test_text_mangling(void)
{
    size_t size;
    unsigned char *bytes = small_file(&size);
    gb_error error;
    bytes[0] &= 0x7F;
    parse_copy(bytes, size, NULL, &error);
    CHECK(strstr(error.message, "top bit was stripped") != NULL, "7-bit copy is named");
    bytes[0] |= 0x80;
    unsigned char *lf = malloc(size - 1); /* drop the 0x0D of the magic */
    memcpy(lf, bytes, 4);
    memcpy(lf + 4, bytes + 5, size - 5);
    parse_copy(lf, size - 1, NULL, &error);
    CHECK(strstr(error.message, "CRLF turned into LF") != NULL, "CRLF to LF is named");
    free(lf);
    unsigned char *crlf = malloc(size + 1); /* 0x0A at 7 becomes 0x0D 0x0A */
    memcpy(crlf, bytes, 7);
    crlf[7] = 0x0D;
    memcpy(crlf + 8, bytes + 7, size - 7);
    parse_copy(crlf, size + 1, NULL, &error);
    CHECK(strstr(error.message, "LF turned into CRLF") != NULL, "LF to CRLF is named");
    free(crlf);
    free(bytes);
}

/* Tables with a valid header checksum but impossible contents. */
static void test_hostile_tables(void)
{
    size_t size;
    unsigned char *bytes = small_file(&size);
    unsigned char *edit = malloc(size);
    gb_error error;
    struct { const char *what; size_t at; uint64_t value; int width; const char *message; }
    cases[] = {
        {"section count 2^32-1", 24, 0xFFFFFFFFu, 4,
         "x.test: truncated or corrupt: 4294967295 sections need a 206158430160-byte table, "
         "the file has 209 bytes"},
        {"a size of 2^64-1", 32 + 32, UINT64_MAX, 8,
         "x.test: section 'a' (18446744073709551615 bytes at offset 176) runs past the end "
         "of the file (209 bytes)"},
        {"an offset of 2^64-8", 32 + 24, UINT64_MAX - 7, 8,
         "x.test: section 'a' is at offset 18446744073709551608, expected 176"},
        {"an unaligned offset", 32 + 48 + 24, 190, 8,
         "x.test: section 'bb' is at offset 190, expected 192"},
        {"a nonzero reserved field", 32 + 44, 1, 4,
         "x.test: section 'a' has a nonzero reserved field"},
        {"container version 2", 16, 2, 4,
         "x.test: container version 2 is newer than this program (1)"},
        {"a big-endian mark", 20, 0x04030201u, 4,
         "x.test: declares big-endian data, which gibake does not read"},
        {"a kind with a space", 8, 0x20534554u, 4,
         "x.test: bad file kind (bytes 8..11 must be ASCII letters or digits)"},
        {"a name of 24 letters", 32 + 48, 0x6262626262626262u, 8, NULL},
        {"bytes after a name's NUL", 32 + 48 * 2 + 5, 0x41, 1,
         "x.test: section 'ccc' has bytes after its name's NUL"},
        {"an empty name", 32, 0, 1, "x.test: the name of section 0 is empty"},
        {"a tab in a name", 32 + 1, 0x09, 1,
         "x.test: the name of section 0 has a byte that is not printable ASCII"},
        {"a duplicated name", 32 + 48 * 2, 0x6262, 4, "x.test: two sections are named 'bb'"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        memcpy(edit, bytes, size);
        if (cases[c].width == 8)
            put_u64(edit + cases[c].at, cases[c].value);
        else if (cases[c].width == 4)
            put_u32(edit + cases[c].at, (uint32_t)cases[c].value);
        else
            edit[cases[c].at] = (unsigned char)cases[c].value;
        if (!cases[c].message) { /* fill the whole 24-byte name of 'bb' */
            memset(edit + 32 + 48, 'b', 24);
            cases[c].message = "x.test: the name of section 1 is longer than 23 bytes";
        }
        reseal(edit, size);
        gb_result result = parse_copy(edit, size, NULL, &error);
        char label[128];
        snprintf(label, sizeof label, "%s is rejected with its message", cases[c].what);
        CHECK(result != GB_OK && strcmp(error.message, cases[c].message) == 0, label);
        if (strcmp(error.message, cases[c].message) != 0)
            printf("#   got '%s'\n", error.message);
    }
    free(edit);
    free(bytes);
}

static void test_read_errors(void)
{
    gb_container container;
    gb_error error;
    const char *missing = scratch_path("missing.test");
    CHECK_EQ_INT(gb_container_read(missing, NULL, &container, &error), GB_ERROR_IO,
                 "reading a missing file is an IO error");
    CHECK(starts_with(error.message, missing) && strstr(error.message, "No such file"),
          "missing file message names the path");
    const char *empty = scratch_path("empty.test");
    scratch_write(empty, "", 0);
    CHECK_EQ_INT(gb_container_read(empty, NULL, &container, &error), GB_ERROR_FORMAT,
                 "reading an empty file is a format error");
    const char *text = scratch_path("text.test");
    scratch_write(text, "hello", 5);
    CHECK_EQ_INT(gb_container_read(text, NULL, &container, &error), GB_ERROR_FORMAT,
                 "reading a 5-byte text file is a format error");
    CHECK(strstr(error.message, "not a gibake file (bad magic)") != NULL,
          "text file message says bad magic");
    CHECK_EQ_INT(gb_container_read(scratch_folder, NULL, &container, &error), GB_ERROR_IO,
                 "reading a folder is an IO error");
    CHECK(container.sections == NULL && container.mapping == NULL,
          "a failed read leaves the container zeroed");
    unlink(empty);
    unlink(text);
}

/* ---- writer ---- */

static void test_writer_arguments(void)
{
    gb_container_writer *writer = gb_container_writer_create("TEST", 1);
    gb_error error;
    CHECK_EQ_INT(gb_container_add(writer, "", "x", 1, &error), GB_ERROR_ARGUMENT,
                 "an empty name is refused");
    CHECK_EQ_INT(gb_container_add(writer, "abcdefghijklmnopqrstuvwx", "x", 1, &error),
                 GB_ERROR_ARGUMENT, "a 24-byte name is refused");
    CHECK_EQ_INT(gb_container_add(writer, "abcdefghijklmnopqrstuvw", "x", 1, &error), GB_OK,
                 "a 23-byte name is accepted");
    CHECK_EQ_INT(gb_container_add(writer, "tab\there", "x", 1, &error), GB_ERROR_ARGUMENT,
                 "a name with a tab is refused");
    CHECK_EQ_INT(gb_container_add(writer, "abcdefghijklmnopqrstuvw", "y", 1, &error),
                 GB_ERROR_ARGUMENT, "a name added twice is refused");
    CHECK_EQ_INT(gb_container_add(writer, "null", NULL, 4, &error), GB_ERROR_ARGUMENT,
                 "NULL data of 4 bytes is refused");
    gb_container_writer_destroy(writer);

    const char *path = scratch_path("bad.test");
    writer = gb_container_writer_create("TOO LONG", 1);
    CHECK(writer != NULL, "create with a bad kind still returns a writer");
    CHECK_EQ_INT(gb_container_commit(writer, path, &error), GB_ERROR_ARGUMENT,
                 "commit with a bad kind is refused");
    gb_container_writer_destroy(writer);
    writer = gb_container_writer_create("TEST", 0);
    CHECK_EQ_INT(gb_container_commit(writer, path, &error), GB_ERROR_ARGUMENT,
                 "commit with version 0 is refused");
    gb_container_writer_destroy(writer);
    CHECK_EQ_INT(count_files(NULL, 0), 0, "refused commits write nothing");
}

typedef struct interrupter {
    int calls;
    int stop_at;     /* the call that stops the commit */
    int kill_self;   /* stop by SIGKILL instead of returning 1 */
} interrupter;

static int interrupt_commit(void *user)
{
    interrupter *state = user;
    if (++state->calls < state->stop_at)
        return 0;
    if (state->kill_self)
        raise(SIGKILL);
    return 1;
}

static void test_cancelled_commit(void)
{
    for (int stop_at = 1; stop_at <= 6; ++stop_at) {
        gb_container_writer *writer = sample_writer();
        interrupter state = {0, stop_at, 0};
        gb_container_writer_set_interrupt(writer, interrupt_commit, &state);
        gb_error error = {""};
        const char *path = scratch_path("cancelled.test");
        gb_result result = gb_container_commit(writer, path, &error);
        gb_container_writer_destroy(writer);
        char label[128];
        snprintf(label, sizeof label,
                 "commit cancelled at call %d of 6 fails as interrupted", stop_at);
        CHECK(result == GB_ERROR_INTERRUPTED && state.calls == stop_at, label);
        snprintf(label, sizeof label, "cancelled at call %d: message and no file left",
                 stop_at);
        CHECK(starts_with(error.message, path) && strstr(error.message, "interrupted") &&
                  !exists(path) && count_files(NULL, 0) == 0,
              label);
    }
    gb_container_writer *writer = sample_writer();
    interrupter state = {0, 1000, 0};
    gb_container_writer_set_interrupt(writer, interrupt_commit, &state);
    gb_error error;
    const char *path = scratch_path("counted.test");
    CHECK_EQ_INT(gb_container_commit(writer, path, &error), GB_OK,
                 "an interrupter that returns 0 lets the commit finish");
    CHECK_EQ_INT(state.calls, 6, "the interrupter runs before each of 5 sections and once more");
    gb_container_writer_destroy(writer);
    unlink(path);
}

static void test_replace_is_atomic(void)
{
    const char *path = scratch_path("replace.test");
    gb_container_writer *old = gb_container_writer_create("TEST", 1);
    gb_error error;
    gb_container_add(old, "old", "old content", 11, &error);
    gb_container_commit(old, path, &error);
    gb_container_writer_destroy(old);
    size_t old_size, now_size;
    unsigned char *before = scratch_read(path, &old_size);

    gb_container_writer *writer = sample_writer();
    interrupter state = {0, 6, 0}; /* the last call, after every payload is written */
    gb_container_writer_set_interrupt(writer, interrupt_commit, &state);
    CHECK_EQ_INT(gb_container_commit(writer, path, &error), GB_ERROR_INTERRUPTED,
                 "a replacing commit cancelled before the rename fails");
    gb_container_writer_destroy(writer);
    unsigned char *after = scratch_read(path, &now_size);
    CHECK(after && now_size == old_size && memcmp(before, after, old_size) == 0,
          "the old file is intact after a cancelled replacement");
    CHECK_EQ_INT(count_files(NULL, 0), 1, "no temporary is left beside it");
    free(after);

    writer = sample_writer();
    CHECK_EQ_INT(gb_container_commit(writer, path, &error), GB_OK,
                 "an uncancelled replacing commit succeeds");
    gb_container_writer_destroy(writer);
    gb_container container;
    CHECK(gb_container_read(path, "TEST", &container, &error) == GB_OK &&
              container.section_count == 5,
          "the new file replaced the old one");
    gb_container_close(&container);
    free(before);
    unlink(path);
}

/* A child process commits and kills itself (SIGKILL, no cleanup possible)
 * from inside the interrupter at call stop_at. */
static void test_killed_commit(int stop_at)
{
    const char *path = scratch_path("killed.test");
    fflush(stdout);
    pid_t child = fork();
    if (child == 0) {
        gb_container_writer *writer = sample_writer();
        interrupter state = {0, stop_at, 1};
        gb_container_writer_set_interrupt(writer, interrupt_commit, &state);
        gb_error error;
        gb_container_commit(writer, path, &error);
        _exit(0);
    }
    int status = 0;
    waitpid(child, &status, 0);
    char label[128], name[256] = "";
    snprintf(label, sizeof label, "child killed by SIGKILL at interrupter call %d", stop_at);
    CHECK(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL, label);
    snprintf(label, sizeof label, "killed at call %d: no file at the final name", stop_at);
    CHECK(!exists(path), label);
    int files = count_files(name, sizeof name);
    snprintf(label, sizeof label, "killed at call %d: only a killed.test.tmp.* is left",
             stop_at);
    CHECK(files == 1 && starts_with(name, "killed.test.tmp."), label);
    scratch_empty();
}

static void test_missing_folder(void)
{
    gb_container_writer *writer = sample_writer();
    gb_error error = {""};
    const char *path = scratch_path("no/such/folder/x.test");
    CHECK_EQ_INT(gb_container_commit(writer, path, &error), GB_ERROR_IO,
                 "commit into a missing folder is an IO error");
    CHECK(starts_with(error.message, path) && strstr(error.message, "No such file"),
          "the message names the path and the reason");
    gb_container_writer_destroy(writer);
}

/* ---- arrays in one call ---- */

/* gb_container_write_arrays writes the bytes of the section-by-section
 * writer; gb_container_find_arrays finds each array and stops, with NULL
 * data from there on, at the first of the wrong size. */
static void test_arrays(void)
{
    gb_error error = {""};
    const char *by_sections = scratch_path("sections.test");
    const char *by_arrays = scratch_path("arrays.test");
    gb_container_writer *writer = sample_writer();
    gb_container_commit(writer, by_sections, &error);
    gb_container_writer_destroy(writer);
    const gb_container_array arrays[] = {
        {"positions", 25, 4, positions}, {"empty", 0, 8, NULL}, {"indices", 33, 1, indices},
        {"aligned", 2, 16, aligned},     {"one", 1, 1, one},
    };
    CHECK_EQ_INT(gb_container_write_arrays(by_arrays, "TEST", 2, arrays, 5, &error), GB_OK,
                 "write_arrays succeeds");
    size_t size_a, size_b;
    unsigned char *a = scratch_read(by_sections, &size_a), *b = scratch_read(by_arrays, &size_b);
    CHECK(a && b && size_a == size_b && memcmp(a, b, size_a) == 0,
          "write_arrays writes the bytes of adding the sections one by one");
    free(a);
    free(b);

    gb_container container;
    gb_container_read(by_arrays, "TEST", &container, &error);
    gb_container_array found[] = {
        {"positions", 25, 4, NULL}, {"indices", 33, 1, NULL}, {"aligned", 2, 16, NULL}};
    CHECK_EQ_INT(gb_container_find_arrays(&container, found, 3, 16, by_arrays, &error), GB_OK,
                 "find_arrays finds three arrays of the right sizes");
    CHECK(found[0].data == gb_container_find(&container, "positions")->data &&
              found[1].data == gb_container_find(&container, "indices")->data &&
              found[2].data == gb_container_find(&container, "aligned")->data,
          "find_arrays gives each array its section's payload");
    found[1].count = 34;
    CHECK_EQ_INT(gb_container_find_arrays(&container, found, 3, 16, by_arrays, &error),
                 GB_ERROR_FORMAT, "find_arrays fails on a section of the wrong size");
    CHECK(found[0].data && !found[1].data && !found[2].data,
          "find_arrays stops there: the arrays before it found, the rest NULL");
    CHECK(strstr(error.message, "\"indices\" section has 33 bytes") != NULL,
          "the error names the section and its size");
    gb_container_close(&container);
    unlink(by_sections);
    unlink(by_arrays);
}

int main(void)
{
    umask(022);
    scratch_create("container");
    fill_payloads();
    test_round_trip();
    test_empty_container();
    test_deterministic();
    test_check_version();
    test_every_byte_flip();
    test_truncations_and_trailing();
    test_wrong_kind();
    test_text_mangling();
    test_hostile_tables();
    test_read_errors();
    test_writer_arguments();
    test_cancelled_commit();
    test_replace_is_atomic();
    test_killed_commit(1);
    test_killed_commit(3);
    test_killed_commit(6);
    test_missing_folder();
    test_arrays();
    scratch_remove();
    return tap_done();
}
