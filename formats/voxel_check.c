/* voxel_check.c — an OpenVDB 10 file walked the way io::Stream reads it,
 * every size checked before OpenVDB allocates or copies by it (see
 * voxel_check.h). References are to OpenVDB 10's headers: io/Compression.h
 * (readCompressedValues, readData), tree/RootNode.h, InternalNode.h,
 * LeafNode*.h (readTopology, readBuffers), Metadata.h, math/Maps.h. */
#include "voxel_check.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "array_reserve.h"

enum {
    FILE_VERSION = 224,
    COMPRESS_ZIP = 0x1,
    COMPRESS_ACTIVE_MASK = 0x2,
    COMPRESS_BLOSC = 0x4,
    ROOT_CHILD_DIM = 4096,      /* 2^(5+4+3): the span of a root entry */
    N5_VALUES = 32768, N5_MASK = 4096,
    N4_VALUES = 4096, N4_MASK = 512,
    LEAF_VALUES = 512, LEAF_MASK = 64,
};

/* readCompressedValues' metadata byte. */
enum { NO_MASK_AND_ONE_INACTIVE_VAL = 2, MASK_AND_NO_INACTIVE_VALS = 3,
       MASK_AND_ONE_INACTIVE_VAL = 4, MASK_AND_TWO_INACTIVE_VALS = 5, NO_MASK_AND_ALL_VALS = 6 };

typedef enum leaf_kind { LEAF_OF_VALUES, LEAF_OF_BOOLS, LEAF_OF_MASK } leaf_kind;

typedef struct root_child {
    int32_t origin[3];
    const unsigned char *child_mask;    /* of its InternalNode<5> */
    size_t first_n4;                    /* index in walk.n4_masks */
} root_child;

typedef struct walk {
    const unsigned char *begin, *at, *end;
    const char *path;
    gb_error *error;
    const char *grid;                   /* the grid's name, for messages */
    char grid_name[65];
    uint32_t compression;
    int value_size, is_bool;
    leaf_kind leaf;
    root_child *children;
    size_t child_count;
    int32_t (*origins)[3];              /* tiles and children of the root */
    size_t origin_count;
    const unsigned char **n4_masks;     /* child masks of the InternalNode<4>s, in order */
    size_t n4_count, n4_capacity;
} walk;

static uint32_t get_u32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static uint64_t get_u64(const unsigned char *p)
{
    return get_u32(p) | (uint64_t)get_u32(p + 4) << 32;
}

static size_t left(const walk *w)
{
    return (size_t)(w->end - w->at);
}

static gb_result fail(walk *w, gb_result result, const char *what)
{
    if (w->grid)
        return gb_fail(w->error, result, "%s: grid '%.64s': %s", w->path, w->grid, what);
    return gb_fail(w->error, result, "%s: %s", w->path, what);
}

/* The next n bytes, or NULL (and the message) when the file ends first. */
static const unsigned char *take(walk *w, size_t n, const char *what, gb_result *result)
{
    if (left(w) < n) {
        char message[160];
        snprintf(message, sizeof message, "the file ends inside %s", what);
        *result = fail(w, GB_ERROR_FORMAT, message);
        return NULL;
    }
    const unsigned char *p = w->at;
    w->at += n;
    return p;
}

/* readString: a u32 length, then the bytes. */
static gb_result read_string(walk *w, const char *what, const unsigned char **text,
                             uint32_t *length)
{
    gb_result result = GB_OK;
    const unsigned char *p = take(w, 4, what, &result);
    if (p && (*length = get_u32(p), *text = take(w, *length, what, &result)))
        return GB_OK;
    return result;
}

static int string_is(const unsigned char *text, uint32_t length, const char *word)
{
    return length == strlen(word) && memcmp(text, word, length) == 0;
}

static gb_result check_bools(walk *w, const unsigned char *bytes, size_t n, const char *what)
{
    for (size_t i = 0; i < n; ++i)
        if (bytes[i] > 1) {
            char message[160];
            snprintf(message, sizeof message, "%s: a bool of value %u", what, bytes[i]);
            return fail(w, GB_ERROR_FORMAT, message);
        }
    return GB_OK;
}

