/* atlas.c — the lightmap atlas file (formats/atlas.h, formats/FORMATS.md
 * "Atlas"). Every section is an array of fixed layout written and read in
 * place, which needs a little-endian host. */
#include "atlas.h"

#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "array_reserve.h"
#include "atlas_mask.h"
#include "container_kind.h"

#if !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "atlases are read in place: gibake needs a little-endian host"
#endif

_Static_assert(sizeof(gb_atlas_header) == 64, "header is 64 bytes");
_Static_assert(sizeof(gb_atlas_chart) == 32, "chart record is 32 bytes");

enum { ALIGNMENT = 16, SECTION_COUNT = 4 };

/* ---- header and charts ---- */

static gb_result check_header(const gb_atlas_header *h, const char *path, gb_error *error)
{
    if (h->triangle_count < 1 || h->chart_count < 1 || h->chart_count > h->triangle_count)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: %u charts for %u triangles", path,
                       h->chart_count, h->triangle_count);
    if (h->width < 1 || h->width > GB_ATLAS_MAX_SIZE || h->height < 1 ||
        h->height > GB_ATLAS_MAX_SIZE)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: atlas size %u x %u is not in 1..%d", path,
                       h->width, h->height, GB_ATLAS_MAX_SIZE);
    if (!(h->texels_per_unit > 0.0f) || !isfinite(h->texels_per_unit))
        return gb_fail(error, GB_ERROR_FORMAT, "%s: bad texel density %g", path,
                       (double)h->texels_per_unit);
    if (h->padding > h->width / 2 || h->padding > h->height / 2)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: padding %u does not fit a %u x %u atlas",
                       path, h->padding, h->width, h->height);
    for (int i = 0; i < 8; ++i)
        if (h->reserved[i])
            return gb_fail(error, GB_ERROR_FORMAT, "%s: reserved header field is not zero",
                           path);
    return GB_OK;
}

/* The rect of a chart grown by the padding on every side, as x0, y0, x1, y1
 * (x1, y1 excluded); signed, so that a rect too near the origin shows. */
static void grown_rect(const gb_atlas_chart *chart, uint32_t padding, int64_t out[4])
{
    out[0] = (int64_t)chart->rect[0] - padding;
    out[1] = (int64_t)chart->rect[1] - padding;
    out[2] = (int64_t)chart->rect[0] + chart->rect[2] + padding;
    out[3] = (int64_t)chart->rect[1] + chart->rect[3] + padding;
}

static gb_result check_chart(const gb_atlas *atlas, uint32_t i, const char *path,
                             gb_error *error)
{
    const gb_atlas_header *h = &atlas->header;
    const gb_atlas_chart *chart = &atlas->chart_records[i];
    if (chart->triangle_count < 1 || !(chart->area >= 0.0f) || !isfinite(chart->area))
        return gb_fail(error, GB_ERROR_FORMAT, "%s: chart %u: %u triangles of area %g", path,
                       i, chart->triangle_count, (double)chart->area);
    if (!(chart->max_angle_distortion >= 0.0f && chart->max_angle_distortion <= 180.0f) ||
        !(chart->mean_angle_distortion >= 0.0f &&
          chart->mean_angle_distortion <= chart->max_angle_distortion))
        return gb_fail(error, GB_ERROR_FORMAT, "%s: chart %u: bad angle distortion (max %g, "
                       "mean %g)", path, i, (double)chart->max_angle_distortion,
                       (double)chart->mean_angle_distortion);
    int64_t r[4];
    grown_rect(chart, h->padding, r);
    if (r[0] < 0 || r[1] < 0 || r[2] > h->width || r[3] > h->height)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: chart %u: rect %u,%u %ux%u with its "
                       "padding of %u is not inside the %ux%u atlas", path, i, chart->rect[0],
                       chart->rect[1], chart->rect[2], chart->rect[3], h->padding, h->width,
                       h->height);
    return GB_OK;
}

/* ---- triangles ---- */

static gb_result check_corner(const gb_atlas *atlas, uint32_t t, int corner,
                              const gb_atlas_chart *chart, const char *path, gb_error *error)
{
    const gb_atlas_header *h = &atlas->header;
    double u = atlas->uvs[6 * (size_t)t + 2 * corner];
    double v = atlas->uvs[6 * (size_t)t + 2 * corner + 1];
    double x = u * h->width, y = v * h->height;
    if (!(u >= 0.0 && u <= 1.0 && v >= 0.0 && v <= 1.0))
        return gb_fail(error, GB_ERROR_FORMAT, "%s: triangle %u: corner %d's UV (%g, %g) is "
                       "not in [0, 1]", path, t, corner, u, v);
    if (x < chart->rect[0] - GB_ATLAS_RECT_TOLERANCE ||
        x > (double)chart->rect[0] + chart->rect[2] + GB_ATLAS_RECT_TOLERANCE ||
        y < chart->rect[1] - GB_ATLAS_RECT_TOLERANCE ||
        y > (double)chart->rect[1] + chart->rect[3] + GB_ATLAS_RECT_TOLERANCE)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: triangle %u: corner %d at texel (%g, %g) "
                       "is outside its chart's rect", path, t, corner, x, y);
    return GB_OK;
}

