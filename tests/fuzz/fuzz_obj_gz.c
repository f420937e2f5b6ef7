/* fuzz_obj_gz.c — libFuzzer target for the gzip path of the OBJ reader
 * (gb_obj_read of a `.obj.gz`, through gb_text_load and zlib's gzread):
 * any input gives either a scene or an error "path: ...", never a crash, a
 * leak, a hang or a read out of bounds (run under ASan/UBSan by
 * `make fuzz`). fuzz_obj fuzzes the OBJ text itself; this one the
 * compressed stream (truncated, concatenated or corrupt members, trailing
 * bytes, plain text).
 *
 * The input is written as fuzz.obj.gz in a private temporary folder (made
 * and removed for each input: libFuzzer ends with _Exit, no atexit handler
 * runs), beside a fuzz.mtl (so that "mtllib fuzz.mtl" reads one), and read
 * as a tool reads it. A damaged deflate stream is nearly always caught by the gzip trailer's
 * CRC-32: each input is read as it is, then, when it is one gzip member
 * whose deflate stream decodes, again with its trailer (CRC-32 and length)
 * recomputed, which lets the mutations reach the OBJ parser through zlib.
 * Seeds: tests/fuzz/corpus/fuzz_obj_gz.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <zlib.h>

#include "fuzz_reader.h"
#include "obj.h"
#include "scene.h"

static void path_in_folder(const char *folder, const char *name, char *path, size_t size)
{
    snprintf(path, size, "%s/%s", folder, name);
}

static void remove_folder(const char *folder)
{
    char path[128];
    path_in_folder(folder, "fuzz.obj.gz", path, sizeof path);
    unlink(path);
    path_in_folder(folder, "fuzz.mtl", path, sizeof path);
    unlink(path);
    rmdir(folder);
}

static void write_file(const char *path, const void *data, size_t size)
{
    FILE *file = fopen(path, "wb");
    if (!file || fwrite(data, 1, size, file) != size || fclose(file) != 0)
        abort();
}

static void make_folder(char *folder)
{
    static const char mtl[] = "newmtl white\nKd 0.7 0.7 0.7\nnewmtl light\nKe 10 10 10\n";
    char path[128];
    if (!mkdtemp(folder))
        abort();
    path_in_folder(folder, "fuzz.mtl", path, sizeof path);
    write_file(path, mtl, sizeof mtl - 1);
}

/* The length of a gzip header (RFC 1952) at bytes, 0 if it is not one. */
static size_t gzip_header_length(const uint8_t *bytes, size_t size)
{
    if (size < 10 || bytes[0] != 0x1f || bytes[1] != 0x8b || bytes[2] != 8)
        return 0;
    uint8_t flags = bytes[3];
    size_t at = 10;
    if (flags & 4) {            /* FEXTRA */
        if (size < at + 2)
            return 0;
        at += 2 + (size_t)(bytes[at] | bytes[at + 1] << 8);
    }
    for (int field = 8; field <= 16; field <<= 1)   /* FNAME, FCOMMENT */
        if (flags & field) {
            while (at < size && bytes[at])
                ++at;
            ++at;
        }
    if (flags & 2)              /* FHCRC */
        at += 2;
    return at < size ? at : 0;
}

/* Rewrites the trailer of a one-member gzip file after its deflate stream;
 * 0 when the stream does not decode or the trailer is not where it ends. */
static int fix_trailer(uint8_t *bytes, size_t size)
{
    size_t header = gzip_header_length(bytes, size);
    if (!header)
        return 0;
    z_stream z;
    memset(&z, 0, sizeof z);
    if (inflateInit2(&z, -15) != Z_OK)
        return 0;
    unsigned char out[1 << 14];
    uLong crc = crc32(0L, Z_NULL, 0), length = 0;
    z.next_in = bytes + header;
    z.avail_in = (uInt)(size - header);
    int status;
    do {
        z.next_out = out;
        z.avail_out = sizeof out;
        status = inflate(&z, Z_NO_FLUSH);
        size_t got = sizeof out - z.avail_out;
        crc = crc32(crc, out, (uInt)got);
        length += got;
    } while (status == Z_OK);
    size_t end = size - z.avail_in;
    inflateEnd(&z);
    if (status != Z_STREAM_END || size - end < 8)
        return 0;
    for (int i = 0; i < 4; ++i) {
        bytes[end + i] = (uint8_t)(crc >> (8 * i));
        bytes[end + 4 + i] = (uint8_t)(length >> (8 * i));
    }
    return 1;
}

static void read_obj(const char *path, const uint8_t *data, size_t size)
{
    write_file(path, data, size);
    gb_scene scene = {0};
    gb_error error;
    error.message[0] = '\0';
    if (gb_obj_read(path, &scene, &error) == GB_OK) {
        gb_fuzz_check_triangles(&scene, 0);
    } else if (!gb_fuzz_names(&error, path)) {
        __builtin_trap(); /* every failure names the file */
    }
    gb_scene_free(&scene);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char folder[] = "/tmp/fuzz_obj_gz.XXXXXX", path[128];
    make_folder(folder);
    path_in_folder(folder, "fuzz.obj.gz", path, sizeof path);
    read_obj(path, data, size);
    uint8_t *copy = malloc(size + 1);
    if (copy) {
        memcpy(copy, data, size);
        if (fix_trailer(copy, size) && memcmp(copy, data, size) != 0)
            read_obj(path, copy, size);
        free(copy);
    }
    remove_folder(folder);
    return 0;
}
