/* fuzz_voxel_grid.c — libFuzzer target for the `.vdb` readers of the
 * OpenVDB adapter (formats/openvdb/): voxelize's voxel file
 * (gb_voxel_grid_read) and int32 grids such as thin's "nearest_node"
 * (gb_voxel_grid_read_int32). Any input gives either a grid that holds what
 * voxel_grid.h promises, or an error "path: ...", never a crash, a leak or a
 * read out of bounds (run under ASan/UBSan by `make fuzz`).
 *
 * The readers take a path: the input is written to a memfd and read through
 * /proc/self/fd/N. Both readers run on every input (so a voxel file is also
 * read as an int32 grid and a nearest-node grid as a voxel file). The
 * readers verify the content UUID (FORMATS.md, "Voxel file", "Checksum",
 * format 2) before OpenVDB parses anything, so almost every mutation would
 * stop there: each input is read as it is, then again with its UUID
 * recomputed, which lets the mutations reach OpenVDB and the adapter's
 * checks. Seeds: tests/fuzz/corpus/fuzz_voxel_grid, written by voxelize
 * and thin.
 */
#include "voxel_grid.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

static volatile double sink;

enum { UUID_OFFSET = 21, UUID_LENGTH = 36 };

static void mix(uint64_t lane[2], uint64_t word)
{
    static const uint64_t multiplier[2] = {0xc4ceb9fe1a85ec53ull, 0xff51afd7ed558ccdull};
    for (int l = 0; l < 2; ++l) {
        lane[l] = (lane[l] ^ word) * multiplier[l];
        lane[l] ^= lane[l] >> 29;
    }
}

/* The content UUID of FORMATS.md ("Voxel file", "Checksum", format 2):
 * 8-byte little-endian words of bytes 0..20 then 57.. (the last one
 * zero-padded), then the file's length; UUID version 8. */
static void write_content_uuid(unsigned char *bytes, size_t size)
{
    if (size < UUID_OFFSET + UUID_LENGTH)
        return;
    uint64_t lane[2] = {0x9e3779b97f4a7c15ull, 0xc2b2ae3d27d4eb4full}, word = 0;
    int count = 0;
    for (size_t i = 0; i < size; ++i) {
        if (i == UUID_OFFSET && (i += UUID_LENGTH) == size)
            break;
        word |= (uint64_t)bytes[i] << (8 * count);
        if (++count == 8) {
            mix(lane, word);
            word = 0;
            count = 0;
        }
    }
    if (count)
        mix(lane, word);
    mix(lane, size);
    char uuid[UUID_LENGTH + 1];
    snprintf(uuid, sizeof uuid, "%08x-%04x-%04x-%04x-%012llx", (unsigned)(lane[0] >> 32),
             (unsigned)(lane[0] >> 16 & 0xffff), (unsigned)(0x8000 | (lane[0] & 0x0fff)),
             (unsigned)(0x8000 | (lane[1] >> 48 & 0x3fff)),
             (unsigned long long)(lane[1] & 0xffffffffffffull));
    memcpy(bytes + UUID_OFFSET, uuid, UUID_LENGTH);
}

static int frame_is_sane(const gb_voxel_grid *g)
{
    for (int a = 0; a < 3; ++a)
        if (g->size[a] <= 0 || !isfinite(g->world_origin[a]))
            return 0;
    return isfinite(g->voxel_size) && g->voxel_size > 0;
}

static size_t voxel_count(const gb_voxel_grid *g)
{
    return (size_t)g->size[0] * (size_t)g->size[1] * (size_t)g->size[2];
}

static void check_voxel_grid(const gb_voxel_grid *g)
{
    if (!frame_is_sane(g) || !g->surface)
        __builtin_trap();
    double sum = 0;
    for (size_t i = 0, n = voxel_count(g); i < n; ++i) {
        if (g->surface[i] > 1)
            __builtin_trap(); /* the reader promises 0/1 */
        sum += g->surface[i];
    }
    sink += sum;
}

static void check_int32_grid(const gb_voxel_grid *g, const int32_t *values)
{
    if (!frame_is_sane(g) || g->surface || !values)
        __builtin_trap();
    for (size_t i = 0, n = voxel_count(g); i < n; ++i)
        if (values[i] < -1)
            __builtin_trap(); /* inactive voxels are -1, active ones >= 0 */
}

static void check_failure(const char *path, const gb_error *error)
{
    size_t n = strlen(path);
    if (strncmp(error->message, path, n) != 0 || strncmp(error->message + n, ": ", 2) != 0)
        __builtin_trap(); /* every failure has a "path: ..." message */
}

static void read_both(int fd, const unsigned char *bytes, size_t size, const char *path)
{
    if (ftruncate(fd, 0) != 0 || pwrite(fd, bytes, size, 0) != (ssize_t)size)
        abort();
    gb_voxel_grid grid = {0};
    gb_error error;
    if (gb_voxel_grid_read(path, &grid, &error) == GB_OK) {
        check_voxel_grid(&grid);
        gb_voxel_grid_free(&grid);
    } else {
        check_failure(path, &error);
    }
    gb_voxel_grid frame = {0};
    int32_t *values = NULL;
    if (gb_voxel_grid_read_int32(path, "nearest_node", &frame, &values, &error) == GB_OK) {
        check_int32_grid(&frame, values);
        free(values);
    } else {
        check_failure(path, &error);
        if (values)
            __builtin_trap();
    }
}

/* A library leak the adapter cannot prevent (docs/figures.md, "fuzzing"): OpenVDB's
 * RootNode::readTopology allocates a child node, reads its topology, and
 * only then links it into the root; when the read throws (a corrupt
 * compressed chunk of tile values), that child and its subtree leak. Only a
 * file with a valid content UUID gets there, so only a crafted one. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void)
{
    return "leak:openvdb::*RootNode*::readTopology\n";
}

/* Whether the input declares a frame (metadata grid_size, vec3i) of more
 * than 2^24 voxels. The readers refuse only frames beyond the machine's
 * memory (a small file may rightly describe a big, mostly empty grid), and
 * fill a dense array of 5 bytes a voxel: beyond libFuzzer's memory limit,
 * such inputs are skipped. */
static int declares_big_frame(const uint8_t *data, size_t size)
{
    static const char key[] = "\x09\0\0\0grid_size\x05\0\0\0vec3i\x0c\0\0\0";
    size_t n = sizeof key - 1;
    for (const uint8_t *at = data; (at = memmem(at, size - (size_t)(at - data), key, n));
         at += n) {
        if ((size_t)(data + size - at) < n + 12)
            break;
        double voxels = 1;
        for (int k = 0; k < 3; ++k) {
            const uint8_t *p = at + n + 4 * k;
            voxels *= (double)(int32_t)((uint32_t)p[0] | (uint32_t)p[1] << 8 |
                                        (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24);
        }
        if (voxels > (double)(1 << 24))
            return 1;
    }
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int fd = -1;
    if (declares_big_frame(data, size))
        return 0;
    static char path[64];
    if (fd < 0) {
        fd = memfd_create("fuzz_voxel_grid", 0);
        if (fd < 0)
            abort();
        snprintf(path, sizeof path, "/proc/self/fd/%d", fd);
    }
    unsigned char *bytes = malloc(size + 1);
    if (!bytes)
        return 0;
    memcpy(bytes, data, size);
    read_both(fd, bytes, size, path);
    write_content_uuid(bytes, size);
    if (memcmp(bytes, data, size) != 0)   /* the UUID was not the content's */
        read_both(fd, bytes, size, path);
    free(bytes);
    return 0;
}
