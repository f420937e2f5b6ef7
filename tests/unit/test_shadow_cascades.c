/* test_shadow_cascades — the cascades of a directional light's shadow map
 * (runtime/shadow_cascades.h) against what they must hold, checked point
 * by point: the splits of the practical scheme, each slice of the view
 * inside its map, every occluder of the scene within its depth range, and
 * texels that neither resize nor slide as the eye turns and moves. */
#include <math.h>
#include <string.h>

#include "../../runtime/shadow_cascades.h"
#include "tap.h"

static gb_scene box_scene(void)
{
    gb_scene scene;
    memset(&scene, 0, sizeof scene);
    float low[3] = {-10, 0, -6}, high[3] = {12, 8, 6};
    memcpy(scene.bounds_min, low, sizeof low);
    memcpy(scene.bounds_max, high, sizeof high);
    return scene;
}

static gb_view eye_at(gb_vec3 position, gb_vec3 forward)
{
    gb_view view = {.position = position, .fov_y = 60.0f, .near = 0.05f};
    view.forward = gb_vec3_normalize(forward);
    view.world_up = gb_vec3_make(0, 1, 0);
    view.right = gb_vec3_normalize(gb_vec3_cross(view.forward, view.world_up));
    view.up = gb_vec3_cross(view.right, view.forward);
    return view;
}

static void test_splits(void)
{
    float s[GB_SHADOW_CASCADES + 1];
    gb_cascade_splits(0.1f, 100.0f, GB_SHADOW_CASCADES, 1.0f, s);
    int geometric = 1;
    for (int i = 1; i < GB_SHADOW_CASCADES; ++i)
        geometric &= fabsf(s[i] * s[i] - s[i - 1] * s[i + 1]) < 1e-3f * s[i] * s[i];
    CHECK(geometric, "splits, logarithmic: each the geometric mean of its neighbours");
    gb_cascade_splits(0.1f, 100.0f, GB_SHADOW_CASCADES, 0.0f, s);
    CHECK_NEAR(s[1] - s[0], (100.0f - 0.1f) / GB_SHADOW_CASCADES, 1e-3, "splits, uniform: equal");
    gb_cascade_splits(0.1f, 100.0f, GB_SHADOW_CASCADES, GB_CASCADE_LOG_SHARE, s);
    int increasing = s[0] == 0.1f && s[GB_SHADOW_CASCADES] == 100.0f;
    for (int i = 0; i < GB_SHADOW_CASCADES; ++i)
        increasing &= s[i] < s[i + 1];
    CHECK(increasing, "splits, mixed: from near to far, increasing");
}

/* The slice's corners, built here from the field of view. */
static void corners_of(const gb_view *view, float aspect, float z0, float z1, gb_vec3 out[8])
{
    float t = tanf(0.5f * view->fov_y * 3.14159265f / 180.0f);
    for (int k = 0; k < 8; ++k) {
        float z = k & 4 ? z1 : z0;
        gb_vec3 p = gb_vec3_madd(view->position, view->forward, z);
        p = gb_vec3_madd(p, view->right, (k & 1 ? 1.0f : -1.0f) * z * t * aspect);
        out[k] = gb_vec3_madd(p, view->up, (k & 2 ? 1.0f : -1.0f) * z * t);
    }
}

