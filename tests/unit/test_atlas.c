/* test_atlas.c — unit tests of tools/atlas: a planar chart is mapped
 * without angle distortion (measured here from the written UVs against
 * the 3-D angles); a cube gives its six faces; a closed sphere, an open
 * cylinder and a flat ring come out as topological discs (counted here
 * from the scene's indices); needle and near-degenerate triangles get
 * finite UVs of positive area; no two triangles overlap (every pair,
 * tested here without the grid and without the tool's predicate); the
 * overlap predicate and grid against hand cases and brute force; the
 * charts kept apart as the file's padded masks promise, measured pair by
 * pair of triangles (uv_distance.h, apart from the raster the packer and
 * the reader share) on built scenes, McGuire's Cornell box and the first
 * triangles of Sponza; the LSCM adapter refuses a closed mesh; the file
 * reads back; the same scene gives the same bytes. */
#include "../../tools/atlas/atlas_build.h"
#include "../../tools/atlas/lscm.h"
#include "../../tools/atlas/merge.h"
#include "../../tools/atlas/min_area_rect.h"
#include "../../tools/atlas/overlap.h"
#include "scene_builder.h"
#include "scratch.h"
#include "tap.h"
#include "uv_distance.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- meshes with shared vertices ---- */

static uint32_t add_vertex(gb_scene *scene, double x, double y, double z)
{
    uint32_t v = scene->vertex_count++;
    scene->positions = builder_grow(scene->positions, 3 * (size_t)scene->vertex_count,
                                    sizeof *scene->positions);
    scene->positions[3 * v] = (float)x;
    scene->positions[3 * v + 1] = (float)y;
    scene->positions[3 * v + 2] = (float)z;
    return v;
}

/* Quad a b c d, counterclockwise seen from its front. */
static void add_quad_indices(gb_scene *scene, uint32_t a, uint32_t b, uint32_t c, uint32_t d)
{
    add_triangle(scene, a, b, c, 0);
    add_triangle(scene, a, c, d, 0);
}

static void begin(gb_scene *scene)
{
    memset(scene, 0, sizeof *scene);
    add_grey(scene, 0.5f, 0.0f);
}

/* A small deterministic jitter in [-amount, amount]. */
static double jitter(uint32_t i, double amount)
{
    uint32_t h = i * 2654435761u;
    h ^= h >> 15;
    return amount * (2.0 * (h % 10007) / 10006.0 - 1.0);
}

/* An n x n grid of quads on a tilted plane, its inner vertices moved in
 * the plane. */
static void build_tilted_grid(gb_scene *scene, int n)
{
    const double e1[3] = {0.6, 0.0, 0.8}, e2[3] = {0.0, 1.0, 0.0}, o[3] = {1, 2, 3};
    begin(scene);
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            int inner = i > 0 && i < n && j > 0 && j < n;
            double x = i + (inner ? jitter(2 * (j * (n + 1) + i), 0.3) : 0.0);
            double y = j + (inner ? jitter(2 * (j * (n + 1) + i) + 1, 0.3) : 0.0);
            add_vertex(scene, o[0] + x * e1[0] + y * e2[0], o[1] + x * e1[1] + y * e2[1],
                       o[2] + x * e1[2] + y * e2[2]);
        }
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            uint32_t a = j * (n + 1) + i;
            add_quad_indices(scene, a, a + 1, a + n + 2, a + n + 1);
        }
    scene_done(scene);
}

/* The unit cube on 8 shared vertices, faces outward. */
static void build_cube(gb_scene *scene)
{
    begin(scene);
    for (int v = 0; v < 8; ++v)
        add_vertex(scene, v & 1, (v >> 1) & 1, (v >> 2) & 1);
    add_quad_indices(scene, 0, 2, 3, 1);
    add_quad_indices(scene, 4, 5, 7, 6);
    add_quad_indices(scene, 0, 1, 5, 4);
    add_quad_indices(scene, 2, 6, 7, 3);
    add_quad_indices(scene, 0, 4, 6, 2);
    add_quad_indices(scene, 1, 3, 7, 5);
    scene_done(scene);
}

/* A closed UV sphere: poles, rings of `around` vertices, faces outward. */
static void build_sphere(gb_scene *scene, int rings, int around)
{
    begin(scene);
    uint32_t south = add_vertex(scene, 0, 0, -1);
    for (int r = 1; r < rings; ++r)
        for (int k = 0; k < around; ++k) {
            double theta = M_PI * r / rings - M_PI / 2, phi = 2 * M_PI * k / around;
            add_vertex(scene, cos(theta) * cos(phi), cos(theta) * sin(phi), sin(theta));
        }
    uint32_t north = add_vertex(scene, 0, 0, 1);
    for (int k = 0; k < around; ++k) {
        uint32_t a = 1 + k, b = 1 + (k + 1) % around;
        add_triangle(scene, south, b, a, 0);
        uint32_t top = 1 + (rings - 2) * around;
        add_triangle(scene, north, top + k, top + (k + 1) % around, 0);
    }
    for (int r = 0; r + 2 < rings; ++r)
        for (int k = 0; k < around; ++k) {
            uint32_t a = 1 + r * around + k, b = 1 + r * around + (k + 1) % around;
            add_quad_indices(scene, a, b, b + around, a + around);
        }
    scene_done(scene);
}

