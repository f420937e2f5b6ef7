#include "timings.h"

#include <string.h>

const char *gb_pass_name(gb_pass pass)
{
    switch (pass) {
    case GB_PASS_SHADOW_MAPS: return "shadow maps";
    case GB_PASS_GBUFFER: return "g-buffer";
    case GB_PASS_DIRECT_LIGHT: return "direct light";
    case GB_PASS_INDIRECT_LIGHT: return "indirect light";
    case GB_PASS_PRESENT: return "present";
    case GB_PASS_COUNT: break;
    }
    return "?";
}

void gb_timings_create(gb_timings *timings)
{
    memset(timings, 0, sizeof *timings);
    glCreateQueries(GL_TIMESTAMP, 2 * GB_PASS_COUNT, timings->queries);
}

void gb_timings_begin(gb_timings *timings, gb_pass pass)
{
    glQueryCounter(timings->queries[2 * pass], GL_TIMESTAMP);
    timings->running[pass] = 1;
}

void gb_timings_end(gb_timings *timings, gb_pass pass)
{
    if (timings->finish_passes)
        glFinish();
    glQueryCounter(timings->queries[2 * pass + 1], GL_TIMESTAMP);
}

static double collect_pass(gb_timings *t, int pass)
{
    GLuint64 begin = 0, end = 0;
    glGetQueryObjectui64v(t->queries[2 * pass], GL_QUERY_RESULT, &begin);
    glGetQueryObjectui64v(t->queries[2 * pass + 1], GL_QUERY_RESULT, &end);
    t->running[pass] = 0;
    return end > begin ? (double)(end - begin) * 1e-6 : 0.0;
}

void gb_timings_end_frame(gb_timings *t, double wall_ms)
{
    double gpu_ms = 0.0;
    int first = t->frames == 0;
    for (int pass = 0; pass < GB_PASS_COUNT; ++pass) {
        t->last_ms[pass] = t->running[pass] ? collect_pass(t, pass) : 0.0;
        gpu_ms += t->last_ms[pass];
        if (first)
            t->first_ms[pass] = t->last_ms[pass];
        else if (t->last_ms[pass] > 0.0) {
            t->total_ms[pass] += t->last_ms[pass];
            t->runs[pass] += 1;
        }
    }
    t->last_frame_gpu_ms = gpu_ms;
    t->last_frame_wall_ms = wall_ms;
    if (first) {
        t->first_gpu_ms = gpu_ms;
        t->first_wall_ms = wall_ms;
    } else {
        t->total_gpu_ms += gpu_ms;
        t->total_wall_ms += wall_ms;
    }
    t->frames += 1;
}

double gb_timings_mean_ms(const gb_timings *t, gb_pass pass)
{
    if (pass == GB_PASS_COUNT)
        return t->frames > 1 ? t->total_gpu_ms / (t->frames - 1) : t->first_gpu_ms;
    if (t->runs[pass])
        return t->total_ms[pass] / t->runs[pass];
    return t->first_ms[pass];
}

static void print_line(FILE *out, const char *name, double mean, double first)
{
    fprintf(out, "%-16s %10.3f %12.3f\n", name, mean, first);
}

void gb_timings_print(const gb_timings *t, FILE *out)
{
    fprintf(out, "%-16s %10s %12s   frames: %u\n", "pass", "mean_ms", "first_ms", t->frames);
    for (int pass = 0; pass < GB_PASS_COUNT; ++pass)
        if (t->runs[pass] || t->first_ms[pass] > 0.0)
            print_line(out, gb_pass_name((gb_pass)pass), gb_timings_mean_ms(t, (gb_pass)pass),
                       t->first_ms[pass]);
    if (t->frames) {
        print_line(out, "frame (gpu)", gb_timings_mean_ms(t, GB_PASS_COUNT), t->first_gpu_ms);
        print_line(out, "frame (wall)",
                   t->frames > 1 ? t->total_wall_ms / (t->frames - 1) : t->first_wall_ms,
                   t->first_wall_ms);
    }
}

void gb_timings_format_last(const gb_timings *t, char *text, size_t size)
{
    size_t used = 0;
    text[0] = '\0';
    for (int pass = 0; pass < GB_PASS_COUNT && used < size; ++pass)
        if (t->last_ms[pass] > 0.0) {
            int n = snprintf(text + used, size - used, "%s %.2f | ", gb_pass_name((gb_pass)pass),
                             t->last_ms[pass]);
            used += n > 0 ? (size_t)n : 0;
        }
    if (used < size)
        snprintf(text + used, size - used, "frame %.2f ms", t->last_frame_wall_ms);
}

void gb_timings_destroy(gb_timings *timings)
{
    if (timings->queries[0])
        glDeleteQueries(2 * GB_PASS_COUNT, timings->queries);
    memset(timings, 0, sizeof *timings);
}
