/* random.h — PCG32 (O'Neill 2014), the one random number generator of
 * gibake: a stream per photon, pixel or element index, never per thread, so
 * results do not depend on the number of threads.
 *
 *   gb_random rng = gb_random_make(seed, stream_index);
 *   float u = gb_random_float(&rng);          // [0, 1)
 * The state is a plain value owned by the caller.
 */
#ifndef GB_RANDOM_H
#define GB_RANDOM_H

#include <stdint.h>

typedef struct gb_random {
    uint64_t state;
    uint64_t increment;          /* odd: selects the stream */
} gb_random;

static inline uint32_t gb_random_uint32(gb_random *rng)
{
    uint64_t old = rng->state;
    rng->state = old * 6364136223846793005ULL + rng->increment;
    uint32_t xorshifted = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rotation = (uint32_t)(old >> 59u);
    return (xorshifted >> rotation) | (xorshifted << ((32u - rotation) & 31u));
}

/* The generator of stream `stream` (any 64-bit value) for `seed`. */
static inline gb_random gb_random_make(uint64_t seed, uint64_t stream)
{
    gb_random rng = {0u, (stream << 1u) | 1u};
    gb_random_uint32(&rng);
    rng.state += seed;
    gb_random_uint32(&rng);
    return rng;
}

/* Uniform in [0, 1), never 1. */
static inline float gb_random_float(gb_random *rng)
{
    return (float)(gb_random_uint32(rng) >> 8) * 0x1p-24f;
}

/* Uniform in [0, n) for n > 0, without modulo bias. */
static inline uint32_t gb_random_below(gb_random *rng, uint32_t n)
{
    uint32_t threshold = (0u - n) % n;
    for (;;) {
        uint32_t r = gb_random_uint32(rng);
        if (r >= threshold)
            return r % n;
    }
}

#endif
