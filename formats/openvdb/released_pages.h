// released_pages.h — giving the memory pages of a dense array back to the
// system while a sparse copy of it is built (dense_sparse.h), so that the
// two are not held at once.
#ifndef GB_OPENVDB_RELEASED_PAGES_H
#define GB_OPENVDB_RELEASED_PAGES_H

namespace gb_openvdb {

// Gives the whole memory pages inside [begin, end) back to the system: they
// read as zeros afterwards. Only for arrays about to be freed, never on bytes
// outside them (so not on an allocator's own headers).
void release_pages(const void *begin, const void *end);

} // namespace gb_openvdb

#endif
