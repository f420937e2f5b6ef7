// grid_frame.cpp — a frame as OpenVDB metadata and transform (grid_frame.h).
#include "grid_frame.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <string>

#include <unistd.h>

#include "adapter_host.h"

namespace gb_openvdb {

bool frame_is_valid(const gb_voxel_grid *frame)
{
    for (int axis = 0; axis < 3; ++axis)
        if (frame->size[axis] <= 0 || frame->size[axis] > MAX_SIDE
            || !std::isfinite(frame->world_origin[axis]))
            return false;
    return std::isfinite(frame->voxel_size) && frame->voxel_size > 0;
}

size_t frame_voxel_count(const gb_voxel_grid *frame)
{
    return (size_t)frame->size[0] * (size_t)frame->size[1] * (size_t)frame->size[2];
}

bool same_frame(const gb_voxel_grid *a, const gb_voxel_grid *b)
{
    return a->size[0] == b->size[0] && a->size[1] == b->size[1] && a->size[2] == b->size[2]
           && a->voxel_size == b->voxel_size && a->world_origin[0] == b->world_origin[0]
           && a->world_origin[1] == b->world_origin[1]
           && a->world_origin[2] == b->world_origin[2] && a->scene_hash == b->scene_hash
           && a->resolution == b->resolution;
}

namespace {

openvdb::math::Transform::Ptr frame_transform(const gb_voxel_grid *frame)
{
    double h = frame->voxel_size;
    auto transform = openvdb::math::Transform::createLinearTransform(h);
    transform->postTranslate(openvdb::Vec3d(frame->world_origin[0] + 0.5 * h,
                                            frame->world_origin[1] + 0.5 * h,
                                            frame->world_origin[2] + 0.5 * h));
    return transform;
}

std::string hash_to_hex(uint64_t hash)
{
    char text[17];
    std::snprintf(text, sizeof text, "%016" PRIx64, hash);
    return text;
}

bool hex_to_hash(const std::string &text, uint64_t *hash)
{
    if (text.size() != 16)
        return false;
    uint64_t value = 0;
    for (char c : text) {
        int digit = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
        if (digit < 0)
            return false;
        value = value << 4 | (uint64_t)digit;
    }
    *hash = value;
    return true;
}

template <typename T>
bool find_meta(const openvdb::GridBase &grid, const char *key, T *value)
{
    auto meta = grid.getMetadata<openvdb::TypedMetadata<T>>(key);
    if (!meta)
        return false;
    *value = meta->value();
    return true;
}

// Whether grid's transform is the one of voxel_size and origin.
bool transform_matches(const openvdb::GridBase &grid, double voxel_size,
                       const openvdb::Vec3d &origin)
{
    const openvdb::math::Transform &transform = grid.transform();
    openvdb::Vec3d centre = transform.indexToWorld(openvdb::Vec3d(0, 0, 0));
    openvdb::Vec3d step = transform.indexToWorld(openvdb::Vec3d(1, 1, 1)) - centre;
    double tolerance = 1e-9 * voxel_size;
    bool matches = transform.isLinear() && transform.hasUniformScale();
    for (int axis = 0; axis < 3 && matches; ++axis)
        matches = std::fabs(step[axis] - voxel_size) <= tolerance
                  && std::fabs(centre[axis] - (origin[axis] + 0.5 * voxel_size))
                         <= tolerance + 1e-12 * std::fabs(origin[axis]);
    return matches;
}

} // namespace

void attach_frame(openvdb::GridBase &grid, const gb_voxel_grid *frame, const char *name,
                  const char *creator, int32_t version)
{
    grid.setName(name);
    grid.setCreator(creator);
    grid.setTransform(frame_transform(frame));
    grid.insertMeta("gibake_format", openvdb::Int32Metadata(version));
    grid.insertMeta("voxel_size", openvdb::DoubleMetadata(frame->voxel_size));
    grid.insertMeta("world_origin", openvdb::Vec3DMetadata(openvdb::Vec3d(
        frame->world_origin[0], frame->world_origin[1], frame->world_origin[2])));
    grid.insertMeta("grid_size", openvdb::Vec3IMetadata(openvdb::Vec3i(
        frame->size[0], frame->size[1], frame->size[2])));
    grid.insertMeta("scene_hash", openvdb::StringMetadata(hash_to_hex(frame->scene_hash)));
    grid.insertMeta("resolution", openvdb::Int32Metadata((int32_t)frame->resolution));
}

gb_result read_frame(const char *path, const openvdb::GridBase &grid, int32_t version,
                     const char *remake, double bytes_per_voxel, gb_voxel_grid *frame,
                     gb_error *error)
{
    const std::string grid_name = grid.getName();
    const char *name = grid_name.c_str();
    int32_t found_version = 0, resolution = 0;
    double voxel_size = 0;
    openvdb::Vec3d origin;
    openvdb::Vec3i size;
    std::string hash_text;
    const char *missing = !find_meta(grid, "gibake_format", &found_version) ? "gibake_format (int32)"
        : !find_meta(grid, "voxel_size", &voxel_size) ? "voxel_size (double)"
        : !find_meta(grid, "world_origin", &origin) ? "world_origin (vec3d)"
        : !find_meta(grid, "grid_size", &size) ? "grid_size (vec3i)"
        : !find_meta(grid, "scene_hash", &hash_text) ? "scene_hash (string)"
        : !find_meta(grid, "resolution", &resolution) ? "resolution (int32)"
        : nullptr;
    if (missing)
        return host->fail(error, GB_ERROR_FORMAT, "%s: grid '%s' has no metadata %s", path, name,
                          missing);
    if (found_version != version)
        return host->fail(error, found_version < version ? GB_ERROR_UNSUPPORTED : GB_ERROR_FORMAT,
                          "%s: grid '%s' has gibake_format %d, this program reads %d%s%s", path,
                          name, (int)found_version, (int)version,
                          found_version < version ? ": make it again with " : "",
                          found_version < version ? remake : "");
    uint64_t hash = 0;
    if (!hex_to_hash(hash_text, &hash))
        return host->fail(error, GB_ERROR_FORMAT,
                          "%s: grid '%s': scene_hash '%.40s' is not 16 lowercase hex digits",
                          path, name, hash_text.c_str());
    if (resolution < 0)
        return host->fail(error, GB_ERROR_FORMAT, "%s: grid '%s': negative resolution %d", path,
                          name, (int)resolution);
    gb_voxel_grid read = {};
    read.voxel_size = voxel_size;
    for (int axis = 0; axis < 3; ++axis) {
        read.size[axis] = size[axis];
        read.world_origin[axis] = origin[axis];
    }
    read.scene_hash = hash;
    read.resolution = (uint32_t)resolution;
    if (!frame_is_valid(&read))
        return host->fail(error, GB_ERROR_FORMAT,
                          "%s: grid '%s': bad frame (grid_size %d x %d x %d, voxel_size %g)",
                          path, name, (int)size[0], (int)size[1], (int)size[2], voxel_size);
    // The readers fill a dense array of the frame: refused before it is
    // allocated when it could never fit, rather than left to the allocator
    // or the OOM killer.
    double dense = bytes_per_voxel * (double)frame_voxel_count(&read);
    double memory = (double)sysconf(_SC_PHYS_PAGES) * (double)sysconf(_SC_PAGESIZE);
    if (memory > 0 && dense > memory)
        return host->fail(error, GB_ERROR_UNSUPPORTED,
                          "%s: grid '%s': grid_size %d x %d x %d needs %.1f GiB in memory, more "
                          "than this machine's %.1f GiB", path, name, (int)size[0],
                          (int)size[1], (int)size[2], dense / (1 << 30), memory / (1 << 30));
    if (!transform_matches(grid, voxel_size, origin))
        return host->fail(error, GB_ERROR_FORMAT,
                          "%s: grid '%s': transform does not match voxel_size and world_origin",
                          path, name);
    *frame = read;
    return GB_OK;
}

} // namespace gb_openvdb
