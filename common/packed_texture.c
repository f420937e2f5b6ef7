#include "packed_texture.h"

#include <math.h>
#include <stdlib.h>

#include "bisection.h"

/* The linear value of 8-bit sRGB code k (IEC 61966-2-1). */
static double srgb_decode(int k)
{
    double v = k / 255.0;
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4);
}

typedef struct code_query {
    const float *table;
    float value;
} code_query;

static int at_or_below_value(const void *user, size_t k)
{
    const code_query *query = user;
    return query->table[k] <= query->value;
}

/* The code whose decoded value is nearest to value, by bisection on the
 * increasing table; -1 when value is more than 1e-4 (relative) from it. */
static int nearest_code(const float table[256], float value)
{
    code_query query = {table, value};
    int low = (int)gb_bisection_last(255, at_or_below_value, &query), high = low + 1;
    int k = fabsf(table[high] - value) < fabsf(value - table[low]) ? high : low;
    return fabsf(table[k] - value) <= 1e-4f * fmaxf(table[k], 1e-3f) ? k : -1;
}

enum { TILE = 4 };              /* 4x4 texels of 4 bytes: one 64-byte line */

/* Index of texel (x, y) in the tiled codes. */
static size_t tiled_index(const gb_packed_texture *packed, int x, int y)
{
    size_t tile = (size_t)(y / TILE) * (size_t)packed->tiles_x + (size_t)(x / TILE);
    return tile * TILE * TILE + (size_t)(y % TILE) * TILE + (size_t)(x % TILE);
}

/* The code of value: the previous texel's code when it decodes to value
 * (neighbouring texels are alike), else the nearest; -1 when value is not
 * from an 8-bit sRGB code or another value already has that code. */
static int code_of(const float table[256], unsigned char seen[256], float decode[256],
                   int previous, float value)
{
    if (seen[previous] && decode[previous] == value)
        return previous;
    int k = nearest_code(table, value);
    if (k < 0 || (seen[k] && decode[k] != value))
        return -1;
    seen[k] = 1;
    decode[k] = value;
    return k;
}

/* Codes of every texel; 0 when the texture is not 8-bit sRGB. */
static int pack_codes(const gb_texture *texture, gb_packed_texture *packed)
{
    float table[256];
    unsigned char seen[256] = {0};
    for (int k = 0; k < 256; ++k)
        table[k] = (float)srgb_decode(k);
    int previous[3] = {0, 0, 0};
    for (int y = 0; y < texture->height; ++y)
        for (int x = 0; x < texture->width; ++x) {
            const float *rgb = &texture->rgb[3 * ((size_t)y * texture->width + x)];
            uint32_t code = 0;
            for (int c = 0; c < 3; ++c) {
                previous[c] = code_of(table, seen, packed->decode, previous[c], rgb[c]);
                if (previous[c] < 0)
                    return 0;
                code |= (uint32_t)previous[c] << (8 * c);
            }
            packed->codes[tiled_index(packed, x, y)] = code;
        }
    return 1;
}

gb_result gb_packed_texture_make(const gb_texture *texture, gb_packed_texture *packed,
                                 gb_error *error)
{
    *packed = (gb_packed_texture){.source = texture};
    if (!texture->rgb || texture->width <= 0 || texture->height <= 0)
        return GB_OK;
    packed->tiles_x = (texture->width + TILE - 1) / TILE;
    size_t tiles = (size_t)packed->tiles_x * (size_t)((texture->height + TILE - 1) / TILE);
    packed->codes = aligned_alloc(64, tiles * TILE * TILE * sizeof *packed->codes);
    packed->owns_codes = 1;
    if (!packed->codes)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "texture: out of memory");
    if (!pack_codes(texture, packed)) {
        free(packed->codes);
        packed->codes = NULL;
    }
    return GB_OK;
}

void gb_packed_texture_free(gb_packed_texture *packed)
{
    if (packed->owns_codes)
        free(packed->codes);
    packed->codes = NULL;
}

