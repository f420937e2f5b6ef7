/* packing.c — orient, scale and skyline-pack the charts (packing.h). */
#include "packing.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "atlas.h"
#include "min_area_rect.h"

/* ---- orientation ---- */

static void rotate(gb_chart *chart, double c, double s)
{
    for (size_t k = 0; k < 3 * (size_t)chart->triangle_count; ++k) {
        double x = chart->uvs[2 * k], y = chart->uvs[2 * k + 1];
        chart->uvs[2 * k] = c * x + s * y;
        chart->uvs[2 * k + 1] = -s * x + c * y;
    }
}

/* The chart's UV box: minimum u, v and extent u, v into box. */
static void box_of(const gb_chart *chart, double box[4])
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (size_t k = 0; k < 3 * (size_t)chart->triangle_count; ++k)
        for (int d = 0; d < 2; ++d) {
            lo[d] = fmin(lo[d], chart->uvs[2 * k + d]);
            hi[d] = fmax(hi[d], chart->uvs[2 * k + d]);
        }
    box[0] = lo[0];
    box[1] = lo[1];
    box[2] = hi[0] - lo[0];
    box[3] = hi[1] - lo[1];
}

gb_result gb_packing_orient(gb_chart_list *list, gb_error *error)
{
    size_t largest = 0;
    for (uint32_t i = 0; i < list->count; ++i)
        if (list->charts[i].triangle_count > largest)
            largest = list->charts[i].triangle_count;
    double *points = malloc(2 * (3 * largest) * sizeof *points);
    double *scratch = malloc(2 * (3 * largest + 1) * sizeof *scratch);
    if (!points || !scratch) {
        free(points);
        free(scratch);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (packing)");
    }
    for (uint32_t i = 0; i < list->count; ++i) {
        gb_chart *chart = &list->charts[i];
        size_t n = 3 * (size_t)chart->triangle_count;
        memcpy(points, chart->uvs, 2 * n * sizeof *points);
        double c, s, box[4];
        gb_min_area_rect(points, n, scratch, &c, &s);
        rotate(chart, c, s);
        box_of(chart, box);
        if (box[3] > box[2])
            rotate(chart, 0.0, 1.0);  /* a quarter turn: (x, y) -> (y, -x) */
    }
    free(points);
    free(scratch);
    return GB_OK;
}

/* ---- sizes ---- */

/* The rect's width and height (padding excluded) at density: the box's
 * extent in texels rounded up, at least 1. */
static void size_of(const double box[4], double density, uint64_t size[2])
{
    for (int d = 0; d < 2; ++d) {
        double texels = fmax(1.0, ceil(box[2 + d] * density));
        size[d] = texels < 4.0 * GB_ATLAS_MAX_SIZE ? (uint64_t)texels
                                                    : 4 * (uint64_t)GB_ATLAS_MAX_SIZE;
    }
}

/* Texels per world unit of a chart of this box at density: the largest
 * one scale, at least density, at which the box still fits its rect
 * (packing.h). */
static double scale_of(const double box[4], double density)
{
    uint64_t size[2];
    size_of(box, density, size);
    double scale = INFINITY;
    for (int d = 0; d < 2; ++d)
        if (box[2 + d] > 0.0)
            scale = fmin(scale, (double)size[d] / box[2 + d]);
    return isfinite(scale) && scale > density ? scale : density;
}

/* ---- skyline ---- */

typedef struct segment {
    uint64_t x, y, width;
} segment;

typedef struct skyline {
    segment *segments;
    uint32_t count;
    uint64_t width, height_limit, top;
} skyline;

/* Where a w x h rect goes: the lowest place, then the leftmost; 0 if none. */
static int find_place(const skyline *sky, uint64_t w, uint64_t h, uint32_t *at, uint64_t *y_at)
{
    int found = 0;
    uint64_t best_y = 0, best_x = 0;
    for (uint32_t i = 0; i < sky->count; ++i) {
        uint64_t x = sky->segments[i].x, y = 0, covered = 0;
        if (x + w > sky->width)
            break;
        for (uint32_t j = i; j < sky->count && covered < w; ++j) {
            if (sky->segments[j].y > y)
                y = sky->segments[j].y;
            covered = sky->segments[j].x + sky->segments[j].width - x;
        }
        if (y + h > sky->height_limit)
            continue;
        if (!found || y < best_y || (y == best_y && x < best_x)) {
            found = 1;
            best_y = y;
            best_x = x;
            *at = i;
        }
    }
    *y_at = best_y;
    return found;
}

