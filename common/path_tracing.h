/* path_tracing.h — the light arriving along a ray, by path tracing with
 * next-event estimation: the reference renderer's light transport
 * (tools/reference/reference.h says what it counts), which `lightmap`'s
 * final gather uses too. A "bounce" is a reflection at a surface; the
 * conventions of light and BRDF are those of common/brdf.h.
 *
 * Each vertex takes next-event estimation of every light (area lights one
 * point by power, multiple importance sampling against the BRDF's sample;
 * point, spot and directional lights one shadow ray each) and one BRDF
 * sample; a path goes on with probability min(1, max throughput) after
 * GB_PATH_ROULETTE_START bounces.
 *
 * Thread-safe: the tracer is read only, all mutable state is the caller's
 * gb_path_state; the caller owns every argument.
 */
#ifndef GB_PATH_TRACING_H
#define GB_PATH_TRACING_H

#include "embree_scene.h"
#include "light_sampling.h"
#include "random.h"
#include "surface.h"
#include "vec3.h"

enum { GB_PATH_ROULETTE_START = 3 };   /* bounces before Russian roulette */

typedef struct gb_path_tracer {
    const gb_scene *scene;
    const gb_embree_scene *rays;
    const gb_surface_table *surfaces;
    const gb_light_table *lights;
    /* the light leaving s toward s->wo after more reflections than
     * max_bounces, at the vertex where a path of max_bounces stops (an
     * estimate such as the light octree's); NULL: none */
    gb_vec3 (*beyond)(const void *context, gb_surface *s);
    const void *beyond_context;
} gb_path_tracer;

/* What a tracer traces against and reads, built together:
 *   gb_path_tables tables;
 *   gb_path_tables_build(scene, threads, &tables, &error);   // on failure, freed
 *   gb_path_tracer tracer = gb_path_tracer_over(scene, &tables);
 *   gb_path_tables_free(&tables);
 * The scene must outlive the tables. */
typedef struct gb_path_tables {
    gb_surface_table surfaces;
    gb_light_table lights;
    gb_embree_scene *rays;
} gb_path_tables;

/* threads: Embree's build threads (0: all). */
gb_result gb_path_tables_build(const gb_scene *scene, int threads, gb_path_tables *tables,
                               gb_error *error);
void gb_path_tables_free(gb_path_tables *tables);
/* A tracer over the tables, no estimate beyond its paths. */
gb_path_tracer gb_path_tracer_over(const gb_scene *scene, const gb_path_tables *tables);

typedef struct gb_path_state {
    gb_random rng;              /* the sample's stream */
    uint64_t rays;              /* rays traced so far */
} gb_path_state;

/* Radiance arriving at origin from the unit direction -dir (traced along
 * dir) by every path of min_bounces..max_bounces reflections: 0 counts the
 * emitter or the background the ray finds. */
gb_vec3 gb_path_radiance(const gb_path_tracer *tracer, gb_vec3 origin, gb_vec3 dir,
                         int min_bounces, int max_bounces, gb_path_state *state);

/* Radiance leaving the surface s toward s->wo (s a ray's hit, as
 * gb_surface_at_hit makes it) by the paths whose reflections, s's the first,
 * number min_bounces..max_bounces: 0 counts s's emission; 1..1 is the
 * light reflected once at s (the lights by next-event estimation, the
 * emitters and background one BRDF sample finds). */
gb_vec3 gb_path_radiance_leaving(const gb_path_tracer *tracer, gb_surface *s,
                                 int min_bounces, int max_bounces, gb_path_state *state);

/* Whether s can reflect light from wi toward s->wo: both above the shading
 * normal, wi above the geometric surface too. */
int gb_path_reflects(const gb_surface *s, gb_vec3 wi);

/* f(wo, wi) dot(n, wi) at s, for a wi that s reflects. */
gb_vec3 gb_path_reflected(const gb_path_tracer *tracer, gb_surface *s, gb_vec3 wi);

/* The next uniform number in [0, 1) of the state's stream. */
float gb_path_uniform(gb_path_state *state);

#endif
