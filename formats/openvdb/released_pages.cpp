// released_pages.cpp — madvise(MADV_DONTNEED) on whole pages (released_pages.h).
#include "released_pages.h"

#include <cstdint>

#include <sys/mman.h>
#include <unistd.h>

namespace gb_openvdb {

void release_pages(const void *begin, const void *end)
{
    uintptr_t page = (uintptr_t)sysconf(_SC_PAGESIZE);
    uintptr_t first = ((uintptr_t)begin + page - 1) / page * page;
    uintptr_t last = (uintptr_t)end / page * page;
    if (first < last)
        madvise((void *)first, last - first, MADV_DONTNEED);
}

} // namespace gb_openvdb
