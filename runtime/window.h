/* window.h — the window face of gbview: a GLFW window showing the image,
 * with a fly camera, a HUD and keys:
 *   mouse, left button held   look around
 *   mouse, right button held  orbit about the point under the cursor
 *   wheel                     fly speed up or down
 *   W A S D, Q E              move forward, left, back, right, down, up
 *   Shift                     move 5x faster
 *   M                         next GI method this scene and bake can run
 *   T                         light terms: direct+indirect, direct, indirect
 *   C                         next camera of the scene (back to its view)
 *   B                         print the view as a .scene camera line
 *   H                         show or hide the keys
 *   F1                        show or hide the HUD
 *   F12 or P                  screenshot, never over an existing file
 *                             (screenshot_path or gbview.png, numbered:
 *                             gbview-000.png, gbview-001.png ...)
 *   Esc, the close button     quit
 * The window draws to a frame budget (renderer.h, gb_renderer_refine):
 * input is read between parts, so a key acts within one part; once the
 * image is final it draws nothing until the next event. A method's long
 * setup (implicit's links) runs beside the frames: the window shows direct
 * light and the setup's progress meanwhile. With frames > 0 it quits after
 * that many full-resolution images (or once the image is final) and saves
 * the last one to screenshot_path when given. The window's size follows
 * the camera's resolution (or the renderer options'); resizing the window
 * resizes the image.
 */
#ifndef GB_WINDOW_H
#define GB_WINDOW_H

#include <stdint.h>

#include "renderer.h"
#include "result.h"
#include "scene.h"
#include "timings.h"

enum { GB_WINDOW_DEFAULT_BUDGET_MS = 50 };

typedef struct gb_window_options {
    gb_renderer_options renderer;   /* width, height 0: the camera's resolution;
                                       budget_ms 0: whole images, every frame */
    uint32_t camera;
    int frames;                     /* > 0: quit after that many images */
    const char *screenshot_path;    /* NULL: gbview.png, numbered */
    const char *title;              /* the scene's name */
    int log_frames;                 /* report a line per presented frame:
                                       its time, the input's latency, the scale */
    /* Called with what the user should know (a screenshot saved, a method
     * skipped, a bookmark): the library does not print. May be NULL. */
    void (*report)(void *user, const char *message);
    void *report_user;
} gb_window_options;

/* Runs until Esc, the window is closed, SIGINT, or options->frames images;
 * timings (may be NULL) gets the frames' times, its GL names zeroed. */
gb_result gb_run_window(const gb_scene *scene, const gb_window_options *options,
                        gb_timings *timings, gb_error *error);

#endif
