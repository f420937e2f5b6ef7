// voxel_grid_openvdb.cpp — the one OpenVDB adapter of gibake: the voxel file
// (grids "surface", "empty", "distance") and int32 grids such as thin's
// "nearest_node", in the frame of a gb_voxel_grid (formats/FORMATS.md,
// "Voxel file"). The C++ stays in this file; the rest of the project sees
// formats/voxel_grid.h. Built as the shared object gibake-openvdb.so,
// loaded by formats/voxel_grid.c on first use; it calls gibake only through
// the host table it is given (voxel_grid_adapter.h).
//
// Index space: voxel (i,j,k) of the dense frame is OpenVDB coordinate
// (i,j,k); its centre is at world_origin + voxel_size * (i+1/2, j+1/2, k+1/2),
// which is what the grids' linear transform says.

#include "voxel_grid_adapter.h"

// Half-float conversions by arithmetic, not by Imath's table: the table lives
// in libImath, which the link line does not name.
#define IMATH_HALF_NO_LOOKUP_TABLE
#include <openvdb/openvdb.h>
#include <openvdb/io/File.h>
#include <openvdb/io/Stream.h>
#include <openvdb/tools/Prune.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <mutex>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace {

const gb_voxel_grid_host *host;

const char *const VOXELIZE_CREATOR = "gibake-voxelize 0.1";
const char *const INT32_CREATOR = "gibake 0.1";
// 2: the checksum covers the whole header and the length (1: bytes 57.. only).
const int32_t FORMAT_VERSION = 2;
const int32_t MAX_SIDE = 1 << 20;

