// grid_file.h — OpenVDB grids to a gibake file and back: the write through
// the one output writer (output_file.h) with the checksum put in after
// (content_checksum.h), and the checked read of every grid of a file.
//
// Writing: write_grids(path, make_grids, error) opens path (a temporary and
// a rename, or a device, FIFO or "-" through a temporary copied), calls
// make_grids() for the grids, writes them compressed (Blosc, else zip, and
// OpenVDB's active-mask compression), puts the checksum in and commits: on
// failure nothing is left beside path and an older file there is kept.
//
// Reading: a Reader checks the checksum, maps the file, has it walked by
// gb_voxel_file_check (voxel_check.h: every size and count OpenVDB will
// allocate or copy by is checked against the file), then lets OpenVDB read
// it from a std::istream that throws on a read past its end; read() then
// gives a grid by name and type. The Reader owns the grids and the mapping.
#ifndef GB_OPENVDB_GRID_FILE_H
#define GB_OPENVDB_GRID_FILE_H

#define IMATH_HALF_NO_LOOKUP_TABLE
#include <openvdb/openvdb.h>

#include <sys/mman.h>

#include "adapter_host.h"
#include "content_checksum.h"

namespace gb_openvdb {

// Writes grids into the file name (the output's temporary for path).
gb_result write_archive(const char *path, const char *name, const openvdb::GridPtrVec &grids,
                        gb_error *error);

// Removes the output's temporary unless committed, exceptions included.
struct OutputGuard {
    gb_output_file *file = nullptr;
    ~OutputGuard() { host->output->abort(file); }
    gb_result commit(gb_error *error)
    {
        gb_output_file *committed = file;
        file = nullptr;
        return host->output->commit(committed, error);
    }
};

template <typename MakeGrids>
gb_result write_grids(const char *path, MakeGrids make_grids, gb_error *error)
{
    OutputGuard out;
    gb_result result = host->output->open(path, GB_OUTPUT_FILE_BY_NAME, &out.file, error);
    if (result != GB_OK)
        return result;
    const char *name = host->output->name(out.file);
    {
        openvdb::GridPtrVec grids = make_grids();
        result = write_archive(path, name, grids, error);
    }
    if (result == GB_OK)
        result = write_content_uuid(path, name, error);
    return result == GB_OK ? out.commit(error) : result;
}

struct Reader {
    const char *path;
    void *mapping = MAP_FAILED;
    size_t size = 0;
    openvdb::GridPtrVecPtr grids;

    explicit Reader(const char *path_) : path(path_) {}
    Reader(const Reader &) = delete;
    Reader &operator=(const Reader &) = delete;
    ~Reader();

    // Checks and reads every grid of the file.
    gb_result open(gb_error *error);

    // The grid name of GridType (type_name, for the message).
    template <typename GridType>
    gb_result read(const char *name, const char *type_name, typename GridType::Ptr *grid,
                   gb_error *error)
    {
        openvdb::GridBase::Ptr found;
        for (const openvdb::GridBase::Ptr &candidate : *grids)
            if (candidate && candidate->getName() == name) {
                found = candidate;
                break;
            }
        if (!found)
            return host->fail(error, GB_ERROR_FORMAT, "%s: no grid '%s'", path, name);
        *grid = openvdb::gridPtrCast<GridType>(found);
        if (!*grid)
            return host->fail(error, GB_ERROR_FORMAT, "%s: grid '%s' is not a %s grid", path,
                              name, type_name);
        return GB_OK;
    }

private:
    gb_result map(gb_error *error);
};

} // namespace gb_openvdb

#endif