/* Twice the signed UV area of triangle t, in texels squared. */
static double twice_texel_area(const gb_atlas *atlas, uint32_t t)
{
    const float *uv = atlas->uvs + 6 * (size_t)t;
    double w = atlas->header.width, h = atlas->header.height;
    double e1u = ((double)uv[2] - uv[0]) * w, e1v = ((double)uv[3] - uv[1]) * h;
    double e2u = ((double)uv[4] - uv[0]) * w, e2v = ((double)uv[5] - uv[1]) * h;
    return e1u * e2v - e1v * e2u;
}

static gb_result check_triangles(const gb_atlas *atlas, uint32_t *counts, const char *path,
                                 gb_error *error)
{
    const gb_atlas_header *h = &atlas->header;
    for (uint32_t t = 0; t < h->triangle_count; ++t) {
        uint32_t c = atlas->charts[t];
        if (c >= h->chart_count)
            return gb_fail(error, GB_ERROR_FORMAT, "%s: triangle %u: chart %u out of range "
                           "(%u charts)", path, t, c, h->chart_count);
        ++counts[c];
        for (int corner = 0; corner < 3; ++corner) {
            gb_result result = check_corner(atlas, t, corner, &atlas->chart_records[c], path,
                                            error);
            if (result != GB_OK)
                return result;
        }
        if (!(twice_texel_area(atlas, t) > 0.0))
            return gb_fail(error, GB_ERROR_FORMAT, "%s: triangle %u: UV area is not positive "
                           "(flipped or degenerate)", path, t);
    }
    return GB_OK;
}

/* ---- charts apart: no texel in two padded masks (atlas_mask.h) ---- */

/* A run of texels of a chart's padded mask, clipped to the atlas. */
typedef struct run {
    uint32_t row, first, last;
} run;

typedef struct apart_check {
    const gb_atlas *atlas;
    const char *path;
    uint32_t *starts, *order;   /* the triangles by chart: order[starts[c] .. starts[c + 1]) */
    uint64_t *taken;            /* a bit a texel, row after row: in a padded mask so far */
    size_t words;               /* per row */
    run *runs;                  /* one chart's padded mask */
    size_t run_count, run_capacity;
    gb_atlas_mask mask;
} apart_check;

static int by_row_then_column(const void *a, const void *b)
{
    const run *p = a, *q = b;
    if (p->row != q->row)
        return (p->row > q->row) - (p->row < q->row);
    return (p->first > q->first) - (p->first < q->first);
}

/* Triangle t's padded mask into a->mask; 0 when out of memory. */
static int mask_of_triangle(apart_check *a, uint32_t t)
{
    const gb_atlas_header *h = &a->atlas->header;
    double corners[6];
    gb_atlas_texel_corners(a->atlas->uvs + 6 * (size_t)t, h->width, h->height, corners);
    return gb_atlas_mask_of(&a->mask, corners, 0.0, h->padding);
}

/* Row k of a->mask clipped to the atlas: 1 with the run, 0 when outside. */
static int clipped_run(const apart_check *a, uint32_t k, run *r)
{
    const gb_atlas_header *h = &a->atlas->header;
    int64_t row = a->mask.first + k;
    int64_t first = a->mask.columns[2 * k], last = a->mask.columns[2 * k + 1];
    first = first < 0 ? 0 : first;
    last = last >= h->width ? (int64_t)h->width - 1 : last;
    if (row < 0 || row >= h->height || first > last)
        return 0;
    *r = (run){(uint32_t)row, (uint32_t)first, (uint32_t)last};
    return 1;
}

/* Chart c's padded mask as runs, sorted; 0 when out of memory. */
static int chart_runs(apart_check *a, uint32_t c)
{
    a->run_count = 0;
    for (uint32_t j = a->starts[c]; j < a->starts[c + 1]; ++j) {
        if (!mask_of_triangle(a, a->order[j]) ||
            !gb_array_reserve(&a->runs, &a->run_capacity, a->run_count + a->mask.count,
                              sizeof *a->runs))
            return 0;
        for (uint32_t k = 0; k < a->mask.count; ++k)
            a->run_count += clipped_run(a, k, &a->runs[a->run_count]);
    }
    qsort(a->runs, a->run_count, sizeof *a->runs, by_row_then_column);
    return 1;
}

