/* topo.c — gb_topo_method: VPL indirect light with implicit visibility
 * through visibility clusters and gates (Noël & Biri 2014, §V). Load time:
 * the bake's .seg, whose gates are drawn as they are (segment fitted them
 * to the openings, tools/segment/gate_openings.h), and .grid.vdb, both
 * borrowed from the gb_bake (bake.h), the voxels' surface flags marked in
 * the cluster lookup when the bake has its .vdb (topo_clusters.c), the VPLs
 * (topo_vpls.c) and their clusters.
 * Each frame: visibility cluster per fragment (GPU compute), IUGC (GPU
 * compute, topo_geometry_clusters_gpu.c; with GB_TOPO_IUGC=cpu in the
 * environment, gb_topo_geometry_clusters_build on the G-buffer read back),
 * LA (GPU compute; gb_topo_assign is its CPU twin), then IL (GPU fragment
 * pass). The
 * frame's G-buffer clusters texture ends with x = visibility cluster and
 * y = geometry cluster. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "indirect_method.h"
#include "method_parameters.h"
#include "progress.h"
#include "topo.h"

enum { DEFAULT_VPLS = 1024 };
static const uint64_t VPL_SEED = 0x746f706f;   /* "topo" */

typedef struct topo_state {
    const gb_segmentation *segmentation;  /* borrowed from the bake */
    int32_t *voxel_clusters;
    gb_vpl_set vpls;
    int32_t *vpl_cluster;
    gb_topo_gates gates;
    gb_topo_visibility visibility;
    gb_topo_cluster_pass cluster_pass;
    gb_topo_gather_pass gather;
    gb_topo_la_gpu la_gpu;
    gb_topo_iugc_gpu iugc_gpu;
    int iugc_on_cpu;            /* GB_TOPO_IUGC=cpu: the reference IUGC */
    gb_geometry_clusters geometry;
    gb_topo_assignment assignment;
    float *depth;
    uint32_t *clusters;
    int width, height;
    int every_vpl;              /* this image gathers every VPL, unshadowed */
    gb_topo_pass_times times;
} topo_state;

static gb_result need_bake(const gb_bake *bake, gb_error *error)
{
    if (!bake)
        return gb_fail(error, GB_ERROR_ARGUMENT,
                       "method topo needs the scene's bake (--bake DIR with NAME.grid.vdb "
                       "and NAME.seg: thin --grid, segment)");
    const gb_bake_kind kinds[] = {GB_BAKE_NEAREST_NODE, GB_BAKE_SEGMENTS};
    for (int i = 0; i < 2; ++i)
        if (gb_bake_problem(bake, kinds[i]))
            return gb_fail(error, GB_ERROR_ARGUMENT, "method topo: %s",
                           gb_bake_problem(bake, kinds[i]));
    return GB_OK;
}

/* The voxels' surface flags marked in the voxels' clusters, when the bake
 * has its voxels: the lookup then takes a surface voxel's cluster only as a
 * last resort (topo_clusters.c). */
static gb_result mark_surface(topo_state *t, const gb_bake *bake, gb_error *error)
{
    const gb_voxel_grid *voxels = gb_bake_voxels(bake);
    if (!voxels)
        return GB_OK;
    gb_result result = gb_segmentation_check_frame(t->segmentation, voxels,
                                                   gb_bake_path(bake, GB_BAKE_VOXELS), error);
    if (result == GB_OK)
        gb_topo_voxel_clusters_mark_surface(t->segmentation, t->voxel_clusters, voxels->surface);
    return result;
}

static gb_result load_clusters(topo_state *t, const gb_bake *bake, gb_error *error)
{
    const gb_voxel_grid *frame;
    const int32_t *nearest = gb_bake_nearest_node(bake, &frame);
    t->segmentation = gb_bake_segmentation(bake);
    gb_result result = gb_segmentation_check_grid(t->segmentation, frame, nearest,
                                                  gb_bake_path(bake, GB_BAKE_NEAREST_NODE),
                                                  error);
    if (result == GB_OK &&
        !(t->voxel_clusters = gb_segmentation_voxel_clusters(t->segmentation, nearest)))
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "topo: out of memory");
    if (result == GB_OK)
        result = mark_surface(t, bake, error);
    if (result == GB_OK)
        result = gb_topo_gates_build(t->segmentation, &t->gates, error);
    return result;
}

