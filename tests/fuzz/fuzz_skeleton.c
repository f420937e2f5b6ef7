/* fuzz_skeleton.c — libFuzzer target for the `.skel` reader
 * (formats/skeleton.c): any input gives either a skeleton that passes
 * gb_skeleton_validate, or an error "fuzz: ...", never a crash or a read
 * out of bounds (run under ASan/UBSan by `make fuzz`). Every node and edge of
 * a parsed skeleton is read through the edges' indices, as segment does.
 *
 * Each input is parsed as it is, then again with its container checksums
 * recomputed (fix_checksums.h), which lets the mutations reach the
 * skeleton's own checks. Seeds: tests/fuzz/corpus/fuzz_skeleton, written by
 * thin.
 */
#include "skeleton.h"

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fix_checksums.h"

static volatile float sink;

static float walk(const gb_skeleton *s)
{
    float sum = 0.0f;
    for (uint32_t e = 0; e < s->edge_count; ++e) {
        const gb_skeleton_node *a = &s->nodes[s->edges[2 * e]], *b = &s->nodes[s->edges[2 * e + 1]];
        sum += a->radius + b->position[2];
    }
    for (uint32_t n = 0; n < s->node_count; ++n)
        sum += s->nodes[n].position[0];
    return sum;
}

static int is_zeroed(const gb_skeleton *s)
{
    return !s->nodes && !s->edges && !s->node_count && !s->edge_count;
}

static void parse(const unsigned char *bytes, size_t size)
{
    gb_skeleton skeleton;
    gb_error error;
    if (gb_skeleton_parse(bytes, size, "fuzz", &skeleton, &error) == GB_OK) {
        if (gb_skeleton_validate(&skeleton, "fuzz", &error) != GB_OK)
            __builtin_trap(); /* what the reader accepts is valid */
        sink += walk(&skeleton);
        gb_skeleton_free(&skeleton);
    } else if (strncmp(error.message, "fuzz: ", 6) != 0 || !is_zeroed(&skeleton)) {
        __builtin_trap(); /* failures name the input and leave a zeroed skeleton */
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gb_fuzz_parse_twice(data, size, parse);
    return 0;
}
