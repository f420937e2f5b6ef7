/* implicit_link_lists.c — the per-element lists of the links (one list a
 * side of an element), the lights' visibility and the depth maps, from
 * the filled bins (implicit_link_lists.h). */
#include "implicit_link_lists.h"

#include <math.h>
#include <stdlib.h>

#include "brdf.h"
#include "vec3.h"

typedef struct bin_link {
    uint32_t source, bin;
    float weight;
} bin_link;

static int compare_bin_links(const void *x, const void *y)
{
    const bin_link *p = x, *q = y;
    if (p->source != q->source)
        return p->source < q->source ? -1 : 1;
    return p->bin < q->bin ? -1 : p->bin > q->bin;
}

/* The side of the node seen along direction d: its back when d runs along
 * its normal (a one-sided surface of a mesh wound away from the receiver:
 * the staircase's ceiling over the front room faces the attic; it
 * reflects there as on its front, common/brdf.h). A node of several
 * segments has no side: its front, both its values being the same. */
static int side_seen(const gb_implicit_node *target, const float d[3])
{
    return gb_implicit_node_has_side(target) && gb_dot3(d, target->normal) > 0.0f
               ? GB_IMPLICIT_BACK
               : GB_IMPLICIT_FRONT;
}

/* One side of element e: the filled bins of that hemisphere into scratch
 * (weights normalised), sorted by source and merged, one link a source
 * and side seen. Returns the links: none on the back of an element of a
 * closed part (gb_implicit_node_two_sided), which gathers nothing. */
static uint32_t side_links(const gb_implicit_slots *l, uint32_t e, int side, bin_link *scratch,
                           float *environment_weight, float *environment_irradiance)
{
    const gb_implicit_model *m = l->model;
    const gb_implicit_node *node = &m->nodes[e];
    const uint64_t *slot = &l->slot[(size_t)e * l->bins->count];
    float facing = side == GB_IMPLICIT_FRONT ? 1.0f : -1.0f;
    if (side == GB_IMPLICIT_BACK && !gb_implicit_node_two_sided(m, node)) {
        *environment_weight = 0.0f;
        for (int k = 0; environment_irradiance && k < 3; ++k)
            environment_irradiance[k] = 0.0f;
        return 0;
    }
    double total = 0.0, environment = 0.0, irradiance[3] = {0, 0, 0};
    uint32_t count = 0;
    for (uint32_t b = 0; b < l->bins->count; ++b) {
        const float *d = &l->bins->directions[3 * b];
        float cosine = facing * gb_dot3(d, node->normal);
        if (cosine <= 0.0f)
            continue;
        float w = cosine * l->bins->solid_angles[b];
        total += w;
        uint32_t target = gb_implicit_slot_node(slot[b]);
        if (target == GB_IMPLICIT_NO_NODE) {
            environment += w;
            for (int k = 0; l->environment && k < 3; ++k)
                irradiance[k] += w * l->environment[3 * (size_t)b + k];
        } else {
            int seen = side_seen(&m->nodes[target], d);
            /* a closed part's back faces its inside: it hides, sends nothing */
            if (seen == GB_IMPLICIT_FRONT || gb_implicit_node_two_sided(m, &m->nodes[target]))
                scratch[count++] = (bin_link){(uint32_t)seen * m->node_count + target, b, w};
        }
    }
    float scale = total > 0.0 ? (float)(GB_PI / total) : 0.0f;
    *environment_weight = (float)environment * scale;
    for (int k = 0; environment_irradiance && k < 3; ++k)
        environment_irradiance[k] = (float)irradiance[k] * scale;
    qsort(scratch, count, sizeof *scratch, compare_bin_links);
    uint32_t merged = 0;
    for (uint32_t i = 0; i < count; ++i) {
        if (merged && scratch[merged - 1].source == scratch[i].source)
            scratch[merged - 1].weight += scratch[i].weight * scale;
        else
            scratch[merged++] = (bin_link){scratch[i].source, scratch[i].bin,
                                           scratch[i].weight * scale};
    }
    return merged;
}

static gb_result append_links(gb_implicit_links *links, size_t *capacity, size_t used,
                              const bin_link *scratch, uint32_t count, gb_error *error)
{
    if (used + count > *capacity) {
        size_t grown = 2 * (used + count);
        uint32_t *source = realloc(links->source, grown * sizeof *source);
        if (source)
            links->source = source;
        float *weight = realloc(links->weight, grown * sizeof *weight);
        if (weight)
            links->weight = weight;
        if (!source || !weight)
            return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
        *capacity = grown;
    }
    for (uint32_t i = 0; i < count; ++i) {
        links->source[used + i] = scratch[i].source;
        links->weight[used + i] = scratch[i].weight;
    }
    return GB_OK;
}

/* Implicit shadows of the scene's lights (section 4.4's idea applied to
 * them): an element sees a light when the bin toward it is empty or holds
 * a link longer than the light's distance. */
