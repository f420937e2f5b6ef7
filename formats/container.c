/* container.c — writes and reads the one binary container of every gibake
 * file (API in formats/container.h, every byte in formats/FORMATS.md).
 *
 * The reader trusts nothing: it checks every header field, every table entry
 * and every padding byte with overflow-safe arithmetic before it hands out a
 * view, and it checks the CRC-32 of the header, the table and each payload, so
 * any input gives either a valid container or an error message. The layout
 * leaves no byte unchecked: changing any single byte of a file is detected.
 *
 * The writer hands the bytes to the one output writer (output_file.h): a
 * regular destination holds either the old file or the complete new one,
 * never a part; a device, FIFO or "-" gets the bytes straight through.
 */
#include "container.h"
#include "array_reserve.h"
#include "mapped_file.h"
#include "little_endian.h"
#include "output_file.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zlib.h>

enum {
    HEADER_SIZE = 32,
    ENTRY_SIZE = 48,
    ALIGNMENT = 16,
    CONTAINER_VERSION = 1,
    /* byte offsets inside the header */
    AT_KIND = 8,
    AT_VERSION = 12,
    AT_CONTAINER_VERSION = 16,
    AT_ENDIAN_MARK = 20,
    AT_SECTION_COUNT = 24,
    AT_HEADER_CRC = 28,
    /* byte offsets inside a table entry */
    AT_OFFSET = 24,
    AT_SIZE = 32,
    AT_PAYLOAD_CRC = 40,
    AT_RESERVED = 44,
};

static const unsigned char MAGIC[8] = {0xAB, 'G', 'B', 'K', 0x0D, 0x0A, 0x1A, 0x0A};
static const uint32_t ENDIAN_MARK = 0x01020304u;

/* ---- little-endian fields, independent of the host's byte order ---- */

/* zlib's crc32 takes an unsigned int length: feed large payloads in chunks. */
static uint32_t crc_update(uint32_t crc, const void *data, uint64_t size)
{
    const unsigned char *bytes = data;
    while (size > 0) {
        uInt chunk = size > (1u << 30) ? (1u << 30) : (uInt)size;
        crc = (uint32_t)crc32(crc, bytes, chunk);
        bytes += chunk;
        size -= chunk;
    }
    return crc;
}

static uint32_t crc_of(const void *data, uint64_t size)
{
    return crc_update((uint32_t)crc32(0L, Z_NULL, 0), data, size);
}

/* The header CRC covers header bytes 0..27, then the whole section table. */
static uint32_t header_crc(const unsigned char *header, const unsigned char *table,
                           uint64_t table_size)
{
    return crc_update(crc_of(header, AT_HEADER_CRC), table, table_size);
}

/* Rounds up to the alignment; 0 when that would overflow. */
static int align_up(uint64_t value, uint64_t *aligned)
{
    if (value > UINT64_MAX - (ALIGNMENT - 1))
        return 0;
    *aligned = (value + (ALIGNMENT - 1)) & ~(uint64_t)(ALIGNMENT - 1);
    return 1;
}

/* ---- names and kinds, shared by reader and writer ---- */

static int is_kind_letter(unsigned char c)
{
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
}

static int is_kind(const char *kind)
{
    if (!kind || strlen(kind) != 4)
        return 0;
    for (int i = 0; i < 4; ++i)
        if (!is_kind_letter((unsigned char)kind[i]))
            return 0;
    return 1;
}

static int is_printable(unsigned char c)
{
    return c >= 0x20 && c <= 0x7E;
}

/* What is wrong with a section name of length bytes, or NULL when it is valid. */
static const char *name_problem(const char *name, size_t length)
{
    if (length == 0)
        return "is empty";
    if (length >= GB_SECTION_NAME_SIZE)
        return "is longer than 23 bytes";
    for (size_t i = 0; i < length; ++i)
        if (!is_printable((unsigned char)name[i]))
            return "has a byte that is not printable ASCII";
    return NULL;
}

/* ---- reader ---- */

