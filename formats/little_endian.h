/* little_endian.h — reading and writing the little-endian integers and
 * floats of gibake's files byte by byte, the same on any host and at any
 * alignment. p points at the first byte; nothing is owned.
 */
#ifndef GB_LITTLE_ENDIAN_H
#define GB_LITTLE_ENDIAN_H

#include <stdint.h>
#include <string.h>

static inline void gb_put_u32(unsigned char *p, uint32_t value)
{
    for (int i = 0; i < 4; ++i)
        p[i] = (unsigned char)(value >> (8 * i));
}

static inline void gb_put_u64(unsigned char *p, uint64_t value)
{
    for (int i = 0; i < 8; ++i)
        p[i] = (unsigned char)(value >> (8 * i));
}

static inline void gb_put_f32(unsigned char *p, float value)
{
    uint32_t bits;
    memcpy(&bits, &value, sizeof bits);
    gb_put_u32(p, bits);
}

static inline void gb_put_f64(unsigned char *p, double value)
{
    uint64_t bits;
    memcpy(&bits, &value, sizeof bits);
    gb_put_u64(p, bits);
}

static inline uint32_t gb_get_u32(const unsigned char *p)
{
    uint32_t value = 0;
    for (int i = 0; i < 4; ++i)
        value |= (uint32_t)p[i] << (8 * i);
    return value;
}

static inline uint64_t gb_get_u64(const unsigned char *p)
{
    uint64_t value = 0;
    for (int i = 0; i < 8; ++i)
        value |= (uint64_t)p[i] << (8 * i);
    return value;
}

static inline float gb_get_f32(const unsigned char *p)
{
    uint32_t bits = gb_get_u32(p);
    float value;
    memcpy(&value, &bits, sizeof value);
    return value;
}

static inline double gb_get_f64(const unsigned char *p)
{
    uint64_t bits = gb_get_u64(p);
    double value;
    memcpy(&value, &bits, sizeof value);
    return value;
}

#endif
