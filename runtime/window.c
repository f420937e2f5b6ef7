#include "window.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include <GLFW/glfw3.h>

#include "context.h"
#include "progress.h"

typedef struct window_state {
    const gb_scene *scene;
    const gb_window_options *options;
    GLFWwindow *window;
    gb_renderer renderer;
    gb_view view;
    uint32_t camera;
    float speed;                /* world units per second */
    double last_x, last_y;
    int dragging;
    int screenshot_requested;
    unsigned screenshot_count;
    double last_title_time;
} window_state;

static void report(window_state *s, const char *message)
{
    if (s->options->report)
        s->options->report(s->options->report_user, message);
}

static void switch_method(window_state *s)
{
    gb_method next = gb_method_next(s->renderer.options.method);
    gb_error error;
    if (next == s->renderer.options.method ||
        gb_renderer_set_method(&s->renderer, next, &error) != GB_OK)
        report(s, "no other GI method is available in this build");
}

static void switch_camera(window_state *s)
{
    gb_error error;
    uint32_t next = (s->camera + 1) % s->scene->camera_count;
    if (gb_scene_view(s->scene, next, &s->view, &error) == GB_OK)
        s->camera = next;
    else
        report(s, error.message);
}

static void on_key(GLFWwindow *window, int key, int scancode, int action, int mods)
{
    (void)scancode, (void)mods;
    window_state *s = glfwGetWindowUserPointer(window);
    if (action != GLFW_PRESS)
        return;
    if (key == GLFW_KEY_ESCAPE)
        glfwSetWindowShouldClose(window, GLFW_TRUE);
    else if (key == GLFW_KEY_M)
        switch_method(s);
    else if (key == GLFW_KEY_T)
        gb_renderer_set_terms(&s->renderer,
                              (gb_terms)((s->renderer.options.terms + 1) % GB_TERMS_COUNT));
    else if (key == GLFW_KEY_C)
        switch_camera(s);
    else if (key == GLFW_KEY_F12 || key == GLFW_KEY_P)
        s->screenshot_requested = 1;
}

static void on_mouse_button(GLFWwindow *window, int button, int action, int mods)
{
    (void)mods;
    window_state *s = glfwGetWindowUserPointer(window);
    if (button != GLFW_MOUSE_BUTTON_LEFT)
        return;
    s->dragging = action == GLFW_PRESS;
    glfwGetCursorPos(window, &s->last_x, &s->last_y);
}

static void on_cursor(GLFWwindow *window, double x, double y)
{
    window_state *s = glfwGetWindowUserPointer(window);
    if (!s->dragging)
        return;
    const float radians_per_pixel = 0.004f;
    gb_view_turn(&s->view, -(float)(x - s->last_x) * radians_per_pixel,
                 -(float)(y - s->last_y) * radians_per_pixel);
    s->last_x = x;
    s->last_y = y;
}

static float key_axis(GLFWwindow *window, int positive, int negative)
{
    return (float)(glfwGetKey(window, positive) == GLFW_PRESS) -
           (float)(glfwGetKey(window, negative) == GLFW_PRESS);
}

static void fly(window_state *s, double seconds)
{
    GLFWwindow *w = s->window;
    float step = s->speed * (float)seconds;
    if (glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS)
        step *= 5.0f;
    gb_view_move(&s->view, step * key_axis(w, GLFW_KEY_W, GLFW_KEY_S),
                 step * key_axis(w, GLFW_KEY_D, GLFW_KEY_A),
                 step * key_axis(w, GLFW_KEY_E, GLFW_KEY_Q));
}

static void save_screenshot(window_state *s)
{
    char path[1024], message[1200];
    if (s->options->screenshot_path)
        snprintf(path, sizeof path, "%s", s->options->screenshot_path);
    else
        snprintf(path, sizeof path, "gbview-%03u.png", s->screenshot_count);
    ++s->screenshot_count;
    gb_image image;
    gb_error error;
    gb_result result = gb_renderer_read(&s->renderer, &image, &error);
    if (result == GB_OK) {
        result = gb_image_write(path, &image, &error);
        gb_image_free(&image);
    }
    if (result == GB_OK)
        snprintf(message, sizeof message, "screenshot: %s", path);
    else
        snprintf(message, sizeof message, "screenshot: %s", error.message);
    report(s, message);
}

