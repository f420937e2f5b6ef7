// adapter_host.h — what every file of the OpenVDB adapter (gibake-openvdb.so,
// formats/openvdb/) shares: the host table gibake gave the adapter's entry
// (voxel_grid_adapter.h: the only way the adapter calls gibake) and
// OpenVDB's one-time initialisation. C++, internal to the adapter.
#ifndef GB_OPENVDB_ADAPTER_HOST_H
#define GB_OPENVDB_ADAPTER_HOST_H

#include <exception>
#include <new>

#include "voxel_grid_adapter.h"

namespace gb_openvdb {

// Set by the entry (adapter_entry.cpp) before any other function runs.
extern const gb_voxel_grid_host *host;

// openvdb::initialize(), once per process, thread-safe.
void initialize_openvdb();

// work() after initialize_openvdb(), an exception turned into a gb_result:
// out of memory, or otherwise (GB_ERROR_IO for a write, GB_ERROR_FORMAT for
// a read) with OpenVDB's message after path.
template <typename Work>
gb_result guarded(const char *path, gb_result otherwise, Work work, gb_error *error)
{
    try {
        initialize_openvdb();
        return work();
    } catch (const std::bad_alloc &) {
        return host->fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    } catch (const std::exception &e) {
        return host->fail(error, otherwise, "%s: %s", path, e.what());
    }
}

} // namespace gb_openvdb

#endif
