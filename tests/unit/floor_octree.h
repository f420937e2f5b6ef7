/* floor_octree.h — the floor of the octree display's tests and a light
 * octree made over it by hand, so that the display (test_octree_display.c)
 * and its CPU twin (test_light_octree_shading.c) are tried on one scene.
 *
 *   floor_scene_begin(&scene, up);       // the quad and the camera above it
 *   ...lights, corner normals...
 *   scene_done(&scene);
 *   floor_octree *h = calloc(1, sizeof *h);      // large: the caller's
 *   floor_octree_punch_holes(h);                 // or cells of its own
 *   floor_octree_make(h, normal, vdls_max, fill, &scene, &octree);
 *   floor_octree_render(&scene, &octree, NULL, FLOOR_IMAGE_SIZE, &image);  // the walk
 *   floor_atlas_make(&scene, square, padding, charts, &a);  // the floor laid flat
 *   floor_octree_render(&scene, &octree, &a.atlas, size, &image);   // through it
 *   floor_bake_open(&scene, &octree, &a.atlas, atlas_path, &bake);  // in the test's scratch
 *
 * The floor: y = 0, FLOOR_HALF each side of the origin in x and z, albedo
 * FLOOR_KD, seen from FLOOR_CAMERA_HEIGHT above its centre. The octree:
 * depth FLOOR_DEPTH 4 over the cube (-2, -2.1, -2) + 4, leaf edge 0.25,
 * surface interpolation (light_octree_shading.h), each leaf's plane the
 * floor's, the floor in layer FLOOR_LAYER 8 (0.1 above its bottom face); every cell
 * (i, 8, k) is a leaf but those marked CELL_MISSING, and the test's `fill`
 * gives each CELL_LIT leaf its VDLs (a CELL_EMPTY leaf has none).
 *
 * The atlas: the floor laid flat by hand in one chart or two of square x
 * square texels, padding texels around each; floor (x, z) at s = (x + 2) /
 * 4, r = (z + 2) / 4 (or swapped, to keep the triangles counterclockwise:
 * `straight` says which), texel coordinates padding + square (s, r). With
 * one chart both triangles share the square; with two, each triangle has a
 * square of its own, side by side, the quad's diagonal a seam between
 * charts. It points into its floor_atlas, the caller's.
 *
 * The caller owns the floor_octree (free it); the gb_light_octree that
 * floor_octree_make fills points into it, so it is not to be given to
 * gb_light_octree_free. floor_octree_make may be called again after the
 * cells change. The rendered image is the caller's (gb_image_free).
 */
#ifndef GB_FLOOR_OCTREE_H
#define GB_FLOOR_OCTREE_H

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "../../runtime/bake.h"
#include "../../runtime/methods.h"
#include "atlas.h"
#include "headless_render.h"
#include "light_octree.h"
#include "scene_builder.h"
#include "scratch.h"

#define FLOOR_HALF 2.0f
#define FLOOR_KD 0.5f
#define FLOOR_CAMERA_HEIGHT 3.0f
#define FLOOR_CAMERA_FOV 30.0f
#define FLOOR_IMAGE_SIZE 64

#define FLOOR_DEPTH 4u
#define FLOOR_GRID (1u << FLOOR_DEPTH)
#define FLOOR_LAYER 8u
#define FLOOR_CELL 0.25
#define FLOOR_VDLS_MAX 3u       /* the most VDLs `fill` may give a leaf */

typedef enum { CELL_LIT, CELL_EMPTY, CELL_MISSING } cell_kind;

typedef struct floor_octree {
    cell_kind cells[FLOOR_GRID][FLOOR_GRID];        /* [i][k] of layer FLOOR_LAYER */
    gb_light_octree_node nodes[FLOOR_GRID * FLOOR_GRID * FLOOR_DEPTH];
    gb_light_octree_leaf leaves[FLOOR_GRID * FLOOR_GRID];
    gb_light_octree_vdl vdls[FLOOR_GRID * FLOOR_GRID * FLOOR_VDLS_MAX];
    uint32_t node_count, leaf_count, vdl_count;
    const float *normal;                            /* every leaf's */
    uint32_t (*fill)(uint32_t i, uint32_t k, gb_light_octree_vdl *vdls);
} floor_octree;

/* The floor quad wound to face toward (its front side), the camera above
 * it; the caller adds what else it needs and calls scene_done. */
static inline void floor_scene_begin(gb_scene *scene, const float toward[3])
{
    memset(scene, 0, sizeof *scene);
    uint32_t grey = add_grey(scene, FLOOR_KD, 0.0f);
    const float h = FLOOR_HALF;
    const float corners[4][3] = {{-h, 0, -h}, {h, 0, -h}, {h, 0, h}, {-h, 0, h}};
    add_quad_facing(scene, corners, toward, grey);
    const float eye[3] = {0, FLOOR_CAMERA_HEIGHT, 0}, target[3] = {0, 0, 0};
    set_camera(scene, eye, target, FLOOR_CAMERA_FOV, FLOOR_IMAGE_SIZE, FLOOR_IMAGE_SIZE);
}

