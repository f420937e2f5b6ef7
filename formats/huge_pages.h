/* huge_pages.h — asking the kernel to back a large array with 2 MiB pages.
 *
 * Linux's transparent huge pages in "madvise" mode (Debian's default) give
 * them only to memory that asks. An array of hundreds of MiB walked all
 * over (thin's lattice, implicit visibility's bins) otherwise takes a page
 * fault and a TLB entry every 4 KiB. Advice only: where the kernel has no
 * huge pages, nothing changes, and the memory stays the caller's, freed as
 * it was allocated.
 */
#ifndef GB_HUGE_PAGES_H
#define GB_HUGE_PAGES_H

#include <stddef.h>

enum { GB_HUGE_PAGE_BYTES = 2u << 20 };

/* Advises huge pages for the whole 4 KiB pages of [memory, memory + bytes)
 * not yet touched (call it right after malloc or calloc). */
void gb_advise_huge_pages(void *memory, size_t bytes);

#endif