/* Says what most likely mangled a file whose magic does not match. */
static const char *magic_problem(const unsigned char *bytes, size_t size)
{
    static const unsigned char lf_only[7] = {0xAB, 'G', 'B', 'K', 0x0A, 0x1A, 0x0A};
    static const unsigned char crlf_twice[9] = {0xAB, 'G', 'B', 'K', 0x0D, 0x0A,
                                                0x1A, 0x0D, 0x0A};
    if (size >= 1 && bytes[0] == (MAGIC[0] & 0x7F) && size >= 4 &&
        memcmp(bytes + 1, MAGIC + 1, 3) == 0)
        return "not a gibake file (bad magic: the top bit was stripped, "
               "copied as 7-bit text?)";
    if (size >= sizeof lf_only && memcmp(bytes, lf_only, sizeof lf_only) == 0)
        return "not a gibake file (bad magic: CRLF turned into LF, copied as text?)";
    if (size >= sizeof crlf_twice && memcmp(bytes, crlf_twice, sizeof crlf_twice) == 0)
        return "not a gibake file (bad magic: LF turned into CRLF, copied as text?)";
    return "not a gibake file (bad magic)";
}

static gb_result check_magic(const unsigned char *bytes, size_t size, const char *path,
                             gb_error *error)
{
    size_t compared = size < sizeof MAGIC ? size : sizeof MAGIC;
    if (size == 0)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: empty file, not a gibake file", path);
    if (memcmp(bytes, MAGIC, compared) != 0)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: %s", path, magic_problem(bytes, size));
    if (size < HEADER_SIZE)
        return gb_fail(error, GB_ERROR_FORMAT,
                       "%s: truncated header (%zu bytes, the header has %d)", path, size,
                       HEADER_SIZE);
    return GB_OK;
}

/* The fields that must be understood before the header CRC can be checked. */
static gb_result check_header_fields(const unsigned char *bytes, size_t size,
                                     const char *path, gb_error *error)
{
    uint32_t container_version = gb_get_u32(bytes + AT_CONTAINER_VERSION);
    uint32_t mark = gb_get_u32(bytes + AT_ENDIAN_MARK);
    uint64_t count = gb_get_u32(bytes + AT_SECTION_COUNT);
    if (container_version == 0)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: bad container version 0", path);
    if (container_version > CONTAINER_VERSION)
        return gb_fail(error, GB_ERROR_UNSUPPORTED,
                       "%s: container version %u is newer than this program (%d)", path,
                       (unsigned)container_version, CONTAINER_VERSION);
    if (mark == 0x04030201u)
        return gb_fail(error, GB_ERROR_UNSUPPORTED,
                       "%s: declares big-endian data, which gibake does not read", path);
    if (mark != ENDIAN_MARK)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: bad endianness mark 0x%08x", path,
                       (unsigned)mark);
    if (count > (size - HEADER_SIZE) / ENTRY_SIZE)
        return gb_fail(error, GB_ERROR_FORMAT,
                       "%s: truncated or corrupt: %llu sections need a %llu-byte table, "
                       "the file has %zu bytes",
                       path, (unsigned long long)count,
                       (unsigned long long)(count * ENTRY_SIZE), size);
    return GB_OK;
}

static gb_result check_kind(const unsigned char *bytes, const char *path,
                            const char *expected_kind, gb_error *error)
{
    char kind[5] = {0};
    memcpy(kind, bytes + AT_KIND, 4);
    for (int i = 0; i < 4; ++i)
        if (!is_kind_letter((unsigned char)kind[i]))
            return gb_fail(error, GB_ERROR_FORMAT,
                           "%s: bad file kind (bytes 8..11 must be ASCII letters or digits)",
                           path);
    if (expected_kind && strcmp(kind, expected_kind) != 0)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: is a %s file, expected %s", path, kind,
                       expected_kind);
    return GB_OK;
}

