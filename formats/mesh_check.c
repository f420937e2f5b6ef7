/* mesh_check.c — PLY, OFF and STL bytes checked before OpenMesh reads them
 * (see mesh_check.h for what is refused and why): the file's suffix picks
 * the checker (mesh_check_ply.c, mesh_check_off.c, mesh_check_stl.c), each
 * of which follows the OpenMesh 9.0 reader of its format step by step, so
 * that a count, an index or a number is checked exactly where OpenMesh
 * will use it. */
#include "mesh_check.h"
#include "mapped_file.h"
#include "mesh_reader.h"
#include "text.h"

/* ---- entry points --------------------------------------------------------------- */

gb_result gb_mesh_check(const void *bytes, size_t size, const char *path,
                        gb_mesh_counts *counts, gb_error *error)
{
    reader r = {bytes, bytes, (const unsigned char *)bytes + size, path, 1};
    counts->vertices = counts->faces = -1;
    counts->short_faces = 0;
    if (gb_path_has_suffix(path, ".ply"))
        return gb_mesh_check_ply(&r, counts, error);
    if (gb_path_has_suffix(path, ".off"))
        return gb_mesh_check_off(&r, counts, error);
    if (gb_path_has_suffix(path, ".stl"))
        return gb_mesh_check_stl(&r, error);
    return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: not a .ply, .off or .stl file", path);
}

gb_result gb_mesh_check_file(const char *path, gb_mesh_counts *counts, gb_error *error)
{
    counts->vertices = counts->faces = -1;
    counts->short_faces = 0;
    gb_mapped_file mapped;
    gb_result result = gb_mapped_file_open(path, &mapped, error);
    if (result != GB_OK)
        return result;
    result = gb_mesh_check(mapped.bytes, mapped.size, path, counts, error);
    gb_mapped_file_close(&mapped);
    return result;
}
