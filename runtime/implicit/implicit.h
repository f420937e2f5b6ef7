/* implicit.h — implicit visibility (Dong, Kautz, Theobalt, Seidel 2007),
 * Algorithm 1, on the CPU; runtime/implicit/implicit.c shows it (gb_implicit_method).
 * One file a step:
 *   implicit_elements.c   CreateSurfels: discs at the vertices (4.1)
 *   implicit_hierarchy.c  CreateGeometricHierarchy: segments, a quadtree a
 *                         segment (4.1)
 *   implicit_update.c     UpdateElements: nodes refitted to the vertices (4.2.1)
 *   implicit_bins.c       the cube map of 6 x N x N bins (4.2.2)
 *   implicit_links.c      CreateHierarchicalLinks, RefineHierarchicalLinks,
 *                         PushdownLinks (4.2.2 - 4.2.4)
 *   implicit_bounce.c     ComputeIlluminateLeafNodes, PullupEnergy (4.3, 4.4)
 *   implicit_environment.c  a lat-long environment map into the bins (4.4)
 *
 * Elements. The paper's models are tessellated finely; scenes here are not
 * (the Cornell box has 4 vertices a wall), so each triangle is first cut
 * into n x n smaller ones (n = ceil(longest edge / element size)) and the
 * elements are the vertices of that finer mesh, welded within a segment. A
 * vertex where segments meet (a box's corner) is one element in each.
 *
 * Segments stand for the paper's UV charts, which scene files do not have:
 * triangles grown from a seed across shared edges while they have the
 * seed's material and a normal within GB_IMPLICIT_SEGMENT_DEGREES of it.
 *
 * Per frame (Algorithm 1, steps 4-11): gb_implicit_update_elements,
 * gb_implicit_create_links (Create, Refine, PushdownLinks), then
 * gb_implicit_illuminate; gb_implicit_model_create (steps 1-2) runs once.
 * bench/implicit_steps.c times each step on a deforming model; the runtime
 * (implicit.c) rebuilds the links each frame while that costs less than
 * GB_IMPLICIT_FRAME_SECONDS (gbview's scenes do not move, so above it the
 * links of the last build, identical, are kept).
 *
 * Light is diffuse (Kd of the material, no texture average, no gloss). The
 * display term of an element is its incident radiance E / pi from the
 * environment and the bounces (what the direct pass does not draw), the
 * renderer multiplies it by the pixel's Kd.
 */
#ifndef GB_IMPLICIT_H
#define GB_IMPLICIT_H

#include <math.h>
#include <stdint.h>

#include "result.h"
#include "scene.h"

#define GB_IMPLICIT_SEGMENT_DEGREES 30.0
#define GB_IMPLICIT_NO_NODE 0xffffffffu

/* Cube map of bins: face = 2 * axis + (direction[axis] < 0), u and v the
 * next two axes (axis + 1, axis + 2 mod 3) over |direction[axis]|. */
typedef struct gb_implicit_bins {
    int n;                      /* bins a face edge */
    uint32_t count;             /* 6 n n */
    float *directions;          /* count * 3: unit direction of each bin's centre */
    float *solid_angles;        /* count: exact solid angle of each bin (sr) */
} gb_implicit_bins;

gb_result gb_implicit_bins_create(int n, gb_implicit_bins *bins, gb_error *error);
void gb_implicit_bins_free(gb_implicit_bins *bins);

/* (b - a) x (c - a) in double: twice the triangle's area along its normal. */
static inline void gb_implicit_triangle_cross(const float *a, const float *b, const float *c,
                                              double n[3])
{
    double u[3], v[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = (double)b[k] - a[k];
        v[k] = (double)c[k] - a[k];
    }
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
}

/* The one bin of direction d (need not be unit), in [0, 6 n n); -1 for the
 * zero vector or a non-finite one. Ties between faces go to the lowest
 * axis; u or v exactly on a face's edge go to the last row or column.
 * Inline: link creation calls it millions of times a frame. */
