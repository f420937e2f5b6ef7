/* test_topo_iugc.c — IUGC on the GPU (runtime/topo/topo_geometry_clusters_gpu.c)
 * against its CPU reference (gb_topo_geometry_clusters_build) on the same
 * G-buffer: the same number of geometry clusters, the same cluster for
 * every pixel (the GPU keeps the CPU's numbering), the same visibility
 * cluster per geometry cluster, boxes and spheres equal within float
 * rounding; and LA from the GPU's clusters gives the CPU's VPL lists. Cases:
 * a synthetic frame of 100 x 70 (partial tiles, pixels without depth or
 * without a visibility cluster, steps in depth and cluster), a noisy frame
 * with hundreds of distinct keys per tile (the sort under stress) and the
 * Cornell box drawn into a G-buffer with four quadrant clusters and gates.
 * Headless GL: a failed check without it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene_builder.h"
#include "tap.h"
#include "tap_printf.h"
#include "topo_quadrants.h"

static int near_enough(float a, float b)
{
    return fabsf(a - b) <= 1e-5f * fmaxf(1.0f, fmaxf(fabsf(a), fabsf(b)));
}

/* Differences between the two clusterings; prints the first few. */
typedef struct comparison {
    int pixels_differ, visibility_differ, bounds_differ;
    uint32_t cpu_count, gpu_count;
} comparison;

static void compare(const uint32_t *cpu_ids, const uint32_t *gpu_ids, int pixels,
                    const gb_geometry_clusters *cpu, const gb_geometry_clusters *gpu,
                    comparison *c)
{
    memset(c, 0, sizeof *c);
    c->cpu_count = cpu->count;
    c->gpu_count = gpu->count;
    for (int i = 0; i < pixels; ++i)
        if (cpu_ids[2 * i] != gpu_ids[2 * i] || cpu_ids[2 * i + 1] != gpu_ids[2 * i + 1]) {
            if (c->pixels_differ++ < 3)
                printf("#   pixel %d: CPU (%u, %u), GPU (%u, %u)\n", i, cpu_ids[2 * i],
                       cpu_ids[2 * i + 1], gpu_ids[2 * i], gpu_ids[2 * i + 1]);
        }
    uint32_t n = cpu->count < gpu->count ? cpu->count : gpu->count;
    for (uint32_t g = 0; g < n; ++g) {
        const gb_geometry_cluster *a = &cpu->clusters[g], *b = &gpu->clusters[g];
        c->visibility_differ += a->visibility_cluster != b->visibility_cluster;
        int same = near_enough(a->radius, b->radius);
        for (int k = 0; k < 3; ++k)
            same &= near_enough(a->box_min[k], b->box_min[k]) &&
                    near_enough(a->box_max[k], b->box_max[k]) &&
                    near_enough(a->centre[k], b->centre[k]);
        if (!same && c->bounds_differ++ < 3)
            printf("#   cluster %u: CPU min %g %g %g r %g, GPU min %g %g %g r %g\n", g,
                   a->box_min[0], a->box_min[1], a->box_min[2], a->radius, b->box_min[0],
                   b->box_min[1], b->box_min[2], b->radius);
    }
}

/* CPU IUGC on the G-buffer read back, then GPU IUGC on the G-buffer itself;
 * *gpu_ids the G-buffer's clusters after the GPU run. */