/* Everything in bytes 0..31 and the table's checksum. */
static gb_result check_header(const unsigned char *bytes, size_t size, const char *path,
                              const char *expected_kind, gb_error *error)
{
    gb_result result = check_magic(bytes, size, path, error);
    if (result == GB_OK)
        result = check_header_fields(bytes, size, path, error);
    if (result != GB_OK)
        return result;
    uint64_t table_size = (uint64_t)gb_get_u32(bytes + AT_SECTION_COUNT) * ENTRY_SIZE;
    if (header_crc(bytes, bytes + HEADER_SIZE, table_size) != gb_get_u32(bytes + AT_HEADER_CRC))
        return gb_fail(error, GB_ERROR_CHECKSUM, "%s: header checksum mismatch", path);
    return check_kind(bytes, path, expected_kind, error);
}

/* Copies and checks the name of table entry index. */
static gb_result read_name(const unsigned char *entry, uint32_t index, const char *path,
                           char *name, gb_error *error)
{
    size_t length = strnlen((const char *)entry, GB_SECTION_NAME_SIZE);
    const char *problem = name_problem((const char *)entry, length);
    if (problem)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: the name of section %u %s", path,
                       (unsigned)index, problem);
    for (size_t i = length; i < GB_SECTION_NAME_SIZE; ++i)
        if (entry[i] != 0)
            return gb_fail(error, GB_ERROR_FORMAT,
                           "%s: section '%.*s' has bytes after its name's NUL", path,
                           (int)length, (const char *)entry);
    memcpy(name, entry, GB_SECTION_NAME_SIZE);
    return GB_OK;
}

/* A payload starts at the first aligned offset after the previous one ends,
 * fits in the file, and the padding before it is zero. */
static gb_result check_placement(const unsigned char *bytes, size_t size, uint64_t end,
                                 uint64_t offset, uint64_t length, const char *name,
                                 const char *path, gb_error *error)
{
    uint64_t expected = 0;
    if (!align_up(end, &expected) || offset != expected)
        return gb_fail(error, GB_ERROR_FORMAT,
                       "%s: section '%s' is at offset %llu, expected %llu", path, name,
                       (unsigned long long)offset, (unsigned long long)expected);
    if (offset > size || length > size - offset)
        return gb_fail(error, GB_ERROR_FORMAT,
                       "%s: section '%s' (%llu bytes at offset %llu) runs past the end of "
                       "the file (%zu bytes)",
                       path, name, (unsigned long long)length, (unsigned long long)offset,
                       size);
    for (uint64_t i = end; i < offset; ++i)
        if (bytes[i] != 0)
            return gb_fail(error, GB_ERROR_FORMAT,
                           "%s: padding byte %llu before section '%s' is not zero", path,
                           (unsigned long long)i, name);
    return GB_OK;
}

/* Checks table entry index and makes its section a view of bytes; *end is the
 * end of the previous payload on entry and of this one on return. */
static gb_result read_entry(const unsigned char *bytes, size_t size, uint32_t index,
                            uint64_t *end, gb_section *section, const char *path,
                            gb_error *error)
{
    const unsigned char *entry = bytes + HEADER_SIZE + (size_t)index * ENTRY_SIZE;
    gb_result result = read_name(entry, index, path, section->name, error);
    if (result != GB_OK)
        return result;
    if (gb_get_u32(entry + AT_RESERVED) != 0)
        return gb_fail(error, GB_ERROR_FORMAT,
                       "%s: section '%s' has a nonzero reserved field", path, section->name);
    uint64_t offset = gb_get_u64(entry + AT_OFFSET);
    uint64_t length = gb_get_u64(entry + AT_SIZE);
    result = check_placement(bytes, size, *end, offset, length, section->name, path, error);
    if (result != GB_OK)
        return result;
    section->data = bytes + offset;
    section->size = length;
    *end = offset + length;
    return GB_OK;
}

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(const char *const *)a, *(const char *const *)b);
}

