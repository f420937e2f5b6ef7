/* huge_pages.c — see huge_pages.h. */
#include "huge_pages.h"

#include <stdint.h>
#include <sys/mman.h>

enum { SMALL_PAGE = 4096 };

void gb_advise_huge_pages(void *memory, size_t bytes)
{
#ifdef MADV_HUGEPAGE
    if (!memory || bytes < GB_HUGE_PAGE_BYTES)
        return;
    uintptr_t first = ((uintptr_t)memory + SMALL_PAGE - 1) & ~(uintptr_t)(SMALL_PAGE - 1);
    uintptr_t end = ((uintptr_t)memory + bytes) & ~(uintptr_t)(SMALL_PAGE - 1);
    if (end > first)
        madvise((void *)first, end - first, MADV_HUGEPAGE);
#else
    (void)memory;
    (void)bytes;
#endif
}