void gb_packed_texture_share(const gb_packed_texture *from, const gb_texture *texture,
                             gb_packed_texture *packed)
{
    *packed = *from;
    packed->source = texture;
    packed->owns_codes = 0;
}

/* x in -1..size: wrapped into 0..size - 1. */
static int wrap_index(int x, int size)
{
    return x < 0 ? x + size : x >= size ? x - size : x;
}

static gb_vec3 texel(const gb_packed_texture *packed, int x, int y)
{
    const gb_texture *texture = packed->source;
    x = wrap_index(x, texture->width);
    y = wrap_index(y, texture->height);
    if (!packed->codes)
        return gb_vec3_load(&texture->rgb[3 * ((size_t)y * texture->width + x)]);
    uint32_t code = packed->codes[tiled_index(packed, x, y)];
    return gb_vec3_make(packed->decode[code & 255], packed->decode[(code >> 8) & 255],
                        packed->decode[(code >> 16) & 255]);
}

static float fraction(float x)
{
    return x - floorf(x);
}

/* The texel index at or below x, kept in -1..size - 1. */
static int texel_floor(float x, int size)
{
    float f = floorf(x);
    return f < -1.0f ? -1 : f > (float)(size - 1) ? size - 1 : (int)f;
}

/* The bilinear footprint of (s, t). */
static gb_texture_footprint footprint(const gb_texture *texture, float s, float t)
{
    s = isfinite(s) ? s : 0.0f;
    t = isfinite(t) ? t : 0.0f;
    float x = fraction(s) * texture->width - 0.5f;
    float y = (1.0f - fraction(t)) * texture->height - 0.5f;
    gb_texture_footprint f = {texel_floor(x, texture->width), texel_floor(y, texture->height),
                              0.0f, 0.0f};
    f.ax = fminf(fmaxf(x - (float)f.x0, 0.0f), 1.0f);
    f.ay = fminf(fmaxf(y - (float)f.y0, 0.0f), 1.0f);
    return f;
}

static const void *texel_address(const gb_packed_texture *packed, int x, int y)
{
    const gb_texture *texture = packed->source;
    x = wrap_index(x, texture->width);
    y = wrap_index(y, texture->height);
    if (!packed->codes)
        return &texture->rgb[3 * ((size_t)y * texture->width + x)];
    return &packed->codes[tiled_index(packed, x, y)];
}

gb_texture_footprint gb_packed_texture_prefetch(const gb_packed_texture *packed, float s,
                                                float t)
{
    gb_texture_footprint f = footprint(packed->source, s, t);
    __builtin_prefetch(texel_address(packed, f.x0, f.y0));
    __builtin_prefetch(texel_address(packed, f.x0 + 1, f.y0 + 1));
    if (!packed->codes) {
        __builtin_prefetch(texel_address(packed, f.x0 + 1, f.y0));
        __builtin_prefetch(texel_address(packed, f.x0, f.y0 + 1));
    }
    return f;
}

gb_vec3 gb_packed_texture_read(const gb_packed_texture *packed, gb_texture_footprint f)
{
    gb_vec3 top = gb_vec3_add(gb_vec3_scale(texel(packed, f.x0, f.y0), 1.0f - f.ax),
                              gb_vec3_scale(texel(packed, f.x0 + 1, f.y0), f.ax));
    gb_vec3 bottom = gb_vec3_add(gb_vec3_scale(texel(packed, f.x0, f.y0 + 1), 1.0f - f.ax),
                                 gb_vec3_scale(texel(packed, f.x0 + 1, f.y0 + 1), f.ax));
    return gb_vec3_add(gb_vec3_scale(top, 1.0f - f.ay), gb_vec3_scale(bottom, f.ay));
}

gb_vec3 gb_packed_texture_lookup(const gb_packed_texture *packed, float s, float t)
{
    return gb_packed_texture_read(packed, footprint(packed->source, s, t));
}
