/* surface.h — what the reference renderer knows of a ray's hit: position,
 * normals turned toward the viewer (common/brdf.h, "Sides"), the BRDF with
 * its texture applied, the emission seen from that side, and how far to move
 * new rays off the surface.
 */
#ifndef GB_SURFACE_H
#define GB_SURFACE_H

#include "brdf.h"
#include "embree_scene.h"
#include "packed_texture.h"
#include "scene.h"
#include "vec3.h"

/* What shading needs of a triangle, in two adjacent cache lines (one memory
 * round trip rather than one per array of the scene): corner 0, the edges to
 * corners 1 and 2, the unit front normal, the ray offset, the material, and
 * the corners' texture coordinates and normals when the scene has them. */
typedef struct gb_triangle_record {
    _Alignas(128) float v0[3];
    float e1[3], e2[3];
    float normal[3];
    float offset;
    uint32_t material;
    float texcoords[6];         /* corner_texcoords, if any */
    float corner_normals[9];    /* corner_normals, if any */
} gb_triangle_record;

/* The records of every triangle of a scene and its packed textures; the
 * caller frees it with gb_surface_table_free. The scene must outlive it. */
typedef struct gb_surface_table {
    const gb_scene *scene;
    gb_triangle_record *records;
    gb_packed_texture *textures; /* one per material */
} gb_surface_table;

gb_result gb_surface_table_build(const gb_scene *scene, gb_surface_table *table,
                                 gb_error *error);
void gb_surface_table_free(gb_surface_table *table);

typedef struct gb_surface {
    gb_vec3 position;           /* from the barycentrics: on the triangle's plane */
    gb_vec3 ng;                 /* unit geometric normal, on the side of wo */
    gb_vec3 n;                  /* unit shading normal, on the side of ng */
    gb_vec3 wo;                 /* unit, toward the previous vertex */
    int front;                  /* wo lies on the front (emitting) side */
    uint32_t triangle;
    uint32_t material;
    gb_texture_footprint texels; /* where the diffuse texture is read */
    int textured;               /* the material has a texture to read */
    int brdf_ready;             /* brdf holds the texture's value (gb_surface_brdf) */
    gb_brdf brdf;               /* read it through gb_surface_brdf */
    gb_vec3 emission;           /* Ke toward wo: zero from the back */
    float offset;               /* ray origins move this far along ng */
} gb_surface;

/* The surface at hit for a ray of unit direction dir. */
void gb_surface_at_hit(const gb_surface_table *table, const gb_hit *hit, gb_vec3 dir,
                       gb_surface *surface);

/* The BRDF at the surface. Its texture is looked up at the first call, not
 * when the surface is made: gb_surface_at_hit only prefetches the texels, so
 * the shadow rays traced in between hide the memory latency. */
const gb_brdf *gb_surface_brdf(const gb_surface_table *table, gb_surface *surface);

/* How far to move a ray origin off a surface point whose coordinates are at
 * most magnitude in absolute value: magnitude * 2^-16. */
float gb_ray_offset(float magnitude);

/* The origin for a new ray leaving the surface toward dir: the position
 * moved by offset along ng, to dir's side. */
gb_vec3 gb_surface_ray_origin(const gb_surface *surface, gb_vec3 dir);

#endif