void initialize_openvdb()
{
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

// ---------------------------------------------------------------- the frame

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

void attach_frame(openvdb::GridBase &grid, const gb_voxel_grid *frame, const char *name,
                  const char *creator)
{
    grid.setName(name);
    grid.setCreator(creator);
    grid.setTransform(frame_transform(frame));
    grid.insertMeta("gibake_format", openvdb::Int32Metadata(FORMAT_VERSION));
    grid.insertMeta("voxel_size", openvdb::DoubleMetadata(frame->voxel_size));
    grid.insertMeta("world_origin", openvdb::Vec3DMetadata(openvdb::Vec3d(
        frame->world_origin[0], frame->world_origin[1], frame->world_origin[2])));
    grid.insertMeta("grid_size", openvdb::Vec3IMetadata(openvdb::Vec3i(
        frame->size[0], frame->size[1], frame->size[2])));
    grid.insertMeta("scene_hash", openvdb::StringMetadata(hash_to_hex(frame->scene_hash)));
    grid.insertMeta("resolution", openvdb::Int32Metadata((int32_t)frame->resolution));
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

// Reads the frame metadata of grid into frame (size, voxel size, origin,
// hash, resolution) and checks it against the grid's transform.
gb_result read_frame(const char *path, const openvdb::GridBase &grid, gb_voxel_grid *frame,
                     gb_error *error)
{
    const std::string grid_name = grid.getName();
    const char *name = grid_name.c_str();
    int32_t version = 0, resolution = 0;
    double voxel_size = 0;
    openvdb::Vec3d origin;
    openvdb::Vec3i size;
    std::string hash_text;
    const char *missing = !find_meta(grid, "gibake_format", &version) ? "gibake_format (int32)"
        : !find_meta(grid, "voxel_size", &voxel_size) ? "voxel_size (double)"
        : !find_meta(grid, "world_origin", &origin) ? "world_origin (vec3d)"
        : !find_meta(grid, "grid_size", &size) ? "grid_size (vec3i)"
        : !find_meta(grid, "scene_hash", &hash_text) ? "scene_hash (string)"
        : !find_meta(grid, "resolution", &resolution) ? "resolution (int32)"
        : nullptr;
    if (missing)
        return host->fail(error, GB_ERROR_FORMAT, "%s: grid '%s' has no metadata %s", path, name,
                       missing);
    if (version != FORMAT_VERSION)
        return host->fail(error, GB_ERROR_FORMAT,
                       "%s: grid '%s' has gibake_format %d, this program reads %d", path,
                       name, (int)version, (int)FORMAT_VERSION);
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
                       "%s: grid '%s': bad frame (grid_size %d x %d x %d, voxel_size %g)", path,
                       name, (int)size[0], (int)size[1], (int)size[2], voxel_size);
    // The readers fill a dense array of the frame (5 bytes a voxel for the
    // voxel file, 4 for an int32 grid): refused before it is allocated when
    // it could never fit, rather than left to the allocator or the OOM killer.
    double dense = 5.0 * (double)frame_voxel_count(&read);
    double memory = (double)sysconf(_SC_PHYS_PAGES) * (double)sysconf(_SC_PAGESIZE);
    if (memory > 0 && dense > memory)
        return host->fail(error, GB_ERROR_UNSUPPORTED,
                       "%s: grid '%s': grid_size %d x %d x %d needs %.1f GiB in memory, more "
                       "than this machine's %.1f GiB", path, name, (int)size[0], (int)size[1],
                       (int)size[2], dense / (1 << 30), memory / (1 << 30));
    const openvdb::math::Transform &transform = grid.transform();
    openvdb::Vec3d centre = transform.indexToWorld(openvdb::Vec3d(0, 0, 0));
    openvdb::Vec3d step = transform.indexToWorld(openvdb::Vec3d(1, 1, 1)) - centre;
    double tolerance = 1e-9 * voxel_size;
    bool matches = transform.isLinear() && transform.hasUniformScale();
    for (int axis = 0; axis < 3 && matches; ++axis)
        matches = std::fabs(step[axis] - voxel_size) <= tolerance
                  && std::fabs(centre[axis] - (origin[axis] + 0.5 * voxel_size))
                         <= tolerance + 1e-12 * std::fabs(origin[axis]);
    if (!matches)
        return host->fail(error, GB_ERROR_FORMAT,
                       "%s: grid '%s': transform does not match voxel_size and world_origin",
                       path, name);
    *frame = read;
    return GB_OK;
}

bool same_frame(const gb_voxel_grid *a, const gb_voxel_grid *b)
{
    return a->size[0] == b->size[0] && a->size[1] == b->size[1] && a->size[2] == b->size[2]
           && a->voxel_size == b->voxel_size && a->world_origin[0] == b->world_origin[0]
           && a->world_origin[1] == b->world_origin[1]
           && a->world_origin[2] == b->world_origin[2] && a->scene_hash == b->scene_hash
           && a->resolution == b->resolution;
}

// ------------------------------------------------------- dense to sparse

// Calls visit(leaf, offset, index) for every voxel of the frame in the
// leaf-sized block at block_origin, where index is the dense index.
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

// Builds a tree whose active voxels are those where active(index) holds,
// with value(index); blocks with no active voxel get no leaf. Slab of 8
// layers by slab, leaves filled in parallel, then added in order (the tree
// does not depend on it); after each slab, released(begin, end) is told
// the dense indices it is done with.
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

// The three grids of the voxel file.
struct VoxelGrids {
    openvdb::BoolGrid::Ptr surface;
    openvdb::MaskGrid::Ptr empty;
    openvdb::FloatGrid::Ptr distance;
};

// The leaves of one 8^3 block of the three grids (null where a grid has no
// active voxel in the block).
struct BlockLeaves {
    openvdb::BoolGrid::TreeType::LeafNodeType *surface = nullptr;
    openvdb::MaskGrid::TreeType::LeafNodeType *empty = nullptr;
    openvdb::FloatGrid::TreeType::LeafNodeType *distance = nullptr;
};

BlockLeaves make_block_leaves(const gb_voxel_grid *grid, const openvdb::Coord &origin)
{
    using FloatLeaf = openvdb::FloatGrid::TreeType::LeafNodeType;
    openvdb::util::NodeMask<3> surface_mask, empty_mask;
    float values[FloatLeaf::SIZE] = {0};
    for_each_block_voxel(grid, origin, [&](openvdb::Index offset, size_t index) {
        if (grid->surface[index]) {
            surface_mask.setOn(offset);
        } else {
            empty_mask.setOn(offset);
            values[offset] = grid->distance[index];
        }
    });
    BlockLeaves leaves;
    if (!surface_mask.isOff()) {
        leaves.surface = new openvdb::BoolGrid::TreeType::LeafNodeType(origin, false, false);
        for (auto on = surface_mask.beginOn(); on; ++on)
            leaves.surface->setValueOn(on.pos(), true);
    }
    if (!empty_mask.isOff()) {
        leaves.empty = new openvdb::MaskGrid::TreeType::LeafNodeType(origin, false, false);
        leaves.empty->setValueMask(empty_mask);
        // Partial: the buffer is allocated by data(), not filled twice.
        leaves.distance = new FloatLeaf(openvdb::PartialCreate(), origin, 0.0f, false);
        std::memcpy(leaves.distance->buffer().data(), values, sizeof values);
        leaves.distance->setValueMask(empty_mask);
    }
    return leaves;
}


// Gives the whole memory pages inside [begin, end) back to the system: they
// read as zeros afterwards. Used only on arrays about to be freed, never on
// bytes outside them (so not on an allocator's own headers).
void release_pages(const void *begin, const void *end)
{
    uintptr_t page = (uintptr_t)sysconf(_SC_PAGESIZE);
    uintptr_t first = ((uintptr_t)begin + page - 1) / page * page;
    uintptr_t last = (uintptr_t)end / page * page;
    if (first < last)
        madvise((void *)first, last - first, MADV_DONTNEED);
}

// The grids "surface", "empty" and "distance" of grid in one pass over its
// voxels, slab of 8 layers by slab: leaves filled in parallel, then added in
// order (the trees do not depend on it); fully active leaves of the bool and
// mask trees become tiles. With release, the dense arrays' pages of each slab
// are given back once its leaves are built, so that the sparse grids replace
// the dense ones in memory instead of adding to them.
VoxelGrids build_voxel_grids(const gb_voxel_grid *grid, bool release)
{
    const int blocks_x = (grid->size[0] + 7) / 8, blocks_y = (grid->size[1] + 7) / 8;
    const size_t slab_blocks = (size_t)blocks_x * blocks_y;
    const size_t layer = (size_t)grid->size[0] * grid->size[1];
    VoxelGrids grids{openvdb::BoolGrid::create(false), openvdb::MaskGrid::create(false),
                     openvdb::FloatGrid::create(0.0f)};
    std::vector<BlockLeaves> leaves(slab_blocks);
    for (int z = 0; z < grid->size[2]; z += 8) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, slab_blocks),
                          [&](const tbb::blocked_range<size_t> &range) {
            for (size_t b = range.begin(); b != range.end(); ++b)
                leaves[b] = make_block_leaves(grid, openvdb::Coord((int)(b % blocks_x) * 8,
                                                                   (int)(b / blocks_x) * 8, z));
        });
        for (const BlockLeaves &block : leaves) {
            if (block.surface)
                grids.surface->tree().addLeaf(block.surface);
            if (block.empty)
                grids.empty->tree().addLeaf(block.empty);
            if (block.distance)
                grids.distance->tree().addLeaf(block.distance);
        }
        if (release) {
            size_t begin = layer * z, end = layer * std::min(z + 8, grid->size[2]);
            release_pages(grid->surface + begin, grid->surface + end);
            release_pages(grid->distance + begin, grid->distance + end);
        }
    }
    openvdb::tools::prune(grids.surface->tree());
    openvdb::tools::prune(grids.empty->tree());
    return grids;
}