/* ---- metadata (MetaMap::readMeta, Metadata::read) --------------------------- */

/* TypedMetadata<T>::readValue reads sizeof(T) bytes whatever the size says. */
static const struct {
    const char *name;
    uint32_t size;
} typed_metadata[] = {
    {"bool", 1},   {"int32", 4},  {"int64", 8},  {"float", 4},  {"double", 8},
    {"vec2i", 8},  {"vec2s", 8},  {"vec2d", 16}, {"vec3i", 12}, {"vec3s", 12},
    {"vec3d", 24}, {"vec4i", 16}, {"vec4s", 16}, {"vec4d", 32}, {"mat4s", 64},
    {"mat4d", 128},
};

/* A Blosc chunk (16-byte header: nbytes at 4, cbytes at 12) of n bytes
 * that decompresses to expected bytes. */
static int blosc_chunk_fits(const unsigned char *chunk, uint64_t n, uint64_t expected)
{
    return n >= 16 && get_u32(chunk + 4) == expected && get_u32(chunk + 12) == n;
}

/* DelayedLoadMetadata::readValue: count, then a mask of count bytes and
 * the compressed sizes (count int64s), each Blosc-compressed (a u32 size
 * > 0) or raw (size 0); 0xffffffff: no compressed sizes. */
static gb_result delayed_load_value(walk *w, const unsigned char *value, uint32_t size)
{
    const unsigned char *at = value, *end = value + size;
    if (size == 0)
        return GB_OK;
    if (end - at < 8)
        return fail(w, GB_ERROR_FORMAT, "delayed-load metadata is truncated");
    uint64_t count = get_u32(at), bytes = get_u32(at + 4);
    at += 8;
    if (count > (uint64_t)(w->end - w->begin))
        return fail(w, GB_ERROR_FORMAT, "delayed-load metadata counts more leaves than the "
                    "file holds");
    for (int part = 0; part < 2; ++part) {
        uint64_t element = part == 0 ? 1 : 8;
        if (part == 1) {
            if (end - at < 4)
                return fail(w, GB_ERROR_FORMAT, "delayed-load metadata is truncated");
            bytes = get_u32(at);
            at += 4;
            if (bytes == 0xffffffffu)
                break;
        }
        /* OpenVDB's bloscCompress pads what is shorter than 128 bytes */
        uint64_t stored = bytes > 0 ? bytes : count * element;
        uint64_t padded = count * element < 128 ? 128 : count * element;
        if (stored > (uint64_t)(end - at) ||
            (bytes > 0 && !blosc_chunk_fits(at, bytes, count * element) &&
             !blosc_chunk_fits(at, bytes, padded)))
            return fail(w, GB_ERROR_FORMAT, "delayed-load metadata: a chunk does not match its "
                        "size");
        at += stored;
    }
    return GB_OK;
}

static gb_result read_metadata(walk *w, const char *what)
{
    gb_result result = GB_OK;
    const unsigned char *p = take(w, 4, what, &result);
    if (!p)
        return result;
    uint32_t count = get_u32(p);
    if (count > left(w) / 12)
        return fail(w, GB_ERROR_FORMAT, "more metadata entries than the file holds");
    for (uint32_t i = 0; i < count; ++i) {
        const unsigned char *name, *type, *value;
        uint32_t name_length, type_length, size;
        if ((result = read_string(w, what, &name, &name_length)) != GB_OK ||
            (result = read_string(w, what, &type, &type_length)) != GB_OK)
            return result;
        if (!(p = take(w, 4, what, &result)))
            return result;
        size = get_u32(p);
        if (!(value = take(w, size, what, &result)))
            return result;
        char message[200];
        int known = 0;
        for (size_t t = 0; t < sizeof typed_metadata / sizeof typed_metadata[0]; ++t)
            if (string_is(type, type_length, typed_metadata[t].name)) {
                known = 1;
                if (size != typed_metadata[t].size) {
                    snprintf(message, sizeof message, "metadata '%.*s' of type %s has %u bytes, "
                             "not %u", (int)(name_length < 64 ? name_length : 64),
                             (const char *)name, typed_metadata[t].name, size,
                             typed_metadata[t].size);
                    return fail(w, GB_ERROR_FORMAT, message);
                }
                if (!strcmp(typed_metadata[t].name, "bool") &&
                    (result = check_bools(w, value, 1, "metadata")) != GB_OK)
                    return result;
            }
        if (string_is(type, type_length, "string"))
            known = 1;
        else if (string_is(type, type_length, "__delayedload")) {
            known = 1;
            if ((result = delayed_load_value(w, value, size)) != GB_OK)
                return result;
        }
        if (!known) {
            snprintf(message, sizeof message, "metadata of type '%.*s', which gibake does not "
                     "read", (int)(type_length < 64 ? type_length : 64), (const char *)type);
            return fail(w, GB_ERROR_UNSUPPORTED, message);
        }
    }
    return GB_OK;
}