/* The holes, all inside the view (cells 4..11 in x and z): a missing leaf,
 * a leaf without VDLs beside a lit one, and an L of three (a missing leaf
 * between two empty ones) whose corner window keeps a single lit leaf. */
static inline void floor_octree_punch_holes(floor_octree *h)
{
    h->cells[6][6] = CELL_MISSING;
    h->cells[9][6] = CELL_EMPTY;
    h->cells[9][9] = CELL_MISSING;
    h->cells[10][9] = CELL_EMPTY;
    h->cells[9][10] = CELL_EMPTY;
}

/* Is there a leaf in the cube of level `level` at cell (x, y, z)? */
static inline int floor_octree_has_leaf(const floor_octree *h, uint32_t level, uint32_t x,
                                        uint32_t y, uint32_t z)
{
    uint32_t span = 1u << (FLOOR_DEPTH - level);
    if (FLOOR_LAYER < y * span || FLOOR_LAYER >= (y + 1) * span)
        return 0;
    for (uint32_t i = x * span; i < (x + 1) * span; ++i)
        for (uint32_t k = z * span; k < (z + 1) * span; ++k)
            if (h->cells[i][k] != CELL_MISSING)
                return 1;
    return 0;
}

/* A leaf's plane (light_octree.h): through the floor's point under its
 * centre, along its normal as stored. */
static inline int16_t floor_octree_plane(const gb_light_octree_leaf *leaf)
{
    float normal[3];
    gb_light_octree_leaf_normal(leaf, normal);
    float centre_height = -2.1f + ((float)FLOOR_LAYER + 0.5f) * (float)FLOOR_CELL;
    return (int16_t)lrintf(-normal[1] * centre_height / (float)FLOOR_CELL *
                           GB_LIGHT_OCTREE_PLANE_ONE);
}

static inline uint32_t floor_octree_add_leaf(floor_octree *h, uint32_t i, uint32_t k)
{
    gb_light_octree_leaf *leaf = &h->leaves[h->leaf_count];
    memset(leaf, 0, sizeof *leaf);
    const uint32_t cell[3] = {i, FLOOR_LAYER, k};
    leaf->normal = gb_photon_pack_direction(h->normal);
    leaf->plane = floor_octree_plane(leaf);
    leaf->cell = gb_light_octree_pack_cell(cell);
    leaf->first_vdl = h->vdl_count;
    if (h->cells[i][k] == CELL_LIT)
        leaf->vdl_count = h->fill(i, k, &h->vdls[h->vdl_count]);
    h->vdl_count += leaf->vdl_count;
    return h->leaf_count++;
}

/* The node pool in preorder, leaves in Morton order (children in order
 * c = x | y << 1 | z << 2, as light_octree.h says). */
static inline uint32_t floor_octree_node(floor_octree *h, uint32_t level, uint32_t x,
                                         uint32_t y, uint32_t z)
{
    if (!floor_octree_has_leaf(h, level, x, y, z))
        return GB_LIGHT_OCTREE_NONE;
    if (level == FLOOR_DEPTH)
        return floor_octree_add_leaf(h, x, z);
    uint32_t node = h->node_count++;
    for (uint32_t c = 0; c < 8; ++c)
        h->nodes[node].child[c] = floor_octree_node(h, level + 1, 2 * x + (c & 1),
                                                    2 * y + (c >> 1 & 1), 2 * z + (c >> 2));
    return node;
}

/* The octree of h's cells, every leaf's normal `normal`, a CELL_LIT leaf
 * (i, k)'s VDLs written by fill (it returns how many, 1 to vdls_max, at
 * most FLOOR_VDLS_MAX), for scene. */
static inline void floor_octree_make(floor_octree *h, const float normal[3], uint32_t vdls_max,
                                     uint32_t (*fill)(uint32_t i, uint32_t k,
                                                      gb_light_octree_vdl *vdls),
                                     const gb_scene *scene, gb_light_octree *octree)
{
    h->node_count = h->leaf_count = h->vdl_count = 0;
    h->normal = normal;
    h->fill = fill;
    floor_octree_node(h, 0, 0, 0, 0);
    memset(octree, 0, sizeof *octree);
    octree->header = (gb_light_octree_header){
        .depth = FLOOR_DEPTH, .node_count = h->node_count, .leaf_count = h->leaf_count,
        .vdl_count = h->vdl_count, .origin = {-2.0f, -2.1f, -2.0f}, .size = 4.0f,
        .scene_hash = scene->hash, .photon_count = 1, .emitted_count = 1, .knn = 1,
        .radius = 1.0f, .vdls_max = vdls_max, .tolerance = 0.2f, .flattening = 0.5f,
        .interpolation = GB_LIGHT_OCTREE_SURFACE};
    octree->nodes = h->nodes;
    octree->leaves = h->leaves;
    octree->vdls = h->vdls;
}

