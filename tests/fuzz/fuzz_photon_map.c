/* fuzz_photon_map.c — libFuzzer target for the `.phot` reader
 * (formats/photon_map.c): any input gives either a map that passes
 * gb_photon_map_check, or an error "fuzz: ...", never a crash or a read out
 * of bounds (run under ASan/UBSan by `make fuzz`). The input is copied into
 * a 16-byte aligned buffer, as a mapped file is, and every photon of a parsed
 * map is read and unpacked.
 */
#include "photon_map.h"

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static volatile float sink;

static float walk(const gb_photon_map *map)
{
    float sum = 0.0f;
    for (uint64_t i = 0; i < map->count; ++i) {
        float d[3], n[3];
        gb_photon_unpack_direction(map->directions[i], d);
        gb_photon_unpack_normal(map->normals[i], n);
        sum += map->positions[3 * i] + map->powers[3 * i + 2] + d[0] + n[1] +
               (float)gb_photon_bounce(map->normals[i]);
    }
    return sum;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    unsigned char *aligned = aligned_alloc(16, (size + 16) & ~(size_t)15);
    if (!aligned)
        return 0;
    memcpy(aligned, data, size);
    gb_photon_map map;
    gb_error error;
    if (gb_photon_map_parse(aligned, size, "fuzz", &map, &error) == GB_OK) {
        if (gb_photon_map_check(&map, "fuzz", &error) != GB_OK)
            __builtin_trap(); /* a parsed map is always valid */
        sink += walk(&map);
        gb_photon_map_free(&map);
    } else if (strncmp(error.message, "fuzz: ", 6) != 0 || map.count || map.positions) {
        __builtin_trap(); /* failures name the input and leave an empty map */
    }
    free(aligned);
    return 0;
}
