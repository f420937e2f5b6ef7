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

#include "fuzz_reader.h"

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

GB_FUZZ_READER(parse, gb_skeleton, gb_skeleton_parse, gb_skeleton_validate, gb_skeleton_free,
               walk, is_zeroed)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gb_fuzz_parse_twice(data, size, parse);
    return 0;
}
