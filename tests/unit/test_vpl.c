/* The VPL set file (formats/vpl.[ch]): a round trip keeps every value, and
 * corrupted, inconsistent, invalid, newer or stale sets are refused. */
#include "container.h"
#include "scratch.h"
#include "tap.h"
#include "vpl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static const gb_vpl sample_vpls[3] = {
    {{1, 2, 3}, {0, 1, 0}, {0.5f, 0.25f, 0.125f}},
    {{-1e3f, 0.001f, 7}, {0.6f, 0, 0.8f}, {0, 0, 0}},
    {{0, 0, 0}, {0, 0, -1}, {1e6f, 2e6f, 3e6f}},
};

static void test_round_trip(void)
{
    gb_vpl_set set = {.scene_hash = 0x0123456789abcdefULL, .count = 3,
                      .vpls = (gb_vpl *)sample_vpls};
    gb_error error;
    CHECK_EQ_INT(gb_vpl_write(scratch_path("a.vpls"), &set, &error), GB_OK, "write a VPL set");
    gb_vpl_set read;
    CHECK_EQ_INT(gb_vpl_read(scratch_path("a.vpls"), &read, &error), GB_OK, "read it back");
    CHECK(read.count == 3 && read.scene_hash == set.scene_hash &&
              memcmp(read.vpls, sample_vpls, sizeof sample_vpls) == 0,
          "the round trip keeps the count, the scene hash and every float");
    CHECK_EQ_INT(gb_vpl_check_scene(&read, set.scene_hash, "a.vpls", &error), GB_OK,
                 "the set belongs to its scene");
    CHECK_EQ_INT(gb_vpl_check_scene(&read, 42, "a.vpls", &error), GB_ERROR_STALE,
                 "another scene's hash is refused as stale");
    gb_vpl_free(&read);

    gb_vpl_set empty = {.scene_hash = 9};
    gb_vpl_write(scratch_path("empty.vpls"), &empty, &error);
    CHECK(gb_vpl_read(scratch_path("empty.vpls"), &read, &error) == GB_OK && read.count == 0 &&
              read.scene_hash == 9,
          "an empty set is valid");
    gb_vpl_free(&read);
}

static void test_corruption(void)
{
    size_t size;
    unsigned char *bytes = scratch_read(scratch_path("a.vpls"), &size);
    int refused = 1, messages = 1;
    for (size_t i = 0; bytes && i < size; ++i) {
        bytes[i] ^= 0x10;
        gb_vpl_set set;
        gb_error error;
        refused &= gb_vpl_parse(bytes, size, "a.vpls", &set, &error) != GB_OK;
        messages &= strncmp(error.message, "a.vpls", 6) == 0;
        bytes[i] ^= 0x10;
    }
    CHECK(bytes && refused, "every flipped byte is refused");
    CHECK(messages, "every refusal names the file");
    gb_vpl_set set;
    gb_error error;
    CHECK(bytes && gb_vpl_parse(bytes, size / 2, "a.vpls", &set, &error) != GB_OK,
          "a truncated file is refused");
    free(bytes);
}

/* gb_vpl_read of a container of kind VPLS written as scratch file name
 * with the sections given. */
static gb_result read_raw(const char *name, uint32_t version, const void *header,
                          uint64_t header_size, const void *vpls, uint64_t vpls_size,
                          gb_vpl_set *set)
{
    gb_container_writer *w = gb_container_writer_create("VPLS", version);
    gb_error error;
    gb_container_add(w, "header", header, header_size, &error);
    gb_container_add(w, "vpls", vpls, vpls_size, &error);
    gb_container_commit(w, scratch_path(name), &error);
    gb_container_writer_destroy(w);
    return gb_vpl_read(scratch_path(name), set, &error);
}

static void test_inconsistent(void)
{
    unsigned char header[16] = {3, 0, 0, 0}; /* 3 VPLs, little-endian */
    unsigned char payload[2 * 36] = {0};
    gb_vpl_set set;
    gb_error error;
    CHECK_EQ_INT(read_raw("short.vpls", 1, header, 16, payload, sizeof payload, &set),
                 GB_ERROR_FORMAT, "a count that does not match the payload is refused");
    header[0] = 2;
    CHECK_EQ_INT(read_raw("zero-normal.vpls", 1, header, 16, payload, sizeof payload, &set),
                 GB_ERROR_INVALID, "a VPL whose normal is not unit is refused");
    CHECK_EQ_INT(read_raw("newer.vpls", 2, header, 16, payload, sizeof payload, &set),
                 GB_ERROR_UNSUPPORTED, "a newer format version is refused");
    header[4] = 1;
    CHECK_EQ_INT(read_raw("reserved.vpls", 1, header, 16, payload, sizeof payload, &set),
                 GB_ERROR_FORMAT, "a nonzero reserved field is refused");
    CHECK_EQ_INT(read_raw("small-header.vpls", 1, header, 8, payload, sizeof payload, &set),
                 GB_ERROR_FORMAT, "a header of the wrong size is refused");
    CHECK(set.count == 0 && set.vpls == NULL, "a failed read leaves an empty set");
    gb_container_writer *w = gb_container_writer_create("SKEL", 1);
    gb_container_add(w, "header", header, 16, &error);
    gb_container_commit(w, scratch_path("other.kind"), &error);
    gb_container_writer_destroy(w);
    CHECK(gb_vpl_read(scratch_path("other.kind"), &set, &error) != GB_OK,
          "a container of another kind is refused");
}

static void test_invalid_write(void)
{
    gb_vpl bad[1] = {{{0, 0, 0}, {0, 2, 0}, {1, 1, 1}}};
    gb_vpl_set set = {.count = 1, .vpls = bad};
    gb_error error;
    CHECK_EQ_INT(gb_vpl_write(scratch_path("bad.vpls"), &set, &error), GB_ERROR_INVALID,
                 "writing a non-unit normal is refused");
    CHECK(access(scratch_path("bad.vpls"), F_OK) != 0, "and leaves no file");
    bad[0].normal[1] = 1;
    bad[0].power[2] = -1;
    CHECK_EQ_INT(gb_vpl_write(scratch_path("bad.vpls"), &set, &error), GB_ERROR_INVALID,
                 "writing a negative power is refused");
    CHECK_EQ_INT(gb_vpl_read(scratch_path("missing.vpls"), &set, &error), GB_ERROR_IO,
                 "a missing file is an I/O error");
}

int main(void)
{
    scratch_create("vpl");
    test_round_trip();
    test_corruption();
    test_inconsistent();
    test_invalid_write();
    scratch_remove();
    return tap_done();
}
