/* fix_checksums.h — recomputes the CRC-32s of a gibake container in a fuzz
 * input, so that mutations reach the checks of the format inside it instead
 * of all stopping at the container's checksums. Used by the fuzz targets of
 * container-based formats (.lot, .skel, .atlas): each input is parsed as it is, then
 * again after gb_fuzz_fix_container_checksums (gb_fuzz_parse_twice, fuzz_reader.h).
 *
 * Layout (formats/FORMATS.md, "Container"): a 32-byte header whose section
 * count is the u32 at 24 and whose CRC at 28 covers its first 28 bytes and
 * the table; 48-byte table entries after it, payload offset (u64) at 24,
 * size (u64) at 32, CRC (u32) at 40. Entries that point outside the input
 * are left as they are.
 */
#ifndef GB_FUZZ_FIX_CHECKSUMS_H
#define GB_FUZZ_FIX_CHECKSUMS_H

#include <stddef.h>
#include <stdint.h>
#include <zlib.h>

static inline uint32_t gb_fuzz_get_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static inline uint64_t gb_fuzz_get_u64(const unsigned char *p)
{
    return gb_fuzz_get_u32(p) | (uint64_t)gb_fuzz_get_u32(p + 4) << 32;
}

static inline void gb_fuzz_put_u32(unsigned char *p, uint32_t v)
{
    for (int i = 0; i < 4; ++i)
        p[i] = (unsigned char)(v >> (8 * i));
}

static inline void gb_fuzz_fix_container_checksums(unsigned char *bytes, size_t size)
{
    if (size < 32)
        return;
    uint64_t count = gb_fuzz_get_u32(bytes + 24);
    if (count > (size - 32) / 48)
        return;
    for (uint64_t i = 0; i < count; ++i) {
        unsigned char *entry = bytes + 32 + i * 48;
        uint64_t offset = gb_fuzz_get_u64(entry + 24), length = gb_fuzz_get_u64(entry + 32);
        if (offset <= size && length <= size - offset && length <= UINT32_MAX)
            gb_fuzz_put_u32(entry + 40, (uint32_t)crc32(crc32(0L, Z_NULL, 0), bytes + offset,
                                                        (uInt)length));
    }
    uLong crc = crc32(crc32(0L, Z_NULL, 0), bytes, 28);
    gb_fuzz_put_u32(bytes + 28, (uint32_t)crc32(crc, bytes + 32, (uInt)(count * 48)));
}

#endif
