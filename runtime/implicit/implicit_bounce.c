/* implicit_bounce.c — the light (Dong 2007, 4.3 and 4.4), by gathering:
 *
 *   direct     each element gathers Le from the emitters it links to (area
 *              lights are geometry whose outgoing radiance starts non-zero)
 *              and the environment's radiance through its empty bins, plus
 *              the scene's own point, spot and directional lights
 *              (gb_scene_own_light_count: not those standing for the
 *              environment in the direct pass, which would count the sky
 *              twice) with implicit shadows:
 *              a light counts when the element's bin toward it holds no
 *              link nearer than the light (links->light_visible; no ray is
 *              traced), or unshadowed when the links were made without
 *              the scene's lights;
 *   display    starts with the environment's share of the direct light
 *              when the direct pass leaves it out (a scene without
 *              environment lights, common/environment_lights.h), then
 *              adds each bounce;
 *   bounces    ComputeIlluminateLeafNodes: every element gathers the
 *              outgoing radiance of the nodes it links to; PullupEnergy:
 *              every internal node takes the area-weighted mean of its
 *              children.
 * A link's weight is its bin's cosine-weighted solid angle, so an element
 * gathers E = sum of w L over its links, and reflects Kd E / pi.
 * Each side of an element does this apart, from its own hemisphere's
 * links (implicit_model.h's sides): the light a side reflects is what that
 * side gathered, and a link reads the side of its source it sees. Emission
 * is the front's only (common/brdf.h). A node of several segments has no
 * side; it sends the mean of its children's fronts whichever way it is
 * seen, as it did when elements had one side: on a closed model those are
 * the faces seen from outside.
 * Elements of a closed part (gb_implicit_node_two_sided) have no back:
 * no links there, no light, nothing reflected (0), as when elements had
 * one side.
 * The gathering runs on two threads (elements split in halves, both
 * sides of each).
 */
#include "implicit_bounce.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "brdf.h"
#include "threads.h"

/* The value of node n's side (implicit_model.h's layout). */
static float *side_value(const gb_implicit_model *model, float *values, int side, uint32_t n)
{
    return &values[3 * ((size_t)side * model->node_count + n)];
}

/* One internal node's value on one side: the area-weighted mean of its
 * children's on that side, or of their fronts for a node with no side. */
static void pullup_node(const gb_implicit_model *model, float *values, uint32_t i, int side)
{
    const gb_implicit_node *node = &model->nodes[i];
    int from = gb_implicit_node_has_side(node) ? side : GB_IMPLICIT_FRONT;
    double sum[3] = {0, 0, 0}, area = 0.0;
    for (uint32_t c = 0; c < node->child_count; ++c) {
        uint32_t child = model->children[node->first_child + c];
        double a = model->nodes[child].area;
        const float *v = side_value(model, values, from, child);
        area += a;
        for (int k = 0; k < 3; ++k)
            sum[k] += a * v[k];
    }
    float *out = side_value(model, values, side, i);
    for (int k = 0; k < 3; ++k)
        out[k] = area > 0.0 ? (float)(sum[k] / area) : 0.0f;
}

void gb_implicit_pullup(const gb_implicit_model *model, float *values)
{
    /* Internal nodes come after all their children: one pass upward. */
    for (uint32_t i = model->element_count; i < model->node_count; ++i)
        for (int side = 0; side < GB_IMPLICIT_SIDES; ++side)
            pullup_node(model, values, i, side);
}

/* Irradiance from the scene's point, spot and directional lights, unless
 * visible says shadowed, on each side of the node: E[side]. */
static void light_irradiance(const gb_scene *scene, const gb_implicit_node *node,
                             int two_sided, const uint8_t *visible, float E[GB_IMPLICIT_SIDES][3])
{
    memset(E, 0, GB_IMPLICIT_SIDES * sizeof E[0]);
    for (uint32_t i = 0; i < gb_scene_own_light_count(scene); ++i) {
        const gb_light *light = &scene->lights[i];
        if (visible && !visible[i])
            continue;
        float wi[3], factor;
        if (light->type == GB_LIGHT_DIRECTIONAL) {
            for (int k = 0; k < 3; ++k)
                wi[k] = -light->direction[k];
            factor = 1.0f;
        } else {
            float r2 = 0.0f;
            for (int k = 0; k < 3; ++k) {
                wi[k] = light->position[k] - node->position[k];
                r2 += wi[k] * wi[k];
            }
            if (r2 <= 0.0f)
                continue;
            float r = sqrtf(r2);
            for (int k = 0; k < 3; ++k)
                wi[k] /= r;
            factor = gb_inverse_square(r2);
            const float *axis = light->direction;
            float cos_angle = -(axis[0] * wi[0] + axis[1] * wi[1] + axis[2] * wi[2]);
            if (light->type == GB_LIGHT_SPOT)
                factor *= gb_spot_falloff(cos_angle, light->cone_angle, light->falloff_angle);
        }
        float cosine = wi[0] * node->normal[0] + wi[1] * node->normal[1] + wi[2] * node->normal[2];
        int side = cosine > 0.0f ? GB_IMPLICIT_FRONT : GB_IMPLICIT_BACK;
        if (side == GB_IMPLICIT_BACK && !two_sided)
            continue;
        for (int k = 0; k < 3; ++k)
            E[side][k] += light->intensity[k] * factor * fabsf(cosine);
    }
}

typedef struct gather_job {
    const gb_implicit_links *links;
    const float *source;
    float *gathered;
    uint32_t element_count;
} gather_job;

