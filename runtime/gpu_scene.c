#include "gpu_scene.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "mat4.h"
#include "scene_triangles.h"

typedef struct gpu_vertex {
    float position[3];
    float normal[3];
    float face_normal[3];
    float texcoord[2];
    uint32_t material;
} gpu_vertex;

typedef struct gpu_material {
    float Kd_textured[4];
    float Ks_Ns[4];
    float Ke[4];
} gpu_material;

static void store3(float out[3], gb_vec3 v)
{
    out[0] = v.x, out[1] = v.y, out[2] = v.z;
}

static void fill_triangle(const gb_scene *scene, uint32_t t, gpu_vertex out[3])
{
    gb_vec3 face = gb_triangle_normal(scene, t);
    for (int k = 0; k < 3; ++k) {
        gpu_vertex *v = &out[k];
        store3(v->position, gb_triangle_corner(scene, t, k));
        store3(v->normal, gb_corner_normal(scene, t, k, face));
        store3(v->face_normal, face);
        const float *uv = scene->corner_texcoords ? &scene->corner_texcoords[6 * (size_t)t + 2 * k]
                                                  : NULL;
        v->texcoord[0] = uv ? uv[0] : 0.0f;
        v->texcoord[1] = uv ? uv[1] : 0.0f;
        v->material = scene->triangle_material[t];
    }
}

/* Triangles in material order (a counting sort, stable): ranges[] gets one
 * entry per material that has triangles. */
static gb_result sort_by_material(const gb_scene *scene, gb_gpu_scene *gpu, uint32_t **order,
                                  gb_error *error)
{
    uint32_t *first = calloc((size_t)scene->material_count + 1, sizeof *first);
    *order = malloc(((size_t)scene->triangle_count + 1) * sizeof **order);
    gpu->ranges = calloc((size_t)scene->material_count + 1, sizeof *gpu->ranges);
    if (!first || !*order || !gpu->ranges) {
        free(first);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "gpu scene: out of memory");
    }
    for (uint32_t t = 0; t < scene->triangle_count; ++t)
        ++first[scene->triangle_material[t] + 1];
    for (uint32_t m = 0; m < scene->material_count; ++m) {
        if (first[m + 1])
            gpu->ranges[gpu->range_count++] = (gb_gpu_range){m, 3 * first[m], 3 * first[m + 1]};
        first[m + 1] += first[m];
    }
    for (uint32_t t = 0; t < scene->triangle_count; ++t)
        (*order)[first[scene->triangle_material[t]]++] = t;
    free(first);
    return GB_OK;
}

static gb_result upload_vertices(const gb_scene *scene, gb_gpu_scene *gpu, gb_error *error)
{
    uint32_t *order = NULL;
    gb_result result = sort_by_material(scene, gpu, &order, error);
    gpu_vertex *vertices = malloc(((size_t)scene->triangle_count * 3 + 1) * sizeof *vertices);
    if (result == GB_OK && !vertices)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "gpu scene: out of memory");
    if (result == GB_OK) {
        for (uint32_t i = 0; i < scene->triangle_count; ++i)
            fill_triangle(scene, order[i], &vertices[3 * (size_t)i]);
        gpu->vertex_count = 3 * scene->triangle_count;
        glCreateBuffers(1, &gpu->vertex_buffer);
        glNamedBufferStorage(gpu->vertex_buffer,
                             (GLsizeiptr)((gpu->vertex_count + 1) * sizeof *vertices), vertices, 0);
    }
    free(vertices);
    free(order);
    return result;
}

static void attribute(GLuint vao, GLuint location, GLint size, size_t offset)
{
    glEnableVertexArrayAttrib(vao, location);
    glVertexArrayAttribFormat(vao, location, size, GL_FLOAT, GL_FALSE, (GLuint)offset);
    glVertexArrayAttribBinding(vao, location, 0);
}

static void make_vertex_array(gb_gpu_scene *gpu)
{
    GLuint vao;
    glCreateVertexArrays(1, &vao);
    glVertexArrayVertexBuffer(vao, 0, gpu->vertex_buffer, 0, sizeof(gpu_vertex));
    attribute(vao, 0, 3, offsetof(gpu_vertex, position));
    attribute(vao, 1, 3, offsetof(gpu_vertex, normal));
    attribute(vao, 2, 3, offsetof(gpu_vertex, face_normal));
    attribute(vao, 3, 2, offsetof(gpu_vertex, texcoord));
    glEnableVertexArrayAttrib(vao, 4);
    glVertexArrayAttribIFormat(vao, 4, 1, GL_UNSIGNED_INT, offsetof(gpu_vertex, material));
    glVertexArrayAttribBinding(vao, 4, 0);
    gpu->vertex_array = vao;
}

/* Linear RGB floats to sRGB 8-bit texels: the texture is stored as
 * GL_SRGB8, so sampling (and mipmapping) gives linear values back. */
static unsigned char linear_to_srgb8(float linear)
{
    float c = linear <= 0.0f ? 0.0f : linear >= 1.0f ? 1.0f : linear;
    float s = c <= 0.0031308f ? 12.92f * c : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
    return (unsigned char)(s * 255.0f + 0.5f);
}

