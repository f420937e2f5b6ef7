/* fuzz_vpl.c — libFuzzer target for the VPL set reader (formats/vpl.c): any
 * input gives either a valid set, whose every VPL passes gb_vpl_check, or an
 * error naming the input, never a crash or a read out of bounds.
 */
#include "vpl.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "fuzz_reader.h"

static float walk(const gb_vpl_set *set)
{
    float sum = 0.0f;
    for (uint32_t i = 0; i < set->count; ++i)
        sum += set->vpls[i].power[0] + set->vpls[i].position[2];
    return sum;
}

static int is_empty(const gb_vpl_set *set)
{
    return !set->vpls && !set->count;
}

GB_FUZZ_READER(parse, gb_vpl_set, gb_vpl_parse, gb_vpl_check, gb_vpl_free, walk, is_empty)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    parse(data, size);
    return 0;
}
