/* path_tracing.c — path tracing with next-event estimation and multiple
 * importance sampling (Veach 1997, ch. 9, power heuristic), restricted to a
 * range of bounce counts (path_tracing.h). */
#include "path_tracing.h"

#include <math.h>
#include <string.h>

#include "brdf_sampling.h"
#include "environment.h"

static const gb_vec3 BLACK = {0.0f, 0.0f, 0.0f};

float gb_path_uniform(gb_path_state *state)
{
    return gb_random_float(&state->rng);
}

/* Veach's power heuristic (beta = 2) for a sample of density a against b. */
static float power_heuristic(float a, float b)
{
    if (isinf(a))
        return 1.0f;
    a *= a;
    b *= b;
    return a + b > 0.0f ? a / (a + b) : 0.0f;
}

/* Whether s can reflect light from wi toward wo: both above the shading
 * normal, wi above the geometric surface too. Tested before a shadow ray, so
 * that the BRDF (and its texture) is read after it. */
int gb_path_reflects(const gb_surface *s, gb_vec3 wi)
{
    return gb_vec3_dot(s->ng, wi) > 0.0f && gb_vec3_dot(s->n, wi) > 0.0f &&
           gb_vec3_dot(s->n, s->wo) > 0.0f;
}

/* f(wo, wi) dot(n, wi) at s, for a wi that s reflects. */
gb_vec3 gb_path_reflected(const gb_path_tracer *in, gb_surface *s, gb_vec3 wi)
{
    const gb_brdf *brdf = gb_surface_brdf(in->surfaces, s);
    return gb_vec3_scale(gb_brdf_eval_vectors(brdf, s->n, s->wo, wi), gb_vec3_dot(s->n, wi));
}

/* One point on an area light, weighted against BRDF sampling. */
static gb_vec3 area_light(const gb_path_tracer *in, gb_surface *s, gb_path_state *state)
{
    gb_area_light_sample light;
    float u_pick = gb_path_uniform(state), u1 = gb_path_uniform(state), u2 = gb_path_uniform(state);
    if (!gb_light_table_sample(in->lights, in->surfaces, u_pick, u1, u2, &light))
        return BLACK;
    gb_vec3 to_light = gb_vec3_sub(light.position, s->position);
    float d2 = gb_vec3_dot(to_light, to_light);
    if (!(d2 > 0.0f))
        return BLACK;
    gb_vec3 wi = gb_vec3_scale(to_light, 1.0f / sqrtf(d2));
    float cos_light = -gb_vec3_dot(light.normal, wi);
    if (cos_light <= 0.0f || !gb_path_reflects(s, wi))
        return BLACK;
    gb_vec3 origin = gb_surface_ray_origin(s, wi);
    gb_vec3 target = gb_vec3_madd(light.position, light.normal, light.offset);
    gb_vec3 segment = gb_vec3_sub(target, origin);
    float distance = gb_vec3_length(segment);
    if (gb_embree_occluded(in->rays, origin, gb_vec3_scale(segment, 1.0f / distance), 0.0f,
                           distance, &state->rays))
        return BLACK;
    gb_vec3 f_cos = gb_path_reflected(in, s, wi);
    float pdf_light = light.pdf_area * d2 / cos_light;
    float pdf_brdf = gb_brdf_pdf(gb_surface_brdf(in->surfaces, s), s->n, s->wo, wi);
    float weight = power_heuristic(pdf_light, pdf_brdf);
    return gb_vec3_scale(gb_vec3_mul(f_cos, light.radiance), weight / pdf_light);
}

/* Every point, spot and directional light, one shadow ray each. */
static gb_vec3 delta_lights(const gb_path_tracer *in, gb_surface *s, gb_path_state *state)
{
    gb_vec3 sum = BLACK;
    for (uint32_t i = 0; i < in->scene->light_count; ++i) {
        gb_delta_light_sample light;
        if (!gb_delta_light_arriving(&in->scene->lights[i], s->position, &light) ||
            !gb_path_reflects(s, light.wi))
            continue;
        if (gb_embree_occluded(in->rays, gb_surface_ray_origin(s, light.wi), light.wi, 0.0f,
                               light.distance, &state->rays))
            continue;
        sum = gb_vec3_add(sum, gb_vec3_mul(gb_path_reflected(in, s, light.wi), light.irradiance));
    }
    return sum;
}

/* Next-event estimation: light arriving at s straight from the lights,
 * reflected toward s->wo. */
static gb_vec3 direct_light(const gb_path_tracer *in, gb_surface *s, gb_path_state *state)
{
    return gb_vec3_add(area_light(in, s, state), delta_lights(in, s, state));
}

/* What a BRDF-sampled ray leaving `from` finds. */
typedef struct bounce {
    gb_vec3 weight;             /* f cos / pdf */
    gb_vec3 light;              /* emission (MIS-weighted) or environment found */
    int hit;
    gb_surface next;
} bounce;

/* Emission of `to` seen from `from` along a BRDF sample of density pdf_brdf,
 * weighted against area-light sampling. */
