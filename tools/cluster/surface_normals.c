/* surface_normals.c — area-weighted groups of normals (surface_normals.h). */
#include "surface_normals.h"

#include <math.h>
#include <stdlib.h>

void gb_surface_normals_add(gb_surface_normal *groups, uint32_t *count, uint32_t capacity,
                            const float normal[3], float area)
{
    if (!(area > 0.0f))
        return;
    for (uint32_t g = 0; g < *count; ++g) {
        gb_surface_normal *s = &groups[g];
        float cosine = s->normal[0] * normal[0] + s->normal[1] * normal[1] +
                       s->normal[2] * normal[2];
        if (cosine < GB_SURFACE_NORMAL_MERGE_COS)
            continue;
        float sum[3], length = 0.0f;
        for (int k = 0; k < 3; ++k) {
            sum[k] = s->normal[k] * s->area + normal[k] * area;
            length += sum[k] * sum[k];
        }
        length = sqrtf(length);
        for (int k = 0; k < 3; ++k)
            s->normal[k] = sum[k] / length;
        s->area += area;
        return;
    }
    if (*count < capacity)
        groups[(*count)++] = (gb_surface_normal){{normal[0], normal[1], normal[2]}, area};
}

static int larger_first(const void *a, const void *b)
{
    const gb_surface_normal *x = a, *y = b;
    if (x->area != y->area)
        return x->area > y->area ? -1 : 1;
    for (int k = 0; k < 3; ++k)
        if (x->normal[k] != y->normal[k])
            return x->normal[k] < y->normal[k] ? -1 : 1;
    return 0;
}

void gb_surface_normals_keep_largest(gb_surface_normal *groups, uint32_t *count, uint32_t keep)
{
    qsort(groups, *count, sizeof *groups, larger_first);
    if (*count > keep)
        *count = keep;
}
