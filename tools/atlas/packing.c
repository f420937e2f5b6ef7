/* packing.c — orient, scale and pack the charts: by padded rect on a
 * skyline, then by shape (packing.h). */
#include "packing.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "atlas.h"
#include "chart_mask.h"
#include "min_area_rect.h"
#include "occupancy.h"

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
 * extent in texels plus four times the margin, rounded up, at least 1. */
static void size_of(const double box[4], double density, double margin, uint64_t size[2])
{
    for (int d = 0; d < 2; ++d) {
        double texels = fmax(1.0, ceil(box[2 + d] * density + 4.0 * margin));
        size[d] = texels < 4.0 * GB_ATLAS_MAX_SIZE ? (uint64_t)texels
                                                    : 4 * (uint64_t)GB_ATLAS_MAX_SIZE;
    }
}

/* Texels per world unit of a chart of this box at density: the largest
 * one scale, at least density, at which the box still fits its rect less
 * twice the margin on every side (packing.h). */
static double scale_of(const double box[4], double density, double margin)
{
    uint64_t size[2];
    size_of(box, density, margin, size);
    double scale = INFINITY;
    for (int d = 0; d < 2; ++d)
        if (box[2 + d] > 0.0)
            scale = fmin(scale, ((double)size[d] - 4.0 * margin) / box[2 + d]);
    return isfinite(scale) && scale > density ? scale : density;
}

/* Chart i's corners in its rect's texel coordinates (the rect's top left
 * corner at 0, 0), its box's corner at twice the margin from it, turned a
 * quarter when turned: 6 per triangle into texels; its rect's sides into
 * size. */