static gb_result run_both(const gb_gbuffer *gbuffer, const gb_topo_frame_input *frame_in,
                          gb_topo_iugc_gpu *iugc, gb_geometry_clusters *cpu,
                          gb_geometry_clusters *gpu, uint32_t *cpu_ids, uint32_t *gpu_ids,
                          gb_error *error)
{
    int n = frame_in->width * frame_in->height;
    float *depth = malloc((size_t)n * sizeof *depth);
    gb_topo_frame_input frame = *frame_in;
    frame.depth = depth;
    frame.clusters = cpu_ids;
    glGetTextureImage(gbuffer->depth, 0, GL_DEPTH_COMPONENT, GL_FLOAT, n * 4, depth);
    glGetTextureImage(gbuffer->clusters, 0, GL_RG_INTEGER, GL_UNSIGNED_INT, n * 8, cpu_ids);
    gb_result result = gb_topo_geometry_clusters_build(&frame, cpu, error);
    uint32_t count = 0;
    if (result == GB_OK)
        result = gb_topo_iugc_gpu_run(iugc, gbuffer->depth, gbuffer->clusters, &frame, &count,
                                      error);
    if (result == GB_OK)
        result = gb_topo_iugc_gpu_read(iugc, count, gpu, error);
    glGetTextureImage(gbuffer->clusters, 0, GL_RG_INTEGER, GL_UNSIGNED_INT, n * 8, gpu_ids);
    free(depth);
    return result;
}

static uint32_t next_random(uint32_t *state)
{
    *state = *state * 1664525u + 1013904223u;
    return *state >> 8;
}

/* A frame of W x H from depth and clusters given per pixel. */
static void check_synthetic(const char *name, int W, int H, const float *depth,
                            const uint32_t *ids, uint32_t min_count)
{
    gb_error error;
    gb_gbuffer gbuffer = {0};
    gb_topo_iugc_gpu iugc = {0};
    gb_result result = gb_gbuffer_create(W, H, &gbuffer, &error);
    if (result == GB_OK)
        result = gb_topo_iugc_gpu_create(&iugc, &error);
    uint32_t *cpu_ids = malloc((size_t)W * H * 2 * sizeof *cpu_ids);
    uint32_t *gpu_ids = malloc((size_t)W * H * 2 * sizeof *gpu_ids);
    gb_geometry_clusters cpu = {0}, gpu = {0};
    gb_topo_frame_input frame = {W, H, NULL, NULL,
                                 {0.8f, 0.6f, 0, 0, -0.6f, 0.8f, 0, 0, 0, 0, 1, 0, 3, -2, 5, 1},
                                 {0.7f, 0.5f}, 0.05f};
    if (result == GB_OK) {
        glTextureSubImage2D(gbuffer.depth, 0, 0, 0, W, H, GL_DEPTH_COMPONENT, GL_FLOAT, depth);
        glTextureSubImage2D(gbuffer.clusters, 0, 0, 0, W, H, GL_RG_INTEGER, GL_UNSIGNED_INT, ids);
        result = run_both(&gbuffer, &frame, &iugc, &cpu, &gpu, cpu_ids, gpu_ids, &error);
    }
    if (result != GB_OK)
        printf("#   %s\n", error.message);
    CHECKF(result == GB_OK, "IUGC GPU, %s: ran", name);
    comparison c;
    compare(cpu_ids, gpu_ids, W * H, &cpu, &gpu, &c);
    printf("# %s: CPU %u geometry clusters, GPU %u\n", name, c.cpu_count, c.gpu_count);
    CHECKF(c.cpu_count >= min_count && c.gpu_count == c.cpu_count,
           "IUGC GPU, %s: as many geometry clusters as the CPU (at least %u)", name, min_count);
    CHECKF(c.pixels_differ == 0, "IUGC GPU, %s: every pixel in the CPU's cluster", name);
    CHECKF(c.visibility_differ == 0 && c.bounds_differ == 0,
           "IUGC GPU, %s: visibility cluster, box and sphere of each cluster the CPU's", name);
    gb_geometry_clusters_free(&cpu);
    gb_geometry_clusters_free(&gpu);
    free(cpu_ids);
    free(gpu_ids);
    gb_topo_iugc_gpu_destroy(&iugc);
    gb_gbuffer_destroy(&gbuffer);
}

/* Steps: clusters change every 13 columns and 17 rows, depth in bands
 * (several slices per tile), a hole without depth, a strip without a
 * visibility cluster. */