/* An open tube around z, faces outward. */
static void build_cylinder(gb_scene *scene, int around, int levels)
{
    begin(scene);
    for (int l = 0; l <= levels; ++l)
        for (int k = 0; k < around; ++k)
            add_vertex(scene, cos(2 * M_PI * k / around), sin(2 * M_PI * k / around),
                       (double)l / levels * 3.0);
    for (int l = 0; l < levels; ++l)
        for (int k = 0; k < around; ++k) {
            uint32_t a = l * around + k, b = l * around + (k + 1) % around;
            add_quad_indices(scene, a, b, b + around, a + around);
        }
    scene_done(scene);
}

/* A flat ring in z = 0, facing +z: one normal, not a disc. */
static void build_ring(gb_scene *scene, int around)
{
    begin(scene);
    for (int k = 0; k < around; ++k) {
        double phi = 2 * M_PI * k / around;
        add_vertex(scene, cos(phi), sin(phi), 0);
        add_vertex(scene, 2 * cos(phi), 2 * sin(phi), 0);
    }
    for (int k = 0; k < around; ++k) {
        uint32_t a = 2 * k, b = 2 * ((k + 1) % around);
        add_quad_indices(scene, a, a + 1, b + 1, b);
    }
    scene_done(scene);
}

/* A flat fan with a needle (a corner 1e-6 of the edge's length off it)
 * and a near-degenerate sliver, and a lone needle apart. */
static void build_needles(gb_scene *scene)
{
    begin(scene);
    uint32_t c = add_vertex(scene, 0, 0, 0);
    uint32_t p0 = add_vertex(scene, 1, 0, 0), p1 = add_vertex(scene, 1, 1e-6, 0);
    uint32_t p2 = add_vertex(scene, 0, 1, 0), p3 = add_vertex(scene, -1, 0, 0);
    uint32_t p4 = add_vertex(scene, 0.5, -1e-5, 0), p5 = add_vertex(scene, 0, -1, 0);
    add_triangle(scene, c, p0, p1, 0);   /* the needle */
    add_triangle(scene, c, p1, p2, 0);
    add_triangle(scene, c, p2, p3, 0);
    add_triangle(scene, c, p3, p5, 0);
    add_triangle(scene, c, p5, p4, 0);   /* the sliver: p4 near the line c..p0 */
    add_triangle(scene, c, p4, p0, 0);
    uint32_t q0 = add_vertex(scene, 5, 5, 5), q1 = add_vertex(scene, 7, 5, 5);
    uint32_t q2 = add_vertex(scene, 6, 5 + 1e-6, 5);
    add_triangle(scene, q0, q1, q2, 0);
    /* a needle whose short edge (1.4e-7) is under 4 UV steps at this density */
    uint32_t r0 = add_vertex(scene, 0, 0, 2), r1 = add_vertex(scene, 1, 0, 2);
    uint32_t r2 = add_vertex(scene, 1e-7, 1e-7, 2);
    add_triangle(scene, r0, r1, r2, 0);
    scene_done(scene);
}

static gb_result build(const gb_scene *scene, double cone, gb_atlas *atlas, gb_atlas_stats *stats)
{
    gb_atlas_options options = {.cone_degrees = cone, .size = 256,
                                .padding = GB_ATLAS_DEFAULT_PADDING};
    gb_error error;
    gb_result result = gb_atlas_build(scene, &options, atlas, stats, &error);
    if (result != GB_OK)
        printf("# gb_atlas_build: %s\n", error.message);
    return result;
}

/* ---- independent measures ---- */

/* Corner c's angle of triangle t, in 3-D and in the atlas (texel units),
 * by acos of normalised dot products. */
static double angle_3d(const gb_scene *s, uint32_t t, int c)
{
    const float *o = s->positions + 3 * s->indices[3 * t + c];
    const float *a = s->positions + 3 * s->indices[3 * t + (c + 1) % 3];
    const float *b = s->positions + 3 * s->indices[3 * t + (c + 2) % 3];
    double u[3], v[3], uu = 0, vv = 0, uv = 0;
    for (int k = 0; k < 3; ++k) {
        u[k] = (double)a[k] - o[k];
        v[k] = (double)b[k] - o[k];
        uu += u[k] * u[k];
        vv += v[k] * v[k];
        uv += u[k] * v[k];
    }
    return acos(fmax(-1.0, fmin(1.0, uv / sqrt(uu * vv))));
}