/* The first texel of first .. last of a row of a->taken already taken
 * (1, its column in *at) or none (0); takes them all. */
static int take(apart_check *a, uint32_t row, uint32_t first, uint32_t last, uint32_t *at)
{
    uint64_t *words = a->taken + (size_t)row * a->words;
    for (uint32_t w = first / 64; w <= last / 64; ++w) {
        uint32_t lo = w == first / 64 ? first % 64 : 0, hi = w == last / 64 ? last % 64 : 63;
        uint64_t bits = (~UINT64_C(0) >> (63 - hi)) & (~UINT64_C(0) << lo);
        if (words[w] & bits) {
            *at = w * 64 + (uint32_t)__builtin_ctzll(words[w] & bits);
            return 1;
        }
        words[w] |= bits;
    }
    return 0;
}

/* The chart other than c whose padded mask holds texel (i, j) (the
 * message's; found again, only when the check fails). */
static uint32_t other_chart(apart_check *a, uint32_t c, uint32_t i, uint32_t j)
{
    for (uint32_t t = 0; t < a->atlas->header.triangle_count; ++t) {
        run r;
        if (a->atlas->charts[t] == c || !mask_of_triangle(a, t))
            continue;
        for (uint32_t k = 0; k < a->mask.count; ++k)
            if (clipped_run(a, k, &r) && r.row == j && r.first <= i && i <= r.last)
                return a->atlas->charts[t];
    }
    return c;
}

/* Chart c's padded mask taken, each run's texels once (a chart's own
 * triangles' masks overlap); fails on a texel an earlier chart took. */
static gb_result take_chart(apart_check *a, uint32_t c, gb_error *error)
{
    if (!chart_runs(a, c))
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", a->path);
    int64_t row = -1, taken_to = -1;
    for (size_t k = 0; k < a->run_count; ++k) {
        const run *r = &a->runs[k];
        if (r->row != row)
            row = r->row, taken_to = -1;
        uint32_t first = (int64_t)r->first > taken_to ? r->first : (uint32_t)(taken_to + 1), at;
        if (first <= r->last && take(a, r->row, first, r->last, &at)) {
            uint32_t other = other_chart(a, c, at, r->row);
            return gb_fail(error, GB_ERROR_FORMAT, "%s: charts %u and %u: texel (%u, %u) lies "
                           "in both padded masks", a->path, other < c ? other : c,
                           other < c ? c : other, at, r->row);
        }
        taken_to = r->last > taken_to ? r->last : taken_to;
    }
    return GB_OK;
}

/* The triangles by chart (a counting sort), into a->starts and a->order. */
static int sort_by_chart(apart_check *a)
{
    const gb_atlas_header *h = &a->atlas->header;
    a->starts = calloc((size_t)h->chart_count + 1, sizeof *a->starts);
    a->order = malloc((size_t)h->triangle_count * sizeof *a->order);
    if (!a->starts || !a->order)
        return 0;
    for (uint32_t t = 0; t < h->triangle_count; ++t)
        ++a->starts[a->atlas->charts[t] + 1];
    for (uint32_t c = 0; c < h->chart_count; ++c)
        a->starts[c + 1] += a->starts[c];
    for (uint32_t t = 0; t < h->triangle_count; ++t)
        a->order[a->starts[a->atlas->charts[t]]++] = t;
    for (uint32_t c = h->chart_count; c > 0; --c)
        a->starts[c] = a->starts[c - 1];
    a->starts[0] = 0;
    return 1;
}

/* No texel lies in the padded masks of two charts: chart after chart,
 * each texel of its padded mask taken in a bitmap of the atlas (32 MiB at
 * the largest), the first one taken twice named. */
static gb_result check_charts_apart(const gb_atlas *atlas, const char *path, gb_error *error)
{
    const gb_atlas_header *h = &atlas->header;
    apart_check a = {.atlas = atlas, .path = path, .words = (h->width + 63) / 64};
    a.taken = calloc(a.words * h->height, sizeof *a.taken);
    gb_result result = a.taken && sort_by_chart(&a)
                           ? GB_OK
                           : gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    for (uint32_t c = 0; result == GB_OK && c < h->chart_count; ++c)
        result = take_chart(&a, c, error);
    gb_atlas_mask_free(&a.mask);
    free(a.runs);
    free(a.taken);
    free(a.starts);
    free(a.order);
    return result;
}

