/* gltf_binary.h — a glTF 2.0 binary file (.glb; Khronos glTF 2.0 spec,
 * "GLB File Format Specification"; formats/FORMATS.md, "glTF export"):
 * the 12-byte header (magic "glTF", version 2, total length), the JSON
 * chunk padded with spaces to 4 bytes, then, when bin_size > 0, the BIN
 * chunk padded with zeros to 4 bytes. Written through the one output
 * writer (output_file.h): whole or not at all.
 *
 * The caller owns json (UTF-8, json_size bytes, no NUL needed) and bin, and
 * keeps them consistent: the JSON's buffers[0].byteLength is bin_size (the
 * padding excluded, as the spec allows).
 */
#ifndef GB_GLTF_BINARY_H
#define GB_GLTF_BINARY_H

#include <stddef.h>

#include "result.h"

gb_result gb_gltf_binary_write(const char *path, const char *json, size_t json_size,
                               const void *bin, size_t bin_size, gb_error *error);

#endif