static inline int gb_implicit_bin(int n, const float d[3])
{
    if (n <= 0 || !isfinite(d[0]) || !isfinite(d[1]) || !isfinite(d[2]))
        return -1;
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (fabsf(d[a]) > fabsf(d[axis]))
            axis = a;
    float major = fabsf(d[axis]);
    if (major == 0.0f)
        return -1;
    int face = 2 * axis + (d[axis] < 0.0f);
    int cell[2];
    for (int k = 0; k < 2; ++k) {
        float t = d[(axis + 1 + k) % 3] / major;           /* in [-1, 1] */
        int i = (int)floorf(0.5f * (t + 1.0f) * (float)n);
        cell[k] = i < 0 ? 0 : i >= n ? n - 1 : i;
    }
    return (face * n + cell[1]) * n + cell[0];
}

/* A node of the geometric hierarchy: nodes [0, element_count) are the
 * elements (leaves); internal nodes follow, each after all its children. */
typedef struct gb_implicit_node {
    float position[3];          /* area-weighted mean of the children */
    float normal[3];            /* unit, area-weighted mean */
    float area;
    float box_min[3], box_max[3];
    uint32_t first_child, child_count;  /* into children[]; 0 children: a leaf */
    uint32_t segment;
} gb_implicit_node;

typedef struct gb_implicit_model {
    uint32_t segment_count;
    uint32_t *triangle_segment; /* scene triangle -> segment */
    uint32_t element_count, node_count;
    gb_implicit_node *nodes;
    uint32_t *children;
    uint32_t root_count;        /* one per segment */
    uint32_t *roots;
    float *Kd, *Le;             /* element_count * 3: diffuse reflectance, emission */
    float *vertices;            /* element_count * 3: the vertex of each element
                                   (its node's position is the centroid of its area) */
    uint32_t triangle_count;    /* the finer mesh, for display */
    uint32_t *triangles;        /* triangle_count * 3 elements */
    float element_size;         /* target edge of the finer mesh */
} gb_implicit_model;

/* Element size as a fraction of the scene's bounding diagonal, by default. */
#define GB_IMPLICIT_ELEMENTS_PER_DIAGONAL 28.0f

/* Steps 1-2. element_size 0: the default. */
gb_result gb_implicit_model_create(const gb_scene *scene, float element_size,
                                   gb_implicit_model *model, gb_error *error);
void gb_implicit_model_free(gb_implicit_model *model);
/* implicit_hierarchy.c: segments of the scene's triangles. */
gb_result gb_implicit_segment_faces(const gb_scene *scene, gb_implicit_model *model,
                                    gb_error *error);
/* implicit_hierarchy.c: the quadtrees over the elements already made. */
gb_result gb_implicit_create_geometric_hierarchy(gb_implicit_model *model, gb_error *error);
/* implicit_elements.c: the elements of the finer mesh. */
gb_result gb_implicit_create_surfels(const gb_scene *scene, gb_implicit_model *model,
                                     gb_error *error);
/* implicit_hierarchy.c: an internal node's position (area-weighted mean),
 * normal, area and box from its children's. */
void gb_implicit_summarise(gb_implicit_model *model, gb_implicit_node *node);
/* Step 4, UpdateElements (implicit_update.c): every node again from
 * model->vertices, which the caller may have moved (a deforming model),
 * leaves from the finer triangles, internal nodes from their children; the
 * hierarchy stays. gb_implicit_update_leaves does the leaves only. */
gb_result gb_implicit_update_elements(gb_implicit_model *model, gb_error *error);
gb_result gb_implicit_update_leaves(gb_implicit_model *model, gb_error *error);

/* Seconds (wall clock, or CPU time of the process: both threads count) of
 * CreateHierarchicalLinks, Refine + PushdownLinks, and the per-element
 * lists with the lights' visibility. */
typedef struct gb_implicit_link_seconds {
    double create, refine, compact;
} gb_implicit_link_seconds;

/* Section 4.4 with a map (implicit_environment.c): the mean radiance of a
 * lat-long RGB map (formats/environment.h: its convention and lookup) over
 * each bin, times scale, into radiance (bins->count * 3, the caller's).
 * Each bin is sampled on a GB_IMPLICIT_MAP_SAMPLES^2 grid over its face
 * square, each sample weighted by its solid angle. */
