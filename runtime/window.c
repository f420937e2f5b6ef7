#include "window.h"

#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>

#include <GLFW/glfw3.h>

#include "context.h"
#include "hud.h"
#include "method_cycle.h"
#include "progress.h"
#include "screenshot_path.h"

/* How long an idle window sleeps between looks at SIGINT, seconds. */
static const double IDLE_WAIT_SECONDS = 0.25;
/* ... and while a method's setup runs, between looks at its progress. */
static const double SETUP_WAIT_SECONDS = 0.1;
static const float RADIANS_PER_PIXEL = 0.004f;
static const float WHEEL_SPEED_FACTOR = 1.25f;

static volatile sig_atomic_t interrupted;

static void on_interrupt(int signal)
{
    (void)signal;
    interrupted = 1;
}

typedef struct window_state {
    const gb_scene *scene;
    const gb_window_options *options;
    GLFWwindow *window;
    gb_renderer renderer;
    gb_method_cycle cycle;
    gb_view view;
    uint32_t camera;
    float speed;                /* world units per second */
    double last_x, last_y;      /* the cursor's last position, window pixels */
    int dragging;               /* GLFW_MOUSE_BUTTON_LEFT (look) or _RIGHT (orbit), or -1 */
    gb_vec3 pivot;              /* of the orbit */
    int screenshot_requested;
    unsigned screenshot_next;
    int redraw;                 /* present again: exposed, resized, a key's effect */
    double input_time;          /* the first input since the last present, or 0 */
    uint32_t frames;            /* that drew */
    double start_time;          /* the window's creation, gb_seconds() */
    int quit_told;
    gb_hud hud;
    int hud_hidden, keys_shown;
    char hud_text[768];         /* as last presented */
    double frame_seconds;       /* between frames that drew, a running mean */
} window_state;

static void report(window_state *s, const char *message)
{
    if (s->options->report)
        s->options->report(s->options->report_user, message);
}

static void report_to(void *user, const char *message)
{
    report(user, message);
}

/* A method's setup runs on its thread: the window shows its progress. */
static int setting_up(const window_state *s)
{
    return s->renderer.status.setup_fraction >= 0.0;
}

