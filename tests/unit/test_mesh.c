/* test_mesh.c — PLY, OFF and STL checked before OpenMesh reads them
 * (formats/mesh_check.h): NaN, Inf and malformed numbers named with their
 * line and vertex (ASCII) or vertex (binary), and the headers and counts
 * OpenMesh would crash, loop or over-allocate on refused with a message;
 * valid files still load through gb_scene_load. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mesh_check.h"
#include "scene.h"
#include "scratch.h"
#include "tap.h"

/* Loads name (written with text) through gb_scene_load; 1 when it fails
 * with result and a message that is "<folder>/" followed by expected. */
static int load_fails(const char *name, const void *bytes, size_t size, gb_result result,
                      const char *expected)
{
    char path[4096], want[4096];
    scratch_write(scratch_path_into(name, path, sizeof path), bytes, size);
    scratch_path_into(expected, want, sizeof want);
    gb_scene scene;
    gb_error error;
    gb_result got = gb_scene_load(path, NULL, &scene, &error);
    if (got == GB_OK) {
        printf("#   %s loaded\n", name);
        gb_scene_free(&scene);
        return 0;
    }
    if (got != result || strcmp(error.message, want) != 0) {
        printf("#   got %s: %s\n#   expected %s: %s\n", gb_result_name(got), error.message,
               gb_result_name(result), want);
        return 0;
    }
    return 1;
}

static int loads(const char *name, const void *bytes, size_t size, uint32_t triangles)
{
    char path[4096];
    scratch_write(scratch_path_into(name, path, sizeof path), bytes, size);
    gb_scene scene;
    gb_error error;
    if (gb_scene_load(path, NULL, &scene, &error) != GB_OK) {
        printf("#   %s\n", error.message);
        return 0;
    }
    int ok = scene.triangle_count == triangles;
    if (!ok)
        printf("#   %u triangles, expected %u\n", scene.triangle_count, triangles);
    gb_scene_free(&scene);
    return ok;
}

/* gb_mesh_check on text: 1 when it fails with result and message. */
static int check_fails(const char *name, const void *bytes, size_t size, gb_result result,
                       const char *expected)
{
    gb_mesh_counts counts;
    gb_error error;
    gb_result got = gb_mesh_check(bytes, size, name, &counts, &error);
    if (got == GB_OK) {
        printf("#   %s passed the check\n", name);
        return 0;
    }
    if (got != result || !strstr(error.message, expected)) {
        printf("#   got %s: %s\n#   expected %s: ...%s...\n", gb_result_name(got),
               error.message, gb_result_name(result), expected);
        return 0;
    }
    return 1;
}

#define TEXT(s) s, sizeof s - 1

static const char ply_head[] =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

static void test_ascii_non_finite(void)
{
    static const struct {
        const char *name, *body, *message;
        gb_result result;
    } cases[] = {
        {"nan.ply", "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", "nan.ply:11: vertex 1: y 'nan' is not finite",
         GB_ERROR_INVALID},
        {"inf.ply", "0 0 0\n1 0 0\n-Infinity 1 0\n3 0 1 2\n",
         "inf.ply:12: vertex 2: x '-Infinity' is not finite", GB_ERROR_INVALID},
        {"big.ply", "0 0 1e39\n1 0 0\n0 1 0\n3 0 1 2\n", "big.ply:10: vertex 0: z '1e39' is not finite",
         GB_ERROR_INVALID},
        {"bad.ply", "0 0 0\n1 0 0\n0 1.0.0 0\n3 0 1 2\n",
         "bad.ply:12: vertex 2: y '1.0.0' is not a number", GB_ERROR_PARSE},
        {"hex.ply", "0 0 0\n0x1p0 0 0\n0 1 0\n3 0 1 2\n",
         "hex.ply:11: vertex 1: x '0x1p0' is not a number", GB_ERROR_PARSE},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        char text[1024], what[256];
        snprintf(text, sizeof text, "%s%s", ply_head, cases[i].body);
        snprintf(what, sizeof what, "ASCII PLY: %s", cases[i].message);
        CHECK(load_fails(cases[i].name, text, strlen(text), cases[i].result, cases[i].message),
              what);
    }
    CHECK(load_fails("nan.off", TEXT("OFF\n3 1 0\n0 0 0\n1 0 0\n0 NaN 0\n3 0 1 2\n"),
                     GB_ERROR_INVALID, "nan.off:5: vertex 2: y 'NaN' is not finite"),
          "ASCII OFF: the NaN, its line and its vertex");
    CHECK(load_fails("inf.off", TEXT("NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 inf\n0 1 0 0 0 1\n"
                                     "3 0 1 2\n"),
                     GB_ERROR_INVALID, "inf.off:4: vertex 1: nz 'inf' is not finite"),
          "ASCII OFF: an infinite normal too");
    CHECK(load_fails("nan.stl", TEXT("solid t\n facet normal 0 0 1\n  outer loop\n"
                                     "   vertex 0 0 0\n   vertex 1 0 nan\n   vertex 0 1 0\n"
                                     "  endloop\n endfacet\nendsolid t\n"),
                     GB_ERROR_INVALID, "nan.stl:5: facet 0: vertex 1: z 'nan' is not finite"),
          "ASCII STL: the NaN, its line, facet and vertex (was: no triangles)");
    CHECK(load_fails("short.stl", TEXT("solid t\n facet normal 0 0 1\n  outer loop\n"
                                       "   vertex 0 0 0\n   vertex 1 0\n   vertex 0 1 0\n"
                                       "  endloop\n endfacet\nendsolid t\n"),
                     GB_ERROR_PARSE, "short.stl:5: facet 0: vertex 1: no z coordinate"),
          "ASCII STL: a missing coordinate");
    char text[1024];
    snprintf(text, sizeof text, "%s", "ply\nformat ascii 1.0\nelement vertex 3\n"
             "property float x\nproperty float y\nproperty float z\nproperty float quality\n"
             "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
             "0 0 0 nan\n1 0 0 nan\n0 1 0 nan\n3 0 1 2\n");
    CHECK(loads("quality.ply", text, strlen(text), 1),
          "a NaN in a property OpenMesh skips (quality) is accepted");
}