#define GB_IMPLICIT_MAP_SAMPLES 8
gb_result gb_implicit_environment_bins(const gb_implicit_bins *bins, const gb_texture *map,
                                       float scale, float *radiance, gb_error *error);

/* Links after PushdownLinks: each element's receiving links, one per
 * filled bin, weighted by the bin's max(0, cos) solid angle, normalised so
 * that the weights of all bins above the element sum to pi. */
typedef struct gb_implicit_links {
    uint32_t *first;            /* element_count + 1 */
    uint32_t *source;           /* first[element_count]: the node seen */
    float *weight;
    float *environment_weight;  /* element_count: the empty bins' share */
    float *environment_irradiance;  /* element_count * 3 when the links were
                                   made with an environment map: sum over the
                                   empty bins of weight x its radiance; else NULL */
    uint8_t *light_visible;     /* element_count * light_count, or NULL: 1 when
                                   the bin toward the light holds no nearer link */
    uint32_t light_count;
    uint64_t created;           /* links stored while creating (statistics) */
    gb_implicit_link_seconds wall, cpu;  /* statistics: time of each step */
} gb_implicit_links;

typedef struct gb_implicit_link_options {
    int hierarchical;           /* 0: every element pair (the brute force) */
    const gb_scene *lights;     /* its point, spot and directional lights get
                                   implicit shadows; NULL: unshadowed */
    const float *environment;   /* bins->count * 3: the environment's radiance
                                   a bin (gb_implicit_environment_bins), or
                                   NULL: the scene's constant colour */
} gb_implicit_link_options;

/* Steps 5-7 for a static scene. bin_targets, when not NULL, receives the
 * node_count * bins->count bins before compaction (tests), the caller frees. */
gb_result gb_implicit_create_links(const gb_implicit_model *model, const gb_implicit_bins *bins,
                                   const gb_implicit_link_options *options,
                                   gb_implicit_links *links, uint32_t **bin_targets,
                                   gb_error *error);
void gb_implicit_links_free(gb_implicit_links *links);

/* Steps 8-11. radiance: node_count * 3 scratch; display: element_count * 3
 * out, the incident radiance (E / pi) the runtime's direct pass does not
 * draw: the environment's, through the empty bins (4.4), plus the indirect
 * light summed over bounces. */
typedef struct gb_implicit_solution {
    float *direct;              /* element_count * 3: E / pi from lights */
    float *sky;                 /* element_count * 3: its environment part */
    float *radiance;            /* node_count * 3: outgoing radiance */
    float *emission;            /* node_count * 3: Le pulled up */
    float *display;             /* element_count * 3 */
    float *gathered;            /* element_count * 3 scratch */
} gb_implicit_solution;

gb_result gb_implicit_solution_create(const gb_implicit_model *model,
                                      gb_implicit_solution *solution, gb_error *error);
void gb_implicit_solution_free(gb_implicit_solution *solution);
/* Direct light at the elements: area lights through the links, the
 * environment through the empty bins, point, spot and directional lights
 * unshadowed. Then bounces of indirect light into display. */
void gb_implicit_illuminate(const gb_scene *scene, const gb_implicit_model *model,
                            const gb_implicit_links *links, int bounces,
                            gb_implicit_solution *solution);
/* PullupEnergy of per-element values (element_count * 3 at the start of
 * values, node_count * 3 in all): each internal node gets the area-weighted
 * mean of its children. */
void gb_implicit_pullup(const gb_implicit_model *model, float *values);

/* implicit.c: the GI method listed in methods.c. It runs steps 4-7 again
 * each frame while they took under this (the paper's frames: 0.11-0.22 s). */
#define GB_IMPLICIT_FRAME_SECONDS 0.25

/* Milliseconds of each step summed over the frames drawn (implicit.c). */
typedef struct gb_implicit_step_times {
    uint32_t frames, rebuilds;  /* frames drawn, of which links rebuilt */
    double update_ms, create_ms, refine_ms, illuminate_ms;
} gb_implicit_step_times;
void gb_implicit_times(const void *method_state, gb_implicit_step_times *times);

struct gb_indirect_method;
extern const struct gb_indirect_method gb_implicit_method;

#endif