static gb_result make_vpls(topo_state *t, const gb_indirect_setup *setup, gb_error *error)
{
    int count = setup->parameters->topo.vpls > 0 ? setup->parameters->topo.vpls : DEFAULT_VPLS;
    gb_result result = gb_topo_vpls_generate(setup->scene, (uint32_t)count, VPL_SEED, &t->vpls,
                                             error);
    if (result == GB_OK && setup->parameters->topo.write_vpls)
        result = gb_vpl_write(setup->parameters->topo.write_vpls, &t->vpls, error);
    if (result == GB_OK && !(t->vpl_cluster = malloc((t->vpls.count + 1u) * sizeof(int32_t))))
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "topo: out of memory");
    for (uint32_t i = 0; result == GB_OK && i < t->vpls.count; ++i)
        t->vpl_cluster[i] = gb_topo_surface_cluster(t->segmentation, t->voxel_clusters,
                                                    t->vpls.vpls[i].position,
                                                    t->vpls.vpls[i].normal);
    return result;
}

static void topo_destroy(void *state)
{
    topo_state *t = state;
    if (!t)
        return;
    gb_topo_la_gpu_destroy(&t->la_gpu);
    gb_topo_iugc_gpu_destroy(&t->iugc_gpu);
    gb_topo_gather_destroy(&t->gather);
    gb_topo_cluster_pass_destroy(&t->cluster_pass);
    gb_topo_assignment_free(&t->assignment);
    gb_geometry_clusters_free(&t->geometry);
    gb_topo_gates_free(&t->gates);
    gb_vpl_free(&t->vpls);
    free(t->vpl_cluster);
    free(t->voxel_clusters);
    free(t->depth);
    free(t->clusters);
    free(t);
}

static gb_result topo_create(const gb_indirect_setup *setup, void **state, gb_error *error)
{
    *state = NULL;
    gb_result result = need_bake(setup->bake, error);
    if (result != GB_OK)
        return result;
    if (setup->parameters->topo.visibility < GB_TOPO_FULL ||
        setup->parameters->topo.visibility > GB_TOPO_NONE)
        return gb_fail(error, GB_ERROR_ARGUMENT, "topo: bad visibility mode %d",
                       setup->parameters->topo.visibility);
    topo_state *t = calloc(1, sizeof *t);
    if (!t)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "topo: out of memory");
    t->visibility = (gb_topo_visibility)setup->parameters->topo.visibility;
    result = load_clusters(t, setup->bake, error);
    if (result == GB_OK)
        result = make_vpls(t, setup, error);
    if (result == GB_OK)
        result = gb_topo_cluster_pass_create(t->segmentation, t->voxel_clusters,
                                             &t->cluster_pass, error);
    if (result == GB_OK)
        result = gb_topo_gather_create(
            &t->vpls, t->segmentation, &t->gates,
            gb_topo_vsl_radius(setup->scene, t->vpls.count, (float)t->segmentation->voxel_size),
            &t->gather, error);
    if (result == GB_OK)
        result = gb_topo_la_gpu_create(&t->vpls, t->vpl_cluster, &t->gates, &t->la_gpu, error);
    const char *iugc = getenv("GB_TOPO_IUGC");
    t->iugc_on_cpu = iugc && strcmp(iugc, "cpu") == 0;
    if (result == GB_OK && !t->iugc_on_cpu)
        result = gb_topo_iugc_gpu_create(&t->iugc_gpu, error);
    if (result != GB_OK) {
        topo_destroy(t);
        return result;
    }
    *state = t;
    return GB_OK;
}

static int fit_frame(topo_state *t, int width, int height)
{
    if (t->width == width && t->height == height && t->depth)
        return 1;
    free(t->depth);
    free(t->clusters);
    size_t n = (size_t)width * (size_t)height;
    t->depth = malloc(n * sizeof *t->depth);
    t->clusters = malloc(2 * n * sizeof *t->clusters);
    t->width = t->depth && t->clusters ? width : 0;
    t->height = t->depth && t->clusters ? height : 0;
    return t->width != 0;
}

/* IUGC and LA on the GPU; the geometry clusters' count is the one value
 * read back (LA's CPU prefix sum needs it). 0 when out of memory (the frame
 * then gathers every VPL, unshadowed). */
static int cluster_and_assign_gpu(topo_state *t, const gb_indirect_frame *frame,
                                  const gb_topo_frame_input *input)
{
    const gb_gbuffer *g = frame->gbuffer;
    double start = gb_seconds();
    gb_error error;
    uint32_t count = 0;
    int ok = gb_topo_iugc_gpu_run(&t->iugc_gpu, g->depth, g->clusters, input, &count,
                                  &error) == GB_OK;
    glFinish();
    double iugc = gb_seconds();
    ok = ok && gb_topo_la_gpu_run_resident(&t->la_gpu, t->iugc_gpu.clusters, count,
                                           t->visibility, &t->gather, &t->assignment,
                                           &error) == GB_OK;
    glFinish();
    double la = gb_seconds();
    t->times.iugc_ms += 1e3 * (iugc - start);
    t->times.la_ms += 1e3 * (la - iugc);
    return ok;
}