/* ---- node values (io::readCompressedValues, readData) ------------------------- */

static unsigned count_on(const unsigned char *mask, size_t bytes)
{
    unsigned count = 0;
    for (size_t i = 0; i < bytes; ++i)
        count += (unsigned)__builtin_popcount(mask[i]);
    return count;
}

static int bit_on(const unsigned char *mask, unsigned i)
{
    return mask[i >> 3] >> (i & 7) & 1;
}

/* A chunk of expected bytes: Blosc or zip (an int64 size, <= 0 for raw
 * bytes, whose count must then be the expected one), else raw. */
static gb_result read_chunk(walk *w, uint64_t expected, const char *what)
{
    gb_result result = GB_OK;
    const unsigned char *p;
    if (!(w->compression & (COMPRESS_BLOSC | COMPRESS_ZIP))) {
        if (!(p = take(w, expected, what, &result)))
            return result;
        return w->is_bool ? check_bools(w, p, expected, what) : GB_OK;
    }
    if (!(p = take(w, 8, what, &result)))
        return result;
    int64_t n = (int64_t)get_u64(p);
    if (n <= 0) {
        if ((uint64_t)0 - (uint64_t)n != expected)
            return fail(w, GB_ERROR_FORMAT, "an uncompressed chunk of the wrong size");
        if (!(p = take(w, expected, what, &result)))
            return result;
        return w->is_bool ? check_bools(w, p, expected, what) : GB_OK;
    }
    if (!(p = take(w, (uint64_t)n, what, &result)))
        return result;
    if ((w->compression & COMPRESS_BLOSC) && !blosc_chunk_fits(p, (uint64_t)n, expected))
        return fail(w, GB_ERROR_FORMAT, "a Blosc chunk whose header does not match its node");
    return GB_OK;
}

static gb_result read_values(walk *w, const unsigned char *value_mask, unsigned values,
                             size_t mask_bytes, const char *what)
{
    gb_result result = GB_OK;
    const unsigned char *p = take(w, 1, what, &result);
    if (!p)
        return result;
    int8_t metadata = (int8_t)p[0];
    if (metadata == NO_MASK_AND_ONE_INACTIVE_VAL || metadata == MASK_AND_ONE_INACTIVE_VAL ||
        metadata == MASK_AND_TWO_INACTIVE_VALS) {
        size_t n = (size_t)w->value_size * (metadata == MASK_AND_TWO_INACTIVE_VALS ? 2 : 1);
        if (!(p = take(w, n, what, &result)))
            return result;
        if (w->is_bool && (result = check_bools(w, p, n, what)) != GB_OK)
            return result;
    }
    if ((metadata == MASK_AND_NO_INACTIVE_VALS || metadata == MASK_AND_ONE_INACTIVE_VAL ||
         metadata == MASK_AND_TWO_INACTIVE_VALS) && !take(w, mask_bytes, what, &result))
        return result;
    unsigned count = (w->compression & COMPRESS_ACTIVE_MASK) && metadata != NO_MASK_AND_ALL_VALS
        ? count_on(value_mask, mask_bytes) : values;
    return read_chunk(w, (uint64_t)count * (uint64_t)w->value_size, what);
}

/* ---- the tree ------------------------------------------------------------------ */

