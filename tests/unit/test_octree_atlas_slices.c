/* test_octree_atlas_slices.c — the octree method's atlas rendered in slices
 * (octree.h, octree_atlas.h): draw renders bands of it at part 0 of each
 * image until the frame's budget is spent, shows the walk until it is
 * complete, and says so. Driven as the renderer drives a method
 * (indirect_method.h: the output bound, additive blending, the scissor on
 * each part's band), on the floor of floor_octree.h under a hand-made
 * octree with holes, laid flat in an atlas of one chart (the two
 * triangles' reaches overlap on the diagonal, where the nearest keeps a
 * texel) and in one of two (a seam between them), 2 texels of padding (a
 * gutter round past the triangles' reach), 128 rows:
 *
 *  1. Budget 0: the first image completes the atlas and shows it (draw
 *     returns 0). In one chart every texel of both layers is filled: the
 *     chart's square reaches to 2 texels of the atlas's edges, which the
 *     triangles' reach (√2 texels) leaves to the gutter.
 *  2. Budget 10^-3 ms, three parts an image: one slice an image, so many
 *     images; each image before the atlas is complete is the walk's
 *     (--atlas none), byte for byte, and draw returns nonzero; once it
 *     returns 0 the atlas texture is byte-identical to budget 0's and the
 *     image is budget 0's, and the next image too.
 *  3. The walk with three parts is the walk with one (the band kept).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../../runtime/context.h"
#include "../../runtime/octree/octree.h"
#include "../../runtime/octree/octree_atlas.h"
#include "../../runtime/renderer.h"
#include "floor_octree.h"
#include "photon_map.h"
#include "tap.h"

enum { SIZE = FLOOR_IMAGE_SIZE, PARTS = 3 };
/* Charts of 124 texels, 2 of padding: an atlas of 128 x 128 (one chart)
 * or 256 x 128 (two). */
#define ATLAS_SQUARE 124
#define ATLAS_PADDING 2
#define TINY_BUDGET_MS 1e-3
/* More images than this: the render never completes. */
#define IMAGES_MAX 100000

/* ---- the floor, its octree and atlas ---- */

static const float up[3] = {0, 1, 0};

/* One VDL straight up a lit leaf, its irradiance growing across the floor. */
static uint32_t fill_vdl(uint32_t i, uint32_t k, gb_light_octree_vdl *vdl)
{
    float e = 1.0f + 0.05f * (float)i + 0.03f * (float)k;
    vdl->irradiance[0] = vdl->irradiance[1] = vdl->irradiance[2] = e;
    vdl->direction = gb_photon_pack_direction(up);
    return 1;
}

static void build_floor(gb_scene *scene)
{
    floor_scene_begin(scene, up);
    const float sun[3] = {0.6f, -0.8f, 0.0f}, irradiance[3] = {2, 2, 2};
    add_point_light(scene, GB_LIGHT_DIRECTIONAL, NULL, sun, irradiance);
    scene_done(scene);
}

/* ---- driving the method as the renderer does ---- */

typedef struct rig {
    const gb_scene *scene;
    gb_renderer renderer;       /* its G-buffer, output and GPU scene */
    gb_bake *bake;              /* the octree, and the atlas of one chart */
    char atlas_paths[2][512];   /* the atlases of one chart and of two */
    gb_view view;
    gb_mat4 view_matrix, projection;
    uint32_t frame_index;
} rig;

/* The method's state, showing the floor through the atlas (atlas the
 * path) or by the walk ("none"); NULL with the reason printed. */
static void *create_state(const rig *r, const char *atlas)
{
    gb_method_parameters parameters = {.octree = {.atlas = atlas}};
    gb_indirect_setup setup = {
        .scene = r->scene, .gpu_scene = &r->renderer.gpu_scene,
        .shadows = &r->renderer.shadows, .bake = r->bake, .parameters = &parameters,
        .width = SIZE, .height = SIZE,
    };
    void *state = NULL;
    gb_error error;
    if (!succeeded(gb_octree_method.create(&setup, &state, &error), &error))
        return NULL;
    return state;
}

/* One image in parts, as the renderer draws it, read back into image (the
 * caller frees it); what draw returned at the last part, -1 when the parts
 * disagreed. */