/* The rect [x, x + w) raised to top: the segments under it replaced. */
static int raise_skyline(skyline *sky, uint32_t at, uint64_t w, uint64_t top)
{
    uint64_t x = sky->segments[at].x, end = x + w;
    uint32_t j = at;
    while (j < sky->count && sky->segments[j].x + sky->segments[j].width <= end)
        ++j;
    /* segments at .. j-1 lie under the rect; j, if any, sticks out past end */
    if (j < sky->count && sky->segments[j].x < end) {
        sky->segments[j].width -= end - sky->segments[j].x;
        sky->segments[j].x = end;
    }
    uint32_t removed = j - at;
    if (removed == 0) {
        segment *grown = realloc(sky->segments, (sky->count + 1) * sizeof *grown);
        if (!grown)
            return 0;
        sky->segments = grown;
        memmove(sky->segments + at + 1, sky->segments + at,
                (sky->count - at) * sizeof *sky->segments);
        ++sky->count;
    } else if (removed > 1) {
        memmove(sky->segments + at + 1, sky->segments + j,
                (sky->count - j) * sizeof *sky->segments);
        sky->count -= removed - 1;
    }
    sky->segments[at] = (segment){x, top, w};
    if (top > sky->top)
        sky->top = top;
    return 1;
}

typedef struct item {
    uint64_t w, h;              /* padding included */
    uint32_t chart;
} item;

static int taller_first(const void *a, const void *b)
{
    const item *p = a, *q = b;
    if (p->h != q->h)
        return p->h > q->h ? -1 : 1;
    if (p->w != q->w)
        return p->w > q->w ? -1 : 1;
    return (p->chart > q->chart) - (p->chart < q->chart);
}

/* The items sorted at density, padding included; their total area. */
static double make_items(const gb_packing *packing, uint32_t count, double density,
                         uint32_t padding, item *items)
{
    double area = 0.0;
    for (uint32_t i = 0; i < count; ++i) {
        uint64_t size[2];
        size_of(packing->boxes + 4 * (size_t)i, density, size);
        items[i] = (item){size[0] + 2 * padding, size[1] + 2 * padding, i};
        area += (double)items[i].w * (double)items[i].h;
    }
    qsort(items, count, sizeof *items, taller_first);
    return area;
}

/* Packs the items into width x height_limit; rects filled when it fits.
 * Returns 1 fits, 0 does not, -1 out of memory. */
static int skyline_pack(const item *items, uint32_t count, uint64_t width, uint64_t height_limit,
                        uint32_t padding, uint32_t *rects, uint64_t *top)
{
    skyline sky = {malloc(sizeof(segment)), 1, width, height_limit, 0};
    if (!sky.segments)
        return -1;
    sky.segments[0] = (segment){0, 0, width};
    int fits = 1;
    for (uint32_t i = 0; i < count && fits == 1; ++i) {
        uint32_t at;
        uint64_t y;
        if (items[i].w > width || !find_place(&sky, items[i].w, items[i].h, &at, &y)) {
            fits = 0;
            break;
        }
        uint32_t *rect = rects + 4 * (size_t)items[i].chart;
        rect[0] = (uint32_t)(sky.segments[at].x + padding);
        rect[1] = (uint32_t)(y + padding);
        rect[2] = (uint32_t)(items[i].w - 2 * padding);
        rect[3] = (uint32_t)(items[i].h - 2 * padding);
        if (!raise_skyline(&sky, at, items[i].w, y + items[i].h))
            fits = -1;
    }
    *top = sky.top;
    free(sky.segments);
    return fits;
}

/* ---- density ---- */