/* The bake folder of scene in the scratch folder (scratch.h's, made by
 * the caller): octree written as floor.lot, and atlas as floor.atlas (its
 * path into atlas_path) when it is not NULL; *bake opened on it (the
 * caller releases it). 0 when it cannot, with the reason printed. */
static inline int floor_bake_open(const gb_scene *scene, const gb_light_octree *octree,
                                  const gb_atlas *atlas, char atlas_path[512], gb_bake **bake)
{
    char path[512], scene_path[512];
    gb_error error;
    scratch_path_into("floor.lot", path, sizeof path);
    scratch_path_into("floor.scene", scene_path, sizeof scene_path);
    scratch_path_into("floor.atlas", atlas_path, 512);
    *bake = NULL;
    if (gb_light_octree_write(path, octree, &error) != GB_OK ||
        (atlas && gb_atlas_write(atlas_path, atlas, &error) != GB_OK) ||
        gb_bake_open(scene, scene_path, scratch_folder, bake, &error) != GB_OK) {
        printf("# %s\n", error.message);
        return 0;
    }
    if (gb_bake_problem(*bake, GB_BAKE_LIGHT_OCTREE)) {
        printf("# %s\n", gb_bake_problem(*bake, GB_BAKE_LIGHT_OCTREE));
        return 0;
    }
    return 1;
}

/* The octree's indirect term of scene, size x size pixels, rendered
 * headless as gbview --method octree --terms indirect --bake FOLDER
 * renders it, FOLDER floor_bake_open's in a scratch folder of its own (the
 * test's left as it was): the walk, or through atlas (--atlas FILE) when
 * it is not NULL. 0 when it cannot, with the reason printed. */
static inline int floor_octree_render(const gb_scene *scene, const gb_light_octree *octree,
                                      const gb_atlas *atlas, int size, gb_image *image)
{
    char atlas_path[512], outer[sizeof scratch_folder];
    memcpy(outer, scratch_folder, sizeof outer);  /* the test's own, if it has one */
    scratch_create("floor-octree");
    int ok = 0;
    gb_bake *bake = NULL;
    if (floor_bake_open(scene, octree, atlas, atlas_path, &bake)) {
        gb_headless_options options = {
            .renderer = {.method = GB_METHOD_OCTREE, .terms = GB_TERMS_INDIRECT,
                         .width = size, .height = size, .bake = bake,
                         .parameters = {.octree = {.atlas = atlas ? atlas_path : "none"}}},
        };
        ok = render_headless(scene, &options, image);
    }
    gb_bake_release(bake);
    scratch_remove();
    memcpy(scratch_folder, outer, sizeof outer);
    return ok;
}

typedef struct floor_atlas {
    gb_atlas atlas;
    float uvs[2 * 6];
    uint32_t charts[2];
    gb_atlas_chart records[2];
    int straight;               /* s from x (else from z) */
} floor_atlas;

static inline void floor_atlas_make(const gb_scene *scene, uint32_t square, uint32_t padding,
                                    uint32_t chart_count, floor_atlas *a)
{
    const uint32_t side = square + 2 * padding;
    memset(a, 0, sizeof *a);
    const float *p[3];
    for (int c = 0; c < 3; ++c)
        p[c] = scene->positions + 3 * scene->indices[c];
    a->straight = (p[1][0] - p[0][0]) * (p[2][2] - p[0][2]) -
                  (p[1][2] - p[0][2]) * (p[2][0] - p[0][0]) > 0.0f;
    for (uint32_t t = 0; t < 2; ++t) {
        uint32_t chart = chart_count == 1 ? 0 : t;
        a->charts[t] = chart;
        for (int c = 0; c < 3; ++c) {
            const float *q = scene->positions + 3 * scene->indices[3 * t + c];
            float s = (q[a->straight ? 0 : 2] + FLOOR_HALF) / (2.0f * FLOOR_HALF);
            float r = (q[a->straight ? 2 : 0] + FLOOR_HALF) / (2.0f * FLOOR_HALF);
            a->uvs[6 * t + 2 * c] =
                (float)(chart * side + padding + s * square) / (chart_count * side);
            a->uvs[6 * t + 2 * c + 1] = (float)(padding + r * square) / side;
        }
    }
    for (uint32_t chart = 0; chart < chart_count; ++chart)
        a->records[chart] = (gb_atlas_chart){
            2 / chart_count, 4.0f * FLOOR_HALF * FLOOR_HALF / chart_count, 0.0f, 0.0f,
            {chart * side + padding, padding, square, square}};
    a->atlas.header = (gb_atlas_header){
        .scene_hash = scene->hash, .triangle_count = 2, .chart_count = chart_count,
        .width = chart_count * side, .height = side,
        .texels_per_unit = square / (2.0f * FLOOR_HALF), .padding = padding};
    a->atlas.uvs = a->uvs;
    a->atlas.charts = a->charts;
    a->atlas.chart_records = a->records;
}

#endif
