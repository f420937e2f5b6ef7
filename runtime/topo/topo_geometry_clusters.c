/* topo_geometry_clusters.c — IUGC (Noël & Biri 2014, §V.B): geometry
 * clusters as clustered shading makes them (Olsson et al. 2012, "local
 * sorting": per screen tile, sort the fragments' keys and give each distinct
 * key a cluster), with the paper's constraint that every fragment of a
 * geometry cluster has the same visibility cluster: the key is (depth slice,
 * visibility cluster). Each geometry cluster keeps its bounding box and the
 * bounding sphere of that box, for LA. Runs on the CPU on the G-buffer read
 * back (depth and clusters). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "array_reserve.h"
#include "gbuffer.h"
#include "topo.h"

typedef struct keyed_pixel {
    uint64_t key;               /* slice << 32 | visibility cluster */
    uint32_t pixel;
} keyed_pixel;

void gb_topo_pixel_position(const gb_topo_frame_input *f, int x, int y, float d, float out[3])
{
    float ndc_x = 2.0f * ((float)x + 0.5f) / (float)f->width - 1.0f;
    float ndc_y = 2.0f * ((float)y + 0.5f) / (float)f->height - 1.0f;
    float z = -f->near / d;
    float v[4] = {ndc_x * f->tan_half_fov[0] * -z, ndc_y * f->tan_half_fov[1] * -z, z, 1.0f};
    for (int r = 0; r < 3; ++r) {
        out[r] = 0.0f;
        for (int c = 0; c < 4; ++c)
            out[r] += f->view_to_world[4 * c + r] * v[c];
    }
}

/* Olsson et al. 2012, eq. 3: slices whose depth grows like the tiles' width. */
static uint32_t depth_slice(const gb_topo_frame_input *f, float d, int tiles_y);

uint32_t gb_topo_depth_slice(const gb_topo_frame_input *f, float d)
{
    return depth_slice(f, d, (f->height + GB_TOPO_TILE - 1) / GB_TOPO_TILE);
}

static uint32_t depth_slice(const gb_topo_frame_input *f, float d, int tiles_y)
{
    float z = f->near / d;      /* -view z, >= near */
    float k = logf(fmaxf(z / f->near, 1.0f)) /
              logf(1.0f + 2.0f * f->tan_half_fov[1] / (float)tiles_y);
    return k < 4e9f ? (uint32_t)k : 0xfffffffeu;
}

static int compare_keys(const void *a, const void *b)
{
    const keyed_pixel *p = a, *q = b;
    if (p->key != q->key)
        return p->key < q->key ? -1 : 1;
    return p->pixel < q->pixel ? -1 : p->pixel > q->pixel;
}

static gb_geometry_cluster *new_cluster(gb_geometry_clusters *out, uint32_t visibility_cluster)
{
    if (!gb_array_reserve(&out->clusters, &out->capacity, out->count + 1, sizeof *out->clusters))
        return NULL;
    gb_geometry_cluster *g = &out->clusters[out->count++];
    g->visibility_cluster = visibility_cluster;
    for (int a = 0; a < 3; ++a) {
        g->box_min[a] = INFINITY;
        g->box_max[a] = -INFINITY;
    }
    return g;
}

static void finish_sphere(gb_geometry_cluster *g)
{
    float r2 = 0.0f;
    for (int a = 0; a < 3; ++a) {
        g->centre[a] = 0.5f * (g->box_min[a] + g->box_max[a]);
        float h = 0.5f * (g->box_max[a] - g->box_min[a]);
        r2 += h * h;
    }
    g->radius = sqrtf(r2);
}

/* Keys of the tile's fragments that have a visibility cluster; returns how many. */
static uint32_t tile_keys(const gb_topo_frame_input *f, int tx, int ty, int tiles_y,
                          keyed_pixel *keys)
{
    uint32_t n = 0;
    for (int y = ty * GB_TOPO_TILE; y < (ty + 1) * GB_TOPO_TILE && y < f->height; ++y)
        for (int x = tx * GB_TOPO_TILE; x < (tx + 1) * GB_TOPO_TILE && x < f->width; ++x) {
            uint32_t i = (uint32_t)(y * f->width + x);
            float d = f->depth[i];
            uint32_t c = f->clusters[2 * i];
            f->clusters[2 * i + 1] = GB_NO_CLUSTER;
            if (!(d > 0.0f) || c == GB_NO_CLUSTER)
                continue;
            keys[n++] = (keyed_pixel){(uint64_t)depth_slice(f, d, tiles_y) << 32 | c, i};
        }
    return n;
}

static gb_result cluster_tile(const gb_topo_frame_input *f, int tx, int ty, int tiles_y,
                              keyed_pixel *keys, gb_geometry_clusters *out, gb_error *error)
{
    uint32_t n = tile_keys(f, tx, ty, tiles_y, keys);
    qsort(keys, n, sizeof *keys, compare_keys);
    gb_geometry_cluster *g = NULL;
    for (uint32_t k = 0; k < n; ++k) {
        if (k == 0 || keys[k].key != keys[k - 1].key) {
            if (g)
                finish_sphere(g);
            if (!(g = new_cluster(out, (uint32_t)keys[k].key)))
                return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "IUGC: out of memory");
        }
        uint32_t i = keys[k].pixel;
        float p[3];
        gb_topo_pixel_position(f, (int)(i % (uint32_t)f->width), (int)(i / (uint32_t)f->width),
                               f->depth[i], p);
        for (int a = 0; a < 3; ++a) {
            g->box_min[a] = fminf(g->box_min[a], p[a]);
            g->box_max[a] = fmaxf(g->box_max[a], p[a]);
        }
        f->clusters[2 * i + 1] = out->count - 1;
    }
    if (g)
        finish_sphere(g);
    return GB_OK;
}

gb_result gb_topo_geometry_clusters_build(const gb_topo_frame_input *f,
                                          gb_geometry_clusters *out, gb_error *error)
{
    out->count = 0;
    keyed_pixel *keys = malloc(GB_TOPO_TILE * GB_TOPO_TILE * sizeof *keys);
    if (!keys)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "IUGC: out of memory");
    int tiles_x = (f->width + GB_TOPO_TILE - 1) / GB_TOPO_TILE;
    int tiles_y = (f->height + GB_TOPO_TILE - 1) / GB_TOPO_TILE;
    gb_result result = GB_OK;
    for (int ty = 0; ty < tiles_y && result == GB_OK; ++ty)
        for (int tx = 0; tx < tiles_x && result == GB_OK; ++tx)
            result = cluster_tile(f, tx, ty, tiles_y, keys, out, error);
    free(keys);
    return result;
}

void gb_geometry_clusters_free(gb_geometry_clusters *clusters)
{
    free(clusters->clusters);
    memset(clusters, 0, sizeof *clusters);
}