static double angle_uv(const gb_atlas *a, uint32_t t, int c)
{
    const float *q = a->uvs + 6 * t;
    double w = a->header.width, h = a->header.height;
    int i = c, j = (c + 1) % 3, k = (c + 2) % 3;
    double ux = (q[2 * j] - q[2 * i]) * w, uy = (q[2 * j + 1] - q[2 * i + 1]) * h;
    double vx = (q[2 * k] - q[2 * i]) * w, vy = (q[2 * k + 1] - q[2 * i + 1]) * h;
    double d = (ux * vx + uy * vy) / sqrt((ux * ux + uy * uy) * (vx * vx + vy * vy));
    return acos(fmax(-1.0, fmin(1.0, d)));
}

/* The length in texels of edge c (corner c to corner c + 1) of t's UVs. */
static double uv_edge_texels(const gb_atlas *a, uint32_t t, int c)
{
    const float *q = a->uvs + 6 * t;
    int j = (c + 1) % 3;
    return hypot((q[2 * j] - q[2 * c]) * (double)a->header.width,
                 (q[2 * j + 1] - q[2 * c + 1]) * (double)a->header.height);
}

static double max_distortion_degrees(const gb_scene *s, const gb_atlas *a)
{
    double worst = 0.0;
    for (uint32_t t = 0; t < s->triangle_count; ++t)
        for (int c = 0; c < 3; ++c)
            worst = fmax(worst, fabs(angle_uv(a, t, c) - angle_3d(s, t, c)) * 180.0 / M_PI);
    return worst;
}

static double twice_area_texels(const gb_atlas *a, uint32_t t)
{
    const float *q = a->uvs + 6 * t;
    double w = a->header.width, h = a->header.height;
    return ((q[2] - q[0]) * w) * ((q[5] - q[1]) * h) - ((q[3] - q[1]) * h) * ((q[4] - q[0]) * w);
}

static int all_finite_and_positive(const gb_atlas *a)
{
    for (uint32_t t = 0; t < a->header.triangle_count; ++t) {
        for (int k = 0; k < 6; ++k)
            if (!isfinite(a->uvs[6 * t + k]))
                return 0;
        if (!(twice_area_texels(a, t) > 0.0))
            return 0;
    }
    return 1;
}

static uint32_t root(uint32_t *parent, uint32_t i)
{
    while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
    return i;
}

/* Whether every chart is connected over shared edges with V - E + F = 1,
 * counted on the scene's indices (the meshes here have one index per
 * position). */
static int every_chart_a_disc(const gb_scene *s, const gb_atlas *a)
{
    int ok = 1;
    uint32_t *parent = malloc(s->triangle_count * sizeof *parent);
    for (uint32_t c = 0; c < a->header.chart_count && ok; ++c) {
        long faces = 0, edges = 0, vertices = 0;
        uint32_t first = UINT32_MAX;
        for (uint32_t t = 0; t < s->triangle_count; ++t)
            parent[t] = t;
        for (uint32_t t = 0; t < s->triangle_count; ++t) {
            if (a->charts[t] != c)
                continue;
            ++faces;
            first = first == UINT32_MAX ? t : first;
            for (int e = 0; e < 3; ++e) {
                uint32_t p = s->indices[3 * t + e], q = s->indices[3 * t + (e + 1) % 3];
                int seen_edge = 0;
                for (uint32_t u = 0; u < t; ++u)
                    if (a->charts[u] == c)
                        for (int f = 0; f < 3; ++f) {
                            uint32_t x = s->indices[3 * u + f], y = s->indices[3 * u + (f + 1) % 3];
                            if ((x == p && y == q) || (x == q && y == p)) {
                                seen_edge = 1;
                                parent[root(parent, t)] = root(parent, u);
                            }
                        }
                edges += !seen_edge;
                int seen_vertex = 0;
                for (uint32_t u = 0; u <= t && !seen_vertex; ++u)
                    if (a->charts[u] == c)
                        for (int f = 0; f < (u == t ? e : 3); ++f)
                            seen_vertex |= s->indices[3 * u + f] == p;
                vertices += !seen_vertex;
            }
        }
        for (uint32_t t = 0; t < s->triangle_count; ++t)
            if (a->charts[t] == c && root(parent, t) != root(parent, first))
                ok = 0;
        if (vertices - edges + faces != 1)
            ok = 0;
    }
    free(parent);
    return ok;
}

/* Whether the interiors of two UV triangles (texel units) meet, tested
 * apart from overlap.c: a proper crossing of two edges, a corner strictly
 * inside the other, or the same three corners. */
static double orient(const double *o, const double *a, const double *b)
{
    return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

static int strictly_inside(const double *p, const double *t)
{
    return orient(t, t + 2, p) > 0 && orient(t + 2, t + 4, p) > 0 && orient(t + 4, t, p) > 0;
}

static int interiors_meet(const double *s, const double *t)
{
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const double *a = s + 2 * i, *b = s + 2 * ((i + 1) % 3);
            const double *c = t + 2 * j, *d = t + 2 * ((j + 1) % 3);
            double o1 = orient(a, b, c), o2 = orient(a, b, d), o3 = orient(c, d, a),
                   o4 = orient(c, d, b);
            if (((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0)) &&
                ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0)))
                return 1;
        }
    double cs[2] = {(s[0] + s[2] + s[4]) / 3, (s[1] + s[3] + s[5]) / 3};
    double ct[2] = {(t[0] + t[2] + t[4]) / 3, (t[1] + t[3] + t[5]) / 3};
    for (int k = 0; k < 3; ++k)
        if (strictly_inside(s + 2 * k, t) || strictly_inside(t + 2 * k, s))
            return 1;
    return strictly_inside(cs, t) || strictly_inside(ct, s);
}

