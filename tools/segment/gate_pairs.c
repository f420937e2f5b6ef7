/* gate_pairs.c — the gates by cluster pair (gate_pairs.h). */
#include "gate_pairs.h"

#include <stdlib.h>
#include <string.h>

static int compare_pairs(const void *a, const void *b)
{
    const gb_gate_pair *x = a, *y = b;
    if (x->low != y->low)
        return x->low < y->low ? -1 : 1;
    if (x->high != y->high)
        return x->high < y->high ? -1 : 1;
    return x->gate < y->gate ? -1 : x->gate > y->gate;
}

gb_result gb_gate_pairs_build(const gb_segmentation *s, gb_gate_pairs *out, gb_error *error)
{
    memset(out, 0, sizeof *out);
    out->pairs = malloc(((size_t)s->gate_count + 1) * sizeof *out->pairs);
    if (!out->pairs)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "out of memory for %u gates",
                       s->gate_count);
    out->count = s->gate_count;
    for (uint32_t g = 0; g < s->gate_count; ++g) {
        const uint32_t *c = s->gates[g].clusters;
        out->pairs[g] = (gb_gate_pair){c[0] < c[1] ? c[0] : c[1], c[0] < c[1] ? c[1] : c[0], g};
    }
    qsort(out->pairs, out->count, sizeof *out->pairs, compare_pairs);
    return GB_OK;
}

uint32_t gb_gate_pairs_find(const gb_gate_pairs *p, uint32_t a, uint32_t b, uint32_t *first)
{
    gb_gate_pair key = {a < b ? a : b, a < b ? b : a, 0};
    uint32_t low = 0, high = p->count;
    while (low < high) {
        uint32_t middle = low + (high - low) / 2;
        if (compare_pairs(&p->pairs[middle], &key) < 0)
            low = middle + 1;
        else
            high = middle;
    }
    uint32_t end = low;
    while (end < p->count && p->pairs[end].low == key.low && p->pairs[end].high == key.high)
        ++end;
    *first = low;
    return end - low;
}

void gb_gate_pairs_free(gb_gate_pairs *p)
{
    free(p->pairs);
    memset(p, 0, sizeof *p);
}