static void light_visibility(const gb_implicit_slots *l, const gb_scene *scene, uint32_t e,
                             uint8_t *visible)
{
    const gb_implicit_node *node = &l->model->nodes[e];
    for (uint32_t i = 0; i < gb_scene_own_light_count(scene); ++i) {
        const gb_light *light = &scene->lights[i];
        float d[3], distance = INFINITY;
        for (int k = 0; k < 3; ++k)
            d[k] = light->type == GB_LIGHT_DIRECTIONAL ? -light->direction[k]
                                                       : light->position[k] - node->position[k];
        if (light->type != GB_LIGHT_DIRECTIONAL)
            distance = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        int bin = gb_implicit_bin(l->bins->n, d);
        uint64_t slot = l->slot[(size_t)e * l->bins->count + (uint32_t)(bin < 0 ? 0 : bin)];
        visible[i] = bin < 0 || gb_implicit_slot_node(slot) == GB_IMPLICIT_NO_NODE ||
                     gb_implicit_slot_distance(slot) >= distance;
    }
}

/* The element's depth map: (bin, distance) of each bin that holds a link
 * (the bins side_links counts on either side), appended to
 * links->depth_bin and depth from *used on. */
static gb_result append_depths(const gb_implicit_slots *l, uint32_t e,
                               gb_implicit_links *links,
                               size_t *capacity, size_t *used, gb_error *error)
{
    size_t row = (size_t)e * l->bins->count;
    for (uint32_t b = 0; b < l->bins->count; ++b) {
        uint32_t target = gb_implicit_slot_node(l->slot[row + b]);
        if (target == GB_IMPLICIT_NO_NODE)
            continue;
        if (*used == *capacity) {
            size_t grown = 2 * *capacity + 1024;
            uint32_t *bin = realloc(links->depth_bin, grown * sizeof *bin);
            if (bin)
                links->depth_bin = bin;
            float *depth = realloc(links->depth, grown * sizeof *depth);
            if (depth)
                links->depth = depth;
            if (!bin || !depth)
                return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
            *capacity = grown;
        }
        links->depth_bin[*used] = b;
        links->depth[*used] = gb_implicit_slot_distance(l->slot[row + b]);
        ++*used;
    }
    return GB_OK;
}

static gb_result compact_depths(const gb_implicit_slots *l, gb_implicit_links *links,
                                gb_error *error)
{
    uint32_t elements = l->model->element_count;
    links->depth_first = malloc(((size_t)elements + 1) * sizeof *links->depth_first);
    if (!links->depth_first)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    size_t used = 0, capacity = 0;
    gb_result result = GB_OK;
    for (uint32_t e = 0; result == GB_OK && e < elements; ++e) {
        links->depth_first[e] = (uint32_t)used;
        result = append_depths(l, e, links, &capacity, &used, error);
        if (used > UINT32_MAX / 2)
            result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: too many depths");
    }
    links->depth_first[elements] = (uint32_t)used;
    return result;
}

static gb_result compact(const gb_implicit_slots *l, gb_implicit_links *links,
                         gb_error *error)
{
    uint32_t elements = l->model->element_count;
    size_t receivers = (size_t)GB_IMPLICIT_SIDES * elements;
    links->first = malloc((receivers + 1) * sizeof *links->first);
    links->environment_weight = malloc((receivers + 1) * sizeof(float));
    if (l->environment)
        links->environment_irradiance = malloc(3 * (receivers + 1) * sizeof(float));
    bin_link *scratch = malloc(l->bins->count * sizeof *scratch);
    const gb_scene *scene = l->lights;
    links->light_count = scene ? gb_scene_own_light_count(scene) : 0;
    if (links->light_count)
        links->light_visible = malloc((size_t)elements * links->light_count);
    gb_result result = GB_OK;
    if (!links->first || !links->environment_weight || !scratch ||
        (l->environment && !links->environment_irradiance) ||
        (links->light_count && !links->light_visible))
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    size_t used = 0, capacity = 0;
    for (size_t r = 0; result == GB_OK && r < receivers; ++r) {
        uint32_t e = (uint32_t)(r % elements);
        int side = r < elements ? GB_IMPLICIT_FRONT : GB_IMPLICIT_BACK;
        links->first[r] = (uint32_t)used;
        uint32_t count = side_links(l, e, side, scratch, &links->environment_weight[r],
                                    links->environment_irradiance
                                        ? &links->environment_irradiance[3 * r]
                                        : NULL);
        if (links->light_count && side == GB_IMPLICIT_FRONT)
            light_visibility(l, scene, e, &links->light_visible[(size_t)e * links->light_count]);
        result = append_links(links, &capacity, used, scratch, count, error);
        used += count;
        if (used > UINT32_MAX / 2)
            result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: too many links");
    }
    if (result == GB_OK)
        links->first[receivers] = (uint32_t)used;
    free(scratch);
    return result;
}

gb_result gb_implicit_link_lists(const gb_implicit_slots *slots, int depths,
                                 gb_implicit_links *links, gb_error *error)
{
    gb_result result = compact(slots, links, error);
    return result == GB_OK && depths ? compact_depths(slots, links, error) : result;
}