static void test_steps(void)
{
    enum { W = 100, H = 70 };
    static float depth[W * H];
    static uint32_t ids[2 * W * H];
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            int i = y * W + x;
            depth[i] = 0.05f / (1.0f + 0.08f * (float)((x + 2 * y) / 6));
            ids[2 * i] = (uint32_t)((x / 13 + y / 17) % 5);
            ids[2 * i + 1] = GB_NO_CLUSTER;
            if (x >= 40 && x < 47 && y >= 10 && y < 50)
                depth[i] = 0.0f;
            if (y == 33)
                ids[2 * i] = GB_NO_CLUSTER;
        }
    check_synthetic("steps 100x70", W, H, depth, ids, 20);
}

/* Noise: depth spread over 6 decades, 200 visibility clusters: most of the
 * 1024 keys of a tile distinct. */
static void test_noise(void)
{
    enum { W = 96, H = 64 };
    static float depth[W * H];
    static uint32_t ids[2 * W * H];
    uint32_t state = 12345;
    for (int i = 0; i < W * H; ++i) {
        depth[i] = 0.05f * powf(10.0f, -6.0f * (float)(next_random(&state) % 10000) / 1e4f);
        ids[2 * i] = next_random(&state) % 200;
        ids[2 * i + 1] = GB_NO_CLUSTER;
    }
    check_synthetic("noise 96x64", W, H, depth, ids, 6 * 500);
}

/* The Cornell box's voxel grid cut into four quadrant clusters
 * (topo_quadrants.h), the gates at 0.3 of its height. */
typedef struct quadrants {
    gb_segmentation s;
    gb_visibility_gate gates[4];
    int32_t *voxels;
} quadrants;

static void make_quadrants(const gb_scene *scene, quadrants *q)
{
    memset(q, 0, sizeof *q);
    q->voxels = quadrant_voxels(scene, &q->s);
    float mid[3], size[3];
    for (int a = 0; a < 3; ++a) {
        mid[a] = (float)(q->s.world_origin[a] + (q->s.grid_size[a] / 2) * q->s.voxel_size);
        size[a] = scene->bounds_max[a] - scene->bounds_min[a];
    }
    quadrant_gates(q->gates, mid, size, scene->bounds_min[1] + 0.3f * size[1], &q->s);
}

/* LA from the CPU's clusters and from the GPU's (left on the GPU): the same
 * lists. */
static void check_assignment(const gb_scene *scene, const quadrants *q,
                             const gb_geometry_clusters *cpu, const gb_topo_iugc_gpu *iugc)
{
    gb_error error;
    gb_vpl_set vpls;
    gb_topo_vpls_generate(scene, 512, 3, &vpls, &error);
    int32_t *vpl_cluster = malloc(vpls.count * sizeof *vpl_cluster);
    for (uint32_t i = 0; i < vpls.count; ++i)
        vpl_cluster[i] = gb_topo_surface_cluster(&q->s, q->voxels, vpls.vpls[i].position,
                                                 vpls.vpls[i].normal);
    gb_topo_gates gates;
    gb_topo_gather_pass gather;
    gb_topo_la_gpu la;
    gb_topo_assignment from_cpu = {0}, from_gpu = {0};
    gb_result result = gb_topo_gates_build(&q->s, &gates, &error);
    if (result == GB_OK)
        result = gb_topo_gather_create(&vpls, &q->s, &gates, 1.0f, &gather, &error);
    if (result == GB_OK)
        result = gb_topo_la_gpu_create(&vpls, vpl_cluster, &gates, &la, &error);
    if (result == GB_OK)
        result = gb_topo_la_gpu_run(&la, cpu, GB_TOPO_FULL, &gather, &from_cpu, &error);
    if (result == GB_OK)
        result = gb_topo_la_gpu_read(&gather, &from_cpu, &error);
    if (result == GB_OK)
        result = gb_topo_la_gpu_run_resident(&la, iugc->clusters, cpu->count, GB_TOPO_FULL,
                                             &gather, &from_gpu, &error);
    if (result == GB_OK)
        result = gb_topo_la_gpu_read(&gather, &from_gpu, &error);
    if (result != GB_OK)
        printf("#   %s\n", error.message);
    int gated = 0;
    for (uint32_t i = 0; result == GB_OK && i < from_cpu.entry_count; ++i)
        gated += from_cpu.entries[i].group != GB_TOPO_NO_GATE;
    printf("# Cornell LA: %u entries (%d through a gate) from the CPU's clusters, %u from "
           "the GPU's\n", from_cpu.entry_count, gated, from_gpu.entry_count);
    CHECK(result == GB_OK && gated > 0 && from_gpu.entry_count == from_cpu.entry_count &&
              memcmp(from_gpu.ranges, from_cpu.ranges, 2 * cpu->count * sizeof(uint32_t)) == 0 &&
              memcmp(from_gpu.entries, from_cpu.entries,
                     from_cpu.entry_count * sizeof *from_cpu.entries) == 0,
          "IUGC GPU, Cornell box: LA gives the same VPL lists (some through gates) as from "
          "the CPU's clusters");
    gb_topo_la_gpu_destroy(&la);
    gb_topo_gather_destroy(&gather);
    gb_topo_assignment_free(&from_cpu);
    gb_topo_assignment_free(&from_gpu);
    gb_topo_gates_free(&gates);
    free(vpl_cluster);
    gb_vpl_free(&vpls);
}