/* Sorting keeps this O(n log n) however many sections a hostile file declares. */
static gb_result check_unique_names(const gb_section *sections, uint32_t count,
                                    const char *path, gb_error *error)
{
    if (count < 2)
        return GB_OK;
    const char **names = malloc((size_t)count * sizeof *names);
    if (!names)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    for (uint32_t i = 0; i < count; ++i)
        names[i] = sections[i].name;
    qsort(names, count, sizeof *names, compare_names);
    gb_result result = GB_OK;
    for (uint32_t i = 1; i < count && result == GB_OK; ++i)
        if (strcmp(names[i - 1], names[i]) == 0)
            result = gb_fail(error, GB_ERROR_FORMAT, "%s: two sections are named '%s'",
                             path, names[i]);
    free(names);
    return result;
}

static gb_result check_payload_crcs(const unsigned char *bytes, const gb_section *sections,
                                    uint32_t count, const char *path, gb_error *error)
{
    for (uint32_t i = 0; i < count; ++i) {
        const unsigned char *entry = bytes + HEADER_SIZE + (size_t)i * ENTRY_SIZE;
        if (crc_of(sections[i].data, sections[i].size) != gb_get_u32(entry + AT_PAYLOAD_CRC))
            return gb_fail(error, GB_ERROR_CHECKSUM, "%s: section '%s' checksum mismatch",
                           path, sections[i].name);
    }
    return GB_OK;
}

/* The table, the payloads' places, the end of the file, names, checksums. */
static gb_result read_sections(const unsigned char *bytes, size_t size,
                               gb_section *sections, uint32_t count, const char *path,
                               gb_error *error)
{
    uint64_t end = HEADER_SIZE + (uint64_t)count * ENTRY_SIZE;
    for (uint32_t i = 0; i < count; ++i) {
        gb_result result = read_entry(bytes, size, i, &end, &sections[i], path, error);
        if (result != GB_OK)
            return result;
    }
    if (end != size)
        return gb_fail(error, GB_ERROR_FORMAT,
                       "%s: %llu trailing bytes after the last section", path,
                       (unsigned long long)(size - end));
    gb_result result = check_unique_names(sections, count, path, error);
    if (result != GB_OK)
        return result;
    return check_payload_crcs(bytes, sections, count, path, error);
}

gb_result gb_container_parse(const void *bytes, size_t size, const char *path,
                             const char *expected_kind, gb_container *out,
                             gb_error *error)
{
    if (!path)
        path = "(buffer)";
    if (!out || (!bytes && size > 0))
        return gb_fail(error, GB_ERROR_ARGUMENT, "%s: no buffer or no container to fill",
                       path);
    memset(out, 0, sizeof *out);
    if (expected_kind && !is_kind(expected_kind))
        return gb_fail(error, GB_ERROR_ARGUMENT,
                       "%s: expected kind '%s' is not four ASCII letters or digits", path,
                       expected_kind);
    const unsigned char *b = bytes;
    gb_result result = check_header(b, size, path, expected_kind, error);
    if (result != GB_OK)
        return result;
    uint32_t count = gb_get_u32(b + AT_SECTION_COUNT);
    gb_section *sections = count ? calloc(count, sizeof *sections) : NULL;
    if (count && !sections)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    result = read_sections(b, size, sections, count, path, error);
    if (result != GB_OK) {
        free(sections);
        return result;
    }
    memcpy(out->kind, b + AT_KIND, 4);
    out->version = gb_get_u32(b + AT_VERSION);
    out->section_count = count;
    out->sections = sections;
    return GB_OK;
}

gb_result gb_container_read(const char *path, const char *expected_kind,
                            gb_container *out, gb_error *error)
{
    if (!path || !out)
        return gb_fail(error, GB_ERROR_ARGUMENT, "gb_container_read: no path or no container");
    memset(out, 0, sizeof *out);
    gb_mapped_file file;
    gb_result result = gb_mapped_file_open(path, &file, error);
    if (result != GB_OK)
        return result;
    result = gb_container_parse(file.bytes, file.size, path, expected_kind, out, error);
    if (result != GB_OK) {
        gb_mapped_file_close(&file);
        return result;
    }
    out->mapping = file.mapping;
    out->mapping_size = file.size;
    return GB_OK;
}

