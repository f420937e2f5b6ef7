/* test_atlas_file.c — the atlas file (formats/atlas.c): a hand-made atlas
 * of two charts written and read back byte for byte, and each rule of
 * gb_atlas_check (formats/FORMATS.md, "Atlas") broken once on a copy of
 * it: the reader must refuse it with the message naming what is wrong.
 * Charts are apart by their padded masks (formats/atlas_mask.h), not by
 * their rects: a chart inside another's rect passes when the padded masks
 * share no texel and is refused when they share one. A file of format
 * version 1 is refused, saying to make it again.
 */
#include <stdlib.h>
#include <string.h>
#include <zlib.h>

#include "atlas.h"
#include "scratch.h"
#include "tap.h"

enum { TRIANGLES = 3, CHARTS = 2, SIZE = 32, PADDING = 2 };

/* Chart 0: a 8x8 texel square at (2, 2) holding two triangles (a quad cut
 * along its diagonal); chart 1: one triangle in a 6x4 rect at (16, 2). UVs
 * are texel coordinates over SIZE, counterclockwise in (u, v). */
typedef struct hand_atlas {
    gb_atlas atlas;
    float uvs[TRIANGLES * 6];
    uint32_t charts[TRIANGLES];
    gb_atlas_chart records[CHARTS];
} hand_atlas;

static void make_hand_atlas(hand_atlas *a)
{
    static const float texels[TRIANGLES * 6] = {
        2, 2, 10, 2, 10, 10,
        2, 2, 10, 10, 2, 10,
        16, 2, 22, 2, 16, 6,
    };
    memset(a, 0, sizeof *a);
    for (int i = 0; i < TRIANGLES * 6; ++i)
        a->uvs[i] = texels[i] / SIZE;
    a->charts[0] = a->charts[1] = 0;
    a->charts[2] = 1;
    a->records[0] = (gb_atlas_chart){2, 2.0f, 0.0f, 0.0f, {2, 2, 8, 8}};
    a->records[1] = (gb_atlas_chart){1, 0.5f, 1.0f, 1.0f, {16, 2, 6, 4}};
    a->atlas.header = (gb_atlas_header){.scene_hash = 0x1234, .triangle_count = TRIANGLES,
                                        .chart_count = CHARTS, .width = SIZE, .height = SIZE,
                                        .texels_per_unit = 8.0f, .padding = PADDING};
    a->atlas.uvs = a->uvs;
    a->atlas.charts = a->charts;
    a->atlas.chart_records = a->records;
}

/* The message of the check of a, or "" when it passes. */
static const char *check_message(const hand_atlas *a)
{
    static gb_error error;
    memset(&error, 0, sizeof error);
    return gb_atlas_check(&a->atlas, "x.atlas", &error) == GB_OK ? "" : error.message;
}

static void check_refused(const hand_atlas *a, const char *expected, const char *what)
{
    const char *message = check_message(a);
    if (!CHECK(strstr(message, expected) != NULL, what))
        printf("#   message \"%s\", expected to contain \"%s\"\n", message, expected);
}

static void test_round_trip(void)
{
    hand_atlas a;
    make_hand_atlas(&a);
    CHECK(strcmp(check_message(&a), "") == 0, "the hand-made atlas passes the check");
    const char *path = scratch_path("hand.atlas");
    gb_error error = {0};
    CHECK(gb_atlas_write(path, &a.atlas, &error) == GB_OK, "written");
    gb_atlas back = {0};
    CHECK(gb_atlas_read(path, &back, &error) == GB_OK, "read back");
    CHECK(memcmp(&back.header, &a.atlas.header, sizeof back.header) == 0 &&
              memcmp(back.uvs, a.uvs, sizeof a.uvs) == 0 &&
              memcmp(back.charts, a.charts, sizeof a.charts) == 0 &&
              memcmp(back.chart_records, a.records, sizeof a.records) == 0,
          "every section reads back byte for byte");
    CHECK(gb_atlas_check_scene(&back, 0x1234, TRIANGLES, path, &error) == GB_OK,
          "it belongs to its scene");
    CHECK(gb_atlas_check_scene(&back, 0x1235, TRIANGLES, path, &error) == GB_ERROR_STALE &&
              gb_atlas_check_scene(&back, 0x1234, TRIANGLES + 1, path, &error) ==
                  GB_ERROR_STALE,
          "another scene hash or triangle count: stale");
    gb_atlas_free(&back);
}

