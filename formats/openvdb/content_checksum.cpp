// content_checksum.cpp — the voxel file's checksum in OpenVDB's UUID bytes
// (content_checksum.h; FORMATS.md, "Voxel file", "Checksum").
#include "content_checksum.h"

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include "adapter_host.h"

namespace gb_openvdb {

namespace {

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

} // namespace

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

} // namespace gb_openvdb