// ------------------------------------------------------- sparse to dense

// Calls visit(index, value) for every active voxel and every voxel of every
// active tile; returns false (without visiting further) at the first one
// outside the frame. The tiles above the leaves are walked by the tree's
// value iterator, the leaves one by one, each voxel found by its offset in
// the leaf (x * 64 + y * 8 + z). The value iterator alone made a box and a
// bounds test per voxel: gb_voxel_grid_read_surface of the Cornell box at
// 512 (132 M empty voxels) took 4.5-4.7 s with it, 3.6 s without.
template <typename GridType, typename Visit>
bool for_each_active_voxel(const GridType &grid, const gb_voxel_grid *frame, Visit visit)
{
    openvdb::CoordBBox frame_box(openvdb::Coord(0, 0, 0),
                                 openvdb::Coord(frame->size[0] - 1, frame->size[1] - 1,
                                                frame->size[2] - 1));
    auto tile = grid.cbeginValueOn();
    tile.setMaxDepth(decltype(tile)::LEAF_DEPTH - 1);
    for (; tile; ++tile) {
        openvdb::CoordBBox box;
        tile.getBoundingBox(box);
        if (!frame_box.isInside(box))
            return false;
        for (int k = box.min().z(); k <= box.max().z(); ++k)
            for (int j = box.min().y(); j <= box.max().y(); ++j)
                for (int i = box.min().x(); i <= box.max().x(); ++i)
                    visit(gb_voxel_index(frame, i, j, k), *tile);
    }
    for (auto leaf = grid.tree().cbeginLeaf(); leaf; ++leaf) {
        const openvdb::Coord origin = leaf->origin();
        bool whole = frame_box.isInside(leaf->getNodeBoundingBox());
        for (auto voxel = leaf->cbeginValueOn(); voxel; ++voxel) {
            openvdb::Index n = voxel.pos();
            int i = origin.x() + (int)(n >> 6), j = origin.y() + (int)((n >> 3) & 7),
                k = origin.z() + (int)(n & 7);
            if (!whole && !frame_box.isInside(openvdb::Coord(i, j, k)))
                return false;
            visit(gb_voxel_index(frame, i, j, k), *voxel);
        }
    }
    return true;
}

// ------------------------------------------------------- files

// Blosc (fast, and OpenVDB's own default) when this OpenVDB has it, else zip.
uint32_t compression()
{
    return openvdb::io::COMPRESS_ACTIVE_MASK
           | (openvdb::io::Archive::hasBloscCompression() ? openvdb::io::COMPRESS_BLOSC
                                                          : openvdb::io::COMPRESS_ZIP);
}

// OpenVDB writes a random UUID in the file header: 36 ASCII characters at
// bytes 21..56, after the magic (8 bytes), the file format version and the
// library's major and minor versions (u32 each) and the grid-offsets flag (1
// byte). gibake writes there instead a UUID made from every other byte of the
// file and its length (FORMATS.md, "Voxel file", "Checksum"): the same grids
// then give the same bytes, and the UUID is the checksum that readers verify
// before OpenVDB parses anything.
const size_t UUID_OFFSET = 8 + 4 + 4 + 4 + 1;
const size_t UUID_LENGTH = 36;
const size_t HEADER_BYTES = UUID_OFFSET + UUID_LENGTH;
const size_t VERSION_CHARACTER = 14;   // the UUID's version digit
const size_t READ_CHUNK = 1 << 20;

