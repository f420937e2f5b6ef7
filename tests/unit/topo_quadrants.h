/* topo_quadrants.h — the Cornell box cut into four visibility clusters, the
 * quadrants of x and z, for the tests of the topological method
 * (test_topo.c, test_topo_iugc.c): a gate in the middle of each inner wall,
 * a voxel grid of the quadrants, and the box drawn into a G-buffer whose
 * fragments get their cluster on the GPU.
 *
 *   int32_t *voxels = quadrant_voxels(&scene, &s);   // the caller frees it
 *   quadrant_gates(gates, mid, size, height, &s);    // s points at gates
 *   cluster_frame f;
 *   if (cluster_frame_draw(&f, &scene, &s, voxels, W, H, &error) == GB_OK) ...
 *   cluster_frame_destroy(&f);                       // whatever the result
 *
 * The frame needs a current GL context: gpu_context makes one headless,
 * and fails a check when it cannot (CI has Mesa's llvmpipe).
 */
#ifndef GB_TOPO_QUADRANTS_H
#define GB_TOPO_QUADRANTS_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "../../runtime/context.h"
#include "../../runtime/gbuffer.h"
#include "../../runtime/topo/topo.h"
#include "../../runtime/view.h"
#include "scene.h"
#include "tap.h"

/* A headless GL context (1; gb_context_destroy it), or 0 after the failed
 * check "what: a headless GL context" and its reason. */
static inline int gpu_context(gb_context *context, const char *what)
{
    gb_error error;
    int made = gb_context_create_headless(context, &error) == GB_OK;
    char label[160];
    snprintf(label, sizeof label, "%s: a headless GL context", what);
    if (!CHECK(made, label))
        printf("#   %s\n", error.message);
    return made;
}

/* The four gates of the inner walls, 0|1 and 2|3 facing x, 0|2 and 1|3
 * facing z, each a quarter of the box from the middle `mid` of the walls,
 * at y = height, of radius a tenth of the box's x size; s's clusters and
 * gates (pointing at `gates`). */
static inline void quadrant_gates(gb_visibility_gate gates[4], const float mid[3],
                                  const float size[3], float height, gb_segmentation *s)
{
    static const uint32_t pairs[4][2] = {{0, 1}, {2, 3}, {0, 2}, {1, 3}};
    memset(gates, 0, 4 * sizeof *gates);
    for (int i = 0; i < 4; ++i) {
        int along_x = i < 2;
        float *c = gates[i].centre;
        c[0] = mid[0] + (along_x ? 0.0f : (i == 2 ? -0.25f : 0.25f) * size[0]);
        c[1] = height;
        c[2] = mid[2] + (along_x ? (i == 0 ? -0.25f : 0.25f) * size[2] : 0.0f);
        gates[i].normal[along_x ? 0 : 2] = 1.0f;
        gates[i].radius = 0.1f * size[0];
        gates[i].clusters[0] = pairs[i][0];
        gates[i].clusters[1] = pairs[i][1];
        gates[i].edge = (uint32_t)i;
    }
    s->cluster_count = 4;
    s->gate_count = 4;
    s->gates = gates;
}

/* A voxel grid over the box (s zeroed, then its frame: voxels of 20, two
 * of margin) whose clusters are its four quadrants in x and z, and -1 in
 * five layers under the ceiling, as if they had no node: deep enough that
 * the lookup's offsets and its 27-voxel fallback find nothing for the
 * ceiling's fragments. */
static inline int32_t *quadrant_voxels(const gb_scene *scene, gb_segmentation *s)
{
    memset(s, 0, sizeof *s);
    s->voxel_size = 20.0;
    for (int a = 0; a < 3; ++a) {
        s->world_origin[a] = scene->bounds_min[a] - 2.0 * s->voxel_size;
        s->grid_size[a] = (int32_t)ceil((scene->bounds_max[a] - scene->bounds_min[a]) /
                                        s->voxel_size) + 4;
    }
    const int32_t *n = s->grid_size;
    int32_t *clusters = malloc((size_t)n[0] * n[1] * n[2] * sizeof *clusters);
    for (int32_t k = 0; k < n[2]; ++k)
        for (int32_t j = 0; j < n[1]; ++j)
            for (int32_t i = 0; i < n[0]; ++i)
                clusters[i + n[0] * (j + n[1] * k)] =
                    j >= n[1] - 7 && j <= n[1] - 3 ? -1
                                                   : (i >= n[0] / 2) + 2 * (k >= n[2] / 2);
    return clusters;
}

/* The scene drawn from its camera 0 into a G-buffer, each fragment's
 * visibility cluster looked up on the GPU from s and voxels. */
typedef struct cluster_frame {
    gb_gpu_scene gpu;
    gb_gbuffer gbuffer;
    gb_topo_cluster_pass pass;
    gb_topo_frame_input frame;  /* set when drawn */
} cluster_frame;

static inline gb_result cluster_frame_draw(cluster_frame *f, const gb_scene *scene,
                                           const gb_segmentation *s, const int32_t *voxels,
                                           int width, int height, gb_error *error)
{
    memset(f, 0, sizeof *f);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    gb_view view;
    gb_result result = gb_gpu_scene_create(scene, &f->gpu, error);
    if (result == GB_OK)
        result = gb_gbuffer_create(width, height, &f->gbuffer, error);
    if (result == GB_OK)
        result = gb_topo_cluster_pass_create(s, voxels, &f->pass, error);
    if (result == GB_OK)
        result = gb_scene_view(scene, 0, &view, error);
    if (result != GB_OK)
        return result;
    gb_mat4 world_to_view = gb_view_matrix(&view);
    gb_mat4 projection = gb_view_projection(&view, width, height);
    gb_gbuffer_draw(&f->gbuffer, &f->gpu, &world_to_view, &projection);
    f->frame = gb_topo_frame_input_of_view(&view, width, height);
    gb_topo_cluster_pass_run(&f->pass, f->gbuffer.depth, f->gbuffer.normal,
                             f->gbuffer.clusters, width, height, f->frame.view_to_world,
                             f->frame.tan_half_fov, f->frame.near);
    return GB_OK;
}

static inline void cluster_frame_destroy(cluster_frame *f)
{
    gb_topo_cluster_pass_destroy(&f->pass);
    gb_gbuffer_destroy(&f->gbuffer);
    gb_gpu_scene_destroy(&f->gpu);
}

#endif