static void test_coverage(void)
{
    gb_scene scene = box_scene();
    gb_view view = eye_at(gb_vec3_make(-8, 2, 1), gb_vec3_make(1, 0.2f, -0.3f));
    gb_vec3 sun = gb_vec3_make(-0.25f, -1.0f, -0.3f);
    float far = gb_cascade_view_far(&view, &scene), s[GB_SHADOW_CASCADES + 1];
    CHECK(far > 19.0f && far < 25.0f, "the view's far: the farthest corner's depth");
    gb_cascade_splits(view.near, far, GB_SHADOW_CASCADES, GB_CASCADE_LOG_SHARE, s);
    int inside = 1, occluders = 1;
    for (int c = 0; c < GB_SHADOW_CASCADES; ++c) {
        gb_cascade k = gb_cascade_fit(&view, 16.0f / 9.0f, s[c], s[c + 1], sun, &scene, 1024);
        gb_vec3 corners[8];
        corners_of(&view, 16.0f / 9.0f, s[c], s[c + 1], corners);
        for (int i = 0; i < 8; ++i) {
            gb_vec3 p = gb_mat4_transform_point(&k.world_to_clip, corners[i]);
            inside &= fabsf(p.x) <= 1.0f && fabsf(p.y) <= 1.0f;
        }
        for (int i = 0; i < 8; ++i) {
            gb_vec3 b = gb_vec3_make(i & 1 ? scene.bounds_max[0] : scene.bounds_min[0],
                                     i & 2 ? scene.bounds_max[1] : scene.bounds_min[1],
                                     i & 4 ? scene.bounds_max[2] : scene.bounds_min[2]);
            gb_vec3 p = gb_mat4_transform_point(&k.world_to_clip, b);
            occluders &= p.z > 0.0f && p.z < 1.0f;
        }
        /* the map's world width over its texels: a unit step across the
           light moves 2 / width in clip x and y (the map is square) */
        gb_vec3 a = gb_mat4_transform_point(&k.world_to_clip, corners[0]);
        gb_vec3 across = gb_vec3_normalize(gb_vec3_cross(sun, gb_vec3_make(0.3f, 0.2f, 0.9f)));
        gb_vec3 b = gb_mat4_transform_point(&k.world_to_clip, gb_vec3_add(corners[0], across));
        float world_width = 2.0f / hypotf(b.x - a.x, b.y - a.y);
        CHECK_NEAR(k.texel, world_width / 1024.0f, 1e-3f * k.texel, "a cascade's texel: its width / size");
        CHECK_NEAR(k.far, s[c + 1], 1e-6, "a cascade ends at its split");
    }
    CHECK(inside, "every slice's corners inside its cascade");
    CHECK(occluders, "every corner of the scene within each cascade's depth range");
}

/* Turning keeps the texel's size; moving keeps a world point on the same
 * place within its texel. */
static void test_stability(void)
{
    gb_scene scene = box_scene();
    gb_vec3 sun = gb_vec3_make(-0.25f, -1.0f, -0.3f), point = gb_vec3_make(1.3f, 0.7f, -2.1f);
    gb_view a = eye_at(gb_vec3_make(-8, 2, 1), gb_vec3_make(1, 0.2f, -0.3f));
    gb_view turned = eye_at(a.position, gb_vec3_make(0.3f, -0.1f, 1));
    gb_cascade ka = gb_cascade_fit(&a, 1.5f, 2.0f, 6.0f, sun, &scene, 1024);
    gb_cascade kt = gb_cascade_fit(&turned, 1.5f, 2.0f, 6.0f, sun, &scene, 1024);
    CHECK_NEAR(kt.texel, ka.texel, 1e-5f * ka.texel, "turning the eye keeps the texel size");
    double worst = 0.0;
    for (int step = 1; step <= 8; ++step) {
        gb_view moved = a;
        moved.position = gb_vec3_add(a.position, gb_vec3_make(0.013f * step, 0.007f * step, -0.011f * step));
        gb_cascade km = gb_cascade_fit(&moved, 1.5f, 2.0f, 6.0f, sun, &scene, 1024);
        float xa = 0.5f * (gb_mat4_transform_point(&ka.world_to_clip, point).x + 1.0f) * 1024.0f;
        float xm = 0.5f * (gb_mat4_transform_point(&km.world_to_clip, point).x + 1.0f) * 1024.0f;
        double shift = xm - xa;
        worst = fmax(worst, fabs(shift - round(shift)));
    }
    CHECK_NEAR(worst, 0.0, 0.02, "moving the eye shifts the map by whole texels");
}

int main(void)
{
    test_splits();
    test_coverage();
    test_stability();
    return tap_done();
}
