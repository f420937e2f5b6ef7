/* timings.h — per-pass GPU times of the frame, which gbview prints with
 * --timings and shows in the window's HUD. Each pass is a pair of
 * GL_TIMESTAMP queries (glQueryCounter) rather than a GL_TIME_ELAPSED query,
 * whose first result llvmpipe reports from a zero start.
 *
 *   gb_timings_begin(&t, GB_PASS_GBUFFER); ...draw...; gb_timings_end(&t, GB_PASS_GBUFFER);
 *   gb_timings_end_frame(&t, wall_seconds);   // waits for the results
 * A pass that
 * did not run in a frame (the shadow maps are drawn once) adds nothing to
 * it. The first frame is kept apart (on llvmpipe it compiles the shaders, and
 * it draws the shadow maps): means are over the later frames in which the
 * pass ran, or over the first when it is the only one.
 *
 * Create → use → destroy (also on a zeroed one). Needs a current context.
 */
#ifndef GB_TIMINGS_H
#define GB_TIMINGS_H

#include <stdint.h>
#include <stdio.h>

#include <epoxy/gl.h>

typedef enum gb_pass {
    GB_PASS_SHADOW_MAPS,
    GB_PASS_GBUFFER,
    GB_PASS_DIRECT_LIGHT,
    GB_PASS_INDIRECT_LIGHT,
    GB_PASS_PRESENT,
    GB_PASS_COUNT,
} gb_pass;

typedef struct gb_timings {
    GLuint queries[2 * GB_PASS_COUNT];  /* begin, end of each pass */
    int running[GB_PASS_COUNT];     /* began this frame */
    double last_ms[GB_PASS_COUNT];  /* the last frame's, 0 when it did not run */
    double first_ms[GB_PASS_COUNT]; /* the first frame's */
    double total_ms[GB_PASS_COUNT]; /* over the frames after the first */
    uint32_t runs[GB_PASS_COUNT];   /* frames after the first in which it ran */
    double last_frame_gpu_ms, last_frame_wall_ms;
    double first_gpu_ms, first_wall_ms;
    double total_gpu_ms, total_wall_ms; /* over the frames after the first */
    uint32_t frames;                /* all, the first included */
    int finish_passes;              /* glFinish before each pass's end query:
                                       llvmpipe rasterizes at the flush, so
                                       without it a pass's fragments land in
                                       whichever pass flushes next */
} gb_timings;

const char *gb_pass_name(gb_pass pass);
void gb_timings_create(gb_timings *timings);
void gb_timings_begin(gb_timings *timings, gb_pass pass);
void gb_timings_end(gb_timings *timings, gb_pass pass);
/* Collects this frame's queries (blocking) and adds wall_ms, the frame's
 * wall-clock time, to the totals. */
void gb_timings_end_frame(gb_timings *timings, double wall_ms);
/* The table: one pass a line, then the frame, its mean and first frame. */
void gb_timings_print(const gb_timings *timings, FILE *out);
/* The mean of pass over the frames (see above), 0 when it never ran;
 * GB_PASS_COUNT gives the whole frame's GPU time. */
double gb_timings_mean_ms(const gb_timings *timings, gb_pass pass);
/* "gbuffer 1.2 | direct 3.4 | ... ms" of the last frame, into text. */
void gb_timings_format_last(const gb_timings *timings, char *text, size_t size);
void gb_timings_destroy(gb_timings *timings);

#endif
