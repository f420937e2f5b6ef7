// voxelize_bench.cpp — times one step of the voxelize benchmark on one scene
// at one resolution, for bench/voxelize.sh (which runs each mode in its own
// process to measure its peak memory):
//
//   voxelize_bench voxelize SCENE RESOLUTION OUT.vdb
//       load, surface, write: seconds of each, then the counts
//   voxelize_bench mesh_to_volume SCENE RESOLUTION
//       OpenVDB's meshToVolume (unsigned distance, 1-voxel band) on the same
//       triangles with the same voxel size, for comparison
//
// Prints one line of key=value pairs. Bench code: C++ only to call OpenVDB.

extern "C" {
#include "progress.h"
#include "scene.h"
#include "voxel_grid.h"
#include "../tools/voxelize/voxelize.h"
}

#define IMATH_HALF_NO_LOOKUP_TABLE
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

static void fail(const char *what, const gb_error &error)
{
    std::fprintf(stderr, "voxelize_bench: %s: %s\n", what, error.message);
    std::exit(1);
}

static void bounds_of(const gb_scene &scene, double lower[3], double upper[3])
{
    for (int d = 0; d < 3; ++d) {
        lower[d] = INFINITY;
        upper[d] = -INFINITY;
    }
    for (uint32_t i = 0; i < 3 * scene.triangle_count; ++i)
        for (int d = 0; d < 3; ++d) {
            double x = scene.positions[3 * (size_t)scene.indices[i] + d];
            lower[d] = std::fmin(lower[d], x);
            upper[d] = std::fmax(upper[d], x);
        }
}

struct voxelized {
    gb_voxel_grid grid;
    double surface_seconds;
};

static voxelized voxelize(const gb_scene &scene, uint32_t resolution)
{
    gb_error error;
    gb_voxelize_options options = {};
    options.resolution = resolution;
    double lower[3], upper[3];
    bounds_of(scene, lower, upper);
    gb_voxel_grid grid = {};
    double start = gb_seconds();
    if (gb_voxelize_frame(lower, upper, &options, &grid, &error) != GB_OK)
        fail("frame", error);
    int32_t size[3] = {grid.size[0], grid.size[1], grid.size[2]};
    if (gb_voxel_grid_allocate(&grid, size, &error) != GB_OK)
        fail("allocate", error);
    double pad[3] = {GB_VOXELIZE_DEFAULT_PAD, GB_VOXELIZE_DEFAULT_PAD, GB_VOXELIZE_DEFAULT_PAD};
    if (gb_voxelize_surface(&grid, lower, pad, scene.positions, scene.vertex_count,
                            scene.indices, scene.triangle_count, &options, &error) != GB_OK)
        fail("surface", error);
    double surface_done = gb_seconds();
    grid.scene_hash = scene.hash;
    return {grid, surface_done - start};
}

static int run_voxelize(const gb_scene &scene, uint32_t resolution, const char *output,
                        double load_seconds)
{
    gb_error error;
    voxelized v = voxelize(scene, resolution);
    gb_voxel_grid &grid = v.grid;
    int32_t size[3] = {grid.size[0], grid.size[1], grid.size[2]}; /* the write frees grid */
    size_t count = (size_t)size[0] * size[1] * size[2], surface = 0;
    for (size_t i = 0; i < count; ++i)
        surface += grid.surface[i];
    double write_start = gb_seconds();
    if (gb_voxel_grid_write_and_free(output, &grid, &error) != GB_OK)
        fail("write", error);
    double write_done = gb_seconds();
    std::printf("load=%.3f surface=%.3f write=%.3f size=%dx%dx%d surface_voxels=%zu\n",
                load_seconds, v.surface_seconds, write_done - write_start,
                size[0], size[1], size[2], surface);
    return 0;
}

static int run_mesh_to_volume(const gb_scene &scene, uint32_t resolution, double load_seconds)
{
    openvdb::initialize();
    double lower[3], upper[3];
    bounds_of(scene, lower, upper);
    double longest = std::fmax(upper[0] - lower[0],
                               std::fmax(upper[1] - lower[1], upper[2] - lower[2]));
    std::vector<openvdb::Vec3s> points(scene.vertex_count);
    for (uint32_t v = 0; v < scene.vertex_count; ++v)
        points[v] = openvdb::Vec3s(scene.positions[3 * v], scene.positions[3 * v + 1],
                                   scene.positions[3 * v + 2]);
    std::vector<openvdb::Vec3I> triangles(scene.triangle_count);
    for (uint32_t t = 0; t < scene.triangle_count; ++t)
        triangles[t] = openvdb::Vec3I(scene.indices[3 * t], scene.indices[3 * t + 1],
                                      scene.indices[3 * t + 2]);
    std::vector<openvdb::Vec4I> quads;
    auto transform = openvdb::math::Transform::createLinearTransform(longest / resolution);
    double start = gb_seconds();
    auto grid = openvdb::tools::meshToUnsignedDistanceField<openvdb::FloatGrid>(
        *transform, points, triangles, quads, 1.0f);
    double done = gb_seconds();
    std::printf("load=%.3f mesh_to_volume=%.3f active_voxels=%llu\n", load_seconds,
                done - start, (unsigned long long)grid->activeVoxelCount());
    return 0;
}

int main(int argc, char **argv)
{
    bool with_output = argc > 1 && std::strcmp(argv[1], "mesh_to_volume") != 0;
    if (argc != (with_output ? 5 : 4)) {
        std::fprintf(stderr, "usage: voxelize_bench voxelize SCENE RESOLUTION OUT.vdb\n"
                             "       voxelize_bench mesh_to_volume SCENE RESOLUTION\n");
        return 2;
    }
    gb_scene scene;
    gb_error error;
    double start = gb_seconds();
    if (gb_scene_load(argv[2], nullptr, &scene, &error) != GB_OK)
        fail(argv[2], error);
    double load_seconds = gb_seconds() - start;
    uint32_t resolution = (uint32_t)std::atoi(argv[3]);
    int status = std::strcmp(argv[1], "voxelize") == 0
                     ? run_voxelize(scene, resolution, argv[4], load_seconds)
                     : run_mesh_to_volume(scene, resolution, load_seconds);
    gb_scene_free(&scene);
    return status;
}
