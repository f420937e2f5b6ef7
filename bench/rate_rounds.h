/* rate_rounds.h — what the rate benchmarks (photons_rate, reference_rate)
 * share: the median over --rounds rounds of each column of a round's row,
 * and the loop over the scenes that loads each, measures it and prints its
 * line. Bench code, included by those programs.
 *
 *   rate_medians    ROUNDS rounds of a round function, then the median of
 *                   each of COLUMNS columns (at most RATE_MAX_COLUMNS);
 *   rate_scenes     for each scene path: load (textures too, as the tools
 *                   do), the program's line function, free; a failure is
 *                   said as "PROGRAM: message" on stderr and the next scene
 *                   goes on. Returns the exit status (1 if any failed).
 */
#ifndef GB_RATE_ROUNDS_H
#define GB_RATE_ROUNDS_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene.h"

enum { MAX_ROUNDS = 15, RATE_MAX_COLUMNS = 16 };

/* One round: fills row (COLUMNS values); 0 on failure, error set. */
typedef int (*rate_round)(const gb_scene *scene, void *user, double *row, gb_error *error);
/* One scene's line on stdout (name: the file's name); 0 on failure. */
typedef int (*rate_line)(const gb_scene *scene, const char *name, void *user, gb_error *error);

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *values, int count)
{
    qsort(values, (size_t)count, sizeof *values, compare_doubles);
    return count % 2 ? values[count / 2] : 0.5 * (values[count / 2 - 1] + values[count / 2]);
}

static int rate_medians(const gb_scene *scene, int rounds, int columns, rate_round round,
                        void *user, double *out, gb_error *error)
{
    double values[RATE_MAX_COLUMNS][MAX_ROUNDS], row[RATE_MAX_COLUMNS];
    for (int r = 0; r < rounds; ++r) {
        if (!round(scene, user, row, error))
            return 0;
        for (int k = 0; k < columns; ++k)
            values[k][r] = row[k];
    }
    for (int k = 0; k < columns; ++k)
        out[k] = median(values[k], rounds);
    return 1;
}

static int rate_scenes(const char *program, char **paths, int count, rate_line line,
                       void *user)
{
    int status = 0;
    for (int i = 0; i < count; ++i) {
        gb_scene scene;
        gb_error error;
        gb_scene_options scene_options = {.load_textures = 1};
        if (gb_scene_load(paths[i], &scene_options, &scene, &error) != GB_OK) {
            fprintf(stderr, "%s: %s\n", program, error.message);
            status = 1;
            continue;
        }
        const char *name = strrchr(paths[i], '/');
        if (line(&scene, name ? name + 1 : paths[i], user, &error)) {
            fflush(stdout);
        } else {
            fprintf(stderr, "%s: %s\n", program, error.message);
            status = 1;
        }
        gb_scene_free(&scene);
    }
    return status;
}

#endif
