/* environment.c — background radiance (environment.h). */
#include "environment.h"

#include <math.h>
#include <stddef.h>


/* Bilinear RGB at u in [0, 1) (wrapping) and v in [0, 1] (clamped). */
static void lookup(const gb_texture *map, double u, double v, float rgb[3])
{
    double x = u * map->width - 0.5, y = v * map->height - 0.5;
    double x0 = floor(x), y0 = floor(y), fx = x - x0, fy = y - y0;
    double sum[3] = {0.0, 0.0, 0.0};
    for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
            long column = ((long)x0 + i) % map->width, row = (long)y0 + j;
            column += column < 0 ? map->width : 0;
            row = row < 0 ? 0 : row >= map->height ? map->height - 1 : row;
            double w = (i ? fx : 1.0 - fx) * (j ? fy : 1.0 - fy);
            const float *p = &map->rgb[3 * ((size_t)row * (size_t)map->width + (size_t)column)];
            for (int k = 0; k < 3; ++k)
                sum[k] += w * p[k];
        }
    for (int k = 0; k < 3; ++k)
        rgb[k] = (float)sum[k];
}

void gb_environment_map_radiance(const gb_texture *map, const float d[3], float rgb[3])
{
    double u = atan2(d[0], -d[2]) / (2.0 * M_PI) + 0.5;
    double v = acos(fmax(-1.0, fmin(1.0, d[1]))) / M_PI;
    lookup(map, u >= 1.0 ? u - 1.0 : u, v, rgb);
}

void gb_environment_radiance(const gb_scene *scene, const float d[3], float rgb[3])
{
    if (scene->environment_texture.rgb) {
        gb_environment_map_radiance(&scene->environment_texture, d, rgb);
        return;
    }
    for (int k = 0; k < 3; ++k)
        rgb[k] = scene->environment[k];
}

gb_result gb_environment_map_check(const gb_texture *map, const char *path, gb_error *error)
{
    if (!map->rgb || map->width < 1 || map->height < 1)
        return gb_fail(error, GB_ERROR_INVALID, "%s: the environment map is empty", path);
    size_t values = 3 * (size_t)map->width * (size_t)map->height;
    for (size_t i = 0; i < values; ++i)
        if (!isfinite(map->rgb[i]) || map->rgb[i] < 0.0f)
            return gb_fail(error, GB_ERROR_INVALID, "%s: the environment map has a negative or "
                           "non-finite pixel (%zu)", path, i / 3);
    return GB_OK;
}