/* An input arrived: the latency of the next present counts from here. */
static void note_input(window_state *s)
{
    if (s->input_time == 0.0)
        s->input_time = gb_seconds();
    s->redraw = 1;
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

static void print_bookmark(window_state *s)
{
    char line[512];
    gb_view_camera_line(&s->view, s->renderer.options.width, s->renderer.options.height, line,
                        sizeof line);
    report(s, line);
}

static void toggle_keys(window_state *s)
{
    s->keys_shown = !s->keys_shown;
    if (s->options->log_frames)
        report(s, s->keys_shown ? "keys shown" : "keys hidden");
}

static void on_key(GLFWwindow *window, int key, int scancode, int action, int mods)
{
    (void)scancode, (void)mods;
    window_state *s = glfwGetWindowUserPointer(window);
    if (action != GLFW_PRESS)
        return;
    note_input(s);
    if (key == GLFW_KEY_ESCAPE)
        glfwSetWindowShouldClose(window, GLFW_TRUE);
    else if (key == GLFW_KEY_M)
        gb_method_cycle_next(&s->cycle, &s->renderer, report_to, s);
    else if (key == GLFW_KEY_T)
        gb_renderer_set_terms(&s->renderer,
                              (gb_terms)((s->renderer.options.terms + 1) % GB_TERMS_COUNT));
    else if (key == GLFW_KEY_C)
        switch_camera(s);
    else if (key == GLFW_KEY_B)
        print_bookmark(s);
    else if (key == GLFW_KEY_H)
        toggle_keys(s);
    else if (key == GLFW_KEY_F1)
        s->hud_hidden = !s->hud_hidden;
    else if (key == GLFW_KEY_F12 || key == GLFW_KEY_P)
        s->screenshot_requested = 1;
}

/* The point the cursor shows, or the scene's centre where it shows none. */
static gb_vec3 point_under_cursor(window_state *s)
{
    int width, height;
    glfwGetWindowSize(s->window, &width, &height);
    gb_vec3 point;
    if (width > 0 && height > 0 &&
        gb_renderer_point_at(&s->renderer, &s->view, (float)(s->last_x / width),
                             (float)(s->last_y / height), &point))
        return point;
    const float *lo = s->scene->bounds_min, *hi = s->scene->bounds_max;
    return gb_vec3_make(0.5f * (lo[0] + hi[0]), 0.5f * (lo[1] + hi[1]), 0.5f * (lo[2] + hi[2]));
}

static void on_mouse_button(GLFWwindow *window, int button, int action, int mods)
{
    (void)mods;
    window_state *s = glfwGetWindowUserPointer(window);
    if (button != GLFW_MOUSE_BUTTON_LEFT && button != GLFW_MOUSE_BUTTON_RIGHT)
        return;
    if (action == GLFW_RELEASE) {
        if (button == s->dragging)
            s->dragging = -1;
        return;
    }
    s->dragging = button;
    if (button == GLFW_MOUSE_BUTTON_RIGHT)
        s->pivot = point_under_cursor(s);
}

static void on_cursor(GLFWwindow *window, double x, double y)
{
    window_state *s = glfwGetWindowUserPointer(window);
    if (s->dragging < 0) {  /* where a drag starts: the events' own positions,
                               not the pointer's now, which may be further */
        s->last_x = x;
        s->last_y = y;
        return;
    }
    float yaw = -(float)(x - s->last_x) * RADIANS_PER_PIXEL;
    float pitch = -(float)(y - s->last_y) * RADIANS_PER_PIXEL;
    if (s->dragging == GLFW_MOUSE_BUTTON_RIGHT)
        gb_view_orbit(&s->view, s->pivot, yaw, pitch);
    else
        gb_view_turn(&s->view, yaw, pitch);
    s->last_x = x;
    s->last_y = y;
    note_input(s);
}

static void on_scroll(GLFWwindow *window, double dx, double dy)
{
    (void)dx;
    window_state *s = glfwGetWindowUserPointer(window);
    s->speed *= powf(WHEEL_SPEED_FACTOR, (float)dy);
    note_input(s);
}

static void on_refresh(GLFWwindow *window)
{
    window_state *s = glfwGetWindowUserPointer(window);
    s->redraw = 1;
}

static float key_axis(GLFWwindow *window, int positive, int negative)
{
    return (float)(glfwGetKey(window, positive) == GLFW_PRESS) -
           (float)(glfwGetKey(window, negative) == GLFW_PRESS);
}

/* Moves the view by the keys held over seconds (at most a capped step). */
static void fly(window_state *s, double seconds)
{
    GLFWwindow *w = s->window;
    float forward = key_axis(w, GLFW_KEY_W, GLFW_KEY_S), right = key_axis(w, GLFW_KEY_D, GLFW_KEY_A),
          up = key_axis(w, GLFW_KEY_E, GLFW_KEY_Q);
    if (forward == 0.0f && right == 0.0f && up == 0.0f)
        return;
    float step = gb_view_step_length(s->speed, seconds);
    if (glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS)
        step *= 5.0f;
    gb_view_move(&s->view, step * forward, step * right, step * up);
    note_input(s);
}

static void save_screenshot(window_state *s, const char *path)
{
    char message[1200];
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

static void take_screenshot(window_state *s)
{
    char path[1024];
    gb_error error;
    const char *base = s->options->screenshot_path ? s->options->screenshot_path : "gbview.png";
    if (gb_screenshot_path(base, &s->screenshot_next, path, sizeof path, &error) == GB_OK)
        save_screenshot(s, path);
    else
        report(s, error.message);
}

static void update_title(window_state *s)
{
    char title[512];
    snprintf(title, sizeof title, "gbview %s - %s - %s", s->options->title,
             gb_method_name(s->renderer.options.method),
             gb_terms_name(s->renderer.options.terms));
    glfwSetWindowTitle(s->window, title);
}

/* With log_frames, a line a frame that drew: bench/viewer.sh and the
 * window test read them. latency: from the first input the frame answers to
 * its image on screen. */
static void log_frame(window_state *s, int moving, int presented, double now)
{
    if (!s->options->log_frames)
        return;
    const gb_renderer_status *st = &s->renderer.status;
    char line[256];
    snprintf(line, sizeof line,
             "frame %u: %.1f ms, t %.3f s, 1/%d, part %d/%d, images %u%s%s%s", s->frames,
             s->renderer.timings.last_frame_wall_ms, now - s->start_time, st->divisor,
             st->part, st->parts, st->images, moving ? ", moving" : "",
             st->converged && !setting_up(s) ? ", final" : "", presented ? ", presented" : "");
    if (setting_up(s))
        snprintf(line + strlen(line), sizeof line - strlen(line), ", setup %.0f %%",
                 100.0 * st->setup_fraction);
    if (presented && s->input_time > 0.0)
        snprintf(line + strlen(line), sizeof line - strlen(line), ", latency %.1f ms",
                 1e3 * (now - s->input_time));
    report(s, line);
}

static const char keys_text[] =
    "left button: look      right button: orbit\n"
    "W A S D Q E: fly       Shift: 5x   wheel: speed\n"
    "M: method   T: terms   C: camera\n"
    "B: print the view as a .scene camera line\n"
    "P, F12: screenshot     F1: HUD   H: these keys\n"
    "Esc: quit";

/* Where the image is: refining it, moving, final. */
static void describe_image(const window_state *s, char *text, size_t size)
{
    const gb_renderer_status *st = &s->renderer.status;
    if (s->renderer.options.budget_ms <= 0.0)
        snprintf(text, size, "whole frames (--budget 0)");
    else if (st->converged && !setting_up(s))
        snprintf(text, size, "final%s", st->images > 1 ? " (samples)" : "");
    else if (st->converged)
        snprintf(text, size, "direct light, final");
    else if (st->provisional)
        snprintf(text, size, "a stand-in while the method's setup goes on");
    else if (st->parts > 1)
        snprintf(text, size, "1/%d shown; drawing part %d/%d", st->divisor, st->part, st->parts);
    else if (st->images > 0)
        snprintf(text, size, "refining: %u images", st->images);
    else
        snprintf(text, size, "1/%d resolution", st->divisor);
}

static void make_hud_text(const window_state *s, char *text, size_t size)
{
    char image[128];
    describe_image(s, image, sizeof image);
    const gb_renderer *r = &s->renderer;
    gb_vec3 eye = s->view.position;
    char setup[96] = "";
    if (setting_up(s))
        snprintf(setup, sizeof setup, "\n%s: setting up, %.0f %% (direct light meanwhile)",
                 gb_method_name(r->options.method), 100.0 * r->status.setup_fraction);
    char passes[256];
    gb_timings_format_last(&r->timings, passes, sizeof passes);
    snprintf(text, size,
             "%s - %s%s\n%.1f fps, budget %.0f ms; last frame: %s\n%s\n"
             "eye %.4g %.4g %.4g, speed %.3g\nH: keys",
             gb_method_name(r->options.method), gb_terms_name(r->options.terms), setup,
             s->frame_seconds > 0.0 ? 1.0 / s->frame_seconds : 0.0, r->options.budget_ms,
             passes, image, eye.x, eye.y, eye.z, s->speed);
}

/* The HUD's text changed since it was last shown. */
static int hud_changed(window_state *s)
{
    char text[sizeof s->hud_text];
    make_hud_text(s, text, sizeof text);
    if (s->hud_hidden || strcmp(text, s->hud_text) == 0)
        return 0;
    memcpy(s->hud_text, text, sizeof text);
    return 1;
}

static void present(window_state *s, int width, int height)
{
    gb_renderer_present(&s->renderer, width, height);
    if (!s->hud_hidden) {
        make_hud_text(s, s->hud_text, sizeof s->hud_text);
        gb_hud_draw(&s->hud, s->hud_text, GB_HUD_TOP_LEFT, width, height);
    }
    if (s->keys_shown)
        gb_hud_draw(&s->hud, keys_text, GB_HUD_BOTTOM_LEFT, width, height);
    glfwSwapBuffers(s->window);
    glFinish();
    s->redraw = 0;
    update_title(s);
}

/* Draws toward the image: its next parts to the budget, or a whole image
 * with --budget 0. *changed when the image to show changed. */
static gb_result draw(window_state *s, int *changed, gb_error *error)
{
    if (s->renderer.options.budget_ms > 0.0)
        return gb_renderer_refine(&s->renderer, &s->view, changed, error);
    gb_renderer_draw(&s->renderer, &s->view);
    *changed = 1;
    return GB_OK;
}

/* Waits for input when there is nothing to draw, else only looks. */
static void wait_or_poll(window_state *s)
{
    if (s->renderer.status.converged && !s->redraw)
        glfwWaitEventsTimeout(setting_up(s) ? SETUP_WAIT_SECONDS : IDLE_WAIT_SECONDS);
    else
        glfwPollEvents();
    if (interrupted)
        glfwSetWindowShouldClose(s->window, GLFW_TRUE);
    if (glfwWindowShouldClose(s->window) && !s->quit_told && s->options->log_frames) {
        report(s, "quit asked");
        s->quit_told = 1;
    }
}

/* --frames K: K images, or a final one, of the method itself (not the
 * direct light shown while its setup runs). */
static int done(const window_state *s)
{
    const gb_renderer_status *st = &s->renderer.status;
    return s->options->frames > 0 && !setting_up(s) &&
           (st->images >= (uint32_t)s->options->frames || st->converged);
}

/* Nonzero when refine has nothing to draw: the image is final and neither
 * the view nor anything else asked for another. */
static int idle(const window_state *s, int moving)
{
    return s->renderer.status.converged && !s->renderer.restart && !moving;
}


/* One turn of the loop: input, then the next slice of the image, shown when
 * it changed. */
static gb_result run_frame(window_state *s, double seconds, gb_error *error)
{
    fly(s, seconds);
    int width, height, changed = 0;
    glfwGetFramebufferSize(s->window, &width, &height);
    if (width <= 0 || height <= 0)
        return GB_OK;   /* minimised */
    gb_result result = gb_renderer_resize(&s->renderer, width, height, error);
    if (result == GB_OK)
        result = gb_renderer_poll_setup(&s->renderer, error);
    int moving = memcmp(&s->view, &s->renderer.view, sizeof s->view) != 0;
    int drawing = result == GB_OK && !idle(s, moving);
    if (drawing)
        result = draw(s, &changed, error);
    if (drawing && result == GB_OK)
        result = gb_renderer_finish_frame(&s->renderer, error);
    int presented = result == GB_OK && (changed || s->redraw || hud_changed(s));
    if (presented)
        present(s, width, height);
    if (drawing) {
        log_frame(s, moving, presented, gb_seconds());
        s->frame_seconds += 0.1 * (seconds - s->frame_seconds);
    }
    s->frames += drawing;
    if (presented)
        s->input_time = 0.0;
    if (result == GB_OK && s->screenshot_requested) {
        s->screenshot_requested = 0;
        take_screenshot(s);
    }
    return result;
}

static gb_result run_frames(window_state *s, gb_error *error)
{
    double previous = gb_seconds();
    gb_result result = GB_OK;
    while (result == GB_OK && !done(s)) {
        wait_or_poll(s);
        if (glfwWindowShouldClose(s->window))
            break;
        double now = gb_seconds();
        result = run_frame(s, now - previous, error);
        previous = now;
    }
    if (result == GB_OK && done(s) && s->options->screenshot_path)
        save_screenshot(s, s->options->screenshot_path);
    return result;
}

static void install_callbacks(window_state *s)
{
    glfwSetWindowUserPointer(s->window, s);
    glfwSetKeyCallback(s->window, on_key);
    glfwSetMouseButtonCallback(s->window, on_mouse_button);
    glfwSetCursorPosCallback(s->window, on_cursor);
    glfwSetScrollCallback(s->window, on_scroll);
    glfwSetWindowRefreshCallback(s->window, on_refresh);
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
    s.dragging = -1;
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
    s.start_time = gb_seconds();
    interrupted = 0;
    void (*previous_handler)(int) = signal(SIGINT, on_interrupt);
    result = gb_renderer_create(scene, &renderer_options, &context.errors, &s.renderer, error);
    if (result == GB_OK)
        result = gb_hud_create(&s.hud, error);
    if (result == GB_OK) {
        install_callbacks(&s);
        result = run_frames(&s, error);
    }
    signal(SIGINT, previous_handler);
    if (timings) {
        *timings = s.renderer.timings;
        memset(timings->queries, 0, sizeof timings->queries);
    }
    gb_hud_destroy(&s.hud);
    gb_renderer_destroy(&s.renderer);
    gb_context_destroy(&context);
    return result;
}