static gb_result push_n4(walk *w, const unsigned char *child_mask)
{
    if (!gb_array_reserve(&w->n4_masks, &w->n4_capacity, w->n4_count + 1, sizeof *w->n4_masks))
        return fail(w, GB_ERROR_OUT_OF_MEMORY, "out of memory");
    w->n4_masks[w->n4_count++] = child_mask;
    return GB_OK;
}

/* InternalNode<5>::readTopology: child and value masks, its values, then
 * each child InternalNode<4> (masks, values, then each leaf's mask). */
static gb_result read_n5_topology(walk *w, root_child *child)
{
    gb_result result = GB_OK;
    const unsigned char *masks = take(w, 2 * N5_MASK, "an internal node", &result);
    if (!masks)
        return result;
    child->child_mask = masks;
    child->first_n4 = w->n4_count;
    if ((result = read_values(w, masks + N5_MASK, N5_VALUES, N5_MASK, "an internal node")) !=
        GB_OK)
        return result;
    for (unsigned i = 0; i < N5_VALUES; ++i) {
        if (!bit_on(masks, i))
            continue;
        const unsigned char *n4 = take(w, 2 * N4_MASK, "an internal node", &result);
        if (!n4 || (result = push_n4(w, n4)) != GB_OK ||
            (result = read_values(w, n4 + N4_MASK, N4_VALUES, N4_MASK, "an internal node")) !=
                GB_OK)
            return result;
        unsigned leaves = count_on(n4, N4_MASK);
        if (!take(w, (size_t)leaves * LEAF_MASK, "a leaf node", &result))
            return result;
    }
    return GB_OK;
}

static int origin_less(const int32_t *a, const int32_t *b)
{
    return a[0] != b[0] ? a[0] < b[0] : a[1] != b[1] ? a[1] < b[1] : a[2] < b[2];
}

static int compare_origins(const void *a, const void *b)
{
    const int32_t *p = a, *q = b;
    return origin_less(p, q) ? -1 : origin_less(q, p);
}

static int compare_children(const void *a, const void *b)
{
    return compare_origins(((const root_child *)a)->origin, ((const root_child *)b)->origin);
}

static gb_result read_origin(walk *w, int32_t origin[3], const char *what)
{
    gb_result result = GB_OK;
    const unsigned char *p = take(w, 12, what, &result);
    if (!p)
        return result;
    for (int k = 0; k < 3; ++k) {
        origin[k] = (int32_t)get_u32(p + 4 * k);
        if (origin[k] & (ROOT_CHILD_DIM - 1))
            return fail(w, GB_ERROR_FORMAT, "a root entry at an unaligned origin");
    }
    memcpy(w->origins[w->origin_count++], origin, 12);
    return GB_OK;
}

/* RootNode::readTopology: background, tile and child counts, the tiles,
 * then the children. */
static gb_result read_topology(walk *w)
{
    gb_result result = GB_OK;
    const unsigned char *p = take(w, 4 + (size_t)w->value_size + 8, "the root node", &result);
    if (!p)
        return result;
    if (get_u32(p) != 1)
        return fail(w, GB_ERROR_FORMAT, "a tree with other than one buffer");
    if (w->is_bool && (result = check_bools(w, p + 4, 1, "the background")) != GB_OK)
        return result;
    uint64_t tiles = get_u32(p + 4 + w->value_size), children = get_u32(p + 8 + w->value_size);
    size_t tile_size = 12 + (size_t)w->value_size + 1;
    if (tiles > left(w) / tile_size || children > (left(w) - tiles * tile_size) / (12 + 2 * N5_MASK))
        return fail(w, GB_ERROR_FORMAT, "more root entries than the file holds");
    w->origins = malloc((size_t)(tiles + children + 1) * sizeof *w->origins);
    w->children = malloc((size_t)(children + 1) * sizeof *w->children);
    if (!w->origins || !w->children)
        return fail(w, GB_ERROR_OUT_OF_MEMORY, "out of memory");
    for (uint64_t t = 0; t < tiles; ++t) {
        int32_t origin[3];
        if ((result = read_origin(w, origin, "a root tile")) != GB_OK)
            return result;
        p = take(w, (size_t)w->value_size + 1, "a root tile", &result);
        if (!p || (w->is_bool && (result = check_bools(w, p, 1, "a root tile")) != GB_OK) ||
            (result = check_bools(w, p + w->value_size, 1, "a root tile's active flag")) !=
                GB_OK)
            return result;
    }
    for (uint64_t c = 0; c < children; ++c) {
        root_child *child = &w->children[w->child_count++];
        if ((result = read_origin(w, child->origin, "a root child")) != GB_OK ||
            (result = read_n5_topology(w, child)) != GB_OK)
            return result;
    }
    qsort(w->origins, w->origin_count, sizeof *w->origins, compare_origins);
    for (size_t i = 1; i < w->origin_count; ++i)
        if (!compare_origins(w->origins[i - 1], w->origins[i]))
            return fail(w, GB_ERROR_FORMAT, "two root entries at one origin");
    return GB_OK;
}

