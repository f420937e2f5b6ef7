/* implicit_bounce.c — the light (Dong 2007, 4.3 and 4.4), by gathering:
 *
 *   direct     each element gathers Le from the emitters it links to (area
 *              lights are geometry whose outgoing radiance starts non-zero)
 *              and the environment's radiance through its empty bins, plus
 *              point, spot and directional lights with implicit shadows:
 *              a light counts when the element's bin toward it holds no
 *              link nearer than the light (links->light_visible; no ray is
 *              traced), or unshadowed when the links were made without
 *              the scene's lights;
 *   display    starts with the environment's share of the direct light
 *              (the runtime's direct pass leaves the sky's reflection to
 *              the GI method), then adds each bounce;
 *   bounces    ComputeIlluminateLeafNodes: every element gathers the
 *              outgoing radiance of the nodes it links to; PullupEnergy:
 *              every internal node takes the area-weighted mean of its
 *              children.
 * A link's weight is its bin's cosine-weighted solid angle, so an element
 * gathers E = sum of w L over its links, and reflects Kd E / pi.
 * The gathering runs on two threads (elements split in halves).
 */
#include "implicit_bounce.h"

#include <stdlib.h>
#include <string.h>

#include "brdf.h"
#include "threads.h"

void gb_implicit_pullup(const gb_implicit_model *model, float *values)
{
    /* Internal nodes come after all their children: one pass upward. */
    for (uint32_t i = model->element_count; i < model->node_count; ++i) {
        const gb_implicit_node *node = &model->nodes[i];
        double sum[3] = {0, 0, 0}, area = 0.0;
        for (uint32_t c = 0; c < node->child_count; ++c) {
            uint32_t child = model->children[node->first_child + c];
            double a = model->nodes[child].area;
            area += a;
            for (int k = 0; k < 3; ++k)
                sum[k] += a * values[3 * (size_t)child + k];
        }
        for (int k = 0; k < 3; ++k)
            values[3 * (size_t)i + k] = area > 0.0 ? (float)(sum[k] / area) : 0.0f;
    }
}

/* Irradiance from the scene's point, spot and directional lights, unshadowed. */
static void light_irradiance(const gb_scene *scene, const gb_implicit_node *node,
                             const uint8_t *visible, float E[3])
{
    E[0] = E[1] = E[2] = 0.0f;
    for (uint32_t i = 0; i < scene->light_count; ++i) {
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
        if (cosine > 0.0f)
            for (int k = 0; k < 3; ++k)
                E[k] += light->intensity[k] * factor * cosine;
    }
}

typedef struct gather_job {
    const gb_implicit_links *links;
    const float *source;
    float *gathered;
    uint32_t element_count;
} gather_job;

/* Thread t of thread_count: its share of the elements. */
static void gather(void *context, int t, int thread_count)
{
    const gather_job *job = context;
    const gb_implicit_links *links = job->links;
    const float *source = job->source;
    float *gathered = job->gathered;
    uint32_t begin = (uint32_t)((uint64_t)job->element_count * t / thread_count);
    uint32_t end = (uint32_t)((uint64_t)job->element_count * (t + 1) / thread_count);
    for (uint32_t e = begin; e < end; ++e) {
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

/* ComputeIlluminateLeafNodes: gathered[e] = sum of w L(source) / pi, on two
 * threads over halves of the elements (each element's sum is the same
 * whichever thread makes it: deterministic). */
static void compute_illuminate_leaf_nodes(const gb_implicit_model *model,
                                          const gb_implicit_links *links, const float *source,
                                          float *gathered)
{
    gather_job job = {links, source, gathered, model->element_count};
    gb_run_threads(gather, &job, model->element_count >= 2048 ? 2 : 1);
}

static void direct_light(const gb_scene *scene, const gb_implicit_model *model,
                         const gb_implicit_links *links, gb_implicit_solution *s)
{
    memcpy(s->emission, model->Le, 3 * (size_t)model->element_count * sizeof(float));
    gb_implicit_pullup(model, s->emission);
    compute_illuminate_leaf_nodes(model, links, s->emission, s->direct);
    for (uint32_t e = 0; e < model->element_count; ++e) {
        float E[3];
        const uint8_t *visible = links->light_visible && links->light_count == scene->light_count
                                     ? &links->light_visible[(size_t)e * links->light_count]
                                     : NULL;
        light_irradiance(scene, &model->nodes[e], visible, E);
        for (int k = 0; k < 3; ++k) {
            float sky = (links->environment_irradiance
                             ? links->environment_irradiance[3 * (size_t)e + k]
                             : links->environment_weight[e] * scene->environment[k]) /
                        GB_PI;
            s->sky[3 * (size_t)e + k] = sky;
            s->direct[3 * (size_t)e + k] += sky + E[k] / GB_PI;
        }
    }
}

/* radiance[e] = Kd incident, then pulled up. */
static void reflect(const gb_implicit_model *model, const float *incident, float *radiance)
{
    for (size_t i = 0; i < 3 * (size_t)model->element_count; ++i)
        radiance[i] = model->Kd[i] * incident[i];
    gb_implicit_pullup(model, radiance);
}

void gb_implicit_illuminate(const gb_scene *scene, const gb_implicit_model *model,
                            const gb_implicit_links *links, int bounces,
                            gb_implicit_solution *s)
{
    direct_light(scene, model, links, s);
    reflect(model, s->direct, s->radiance);
    memcpy(s->display, s->sky, 3 * (size_t)model->element_count * sizeof(float));
    for (int bounce = 0; bounce < bounces; ++bounce) {
        compute_illuminate_leaf_nodes(model, links, s->radiance, s->gathered);
        for (size_t i = 0; i < 3 * (size_t)model->element_count; ++i)
            s->display[i] += s->gathered[i];
        if (bounce + 1 < bounces)
            reflect(model, s->gathered, s->radiance);
    }
}

gb_result gb_implicit_solution_create(const gb_implicit_model *model,
                                      gb_implicit_solution *s, gb_error *error)
{
    size_t elements = 3 * (size_t)model->element_count + 1;
    size_t nodes = 3 * (size_t)model->node_count + 1;
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
