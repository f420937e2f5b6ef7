/* atlas.c — the lightmap atlas file (formats/atlas.h, formats/FORMATS.md
 * "Atlas"). Every section is an array of fixed layout written and read in
 * place, which needs a little-endian host. */
#include "atlas.h"

#include <inttypes.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

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

/* ---- charts apart ---- */

static int by_left_edge(const void *a, const void *b, void *charts)
{
    const gb_atlas_chart *records = charts;
    uint32_t xa = records[*(const uint32_t *)a].rect[0];
    uint32_t xb = records[*(const uint32_t *)b].rect[0];
    return (xa > xb) - (xa < xb);
}

/* No two rects grown by the padding overlap: a sweep over the charts by left
 * edge, each compared with those that start before it ends. */
static gb_result check_charts_apart(const gb_atlas *atlas, const char *path, gb_error *error)
{
    const gb_atlas_header *h = &atlas->header;
    uint32_t *order = malloc(h->chart_count * sizeof *order);
    if (!order)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    for (uint32_t i = 0; i < h->chart_count; ++i)
        order[i] = i;
    qsort_r(order, h->chart_count, sizeof *order, by_left_edge,
            (void *)atlas->chart_records);
    gb_result result = GB_OK;
    for (uint32_t i = 0; i < h->chart_count && result == GB_OK; ++i) {
        int64_t a[4], b[4];
        grown_rect(&atlas->chart_records[order[i]], h->padding, a);
        for (uint32_t j = i + 1; j < h->chart_count && result == GB_OK; ++j) {
            grown_rect(&atlas->chart_records[order[j]], h->padding, b);
            if (b[0] >= a[2])
                break;
            if (b[1] < a[3] && a[1] < b[3])
                result = gb_fail(error, GB_ERROR_FORMAT, "%s: charts %u and %u overlap "
                                 "(their padding included)", path, order[i], order[j]);
        }
    }
    free(order);
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
