// grid_file.cpp — writing and reading the grids of a gibake OpenVDB file
// (grid_file.h).
#include "grid_file.h"

#include <openvdb/io/Stream.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <istream>
#include <streambuf>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace gb_openvdb {

namespace {

// Blosc (fast, and OpenVDB's own default) when this OpenVDB has it, else zip.
uint32_t compression()
{
    return openvdb::io::COMPRESS_ACTIVE_MASK
           | (openvdb::io::Archive::hasBloscCompression() ? openvdb::io::COMPRESS_BLOSC
                                                          : openvdb::io::COMPRESS_ZIP);
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

} // namespace

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

namespace {

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

} // namespace

// The stream throws on a read past the end, so that no count OpenVDB trusts
// can make it go on reading zeros at the end of a damaged file.
gb_result Reader::open(gb_error *error)
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

Reader::~Reader()
{
    grids.reset();
    if (mapping != MAP_FAILED)
        munmap(mapping, size);
}

gb_result Reader::map(gb_error *error)
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

} // namespace gb_openvdb
