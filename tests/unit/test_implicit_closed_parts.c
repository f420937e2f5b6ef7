/* test_implicit_closed_parts.c — which parts of a mesh have a back that can
 * be seen (runtime/implicit/implicit_closed_parts.h), on cubes built by
 * hand: the answers follow from how each mesh is made. The unit cube's
 * corners are numbered x + 2y + 4z; each face is listed counter-clockwise
 * seen from outside ((b - a) x (c - a) along the outward normal, checked
 * by hand for each face), so the whole cube is closed, wound
 * consistently, its fronts facing out.
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "../../runtime/implicit/implicit_closed_parts.h"
#include "tap.h"
#include "tap_printf.h"

/* -x, +x, -y, +y, -z, +z */
static const uint32_t cube_faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                          {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};

typedef struct mesh {
    float positions[3 * 64];
    uint32_t indices[3 * 64];
    uint32_t vertex_count, triangle_count;
} mesh;

static uint32_t add_vertex(mesh *m, const float offset[3], uint32_t corner)
{
    for (int k = 0; k < 3; ++k)
        m->positions[3 * m->vertex_count + k] = offset[k] + (float)((corner >> k) & 1);
    return m->vertex_count++;
}

/* A unit cube at offset, its faces but `missing` (-1: none); face
 * `flipped` wound the other way; all faces flipped when inward. Shared:
 * the faces index 8 shared corners; else each face has its own 4
 * vertices (matched by position only). */
static void add_cube(mesh *m, const float offset[3], int missing, int flipped, int inward,
                     int shared)
{
    uint32_t corner[8];
    for (uint32_t c = 0; shared && c < 8; ++c)
        corner[c] = add_vertex(m, offset, c);
    for (int f = 0; f < 6; ++f) {
        if (f == missing)
            continue;
        uint32_t q[4];
        for (int i = 0; i < 4; ++i)
            q[i] = shared ? corner[cube_faces[f][i]] : add_vertex(m, offset, cube_faces[f][i]);
        if ((f == flipped) != inward) {
            uint32_t t = q[1];
            q[1] = q[3];
            q[3] = t;
        }
        const uint32_t triangles[2][3] = {{q[0], q[1], q[2]}, {q[0], q[2], q[3]}};
        memcpy(&m->indices[3 * m->triangle_count], triangles, sizeof triangles);
        m->triangle_count += 2;
    }
}

/* Checks open[] against expected for triangles [first, first + count). */
static void check(const char *name, const mesh *m, const float *points, uint32_t point_count,
                  uint32_t first, uint32_t count, int expected)
{
    uint8_t open[64];
    gb_error error = {0};
    gb_result result = gb_implicit_open_triangles(m->positions, m->indices, m->triangle_count,
                                                  points, point_count, open, &error);
    int right = 0;
    for (uint32_t t = first; result == GB_OK && t < first + count; ++t)
        right += open[t] == expected;
    CHECK_EQ_INTF(right, count, "%s: %u triangles %s", name, count,
                  expected ? "open (two-sided)" : "closed (one-sided)");
}

int main(void)
{
    const float origin[3] = {0, 0, 0}, beside[3] = {3, 0, 0};
    mesh m = {0};
    add_cube(&m, origin, -1, -1, 0, 1);
    check("closed cube", &m, NULL, 0, 0, 12, 0);
    const float outside[3] = {2, 0.5f, 0.5f}, inside[3] = {0.5f, 0.5f, 0.5f};
    check("closed cube, a light outside", &m, outside, 1, 0, 12, 0);
    check("closed cube, a light inside", &m, inside, 1, 0, 12, 1);

    m = (mesh){0};
    add_cube(&m, origin, -1, -1, 0, 0);
    check("closed cube, faces matched by position", &m, NULL, 0, 0, 12, 0);

    m = (mesh){0};
    add_cube(&m, origin, 3, -1, 0, 1);
    check("cube, one face removed", &m, NULL, 0, 0, 10, 1);

    m = (mesh){0};
    add_cube(&m, origin, -1, 5, 0, 1);
    check("cube, one face's winding flipped", &m, NULL, 0, 0, 12, 1);

    m = (mesh){0};
    add_cube(&m, origin, -1, -1, 1, 1);
    check("cube wound inward (its fronts face the inside)", &m, NULL, 0, 0, 12, 1);

    m = (mesh){0};
    add_cube(&m, origin, -1, -1, 0, 1);
    add_cube(&m, beside, 0, -1, 0, 0);
    check("two parts: the closed cube", &m, NULL, 0, 0, 12, 0);
    check("two parts: the cube with a face removed", &m, NULL, 0, 12, 10, 1);

    /* a triangle with two corners at one position joins no part */
    m = (mesh){0};
    add_cube(&m, origin, -1, -1, 0, 1);
    const uint32_t degenerate[3] = {0, 0, 7};
    memcpy(&m.indices[3 * m.triangle_count++], degenerate, sizeof degenerate);
    check("closed cube and a triangle of no area", &m, NULL, 0, 0, 13, 0);
    return tap_done();
}