static void local_texels(const gb_chart *chart, const double box[4], double density,
                         double margin, int turned, double *texels, uint64_t size[2])
{
    uint64_t s[2];
    size_of(box, density, margin, s);
    double scale = scale_of(box, density, margin), gap = 2.0 * margin;
    for (size_t k = 0; k < 3 * (size_t)chart->triangle_count; ++k) {
        double x = (chart->uvs[2 * k] - box[0]) * scale + gap;
        double y = (chart->uvs[2 * k + 1] - box[1]) * scale + gap;
        texels[2 * k] = turned ? (double)s[1] - y : x;
        texels[2 * k + 1] = turned ? x : y;
    }
    size[0] = turned ? s[1] : s[0];
    size[1] = turned ? s[0] : s[1];
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

static int bigger_first(const void *a, const void *b)
{
    const item *p = a, *q = b;
    if (p->w * p->h != q->w * q->h)
        return p->w * p->h > q->w * q->h ? -1 : 1;
    return taller_first(a, b);
}

/* The items at density, padding included, sorted by order; their total
 * area. */
static double make_items(const gb_packing *packing, uint32_t count, double density,
                         uint32_t padding, item *items, int (*order)(const void *, const void *))
{
    double area = 0.0;
    for (uint32_t i = 0; i < count; ++i) {
        uint64_t size[2];
        size_of(packing->boxes + 4 * (size_t)i, density, packing->margin, size);
        items[i] = (item){size[0] + 2 * padding, size[1] + 2 * padding, i};
        area += (double)items[i].w * (double)items[i].h;
    }
    qsort(items, count, sizeof *items, order);
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

/* ---- by shape ---- */

/* Where shapes were placed last in a packing: the row of the last chart
 * whose two masks (as it is and turned) hashed to the same 64 bits, so
 * that a chart of the same shape (scenes repeat their pillars and steps)
 * starts its search there (occupancy.h). */
typedef struct seen_shapes {
    uint64_t *hashes;           /* 0: free */
    uint32_t *rows;
    size_t capacity;            /* a power of two */
} seen_shapes;

static uint64_t fnv1a(uint64_t hash, const uint32_t *words, size_t count)
{
    for (size_t i = 0; i < count; ++i)
        for (int b = 0; b < 4; ++b)
            hash = (hash ^ ((words[i] >> (8 * b)) & 0xff)) * UINT64_C(0x100000001b3);
    return hash;
}

static uint64_t shape_hash(const gb_chart_mask masks[2])
{
    uint64_t hash = UINT64_C(0xcbf29ce484222325);
    for (int i = 0; i < 2; ++i) {
        const gb_chart_mask *m = &masks[i];
        uint32_t sides[2] = {m->width, m->height};
        hash = fnv1a(hash, sides, 2);
        hash = fnv1a(hash, m->row_starts, (size_t)m->height + 1);
        hash = fnv1a(hash, m->runs, 2 * (size_t)m->row_starts[m->height]);
    }
    return hash ? hash : 1;
}

/* The slot of hash: its own, or the free one where it would go. */
static size_t shape_slot(const seen_shapes *seen, uint64_t hash)
{
    size_t k = (size_t)hash & (seen->capacity - 1);
    while (seen->hashes[k] && seen->hashes[k] != hash)
        k = (k + 1) & (seen->capacity - 1);
    return k;
}

typedef struct shape_packer {
    const gb_chart_list *list;
    const gb_packing *packing;  /* its boxes and margin */
    uint32_t padding;
    double *texels;             /* room for the largest chart's corners */
    gb_atlas_mask scratch;
    gb_occupancy occupancy;
    uint32_t *rects;            /* 4 per chart */
    uint8_t *turned;            /* per chart */
    uint64_t top;               /* the first row below every mask */
    seen_shapes seen;
} shape_packer;

/* Chart c's padded mask at density, turned or not, and its rect's sides;
 * 0 when out of memory. */
static int mask_of(shape_packer *s, uint32_t c, double density, int turned, gb_chart_mask *mask,
                   uint64_t size[2])
{
    const gb_chart *chart = &s->list->charts[c];
    local_texels(chart, s->packing->boxes + 4 * (size_t)c, density, s->packing->margin, turned,
                 s->texels, size);
    return gb_chart_mask_make(mask, s->texels, chart->triangle_count, (uint32_t)size[0],
                              (uint32_t)size[1], s->packing->margin, s->padding, &s->scratch);
}

/* The item placed at its first place, as it is or turned: 1, 0 when it
 * fits nowhere, -1 out of memory. */
static int place_shape(shape_packer *s, const item *it, double density)
{
    const gb_occupancy *o = &s->occupancy;
    if ((it->w > o->width || it->h > o->height) && (it->h > o->width || it->w > o->height))
        return 0;
    gb_chart_mask masks[2] = {{0}, {0}};
    const gb_chart_mask *candidates[2] = {&masks[0], &masks[1]};
    uint64_t sizes[2][2];
    if (!mask_of(s, it->chart, density, 0, &masks[0], sizes[0]) ||
        !mask_of(s, it->chart, density, 1, &masks[1], sizes[1])) {
        gb_chart_mask_free(&masks[0]);
        return -1;
    }
    int which = 0;
    uint32_t x = 0, y = 0;
    uint64_t hash = shape_hash(masks);
    size_t slot = shape_slot(&s->seen, hash);
    uint32_t first_row = s->seen.hashes[slot] ? s->seen.rows[slot] : 0;
    int found = gb_occupancy_find(o, candidates, 2, first_row, &which, &x, &y);
    if (found) {
        s->seen.hashes[slot] = hash;
        s->seen.rows[slot] = y;
        gb_occupancy_mark(&s->occupancy, &masks[which], x, y);
        uint32_t *rect = s->rects + 4 * (size_t)it->chart;
        rect[0] = x + s->padding;
        rect[1] = y + s->padding;
        rect[2] = (uint32_t)sizes[which][0];
        rect[3] = (uint32_t)sizes[which][1];
        s->turned[it->chart] = (uint8_t)which;
        if (y + masks[which].height > s->top)
            s->top = y + masks[which].height;
    }
    gb_chart_mask_free(&masks[0]);
    gb_chart_mask_free(&masks[1]);
    return found;
}

/* Packs the items (bigger_first) by shape into width x height; s->rects,
 * s->turned and s->top filled when they fit. Returns 1 fits, 0 does not,
 * -1 out of memory. */
static int shape_pack(shape_packer *s, const item *items, uint32_t count, double density,
                      uint32_t width, uint32_t height)
{
    if (!gb_occupancy_init(&s->occupancy, width, height))
        return -1;
    s->top = 0;
    memset(s->seen.hashes, 0, s->seen.capacity * sizeof *s->seen.hashes);
    int fits = 1;
    for (uint32_t i = 0; i < count && fits == 1; ++i)
        fits = place_shape(s, &items[i], density);
    gb_occupancy_free(&s->occupancy);
    return fits;
}

static int shape_packer_init(shape_packer *s, const gb_chart_list *list,
                             const gb_packing *packing, uint32_t padding)
{
    size_t largest = 0;
    for (uint32_t i = 0; i < list->count; ++i)
        if (list->charts[i].triangle_count > largest)
            largest = list->charts[i].triangle_count;
    *s = (shape_packer){.list = list, .packing = packing, .padding = padding};
    s->texels = malloc(6 * (largest ? largest : 1) * sizeof *s->texels);
    s->rects = malloc(4 * (size_t)list->count * sizeof *s->rects);
    s->turned = calloc(list->count ? list->count : 1, 1);
    for (s->seen.capacity = 16; s->seen.capacity < 2 * (size_t)list->count;)
        s->seen.capacity *= 2;
    s->seen.hashes = malloc(s->seen.capacity * sizeof *s->seen.hashes);
    s->seen.rows = malloc(s->seen.capacity * sizeof *s->seen.rows);
    return s->texels && s->rects && s->turned && s->seen.hashes && s->seen.rows;
}

static void shape_packer_free(shape_packer *s)
{
    free(s->texels);
    free(s->rects);
    free(s->turned);
    free(s->seen.hashes);
    free(s->seen.rows);
    gb_atlas_mask_free(&s->scratch);
}

/* The shape packer's places into packing. */
static void keep_shapes(const shape_packer *s, gb_packing *packing, uint32_t count)
{
    memcpy(packing->rects, s->rects, 4 * (size_t)count * sizeof *s->rects);
    memcpy(packing->turned, s->turned, count);
}

/* ---- density ---- */

static gb_result too_large(const gb_packing_options *o, const char *side, gb_error *error)
{
    return gb_fail(error, GB_ERROR_UNSUPPORTED, "%g texels per unit needs an atlas %s than "
                   "%d texels", o->texels_per_unit, side, GB_ATLAS_MAX_SIZE);
}

static gb_result fixed_density(const gb_chart_list *list, const gb_packing_options *o,
                               int by_shape, item *items, gb_packing *packing, gb_error *error)
{
    double area = make_items(packing, list->count, o->texels_per_unit, o->padding, items,
                             by_shape ? bigger_first : taller_first);
    uint64_t width = (uint64_t)ceil(sqrt(area / 0.9)), top = 0;
    for (uint32_t i = 0; i < list->count; ++i)
        if (items[i].w > width)
            width = items[i].w;
    if (width > GB_ATLAS_MAX_SIZE)
        return too_large(o, "wider", error);
    shape_packer s;
    int fits = -1;
    if (!by_shape)
        fits = skyline_pack(items, list->count, width, GB_ATLAS_MAX_SIZE, o->padding,
                            packing->rects, &top);
    else if (shape_packer_init(&s, list, packing, o->padding)) {
        fits = shape_pack(&s, items, list->count, o->texels_per_unit, (uint32_t)width,
                          GB_ATLAS_MAX_SIZE);
        if (fits > 0)
            keep_shapes(&s, packing, list->count);
        top = s.top;
    }
    if (by_shape)
        shape_packer_free(&s);
    if (fits < 0)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (packing)");
    if (!fits)
        return too_large(o, "taller", error);
    packing->width = (uint32_t)width;
    packing->height = (uint32_t)(top > 2 * o->padding ? top : 2 * o->padding + 1);
    packing->texels_per_unit = o->texels_per_unit;
    return GB_OK;
}

/* Whether the padded rects fit size x size at density; -1 out of memory. */
static int rects_fit_at(const gb_chart_list *list, const gb_packing_options *o, double density,
                        item *items, gb_packing *packing)
{
    uint64_t top;
    make_items(packing, list->count, density, o->padding, items, taller_first);
    return skyline_pack(items, list->count, o->size, o->size, o->padding, packing->rects, &top);
}

/* The largest density at which the padded rects fit, packed (packing.h). */
static gb_result rects_density(const gb_chart_list *list, const gb_packing_options *o,
                               item *items, gb_packing *packing, gb_error *error)
{
    double area = 0.0;
    for (uint32_t i = 0; i < list->count; ++i)
        area += list->charts[i].area;
    double hi = (double)o->size / sqrt(area > 0.0 ? area : 1e-30), lo = hi * 1e-6;
    int fits = rects_fit_at(list, o, lo, items, packing);
    if (fits == 0)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%u charts with a padding of %u do "
                       "not fit a %u x %u atlas at any density", list->count, o->padding,
                       o->size, o->size);
    for (int step = 0; step < 40 && fits >= 0; ++step) {
        double middle = sqrt(lo * hi);
        fits = rects_fit_at(list, o, middle, items, packing);
        if (fits > 0)
            lo = middle;
        else if (fits == 0)
            hi = middle;
    }
    if (fits >= 0)
        fits = rects_fit_at(list, o, lo, items, packing);
    if (fits < 0)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (packing)");
    packing->width = packing->height = o->size;
    packing->texels_per_unit = lo;
    return GB_OK;
}

/* Whether the masks fit size x size at density (kept in packing when they
 * do); -1 out of memory. */
static int shapes_fit_at(shape_packer *s, const gb_packing_options *o, double density,
                         item *items, gb_packing *packing)
{
    make_items(packing, s->list->count, density, o->padding, items, bigger_first);
    int fits = shape_pack(s, items, s->list->count, density, o->size, o->size);
    if (fits > 0) {
        keep_shapes(s, packing, s->list->count);
        packing->texels_per_unit = density;
    }
    return fits;
}

/* The next density to try by shape between lo, which fits with its masks
 * down to row top, and hi, which does not (or is the density at which
 * the charts alone fill the atlas): while no density has failed, lo grown
 * as the rows it used grow to the atlas's (the area goes as the density
 * squared), by 1 % at least; then the middle (packing.h). */
static double next_density(double lo, double hi, int hi_failed, uint64_t top, uint32_t size)
{
    if (hi_failed)
        return sqrt(lo * hi);
    double grown = lo * fmax(1.01, sqrt((double)size / (double)(top ? top : 1)));
    return grown < hi ? grown : sqrt(lo * hi);
}

/* From the rects' density up, by shape (packing.h). */
static gb_result chosen_density(const gb_chart_list *list, const gb_packing_options *o,
                                item *items, gb_packing *packing, gb_error *error)
{
    gb_result result = rects_density(list, o, items, packing, error);
    if (result != GB_OK)
        return result;
    double area = 0.0;
    for (uint32_t i = 0; i < list->count; ++i)
        area += list->charts[i].area;
    double lo = packing->texels_per_unit, hi = (double)o->size / sqrt(area > 0.0 ? area : 1e-30);
    shape_packer s;
    int fits = shape_packer_init(&s, list, packing, o->padding) ? 1 : -1, hi_failed = 0;
    if (fits > 0 && o->hint > lo && o->hint < hi) {
        fits = shapes_fit_at(&s, o, o->hint, items, packing);
        if (fits > 0) {
            shape_packer_free(&s);
            return GB_OK;
        }
        hi = o->hint, hi_failed = 1;
        fits = fits < 0 ? -1 : 1;
    }
    if (fits > 0)
        fits = shapes_fit_at(&s, o, lo, items, packing);
    uint64_t top = s.top;
    for (int step = 0; fits > 0 && hi > lo && step < GB_PACKING_SHAPE_STEPS; ++step) {
        double density = next_density(lo, hi, hi_failed, top, o->size);
        int density_fits = shapes_fit_at(&s, o, density, items, packing);
        if (density_fits > 0)
            lo = density, top = s.top;
        else if (density_fits == 0)
            hi = density, hi_failed = 1;
        else
            fits = -1;
    }
    shape_packer_free(&s);
    return fits < 0 ? gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (packing)") : GB_OK;
}

static gb_result pack(const gb_chart_list *list, const gb_packing_options *options,
                      int by_shape, gb_packing *packing, gb_error *error)
{
    memset(packing, 0, sizeof *packing);
    packing->margin = options->margin;
    packing->rects = malloc(4 * (size_t)list->count * sizeof *packing->rects);
    packing->boxes = malloc(4 * (size_t)list->count * sizeof *packing->boxes);
    packing->turned = calloc(list->count ? list->count : 1, 1);
    item *items = malloc((size_t)list->count * sizeof *items);
    gb_result result = GB_OK;
    if (!packing->rects || !packing->boxes || !packing->turned || !items)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory (packing)");
    for (uint32_t i = 0; result == GB_OK && i < list->count; ++i)
        box_of(&list->charts[i], packing->boxes + 4 * (size_t)i);
    if (result == GB_OK && options->texels_per_unit > 0.0)
        result = fixed_density(list, options, by_shape, items, packing, error);
    else if (result == GB_OK)
        result = by_shape ? chosen_density(list, options, items, packing, error)
                          : rects_density(list, options, items, packing, error);
    free(items);
    if (result != GB_OK)
        gb_packing_free(packing);
    return result;
}

gb_result gb_pack(const gb_chart_list *list, const gb_packing_options *options,
                  gb_packing *packing, gb_error *error)
{
    return pack(list, options, 1, packing, error);
}

gb_result gb_pack_rects(const gb_chart_list *list, const gb_packing_options *options,
                        gb_packing *packing, gb_error *error)
{
    return pack(list, options, 0, packing, error);
}

void gb_packing_free(gb_packing *packing)
{
    free(packing->rects);
    free(packing->boxes);
    free(packing->turned);
    memset(packing, 0, sizeof *packing);
}

void gb_packing_texels(const gb_chart_list *list, const gb_packing *packing, uint32_t i,
                       double *texels)
{
    const gb_chart *chart = &list->charts[i];
    const uint32_t *rect = packing->rects + 4 * (size_t)i;
    uint64_t size[2];
    local_texels(chart, packing->boxes + 4 * (size_t)i, packing->texels_per_unit,
                 packing->margin, packing->turned[i], texels, size);
    for (size_t k = 0; k < 3 * (size_t)chart->triangle_count; ++k)
        for (int d = 0; d < 2; ++d)
            texels[2 * k + d] += rect[d];
}