static long overlapping_pairs_brute_force(const gb_atlas *a)
{
    uint32_t n = a->header.triangle_count;
    double *q = malloc(6 * (size_t)n * sizeof *q);
    for (uint32_t t = 0; t < n; ++t)
        for (int k = 0; k < 6; ++k)
            q[6 * t + k] = a->uvs[6 * t + k] * (k % 2 ? a->header.height : a->header.width);
    long pairs = 0;
    for (uint32_t s = 0; s < n; ++s)
        for (uint32_t t = s + 1; t < n; ++t)
            pairs += interiors_meet(q + 6 * s, q + 6 * t);
    free(q);
    return pairs;
}

/* How far apart the boxes of triangles s and t are along x or y: no more
 * than the triangles are. */
static double box_gap(const double *s, const double *t)
{
    double gap = 0.0;
    for (int d = 0; d < 2; ++d) {
        double s_lo = fmin(s[d], fmin(s[2 + d], s[4 + d])), s_hi = fmax(s[d], fmax(s[2 + d], s[4 + d]));
        double t_lo = fmin(t[d], fmin(t[2 + d], t[4 + d])), t_hi = fmax(t[d], fmax(t[2 + d], t[4 + d]));
        gap = fmax(gap, fmax(t_lo - s_hi, s_lo - t_hi));
    }
    return gap;
}

/* The least distance along x or y (uv_distance.h) between two triangles
 * of different charts, over every pair, up to wanted: a pair whose boxes
 * are that far apart is not measured further; +inf with one chart. */
static double charts_apart_brute_force(const gb_atlas *a, double wanted)
{
    uint32_t n = a->header.triangle_count;
    double *q = malloc(6 * (size_t)n * sizeof *q), least = INFINITY;
    for (uint32_t t = 0; t < n; ++t)
        for (int k = 0; k < 6; ++k)
            q[6 * t + k] = a->uvs[6 * t + k] * (k % 2 ? a->header.height : a->header.width);
    for (uint32_t s = 0; s < n; ++s)
        for (uint32_t t = s + 1; t < n; ++t)
            if (a->charts[s] != a->charts[t]) {
                double gap = box_gap(q + 6 * s, q + 6 * t);
                least = fmin(least, gap >= wanted ? gap : uv_distance(q + 6 * s, q + 6 * t));
            }
    free(q);
    return least;
}

/* Whether every two triangles of different charts are at least twice the
 * padding apart along x or y (the written floats are what the reader
 * rastered: only the rounding of double arithmetic is allowed). */
static void check_charts_apart(const gb_atlas *atlas, const char *name)
{
    char what[160];
    double wanted = 2.0 * atlas->header.padding, least = charts_apart_brute_force(atlas, wanted);
    snprintf(what, sizeof what, "%s: triangles of different charts at least 2P = %g texels "
             "apart along x or y (every pair; least %.4f)", name, wanted, least);
    CHECK(least >= wanted - 1e-9, what);
}

/* ---- the tests ---- */

static void test_planar_chart(void)
{
    gb_scene scene;
    build_tilted_grid(&scene, 6);
    gb_atlas atlas;
    gb_atlas_stats stats;
    if (!CHECK(build(&scene, 0, &atlas, &stats) == GB_OK, "planar grid: built"))
        return;
    CHECK_EQ_INT(atlas.header.chart_count, 1, "planar grid: one chart");
    double worst = max_distortion_degrees(&scene, &atlas);
    CHECK(worst < 0.01, "planar grid: LSCM keeps every angle (within 0.01 degree)");
    printf("# planar grid: largest angle error %.2e degrees\n", worst);
    CHECK_NEAR(atlas.chart_records[0].max_angle_distortion, worst, 1e-3,
               "planar grid: the record's max distortion is the one measured here");
    gb_atlas_free(&atlas);
    gb_scene_free(&scene);
}

/* Every chart of the cube holds triangles of one normal. */
static int charts_are_faces(const gb_scene *s, const gb_atlas *a)
{
    for (uint32_t t = 0; t < s->triangle_count; ++t)
        for (uint32_t u = 0; u < s->triangle_count; ++u)
            if (a->charts[t] == a->charts[u] && t / 2 != u / 2)
                return 0;
    return 1;
}

