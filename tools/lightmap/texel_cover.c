/* texel_cover.c — the triangles rasterised at their atlas UVs
 * (texel_cover.h): edge functions in double over each triangle's bounding
 * box of texel centres. */
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

/* Whether a centre exactly on edge a -> b belongs to the triangle on its
 * left: of two triangles sharing the edge (which run it opposite ways),
 * exactly one says yes. */
static int owns_edge(const double a[2], const double b[2])
{
    double dx = b[0] - a[0], dy = b[1] - a[1];
    return dy > 0.0 || (dy == 0.0 && dx < 0.0);
}

static int inside(const double p[3][2], const double centre[2])
{
    for (int e = 0; e < 3; ++e) {
        const double *a = p[e], *b = p[(e + 1) % 3];
        double s = edge(a, b, centre);
        if (s < 0.0 || (s == 0.0 && !owns_edge(a, b)))
            return 0;
    }
    return 1;
}

/* The first and last texel index whose centre k + 0.5 lies in [low, high],
 * clamped to 0 .. size - 1; first > last when none. */
static void centre_range(double low, double high, uint32_t size, long *first, long *last)
{
    *first = (long)fmax(ceil(low - 0.5), 0.0);
    *last = (long)fmin(floor(high - 0.5), (double)size - 1.0);
}

static void cover_triangle(const gb_atlas *atlas, uint32_t t, gb_texel_cover *cover)
{
    double p[3][2];
    for (int c = 0; c < 3; ++c)
        corner(atlas, t, c, p[c]);
    long i0, i1, j0, j1;
    centre_range(fmin(p[0][0], fmin(p[1][0], p[2][0])), fmax(p[0][0], fmax(p[1][0], p[2][0])),
                 cover->width, &i0, &i1);
    centre_range(fmin(p[0][1], fmin(p[1][1], p[2][1])), fmax(p[0][1], fmax(p[1][1], p[2][1])),
                 cover->height, &j0, &j1);
    for (long j = j0; j <= j1; ++j)
        for (long i = i0; i <= i1; ++i) {
            const double centre[2] = {(double)i + 0.5, (double)j + 0.5};
            if (inside(p, centre))
                cover->triangle[(size_t)j * cover->width + (size_t)i] = t;
        }
}

gb_result gb_texel_cover_make(const gb_atlas *atlas, gb_texel_cover *cover, gb_error *error)
{
    cover->width = atlas->header.width;
    cover->height = atlas->header.height;
    size_t count = (size_t)cover->width * cover->height;
    cover->triangle = malloc(count * sizeof *cover->triangle);
    if (!cover->triangle)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "lightmap: out of memory (%u x %u texels)",
                       cover->width, cover->height);
    for (size_t k = 0; k < count; ++k)
        cover->triangle[k] = GB_TEXEL_NONE;
    for (uint32_t t = 0; t < atlas->header.triangle_count; ++t)
        cover_triangle(atlas, t, cover);
    return GB_OK;
}

void gb_texel_cover_free(gb_texel_cover *cover)
{
    free(cover->triangle);
    cover->triangle = NULL;
}

/* The squared distance from q (texel units) to the nearest point of
 * triangle t. */
static double squared_distance(const gb_atlas *atlas, uint32_t t, const double q[2])
{
    double p[3][2];
    for (int c = 0; c < 3; ++c)
        corner(atlas, t, c, p[c]);
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

uint32_t gb_texel_border_triangle(const gb_atlas *atlas, const gb_texel_cover *cover,
                                  uint32_t i, uint32_t j, double weights[3])
{
    const double q[2] = {(double)i + 0.5, (double)j + 0.5};
    uint32_t chosen = GB_TEXEL_NONE;
    double best = INFINITY;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            long x = (long)i + dx, y = (long)j + dy;
            if (x < 0 || y < 0 || x >= (long)cover->width || y >= (long)cover->height)
                continue;
            uint32_t t = cover->triangle[(size_t)y * cover->width + (size_t)x];
            if (t == GB_TEXEL_NONE)
                continue;
            double d = squared_distance(atlas, t, q);
            if (d < best || (d == best && t < chosen)) {
                best = d;
                chosen = t;
            }
        }
    if (chosen != GB_TEXEL_NONE)
        gb_texel_barycentric(atlas, chosen, i, j, weights);
    return chosen;
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
