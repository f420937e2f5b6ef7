// content_checksum.h — the voxel file's checksum (FORMATS.md, "Voxel file",
// "Checksum").
//
// OpenVDB writes a random UUID in the file header: 36 ASCII characters at
// bytes 21..56, after the magic (8 bytes), the file format version and the
// library's major and minor versions (u32 each) and the grid-offsets flag (1
// byte). gibake writes there instead a UUID made from every other byte of the
// file and its length: the same grids then give the same bytes, and the UUID
// is the checksum that readers verify before OpenVDB parses anything.
#ifndef GB_OPENVDB_CONTENT_CHECKSUM_H
#define GB_OPENVDB_CONTENT_CHECKSUM_H

#include <cstddef>

#include "result.h"

namespace gb_openvdb {

const size_t UUID_OFFSET = 8 + 4 + 4 + 4 + 1;
const size_t UUID_LENGTH = 36;
const size_t HEADER_BYTES = UUID_OFFSET + UUID_LENGTH;

// Rewrites the UUID of the file name (just written by OpenVDB, for path) as
// its checksum.
gb_result write_content_uuid(const char *path, const char *name, gb_error *error);

// Checks the magic, then the checksum, of the file at path; a file of the
// older checksum (format 1) is named as such.
gb_result check_file(const char *path, gb_error *error);

// The checksum bytes (size bytes, the whole file) should carry, as 36
// characters and a NUL in uuid; 0 when size is below HEADER_BYTES.
int file_checksum(const void *bytes, size_t size, char uuid[37]);

} // namespace gb_openvdb

#endif