static void test_cube(void)
{
    gb_scene scene;
    build_cube(&scene);
    gb_atlas atlas;
    gb_atlas_stats stats;
    if (!CHECK(build(&scene, 0, &atlas, &stats) == GB_OK, "cube: built"))
        return;
    CHECK_EQ_INT(atlas.header.chart_count, 6, "cube: six charts with the default cone");
    CHECK(charts_are_faces(&scene, &atlas), "cube: each chart is one face");
    CHECK(max_distortion_degrees(&scene, &atlas) < 0.01, "cube: no angle distortion");
    gb_atlas_free(&atlas);
    gb_scene_free(&scene);
}

static void check_discs(gb_scene *scene, const char *name, double cone)
{
    char what[128];
    gb_atlas atlas;
    gb_atlas_stats stats;
    snprintf(what, sizeof what, "%s: built", name);
    if (!CHECK(build(scene, cone, &atlas, &stats) == GB_OK, what))
        return;
    snprintf(what, sizeof what, "%s: more than one chart (%u)", name, atlas.header.chart_count);
    CHECK(atlas.header.chart_count > 1, what);
    printf("# %s: %u grown, %u charts, %u lone; split: %u not discs, %u folded, %u overlapping, "
           "%u wasteful, %u LSCM failures\n", name, stats.grown_charts, stats.charts,
           stats.lone_triangles, stats.splits, stats.folded, stats.overlapping, stats.wasteful,
           stats.lscm_failures);
    snprintf(what, sizeof what, "%s: every chart a topological disc", name);
    CHECK(every_chart_a_disc(scene, &atlas), what);
    snprintf(what, sizeof what, "%s: every UV finite, every triangle of positive area", name);
    CHECK(all_finite_and_positive(&atlas), what);
    snprintf(what, sizeof what, "%s: no two triangles overlap (every pair)", name);
    CHECK_EQ_INT(overlapping_pairs_brute_force(&atlas), 0, what);
    gb_atlas_free(&atlas);
    gb_scene_free(scene);
}

static void test_discs(void)
{
    gb_scene scene;
    build_sphere(&scene, 10, 16);
    check_discs(&scene, "closed sphere", 0);
    build_cylinder(&scene, 24, 4);
    check_discs(&scene, "open cylinder", 0);
    build_ring(&scene, 24);
    gb_atlas atlas;
    gb_atlas_stats stats;
    if (CHECK(build(&scene, 0, &atlas, &stats) == GB_OK, "flat ring: built")) {
        CHECK_EQ_INT(stats.grown_charts, 1, "flat ring: one chart grown (one normal)");
        CHECK(stats.splits >= 1, "flat ring: split for not being a disc");
        gb_atlas_free(&atlas);
    }
    check_discs(&scene, "flat ring", 0);
    build_sphere(&scene, 10, 16);
    check_discs(&scene, "closed sphere, a 90 degree cone", 90);
}

static void test_needles(void)
{
    gb_scene scene;
    build_needles(&scene);
    CHECK_EQ_INT(scene.triangle_count, 8, "needles: the loader kept all eight triangles");
    gb_atlas atlas;
    gb_atlas_stats stats;
    if (!CHECK(build(&scene, 0, &atlas, &stats) == GB_OK, "needles: built"))
        return;
    CHECK(all_finite_and_positive(&atlas), "needles: finite UVs, every area positive");
    CHECK_EQ_INT(overlapping_pairs_brute_force(&atlas), 0, "needles: no overlap");
    check_charts_apart(&atlas, "needles");
    int finite = 1;
    for (uint32_t c = 0; c < atlas.header.chart_count; ++c)
        finite &= isfinite(atlas.chart_records[c].max_angle_distortion) &&
                  isfinite(atlas.chart_records[c].mean_angle_distortion);
    CHECK(finite, "needles: distortion finite");
    /* By brute force: a corner is measured when its two UV edges are at
     * least 4 steps of 2^-24 of the side long; the 1e-6 edges are not. */
    double step = atlas.header.width / 16777216.0, worst = 0.0, sum = 0.0;
    uint64_t needles = 0, measured = 0;
    for (uint32_t t = 0; t < scene.triangle_count; ++t)
        for (int c = 0; c < 3; ++c) {
            if (fmin(uv_edge_texels(&atlas, t, c), uv_edge_texels(&atlas, t, (c + 2) % 3)) <
                4.0 * step) {
                ++needles;
                continue;
            }
            double d = fabs(angle_uv(&atlas, t, c) - angle_3d(&scene, t, c)) * 180.0 / M_PI;
            worst = fmax(worst, d);
            sum += d;
            ++measured;
        }
    CHECK(needles >= 2 && stats.needle_corners == needles,
          "needles: the corners at edges under 4 UV steps are counted, not measured");
    CHECK(fabs(stats.max_angle_distortion - worst) < 1e-3 && worst <= GB_ATLAS_MAX_DISTORTION,
          "needles: the largest distortion is that of the measured corners, within 25 degrees");
    CHECK(fabs(stats.mean_angle_distortion - sum / (double)measured) < 1e-6,
          "needles: the mean distortion is over the measured corners");
    gb_atlas_free(&atlas);
    gb_scene_free(&scene);
}

