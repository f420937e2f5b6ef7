/* topo.h — the passes of the topological GI method (Noël & Biri 2014, §V),
 * one file each, and the data they hand on. gb_topo_method (topo.c) runs
 * them each frame:
 *
 *   VPLs      topo_vpls.c               paths from the primary lights (Embree, once)
 *   gates     topo_assignment.c         (once) the .seg's gates, as segment fitted
 *                                       them, in lists per cluster, with routes
 *   GP        gbuffer.c + topo_clusters.c  the visibility cluster of each fragment (GPU)
 *   IUGC      topo_geometry_clusters_gpu.c  geometry clusters (Olsson et al. 2012)
 *                                       that never straddle two visibility clusters
 *             (topo_geometry_clusters.c: the same on the CPU, the tests' oracle)
 *   LA        topo_assignment_gpu.c     VPLs per geometry cluster, with their route
 *                                       (one gate, or two in a row)
 *             (topo_assignment.c: the same on the CPU, the tests' oracle)
 *   IL        topo_gather.c             per fragment, the assigned VPLs, cone test;
 *                                       a fragment with no visibility cluster
 *                                       gathers every VPL, unshadowed
 *
 * The CPU parts (VPLs, CPU IUGC, CPU LA) are plain C on plain arrays, so the
 * unit tests run them without a GL context.
 */
#ifndef GB_TOPO_H
#define GB_TOPO_H

#include <epoxy/gl.h>
#include <stdint.h>

#include "indirect_method.h"
#include "result.h"
#include "scene.h"
#include "segmentation.h"
#include "topo_clusters.h"
#include "vpl.h"

extern const gb_indirect_method gb_topo_method;

/* Wall-clock ms of the method's passes, summed over its frames (glFinish
 * after each): the visibility clusters (GPU), IUGC (GPU, with its count
 * read back; with GB_TOPO_IUGC=cpu: CPU, with the G-buffer read back and
 * the geometry clusters sent back), LA (GPU), IL (GPU). */
typedef struct gb_topo_pass_times {
    double clusters_ms, iugc_ms, la_ms, il_ms;
    uint32_t frames;
} gb_topo_pass_times;

/* The times of a state gb_topo_method.create made. */
void gb_topo_times(const void *state, gb_topo_pass_times *times);

/* How the indirect light is shadowed (gbview --topo-visibility). */
typedef enum gb_topo_visibility {
    GB_TOPO_FULL = 0,           /* own cluster, plus gates' cones (the paper) */
    GB_TOPO_CLUSTERS,           /* own cluster only: gates off */
    GB_TOPO_NONE,               /* every VPL everywhere: no shadows on indirect */
} gb_topo_visibility;

/* topo's gbview options (topo_options.c); zero fields: the defaults. */
typedef struct gb_topo_parameters {
    int vpls;                   /* VPLs traced from the lights (--vpls) */
    const char *write_vpls;     /* write the VPL set here (--write-vpls) */
    int visibility;             /* a gb_topo_visibility (--topo-visibility) */
} gb_topo_parameters;
extern const gb_method_option gb_topo_options[];

enum { GB_TOPO_NO_GATE = 0xffffffffu };

/* ---- VPLs (topo_vpls.c) ------------------------------------------------
 * count VPLs from paths traced from the primary lights: a path starts on a
 * light with power Phi / paths and leaves a VPL at each diffuse hit, of
 * power (incoming flux) * Kd; it goes on in a cosine direction with
 * probability max(Kd) (Russian roulette, flux divided by it). Paths are
 * started until count VPLs exist; every power is divided by the number of
 * paths started. Deterministic for a seed. Lights of no power (a scene
 * with no light, gb_scene_has_light) give no VPL: set->count 0. */
gb_result gb_topo_vpls_generate(const gb_scene *scene, uint32_t count, uint64_t seed,
                                gb_vpl_set *set, gb_error *error);

/* ---- IUGC (topo_geometry_clusters.c) ----------------------------------- */
typedef struct gb_geometry_cluster {
    uint32_t visibility_cluster;
    float box_min[3], box_max[3];
    float centre[3], radius;    /* bounding sphere of the box */
} gb_geometry_cluster;

typedef struct gb_topo_frame_input {
    int width, height;
    const float *depth;         /* width * height, reversed (0: nothing) */
    uint32_t *clusters;         /* width * height * 2: in x, out y = geometry cluster */
    float view_to_world[16];
    float tan_half_fov[2];
    float near;
} gb_topo_frame_input;

/* The frame input of a view at width x height (depth, clusters NULL). */
gb_topo_frame_input gb_topo_frame_input_of_view(const gb_view *view, int width, int height);

typedef struct gb_geometry_clusters {
    uint32_t count;
    size_t capacity;
    gb_geometry_cluster *clusters;
} gb_geometry_clusters;

/* Tiles of GB_TOPO_TILE^2 pixels, depth slices as Olsson et al. (k =
 * floor(log(-z / near) / log(1 + 2 tan(fov_y / 2) / tiles_y))); in each
 * tile the keys (slice, visibility cluster) are sorted locally and each
 * distinct key is one geometry cluster. Fragments without a visibility
 * cluster get GB_NO_CLUSTER. Fills clusters[2 i + 1]. */