static void test_cornell(void)
{
    enum { W = 200, H = 150 };
    gb_error error;
    gb_scene scene = {0};
    build_cornell_box(&scene, W, H);
    quadrants q;
    make_quadrants(&scene, &q);
    cluster_frame f;
    gb_topo_iugc_gpu iugc = {0};
    gb_result result = cluster_frame_draw(&f, &scene, &q.s, q.voxels, W, H, &error);
    if (result == GB_OK)
        result = gb_topo_iugc_gpu_create(&iugc, &error);
    uint32_t *cpu_ids = malloc((size_t)W * H * 2 * sizeof *cpu_ids);
    uint32_t *gpu_ids = malloc((size_t)W * H * 2 * sizeof *gpu_ids);
    gb_geometry_clusters cpu = {0}, gpu = {0};
    if (result == GB_OK)
        result = run_both(&f.gbuffer, &f.frame, &iugc, &cpu, &gpu, cpu_ids, gpu_ids, &error);
    if (result != GB_OK)
        printf("#   %s\n", error.message);
    CHECK(result == GB_OK, "IUGC GPU, Cornell box 200x150: ran");
    comparison c;
    compare(cpu_ids, gpu_ids, W * H, &cpu, &gpu, &c);
    printf("# Cornell: CPU %u geometry clusters, GPU %u\n", c.cpu_count, c.gpu_count);
    CHECK(c.cpu_count > 35 && c.gpu_count == c.cpu_count,
          "IUGC GPU, Cornell box: as many geometry clusters as the CPU (more than one per "
          "tile)");
    CHECK_EQ_INT(c.pixels_differ, 0, "IUGC GPU, Cornell box: every pixel in the CPU's cluster");
    CHECK(c.visibility_differ == 0 && c.bounds_differ == 0,
          "IUGC GPU, Cornell box: visibility cluster, box and sphere of each cluster the CPU's");
    if (result == GB_OK)
        check_assignment(&scene, &q, &cpu, &iugc);
    gb_geometry_clusters_free(&cpu);
    gb_geometry_clusters_free(&gpu);
    free(cpu_ids);
    free(gpu_ids);
    gb_topo_iugc_gpu_destroy(&iugc);
    cluster_frame_destroy(&f);
    free(q.voxels);
    gb_scene_free(&scene);
}

int main(void)
{
    gb_context context;
    if (!gpu_context(&context, "IUGC"))
        return tap_done();
    test_steps();
    test_noise();
    test_cornell();
    gb_context_destroy(&context);
    return tap_done();
}
