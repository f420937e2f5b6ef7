/* glb_builder.c — bufferViews and accessors over one binary buffer
 * (glb_builder.h). */
#include "glb_builder.h"

#include <float.h>
#include <stdlib.h>

static const char *const vector_types[5] = {"", "SCALAR", "VEC2", "VEC3", "VEC4"};

uint32_t gb_glb_add_view(gb_glb_builder *b, const void *bytes, size_t size, int target)
{
    gb_byte_buffer_align(&b->bin, 4);
    size_t offset = b->bin.size;
    gb_byte_buffer_append(&b->bin, bytes, size);
    gb_byte_buffer_printf(&b->views, "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu",
                          b->view_count ? "," : "", offset, size);
    if (target)
        gb_byte_buffer_printf(&b->views, ",\"target\":%d", target);
    gb_byte_buffer_printf(&b->views, "}");
    return b->view_count++;
}

static void print_vector(gb_byte_buffer *json, const char *name, const float *v, int n)
{
    gb_byte_buffer_printf(json, ",\"%s\":[", name);
    for (int k = 0; k < n; ++k)
        gb_byte_buffer_printf(json, "%s%.9g", k ? "," : "", (double)v[k]);
    gb_byte_buffer_printf(json, "]");
}

uint32_t gb_glb_add_floats(gb_glb_builder *b, const float *values, uint32_t count,
                           int components, int stride, int bounds)
{
    float *packed = malloc(((size_t)count * components + 1) * sizeof *packed);
    float low[4] = {FLT_MAX, FLT_MAX, FLT_MAX, FLT_MAX};
    float high[4] = {-FLT_MAX, -FLT_MAX, -FLT_MAX, -FLT_MAX};
    if (!packed) {
        b->bin.failed = 1;
        return 0;
    }
    for (uint32_t i = 0; i < count; ++i)
        for (int k = 0; k < components; ++k) {
            float v = values[(size_t)i * stride + k];
            packed[(size_t)i * components + k] = v;
            low[k] = v < low[k] ? v : low[k];
            high[k] = v > high[k] ? v : high[k];
        }
    uint32_t view = gb_glb_add_view(b, packed, (size_t)count * components * sizeof *packed,
                                    GB_GLTF_ARRAY_BUFFER);
    free(packed);
    gb_byte_buffer_printf(&b->accessors, "%s{\"bufferView\":%u,\"componentType\":%d,"
                          "\"count\":%u,\"type\":\"%s\"", b->accessor_count ? "," : "", view,
                          GB_GLTF_FLOAT, count, vector_types[components]);
    if (bounds) {
        print_vector(&b->accessors, "min", low, components);
        print_vector(&b->accessors, "max", high, components);
    }
    gb_byte_buffer_printf(&b->accessors, "}");
    return b->accessor_count++;
}

uint32_t gb_glb_add_indices(gb_glb_builder *b, const uint32_t *indices, uint32_t count)
{
    uint32_t view = gb_glb_add_view(b, indices, (size_t)count * sizeof *indices,
                                    GB_GLTF_ELEMENT_ARRAY_BUFFER);
    gb_byte_buffer_printf(&b->accessors, "%s{\"bufferView\":%u,\"componentType\":%d,"
                          "\"count\":%u,\"type\":\"SCALAR\"}", b->accessor_count ? "," : "",
                          view, GB_GLTF_UNSIGNED_INT, count);
    return b->accessor_count++;
}

int gb_glb_builder_failed(const gb_glb_builder *b)
{
    return b->bin.failed || b->views.failed || b->accessors.failed;
}

void gb_glb_builder_free(gb_glb_builder *b)
{
    gb_byte_buffer_free(&b->bin);
    gb_byte_buffer_free(&b->views);
    gb_byte_buffer_free(&b->accessors);
}