/* size bytes at p; how many (numbers as they are in memory: the test
 * host is little-endian). */
static size_t put(unsigned char *p, const void *bytes, size_t size)
{
    memcpy(p, bytes, size);
    return size;
}

static void test_binary_non_finite(void)
{
    unsigned char bytes[1024];
    static const char head[] =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nelement face 1\n"
        "property list uchar int vertex_indices\nend_header\n";
    float vertices[9] = {0, 0, 0, 1, 0, 0, 0, NAN, 0};
    int32_t face[3] = {0, 1, 2};
    size_t n = put(bytes, head, sizeof head - 1);
    n += put(bytes + n, vertices, sizeof vertices);
    bytes[n++] = 3;
    n += put(bytes + n, face, sizeof face);
    CHECK(load_fails("nan-binary.ply", bytes, n, GB_ERROR_INVALID,
                     "nan-binary.ply: vertex 2: y is not finite (nan)"),
          "binary PLY: the vertex and coordinate that is NaN");
    vertices[7] = 1;
    put(bytes + sizeof head - 1, vertices, sizeof vertices);
    CHECK(loads("binary.ply", bytes, n, 1), "the same PLY with a finite y loads");

    unsigned char stl[84 + 50] = {0};
    stl[80] = 1;
    float facet[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, INFINITY, 1, 0};
    put(stl + 84, facet, sizeof facet);
    CHECK(load_fails("inf-binary.stl", stl, sizeof stl, GB_ERROR_INVALID,
                     "inf-binary.stl: facet 0: vertex 2: x is not finite (inf)"),
          "binary STL: the facet, vertex and coordinate");

    unsigned char off[256];
    static const char off_head[] = "OFF BINARY\n";
    int32_t counts[3] = {3, 1, 0}, off_face[4] = {3, 0, 1, 2};
    float off_vertices[9] = {0, 0, 0, 1, 0, 0, 0, 1, -INFINITY};
    n = put(off, off_head, sizeof off_head - 1);
    n += put(off + n, counts, sizeof counts);
    n += put(off + n, off_vertices, sizeof off_vertices);
    n += put(off + n, off_face, sizeof off_face);
    CHECK(load_fails("inf-binary.off", off, n, GB_ERROR_INVALID,
                     "inf-binary.off: vertex 2: z is not finite (-inf)"),
          "binary OFF: the vertex and coordinate");
    off_vertices[8] = 0;
    put(off + sizeof off_head - 1 + sizeof counts, off_vertices, sizeof off_vertices);
    CHECK(loads("binary.off", off, n, 1), "the same OFF with a finite z loads (little-endian)");
    for (int i = 0; i < 3; ++i) {   /* the Geomview byte order */
        uint32_t v = (uint32_t)counts[i];
        unsigned char *p = off + sizeof off_head - 1 + 4 * i;
        p[0] = (unsigned char)(v >> 24), p[1] = (unsigned char)(v >> 16);
        p[2] = (unsigned char)(v >> 8), p[3] = (unsigned char)v;
    }
    CHECK(check_fails("be.off", off, n, GB_ERROR_UNSUPPORTED, "big-endian"),
          "binary OFF with big-endian counts: refused (OpenMesh would reserve 134M vertices)");
}