static void test_each_rule(void)
{
    hand_atlas a;
    make_hand_atlas(&a);
    a.uvs[0] = 1.5f;
    check_refused(&a, "not in [0, 1]", "a UV outside [0, 1]");

    make_hand_atlas(&a);
    a.uvs[12] = 12.0f / SIZE; /* chart 1's rect starts at 16 */
    check_refused(&a, "outside its chart's rect", "a UV outside its chart's rect");

    make_hand_atlas(&a);
    float u = a.uvs[14], v = a.uvs[15];
    a.uvs[14] = a.uvs[16], a.uvs[15] = a.uvs[17], a.uvs[16] = u, a.uvs[17] = v;
    check_refused(&a, "not positive", "a clockwise (flipped) triangle");

    make_hand_atlas(&a);
    a.uvs[16] = a.uvs[12], a.uvs[17] = a.uvs[13];
    check_refused(&a, "not positive", "a degenerate triangle");

    make_hand_atlas(&a);
    a.charts[2] = 2;
    check_refused(&a, "out of range", "a chart index out of range");

    make_hand_atlas(&a);
    a.records[0].triangle_count = 1, a.records[1].triangle_count = 2;
    check_refused(&a, "its record says", "a chart record's triangle count");

    /* chart 0 covers texel columns 2..9, its padded mask 0..11 */
    make_hand_atlas(&a);
    a.records[1].rect[0] = 13; /* chart 1's padded mask from 11: column 11 shared */
    a.uvs[12] = a.uvs[16] = 13.0f / SIZE;
    a.uvs[14] = 19.0f / SIZE;
    check_refused(&a, "charts 0 and 1: texel (11, 0) lies in both padded masks",
                  "two charts whose padded masks share a column (their rects apart)");

    make_hand_atlas(&a);
    a.records[1].rect[0] = 14; /* from 12: the padded masks touch, share nothing */
    a.uvs[12] = a.uvs[16] = 14.0f / SIZE;
    a.uvs[14] = 20.0f / SIZE;
    CHECK(strcmp(check_message(&a), "") == 0, "two charts whose padded masks touch pass");

    make_hand_atlas(&a);
    a.records[0].rect[0] = 1, a.records[0].rect[2] = 9;
    check_refused(&a, "is not inside", "a chart whose padding leaves the atlas");

    make_hand_atlas(&a);
    a.atlas.header.reserved[3] = 1;
    check_refused(&a, "reserved", "a reserved field not zero");

    make_hand_atlas(&a);
    a.records[1].mean_angle_distortion = 2.0f;
    check_refused(&a, "angle distortion", "a mean distortion above the max");
}

/* Chart 0: the lower left half of the square (2, 2)..(18, 18), below its
 * diagonal, in the rect of the whole square; chart 1: a triangle in the
 * square's top right corner, its rect inside chart 0's. Texels chart 0
 * touches have i - j <= 0, so its padded mask i - j <= 4. */
static void make_nested(hand_atlas *a, float corner)
{
    make_hand_atlas(a);
    const float texels[12] = {2, 2, 18, 18, 2, 18, corner, 2, 18, 2, 18, 20 - corner};
    for (int i = 0; i < 12; ++i)
        a->uvs[i] = texels[i] / SIZE;
    a->charts[0] = 0, a->charts[1] = 1;
    a->atlas.header.triangle_count = 2;
    a->records[0] = (gb_atlas_chart){1, 1.0f, 0.0f, 0.0f, {2, 2, 16, 16}};
    a->records[1] = (gb_atlas_chart){1, 0.5f, 0.0f, 0.0f,
                                     {(uint32_t)corner, 2, 18 - (uint32_t)corner,
                                      18 - (uint32_t)corner}};
}

static void test_masks_not_rects(void)
{
    hand_atlas a;
    make_nested(&a, 14); /* chart 1: x - y >= 12, its texels i - j >= 10, padded >= 6 */
    CHECK(strcmp(check_message(&a), "") == 0,
          "a chart inside another's rect, their padded masks apart: passes");
    make_nested(&a, 10); /* chart 1: x - y >= 8, its texels i - j >= 8, padded >= 4 */
    check_refused(&a, "lies in both padded masks",
                  "a chart inside another's rect, their padded masks sharing texels: refused");
}

/* The atlas written, then its container's format version set to 1 (the
 * header's CRC made again): refused, saying why. */
static void test_version_one(void)
{
    hand_atlas a;
    make_hand_atlas(&a);
    const char *path = scratch_path("old.atlas");
    gb_error error = {0};
    if (!CHECK(gb_atlas_write(path, &a.atlas, &error) == GB_OK, "version 1: written"))
        return;
    FILE *file = fopen(path, "r+b");
    unsigned char head[32 + 48 * 4];
    size_t got = file ? fread(head, 1, sizeof head, file) : 0;
    uint32_t version = 1, count = head[24] | head[25] << 8, crc;
    memcpy(head + 12, &version, 4);
    crc = (uint32_t)crc32(crc32(0, head, 28), head + 32, 48 * count);
    memcpy(head + 28, &crc, 4);
    int patched = got == sizeof head && count == 4 && fseek(file, 0, SEEK_SET) == 0 &&
                  fwrite(head, 1, 32, file) == 32;
    if (file)
        fclose(file);
    if (!CHECK(patched, "version 1: the version patched"))
        return;
    gb_atlas back = {0};
    CHECK(gb_atlas_read(path, &back, &error) == GB_ERROR_UNSUPPORTED &&
              strstr(error.message, "format version 1") &&
              strstr(error.message, "make the atlas again"),
          "a version 1 atlas is refused, saying to make it again");
    printf("# %s\n", error.message);
}

int main(void)
{
    scratch_create("atlas-file");
    test_round_trip();
    test_each_rule();
    test_masks_not_rects();
    test_version_one();
    scratch_remove();
    return tap_done();
}