static void test_packing(void)
{
    gb_scene scene;
    build_cornell_box(&scene, 64, 64);
    gb_atlas atlas;
    gb_atlas_stats stats;
    if (!CHECK(build(&scene, 0, &atlas, &stats) == GB_OK, "Cornell box: built"))
        return;
    CHECK_EQ_INT(overlapping_pairs_brute_force(&atlas), 0,
                 "Cornell box: no two triangles overlap (every pair)");
    CHECK(stats.fill_ratio > 0.3 && stats.fill_ratio <= 1.0, "Cornell box: fill ratio in (0.3, 1]");
    printf("# Cornell box: %u charts, fill %.3f\n", atlas.header.chart_count, stats.fill_ratio);
    check_charts_apart(&atlas, "Cornell box");
    gb_atlas_free(&atlas);
    gb_scene_free(&scene);
}

/* The first `count` triangles of a loaded scene (every vertex kept). */
static void first_triangles(const gb_scene *from, uint32_t count, gb_scene *scene)
{
    begin(scene);
    for (uint32_t v = 0; v < from->vertex_count; ++v)
        add_vertex(scene, from->positions[3 * v], from->positions[3 * v + 1],
                   from->positions[3 * v + 2]);
    for (uint32_t t = 0; t < count && t < from->triangle_count; ++t)
        add_triangle(scene, from->indices[3 * t], from->indices[3 * t + 1],
                     from->indices[3 * t + 2], 0);
    scene_done(scene);
}

/* Charts apart on real scenes: McGuire's Cornell box whole, and Sponza's
 * first triangles (hundreds of small charts), at a few sizes and
 * paddings; skipped when the shared scenes are not there. */
static void check_scene_file(const char *root, const char *file, uint32_t triangles,
                             const uint32_t sizes[2], const uint32_t paddings[2])
{
    char path[4096], name[160];
    snprintf(path, sizeof path, "%s/scenes/shared/%s", root, file);
    gb_scene loaded, scene;
    gb_error error;
    if (gb_scene_load(path, NULL, &loaded, &error) != GB_OK) {
        printf("# skipped %s: %s\n", file, error.message);
        return;
    }
    first_triangles(&loaded, triangles, &scene);
    gb_scene_free(&loaded);
    for (int k = 0; k < 2; ++k) {
        gb_atlas_options options = {.size = sizes[k], .padding = paddings[k]};
        gb_atlas atlas;
        gb_atlas_stats stats;
        snprintf(name, sizeof name, "%s (%u triangles) at %u, padding %u", file,
                 scene.triangle_count, sizes[k], paddings[k]);
        if (!CHECK(gb_atlas_build(&scene, &options, &atlas, &stats, &error) == GB_OK, name)) {
            printf("# %s\n", error.message);
            continue;
        }
        printf("# %s: %u charts, fill %.3f\n", name, stats.charts, stats.fill_ratio);
        check_charts_apart(&atlas, name);
        gb_atlas_free(&atlas);
    }
    gb_scene_free(&scene);
}

static void test_charts_apart(const char *root)
{
    check_scene_file(root, "cornell-original.scene", UINT32_MAX, (uint32_t[2]){256, 1024},
                     (uint32_t[2]){2, 3});
    check_scene_file(root, "sponza.scene", 3000, (uint32_t[2]){512, 256}, (uint32_t[2]){2, 1});
}

static void test_overlap_predicate(void)
{
    const int64_t a[6] = {0, 0, 10, 0, 0, 10};
    const int64_t shared_edge[6] = {10, 0, 10, 10, 0, 10};
    const int64_t shared_corner[6] = {10, 0, 20, 0, 20, 10};
    const int64_t crossing[6] = {2, 2, 12, 2, 2, 12};
    const int64_t inside[6] = {1, 1, 3, 1, 1, 3};
    const int64_t along_edge[6] = {5, 0, 15, -10, 15, 0};  /* touches a's edge from below */
    CHECK(!gb_triangles_overlap(a, shared_edge), "overlap: a shared edge is not an overlap");
    CHECK(!gb_triangles_overlap(a, shared_corner), "overlap: a shared corner is not");
    CHECK(!gb_triangles_overlap(a, along_edge), "overlap: edge against edge is not");
    CHECK(gb_triangles_overlap(a, crossing), "overlap: crossing triangles overlap");
    CHECK(gb_triangles_overlap(a, inside), "overlap: one inside the other overlaps");
    CHECK(gb_triangles_overlap(a, a), "overlap: a triangle overlaps its copy");

    /* the grid finds what all pairs find, on random small triangles */
    enum { N = 400 };
    int64_t *t = malloc(6 * N * sizeof *t);
    for (int i = 0; i < N; ++i) {
        int64_t x = (int64_t)(jitter(3 * i, 0.5) * 0.9 * GB_OVERLAP_ONE + GB_OVERLAP_ONE / 2);
        int64_t y = (int64_t)(jitter(3 * i + 1, 0.5) * 0.9 * GB_OVERLAP_ONE + GB_OVERLAP_ONE / 2);
        int64_t r = GB_OVERLAP_ONE / 40;
        int64_t p[6] = {x, y, x + r, y + (int64_t)jitter(3 * i + 2, r / 2), x, y + r};
        memcpy(t + 6 * i, p, sizeof p);
    }
    long brute = 0;
    for (int i = 0; i < N; ++i)
        for (int j = i + 1; j < N; ++j)
            brute += gb_triangles_overlap(t + 6 * i, t + 6 * j);
    uint64_t found = 0;
    gb_error error;
    CHECK(gb_find_overlaps(t, N, NULL, 0, &found, &error) == GB_OK, "overlap grid: ran");
    CHECK(brute > 0, "overlap grid: the random triangles do overlap somewhere");
    CHECK_EQ_INT(found, brute, "overlap grid: the grid finds every overlapping pair, once");
    free(t);
}