bool looks_like_uuid(const unsigned char *text)
{
    for (size_t i = 0; i < UUID_LENGTH; ++i) {
        bool dash = i == 8 || i == 13 || i == 18 || i == 23;
        if (dash ? text[i] != '-' : !std::isxdigit(text[i]))
            return false;
    }
    return true;
}

// Two 64-bit lanes; each 8-byte little-endian word w of the bytes added (the
// last one zero-padded) goes in as lane = (lane ^ w) * m, lane ^= lane >> 29.
class ContentHash {
public:
    void add(const unsigned char *bytes, size_t size)
    {
        size_t i = 0;
        for (; i < size && count_ != 0; ++i)
            take(bytes[i]);
        for (; i + 8 <= size; i += 8) {
            uint64_t word = 0;
            for (int b = 7; b >= 0; --b)
                word = word << 8 | bytes[i + b];
            mix(word);
        }
        for (; i < size; ++i)
            take(bytes[i]);
    }

    // Format 2 (UUID version 8): the file's length in bytes is one more word.
    // Format 1 (version 4, gibake before format 2) had no length word.
    std::string uuid(int format, uint64_t length)
    {
        if (count_ != 0)
            mix(pending_);
        pending_ = 0;
        count_ = 0;
        if (format >= 2)
            mix(length);
        unsigned version = format >= 2 ? 0x8000 : 0x4000;
        char text[UUID_LENGTH + 1];
        std::snprintf(text, sizeof text, "%08x-%04x-%04x-%04x-%012llx",
                      (unsigned)(lane_[0] >> 32), (unsigned)(lane_[0] >> 16 & 0xffff),
                      (unsigned)(version | (lane_[0] & 0x0fff)),
                      (unsigned)(0x8000 | (lane_[1] >> 48 & 0x3fff)),
                      (unsigned long long)(lane_[1] & 0xffffffffffffull));
        return text;
    }

private:
    void take(unsigned char byte)
    {
        pending_ |= (uint64_t)byte << (8 * count_);
        if (++count_ == 8) {
            mix(pending_);
            pending_ = 0;
            count_ = 0;
        }
    }

    void mix(uint64_t word)
    {
        static const uint64_t multiplier[2] = {0xc4ceb9fe1a85ec53ull, 0xff51afd7ed558ccdull};
        for (int l = 0; l < 2; ++l) {
            lane_[l] = (lane_[l] ^ word) * multiplier[l];
            lane_[l] ^= lane_[l] >> 29;
        }
    }

    uint64_t lane_[2] = {0x9e3779b97f4a7c15ull, 0xc2b2ae3d27d4eb4full};
    uint64_t pending_ = 0;
    int count_ = 0;
};

// The checksums of the file open as fd (header already in header): format 2
// over bytes 0..20, 57.. and the length; format 1 over bytes 57.. only.
// False on a read error (errno set).
bool content_uuids(int fd, const unsigned char *header, std::string *format2,
                   std::string *format1)
{
    ContentHash current, older;
    current.add(header, UUID_OFFSET);
    std::vector<unsigned char> buffer(READ_CHUNK);
    uint64_t length = HEADER_BYTES;
    for (;;) {
        ssize_t got = pread(fd, buffer.data(), buffer.size(), (off_t)length);
        if (got < 0 && errno == EINTR)
            continue;
        if (got < 0)
            return false;
        if (got == 0)
            break;
        current.add(buffer.data(), (size_t)got);
        if (format1)
            older.add(buffer.data(), (size_t)got);
        length += (uint64_t)got;
    }
    *format2 = current.uuid(2, length);
    if (format1)
        *format1 = older.uuid(1, length);
    return true;
}

bool read_header(int fd, unsigned char header[HEADER_BYTES], size_t *got)
{
    *got = 0;
    while (*got < HEADER_BYTES) {
        ssize_t n = pread(fd, header + *got, HEADER_BYTES - *got, (off_t)*got);
        if (n < 0 && errno == EINTR)
            continue;
        if (n < 0)
            return false;
        if (n == 0)
            break;
        *got += (size_t)n;
    }
    return true;
}

// Rewrites the UUID of the file name (just written for path) as its checksum.
gb_result write_content_uuid(const char *path, const char *name, gb_error *error)
{
    int fd = open(name, O_RDWR | O_CLOEXEC);
    if (fd < 0)
        return host->fail(error, GB_ERROR_IO, "%s: cannot reopen %s: %s", path, name,
                       std::strerror(errno));
    unsigned char header[HEADER_BYTES];
    size_t got = 0;
    std::string uuid;
    gb_result result = GB_OK;
    if (!read_header(fd, header, &got) || !content_uuids(fd, header, &uuid, nullptr))
        result = host->fail(error, GB_ERROR_IO, "%s: cannot read back: %s", path,
                         std::strerror(errno));
    else if (got != HEADER_BYTES || !looks_like_uuid(header + UUID_OFFSET))
        result = host->fail(error, GB_ERROR_IO, "%s: OpenVDB wrote no UUID at bytes 21..56", path);
    else if (pwrite(fd, uuid.data(), UUID_LENGTH, (off_t)UUID_OFFSET) != (ssize_t)UUID_LENGTH)
        result = host->fail(error, GB_ERROR_IO, "%s: cannot write the checksum: %s", path,
                         std::strerror(errno));
    if (close(fd) != 0 && result == GB_OK)
        result = host->fail(error, GB_ERROR_IO, "%s: cannot write: %s", path, std::strerror(errno));
    return result;
}