static int draw_image(rig *r, void *state, double budget_ms, int parts, gb_image *image)
{
    gb_output *output = &r->renderer.output;
    gb_output_bind(output);
    gb_output_clear(output);
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glEnable(GL_SCISSOR_TEST);
    int more = 0, agreed = 1;
    for (int part = 0; part < parts; ++part) {
        int first = part * SIZE / parts, end = (part + 1) * SIZE / parts;
        glScissor(0, first, SIZE, end - first);
        gb_indirect_frame frame = {
            .gbuffer = &r->renderer.gbuffer, .shadows = &r->renderer.shadows,
            .view = &r->view, .view_matrix = &r->view_matrix, .projection = &r->projection,
            .width = SIZE, .height = SIZE, .frame_index = r->frame_index, .part = part,
            .parts = parts, .band = {first, end - first}, .budget_ms = budget_ms,
            .timings = &r->renderer.timings,
        };
        int said = gb_octree_method.draw(state, &frame) != 0;
        agreed &= part == 0 || said == more;
        more = said;
    }
    r->frame_index++;
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    gb_error error;
    if (!succeeded(gb_output_read(output, image, &error), &error))
        memset(image, 0, sizeof *image);
    return agreed ? more : -1;
}

static int same_image(const gb_image *a, const gb_image *b)
{
    return a->pixels && b->pixels && a->width == b->width && a->height == b->height &&
           memcmp(a->pixels, b->pixels,
                  (size_t)a->width * a->height * a->channels * sizeof *a->pixels) == 0;
}

/* The atlas texture of state, both layers (the caller frees it); its
 * float count into *count. */
static float *read_atlas(void *state, size_t *count)
{
    GLuint texture = gb_octree_atlas_texture(gb_octree_atlas_of(state));
    GLint width = 0, height = 0, layers = 0;
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_WIDTH, &width);
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_HEIGHT, &height);
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_DEPTH, &layers);
    *count = (size_t)width * height * layers * 4;
    float *texels = malloc(*count * sizeof *texels);
    if (texels)
        glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, (GLsizei)(*count * sizeof *texels),
                          texels);
    return texels;
}

/* ---- the tests ---- */

/* What the atlas of `charts` charts gives at once, and the walk's image. */
typedef struct whole {
    int charts;
    const char *path;
    float *atlas;               /* budget 0's atlas texture */
    size_t count;
    gb_image image;
    const gb_image *walk;
} whole;

/* what, after "N charts: " (a buffer of its own, until the next call). */
static const char *about(const whole *w, const char *what)
{
    static char message[256];
    snprintf(message, sizeof message, "%d chart%s: %s", w->charts, w->charts > 1 ? "s" : "",
             what);
    return message;
}

/* 3: the walk, in one part and in three. */
static void test_walk(rig *r, gb_image *walk)
{
    void *state = create_state(r, "none");
    if (!CHECK(state, "the walk created (--atlas none)"))
        return;
    gb_image parted;
    CHECK_EQ_INT(draw_image(r, state, 0.0, 1, walk), 0, "the walk: draw says 0");
    CHECK_EQ_INT(draw_image(r, state, 0.0, PARTS, &parted), 0, "the walk in parts: draw says 0");
    CHECK(same_image(walk, &parted), "the walk in three parts: the same bytes as in one");
    gb_image_free(&parted);
    gb_octree_method.destroy(state);
}

/* 1: the atlas at once. */
static void test_whole(rig *r, whole *w)
{
    void *state = create_state(r, w->path);
    if (!CHECK(state != NULL, about(w, "budget 0: the method created with the atlas")))
        return;
    CHECK(!gb_octree_atlas_complete(gb_octree_atlas_of(state)),
          about(w, "create renders nothing of the atlas"));
    CHECK(draw_image(r, state, 0.0, 1, &w->image) == 0,
          about(w, "budget 0: the first image completes the atlas and shows it (draw says 0)"));
    w->atlas = read_atlas(state, &w->count);
    size_t unfilled = 0;
    for (size_t i = 3; w->atlas && i < w->count; i += 4)
        unfilled += w->atlas[i] != 1.0f;
    printf("# %d chart(s): %zu texels in 2 layers, %zu unfilled\n", w->charts, w->count / 4,
           unfilled);
    if (w->charts == 1)
        CHECK(w->atlas && unfilled == 0, about(w, "budget 0: every texel of both layers filled"));
    gb_octree_method.destroy(state);
}