static void update_title(window_state *s)
{
    double now = gb_seconds();
    if (now - s->last_title_time < 0.5)
        return;
    s->last_title_time = now;
    char times[256], title[512];
    gb_timings_format_last(&s->renderer.timings, times, sizeof times);
    snprintf(title, sizeof title, "gbview %s - %s - %s - %s", s->options->title,
             gb_method_name(s->renderer.options.method),
             gb_terms_name(s->renderer.options.terms), times);
    glfwSetWindowTitle(s->window, title);
}

static gb_result follow_window_size(window_state *s, int *width, int *height, gb_error *error)
{
    glfwGetFramebufferSize(s->window, width, height);
    if (*width <= 0 || *height <= 0)
        return GB_OK;   /* minimised */
    return gb_renderer_resize(&s->renderer, *width, *height, error);
}

static gb_result run_frames(window_state *s, gb_error *error)
{
    double previous = gb_seconds();
    gb_result result = GB_OK;
    for (int frame = 0; result == GB_OK && !glfwWindowShouldClose(s->window); ++frame) {
        if (s->options->frames > 0 && frame >= s->options->frames)
            break;
        glfwPollEvents();
        double now = gb_seconds();
        fly(s, now - previous);
        previous = now;
        int width, height;
        result = follow_window_size(s, &width, &height, error);
        if (result != GB_OK || width <= 0 || height <= 0)
            continue;
        gb_renderer_draw(&s->renderer, &s->view);
        gb_renderer_present(&s->renderer, width, height);
        result = gb_renderer_finish_frame(&s->renderer, error);
        if (frame + 1 == s->options->frames && s->options->screenshot_path)
            s->screenshot_requested = 1;
        if (result == GB_OK && s->screenshot_requested) {
            s->screenshot_requested = 0;
            save_screenshot(s);
        }
        glfwSwapBuffers(s->window);
        update_title(s);
    }
    return result;
}

static void install_callbacks(window_state *s)
{
    glfwSetWindowUserPointer(s->window, s);
    glfwSetKeyCallback(s->window, on_key);
    glfwSetMouseButtonCallback(s->window, on_mouse_button);
    glfwSetCursorPosCallback(s->window, on_cursor);
}

static float scene_diagonal(const gb_scene *scene)
{
    float sum = 0.0f;
    for (int c = 0; c < 3; ++c) {
        float d = scene->bounds_max[c] - scene->bounds_min[c];
        sum += d * d;
    }
    return sqrtf(sum);
}

gb_result gb_run_window(const gb_scene *scene, const gb_window_options *options,
                        gb_timings *timings, gb_error *error)
{
    window_state s;
    memset(&s, 0, sizeof s);
    s.scene = scene;
    s.options = options;
    s.camera = options->camera;
    s.speed = 0.25f * scene_diagonal(scene);
    gb_result result = gb_scene_view(scene, options->camera, &s.view, error);
    if (result != GB_OK)
        return result;
    gb_renderer_options renderer_options = options->renderer;
    if (renderer_options.width <= 0 || renderer_options.height <= 0) {
        renderer_options.width = scene->cameras[options->camera].width;
        renderer_options.height = scene->cameras[options->camera].height;
    }
    gb_context context;
    result = gb_context_create_window(&context, "gbview", renderer_options.width,
                                      renderer_options.height, error);
    if (result != GB_OK)
        return result;
    s.window = context.window;
    result = gb_renderer_create(scene, &renderer_options, &context.errors, &s.renderer, error);
    if (result == GB_OK) {
        install_callbacks(&s);
        result = run_frames(&s, error);
    }
    if (timings) {
        *timings = s.renderer.timings;
        memset(timings->queries, 0, sizeof timings->queries);
    }
    gb_renderer_destroy(&s.renderer);
    gb_context_destroy(&context);
    return result;
}