static gb_vec3 emission_seen(const gb_path_tracer *in, const gb_surface *from,
                             const gb_surface *to, float pdf_brdf)
{
    if (gb_vec3_is_zero(to->emission))
        return BLACK;
    float pdf_area = gb_light_table_pdf_area(in->lights, to->triangle);
    if (pdf_area <= 0.0f)
        return to->emission;
    gb_vec3 segment = gb_vec3_sub(to->position, from->position);
    float cos_light = gb_vec3_dot(to->ng, to->wo);
    float pdf_light = pdf_area * gb_vec3_dot(segment, segment) / cos_light;
    return gb_vec3_scale(to->emission, power_heuristic(pdf_brdf, pdf_light));
}

/* The background's radiance along dir, a ray that hit nothing. */
static gb_vec3 environment_seen(const gb_path_tracer *in, gb_vec3 dir)
{
    float d[3] = {dir.x, dir.y, dir.z}, rgb[3];
    gb_environment_radiance(in->scene, d, rgb);
    return gb_vec3_load(rgb);
}

/* Samples the BRDF at s and traces the ray. Returns 0 when the path ends. */
static int scatter(const gb_path_tracer *in, gb_surface *s, gb_path_state *state, bounce *out)
{
    gb_brdf_sample sample;
    float u_lobe = gb_path_uniform(state), u1 = gb_path_uniform(state), u2 = gb_path_uniform(state);
    const gb_brdf *brdf = gb_surface_brdf(in->surfaces, s);
    if (!gb_brdf_sample_direction(brdf, s->n, s->wo, u_lobe, u1, u2, &sample) ||
        gb_vec3_dot(s->ng, sample.wi) <= 0.0f)
        return 0;
    out->weight = sample.weight;
    gb_hit hit;
    out->hit = gb_embree_intersect(in->rays, gb_surface_ray_origin(s, sample.wi), sample.wi,
                                   0.0f, INFINITY, &hit, &state->rays);
    if (!out->hit) {
        out->light = environment_seen(in, sample.wi);
        return 1;
    }
    gb_surface_at_hit(in->surfaces, &hit, sample.wi, &out->next);
    out->light = emission_seen(in, s, &out->next, sample.pdf);
    return 1;
}

/* Continues with probability min(1, max(beta)) after the first bounces;
 * returns 0 to stop, else divides beta by that probability. */
static int russian_roulette(int bounce_count, gb_vec3 *beta, gb_path_state *state)
{
    if (bounce_count < GB_PATH_ROULETTE_START)
        return 1;
    float q = fminf(1.0f, gb_vec3_max(*beta));
    if (!(q > 0.0f) || gb_path_uniform(state) >= q)
        return 0;
    *beta = gb_vec3_scale(*beta, 1.0f / q);
    return 1;
}

gb_vec3 gb_path_radiance(const gb_path_tracer *in, gb_vec3 origin, gb_vec3 dir, int lo, int hi,
                         gb_path_state *state)
{
    gb_hit hit;
    if (!gb_embree_intersect(in->rays, origin, dir, 0.0f, INFINITY, &hit, &state->rays))
        return lo == 0 ? environment_seen(in, dir) : BLACK;
    gb_surface s;
    gb_surface_at_hit(in->surfaces, &hit, dir, &s);
    return gb_path_radiance_leaving(in, &s, lo, hi, state);
}

gb_vec3 gb_path_radiance_leaving(const gb_path_tracer *in, gb_surface *first, int lo, int hi,
                                 gb_path_state *state)
{
    gb_surface s = *first;
    gb_vec3 sum = lo == 0 ? s.emission : BLACK, beta = {1.0f, 1.0f, 1.0f};
    for (int bounce_count = 1; bounce_count <= hi; ++bounce_count) {
        if (bounce_count >= lo)
            sum = gb_vec3_add(sum, gb_vec3_mul(beta, direct_light(in, &s, state)));
        if (bounce_count == hi && in->beyond)
            sum = gb_vec3_add(sum, gb_vec3_mul(beta, in->beyond(in->beyond_context, &s)));
        bounce b;
        if (!scatter(in, &s, state, &b))
            break;
        beta = gb_vec3_mul(beta, b.weight);
        if (bounce_count >= lo)
            sum = gb_vec3_add(sum, gb_vec3_mul(beta, b.light));
        if (!b.hit || !russian_roulette(bounce_count, &beta, state))
            break;
        s = b.next;
    }
    return sum;
}

gb_result gb_path_tables_build(const gb_scene *scene, int threads, gb_path_tables *tables,
                               gb_error *error)
{
    memset(tables, 0, sizeof *tables);
    gb_result result = gb_surface_table_build(scene, &tables->surfaces, error);
    if (result == GB_OK)
        result = gb_light_table_build(scene, &tables->lights, error);
    if (result == GB_OK)
        result = gb_embree_scene_create(scene, threads, &tables->rays, error);
    if (result != GB_OK)
        gb_path_tables_free(tables);
    return result;
}

void gb_path_tables_free(gb_path_tables *tables)
{
    gb_embree_scene_destroy(tables->rays);
    gb_surface_table_free(&tables->surfaces);
    gb_light_table_free(&tables->lights);
    memset(tables, 0, sizeof *tables);
}

gb_path_tracer gb_path_tracer_over(const gb_scene *scene, const gb_path_tables *tables)
{
    gb_path_tracer tracer = {scene, tables->rays, &tables->surfaces, &tables->lights, NULL,
                             NULL};
    return tracer;
}