static int mip_levels(int width, int height)
{
    int levels = 1;
    for (int size = width > height ? width : height; size > 1; size >>= 1)
        ++levels;
    return levels;
}

/* Repeating, trilinear; row 0 of the gb_texture is the top, so rows are
 * flipped to put v = 0 at the bottom as OpenGL samples it. */
static gb_result upload_texture(const gb_texture *texture, GLuint *name, gb_error *error)
{
    size_t row = 3 * (size_t)texture->width;
    unsigned char *texels = malloc(row * (size_t)texture->height);
    if (!texels)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "gpu scene: out of memory for a texture");
    for (int y = 0; y < texture->height; ++y)
        for (size_t i = 0; i < row; ++i)
            texels[(size_t)(texture->height - 1 - y) * row + i] =
                linear_to_srgb8(texture->rgb[(size_t)y * row + i]);
    glCreateTextures(GL_TEXTURE_2D, 1, name);
    glTextureStorage2D(*name, mip_levels(texture->width, texture->height), GL_SRGB8,
                       texture->width, texture->height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(*name, 0, 0, 0, texture->width, texture->height, GL_RGB,
                        GL_UNSIGNED_BYTE, texels);
    glGenerateTextureMipmap(*name);
    glTextureParameteri(*name, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(*name, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    free(texels);
    return GB_OK;
}

static void make_white_texture(gb_gpu_scene *gpu)
{
    static const unsigned char white[3] = {255, 255, 255};
    glCreateTextures(GL_TEXTURE_2D, 1, &gpu->white_texture);
    glTextureStorage2D(gpu->white_texture, 1, GL_SRGB8, 1, 1);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(gpu->white_texture, 0, 0, 0, 1, 1, GL_RGB, GL_UNSIGNED_BYTE, white);
}

static gb_result upload_materials(const gb_scene *scene, gb_gpu_scene *gpu, gb_error *error)
{
    size_t count = scene->material_count ? scene->material_count : 1;
    gpu_material *materials = calloc(count, sizeof *materials);
    gpu->textures = calloc(count, sizeof *gpu->textures);
    if (!materials || !gpu->textures) {
        free(materials);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "gpu scene: out of memory");
    }
    gpu->material_count = scene->material_count;
    gb_result result = GB_OK;
    for (uint32_t m = 0; m < scene->material_count && result == GB_OK; ++m) {
        const gb_material *in = &scene->materials[m];
        gpu_material *out = &materials[m];
        memcpy(out->Kd_textured, in->Kd, sizeof in->Kd);
        memcpy(out->Ks_Ns, in->Ks, sizeof in->Ks);
        out->Ks_Ns[3] = in->Ns > 0.0f ? in->Ns : 0.0f;
        memcpy(out->Ke, in->Ke, sizeof in->Ke);
        if (in->texture.rgb && in->texture.width > 0 && in->texture.height > 0) {
            result = upload_texture(&in->texture, &gpu->textures[m], error);
            out->Kd_textured[3] = 1.0f;
        }
    }
    glCreateBuffers(1, &gpu->material_buffer);
    glNamedBufferStorage(gpu->material_buffer, (GLsizeiptr)(count * sizeof *materials),
                         materials, 0);
    free(materials);
    return result;
}

gb_result gb_gpu_scene_create(const gb_scene *scene, gb_gpu_scene *gpu, gb_error *error)
{
    memset(gpu, 0, sizeof *gpu);
    gb_result result = upload_vertices(scene, gpu, error);
    if (result == GB_OK)
        result = upload_materials(scene, gpu, error);
    if (result != GB_OK) {
        gb_gpu_scene_destroy(gpu);
        return result;
    }
    make_vertex_array(gpu);
    make_white_texture(gpu);
    return GB_OK;
}

void gb_gpu_scene_draw(const gb_gpu_scene *gpu, int with_textures)
{
    glBindVertexArray(gpu->vertex_array);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GB_SSBO_MATERIALS, gpu->material_buffer);
    if (!with_textures) {
        glDrawArrays(GL_TRIANGLES, 0, (GLsizei)gpu->vertex_count);
        return;
    }
    for (uint32_t r = 0; r < gpu->range_count; ++r) {
        const gb_gpu_range *range = &gpu->ranges[r];
        GLuint texture = gpu->textures[range->material];
        glBindTextureUnit(GB_UNIT_MATERIAL_TEXTURE, texture ? texture : gpu->white_texture);
        glDrawArrays(GL_TRIANGLES, (GLint)range->first_vertex, (GLsizei)range->vertex_count);
    }
}

void gb_gpu_scene_destroy(gb_gpu_scene *gpu)
{
    if (gpu->textures)
        for (uint32_t m = 0; m < gpu->material_count; ++m)
            if (gpu->textures[m])
                glDeleteTextures(1, &gpu->textures[m]);
    if (gpu->white_texture)
        glDeleteTextures(1, &gpu->white_texture);
    if (gpu->vertex_buffer)
        glDeleteBuffers(1, &gpu->vertex_buffer);
    if (gpu->material_buffer)
        glDeleteBuffers(1, &gpu->material_buffer);
    if (gpu->vertex_array)
        glDeleteVertexArrays(1, &gpu->vertex_array);
    free(gpu->textures);
    free(gpu->ranges);
    memset(gpu, 0, sizeof *gpu);
}