/* Headers and counts OpenMesh crashes, loops or over-allocates on. */
static void test_guards(void)
{
    /* gb_mesh_check on head (ply_head or none) and body: refused with
     * result, its message holding message. */
    static const struct {
        const char *name, *head, *body;
        gb_result result;
        const char *message, *what;
    } cases[] = {
        {"a.ply", "", "ply\nformat ascii 1.0\ncomment x\nelement vertex 3\nproperty float x\n",
         GB_ERROR_PARSE, "a.ply:6: the PLY header has no end_header",
         "PLY without end_header (OpenMesh loops forever)"},
        {"a.ply", "", "ply\nformat ascii 1.0\nproperty float x\nend_header\n", GB_ERROR_PARSE,
         "a.ply:3: a property before any element",
         "PLY property before any element (OpenMesh: segmentation fault)"},
        {"a.ply", "", "ply\nformat ascii abc\nend_header\n", GB_ERROR_PARSE,
         "PLY version 'abc' is not a number", "PLY malformed version (OpenMesh loops forever)"},
        {"a.ply", "", "ply\nformat ascii 1.0\nelement vertex -1\nend_header\n", GB_ERROR_PARSE,
         "element vertex: count '-1' is not a count", "PLY negative count"},
        {"a.ply", ply_head, "0 0 0\n1 0 0\n0 1 0\n300000000 0 1 2\n", GB_ERROR_FORMAT,
         "a.ply:13: face 0: 300000000 corners, more than the rest of the file holds",
         "PLY face corner count beyond the file (OpenMesh: 2.2 GB, 5 s)"},
        {"a.ply", "",
         "ply\nformat ascii 1.0\nelement vertex 4000000000\n"
         "property float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n",
         GB_ERROR_FORMAT, "element vertex declares 4000000000 items, more than the 7 bytes",
         "PLY vertex count beyond the file (OpenMesh reserves it)"},
        {"a.ply", "",
         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
         "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
         "element face 2\nproperty float q\nend_header\n"
         "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n-1\n",
         GB_ERROR_UNSUPPORTED, "a.ply:9: a second element face",
         "PLY face element declared twice (OpenMesh reads the first with the second's count: "
         "-1 corners, 2^32 of them, out of memory; found by fuzz_mesh)"},
        {"a.ply", ply_head, "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", GB_ERROR_INVALID,
         "a.ply:13: face 0: vertex index 3 out of range (3 vertices)",
         "PLY vertex index out of range, named"},
        {"a.ply", "",
         "ply\nformat ascii 1.0\nelement vertex 3\n"
         "property float x\nproperty float y\nproperty float z\nelement face 2\n"
         "property list uchar int vertex_indices\nproperty list uchar float texcoord\n"
         "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 6 0 0 1 0 0 1\n3 0 2 1 6 0 0 1 0 0 1\n",
         GB_ERROR_UNSUPPORTED, "list property texcoord is not supported",
         "PLY face texcoord list (OpenMesh misreads the next face)"},
        {"a.ply", "",
         "ply\nformat binary_little_endian 1.0\nelement vertex 0\n"
         "property float x\ncomment last\nend_header\n",
         GB_ERROR_UNSUPPORTED, "OpenMesh would read the data from the wrong byte",
         "binary PLY with a comment just before end_header (OpenMesh is off by one byte)"},
        {"a.off", "", "OFF\n# a cube\n8 6 12\n", GB_ERROR_UNSUPPORTED,
         "a.off:2: a comment ('#') in the body", "OFF comment (OpenMesh reads it as a number)"},
        {"a.off", "", "OFF\n3 4000000000 0\n0 0 0\n1 0 0\n0 1 0\n", GB_ERROR_FORMAT,
         "more than the file holds", "OFF face count beyond the file (OpenMesh loops over it)"},
        {"a.off", "", "4OFF\n", GB_ERROR_UNSUPPORTED, "4OFF and nOFF", "4OFF refused"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        char text[1024];
        snprintf(text, sizeof text, "%s%s", cases[i].head, cases[i].body);
        CHECK(check_fails(cases[i].name, text, strlen(text), cases[i].result, cases[i].message),
              cases[i].what);
    }
    CHECK(load_fails("lines.off", TEXT("OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n1 2\n"),
                     GB_ERROR_INVALID, "lines.off: no triangles (empty mesh, all degenerate)"),
          "OFF of a line and a point: degenerate faces, counted (was: faces unread, an index "
          "out of range)");
    gb_mesh_counts counts;
    gb_error error;
    CHECK(gb_mesh_check(TEXT("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2 0\n"), "q.off", &counts,
                        &error) == GB_OK && counts.vertices == 3 && counts.faces == 1,
          "a valid OFF passes, with its declared counts");
    CHECK(gb_mesh_check(TEXT("solid\nendsolid\n"), "e.stl", &counts, &error) == GB_OK &&
              counts.vertices == -1 && counts.faces == -1,
          "STL declares no counts");
}

int main(void)
{
    scratch_create("mesh");
    test_ascii_non_finite();
    test_binary_non_finite();
    test_guards();
    scratch_remove();
    return tap_done();
}
