/* implicit_model.h — the model every step of implicit visibility works on
 * (implicit.h lists the steps): the elements and the geometric hierarchy
 * above them, as nodes; made by implicit_elements.c, the caller owns it. */
#ifndef GB_IMPLICIT_MODEL_H
#define GB_IMPLICIT_MODEL_H

#include <stdint.h>

#define GB_IMPLICIT_SEGMENT_DEGREES 30.0
#define GB_IMPLICIT_NO_NODE 0xffffffffu
/* The segment of a node above the segments' roots (implicit_hierarchy.c):
 * its normal is only a mean, it has no side it faces. */
#define GB_IMPLICIT_SEVERAL_SEGMENTS 0xffffffffu

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

/* Whether the node faces one side: a node of several segments (a cluster
 * of differently oriented surfaces) has none, and lights or hides from
 * every direction. */
static inline int gb_implicit_node_has_side(const gb_implicit_node *node)
{
    return node->segment != GB_IMPLICIT_SEVERAL_SEGMENTS;
}

/* The two sides of a surface. Surfaces reflect on both sides
 * (common/brdf.h), as in the reference: each element gathers on each side
 * from the bins of that hemisphere and shows, seen from a side, what it
 * gathered there (only elements of an open part of the mesh have a back:
 * gb_implicit_node_two_sided below). Values a side are stored side after side: value v of
 * node n (element e) on side s at [s * node_count + n] ([s * element_count
 * + e]). A node of several segments has no side: both its values are the
 * mean of its children's fronts (implicit_bounce.c). */
enum { GB_IMPLICIT_FRONT = 0, GB_IMPLICIT_BACK = 1, GB_IMPLICIT_SIDES = 2 };

typedef struct gb_implicit_model {
    uint32_t segment_count;
    uint32_t *triangle_segment; /* scene triangle -> segment */
    uint8_t *segment_open;      /* segment_count: 1 when its part of the mesh
                                   is open (implicit_closed_parts.h) */
    uint8_t *segment_regrouped; /* segment_count, or NULL: 1 for a segment of
                                   small ones (implicit_small_segments.h),
                                   which is one element */
    uint32_t element_count, node_count;
    gb_implicit_node *nodes;
    uint32_t *children;
    uint32_t root_count;        /* one per segment */
    uint32_t *roots;
    uint32_t top;               /* the root of all: a tree over the roots */
    float *Kd, *Le;             /* element_count * 3: diffuse reflectance, emission */
    uint32_t vertex_count;      /* the finer mesh's vertices, which the caller
                                   moves when the model deforms */
    float *vertices;            /* vertex_count * 3 */
    uint32_t *vertex_element;   /* vertex_count: the element a vertex is part of */
    uint32_t triangle_count;    /* the finer mesh: for the elements' areas and
                                   for display */
    uint32_t *triangles;        /* triangle_count * 3 vertices */
    float element_size;         /* target edge of the finer mesh */
    float element_cell;         /* the grid cell of one element; 0: one a vertex */
} gb_implicit_model;

/* Whether the node has a back that can be seen: it is of one segment, in
 * an open part of the mesh (implicit_closed_parts.h). The back of a closed
 * part faces into the volume it closes: its elements are one-sided, they
 * gather, reflect and show on their front only (shown from behind, their
 * front's light), and a link seeing such a back hides and sends nothing.
 * A node of several segments has no side. */
static inline int gb_implicit_node_two_sided(const gb_implicit_model *model,
                                             const gb_implicit_node *node)
{
    return gb_implicit_node_has_side(node) && model->segment_open[node->segment];
}

/* Element size as a fraction of the scene's bounding diagonal, by default. */
#define GB_IMPLICIT_ELEMENTS_PER_DIAGONAL 28.0f

/* The runtime's element_cell: the finer mesh's vertices of one segment in
 * one cell of a grid of this fraction of the element size are one element,
 * so that a finely tessellated scene gets as many elements as its size
 * needs, not one a vertex (Sponza: 16 238 elements, with its small
 * segments regrouped: implicit_small_segments.h). */
#define GB_IMPLICIT_ELEMENT_CELL 0.5f

#endif