static void test_lscm_adapter(void)
{
    const double tetra[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const uint32_t closed[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    double uvs[8];
    gb_error error;
    CHECK(gb_lscm_parameterize(4, tetra, 4, closed, uvs, &error) != GB_OK,
          "lscm: a closed tetrahedron is refused, not crashed on");
    printf("# lscm on a closed mesh: %s\n", error.message);
    const double quad[12] = {0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0};
    const uint32_t two[6] = {0, 1, 2, 0, 2, 3};
    CHECK(gb_lscm_parameterize(4, quad, 2, two, uvs, &error) == GB_OK, "lscm: a quad maps");
    double e1 = hypot(uvs[2] - uvs[0], uvs[3] - uvs[1]);
    double e2 = hypot(uvs[6] - uvs[0], uvs[7] - uvs[1]);
    CHECK_NEAR(e1 / e2, 2.0, 1e-6, "lscm: the quad keeps its 2:1 sides");
}

static void test_min_area_rect(void)
{
    double angle = 0.3, c0 = cos(angle), s0 = sin(angle), points[8], scratch[10], c, s;
    const double corners[8] = {0, 0, 4, 0, 4, 1, 0, 1};
    for (int i = 0; i < 4; ++i) {
        points[2 * i] = c0 * corners[2 * i] - s0 * corners[2 * i + 1];
        points[2 * i + 1] = s0 * corners[2 * i] + c0 * corners[2 * i + 1];
    }
    double copy[8];
    memcpy(copy, points, sizeof copy);
    gb_min_area_rect(copy, 4, scratch, &c, &s);
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int i = 0; i < 4; ++i) {
        double x = c * points[2 * i] + s * points[2 * i + 1];
        double y = -s * points[2 * i] + c * points[2 * i + 1];
        lo[0] = fmin(lo[0], x);
        hi[0] = fmax(hi[0], x);
        lo[1] = fmin(lo[1], y);
        hi[1] = fmax(hi[1], y);
    }
    CHECK_NEAR((hi[0] - lo[0]) * (hi[1] - lo[1]), 4.0, 1e-9,
               "min area rect: a turned 4 x 1 rectangle is turned back (box area 4)");
}

static void test_file_and_determinism(void)
{
    gb_scene scene;
    build_sphere(&scene, 8, 12);
    gb_atlas atlas, again, back;
    gb_atlas_stats stats;
    gb_error error;
    if (!CHECK(build(&scene, 0, &atlas, &stats) == GB_OK &&
                   build(&scene, 0, &again, &stats) == GB_OK,
               "sphere: built twice"))
        return;
    size_t n = scene.triangle_count;
    CHECK(atlas.header.chart_count == again.header.chart_count &&
          memcmp(atlas.uvs, again.uvs, 6 * n * sizeof *atlas.uvs) == 0 &&
          memcmp(atlas.charts, again.charts, n * sizeof *atlas.charts) == 0,
          "the same scene gives the same atlas");
    scratch_create("atlas");
    const char *path = scratch_path("sphere.atlas");
    CHECK(gb_atlas_write(path, &atlas, &error) == GB_OK, "gb_atlas_write accepts the atlas");
    if (CHECK(gb_atlas_read(path, &back, &error) == GB_OK, "gb_atlas_read reads it back")) {
        CHECK(memcmp(&back.header, &atlas.header, sizeof back.header) == 0 &&
              memcmp(back.uvs, atlas.uvs, 6 * n * sizeof *back.uvs) == 0 &&
              memcmp(back.charts, atlas.charts, n * sizeof *back.charts) == 0 &&
              memcmp(back.chart_records, atlas.chart_records,
                     atlas.header.chart_count * sizeof *back.chart_records) == 0,
              "the file holds what was built");
        CHECK(gb_atlas_check_scene(&back, scene.hash, scene.triangle_count, path, &error) ==
                  GB_OK, "the file belongs to its scene");
        gb_atlas_free(&back);
    }
    scratch_remove();
    gb_atlas_free(&atlas);
    gb_atlas_free(&again);
    gb_scene_free(&scene);
}

/* A chart's cost: its smallest rectangle in whole texels grown by the
 * padding, whatever its turn: a unit square at 3.9 texels per unit,
 * padding 2, costs (4 + 2 * 2)^2 = 64 texels, turned by 45 degrees as
 * well. */
static void test_merge_cost(void)
{
    double square[12] = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1}, turned[12];
    for (int k = 0; k < 6; ++k) {
        double x = square[2 * k], y = square[2 * k + 1], c = sqrt(0.5);
        turned[2 * k] = c * x - c * y;
        turned[2 * k + 1] = c * x + c * y;
    }
    uint32_t triangles[2] = {0, 1};
    gb_chart chart = {2, triangles, square, 1.0};
    CHECK_NEAR(gb_chart_cost(&chart, 3.9, 2), 64.0, 1e-9, "merge: a unit square costs 8 x 8");
    chart.uvs = turned;
    CHECK_NEAR(gb_chart_cost(&chart, 3.9, 2), 64.0, 1e-9, "merge: ... turned by 45 degrees too");
    CHECK_NEAR(gb_chart_cost(&chart, 0.01, 2), 25.0, 1e-9,
               "merge: a chart under a texel costs one texel and its gutter, 5 x 5");
}

