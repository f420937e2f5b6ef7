/* glb_export.h — the scene and its lightmap as a glTF 2.0 binary, so the
 * bake opens in Blender, three.js or Godot (formats/FORMATS.md, "glTF
 * export"; the container: formats/gltf_binary.h).
 *
 * A node of the mesh and a node of the scene's first camera
 * (glb_camera.h); one mesh, one primitive per material that has triangles (in
 * material order, triangles in scene order): POSITION, NORMAL (the corner
 * normals, else the face normal), TEXCOORD_0 the scene's texture
 * coordinates (v flipped to glTF's top-left origin; without them, the
 * atlas UVs' accessor, as glTF wants a TEXCOORD_0 before a TEXCOORD_1),
 * TEXCOORD_1 the atlas UVs, u32 indices; corners that agree in every attribute share a vertex
 * (corner_vertices.h). A material: pbrMetallicRoughness baseColorFactor
 * Kd, metallic 0, roughness 1, doubleSided (the runtime draws both sides),
 * baseColorTexture the map_Kd image when there is one, emission Ke
 * (emissiveFactor, with KHR_materials_emissive_strength above 1), and
 *   "extras": {"lightmap": {"texture": T, "texCoord": 1, "scale": s,
 *                           "encoding": "srgb"}}
 * T the lightmap's texture (an embedded PNG, glb_images.h): the
 * irradiance at a point is s · srgb_to_linear(texture(T, TEXCOORD_1)), the
 * diffuse radiance baseColor / π times it.
 *
 * The caller owns every argument; the file is written whole or not at all.
 */
#ifndef GB_GLB_EXPORT_H
#define GB_GLB_EXPORT_H

#include <stdint.h>

#include "atlas.h"
#include "image.h"
#include "result.h"
#include "scene.h"

typedef struct gb_glb_export_stats {
    uint64_t vertices;
    uint32_t primitives;
    float scale;                /* the lightmap's */
    double png_relative_mse;    /* the PNG read back against the lightmap */
    double seconds;
} gb_glb_export_stats;

/* stats may be NULL. */
gb_result gb_glb_export(const char *path, const gb_scene *scene, const gb_atlas *atlas,
                        const gb_image *lightmap, gb_glb_export_stats *stats, gb_error *error);

#endif