gb_result gb_container_check_version(const gb_container *container, const char *path,
                                     uint32_t newest, gb_error *error)
{
    if (container->version == 0)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: bad format version 0", path);
    if (container->version > newest)
        return gb_fail(error, GB_ERROR_UNSUPPORTED,
                       "%s: format version %u is newer than this program (%u)", path,
                       (unsigned)container->version, (unsigned)newest);
    return GB_OK;
}

const gb_section *gb_container_find(const gb_container *container, const char *name)
{
    if (!container || !name)
        return NULL;
    for (uint32_t i = 0; i < container->section_count; ++i)
        if (strcmp(container->sections[i].name, name) == 0)
            return &container->sections[i];
    return NULL;
}

gb_result gb_container_find_array(const gb_container *container, const char *name,
                                  uint64_t count, uint64_t element_size, unsigned alignment,
                                  const char *path, const gb_section **out, gb_error *error)
{
    const gb_section *section = gb_container_find(container, name);
    *out = NULL;
    if (!section)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: no \"%s\" section", path, name);
    if ((element_size && count > UINT64_MAX / element_size) ||
        section->size != count * element_size)
        return gb_fail(error, GB_ERROR_FORMAT,
                       "%s: \"%s\" section has %llu bytes, %llu x %llu expected", path, name,
                       (unsigned long long)section->size, (unsigned long long)count,
                       (unsigned long long)element_size);
    if (alignment > 1 && (uintptr_t)section->data % alignment)
        return gb_fail(error, GB_ERROR_ARGUMENT,
                       "%s: \"%s\" section is not %u-byte aligned in memory", path, name,
                       alignment);
    *out = section;
    return GB_OK;
}

gb_result gb_container_find_arrays(const gb_container *container, gb_container_array *arrays,
                                   int count, unsigned alignment, const char *path,
                                   gb_error *error)
{
    for (int i = 0; i < count; ++i)
        arrays[i].data = NULL;
    for (int i = 0; i < count; ++i) {
        const gb_section *section;
        gb_result result =
            gb_container_find_array(container, arrays[i].name, arrays[i].count,
                                    arrays[i].item_size, alignment, path, &section, error);
        if (result != GB_OK)
            return result;
        arrays[i].data = section->data;
    }
    return GB_OK;
}

void gb_container_close(gb_container *container)
{
    if (!container)
        return;
    free(container->sections);
    if (container->mapping)
        munmap(container->mapping, container->mapping_size);
    memset(container, 0, sizeof *container);
}

/* ---- writer ---- */

typedef struct pending_section {
    char name[GB_SECTION_NAME_SIZE];
    const void *data;
    uint64_t size;
} pending_section;

struct gb_container_writer {
    char kind[5];
    int kind_is_valid;
    uint32_t version;
    pending_section *sections;
    uint32_t count;
    size_t capacity;
    int (*interrupt)(void *user);
    void *interrupt_user;
};

gb_container_writer *gb_container_writer_create(const char *kind, uint32_t version)
{
    gb_container_writer *writer = calloc(1, sizeof *writer);
    if (!writer)
        return NULL;
    writer->kind_is_valid = is_kind(kind);
    if (writer->kind_is_valid)
        memcpy(writer->kind, kind, 5);
    writer->version = version;
    return writer;
}

void gb_container_writer_set_interrupt(gb_container_writer *writer,
                                       int (*interrupt)(void *user), void *user)
{
    writer->interrupt = interrupt;
    writer->interrupt_user = user;
}

static int has_section(const gb_container_writer *writer, const char *name)
{
    for (uint32_t i = 0; i < writer->count; ++i)
        if (strcmp(writer->sections[i].name, name) == 0)
            return 1;
    return 0;
}

