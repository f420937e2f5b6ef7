/* bit_rows.h — rows of bits in 64-bit words, bit x of a row in word
 * x / 64 at bit x % 64: the bitmaps of chart_mask.c and occupancy.c. The
 * caller owns the words. */
#ifndef GB_ATLAS_BIT_ROWS_H
#define GB_ATLAS_BIT_ROWS_H

#include <stdint.h>

/* Sets bits first .. last (inclusive) of a row. */
static inline void gb_bits_set(uint64_t *row, uint64_t first, uint64_t last)
{
    for (uint64_t w = first / 64; w <= last / 64; ++w) {
        uint64_t lo = w == first / 64 ? first % 64 : 0, hi = w == last / 64 ? last % 64 : 63;
        row[w] |= (~UINT64_C(0) >> (63 - hi)) & (~UINT64_C(0) << lo);
    }
}

/* The first bit at or after from that is set (set = 1) or clear (set =
 * 0), before end; end when none. */
static inline uint64_t gb_bits_next(const uint64_t *row, uint64_t from, uint64_t end, int set)
{
    while (from < end) {
        uint64_t word = set ? row[from / 64] : ~row[from / 64];
        word &= ~UINT64_C(0) << (from % 64);
        if (word) {
            uint64_t at = from / 64 * 64 + (uint64_t)__builtin_ctzll(word);
            return at < end ? at : end;
        }
        from = from / 64 * 64 + 64;
    }
    return end;
}

#endif