/* LeafNode::readBuffers (values: mask and compressed values; bool: mask,
 * origin and value mask; ValueMask: mask and origin). */
static gb_result read_leaf_buffers(walk *w, const int32_t origin[3])
{
    gb_result result = GB_OK;
    const unsigned char *mask = take(w, LEAF_MASK, "a leaf node", &result);
    if (!mask)
        return result;
    if (w->leaf == LEAF_OF_VALUES)
        return read_values(w, mask, LEAF_VALUES, LEAF_MASK, "a leaf node");
    const unsigned char *stored = take(w, 12, "a leaf node", &result);
    if (!stored)
        return result;
    for (int k = 0; k < 3; ++k)
        if ((int32_t)get_u32(stored + 4 * k) != origin[k])
            return fail(w, GB_ERROR_FORMAT, "a leaf whose stored origin is not its place");
    if (w->leaf == LEAF_OF_BOOLS && !take(w, LEAF_MASK, "a leaf node", &result))
        return result;
    return GB_OK;
}

/* Tree::readBuffers: the root's children in the order of its table (sorted
 * by origin), depth first, children in index order. */
static gb_result read_buffers(walk *w)
{
    qsort(w->children, w->child_count, sizeof *w->children, compare_children);
    for (size_t c = 0; c < w->child_count; ++c) {
        const root_child *child = &w->children[c];
        size_t n4 = child->first_n4;
        for (unsigned i = 0; i < N5_VALUES; ++i) {
            if (!bit_on(child->child_mask, i))
                continue;
            const unsigned char *n4_mask = w->n4_masks[n4++];
            int32_t n4_origin[3] = {child->origin[0] + (int32_t)(i >> 10) * 128,
                                    child->origin[1] + (int32_t)(i >> 5 & 31) * 128,
                                    child->origin[2] + (int32_t)(i & 31) * 128};
            for (unsigned j = 0; j < N4_VALUES; ++j) {
                if (!bit_on(n4_mask, j))
                    continue;
                int32_t origin[3] = {n4_origin[0] + (int32_t)(j >> 8) * 8,
                                     n4_origin[1] + (int32_t)(j >> 4 & 15) * 8,
                                     n4_origin[2] + (int32_t)(j & 15) * 8};
                gb_result result = read_leaf_buffers(w, origin);
                if (result != GB_OK)
                    return result;
            }
        }
    }
    return GB_OK;
}

/* ---- grids and the file ----------------------------------------------------- */

static gb_result grid_kind(walk *w, const unsigned char *type, uint32_t length)
{
    static const struct {
        const char *name;
        int value_size, is_bool;
        leaf_kind leaf;
    } kinds[] = {
        {"Tree_bool_5_4_3", 1, 1, LEAF_OF_BOOLS},
        {"Tree_mask_5_4_3", 1, 1, LEAF_OF_MASK},
        {"Tree_float_5_4_3", 4, 0, LEAF_OF_VALUES},
        {"Tree_int32_5_4_3", 4, 0, LEAF_OF_VALUES},
    };
    for (size_t i = 0; i < sizeof kinds / sizeof kinds[0]; ++i)
        if (string_is(type, length, kinds[i].name)) {
            w->value_size = kinds[i].value_size;
            w->is_bool = kinds[i].is_bool;
            w->leaf = kinds[i].leaf;
            return GB_OK;
        }
    char message[160];
    snprintf(message, sizeof message, "type '%.*s' (gibake reads bool, mask, float and int32 "
             "grids)", (int)(length < 64 ? length : 64), (const char *)type);
    return fail(w, GB_ERROR_UNSUPPORTED, message);
}