static gb_result fixed_density(const gb_chart_list *list, const gb_packing_options *o,
                               item *items, gb_packing *packing, gb_error *error)
{
    double area = make_items(packing, list->count, o->texels_per_unit, o->padding, items);
    uint64_t width = (uint64_t)ceil(sqrt(area / 0.9)), top = 0;
    for (uint32_t i = 0; i < list->count; ++i)
        if (items[i].w > width)
            width = items[i].w;
    if (width > GB_ATLAS_MAX_SIZE)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%g texels per unit needs an atlas "
                       "wider than %d texels", o->texels_per_unit, GB_ATLAS_MAX_SIZE);
    int fits = skyline_pack(items, list->count, width, GB_ATLAS_MAX_SIZE, o->padding,
                            packing->rects, &top);
    if (fits < 0)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (packing)");
    if (!fits)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%g texels per unit needs an atlas "
                       "taller than %d texels", o->texels_per_unit, GB_ATLAS_MAX_SIZE);
    packing->width = (uint32_t)width;
    packing->height = (uint32_t)(top > 2 * o->padding ? top : 2 * o->padding + 1);
    packing->texels_per_unit = o->texels_per_unit;
    return GB_OK;
}

/* Whether the charts fit size x size at density; -1 out of memory. */
static int fits_at(const gb_chart_list *list, const gb_packing_options *o, double density,
                   item *items, gb_packing *packing)
{
    uint64_t top;
    make_items(packing, list->count, density, o->padding, items);
    return skyline_pack(items, list->count, o->size, o->size, o->padding, packing->rects, &top);
}

static gb_result chosen_density(const gb_chart_list *list, const gb_packing_options *o,
                                item *items, gb_packing *packing, gb_error *error)
{
    double area = 0.0;
    for (uint32_t i = 0; i < list->count; ++i)
        area += list->charts[i].area;
    double hi = (double)o->size / sqrt(area > 0.0 ? area : 1e-30), lo = hi * 1e-6;
    int fits = fits_at(list, o, lo, items, packing);
    if (fits == 0)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%u charts with a padding of %u do "
                       "not fit a %u x %u atlas at any density", list->count, o->padding,
                       o->size, o->size);
    for (int step = 0; step < 40 && fits >= 0; ++step) {
        double middle = sqrt(lo * hi);
        fits = fits_at(list, o, middle, items, packing);
        if (fits > 0)
            lo = middle;
        else if (fits == 0)
            hi = middle;
    }
    if (fits >= 0)
        fits = fits_at(list, o, lo, items, packing);
    if (fits < 0)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (packing)");
    packing->width = packing->height = o->size;
    packing->texels_per_unit = lo;
    return GB_OK;
}

gb_result gb_pack(const gb_chart_list *list, const gb_packing_options *options,
                  gb_packing *packing, gb_error *error)
{
    memset(packing, 0, sizeof *packing);
    packing->rects = malloc(4 * (size_t)list->count * sizeof *packing->rects);
    packing->boxes = malloc(4 * (size_t)list->count * sizeof *packing->boxes);
    item *items = malloc((size_t)list->count * sizeof *items);
    gb_result result = GB_OK;
    if (!packing->rects || !packing->boxes || !items)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (packing)");
    for (uint32_t i = 0; result == GB_OK && i < list->count; ++i)
        box_of(&list->charts[i], packing->boxes + 4 * (size_t)i);
    if (result == GB_OK)
        result = options->texels_per_unit > 0.0
                     ? fixed_density(list, options, items, packing, error)
                     : chosen_density(list, options, items, packing, error);
    free(items);
    if (result != GB_OK)
        gb_packing_free(packing);
    return result;
}

void gb_packing_free(gb_packing *packing)
{
    free(packing->rects);
    free(packing->boxes);
    memset(packing, 0, sizeof *packing);
}

void gb_packing_texels(const gb_chart_list *list, const gb_packing *packing, uint32_t i,
                       double *texels)
{
    const gb_chart *chart = &list->charts[i];
    const double *box = packing->boxes + 4 * (size_t)i;
    const uint32_t *rect = packing->rects + 4 * (size_t)i;
    double scale = scale_of(box, packing->texels_per_unit);
    for (size_t k = 0; k < 3 * (size_t)chart->triangle_count; ++k)
        for (int d = 0; d < 2; ++d)
            texels[2 * k + d] = rect[d] + (chart->uvs[2 * k + d] - box[d]) * scale;
}
