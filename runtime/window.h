/* window.h — the window face of gbview: a GLFW window showing the frame,
 * with a fly camera and keys:
 *   mouse, left button held   look around
 *   W A S D, Q E              move forward, left, back, right, down, up
 *   Shift                     move 5x faster
 *   M                         next GI method (of those this build has)
 *   T                         light terms: direct+indirect, direct, indirect
 *   C                         next camera of the scene (back to its view)
 *   F12 or P                  screenshot (screenshot_path, or
 *                             gbview-NNN.png in the working folder)
 *   Esc                       quit
 * With frames > 0 and a screenshot path, the last frame is saved there.
 * The window title shows the method, the terms and the last frame's
 * per-pass GPU times. The window's size follows the camera's resolution
 * (or the renderer options'); resizing the window resizes the frame.
 */
#ifndef GB_WINDOW_H
#define GB_WINDOW_H

#include <stdint.h>

#include "renderer.h"
#include "result.h"
#include "scene.h"
#include "timings.h"

typedef struct gb_window_options {
    gb_renderer_options renderer;   /* width, height 0: the camera's resolution */
    uint32_t camera;
    int frames;                     /* > 0: quit after that many frames */
    const char *screenshot_path;    /* NULL: gbview-NNN.png */
    const char *title;              /* the scene's name */
    /* Called with what the user should know (a screenshot saved, a method
     * that is not available): the library does not print. May be NULL. */
    void (*report)(void *user, const char *message);
    void *report_user;
} gb_window_options;

/* Runs until Esc, the window is closed, or options->frames frames; timings
 * (may be NULL) gets the frames' times, its GL names zeroed. */
gb_result gb_run_window(const gb_scene *scene, const gb_window_options *options,
                        gb_timings *timings, gb_error *error);

#endif