gb_result gb_atlas_check(const gb_atlas *atlas, const char *path, gb_error *error)
{
    const gb_atlas_header *h = &atlas->header;
    gb_result result = check_header(h, path, error);
    for (uint32_t i = 0; result == GB_OK && i < h->chart_count; ++i)
        result = check_chart(atlas, i, path, error);
    if (result != GB_OK)
        return result;
    uint32_t *counts = calloc(h->chart_count, sizeof *counts);
    if (!counts)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    result = check_triangles(atlas, counts, path, error);
    for (uint32_t i = 0; result == GB_OK && i < h->chart_count; ++i)
        if (counts[i] != atlas->chart_records[i].triangle_count)
            result = gb_fail(error, GB_ERROR_FORMAT, "%s: chart %u has %u triangles, its "
                             "record says %u", path, i, counts[i],
                             atlas->chart_records[i].triangle_count);
    free(counts);
    if (result == GB_OK)
        result = check_charts_apart(atlas, path, error);
    return result;
}

gb_result gb_atlas_check_scene(const gb_atlas *atlas, uint64_t scene_hash,
                               uint32_t triangle_count, const char *path, gb_error *error)
{
    if (atlas->header.scene_hash == scene_hash && atlas->header.triangle_count == triangle_count)
        return GB_OK;
    return gb_fail(error, GB_ERROR_STALE, "%s: made from another scene (hash %016" PRIx64
                   ", %u triangles; the scene's is %016" PRIx64 ", %u triangles)", path,
                   atlas->header.scene_hash, atlas->header.triangle_count, scene_hash,
                   triangle_count);
}

/* ---- writing ---- */

gb_result gb_atlas_write(const char *path, const gb_atlas *atlas, gb_error *error)
{
    gb_result result = gb_atlas_check(atlas, path, error);
    if (result != GB_OK)
        return result;
    const gb_atlas_header *h = &atlas->header;
    const gb_container_array arrays[] = {
        {"header", 1, sizeof *h, h},
        {"uvs", (uint64_t)h->triangle_count * 6, sizeof *atlas->uvs, atlas->uvs},
        {"charts", h->triangle_count, sizeof *atlas->charts, atlas->charts},
        {"chart_records", h->chart_count, sizeof *atlas->chart_records, atlas->chart_records},
    };
    return gb_container_write_arrays(path, "ATLS", GB_ATLAS_VERSION, arrays, SECTION_COUNT,
                                     error);
}

/* ---- reading ---- */

static gb_result view_sections(const gb_container *container, const char *path,
                               gb_atlas *atlas, gb_error *error)
{
    const gb_section *header;
    gb_result result = gb_container_find_array(container, "header", 1, sizeof atlas->header,
                                               ALIGNMENT, path, &header, error);
    if (result != GB_OK)
        return result;
    memcpy(&atlas->header, header->data, sizeof atlas->header);
    const gb_atlas_header *h = &atlas->header;
    gb_container_array arrays[] = {
        {"uvs", (uint64_t)h->triangle_count * 6, sizeof *atlas->uvs, NULL},
        {"charts", h->triangle_count, sizeof *atlas->charts, NULL},
        {"chart_records", h->chart_count, sizeof *atlas->chart_records, NULL},
    };
    result = gb_container_find_arrays(container, arrays, 3, ALIGNMENT, path, error);
    atlas->uvs = arrays[0].data;
    atlas->charts = arrays[1].data;
    atlas->chart_records = arrays[2].data;
    return result;
}

/* Fills the atlas from a checked ATLS container, which it then keeps: its
 * arrays are views into it (container_kind.h). */
static gb_result adopt_container(const gb_container *container, const char *path, void *object,
                                 gb_error *error)
{
    gb_atlas *atlas = object;
    if (container->version < GB_ATLAS_VERSION)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: format version %u (charts apart by "
                       "their rects) is no longer read; make the atlas again with atlas "
                       "(version %d: charts apart by their padded masks)", path,
                       (unsigned)container->version, GB_ATLAS_VERSION);
    if (container->section_count != SECTION_COUNT)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: %u sections, expected %d", path,
                       (unsigned)container->section_count, SECTION_COUNT);
    gb_result result = view_sections(container, path, atlas, error);
    if (result == GB_OK)
        result = gb_atlas_check(atlas, path, error);
    if (result == GB_OK)
        atlas->container = *container;
    return result;
}

static const gb_container_kind atlas_kind = {"ATLS", GB_ATLAS_VERSION, sizeof(gb_atlas),
                                             adopt_container, 1};

gb_result gb_atlas_read(const char *path, gb_atlas *atlas, gb_error *error)
{
    return gb_container_kind_read(path, &atlas_kind, atlas, error);
}

gb_result gb_atlas_parse(const void *bytes, size_t size, const char *path, gb_atlas *atlas,
                         gb_error *error)
{
    return gb_container_kind_parse(bytes, size, path, &atlas_kind, atlas, error);
}

void gb_atlas_free(gb_atlas *atlas)
{
    free(atlas->storage);
    if (atlas->container.sections || atlas->container.mapping)
        gb_container_close(&atlas->container);
    *atlas = (gb_atlas){0};
}
