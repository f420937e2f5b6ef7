// mesh_openmesh.cpp — the OpenMesh adapter: PLY, OFF and STL to indexed
// triangles (see mesh_openmesh.h). The only file that includes OpenMesh.

#include "mesh_openmesh.h"

#include <cctype>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

// OpenMesh's property vectors trip GCC's -Wmaybe-uninitialized when inlined.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

namespace {

// A polygon mesh: faces are kept as the file has them, so that their number
// can be checked against the file's header, and fan-triangulated here.
typedef OpenMesh::PolyMesh_ArrayKernelT<> Mesh;

// OpenMesh reports problems on omerr(), which writes to std::cerr. While a
// mesh is read, std::cerr's buffer is swapped for a string so the messages
// become part of gibake's error (the library never prints).
class CerrCapture {
public:
    CerrCapture() : saved_(std::cerr.rdbuf(text_.rdbuf())) {}
    ~CerrCapture() { std::cerr.rdbuf(saved_); }
    std::string text() const { return text_.str(); }

private:
    std::ostringstream text_;
    std::streambuf *saved_;
};

// Number of lines of messages that contain phrase.
std::size_t count_lines_with(const std::string &messages, const char *phrase)
{
    std::size_t count = 0;
    for (std::size_t at = messages.find(phrase); at != std::string::npos;
         at = messages.find(phrase, at + 1))
        ++count;
    return count;
}

// The first line of messages, for an error.
std::string first_line(const std::string &messages)
{
    std::string line = messages.substr(0, messages.find('\n'));
    return line.empty() ? std::string("unreadable or unsupported file") : line;
}

bool ends_with(const std::string &text, const char *suffix)
{
    std::size_t n = std::strlen(suffix);
    if (text.size() < n)
        return false;
    for (std::size_t i = 0; i < n; ++i)
        if (std::tolower(static_cast<unsigned char>(text[text.size() - n + i])) != suffix[i])
            return false;
    return true;
}

// What a header declares; -1 where it does not say.
struct Counts {
    long long vertices = -1, faces = -1;
};

// "element vertex N" and "element face N" of a PLY header.
Counts ply_counts(std::istream &in)
{
    Counts counts;
    std::string line;
    while (std::getline(in, line) && line.rfind("end_header", 0) != 0) {
        std::istringstream words(line);
        std::string element, name;
        long long count;
        if (!(words >> element >> name >> count) || element != "element")
            continue;
        if (name == "vertex")
            counts.vertices = count;
        else if (name == "face")
            counts.faces = count;
    }
    return counts;
}

// The next word of an OFF file, skipping '#' comments.
bool off_word(std::istream &in, std::string &word)
{
    while (in >> word) {
        if (word[0] != '#')
            return true;
        std::getline(in, word);
    }
    return false;
}

long long to_count(const std::string &word)
{
    char *end;
    long long count = std::strtoll(word.c_str(), &end, 10);
    return *end == '\0' && !word.empty() ? count : -1;
}

long long big_endian_32(const unsigned char *bytes)
{
    return (long long)bytes[0] << 24 | bytes[1] << 16 | bytes[2] << 8 | bytes[3];
}

// "OFF" then the numbers of vertices, faces and edges (ASCII or binary).
Counts off_counts(std::istream &in)
{
    Counts counts;
    std::string keyword, vertices, faces;
    if (!off_word(in, keyword) || !ends_with(keyword, "off") || !off_word(in, vertices))
        return counts;
    if (vertices == "BINARY") {
        unsigned char bytes[8];
        in.get();   // the end of the header line
        if (in.read(reinterpret_cast<char *>(bytes), 8)) {
            counts.vertices = big_endian_32(bytes);
            counts.faces = big_endian_32(bytes + 4);
        }
        return counts;
    }
    counts.vertices = to_count(vertices);
    if (off_word(in, faces))
        counts.faces = to_count(faces);
    return counts;
}

// What the file says it has; -1s for STL, which says nothing, and for a
// header not understood (then OpenMesh's reading is trusted).
Counts declared_counts(const char *path)
{
    std::ifstream in(path, std::ios::binary);
    std::string name(path);
    if (ends_with(name, ".ply"))
        return ply_counts(in);
    if (ends_with(name, ".off"))
        return off_counts(in);
    return Counts();
}

std::size_t triangle_count_of(const Mesh &mesh)
{
    std::size_t triangles = 0;
    for (Mesh::FaceHandle face : mesh.faces())
        triangles += mesh.valence(face) - 2;
    return triangles;
}

// Fan-triangulates the faces into f.
void copy_triangles(const Mesh &mesh, uint32_t *f)
{
    std::size_t t = 0;
    for (Mesh::FaceHandle face : mesh.faces()) {
        uint32_t first = 0, previous = 0;
        int corner = 0;
        for (Mesh::VertexHandle v : mesh.fv_range(face)) {
            uint32_t index = static_cast<uint32_t>(v.idx());
            if (corner == 0)
                first = index;
            else if (corner >= 2) {
                f[3 * t] = first;
                f[3 * t + 1] = previous;
                f[3 * t + 2] = index;
                ++t;
            }
            previous = index;
            ++corner;
        }
    }
}

gb_result copy_out(const Mesh &mesh, const char *path, float **positions,
                   uint32_t *vertex_count, uint32_t **indices, uint32_t *triangle_count,
                   gb_error *error)
{
    std::size_t vertices = mesh.n_vertices(), triangles = triangle_count_of(mesh);
    if (vertices > UINT32_MAX / 4 || triangles > UINT32_MAX / 4)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: too many vertices or faces", path);
    float *p = static_cast<float *>(std::malloc((vertices + 1) * 3 * sizeof(float)));
    uint32_t *f = static_cast<uint32_t *>(std::malloc((triangles + 1) * 3 * sizeof(uint32_t)));
    if (!p || !f) {
        std::free(p);
        std::free(f);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    for (Mesh::VertexHandle v : mesh.vertices()) {
        const Mesh::Point &point = mesh.point(v);
        for (int k = 0; k < 3; ++k)
            p[3 * v.idx() + k] = point[k];
    }
    copy_triangles(mesh, f);
    *positions = p;
    *indices = f;
    *vertex_count = static_cast<uint32_t>(vertices);
    *triangle_count = static_cast<uint32_t>(triangles);
    return GB_OK;
}

gb_result read(const char *path, float **positions, uint32_t *vertex_count,
               uint32_t **indices, uint32_t *triangle_count, uint32_t *skipped_faces,
               gb_error *error)
{
    Mesh mesh;
    OpenMesh::IO::Options options;
    std::string messages;
    bool read;
    {
        CerrCapture capture;
        read = OpenMesh::IO::read_mesh(mesh, std::string(path), options);
        messages = capture.text();
    }
    if (!read)
        return gb_fail(error, GB_ERROR_PARSE, "%s: OpenMesh cannot read it: %s", path,
                       first_line(messages).c_str());
    std::size_t equal = count_lines_with(messages, "equal vertices");
    Counts declared = declared_counts(path);
    if (declared.vertices > (long long)mesh.n_vertices())
        return gb_fail(error, GB_ERROR_PARSE, "%s: OpenMesh read %zu of %lld vertices", path,
                       mesh.n_vertices(), declared.vertices);
    long long missing = declared.faces >= 0 ? declared.faces - (long long)(mesh.n_faces() + equal)
                                            : 0;
    if (missing > 0)
        return gb_fail(error, GB_ERROR_INVALID, "%s: %lld of %lld faces unread: a vertex index "
                       "out of range (%zu vertices), a malformed number or a truncated file",
                       path, missing, declared.faces, mesh.n_vertices());
    if (count_lines_with(messages, "invalid vertex index"))
        return gb_fail(error, GB_ERROR_INVALID, "%s: faces with a vertex index out of range "
                       "(%zu vertices)", path, mesh.n_vertices());
    *skipped_faces = static_cast<uint32_t>(equal);
    return copy_out(mesh, path, positions, vertex_count, indices, triangle_count, error);
}

} // namespace

extern "C" gb_result gb_openmesh_read(const char *path, float **positions,
                                      uint32_t *vertex_count, uint32_t **indices,
                                      uint32_t *triangle_count, uint32_t *skipped_faces,
                                      gb_error *error)
{
    *positions = nullptr;
    *indices = nullptr;
    *vertex_count = *triangle_count = *skipped_faces = 0;
    try {
        return read(path, positions, vertex_count, indices, triangle_count, skipped_faces,
                    error);
    } catch (const std::bad_alloc &) {
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    } catch (const std::exception &e) {
        return gb_fail(error, GB_ERROR_PARSE, "%s: OpenMesh: %s", path, e.what());
    }
}
