/* texel_cover.c — the triangles rasterised at their atlas UVs with their
 * reach (texel_cover.h): in double, over each triangle's bounding box of
 * texel centres grown by the reach. */
#include "texel_cover.h"

#include <math.h>
#include <stdlib.h>

/* Corner c of triangle t in texel units. */
static void corner(const gb_atlas *atlas, uint32_t t, int c, double p[2])
{
    p[0] = (double)atlas->uvs[6 * (size_t)t + 2 * c] * atlas->header.width;
    p[1] = (double)atlas->uvs[6 * (size_t)t + 2 * c + 1] * atlas->header.height;
}

/* Twice the signed area of (a, b, p): positive when p is left of a -> b
 * (counterclockwise, atlas.h). */
static double edge(const double a[2], const double b[2], const double p[2])
{
    return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
}

/* The squared distance from q (texel units) to the nearest point of
 * triangle p (0 inside it or on its border). */
static double squared_distance(const double p[3][2], const double q[2])
{
    if (edge(p[1], p[2], q) >= 0.0 && edge(p[2], p[0], q) >= 0.0 && edge(p[0], p[1], q) >= 0.0)
        return 0.0;
    double nearest = INFINITY;
    for (int e = 0; e < 3; ++e) {
        const double *a = p[e], *b = p[(e + 1) % 3];
        double ab[2] = {b[0] - a[0], b[1] - a[1]};
        double s = ((q[0] - a[0]) * ab[0] + (q[1] - a[1]) * ab[1]) /
                   (ab[0] * ab[0] + ab[1] * ab[1]);
        s = fmin(fmax(s, 0.0), 1.0);
        double dx = q[0] - (a[0] + s * ab[0]), dy = q[1] - (a[1] + s * ab[1]);
        nearest = fmin(nearest, dx * dx + dy * dy);
    }
    return nearest;
}

/* The first and last texel index whose centre k + 0.5 lies in [low, high],
 * clamped to 0 .. size - 1; first > last when none. */
static void centre_range(double low, double high, uint32_t size, long *first, long *last)
{
    *first = (long)fmax(ceil(low - 0.5), 0.0);
    *last = (long)fmin(floor(high - 0.5), (double)size - 1.0);
}

/* Triangle t takes the texels within reach whose nearest triangle so far is
 * farther (best: their squared distances): in scene order, so a tie keeps
 * the smaller index. */
static void cover_triangle(const gb_atlas *atlas, uint32_t t, double reach,
                           gb_texel_cover *cover, double *best)
{
    double p[3][2];
    for (int c = 0; c < 3; ++c)
        corner(atlas, t, c, p[c]);
    long i0, i1, j0, j1;
    centre_range(fmin(p[0][0], fmin(p[1][0], p[2][0])) - reach,
                 fmax(p[0][0], fmax(p[1][0], p[2][0])) + reach, cover->width, &i0, &i1);
    centre_range(fmin(p[0][1], fmin(p[1][1], p[2][1])) - reach,
                 fmax(p[0][1], fmax(p[1][1], p[2][1])) + reach, cover->height, &j0, &j1);
    for (long j = j0; j <= j1; ++j)
        for (long i = i0; i <= i1; ++i) {
            const double centre[2] = {(double)i + 0.5, (double)j + 0.5};
            size_t k = (size_t)j * cover->width + (size_t)i;
            double d = squared_distance(p, centre);
            if (d <= reach * reach && d < best[k]) {
                best[k] = d;
                cover->triangle[k] = t;
            }
        }
}

gb_result gb_texel_cover_make(const gb_atlas *atlas, double reach, gb_texel_cover *cover,
                              gb_error *error)
{
    cover->width = atlas->header.width;
    cover->height = atlas->header.height;
    size_t count = (size_t)cover->width * cover->height;
    cover->triangle = malloc(count * sizeof *cover->triangle);
    if (!cover->triangle)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "lightmap: out of memory (%u x %u texels)",
                       cover->width, cover->height);
    double *best = malloc(count * sizeof *best);
    if (!best) {
        gb_texel_cover_free(cover);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "lightmap: out of memory (%u x %u texels)",
                       cover->width, cover->height);
    }
    for (size_t k = 0; k < count; ++k) {
        cover->triangle[k] = GB_TEXEL_NONE;
        best[k] = INFINITY;
    }
    for (uint32_t t = 0; t < atlas->header.triangle_count; ++t)
        cover_triangle(atlas, t, reach, cover, best);
    free(best);
    return GB_OK;
}

void gb_texel_cover_free(gb_texel_cover *cover)
{
    free(cover->triangle);
    cover->triangle = NULL;
}

void gb_texel_barycentric(const gb_atlas *atlas, uint32_t t, uint32_t i, uint32_t j,
                          double weights[3])
{
    double p[3][2];
    for (int c = 0; c < 3; ++c)
        corner(atlas, t, c, p[c]);
    const double centre[2] = {(double)i + 0.5, (double)j + 0.5};
    double area = edge(p[0], p[1], p[2]);
    weights[1] = edge(p[2], p[0], centre) / area;
    weights[2] = edge(p[0], p[1], centre) / area;
    weights[0] = 1.0 - weights[1] - weights[2];
}