// Checks the magic, then the content UUID, of path.
gb_result check_file(const char *path, gb_error *error)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        return host->fail(error, GB_ERROR_IO, "%s: %s", path, std::strerror(errno));
    unsigned char header[HEADER_BYTES];
    size_t got = 0;
    // OPENVDB_MAGIC as a little-endian int64.
    const unsigned char magic[8] = {0x20, 0x42, 0x44, 0x56, 0, 0, 0, 0};
    std::string uuid, format1;
    gb_result result = GB_OK;
    const char *damaged = "%s: checksum does not match: the file is damaged or was not "
                          "written by gibake";
    if (!read_header(fd, header, &got))
        result = host->fail(error, GB_ERROR_IO, "%s: %s", path, std::strerror(errno));
    else if (got < sizeof magic || std::memcmp(header, magic, sizeof magic) != 0)
        result = host->fail(error, GB_ERROR_FORMAT, "%s: not an OpenVDB file", path);
    else if (got != HEADER_BYTES || !looks_like_uuid(header + UUID_OFFSET))
        result = host->fail(error, GB_ERROR_CHECKSUM, damaged, path);
    else if (!content_uuids(fd, header, &uuid, &format1))
        result = host->fail(error, GB_ERROR_IO, "%s: %s", path, std::strerror(errno));
    else if (uuid.compare(0, UUID_LENGTH, (const char *)header + UUID_OFFSET, UUID_LENGTH) == 0)
        result = GB_OK;
    else if (header[UUID_OFFSET + VERSION_CHARACTER] == '4'
             && format1.compare(0, UUID_LENGTH, (const char *)header + UUID_OFFSET,
                                UUID_LENGTH) == 0)
        result = host->fail(error, GB_ERROR_UNSUPPORTED,
                         "%s: written by an older gibake (voxel file format 1, whose "
                         "checksum left out the header and the length): make it again "
                         "(voxelize, or thin for a .grid.vdb)",
                         path);
    else
        result = host->fail(error, GB_ERROR_CHECKSUM, damaged, path);
    close(fd);
    return result;
}

// io::File::write never looks at its std::ofstream after writing, so a full
// disk gave a truncated file and exit 0: the grids go through io::Archive's
// own writer into a stream that is checked here.
class CheckedArchive : public openvdb::io::Archive {
public:
    void write_to(std::ostream &stream, const openvdb::GridPtrVec &grids) const
    {
        openvdb::io::Archive::write(stream, grids, /*seekable=*/true);
    }
};

gb_result write_archive(const char *path, const char *name, const openvdb::GridPtrVec &grids,
                        gb_error *error)
{
    std::ofstream stream(name, std::ios_base::out | std::ios_base::binary
                                   | std::ios_base::trunc);
    if (!stream)
        return host->fail(error, GB_ERROR_IO, "%s: cannot open %s: %s", path, name,
                       std::strerror(errno));
    CheckedArchive archive;
    archive.setCompression(compression());
    errno = 0;
    archive.write_to(stream, grids);
    stream.close();
    // the failed write(2) left its errno (ENOSPC, EFBIG, ...): the stream makes
    // no other system call once it has failed
    if (stream.fail())
        return host->fail(error, GB_ERROR_IO, "%s: cannot write: %s", path,
                       errno ? std::strerror(errno) : "output stream error");
    return GB_OK;
}

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

// Opens path through the one output writer (output_file.h), then builds the
// grids (make_grids()), writes them and the checksum into its file, and
// commits: on failure nothing is left beside path and an older file there is
// kept; a device or FIFO gets the bytes copied from a temporary in $TMPDIR.
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

// An open OpenVDB file, from which grids are read by name and type.
// A read-only std::streambuf over the mapped file, seekable as OpenVDB's
// stream reader wants.
class MappedBuffer : public std::streambuf {
public:
    MappedBuffer(const void *bytes, size_t size)
    {
        char *begin = static_cast<char *>(const_cast<void *>(bytes));
        setg(begin, begin, begin + size);
    }

protected:
    pos_type seekoff(off_type offset, std::ios_base::seekdir way,
                     std::ios_base::openmode which) override
    {
        off_type base = way == std::ios_base::beg ? 0
                        : way == std::ios_base::cur ? gptr() - eback() : egptr() - eback();
        return seekpos(pos_type(base + offset), which);
    }
    pos_type seekpos(pos_type position, std::ios_base::openmode which) override
    {
        off_type at = off_type(position);
        if (!(which & std::ios_base::in) || at < 0 || at > egptr() - eback())
            return pos_type(off_type(-1));
        setg(eback(), eback() + at, egptr());
        return position;
    }
};

