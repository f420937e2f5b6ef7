// dense_sparse.h — a dense array in a gb_voxel_grid's frame (x fastest, then
// y, then z) to an OpenVDB tree and back.
//
// dense_to_grid builds a grid whose active voxels are those of a predicate,
// slab of 8 layers by slab, leaves filled in parallel and added in order (the
// tree does not depend on the thread count), then pruned: uniform leaves
// become tiles. After each slab it tells the caller which dense indices it
// is done with, so that a caller that frees the array can give its pages
// back as the tree grows (released_pages.h). for_each_active_voxel visits
// every active voxel and every voxel of every active tile, with its dense
// index, and stops at the first outside the frame.
#ifndef GB_OPENVDB_DENSE_SPARSE_H
#define GB_OPENVDB_DENSE_SPARSE_H

#define IMATH_HALF_NO_LOOKUP_TABLE
#include <openvdb/openvdb.h>
#include <openvdb/tools/Prune.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <vector>

#include "voxel_grid.h"

namespace gb_openvdb {

// Calls visit(offset, index) for every voxel of the frame in the leaf-sized
// block at block_origin, where offset is the voxel's place in an OpenVDB
// leaf and index its dense index.
template <typename Visit>
void for_each_block_voxel(const gb_voxel_grid *frame, const openvdb::Coord &block_origin,
                          Visit visit)
{
    const int dim = 8;
    int i_end = std::min(block_origin.x() + dim, frame->size[0]);
    int j_end = std::min(block_origin.y() + dim, frame->size[1]);
    int k_end = std::min(block_origin.z() + dim, frame->size[2]);
    for (int k = block_origin.z(); k < k_end; ++k)
        for (int j = block_origin.y(); j < j_end; ++j)
            for (int i = block_origin.x(); i < i_end; ++i) {
                // LeafNode offsets run z fastest: ((x & 7) << 6) | ((y & 7) << 3) | (z & 7).
                openvdb::Index offset = (openvdb::Index)(((i & 7) << 6) | ((j & 7) << 3) | (k & 7));
                visit(offset, gb_voxel_index(frame, i, j, k));
            }
}

// The grid whose active voxels are those where active(index) holds, with
// value(index); blocks with no active voxel get no leaf; released(begin,
// end) is told after each slab the dense indices it is done with.
template <typename GridType, typename Active, typename Value, typename Released>
typename GridType::Ptr dense_to_grid(const gb_voxel_grid *frame,
                                     typename GridType::ValueType background, Active active,
                                     Value value, Released released)
{
    using LeafType = typename GridType::TreeType::LeafNodeType;
    const int blocks_x = (frame->size[0] + 7) / 8, blocks_y = (frame->size[1] + 7) / 8;
    const size_t slab_blocks = (size_t)blocks_x * blocks_y;
    const size_t layer = (size_t)frame->size[0] * frame->size[1];
    std::vector<LeafType *> leaves(slab_blocks, nullptr);
    auto grid = GridType::create(background);
    auto &tree = grid->tree();
    for (int z = 0; z < frame->size[2]; z += 8) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, slab_blocks),
                          [&](const tbb::blocked_range<size_t> &range) {
            for (size_t b = range.begin(); b != range.end(); ++b) {
                openvdb::Coord origin((int)(b % blocks_x) * 8, (int)(b / blocks_x) * 8, z);
                LeafType *leaf = nullptr;
                for_each_block_voxel(frame, origin, [&](openvdb::Index offset, size_t index) {
                    if (active(index)) {
                        if (!leaf)
                            leaf = new LeafType(origin, background, false);
                        leaf->setValueOn(offset, value(index));
                    }
                });
                leaves[b] = leaf;
            }
        });
        for (LeafType *leaf : leaves)
            if (leaf)
                tree.addLeaf(leaf);
        released(layer * z, layer * std::min(z + 8, frame->size[2]));
    }
    openvdb::tools::prune(tree);
    return grid;
}

// The frame's voxels as an OpenVDB box.
inline openvdb::CoordBBox frame_box(const gb_voxel_grid *frame)
{
    return openvdb::CoordBBox(openvdb::Coord(0, 0, 0),
                              openvdb::Coord(frame->size[0] - 1, frame->size[1] - 1,
                                             frame->size[2] - 1));
}

// Calls visit(index, value) for every active voxel and every voxel of every
// active tile; returns false (without visiting further) at the first one
// outside the frame. The tiles above the leaves are walked by the tree's
// value iterator, the leaves one by one, each voxel found by its offset in
// the leaf (x * 64 + y * 8 + z): the value iterator alone would make a box
// and a bounds test per voxel.
template <typename GridType, typename Visit>
bool for_each_active_voxel(const GridType &grid, const gb_voxel_grid *frame, Visit visit)
{
    const openvdb::CoordBBox box_of_frame = frame_box(frame);
    auto tile = grid.cbeginValueOn();
    tile.setMaxDepth(decltype(tile)::LEAF_DEPTH - 1);
    for (; tile; ++tile) {
        openvdb::CoordBBox box;
        tile.getBoundingBox(box);
        if (!box_of_frame.isInside(box))
            return false;
        for (int k = box.min().z(); k <= box.max().z(); ++k)
            for (int j = box.min().y(); j <= box.max().y(); ++j)
                for (int i = box.min().x(); i <= box.max().x(); ++i)
                    visit(gb_voxel_index(frame, i, j, k), *tile);
    }
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
        const openvdb::Coord origin = leaf->origin();
        bool whole = box_of_frame.isInside(leaf->getNodeBoundingBox());
        for (auto voxel = leaf->cbeginValueOn(); voxel; ++voxel) {
            openvdb::Index n = voxel.pos();
            int i = origin.x() + (int)(n >> 6), j = origin.y() + (int)((n >> 3) & 7),
                k = origin.z() + (int)(n & 7);
            if (!whole && !box_of_frame.isInside(openvdb::Coord(i, j, k)))
                return false;
            visit(gb_voxel_index(frame, i, j, k), *voxel);
        }
    }
    return true;
}

} // namespace gb_openvdb

#endif