/* A sphere cut by a 10 degree cone into charts of a few texels each (a
 * 96 x 96 atlas): small charts join, no corner beyond the bound (measured
 * here), every chart a disc, no overlap. */
static void test_merge(void)
{
    gb_scene scene;
    build_sphere(&scene, 10, 16);
    gb_atlas_options options = {.cone_degrees = 10, .size = 96,
                                .padding = GB_ATLAS_DEFAULT_PADDING};
    gb_atlas atlas;
    gb_atlas_stats stats;
    gb_error error;
    if (!CHECK(gb_atlas_build(&scene, &options, &atlas, &stats, &error) == GB_OK,
               "merge: sphere built")) {
        printf("# %s\n", error.message);
        gb_scene_free(&scene);
        return;
    }
    printf("# merge: %u grown, %u joins, %u charts, max distortion %.2f\n", stats.grown_charts,
           stats.merged, stats.charts, max_distortion_degrees(&scene, &atlas));
    CHECK(stats.merged > 0 && stats.charts < stats.grown_charts, "merge: small charts joined");
    CHECK(max_distortion_degrees(&scene, &atlas) <= GB_ATLAS_MAX_DISTORTION + 0.5,
          "merge: no corner distorted beyond the bound (+0.5 degree of fixed point)");
    CHECK(every_chart_a_disc(&scene, &atlas), "merge: every chart a disc");
    CHECK_EQ_INT(overlapping_pairs_brute_force(&atlas), 0, "merge: no two triangles overlap");
    check_charts_apart(&atlas, "merge");
    gb_atlas_free(&atlas);
    gb_scene_free(&scene);
}

/* A right isosceles triangle far below a texel beside a large quad: laid
 * flat, its hypotenuse along u, it is scaled (angles kept) until its box
 * fills its 1 x 1 rect: the hypotenuse one texel, its area 1/4 texel. */
static void test_tiny_chart_scale(void)
{
    gb_scene scene;
    begin(&scene);
    uint32_t q[4] = {add_vertex(&scene, 0, 0, 0), add_vertex(&scene, 10, 0, 0),
                     add_vertex(&scene, 10, 10, 0), add_vertex(&scene, 0, 10, 0)};
    add_quad_indices(&scene, q[0], q[1], q[2], q[3]);
    uint32_t a = add_vertex(&scene, 20, 0, 0), b = add_vertex(&scene, 20.001, 0, 0),
             c = add_vertex(&scene, 20, 0.001, 0);
    add_triangle(&scene, a, b, c, 0);
    scene_done(&scene);
    gb_atlas atlas;
    gb_atlas_stats stats;
    if (!CHECK(build(&scene, 0, &atlas, &stats) == GB_OK, "tiny chart: built")) {
        gb_scene_free(&scene);
        return;
    }
    const float *uv = atlas.uvs + 12;
    double area = 0.5 * (((double)uv[2] - uv[0]) * ((double)uv[5] - uv[1]) -
                         ((double)uv[3] - uv[1]) * ((double)uv[4] - uv[0])) *
                  atlas.header.width * atlas.header.height;
    printf("# tiny chart: %.6f texels\n", area);
    CHECK_NEAR(area, 0.25, 1e-3, "tiny chart: scaled to fill its texel, a quarter texel");
    CHECK(max_distortion_degrees(&scene, &atlas) < 0.05, "tiny chart: its angles kept");
    gb_atlas_free(&atlas);
    gb_scene_free(&scene);
}

int main(void)
{
    const char *root = getenv("GB_ROOT");
    root = root ? root : ".";
    test_planar_chart();
    test_cube();
    test_discs();
    test_needles();
    test_packing();
    test_charts_apart(root);
    test_overlap_predicate();
    test_lscm_adapter();
    test_min_area_rect();
    test_file_and_determinism();
    test_merge_cost();
    test_merge();
    test_tiny_chart_scale();
    return tap_done();
}
