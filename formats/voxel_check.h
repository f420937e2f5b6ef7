/* voxel_check.h — an OpenVDB file's bytes walked before the OpenVDB adapter
 * (formats/openvdb/) hands them to OpenVDB.
 *
 * OpenVDB 10 trusts the sizes and counts it reads: a string's or a
 * metadata value's length, a compressed chunk's size (bloscFromStream and
 * unzipFromStream allocate it, and copy an "uncompressed" chunk of any
 * size into a buffer of the expected one), the grid count (reserved), the
 * delayed-load metadata's counts; it reads bytes into bools whatever their
 * value, and keys root nodes by origins it does not check. This walk
 * follows OpenVDB's stream reader (io::Stream: header, file metadata, then
 * per grid its descriptor, compression, metadata, transform, topology and
 * buffers, the buffers in the order of the root's sorted table) for what
 * gibake reads and refuses, with "path: what is wrong":
 *
 *  - file format versions other than 224 (OpenVDB 10), grid types other
 *    than Tree_bool_5_4_3, Tree_mask_5_4_3, Tree_float_5_4_3 and
 *    Tree_int32_5_4_3 (no half floats), instanced grids, metadata types
 *    other than OpenVDB's typed ones ("bool" ... "mat4d", "string",
 *    "__delayedload") and transforms other than the linear maps;
 *  - any size or count that reaches past the end of the file, a typed
 *    metadata value whose size is not its type's, a chunk whose size or
 *    Blosc header does not match what the node expects, a bool that is not
 *    0 or 1 where it is stored uncompressed, root entries at unaligned or
 *    repeated origins, a leaf whose stored origin is not its place.
 *
 * It does not decompress anything: what is inside a Blosc or zlib chunk is
 * checked by those libraries and by OpenVDB (a wrong size throws). */
#ifndef GB_VOXEL_CHECK_H
#define GB_VOXEL_CHECK_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#include "result.h"

gb_result gb_voxel_file_check(const void *bytes, size_t size, const char *path,
                              gb_error *error);

#ifdef __cplusplus
}
#endif

#endif