// The grids of an OpenVDB file, read by name and type. After the checksum,
// the file is mapped, walked by gb_voxel_file_check (voxel_check.h: every
// size and count OpenVDB will allocate or copy by is checked against the
// file), and OpenVDB reads it through io::Stream from a std::istream that
// throws on a read past its end, so that no count OpenVDB trusts can make
// it go on reading zeros at the end of a damaged file.
struct Reader {
    const char *path;
    void *mapping = MAP_FAILED;
    size_t size = 0;
    openvdb::GridPtrVecPtr grids;

    explicit Reader(const char *path_) : path(path_) {}

    gb_result open(gb_error *error)
    {
        gb_result result = check_file(path, error);
        if (result == GB_OK)
            result = map(error);
        if (result == GB_OK)
            result = host->file_check(mapping, size, path, error);
        if (result != GB_OK)
            return result;
        MappedBuffer buffer(mapping, size);
        std::istream in(&buffer);
        in.exceptions(std::ios_base::failbit | std::ios_base::badbit);
        try {
            openvdb::io::Stream stream(in, /*delayLoad=*/false);
            grids = stream.getGrids();
        } catch (const std::ios_base::failure &) {
            return host->fail(error, GB_ERROR_FORMAT, "%s: OpenVDB reads past the end of the file "
                           "(a size or a count in it is wrong)", path);
        } catch (const std::bad_alloc &) {
            return host->fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
        } catch (const std::exception &e) {
            return host->fail(error, GB_ERROR_FORMAT, "%s: %s", path, e.what());
        }
        if (!grids)
            return host->fail(error, GB_ERROR_FORMAT, "%s: no grids", path);
        return GB_OK;
    }

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
            return host->fail(error, GB_ERROR_FORMAT, "%s: grid '%s' is not a %s grid", path, name,
                           type_name);
        return GB_OK;
    }

    ~Reader()
    {
        grids.reset();
        if (mapping != MAP_FAILED)
            munmap(mapping, size);
    }

private:
    gb_result map(gb_error *error)
    {
        int fd = ::open(path, O_RDONLY | O_CLOEXEC);
        struct stat status;
        if (fd < 0 || fstat(fd, &status) != 0) {
            int saved = errno;
            if (fd >= 0)
                close(fd);
            return host->fail(error, GB_ERROR_IO, "%s: %s", path, std::strerror(saved));
        }
        size = (size_t)status.st_size;
        mapping = size ? mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0) : MAP_FAILED;
        int saved = errno;
        close(fd);
        if (mapping == MAP_FAILED)
            return host->fail(error, GB_ERROR_IO, "%s: %s", path,
                           size ? std::strerror(saved) : "empty file");
        return GB_OK;
    }
};

gb_result check_same_frame(const char *path, const openvdb::GridBase &grid,
                           const gb_voxel_grid *expected, gb_error *error)
{
    gb_voxel_grid frame;
    gb_result result = read_frame(path, grid, &frame, error);
    if (result == GB_OK && !same_frame(&frame, expected))
        result = host->fail(error, GB_ERROR_FORMAT,
                         "%s: grid '%s' has another frame than grid 'surface'", path,
                         grid.getName().c_str());
    return result;
}

gb_result outside_frame(const char *path, const char *name, gb_error *error)
{
    return host->fail(error, GB_ERROR_FORMAT, "%s: grid '%s' has voxels outside its grid_size",
                   path, name);
}

// Fills grid->surface from the "surface" grid, then checks that "empty" is
// its complement and that "distance" is active exactly on "empty", finite and
// non-negative, and fills grid->distance from it (with_distance) or leaves
// it NULL.
gb_result read_voxel_grids(const char *path, Reader &reader, bool with_distance,
                           gb_voxel_grid *grid, gb_error *error)
{
    openvdb::BoolGrid::Ptr surface;
    openvdb::MaskGrid::Ptr empty;
    openvdb::FloatGrid::Ptr distance;
    gb_result result = reader.read<openvdb::BoolGrid>("surface", "bool", &surface, error);
    if (result == GB_OK)
        result = reader.read<openvdb::MaskGrid>("empty", "mask", &empty, error);
    if (result == GB_OK)
        result = reader.read<openvdb::FloatGrid>("distance", "float", &distance, error);
    gb_voxel_grid frame;
    if (result == GB_OK)
        result = read_frame(path, *surface, &frame, error);
    if (result == GB_OK)
        result = check_same_frame(path, *empty, &frame, error);
    if (result == GB_OK)
        result = check_same_frame(path, *distance, &frame, error);
    if (result == GB_OK) {
        int32_t size[3] = {frame.size[0], frame.size[1], frame.size[2]};
        gb_error reason;
        result = host->allocate(&frame, size, &reason);
        if (result != GB_OK)
            host->fail(error, result, "%s: %s", path, reason.message);
    }
    if (result != GB_OK)
        return result;
    if (!with_distance) {
        // never touched, so never resident: calloc's pages stay unmapped
        std::free(frame.distance);
        frame.distance = nullptr;
    }

    uint8_t *occupied = frame.surface;
    float *value = frame.distance;
    size_t surface_count = 0, empty_count = 0, distance_count = 0;
    bool inside = for_each_active_voxel(*surface, &frame, [&](size_t index, bool) {
        surface_count += !occupied[index];
        occupied[index] = 1;
    });
    if (!inside) {
        host->free(&frame);
        return outside_frame(path, "surface", error);
    }
    bool disjoint = true, finite = true;
    inside = for_each_active_voxel(*empty, &frame, [&](size_t index, bool) {
        disjoint &= !occupied[index];
        ++empty_count;
    });
    inside = inside && for_each_active_voxel(*distance, &frame, [&](size_t index, float d) {
        disjoint &= !occupied[index];
        finite &= std::isfinite(d) && d >= 0;
        if (value)
            value[index] = d;
        ++distance_count;
    });
    size_t total = frame_voxel_count(&frame);
    if (!inside)
        result = outside_frame(path, "empty or distance", error);
    else if (!disjoint || surface_count + empty_count != total || empty_count != distance_count)
        result = host->fail(error, GB_ERROR_FORMAT,
                         "%s: grids 'empty' and 'distance' are not the complement of 'surface'",
                         path);
    else if (!finite)
        result = host->fail(error, GB_ERROR_FORMAT,
                         "%s: grid 'distance' has a negative or non-finite value", path);
    if (result != GB_OK) {
        host->free(&frame);
        return result;
    }
    *grid = frame;
    return GB_OK;
}

} // namespace