static gb_result grow_sections(gb_container_writer *writer, gb_error *error)
{
    if (writer->count == UINT32_MAX)
        return gb_fail(error, GB_ERROR_INVALID, "too many sections");
    if (!gb_array_reserve(&writer->sections, &writer->capacity, (size_t)writer->count + 1,
                          sizeof *writer->sections))
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory adding a section");
    return GB_OK;
}

gb_result gb_container_add(gb_container_writer *writer, const char *name,
                           const void *data, uint64_t size, gb_error *error)
{
    if (!writer || !name)
        return gb_fail(error, GB_ERROR_ARGUMENT, "gb_container_add: no writer or no name");
    const char *problem = name_problem(name, strnlen(name, GB_SECTION_NAME_SIZE));
    if (problem)
        return gb_fail(error, GB_ERROR_ARGUMENT, "section name '%.40s' %s", name, problem);
    if (has_section(writer, name))
        return gb_fail(error, GB_ERROR_ARGUMENT, "section '%s' is added twice", name);
    if (!data && size > 0)
        return gb_fail(error, GB_ERROR_ARGUMENT, "section '%s' has %llu bytes but no data",
                       name, (unsigned long long)size);
    gb_result result = grow_sections(writer, error);
    if (result != GB_OK)
        return result;
    pending_section *section = &writer->sections[writer->count++];
    memset(section->name, 0, sizeof section->name);
    strcpy(section->name, name);
    section->data = data;
    section->size = size;
    return GB_OK;
}

/* Fills one table entry; *end goes from the end of the previous payload to
 * the end of this one. */
static gb_result fill_entry(unsigned char *entry, const pending_section *section,
                            uint64_t *end, const char *path, gb_error *error)
{
    uint64_t offset = 0;
    if (!align_up(*end, &offset) || section->size > UINT64_MAX - offset)
        return gb_fail(error, GB_ERROR_INVALID, "%s: sections too large for a file", path);
    memcpy(entry, section->name, GB_SECTION_NAME_SIZE);
    gb_put_u64(entry + AT_OFFSET, offset);
    gb_put_u64(entry + AT_SIZE, section->size);
    gb_put_u32(entry + AT_PAYLOAD_CRC, crc_of(section->data, section->size));
    gb_put_u32(entry + AT_RESERVED, 0);
    *end = offset + section->size;
    return GB_OK;
}

/* Builds the header and the section table, checksums included, in *head. */
static gb_result build_head(const gb_container_writer *writer, const char *path,
                            unsigned char **head, size_t *head_size, gb_error *error)
{
    size_t size = HEADER_SIZE + (size_t)writer->count * ENTRY_SIZE;
    unsigned char *bytes = calloc(1, size);
    if (!bytes)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    uint64_t end = size;
    for (uint32_t i = 0; i < writer->count; ++i) {
        gb_result result = fill_entry(bytes + HEADER_SIZE + (size_t)i * ENTRY_SIZE,
                                      &writer->sections[i], &end, path, error);
        if (result != GB_OK) {
            free(bytes);
            return result;
        }
    }
    memcpy(bytes, MAGIC, sizeof MAGIC);
    memcpy(bytes + AT_KIND, writer->kind, 4);
    gb_put_u32(bytes + AT_VERSION, writer->version);
    gb_put_u32(bytes + AT_CONTAINER_VERSION, CONTAINER_VERSION);
    gb_put_u32(bytes + AT_ENDIAN_MARK, ENDIAN_MARK);
    gb_put_u32(bytes + AT_SECTION_COUNT, writer->count);
    gb_put_u32(bytes + AT_HEADER_CRC, header_crc(bytes, bytes + HEADER_SIZE, size - HEADER_SIZE));
    *head = bytes;
    *head_size = size;
    return GB_OK;
}

static gb_result check_interrupt(const gb_container_writer *writer, const char *path,
                                 gb_error *error)
{
    if (writer->interrupt && writer->interrupt(writer->interrupt_user))
        return gb_fail(error, GB_ERROR_INTERRUPTED, "%s: interrupted, nothing written", path);
    return GB_OK;
}

