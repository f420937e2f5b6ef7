/* skeleton.h — the curvilinear skeleton of the empty space (thin's output,
 * segment's input) in memory and in its `.skel` file.
 *
 * The skeleton is a graph embedded in the scene: each node has a world
 * position and the radius of the largest ball of empty space around it; each
 * edge joins two nodes. The file is a gibake container of kind "SKEL"
 * (formats/FORMATS.md, "Skeleton file") with sections "header", "nodes",
 * "edges"; it also records the frame of the voxel grid it was computed on,
 * the scene hash and thin's parameters.
 *
 *   gb_skeleton s = {0};                       // fill counts, arrays, frame
 *   gb_skeleton_write("scene.skel", &s, &error);   // temporary file + rename
 *   gb_skeleton_read("scene.skel", &s, &error);    // checks every field
 *   gb_skeleton_free(&s);
 *
 * The caller owns the gb_skeleton; gb_skeleton_read and thin fill it with
 * malloc'ed arrays that gb_skeleton_free releases (also on a zeroed one).
 */
#ifndef GB_SKELETON_H
#define GB_SKELETON_H

#include <stddef.h>
#include <stdint.h>

#include "result.h"

enum { GB_SKELETON_VERSION = 1 };

typedef struct gb_skeleton_node {
    float position[3];          /* world units */
    float radius;               /* maximal ball: distance to the nearest surface, world units */
} gb_skeleton_node;

typedef struct gb_skeleton {
    uint32_t node_count;
    uint32_t edge_count;
    gb_skeleton_node *nodes;    /* node_count */
    uint32_t *edges;            /* edge_count pairs (a, b): a < b, sorted, no duplicate */

    /* the voxel grid the skeleton was computed on */
    double voxel_size;
    double world_origin[3];
    int32_t grid_size[3];
    uint32_t resolution;
    uint64_t scene_hash;

    /* thin's parameters and what it did */
    double persistence;         /* scale of opening - distance in the lifespan test */
    double min_lifespan;        /* iterations added to it */
    uint32_t iterations;        /* collapse iterations */
    uint32_t cavities_broken;   /* 2-cycles (cavities) opened to get a graph */
} gb_skeleton;

gb_result gb_skeleton_write(const char *path, const gb_skeleton *skeleton, gb_error *error);
/* On failure *skeleton is zeroed. */
gb_result gb_skeleton_read(const char *path, gb_skeleton *skeleton, gb_error *error);
/* The same on a file's bytes in memory (tests, fuzzing); path is for messages. */
gb_result gb_skeleton_parse(const void *bytes, size_t size, const char *path,
                            gb_skeleton *skeleton, gb_error *error);
/* Checks what the reader checks, on a skeleton in memory (the writer calls it). */
gb_result gb_skeleton_validate(const gb_skeleton *skeleton, const char *path, gb_error *error);
void gb_skeleton_free(gb_skeleton *skeleton);

/* The edge rule of a skeleton and of its segmentation: edge_count pairs
 * (a, b) with a < b < node_count, sorted, none repeated; GB_ERROR_INVALID,
 * naming path, for the first that is not. */
gb_result gb_skeleton_check_edges(const uint32_t *edges, uint32_t edge_count, uint32_t node_count,
                                  const char *path, gb_error *error);

#endif
