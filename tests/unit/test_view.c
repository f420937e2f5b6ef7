/* test_view — the window's camera moves (runtime/view.h): the fly step's
 * cap, the orbit that keeps its pivot in place, and the bookmark line that
 * the scene file reads back as the same view. */
#include <stdio.h>
#include <string.h>

#include "../../runtime/view.h"
#include "scene_file.h"
#include "tap.h"

/* pivot in the view's own frame: right, up, forward coordinates. */
static gb_vec3 in_view(const gb_view *view, gb_vec3 pivot)
{
    gb_vec3 d = gb_vec3_sub(pivot, view->position);
    return gb_vec3_make(gb_vec3_dot(d, view->right), gb_vec3_dot(d, view->up),
                        gb_vec3_dot(d, view->forward));
}

static void check_steps(void)
{
    CHECK_NEAR(gb_view_step_length(10.0f, 0.05), 0.5, 1e-6, "a short frame: speed x time");
    CHECK_NEAR(gb_view_step_length(10.0f, 5.0), 10.0 * GB_VIEW_LONGEST_STEP_SECONDS, 1e-6,
               "a 5 s frame: no longer than speed x the longest step");
    CHECK_NEAR(gb_view_step_length(10.0f, -1.0), 0.0, 0.0, "a clock going back: no step");
}

static gb_view test_view(void)
{
    gb_camera camera = {.position = {1, 2, 3}, .target = {4, 2, 7}, .up = {0, 1, 0},
                        .fov_y = 45.0f, .width = 64, .height = 48};
    gb_view view;
    gb_error error;
    gb_view_from_camera(&camera, 10.0f, &view, &error);
    return view;
}

static void check_orbit(void)
{
    gb_view view = test_view();
    gb_vec3 pivot = gb_vec3_make(2.5f, 1.0f, 6.0f);   /* off the view's axis */
    gb_vec3 before = in_view(&view, pivot);
    gb_view_orbit(&view, pivot, 0.3f, -0.2f);
    gb_vec3 after = in_view(&view, pivot);
    CHECK_NEAR(after.x, before.x, 1e-4, "orbit: the pivot keeps its place across the image");
    CHECK_NEAR(after.y, before.y, 1e-4, "orbit: ... and up it");
    CHECK_NEAR(after.z, before.z, 1e-4, "orbit: ... and its depth");
    gb_view start = test_view();
    CHECK(gb_vec3_length(gb_vec3_sub(view.position, start.position)) > 0.1f,
          "orbit: the eye moved");
    CHECK_NEAR(gb_vec3_dot(view.forward, start.forward), cosf(0.3f) * cosf(0.2f), 0.02,
               "orbit: the view turned by the yaw and the pitch");
}

static void check_bookmark(void)
{
    gb_view view = test_view();
    gb_view_turn(&view, 0.7f, 0.1f);
    gb_view_move(&view, 0.5f, -0.25f, 0.125f);
    char line[512], text[700];
    gb_view_camera_line(&view, 320, 200, line, sizeof line);
    snprintf(text, sizeof text, "gibake-scene 1\nmesh m.obj\n%s\n", line);
    gb_scene_file file;
    gb_error error;
    int parsed = gb_scene_file_parse(text, strlen(text), "bookmark", &file, &error) == GB_OK;
    CHECK(parsed, "the bookmark line is a camera the scene file reads");
    if (!parsed) {
        printf("# %s\n", error.message);
        return;
    }
    gb_view back;
    gb_view_from_camera(&file.cameras[0], 10.0f, &back, &error);
    CHECK(gb_vec3_length(gb_vec3_sub(back.position, view.position)) < 1e-5f,
          "read back: the same position");
    CHECK(gb_vec3_dot(back.forward, view.forward) > 1.0f - 1e-6f, "read back: the same direction");
    CHECK_NEAR(back.fov_y, view.fov_y, 1e-5, "read back: the same field of view");
    CHECK(file.cameras[0].width == 320 && file.cameras[0].height == 200,
          "read back: the resolution");
    gb_scene_file_free(&file);
}

int main(void)
{
    check_steps();
    check_orbit();
    check_bookmark();
    return tap_done();
}
