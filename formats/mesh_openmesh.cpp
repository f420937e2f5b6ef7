// mesh_openmesh.cpp — the OpenMesh adapter: PLY, OFF and STL to indexed
// triangles (see mesh_openmesh.h). The only file that includes OpenMesh.

#include "mesh_openmesh.h"
#include "mesh_check.h"

#include <cstdlib>
#include <cstring>
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

// OpenMesh reports problems on omerr(), which writes to std::cerr, and
// notes on omlog() and omout() (std::clog, std::cout: "Unsupported keyword"
// for each unknown word of a PLY header). While a mesh is read, std::cerr's
// buffer is swapped for a string so the messages become part of gibake's
// error, and the other two for one that is dropped (the library never
// prints).
class CerrCapture {
public:
    CerrCapture()
        : saved_(std::cerr.rdbuf(text_.rdbuf())), saved_log_(std::clog.rdbuf(dropped_.rdbuf())),
          saved_out_(std::cout.rdbuf(dropped_.rdbuf()))
    {
    }
    ~CerrCapture()
    {
        std::cerr.rdbuf(saved_);
        std::clog.rdbuf(saved_log_);
        std::cout.rdbuf(saved_out_);
    }
    std::string text() const { return text_.str(); }

private:
    std::ostringstream text_, dropped_;
    std::streambuf *saved_, *saved_log_, *saved_out_;
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
    gb_mesh_counts declared;
    gb_result checked = gb_mesh_check_file(path, &declared, error);
    if (checked != GB_OK)
        return checked;
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
    // faces that repeat a vertex (OpenMesh says so) or have fewer than 3
    // corners (dropped without a word) are degenerate: counted, not errors
    std::size_t equal = count_lines_with(messages, "equal vertices");
    std::size_t degenerate = equal + static_cast<std::size_t>(declared.short_faces);
    if (declared.vertices > (long long)mesh.n_vertices())
        return gb_fail(error, GB_ERROR_PARSE, "%s: OpenMesh read %zu of %lld vertices", path,
                       mesh.n_vertices(), declared.vertices);
    long long missing =
        declared.faces >= 0 ? declared.faces - (long long)(mesh.n_faces() + degenerate) : 0;
    // numbers, indices and the file's length were checked before: what is
    // missing, OpenMesh did not add
    if (missing > 0)
        return gb_fail(error, GB_ERROR_INVALID, "%s: %lld of %lld faces unread: OpenMesh could "
                       "not add them (%s)", path, missing, declared.faces,
                       messages.empty() ? "it says nothing" : first_line(messages).c_str());
    if (count_lines_with(messages, "invalid vertex index"))
        return gb_fail(error, GB_ERROR_INVALID, "%s: faces with a vertex index out of range "
                       "(%zu vertices)", path, mesh.n_vertices());
    *skipped_faces = static_cast<uint32_t>(degenerate);
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