/* 2: a tiny budget. */
static void test_slices(rig *r, const whole *w)
{
    void *state = create_state(r, w->path);
    if (!CHECK(state != NULL, about(w, "budget 10^-3 ms: the method created with the atlas")))
        return;
    int images = 0, more = 1, not_walk = 0, disagreed = 0;
    gb_image image = {0};
    while (more && images < IMAGES_MAX) {
        gb_image_free(&image);
        more = draw_image(r, state, TINY_BUDGET_MS, PARTS, &image);
        disagreed += more < 0;
        not_walk += more && !same_image(&image, w->walk);
        ++images;
    }
    printf("# %d chart(s), budget %g ms, %d parts: the atlas complete at image %d\n",
           w->charts, TINY_BUDGET_MS, PARTS, images);
    CHECK(disagreed == 0, about(w, "every part of an image says the same"));
    CHECK(images > 2 * 2 * ATLAS_PADDING,
          about(w, "budget 10^-3 ms: the atlas takes many images (a slice each)"));
    CHECK(not_walk == 0,
          about(w, "while the atlas is incomplete: the walk's image, and draw says nonzero"));
    CHECK(more == 0 && same_image(&image, &w->image),
          about(w, "once draw says 0: budget 0's image, byte for byte"));
    size_t count = 0;
    float *atlas = read_atlas(state, &count);
    CHECK(atlas && w->atlas && count == w->count &&
              memcmp(atlas, w->atlas, count * sizeof *atlas) == 0,
          about(w, "the atlas in slices: byte-identical to the atlas at once"));
    free(atlas);
    gb_image again;
    CHECK(draw_image(r, state, TINY_BUDGET_MS, PARTS, &again) == 0 &&
              same_image(&again, &w->image),
          about(w, "the next image: the same, draw says 0"));
    gb_image_free(&again);
    gb_image_free(&image);
    gb_octree_method.destroy(state);
}

/* The floor's bake in a scratch folder (the atlas of two charts beside
 * it), a context and a renderer for its passes, the G-buffer drawn from
 * the floor's camera. */
static int rig_create(rig *r, const gb_scene *scene, const gb_light_octree *octree,
                      const gb_atlas *atlases[2], gb_context *context)
{
    memset(r, 0, sizeof *r);
    r->scene = scene;
    gb_error error;
    scratch_path_into("two-charts.atlas", r->atlas_paths[1], sizeof r->atlas_paths[1]);
    if (!floor_bake_open(scene, octree, atlases[0], r->atlas_paths[0], &r->bake) ||
        !succeeded(gb_atlas_write(r->atlas_paths[1], atlases[1], &error), &error) ||
        !succeeded(gb_context_create_headless(context, &error), &error))
        return 0;
    gb_renderer_options options = {.method = GB_METHOD_DIRECT, .terms = GB_TERMS_INDIRECT,
                                   .width = SIZE, .height = SIZE, .bake = r->bake};
    if (!succeeded(gb_renderer_create(scene, &options, &context->errors, &r->renderer, &error),
                   &error) ||
        !succeeded(gb_scene_view(scene, 0, &r->view, &error), &error))
        return 0;
    r->view_matrix = gb_view_matrix(&r->view);
    r->projection = gb_view_projection(&r->view, SIZE, SIZE);
    gb_gbuffer_draw(&r->renderer.gbuffer, &r->renderer.gpu_scene, &r->view_matrix,
                    &r->projection);
    return 1;
}

int main(void)
{
    gb_scene scene;
    build_floor(&scene);
    floor_octree *h = calloc(1, sizeof *h);
    if (!CHECK(h, "memory for the octree"))
        return tap_done();
    floor_octree_punch_holes(h);
    gb_light_octree octree;
    floor_octree_make(h, up, 1, fill_vdl, &scene, &octree);
    floor_atlas one, two;
    floor_atlas_make(&scene, ATLAS_SQUARE, ATLAS_PADDING, 1, &one);
    floor_atlas_make(&scene, ATLAS_SQUARE, ATLAS_PADDING, 2, &two);
    const gb_atlas *atlases[2] = {&one.atlas, &two.atlas};
    scratch_create("octree-atlas-slices");
    gb_context context;
    memset(&context, 0, sizeof context);
    rig r;
    if (CHECK(rig_create(&r, &scene, &octree, atlases, &context),
              "the floor's bake, a headless context and the passes")) {
        gb_image walk = {0};
        test_walk(&r, &walk);
        for (int charts = 1; charts <= 2; ++charts) {
            whole w = {.charts = charts, .path = r.atlas_paths[charts - 1], .walk = &walk};
            test_whole(&r, &w);
            test_slices(&r, &w);
            free(w.atlas);
            gb_image_free(&w.image);
        }
        gb_image_free(&walk);
        gb_error error;
        CHECK(succeeded(gb_gl_check(&context.errors, "slices", &error), &error), "no GL error");
    }
    gb_renderer_destroy(&r.renderer);
    gb_context_destroy(&context);
    gb_bake_release(r.bake);
    scratch_remove();
    free(h);
    gb_scene_free(&scene);
    return tap_done();
}
