/* test_voxel_checksum.c — the checksum of the voxel file (FORMATS.md, "Voxel
 * file", "Checksum"; formats/openvdb/): it covers every byte
 * and the length. Each byte of a small file changed, 1 to 3 bytes appended
 * or cut (zeros too, which the format-1 checksum missed), the OpenVDB file
 * version in bytes 8..20: each is refused before OpenVDB parses anything. A
 * format-1 file gets its own message.
 */
#include "scratch.h"
#include "tap.h"
#include "voxel_grids.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { UUID_OFFSET = 21, UUID_LENGTH = 36, HEADER_BYTES = 57 };

static char path[512]; /* the file the checks write and read */

/* A surface plane at k = 1. */
static int plane_surface(int i, int j, int k)
{
    (void)i, (void)j;
    return k == 1;
}

static void make_grid(gb_voxel_grid *grid)
{
    voxel_grid_make(grid, 9, 5, 4);
    grid->voxel_size = 0.25;
    grid->scene_hash = 0x0123456789abcdefull;
    grid->resolution = 9;
    voxel_grid_fill(grid, plane_surface);
}

/* The result of reading bytes as a voxel file; error gets the message. */
static gb_result read_bytes(const unsigned char *bytes, size_t size, gb_error *error)
{
    scratch_write(path, bytes, size);
    gb_voxel_grid read = {0};
    gb_result result = gb_voxel_grid_read(path, &read, error);
    if (result == GB_OK)
        gb_voxel_grid_free(&read);
    return result;
}

static void mend(unsigned char *bytes, size_t size)
{
    char uuid[UUID_LENGTH + 1];
    if (gb_voxel_file_checksum(bytes, size, uuid))
        memcpy(bytes + UUID_OFFSET, uuid, UUID_LENGTH);
}

/* The checksum of gibake before format 2 (FORMATS.md keeps its definition):
 * bytes 57.. only, no length, UUID version 4. */
static void format1_uuid(const unsigned char *bytes, size_t size, char uuid[UUID_LENGTH + 1])
{
    uint64_t lane[2] = {0x9e3779b97f4a7c15ull, 0xc2b2ae3d27d4eb4full};
    for (size_t i = HEADER_BYTES; i < size; i += 8) {
        uint64_t word = 0;
        for (size_t b = 0; b < 8 && i + b < size; ++b)
            word |= (uint64_t)bytes[i + b] << (8 * b);
        for (int l = 0; l < 2; ++l) {
            lane[l] = (lane[l] ^ word) * (l ? 0xff51afd7ed558ccdull : 0xc4ceb9fe1a85ec53ull);
            lane[l] ^= lane[l] >> 29;
        }
    }
    snprintf(uuid, UUID_LENGTH + 1, "%08x-%04x-%04x-%04x-%012llx", (unsigned)(lane[0] >> 32),
             (unsigned)(lane[0] >> 16 & 0xffff), (unsigned)(0x4000 | (lane[0] & 0x0fff)),
             (unsigned)(0x8000 | (lane[1] >> 48 & 0x3fff)),
             (unsigned long long)(lane[1] & 0xffffffffffffull));
}

