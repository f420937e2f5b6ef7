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

#include "fuzz_reader.h"

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

static int is_empty(const gb_photon_map *map)
{
    return !map->count && !map->positions;
}

GB_FUZZ_READER(parse, gb_photon_map, gb_photon_map_parse, gb_photon_map_check,
               gb_photon_map_free, walk, is_empty)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gb_fuzz_parse_twice(data, size, parse);
    return 0;
}
