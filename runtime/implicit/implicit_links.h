/* implicit_links.h — CreateHierarchicalLinks, RefineHierarchicalLinks and
 * PushdownLinks (4.2.2 - 4.2.4; implicit_links.c). The caller owns the
 * links from create until free. */
#ifndef GB_IMPLICIT_LINKS_H
#define GB_IMPLICIT_LINKS_H

#include <stdint.h>

#include "implicit_bins.h"
#include "implicit_model.h"
#include "progress.h"
#include "result.h"
#include "scene.h"

/* Seconds (wall clock, or CPU time of the process: both threads count) of
 * CreateHierarchicalLinks, Refine + PushdownLinks, and the per-element
 * lists with the lights' visibility. */
typedef struct gb_implicit_link_seconds {
    double create, refine, compact;
} gb_implicit_link_seconds;

/* Links after PushdownLinks: the receiving links of each side of each
 * element (receiver r = side * element_count + e, implicit_model.h), one
 * per source node and side seen, weighted by its bins' |cos| solid angle
 * on that side, normalised so that the weights of all bins of a side's
 * hemisphere sum to pi. */
typedef struct gb_implicit_links {
    uint32_t *first;            /* 2 element_count + 1: receiver r's links */
    uint32_t *source;           /* first[2 element_count]: side seen x node_count
                                   + the node seen (gb_implicit_source_node) */
    float *weight;
    float *environment_weight;  /* 2 element_count: the empty bins' share */
    float *environment_irradiance;  /* 2 element_count * 3 when the links were
                                   made with an environment map: sum over the
                                   empty bins of weight x its radiance; else NULL */
    uint8_t *light_visible;     /* element_count * light_count, or NULL: 1 when
                                   the bin toward the light holds no nearer link */
    uint32_t light_count;
    uint32_t *depth_first;      /* element_count + 1, when made with options->depths,
                                   else NULL: each element's depth map, its */
    uint32_t *depth_bin;        /* depth_first[element_count] filled bins in
                                   increasing order */
    float *depth;               /* and the distance of each bin's link: the
                                   nearest surface the element sees that way
                                   (the "omni-directional shadow map" of 3) */
    gb_implicit_link_seconds wall, cpu;  /* statistics: time of each step */
} gb_implicit_links;

typedef struct gb_implicit_link_options {
    int hierarchical;           /* 0: every element pair (the brute force) */
    const gb_scene *lights;     /* its point, spot and directional lights get
                                   implicit shadows; NULL: unshadowed */
    const float *environment;   /* bins->count * 3: the environment's radiance
                                   a bin (gb_implicit_environment_bins), or
                                   NULL: the scene's constant colour */
    int depths;                 /* 1: keep the depth maps (links->depth_first) */
    int thread_count;           /* for CreateHierarchicalLinks; 0: GB_IMPLICIT_LINK_THREADS.
                                   The links do not depend on it. */
    int paper_rules;            /* 1: 4.2.2's rules alone (gbview --paper-rules,
                                   bench/implicit_steps): subdivide at a whole
                                   bin, store a link in the bin of the other's
                                   centre only (no discs); faster, and leaks
                                   where a surface is near another */
    gb_progress_callback progress;  /* may be NULL: 0.9 x the fraction of
                                   CreateHierarchicalLinks' tasks started (its
                                   first pairs; one task on one thread), then 1
                                   when the links are made; nonzero stops the
                                   work (GB_ERROR_INTERRUPTED) */
    void *progress_user;
} gb_implicit_link_options;

enum { GB_IMPLICIT_LINK_THREADS = 2 };

/* The node of a link's source (links->source); sources from node_count on
 * are nodes' backs. */
static inline uint32_t gb_implicit_source_node(const gb_implicit_model *model, uint32_t source)
{
    return source >= model->node_count ? source - model->node_count : source;
}

/* Steps 5-7 for a static scene. bin_targets, when not NULL, receives the
 * node_count * bins->count bins before compaction (tests), the caller frees. */
gb_result gb_implicit_create_links(const gb_implicit_model *model, const gb_implicit_bins *bins,
                                   const gb_implicit_link_options *options,
                                   gb_implicit_links *links, uint32_t **bin_targets,
                                   gb_error *error);
void gb_implicit_links_free(gb_implicit_links *links);

#endif