namespace {

gb_result write_voxel_grids(const char *path, const gb_voxel_grid *grid, bool release,
                            gb_error *error)
{
    if (!path || !grid || !grid->surface || !grid->distance || !frame_is_valid(grid))
        return host->fail(error, GB_ERROR_ARGUMENT, "%s: voxel grid to write is not valid",
                       path ? path : "(null)");
    try {
        initialize_openvdb();
        return write_grids(path, [&] {
            VoxelGrids built = build_voxel_grids(grid, release);
            attach_frame(*built.surface, grid, "surface", VOXELIZE_CREATOR);
            attach_frame(*built.empty, grid, "empty", VOXELIZE_CREATOR);
            attach_frame(*built.distance, grid, "distance", VOXELIZE_CREATOR);
            built.distance->setGridClass(openvdb::GRID_UNKNOWN);
            built.distance->setSaveFloatAsHalf(false);
            return openvdb::GridPtrVec{built.surface, built.empty, built.distance};
        }, error);
    } catch (const std::bad_alloc &) {
        return host->fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    } catch (const std::exception &e) {
        return host->fail(error, GB_ERROR_IO, "%s: %s", path, e.what());
    }
}

gb_result write(const char *path, const gb_voxel_grid *grid, gb_error *error)
{
    return write_voxel_grids(path, grid, false, error);
}

gb_result write_and_free(const char *path, gb_voxel_grid *grid, gb_error *error)
{
    gb_result result = write_voxel_grids(path, grid, true, error);
    host->free(grid);
    return result;
}

gb_result read(const char *path, gb_voxel_grid *grid, int with_distance, gb_error *error)
{
    if (!path || !grid)
        return host->fail(error, GB_ERROR_ARGUMENT, "voxel grid read: no path or no grid");
    try {
        initialize_openvdb();
        Reader reader(path);
        gb_result result = reader.open(error);
        if (result != GB_OK)
            return result;
        return read_voxel_grids(path, reader, with_distance != 0, grid, error);
    } catch (const std::bad_alloc &) {
        return host->fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    } catch (const std::exception &e) {
        return host->fail(error, GB_ERROR_FORMAT, "%s: %s", path, e.what());
    }
}

// The values of grid "distance" at count dense indices of frame (0 where
// the grid is inactive: a surface voxel), the file's frame checked against
// frame's.
gb_result read_distances(const char *path, const gb_voxel_grid *frame, const size_t *voxels,
                         size_t count, float *distances, gb_error *error)
{
    if (!path || !frame || (count && (!voxels || !distances)))
        return host->fail(error, GB_ERROR_ARGUMENT, "voxel distances read: missing argument");
    try {
        initialize_openvdb();
        Reader reader(path);
        openvdb::FloatGrid::Ptr grid;
        gb_result result = reader.open(error);
        if (result == GB_OK)
            result = reader.read<openvdb::FloatGrid>("distance", "float", &grid, error);
        if (result == GB_OK)
            result = check_same_frame(path, *grid, frame, error);
        if (result != GB_OK)
            return result;
        const size_t nx = (size_t)frame->size[0], ny = (size_t)frame->size[1];
        const size_t total = frame_voxel_count(frame);
        // the tree's own lookups, not an accessor: a handful of voxels, and
        // an accessor registers in a TBB hash map that UBSan faults
        const openvdb::FloatTree &tree = grid->tree();
        for (size_t n = 0; n < count; ++n) {
            size_t v = voxels[n];
            if (v >= total)
                return host->fail(error, GB_ERROR_ARGUMENT,
                                  "%s: voxel %zu is outside the grid", path, v);
            openvdb::Coord ijk((int)(v % nx), (int)(v / nx % ny), (int)(v / nx / ny));
            float d = tree.isValueOn(ijk) ? tree.getValue(ijk) : 0.0f;
            if (!std::isfinite(d) || d < 0)
                return host->fail(error, GB_ERROR_FORMAT,
                                  "%s: grid 'distance' has a negative or non-finite value", path);
            distances[n] = d;
        }
        return GB_OK;
    } catch (const std::bad_alloc &) {
        return host->fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    } catch (const std::exception &e) {
        return host->fail(error, GB_ERROR_FORMAT, "%s: %s", path, e.what());
    }
}

// With release, the pages of values are given back slab by slab as the
// tree takes them over (values is then to be freed, not read).
gb_result write_int32_grid(const char *path, const gb_voxel_grid *frame, const char *name,
                           const int32_t *values, bool release, gb_error *error)
{
    if (!path || !frame || !name || !*name || !values || !frame_is_valid(frame))
        return host->fail(error, GB_ERROR_ARGUMENT, "%s: int32 grid to write is not valid",
                       path ? path : "(null)");
    try {
        initialize_openvdb();
        return write_grids(path, [&] {
            auto grid = dense_to_grid<openvdb::Int32Grid>(
                frame, -1, [=](size_t index) { return values[index] >= 0; },
                [=](size_t index) { return values[index]; },
                [=](size_t begin, size_t end) {
                    if (release)
                        release_pages(values + begin, values + end);
                });
            attach_frame(*grid, frame, name, INT32_CREATOR);
            return openvdb::GridPtrVec{grid};
        }, error);
    } catch (const std::bad_alloc &) {
        return host->fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    } catch (const std::exception &e) {
        return host->fail(error, GB_ERROR_IO, "%s: %s", path, e.what());
    }
}

gb_result write_int32(const char *path, const gb_voxel_grid *frame, const char *name,
                      const int32_t *values, gb_error *error)
{
    return write_int32_grid(path, frame, name, values, false, error);
}

gb_result write_int32_and_free(const char *path, const gb_voxel_grid *frame, const char *name,
                               int32_t *values, gb_error *error)
{
    gb_result result = write_int32_grid(path, frame, name, values, true, error);
    std::free(values);
    return result;
}

gb_result read_int32(const char *path, const char *name, gb_voxel_grid *frame,
                     int32_t **values, gb_error *error)
{
    if (!path || !name || !frame || !values)
        return host->fail(error, GB_ERROR_ARGUMENT, "int32 grid read: missing argument");
    try {
        initialize_openvdb();
        Reader reader(path);
        openvdb::Int32Grid::Ptr grid;
        gb_voxel_grid read;
        gb_result result = reader.open(error);
        if (result == GB_OK)
            result = reader.read<openvdb::Int32Grid>(name, "int32", &grid, error);
        if (result == GB_OK)
            result = read_frame(path, *grid, &read, error);
        if (result != GB_OK)
            return result;
        size_t count = frame_voxel_count(&read);
        int32_t *dense = (int32_t *)std::malloc(count * sizeof *dense);
        if (!dense)
            return host->fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory for %zu voxels",
                           path, count);
        for (size_t index = 0; index < count; ++index)
            dense[index] = -1;
        bool negative = false;
        bool inside = for_each_active_voxel(*grid, &read, [&](size_t index, int32_t value) {
            negative |= value < 0;
            dense[index] = value;
        });
        if (!inside || negative) {
            std::free(dense);
            return inside ? host->fail(error, GB_ERROR_FORMAT,
                                    "%s: grid '%s' has a negative active value", path, name)
                          : outside_frame(path, name, error);
        }
        *frame = read;
        *values = dense;
        return GB_OK;
    } catch (const std::bad_alloc &) {
        return host->fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    } catch (const std::exception &e) {
        return host->fail(error, GB_ERROR_FORMAT, "%s: %s", path, e.what());
    }
}

int file_checksum(const void *bytes, size_t size, char uuid[37])
{
    if (!bytes || size < HEADER_BYTES)
        return 0;
    const unsigned char *file = static_cast<const unsigned char *>(bytes);
    ContentHash hash;
    hash.add(file, UUID_OFFSET);
    hash.add(file + HEADER_BYTES, size - HEADER_BYTES);
    std::memcpy(uuid, hash.uuid(2, size).c_str(), UUID_LENGTH + 1);
    return 1;
}

const gb_voxel_grid_adapter adapter = {write,       write_and_free,       read,
                                       read_distances, write_int32, write_int32_and_free,
                                       read_int32,  file_checksum};

} // namespace

// The entry (adapter.h): host is a gb_voxel_grid_host, the result a
// gb_voxel_grid_adapter.
extern "C" __attribute__((visibility("default"))) const void *
gb_openvdb_adapter(const void *given)
{
    host = static_cast<const gb_voxel_grid_host *>(given);
    return &adapter;
}