enum { GB_TOPO_TILE = 32 };
gb_result gb_topo_geometry_clusters_build(const gb_topo_frame_input *frame,
                                          gb_geometry_clusters *out, gb_error *error);
void gb_geometry_clusters_free(gb_geometry_clusters *clusters);

/* The depth slice of the key at reversed depth d > 0 (the formula above,
 * tiles_y from frame->height); non-increasing in d. */
uint32_t gb_topo_depth_slice(const gb_topo_frame_input *frame, float d);

/* World position of pixel (x, y) at reversed depth d. */
void gb_topo_pixel_position(const gb_topo_frame_input *frame, int x, int y, float d, float out[3]);

/* ---- IUGC on the GPU (topo_geometry_clusters_gpu.c) ---------------------
 * The same geometry clusters, numbered as gb_topo_geometry_clusters_build
 * numbers them (tiles row by row, keys in order within a tile), made by
 * three compute passes: per tile, the distinct keys in order in shared
 * memory; a prefix sum of the tiles' counts; per tile, boxes by atomics on
 * floats as ordered uints, then spheres. The G-buffer's clusters.y gets
 * the geometry cluster, `clusters` the spheres in LA's layout (vec4 centre
 * and radius, uvec4 visibility cluster, 0, 0, 0), `boxes` vec4 min, vec4
 * max. The slice of a depth is looked up in a table of the CPU's slice
 * boundaries, so that the keys are the CPU's bit for bit. */
typedef struct gb_topo_iugc_gpu {
    GLuint tile_program, scan_program, bounds_program;
    GLuint slice_bounds, tile_counts, tile_offsets, total, clusters, boxes;
    uint32_t slice_count, tile_count, capacity;
    int slices_exact;           /* the table covers every positive depth */
    float table_near, table_tan_y;
    int table_height;
} gb_topo_iugc_gpu;

gb_result gb_topo_iugc_gpu_create(gb_topo_iugc_gpu *iugc, gb_error *error);
/* Reads frame's width, height, view_to_world, tan_half_fov, near (not its
 * arrays); depth and clusters: the G-buffer's textures. *count: the number
 * of geometry clusters (the one value read back, for LA). */
gb_result gb_topo_iugc_gpu_run(gb_topo_iugc_gpu *iugc, GLuint depth, GLuint clusters,
                               const gb_topo_frame_input *frame, uint32_t *count,
                               gb_error *error);
/* Copies count clusters back (tests). */
gb_result gb_topo_iugc_gpu_read(const gb_topo_iugc_gpu *iugc, uint32_t count,
                                gb_geometry_clusters *out, gb_error *error);
void gb_topo_iugc_gpu_destroy(gb_topo_iugc_gpu *iugc);

/* ---- LA (topo_assignment.c) -------------------------------------------- */
/* How light leaves a visibility cluster: through one of its gates into the
 * neighbour on the other side (the paper's cones, Fig. 11), or through that
 * gate and then one gate of the neighbour into the cluster beyond (the
 * sample must then lie in both cones). target: the cluster it lights. */
enum { GB_TOPO_ROUTE_GATES = 2 };
typedef struct gb_topo_route {
    uint32_t gates[GB_TOPO_ROUTE_GATES];   /* the second GB_TOPO_NO_GATE: one gate */
    uint32_t target;
} gb_topo_route;

/* The routes from one cluster to one target: routes[first .. first + count). */
typedef struct gb_topo_route_group {
    uint32_t target, first, count;
} gb_topo_route_group;

typedef struct gb_topo_gates {
    uint32_t cluster_count;
    uint32_t *offsets;          /* cluster_count + 1, into gates */
    uint32_t *gates;            /* the gates of each cluster */
    uint32_t route_count;
    uint32_t *route_offsets;    /* cluster_count + 1, into routes */
    gb_topo_route *routes;      /* the routes out of each cluster, by target */
    uint32_t group_count;
    uint32_t *group_offsets;    /* cluster_count + 1, into groups */
    gb_topo_route_group *groups;    /* the groups of each cluster, by target */
} gb_topo_gates;

/* The lists above from the segmentation's gates as they are (with the
 * bake's voxels, segment fitted them to the openings and added the opening
 * gates: tools/segment/gate_openings.h). */
gb_result gb_topo_gates_build(const gb_segmentation *segmentation, gb_topo_gates *gates,
                              gb_error *error);
void gb_topo_gates_free(gb_topo_gates *gates);

/* A VPL assigned to a geometry cluster, with the group of routes its light
 * may take (GB_TOPO_NO_GATE: same visibility cluster). */
typedef struct gb_topo_entry {
    uint32_t vpl, group;
} gb_topo_entry;

typedef struct gb_topo_assignment {
    uint32_t cluster_count, entry_count;
    size_t entry_capacity;
    uint32_t *ranges;           /* cluster_count * 2: offset, count */
    gb_topo_entry *entries;
} gb_topo_assignment;

