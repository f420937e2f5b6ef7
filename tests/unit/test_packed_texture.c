/* Packed textures of the reference renderer (common/packed_texture.c):
 * an 8-bit sRGB texture packed into codes reads back exactly the loader's
 * floats, other textures stay floats, lookups are bilinear and repeat. */
#include <math.h>
#include <stdlib.h>

#include "packed_texture.h"
#include "random.h"
#include "tap.h"

/* 8-bit sRGB decoded in single precision, as an image loader might. */
static float decode_srgb8(int k)
{
    float v = (float)k / 255.0f;
    return v <= 0.04045f ? v / 12.92f : powf((v + 0.055f) / 1.055f, 2.4f);
}

static gb_texture make_texture(int width, int height, int from_codes, uint64_t seed)
{
    gb_texture texture = {width, height, malloc(sizeof(float) * 3 * width * height)};
    gb_random rng = gb_random_make(seed, 0);
    for (int i = 0; i < 3 * width * height; ++i)
        texture.rgb[i] = from_codes ? decode_srgb8((int)gb_random_below(&rng, 256))
                                    : 2.0f * gb_random_float(&rng);
    return texture;
}

/* Bilinear lookup straight from the floats, the definition of common/brdf.h. */
static double expected_lookup(const gb_texture *t, double s, double v, int c)
{
    double x = (s - floor(s)) * t->width - 0.5, y = (1 - (v - floor(v))) * t->height - 0.5;
    double x0 = floor(x), y0 = floor(y), ax = x - x0, ay = y - y0, sum = 0;
    for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
            int xi = (((int)x0 + dx) % t->width + t->width) % t->width;
            int yi = (((int)y0 + dy) % t->height + t->height) % t->height;
            sum += (dx ? ax : 1 - ax) * (dy ? ay : 1 - ay) * t->rgb[3 * (yi * t->width + xi) + c];
        }
    return sum;
}

static double worst_difference(const gb_packed_texture *packed, const gb_texture *t)
{
    gb_random rng = gb_random_make(9, 1);
    double worst = 0;
    for (int i = 0; i < 2000; ++i) {
        float s = 6 * gb_random_float(&rng) - 3, v = 6 * gb_random_float(&rng) - 3;
        gb_vec3 got = gb_packed_texture_lookup(packed, s, v);
        gb_vec3 prefetched = gb_packed_texture_read(packed, gb_packed_texture_prefetch(packed,
                                                                                       s, v));
        if (got.x != prefetched.x || got.y != prefetched.y || got.z != prefetched.z)
            return INFINITY;
        worst = fmax(worst, fabs(got.x - expected_lookup(t, s, v, 0)));
        worst = fmax(worst, fabs(got.z - expected_lookup(t, s, v, 2)));
    }
    return worst;
}

static void test_packing(void)
{
    gb_texture coded = make_texture(13, 7, 1, 1), floats = make_texture(6, 5, 0, 2);
    gb_packed_texture a, b;
    gb_error error;
    gb_packed_texture_make(&coded, &a, &error);
    gb_packed_texture_make(&floats, &b, &error);
    CHECK(a.codes != NULL, "a texture decoded from 8-bit sRGB is packed");
    CHECK(b.codes == NULL, "a texture of other floats is not");
    gb_packed_texture unpacked = {.source = &coded}; /* reads the floats */
    int exact = 1;
    gb_random rng = gb_random_make(3, 3);
    for (int i = 0; i < 2000; ++i) {
        float s = 4 * gb_random_float(&rng) - 2, v = 4 * gb_random_float(&rng) - 2;
        gb_vec3 p = gb_packed_texture_lookup(&a, s, v);
        gb_vec3 q = gb_packed_texture_lookup(&unpacked, s, v);
        exact &= p.x == q.x && p.y == q.y && p.z == q.z;
    }
    CHECK(exact, "packed lookups equal lookups in the loader's floats, bit for bit");
    CHECK(worst_difference(&a, &coded) < 1e-5,
          "packed: bilinear, repeating, v = 0 at the bottom, prefetch + read = lookup");
    CHECK(worst_difference(&b, &floats) < 1e-5,
          "floats: bilinear, repeating, v = 0 at the bottom, prefetch + read = lookup");
    gb_packed_texture shared;
    gb_packed_texture_share(&a, &coded, &shared);
    gb_vec3 p = gb_packed_texture_lookup(&shared, 0.3f, 0.6f);
    gb_vec3 q = gb_packed_texture_lookup(&a, 0.3f, 0.6f);
    CHECK(p.x == q.x && p.y == q.y && p.z == q.z, "a shared texture reads the same");
    gb_packed_texture_free(&shared);
    gb_packed_texture_free(&a);
    gb_packed_texture_free(&b);
    free(coded.rgb);
    free(floats.rgb);
}

int main(void)
{
    test_packing();
    return tap_done();
}