/* Thread t of thread_count: both sides of its share of the elements (an
 * element of a closed part has no back links: halves of the receivers
 * would leave one thread the fronts). */
static void gather(void *context, int t, int thread_count)
{
    const gather_job *job = context;
    const gb_implicit_links *links = job->links;
    const float *source = job->source;
    float *gathered = job->gathered;
    uint32_t begin = (uint32_t)((uint64_t)job->element_count * t / thread_count);
    uint32_t end = (uint32_t)((uint64_t)job->element_count * (t + 1) / thread_count);
    for (uint32_t r = 0; r < GB_IMPLICIT_SIDES * (end - begin); ++r) {
        uint32_t e = begin + r % (end - begin) + r / (end - begin) * job->element_count;
        float sum[3] = {0, 0, 0};
        for (uint32_t i = links->first[e]; i < links->first[e + 1]; ++i) {
            const float *L = &source[3 * (size_t)links->source[i]];
            float w = links->weight[i];
            for (int k = 0; k < 3; ++k)
                sum[k] += w * L[k];
        }
        for (int k = 0; k < 3; ++k)
            gathered[3 * (size_t)e + k] = sum[k] / GB_PI;
    }
}

/* ComputeIlluminateLeafNodes: gathered[r] = sum of w L(source) / pi for
 * each side r of each element, on two threads over halves of the elements (each
 * sum is the same whichever thread makes it: deterministic). */
static void compute_illuminate_leaf_nodes(const gb_implicit_model *model,
                                          const gb_implicit_links *links, const float *source,
                                          float *gathered)
{
    gather_job job = {links, source, gathered, model->element_count};
    gb_run_threads(gather, &job, model->element_count >= 2048 ? 2 : 1);
}

/* Emission: Le on the elements' fronts, none on their backs, pulled up. */
static void emission(const gb_implicit_model *model, float *emission)
{
    memset(emission, 0, 3 * GB_IMPLICIT_SIDES * (size_t)model->node_count * sizeof(float));
    memcpy(emission, model->Le, 3 * (size_t)model->element_count * sizeof(float));
    gb_implicit_pullup(model, emission);
}

static void direct_light(const gb_scene *scene, const gb_implicit_model *model,
                         const gb_implicit_links *links, gb_implicit_solution *s)
{
    emission(model, s->emission);
    compute_illuminate_leaf_nodes(model, links, s->emission, s->direct);
    size_t elements = model->element_count;
    for (uint32_t e = 0; e < elements; ++e) {
        float E[GB_IMPLICIT_SIDES][3];
        const uint8_t *visible = links->light_visible &&
                                         links->light_count == gb_scene_own_light_count(scene)
                                     ? &links->light_visible[(size_t)e * links->light_count]
                                     : NULL;
        const gb_implicit_node *node = &model->nodes[e];
        light_irradiance(scene, node, gb_implicit_node_two_sided(model, node), visible, E);
        for (int side = 0; side < GB_IMPLICIT_SIDES; ++side) {
            size_t r = side * elements + e;
            for (int k = 0; k < 3; ++k) {
                float sky = (links->environment_irradiance
                                 ? links->environment_irradiance[3 * r + k]
                                 : links->environment_weight[r] * scene->environment[k]) /
                            GB_PI;
                s->sky[3 * r + k] = sky;
                s->direct[3 * r + k] += sky + E[side][k] / GB_PI;
            }
        }
    }
}

/* radiance of each element's side = Kd x its incident, then pulled up. */
static void reflect(const gb_implicit_model *model, const float *incident, float *radiance)
{
    size_t elements = 3 * (size_t)model->element_count;
    for (int side = 0; side < GB_IMPLICIT_SIDES; ++side)
        for (size_t i = 0; i < elements; ++i)
            side_value(model, radiance, side, 0)[i] = model->Kd[i] * incident[side * elements + i];
    gb_implicit_pullup(model, radiance);
}

void gb_implicit_illuminate(const gb_scene *scene, const gb_implicit_model *model,
                            const gb_implicit_links *links, int bounces,
                            gb_implicit_solution *s)
{
    direct_light(scene, model, links, s);
    reflect(model, s->direct, s->radiance);
    size_t values = 3 * GB_IMPLICIT_SIDES * (size_t)model->element_count;
    if (scene->environment_light_count)
        memset(s->display, 0, values * sizeof(float));
    else
        memcpy(s->display, s->sky, values * sizeof(float));
    for (int bounce = 0; bounce < bounces; ++bounce) {
        compute_illuminate_leaf_nodes(model, links, s->radiance, s->gathered);
        for (size_t i = 0; i < values; ++i)
            s->display[i] += s->gathered[i];
        if (bounce + 1 < bounces)
            reflect(model, s->gathered, s->radiance);
    }
}

gb_result gb_implicit_solution_create(const gb_implicit_model *model,
                                      gb_implicit_solution *s, gb_error *error)
{
    size_t elements = 3 * GB_IMPLICIT_SIDES * (size_t)model->element_count + 1;
    size_t nodes = 3 * GB_IMPLICIT_SIDES * (size_t)model->node_count + 1;
    memset(s, 0, sizeof *s);
    s->storage = calloc(4 * elements + 2 * nodes, sizeof(float));
    if (!s->storage)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    s->direct = s->storage;
    s->display = s->direct + elements;
    s->gathered = s->display + elements;
    s->sky = s->gathered + elements;
    s->radiance = s->sky + elements;
    s->emission = s->radiance + nodes;
    return GB_OK;
}

void gb_implicit_solution_free(gb_implicit_solution *s)
{
    free(s->storage);
    memset(s, 0, sizeof *s);
}
