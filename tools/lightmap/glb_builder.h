/* glb_builder.h — the binary chunk of a glTF file and the JSON of its
 * bufferViews and accessors, built together (glb_export.h): each block of
 * bytes appended 4-byte aligned as a bufferView of buffer 0, an accessor
 * over a view with its type, count and (for positions) bounds.
 *
 * The caller owns the builder (zeroed to start; gb_glb_builder_free). An
 * allocation failure sets `failed` in one of the buffers: check with
 * gb_glb_builder_failed once at the end.
 */
#ifndef GB_GLB_BUILDER_H
#define GB_GLB_BUILDER_H

#include <stddef.h>
#include <stdint.h>

#include "byte_buffer.h"

enum {
    GB_GLTF_ARRAY_BUFFER = 34962,
    GB_GLTF_ELEMENT_ARRAY_BUFFER = 34963,
    GB_GLTF_FLOAT = 5126,
    GB_GLTF_UNSIGNED_INT = 5125,
};

typedef struct gb_glb_builder {
    gb_byte_buffer bin;             /* the BIN chunk */
    gb_byte_buffer views, accessors;/* JSON array elements, comma-separated */
    uint32_t view_count, accessor_count;
} gb_glb_builder;

/* The bytes as a new bufferView (target 0: none, e.g. an image); its index. */
uint32_t gb_glb_add_view(gb_glb_builder *builder, const void *bytes, size_t size, int target);

/* count elements of `components` floats each, taken every `stride` floats
 * from values (a vertex array's one attribute), as a FLOAT accessor of
 * type "VEC2"/"VEC3"; with bounds, its min and max (POSITION needs them).
 * Returns the accessor's index. */
uint32_t gb_glb_add_floats(gb_glb_builder *builder, const float *values, uint32_t count,
                           int components, int stride, int bounds);

/* Triangle indices as an UNSIGNED_INT SCALAR accessor; its index. */
uint32_t gb_glb_add_indices(gb_glb_builder *builder, const uint32_t *indices, uint32_t count);

int gb_glb_builder_failed(const gb_glb_builder *builder);
void gb_glb_builder_free(gb_glb_builder *builder);

#endif
