/* implicit_link_lists.h — the bins after PushdownLinks (one word a node
 * and bin: the link kept there) made into what the illumination reads
 * (implicit_links.h's gb_implicit_links): the receiving links of each
 * side of each element, one a source node and side seen, the empty bins'
 * share, the lights' implicit shadows
 * and, on request, the depth maps. implicit_links.c fills the words; the
 * caller owns them and the links made. */
#ifndef GB_IMPLICIT_LINK_LISTS_H
#define GB_IMPLICIT_LINK_LISTS_H

#include <stdint.h>
#include <string.h>

#include "implicit_bins.h"
#include "implicit_links.h"
#include "implicit_model.h"
#include "result.h"
#include "scene.h"

/* A bin's link in one word: the distance's bits above the node's index. A
 * distance is a positive float, whose bits order as its value, so the
 * smaller word is the shorter link (of two as short, the smaller node). */
#define GB_IMPLICIT_EMPTY_SLOT UINT64_MAX   /* node GB_IMPLICIT_NO_NODE */

static inline uint64_t gb_implicit_pack_link(uint32_t node, float distance)
{
    uint32_t bits;
    memcpy(&bits, &distance, sizeof bits);
    return (uint64_t)bits << 32 | node;
}

static inline uint32_t gb_implicit_slot_node(uint64_t slot) { return (uint32_t)slot; }

static inline float gb_implicit_slot_distance(uint64_t slot)
{
    uint32_t bits = (uint32_t)(slot >> 32);
    float distance;
    memcpy(&distance, &bits, sizeof distance);
    return distance;
}

/* The filled bins and what the lists take from the options. */
typedef struct gb_implicit_slots {
    const gb_implicit_model *model;
    const gb_implicit_bins *bins;
    const uint64_t *slot;       /* node_count * bins->count words */
    const gb_scene *lights;     /* for implicit shadows, or NULL */
    const float *environment;   /* bins->count * 3 radiance, or NULL */
} gb_implicit_slots;

/* Fills links' lists (and its depth maps when depths is 1); on failure the
 * caller frees what was made with gb_implicit_links_free. */
gb_result gb_implicit_link_lists(const gb_implicit_slots *slots, int depths,
                                 gb_implicit_links *links, gb_error *error);

#endif