int main(void)
{
    scratch_create("voxel-checksum");
    char whole[512], nearest[512];
    scratch_path_into("test.vdb", path, sizeof path);
    scratch_path_into("whole.vdb", whole, sizeof whole);
    scratch_path_into("nearest.vdb", nearest, sizeof nearest);
    gb_voxel_grid grid;
    gb_error error;
    make_grid(&grid);
    CHECK_EQ_INT(gb_voxel_grid_write(whole, &grid, &error), GB_OK, "a small voxel file is written");
    size_t size;
    unsigned char *bytes = scratch_read(whole, &size);
    unsigned char *copy = malloc(size + 16);

    char uuid[UUID_LENGTH + 1];
    CHECK(gb_voxel_file_checksum(bytes, size, uuid) &&
              memcmp(uuid, bytes + UUID_OFFSET, UUID_LENGTH) == 0,
          "bytes 21..56 hold gb_voxel_file_checksum of the file");
    CHECK_EQ_INT(uuid[14], '8', "... a UUID of version 8 (format 2)");
    CHECK_EQ_INT(gb_voxel_file_checksum(bytes, HEADER_BYTES - 1, uuid), 0,
                 "no checksum for fewer than 57 bytes");
    CHECK_EQ_INT(read_bytes(bytes, size, &error), GB_OK, "the file as written reads back");

    /* Every byte outside the UUID, each changed in its lowest bit and in its
     * highest, changes the checksum (in memory: the reader's own function). */
    int changes = 1;
    for (size_t at = 0; at < size; ++at)
        for (int bit = 0; bit < 8 && (at < UUID_OFFSET || at >= HEADER_BYTES); bit += 7) {
            memcpy(copy, bytes, size);
            copy[at] ^= (unsigned char)(1u << bit);
            gb_voxel_file_checksum(copy, size, uuid);
            changes &= memcmp(uuid, bytes + UUID_OFFSET, UUID_LENGTH) != 0;
        }
    char label[128];
    snprintf(label, sizeof label,
             "each of the %zu bytes but the UUID changed (bit 0, bit 7): the checksum changes",
             size - UUID_LENGTH);
    CHECK(changes, label);
    /* On disk: the whole header and the first payload bytes, then every 61st. */
    int refused = 1, header_by_checksum = 1;
    for (size_t at = 0; at < size; at += at < 4 * HEADER_BYTES ? 1 : 61) {
        memcpy(copy, bytes, size);
        copy[at] ^= 1;
        gb_result result = read_bytes(copy, size, &error);
        refused &= result != GB_OK;
        if (at >= 8 && at < UUID_OFFSET)
            header_by_checksum &= result == GB_ERROR_CHECKSUM &&
                                  strstr(error.message, "checksum does not match") != NULL;
    }
    CHECK(refused, "read back: bytes 0..227 and every 61st byte after, each changed, refused");
    CHECK(header_by_checksum,
          "... bytes 8..20 (file version, library version, offsets flag) by the checksum");
    memcpy(copy, bytes, size);
    copy[8] ^= 1;   /* the file version 224 becomes 225 */
    CHECK_EQ_INT(read_bytes(copy, size, &error), GB_ERROR_CHECKSUM,
                 "a flipped file-version byte is refused by the checksum");

    /* the length */
    static const unsigned char tails[2] = {0x00, 0x5a};
    int appended = 1, cut = 1;
    for (int t = 0; t < 2; ++t)
        for (size_t extra = 1; extra <= 3; ++extra) {
            memcpy(copy, bytes, size);
            memset(copy + size, tails[t], extra);
            appended &= read_bytes(copy, size + extra, &error) == GB_ERROR_CHECKSUM;
        }
    for (size_t removed = 1; removed <= 3; ++removed)
        cut &= read_bytes(bytes, size - removed, &error) == GB_ERROR_CHECKSUM;
    CHECK(appended, "1, 2 or 3 bytes appended (zeros or not): refused by the checksum");
    CHECK(cut, "1, 2 or 3 bytes cut: refused by the checksum");

    /* A file that ends in zeros, its checksum mended: cutting one of them
     * leaves the same 8-byte words, which format 1 accepted. */
    memcpy(copy, bytes, size);
    memset(copy + size, 0, 3);
    mend(copy, size + 3);
    unsigned char *shorter = malloc(size + 16);
    memcpy(shorter, copy, size + 2);
    CHECK_EQ_INT(read_bytes(shorter, size + 2, &error), GB_ERROR_CHECKSUM,
                 "a trailing zero cut from a file ending in zeros: refused (the length counts)");
    free(shorter);

    /* format 1 */
    memcpy(copy, bytes, size);
    format1_uuid(copy, size, uuid);
    memcpy(copy + UUID_OFFSET, uuid, UUID_LENGTH);
    CHECK_EQ_INT(read_bytes(copy, size, &error), GB_ERROR_UNSUPPORTED,
                 "a file with the format-1 checksum is refused");
    CHECK(strstr(error.message, "written by an older gibake (voxel file format 1") != NULL,
          "... as written by an older gibake, to make again");

    /* the int32 grid file has the same checksum */
    int32_t *values = malloc((size_t)9 * 5 * 4 * sizeof *values);
    for (int i = 0; i < 9 * 5 * 4; ++i)
        values[i] = i % 3 ? i : -1;
    gb_voxel_grid_write_int32(nearest, &grid, "nearest_node", values, &error);
    size_t int_size;
    unsigned char *int_bytes = scratch_read(nearest, &int_size);
    int_bytes[12] ^= 1;   /* the library major version */
    scratch_write(path, int_bytes, int_size);
    gb_voxel_grid frame;
    int32_t *read_values = NULL;
    CHECK_EQ_INT(gb_voxel_grid_read_int32(path, "nearest_node", &frame, &read_values, &error),
                 GB_ERROR_CHECKSUM, "an int32 grid file with a flipped header byte: refused");
    free(read_values);
    free(int_bytes);
    free(values);

    free(copy);
    free(bytes);
    gb_voxel_grid_free(&grid);
    scratch_remove();
    return tap_done();
}