/* Transform::read: the map's type, then its values (math/Maps.h). */
static gb_result read_transform(walk *w)
{
    static const struct {
        const char *name;
        size_t size;
    } maps[] = {
        {"UniformScaleTranslateMap", 144}, {"ScaleTranslateMap", 144}, {"UniformScaleMap", 120},
        {"ScaleMap", 120}, {"TranslationMap", 24}, {"AffineMap", 128}, {"UnitaryMap", 128},
    };
    const unsigned char *type;
    uint32_t length;
    gb_result result = read_string(w, "the transform", &type, &length);
    if (result != GB_OK)
        return result;
    for (size_t i = 0; i < sizeof maps / sizeof maps[0]; ++i)
        if (string_is(type, length, maps[i].name))
            return take(w, maps[i].size, "the transform", &result) ? GB_OK : result;
    return fail(w, GB_ERROR_UNSUPPORTED, "a transform that is not a linear map");
}

static void reset_tree(walk *w)
{
    free(w->children);
    free(w->origins);
    w->children = NULL;
    w->origins = NULL;
    w->child_count = w->origin_count = w->n4_count = 0;
}

static gb_result read_grid(walk *w)
{
    const unsigned char *name, *type, *parent, *p;
    uint32_t name_length, type_length, parent_length;
    gb_result result = read_string(w, "a grid descriptor", &name, &name_length);
    if (result == GB_OK)
        result = read_string(w, "a grid descriptor", &type, &type_length);
    if (result == GB_OK)
        result = read_string(w, "a grid descriptor", &parent, &parent_length);
    if (result != GB_OK || !take(w, 24, "a grid descriptor", &result))
        return result;
    snprintf(w->grid_name, sizeof w->grid_name, "%.*s",
             (int)(name_length < 64 ? name_length : 64), (const char *)name);
    w->grid = w->grid_name;
    if (parent_length != 0)
        return fail(w, GB_ERROR_UNSUPPORTED, "an instance of another grid");
    if ((result = grid_kind(w, type, type_length)) != GB_OK)
        return result;
    if (!(p = take(w, 4, "the grid's compression", &result)))
        return result;
    w->compression = get_u32(p);
    if ((result = read_metadata(w, "the grid's metadata")) != GB_OK ||
        (result = read_transform(w)) != GB_OK || (result = read_topology(w)) != GB_OK ||
        (result = read_buffers(w)) != GB_OK)
        return result;
    w->grid = NULL;
    return GB_OK;
}

gb_result gb_voxel_file_check(const void *bytes, size_t size, const char *path,
                              gb_error *error)
{
    walk w = {0};
    w.begin = w.at = bytes;
    w.end = w.begin + size;
    w.path = path;
    w.error = error;
    gb_result result = GB_OK;
    /* magic, file version, library major and minor, grid offsets flag, UUID */
    const unsigned char *header = take(&w, 8 + 4 + 4 + 4 + 1 + 36, "the header", &result);
    if (!header)
        return result;
    if (get_u32(header + 8) != FILE_VERSION) {
        char message[96];
        snprintf(message, sizeof message, "OpenVDB file format %u (gibake reads %d)",
                 get_u32(header + 8), FILE_VERSION);
        return fail(&w, GB_ERROR_UNSUPPORTED, message);
    }
    if ((result = read_metadata(&w, "the file's metadata")) != GB_OK)
        return result;
    const unsigned char *p = take(&w, 4, "the grid count", &result);
    if (!p)
        return result;
    uint32_t grids = get_u32(p);
    if (grids > 0x7fffffffu || grids > left(&w) / 36)
        return fail(&w, GB_ERROR_FORMAT, "more grids than the file holds");
    for (uint32_t g = 0; g < grids && result == GB_OK; ++g) {
        result = read_grid(&w);
        reset_tree(&w);
    }
    free(w.n4_masks);
    return result;
}