/* IUGC on the CPU, LA on the GPU; 0 when out of memory (the frame then gathers
 * every VPL, unshadowed). */
static int cluster_and_assign(topo_state *t, const gb_indirect_frame *frame,
                              const gb_topo_frame_input *input)
{
    const gb_gbuffer *g = frame->gbuffer;
    size_t n = (size_t)input->width * (size_t)input->height;
    double start = gb_seconds();
    glGetTextureImage(g->depth, 0, GL_DEPTH_COMPONENT, GL_FLOAT, (GLsizei)(n * sizeof(float)),
                      t->depth);
    glGetTextureImage(g->clusters, 0, GL_RG_INTEGER, GL_UNSIGNED_INT,
                      (GLsizei)(2 * n * sizeof(uint32_t)), t->clusters);
    gb_error error;
    int ok = gb_topo_geometry_clusters_build(input, &t->geometry, &error) == GB_OK;
    if (ok)
        glTextureSubImage2D(g->clusters, 0, 0, 0, input->width, input->height, GL_RG_INTEGER,
                            GL_UNSIGNED_INT, t->clusters);
    glFinish();
    double iugc = gb_seconds();
    ok = ok && gb_topo_la_gpu_run(&t->la_gpu, &t->geometry, t->visibility, &t->gather,
                                  &t->assignment, &error) == GB_OK;
    glFinish();
    double la = gb_seconds();
    t->times.iugc_ms += 1e3 * (iugc - start);
    t->times.la_ms += 1e3 * (la - iugc);
    return ok;
}

gb_topo_frame_input gb_topo_frame_input_of_view(const gb_view *view, int width, int height)
{
    gb_topo_frame_input input = {.width = width, .height = height, .near = view->near};
    gb_mat4 view_to_world = gb_view_inverse_matrix(view);
    memcpy(input.view_to_world, view_to_world.m, sizeof input.view_to_world);
    float tan_y = tanf(0.5f * view->fov_y * (float)M_PI / 180.0f);
    input.tan_half_fov[0] = tan_y * (float)width / (float)height;
    input.tan_half_fov[1] = tan_y;
    return input;
}

/* The view's passes, once an image: visibility cluster per fragment, then
 * IUGC and LA (t->every_vpl when they could not run). */
static void cluster_view(topo_state *t, const gb_indirect_frame *frame,
                         gb_topo_frame_input *input)
{
    double start = gb_seconds();
    const gb_gbuffer *g = frame->gbuffer;
    gb_topo_cluster_pass_run(&t->cluster_pass, g->depth, g->normal, g->clusters, frame->width,
                             frame->height, input->view_to_world, input->tan_half_fov,
                             input->near);
    glFinish();
    t->times.clusters_ms += 1e3 * (gb_seconds() - start);
    t->every_vpl = t->visibility == GB_TOPO_NONE;
    if (!t->every_vpl && !t->iugc_on_cpu) {
        t->every_vpl = !cluster_and_assign_gpu(t, frame, input);
    } else if (!t->every_vpl && fit_frame(t, frame->width, frame->height)) {
        input->depth = t->depth;
        input->clusters = t->clusters;
        t->every_vpl = !cluster_and_assign(t, frame, input);
    }
}

/* The view's passes at part 0, then IL within the part's band. */
static int topo_draw(void *state, const gb_indirect_frame *frame)
{
    topo_state *t = state;
    gb_topo_frame_input input =
        gb_topo_frame_input_of_view(frame->view, frame->width, frame->height);
    if (frame->part == 0)
        cluster_view(t, frame, &input);
    double il_start = gb_seconds();
    gb_gbuffer_bind(frame->gbuffer);
    gb_topo_gather_draw(&t->gather, input.view_to_world, input.tan_half_fov, input.near,
                        t->every_vpl);
    glFinish();
    t->times.il_ms += 1e3 * (gb_seconds() - il_start);
    t->times.frames += frame->part + 1 == frame->parts;
    return 0;
}

void gb_topo_times(const void *state, gb_topo_pass_times *times)
{
    const topo_state *t = state;
    memset(times, 0, sizeof *times);
    if (t)
        *times = t->times;
}

const gb_indirect_method gb_topo_method = {
    .create = topo_create,
    .draw = topo_draw,
    .destroy = topo_destroy,
};
