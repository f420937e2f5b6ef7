// lscm_cgal.cpp — the CGAL adapter of tools/atlas (lscm.h): a chart's mesh
// into a CGAL::Surface_mesh, LSCM with two pinned border vertices, the UVs
// back out. Every CGAL failure (an error code or an exception: CGAL's
// preconditions throw) becomes a gb_result; nothing escapes to C.

#define CGAL_EIGEN3_ENABLED 1

#include "lscm.h"

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Two_vertices_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <cmath>
#include <exception>
#include <vector>

namespace {

typedef CGAL::Simple_cartesian<double> Kernel;
typedef Kernel::Point_2 Point_2;
typedef Kernel::Point_3 Point_3;
typedef CGAL::Surface_mesh<Point_3> Mesh;
typedef Mesh::Vertex_index Vertex;
typedef Mesh::Halfedge_index Halfedge;
namespace SMP = CGAL::Surface_mesh_parameterization;
typedef SMP::Two_vertices_parameterizer_3<Mesh> Border;
typedef SMP::LSCM_parameterizer_3<Mesh, Border> Lscm;

// The chart as a Surface_mesh; false if a face cannot be added (an edge
// used twice the same way round: the chart is not consistently oriented).
bool build_mesh(uint32_t vertex_count, const double *positions, uint32_t triangle_count,
                const uint32_t *triangles, Mesh &mesh)
{
    mesh.reserve(vertex_count, 3 * triangle_count, triangle_count);
    for (uint32_t i = 0; i < vertex_count; ++i)
        mesh.add_vertex(Point_3(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]));
    for (uint32_t t = 0; t < triangle_count; ++t) {
        const uint32_t *c = triangles + 3 * t;
        if (c[0] >= vertex_count || c[1] >= vertex_count || c[2] >= vertex_count)
            return false;
        if (mesh.add_face(Vertex(c[0]), Vertex(c[1]), Vertex(c[2])) == Mesh::null_face())
            return false;
    }
    return true;
}

gb_result parameterize(uint32_t vertex_count, const double *positions, uint32_t triangle_count,
                       const uint32_t *triangles, double *uvs, gb_error *error)
{
    Mesh mesh;
    if (!build_mesh(vertex_count, positions, triangle_count, triangles, mesh))
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "the chart is not an oriented manifold");
    Halfedge border = CGAL::Polygon_mesh_processing::longest_border(mesh).first;
    if (border == Mesh::null_halfedge())
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "the chart has no border");
    Mesh::Property_map<Vertex, Point_2> uv_map =
        mesh.add_property_map<Vertex, Point_2>("v:uv", Point_2(0, 0)).first;
    SMP::Error_code code = SMP::parameterize(mesh, Lscm(), border, uv_map);
    if (code != SMP::OK)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "CGAL LSCM: %s",
                       SMP::get_error_message(code));
    for (uint32_t i = 0; i < vertex_count; ++i) {
        Point_2 uv = uv_map[Vertex(i)];
        if (!std::isfinite(uv.x()) || !std::isfinite(uv.y()))
            return gb_fail(error, GB_ERROR_UNSUPPORTED, "CGAL LSCM: a UV is not finite");
        uvs[2 * i] = uv.x();
        uvs[2 * i + 1] = uv.y();
    }
    return GB_OK;
}

} // namespace

extern "C" gb_result gb_lscm_parameterize(uint32_t vertex_count, const double *positions,
                                          uint32_t triangle_count, const uint32_t *triangles,
                                          double *uvs, gb_error *error)
{
    try {
        return parameterize(vertex_count, positions, triangle_count, triangles, uvs, error);
    } catch (const std::exception &e) {
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "CGAL LSCM: %s", e.what());
    } catch (...) {
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "CGAL LSCM: an unknown exception");
    }
}
