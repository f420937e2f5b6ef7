/* gate_pairs.h — a segmentation's visibility gates by the pair of clusters
 * they join, to answer "which gates join clusters a and b?" by a binary
 * search: the evaluation's one-gate predictor (evaluate.c) and the face of
 * an opening looking for its gate (gate_openings.h). The pairs are sorted
 * by (smaller cluster, larger cluster, gate), so the gates of one pair come
 * in increasing index.
 *
 *   gb_gate_pairs pairs;
 *   gb_gate_pairs_build(&seg, &pairs, &error);
 *   uint32_t first, count = gb_gate_pairs_find(&pairs, a, b, &first);
 *   for (uint32_t i = first; i < first + count; ++i)
 *       use(seg.gates[pairs.pairs[i].gate]);
 *   gb_gate_pairs_free(&pairs);
 *
 * The caller owns the table (malloc'ed; gb_gate_pairs_free, also on a
 * zeroed one). It lists the gates the segmentation had when it was built.
 */
#ifndef GB_SEGMENT_GATE_PAIRS_H
#define GB_SEGMENT_GATE_PAIRS_H

#include <stdint.h>

#include "result.h"
#include "segmentation.h"

typedef struct gb_gate_pair {
    uint32_t low, high;         /* the gate's clusters, smaller first */
    uint32_t gate;              /* index into the segmentation's gates */
} gb_gate_pair;

typedef struct gb_gate_pairs {
    uint32_t count;             /* the segmentation's gate count */
    gb_gate_pair *pairs;
} gb_gate_pairs;

gb_result gb_gate_pairs_build(const gb_segmentation *segmentation, gb_gate_pairs *out,
                              gb_error *error);
/* How many gates join clusters a and b (in either order); *first: where
 * they start in pairs->pairs. */
uint32_t gb_gate_pairs_find(const gb_gate_pairs *pairs, uint32_t a, uint32_t b,
                            uint32_t *first);
void gb_gate_pairs_free(gb_gate_pairs *pairs);

#endif
