// adapter_entry.cpp — the entry of gibake-openvdb.so (adapter.h): it keeps
// the host table it is given and returns the functions of voxel_grid.h that
// the adapter's files implement (voxel_file.cpp, int32_grid.cpp,
// content_checksum.cpp).
#include "adapter_host.h"

#include <mutex>

#define IMATH_HALF_NO_LOOKUP_TABLE
#include <openvdb/openvdb.h>

#include "content_checksum.h"
#include "int32_grid.h"
#include "voxel_file.h"

namespace gb_openvdb {

const gb_voxel_grid_host *host;

void initialize_openvdb()
{
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

namespace {

const gb_voxel_grid_adapter adapter = {write_voxel_file, write_voxel_file_and_free,
                                       read_voxel_file,  write_int32,
                                       write_int32_and_free, read_int32,
                                       file_checksum};

} // namespace

} // namespace gb_openvdb

// host is a gb_voxel_grid_host, the result a gb_voxel_grid_adapter.
extern "C" __attribute__((visibility("default"))) const void *
gb_openvdb_adapter(const void *given)
{
    gb_openvdb::host = static_cast<const gb_voxel_grid_host *>(given);
    return &gb_openvdb::adapter;
}
