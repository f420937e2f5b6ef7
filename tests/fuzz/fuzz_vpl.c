/* fuzz_vpl.c — libFuzzer target for the VPL set reader (formats/vpl.c): any
 * input gives either a valid set, whose every VPL passes gb_vpl_check, or an
 * error naming the input, never a crash or a read out of bounds.
 */
#include "vpl.h"

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

static volatile float sink;

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gb_vpl_set set;
    gb_error error;
    if (gb_vpl_parse(data, size, "fuzz", &set, &error) == GB_OK) {
        if (gb_vpl_check(&set, "fuzz", &error) != GB_OK)
            __builtin_trap(); /* a parsed set is always valid */
        for (uint32_t i = 0; i < set.count; ++i)
            sink += set.vpls[i].power[0] + set.vpls[i].position[2];
        gb_vpl_free(&set);
    } else if (strncmp(error.message, "fuzz: ", 6) != 0 || set.vpls || set.count) {
        __builtin_trap(); /* failures name the input and leave an empty set */
    }
    return 0;
}