/* Sizes are written in chunks that fit a size_t on any host. */
static gb_result write_bytes(gb_output_file *out, const void *data, uint64_t size,
                             gb_error *error)
{
    const unsigned char *bytes = data;
    gb_result result = GB_OK;
    while (size > 0 && result == GB_OK) {
        size_t chunk = size > (1u << 30) ? (1u << 30) : (size_t)size;
        result = gb_output_file_write(out, bytes, chunk, error);
        bytes += chunk;
        size -= chunk;
    }
    return result;
}

/* Writes header, table, padding and payloads to out, asking the interrupter
 * before each payload and once at the end. */
static gb_result write_contents(const gb_container_writer *writer, gb_output_file *out,
                                const unsigned char *head, size_t head_size,
                                const char *path, gb_error *error)
{
    static const unsigned char zeros[ALIGNMENT];
    gb_result result = write_bytes(out, head, head_size, error);
    uint64_t position = head_size;
    for (uint32_t i = 0; i < writer->count && result == GB_OK; ++i) {
        uint64_t offset = gb_get_u64(head + HEADER_SIZE + (size_t)i * ENTRY_SIZE + AT_OFFSET);
        result = check_interrupt(writer, path, error);
        if (result == GB_OK)
            result = write_bytes(out, zeros, offset - position, error);
        if (result == GB_OK)
            result = write_bytes(out, writer->sections[i].data, writer->sections[i].size,
                                 error);
        position = offset + writer->sections[i].size;
    }
    if (result == GB_OK)
        result = check_interrupt(writer, path, error);
    return result;
}

static gb_result check_writer(const gb_container_writer *writer, const char *path,
                              gb_error *error)
{
    if (!writer || !path || !*path)
        return gb_fail(error, GB_ERROR_ARGUMENT, "gb_container_commit: no writer or no path");
    if (!writer->kind_is_valid)
        return gb_fail(error, GB_ERROR_ARGUMENT,
                       "%s: the file kind is not four ASCII letters or digits", path);
    if (writer->version == 0)
        return gb_fail(error, GB_ERROR_ARGUMENT, "%s: format version 0 is not allowed", path);
    return GB_OK;
}

/* The file goes through the one output writer (output_file.h): a temporary
 * beside path, fsync, rename, fsync of the folder; straight through to a
 * device, FIFO or "-". */
gb_result gb_container_commit(gb_container_writer *writer, const char *path,
                              gb_error *error)
{
    gb_result result = check_writer(writer, path, error);
    if (result != GB_OK)
        return result;
    unsigned char *head = NULL;
    size_t head_size = 0;
    result = build_head(writer, path, &head, &head_size, error);
    if (result != GB_OK)
        return result;
    gb_output_file *out = NULL;
    result = gb_output_file_open(path, GB_OUTPUT_FILE_STREAM, &out, error);
    if (result == GB_OK)
        result = write_contents(writer, out, head, head_size, path, error);
    free(head);
    if (result != GB_OK) {
        gb_output_file_abort(out);
        return result;
    }
    return gb_output_file_commit(out, error);
}

void gb_container_writer_destroy(gb_container_writer *writer)
{
    if (!writer)
        return;
    free(writer->sections);
    free(writer);
}

gb_result gb_container_write_arrays(const char *path, const char *kind, uint32_t version,
                                    const gb_container_array *arrays, int count,
                                    gb_error *error)
{
    gb_container_writer *writer = gb_container_writer_create(kind, version);
    if (!writer)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    gb_result result = GB_OK;
    for (int i = 0; i < count && result == GB_OK; ++i) {
        const gb_container_array *a = &arrays[i];
        if (a->item_size && a->count > UINT64_MAX / a->item_size)
            result = gb_fail(error, GB_ERROR_ARGUMENT, "%s: \"%s\" has too many items", path,
                             a->name);
        else
            result = gb_container_add(writer, a->name, a->data, a->count * a->item_size, error);
    }
    if (result == GB_OK)
        result = gb_container_commit(writer, path, error);
    gb_container_writer_destroy(writer);
    return result;
}