/* The cone of a VPL at p through a gate: apex p, axis toward the gate's
 * centre, half-angle atan(radius / distance). A VPL within the radius of
 * the centre has no cone: hits_sphere then says yes, contains tests the
 * segment from p to x against the disk itself (big fitted gates have many
 * VPLs that close; lighting every direction from them lit whole clusters
 * behind walls). */
int gb_topo_cone_hits_sphere(const float p[3], const gb_visibility_gate *gate,
                             const float centre[3], float radius);
int gb_topo_cone_contains(const float p[3], const gb_visibility_gate *gate, const float x[3]);
/* x lies in the cone of every gate of the route. */
int gb_topo_route_contains(const float p[3], const gb_segmentation *segmentation,
                           const gb_topo_route *route, const float x[3]);
/* The group of the routes from cluster from to cluster to; GB_TOPO_NO_GATE:
 * none. */
uint32_t gb_topo_group_of(const gb_topo_gates *gates, uint32_t from, uint32_t to);
/* x lies on one of the group's routes (IL's test). */
int gb_topo_group_contains(const float p[3], const gb_segmentation *segmentation,
                           const gb_topo_gates *gates, uint32_t group, const float x[3]);

/* LA (§V.C): for each geometry cluster, the VPLs of its own visibility
 * cluster, then (GB_TOPO_FULL) every other VPL once, with the group of
 * routes from its cluster to the geometry cluster's, when one route's cones
 * all meet the cluster's bounding sphere. vpl_cluster[i]: the visibility
 * cluster of VPL i (-1: none; such a VPL lights nothing). */
gb_result gb_topo_assign(const gb_geometry_clusters *clusters, const gb_vpl_set *vpls,
                         const int32_t *vpl_cluster, const gb_segmentation *segmentation,
                         const gb_topo_gates *gates, gb_topo_visibility visibility,
                         gb_topo_assignment *out, gb_error *error);
void gb_topo_assignment_free(gb_topo_assignment *assignment);

/* ---- IL (topo_gather.c) ------------------------------------------------ */
typedef struct gb_topo_gather_pass {
    GLuint program, empty_vertex_array;
    GLuint vpl_buffer, gate_buffer, route_buffer, group_buffer, range_buffer, entry_buffer;
    GLsizeiptr range_size, entry_size;
    uint32_t vpl_count;
    float vsl_radius;
} gb_topo_gather_pass;

/* vsl_radius: R of the VPLs as virtual spherical lights (topo_gather.c),
 * the geometric term's 1/r^2 replaced by Omega(r) / (pi R^2). */
gb_result gb_topo_gather_create(const gb_vpl_set *vpls, const gb_segmentation *segmentation,
                                const gb_topo_gates *gates, float vsl_radius,
                                gb_topo_gather_pass *pass, gb_error *error);
/* R for vpl_count VPLs on the scene's surfaces: sqrt(S area / (pi
 * vpl_count)), S = GB_TOPO_VSL_SHARE, the radius of the disc S of them
 * would cover if they tiled the surfaces evenly, at least voxel_size. */
float gb_topo_vsl_radius(const gb_scene *scene, uint32_t vpl_count, float voxel_size);
#define GB_TOPO_VSL_SHARE 16.0
/* Draws the indirect light into the bound framebuffer (additive blending
 * set by the renderer); every_vpl: GB_TOPO_NONE. */
void gb_topo_gather_draw(const gb_topo_gather_pass *pass, const float view_to_world[16],
                         const float tan_half_fov[2], float near, int every_vpl);
void gb_topo_gather_destroy(gb_topo_gather_pass *pass);

/* ---- LA on the GPU (topo_assignment_gpu.c) ------------------------------
 * The same lists as gb_topo_assign, made by compute shaders straight into
 * the gather pass's range and entry buffers; out gets the ranges and the
 * entry count (gb_topo_la_gpu_read copies the entries back, for tests). */
typedef struct gb_topo_la_gpu {
    GLuint count_program, write_program;
    GLuint vpl_cluster, group_offsets, clusters;
    GLsizeiptr clusters_size;
    uint32_t vpl_count;
} gb_topo_la_gpu;

gb_result gb_topo_la_gpu_create(const gb_vpl_set *vpls, const int32_t *vpl_cluster,
                                const gb_topo_gates *gates, gb_topo_la_gpu *la, gb_error *error);
gb_result gb_topo_la_gpu_run(gb_topo_la_gpu *la, const gb_geometry_clusters *clusters,
                             gb_topo_visibility visibility, gb_topo_gather_pass *gather,
                             gb_topo_assignment *out, gb_error *error);
/* The same with count clusters already on the GPU in LA's layout (as
 * gb_topo_iugc_gpu_run leaves them in iugc->clusters). */
gb_result gb_topo_la_gpu_run_resident(gb_topo_la_gpu *la, GLuint clusters, uint32_t count,
                                      gb_topo_visibility visibility, gb_topo_gather_pass *gather,
                                      gb_topo_assignment *out, gb_error *error);
gb_result gb_topo_la_gpu_read(const gb_topo_gather_pass *gather, gb_topo_assignment *out,
                              gb_error *error);
void gb_topo_la_gpu_destroy(gb_topo_la_gpu *la);

#endif
