/* fuzz_segmentation.c — libFuzzer target for the `.seg` reader: any input
 * must give either a segmentation that passes gb_segmentation_validate, or
 * an error "fuzz: ..." and a zeroed segmentation, never a crash or a read out of bounds (run under
 * ASan/UBSan by `make fuzz`). A parsed segmentation is walked through its
 * indices (node map -> node -> cluster, gate -> edge -> nodes; an opening
 * gate, on no edge, only in a fitted file, to two clusters in range), so an
 * index the reader let through out of range is caught. Seeds:
 * tests/fuzz/corpus/fuzz_segmentation, written by segment: the Cornell box at
 * 48 voxels with the paper's gates and with the gates fitted (--voxels
 * --grid), the two rooms at 32 fitted.
 */
#include "segmentation.h"

#include <stddef.h>
#include <stdint.h>

#include "fuzz_reader.h"

static unsigned walk(const gb_segmentation *s)
{
    unsigned sum = 0;
    for (uint32_t k = 0; k < s->skeleton_node_count; ++k)
        sum += s->cluster[s->node_map[k]] + s->nodes[s->node_map[k]].node_class;
    for (uint32_t g = 0; g < s->gate_count; ++g) {
        const gb_visibility_gate *gate = &s->gates[g];
        if (gate->edge == GB_SEGMENTATION_NO_EDGE) { /* an opening gate */
            if (!s->gates_fitted || gate->clusters[0] >= gate->clusters[1] ||
                gate->clusters[1] >= s->cluster_count)
                __builtin_trap();
            continue;
        }
        const uint32_t *edge = s->edges + 2 * gate->edge;
        sum += s->cluster[edge[0]] + s->cluster[edge[1]];
    }
    return sum;
}

/* On failure the segmentation is zeroed (segmentation.h). */
static int is_zeroed(const gb_segmentation *s)
{
    return !s->nodes && !s->edges && !s->cluster && !s->node_map && !s->gates &&
           !s->skeleton_node_count && !s->node_count && !s->edge_count && !s->cluster_count &&
           !s->gate_count;
}

GB_FUZZ_READER(parse, gb_segmentation, gb_segmentation_parse, gb_segmentation_validate,
               gb_segmentation_free, walk, is_zeroed)

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    parse(data, size);
    return 0;
}
