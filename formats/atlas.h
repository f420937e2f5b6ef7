/* atlas.h — the lightmap atlas on disk: the file kind "ATLS"
 * (formats/FORMATS.md, "Atlas"). `atlas` writes it (vivianloc-2007
 * §4.2.3: the scene cut into charts, each parameterised by LSCM and packed
 * into one 2-D atlas); the runtime renders the light octree into it once
 * and `lightmap` bakes it into an image.
 *
 * UV convention (glTF's): u across the image from its left edge, v down it
 * from its top edge, both in [0, 1]; texel (column i, row j) covers
 * u in [i / width, (i + 1) / width), v in [j / height, (j + 1) / height), and
 * row 0 is the first in memory and the top of an image file. A GL texture
 * uploaded row 0 first is then sampled at texture(atlas, uv) as it is.
 * Every triangle winds counterclockwise in (u, v) seen as plain numbers:
 * (u1 - u0)(v2 - v0) - (v1 - v0)(u2 - u0) > 0, for triangle corners 0, 1, 2
 * in the scene's order.
 *
 * Sections (each 16-byte aligned, little-endian, used in place):
 *   header  gb_atlas_header (64 bytes)
 *   uvs     f32[6] per triangle of the scene, in the scene's triangle order:
 *           (u, v) of corners 0, 1, 2
 *   charts  u32 per triangle: its chart, < chart_count
 *   chart_records  gb_atlas_chart per chart
 *
 *   gb_atlas_read("x.atlas", &atlas, &error);   // checks every field
 *   gb_atlas_check_scene(&atlas, scene->hash, scene->triangle_count, path, &error);
 *   gb_atlas_free(&atlas);
 * A gb_atlas owns its storage (malloc'ed arrays, or the mapping).
 */
#ifndef GB_ATLAS_H
#define GB_ATLAS_H

#include <stddef.h>
#include <stdint.h>

#include "container.h"
#include "result.h"

enum {
    GB_ATLAS_VERSION = 2,         /* 1, whose charts were apart by their rects, is refused */
    GB_ATLAS_MAX_SIZE = 16384,          /* texels along a side */
};

/* How far (texels) gb_atlas_check lets a UV lie outside its chart's rect:
 * the rounding of texel coordinates divided by the atlas size and
 * multiplied back. */
#define GB_ATLAS_RECT_TOLERANCE 1e-3

typedef struct gb_atlas_header {
    uint64_t scene_hash;        /* gb_scene.hash of the scene parameterised */
    uint32_t triangle_count;    /* the scene's */
    uint32_t chart_count;       /* >= 1 */
    uint32_t width, height;     /* texels, 1 .. GB_ATLAS_MAX_SIZE */
    float texels_per_unit;      /* texel density: texels per world unit, > 0 */
    uint32_t padding;           /* texels of gutter kept around every chart's mask */
    uint32_t reserved[8];       /* zero */
} gb_atlas_header;

/* A chart: a set of triangles connected over shared edges, a topological
 * disc, parameterised as one piece. */
typedef struct gb_atlas_chart {
    uint32_t triangle_count;
    float area;                 /* world units squared */
    float max_angle_distortion; /* degrees: largest |UV angle - 3-D angle| of its corners */
    float mean_angle_distortion;/* degrees: the mean of the same over its corners */
    uint32_t rect[4];           /* x, y, width, height in texels: the chart's
                                   texel box, padding excluded; every UV of the
                                   chart is inside it. Rects may overlap: the
                                   charts' padded masks may not (gb_atlas_check) */
} gb_atlas_chart;

typedef struct gb_atlas {
    gb_atlas_header header;
    const float *uvs;           /* triangle_count * 6 */
    const uint32_t *charts;     /* triangle_count */
    const gb_atlas_chart *chart_records; /* chart_count */
    void *storage;              /* owned: the arrays when built in memory, or NULL */
    gb_container container;     /* owned: the file the arrays view, when read */
} gb_atlas;

/* Checks the header, every UV (finite, in [0, 1], inside its chart's
 * rect), every triangle's winding (UV area > 0), every chart index, each
 * chart's triangle count, that each chart's rect grown by the padding lies
 * in the atlas, and that no texel lies in the padded masks of two charts
 * (atlas_mask.h: the texels a chart's triangles overlap, grown by the
 * padding along x and y). The last takes a bit a texel of the atlas (32
 * MiB at the largest) and 12 bytes a row of each triangle of the largest
 * chart. */
gb_result gb_atlas_check(const gb_atlas *atlas, const char *path, gb_error *error);
/* Checks, then writes (temporary file, rename). */
gb_result gb_atlas_write(const char *path, const gb_atlas *atlas, gb_error *error);
/* Maps and checks; on failure *atlas is zeroed and needs no freeing. */
gb_result gb_atlas_read(const char *path, gb_atlas *atlas, gb_error *error);
/* The same on a 16-byte aligned buffer that outlives the atlas. */
gb_result gb_atlas_parse(const void *bytes, size_t size, const char *path, gb_atlas *atlas,
                         gb_error *error);
/* GB_ERROR_STALE unless made from the scene of this hash and triangle count. */
gb_result gb_atlas_check_scene(const gb_atlas *atlas, uint64_t scene_hash,
                               uint32_t triangle_count, const char *path, gb_error *error);
void gb_atlas_free(gb_atlas *atlas);

/* How far (texels, from a texel's centre) a chart's field reaches into its
 * gutter when the atlas is rendered: the texels whose centre lies within
 * this distance of one of the chart's triangles hold the chart's own field,
 * evaluated on the plane of the nearest such triangle (extended past its
 * edges). √2 reaches every texel a bilinear read inside a triangle weighs,
 * so a chart's border shows no seam; it is kept under the padding, so that
 * it never reaches another chart's gutter (the padded masks are apart), and
 * is 0 without padding: the runtime's render into the atlas and `lightmap`
 * both use it. */
static inline double gb_atlas_reach(uint32_t padding)
{
    return padding >= 2 ? 1.41421356237 : padding == 1 ? 0.9375 : 0.0;
}

#endif
