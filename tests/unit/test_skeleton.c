/* test_skeleton.c — unit tests of formats/skeleton.[ch]: a round trip keeps
 * every field, the file does not depend on the host (bytes as FORMATS.md
 * says), and corrupt files are refused with a message, never read. */
#include "container.h"
#include "skeleton.h"
#include "scratch.h"
#include "tap.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A small valid skeleton: a square with a tail. */
static gb_skeleton sample(void)
{
    static gb_skeleton_node nodes[5] = {
        {{0.5f, 1.0f, -2.0f}, 0.25f}, {{1.0f, 1.0f, -2.0f}, 0.5f}, {{1.0f, 1.5f, -2.0f}, 0.75f},
        {{0.5f, 1.5f, -2.0f}, 1.0f},  {{1.5f, 1.5f, -2.0f}, 0.0f},
    };
    static uint32_t edges[10] = {0, 1, 0, 3, 1, 2, 2, 3, 2, 4};
    gb_skeleton s;
    memset(&s, 0, sizeof s);
    s.node_count = 5;
    s.edge_count = 5;
    s.nodes = nodes;
    s.edges = edges;
    s.voxel_size = 0.5;
    s.world_origin[0] = -1.0;
    s.world_origin[1] = 0.25;
    s.world_origin[2] = -3.5;
    s.grid_size[0] = 12;
    s.grid_size[1] = 7;
    s.grid_size[2] = 9;
    s.resolution = 12;
    s.scene_hash = 0xfedcba9876543210ull;
    s.persistence = 1.5;
    s.min_lifespan = 2.0;
    s.iterations = 17;
    s.cavities_broken = 3;
    return s;
}

static int same_skeleton(const gb_skeleton *a, const gb_skeleton *b)
{
    return a->node_count == b->node_count && a->edge_count == b->edge_count &&
           !memcmp(a->nodes, b->nodes, a->node_count * sizeof *a->nodes) &&
           !memcmp(a->edges, b->edges, 2 * a->edge_count * sizeof *a->edges) &&
           a->voxel_size == b->voxel_size &&
           !memcmp(a->world_origin, b->world_origin, sizeof a->world_origin) &&
           !memcmp(a->grid_size, b->grid_size, sizeof a->grid_size) &&
           a->resolution == b->resolution && a->scene_hash == b->scene_hash &&
           a->persistence == b->persistence && a->min_lifespan == b->min_lifespan &&
           a->iterations == b->iterations && a->cavities_broken == b->cavities_broken;
}

static void test_round_trip(void)
{
    gb_skeleton s = sample(), back;
    gb_error error;
    const char *path = scratch_path("sample.skel");
    CHECK_EQ_INT(gb_skeleton_write(path, &s, &error), GB_OK, "round trip: write");
    CHECK_EQ_INT(gb_skeleton_read(path, &back, &error), GB_OK, "round trip: read");
    CHECK(same_skeleton(&s, &back), "round trip: every field comes back");
    gb_skeleton_free(&back);

    size_t size = 0;
    unsigned char *bytes = scratch_read(path, &size);
    gb_container container;
    CHECK(bytes && gb_container_parse(bytes, size, path, "SKEL", &container, &error) == GB_OK,
          "layout: a SKEL container");
    const gb_section *header = gb_container_find(&container, "header");
    const gb_section *nodes = gb_container_find(&container, "nodes");
    const gb_section *edges = gb_container_find(&container, "edges");
    CHECK(header && header->size == 88 && nodes && nodes->size == 80 && edges && edges->size == 40,
          "layout: header 88 bytes, 16 per node, 8 per edge");
    CHECK_EQ_INT(container.version, GB_SKELETON_VERSION, "layout: format version");
    if (header && nodes && edges) {
        const unsigned char *h = header->data, *n = nodes->data, *e = edges->data;
        CHECK(h[0] == 5 && h[1] == 0 && h[4] == 5, "layout: counts little-endian at 0 and 4");
        CHECK(h[56] == 0x10 && h[63] == 0xfe, "layout: scene hash little-endian at 56");
        float radius;
        memcpy(&radius, n + 16 + 12, 4);
        CHECK(radius == 0.5f, "layout: node radius at byte 12 of the node");
        CHECK(e[32] == 2 && e[36] == 4, "layout: edge pairs of u32");
    }
    gb_container_close(&container);
    free(bytes);

    gb_skeleton empty;
    memset(&empty, 0, sizeof empty);
    empty.voxel_size = 1.0;
    empty.grid_size[0] = empty.grid_size[1] = empty.grid_size[2] = 1;
    CHECK_EQ_INT(gb_skeleton_write(scratch_path("empty.skel"), &empty, &error), GB_OK,
                 "round trip: a skeleton without nodes is written");
    CHECK_EQ_INT(gb_skeleton_read(scratch_path("empty.skel"), &back, &error), GB_OK,
                 "round trip: and read back");
    CHECK(back.node_count == 0 && back.edge_count == 0, "round trip: still empty");
    gb_skeleton_free(&back);
}

/* Writes a SKEL container made of the given sections (bypassing the
 * writer's checks) and returns what the reader says. */
static gb_result read_crafted(const void *header, uint64_t header_size, const void *nodes,
                              uint64_t node_size, const void *edges, uint64_t edge_size,
                              uint32_t version, gb_error *error)
{
    const char *path = scratch_path("crafted.skel");
    gb_container_writer *w = gb_container_writer_create("SKEL", version);
    if (header)
        gb_container_add(w, "header", header, header_size, NULL);
    if (nodes)
        gb_container_add(w, "nodes", nodes, node_size, NULL);
    if (edges)
        gb_container_add(w, "edges", edges, edge_size, NULL);
    gb_container_commit(w, path, NULL);
    gb_container_writer_destroy(w);
    gb_skeleton s;
    gb_result result = gb_skeleton_read(path, &s, error);
    int zeroed = s.nodes == NULL && s.edges == NULL && s.node_count == 0;
    if (!result)
        gb_skeleton_free(&s);
    else if (!zeroed)
        return (gb_result)-1;
    return result;
}

static void put32(unsigned char *p, uint32_t v)
{
    for (int i = 0; i < 4; ++i)
        p[i] = (unsigned char)(v >> (8 * i));
}

static void put64f(unsigned char *p, double v)
{
    uint64_t bits;
    memcpy(&bits, &v, 8);
    for (int i = 0; i < 8; ++i)
        p[i] = (unsigned char)(bits >> (8 * i));
}

static void valid_header(unsigned char h[88], uint32_t nodes, uint32_t edges)
{
    memset(h, 0, 88);
    put32(h, nodes);
    put32(h + 4, edges);
    put64f(h + 8, 0.5);
    put32(h + 40, 4);
    put32(h + 44, 4);
    put32(h + 48, 4);
    put64f(h + 64, 1.0);
}

static void test_rejections(void)
{
    gb_error error;
    unsigned char header[88], nodes[32], edges[8];
    float node_values[8] = {0, 0, 0, 1, 0.5f, 0, 0, 1};
    memcpy(nodes, node_values, sizeof nodes);
    put32(edges, 0);
    put32(edges + 4, 1);

    valid_header(header, 2, 1);
    /* The valid file, then a section short or missing, one at a time. */
    const struct {
        const void *header;
        uint64_t header_size;
        const void *nodes;
        uint64_t node_size, edge_size;
        gb_result result;
        const char *what;
        int names_nodes;        /* the message names the nodes section */
    } sections[] = {
        {header, 88, nodes, 32, 8, GB_OK, "crafted: the valid file is read", 0},
        {header, 80, nodes, 32, 8, GB_ERROR_FORMAT, "rejects: a short header", 0},
        {header, 88, nodes, 16, 8, GB_ERROR_FORMAT,
         "rejects: fewer node bytes than the count says", 1},
        {header, 88, nodes, 32, 0, GB_ERROR_FORMAT,
         "rejects: fewer edge bytes than the count says", 0},
        {header, 88, NULL, 0, 8, GB_ERROR_FORMAT, "rejects: a missing nodes section", 0},
        {NULL, 0, nodes, 32, 8, GB_ERROR_FORMAT, "rejects: a missing header", 0},
    };
    for (size_t i = 0; i < sizeof sections / sizeof *sections; ++i) {
        CHECK_EQ_INT(read_crafted(sections[i].header, sections[i].header_size, sections[i].nodes,
                                  sections[i].node_size, edges, sections[i].edge_size, 1,
                                  &error),
                     sections[i].result, sections[i].what);
        if (sections[i].names_nodes)
            CHECK(strstr(error.message, "nodes") != NULL,
                  "rejects: the message names the section");
    }
    CHECK(read_crafted(header, 88, nodes, 32, edges, 8, 2, &error) != GB_OK,
          "rejects: a newer format version");

    put32(edges + 4, 2);
    CHECK_EQ_INT(read_crafted(header, 88, nodes, 32, edges, 8, 1, &error), GB_ERROR_INVALID,
                 "rejects: an edge to a node that does not exist");
    put32(edges + 4, 0);
    CHECK_EQ_INT(read_crafted(header, 88, nodes, 32, edges, 8, 1, &error), GB_ERROR_INVALID,
                 "rejects: an edge from a node to itself");
    put32(edges + 4, 1);

    float bad = NAN;
    memcpy(nodes + 4, &bad, 4);
    CHECK_EQ_INT(read_crafted(header, 88, nodes, 32, edges, 8, 1, &error), GB_ERROR_INVALID,
                 "rejects: a NaN position");
    memcpy(nodes + 4, &node_values[1], 4);
    bad = -1.0f;
    memcpy(nodes + 12, &bad, 4);
    CHECK_EQ_INT(read_crafted(header, 88, nodes, 32, edges, 8, 1, &error), GB_ERROR_INVALID,
                 "rejects: a negative radius");
    bad = INFINITY;
    memcpy(nodes + 12, &bad, 4);
    CHECK_EQ_INT(read_crafted(header, 88, nodes, 32, edges, 8, 1, &error), GB_ERROR_INVALID,
                 "rejects: an infinite radius");
    memcpy(nodes + 12, &node_values[3], 4);

    put64f(header + 8, 0.0);
    CHECK_EQ_INT(read_crafted(header, 88, nodes, 32, edges, 8, 1, &error), GB_ERROR_INVALID,
                 "rejects: a zero voxel size");
    valid_header(header, 2, 1);
    put32(header + 44, 0);
    CHECK_EQ_INT(read_crafted(header, 88, nodes, 32, edges, 8, 1, &error), GB_ERROR_INVALID,
                 "rejects: a zero grid size");
    valid_header(header, 0xffffffffu, 1);
    CHECK_EQ_INT(read_crafted(header, 88, nodes, 32, edges, 8, 1, &error), GB_ERROR_FORMAT,
                 "rejects: a huge node count");

    unsigned char two_edges[16];
    put32(two_edges, 0);
    put32(two_edges + 4, 1);
    put32(two_edges + 8, 0);
    put32(two_edges + 12, 1);
    valid_header(header, 2, 2);
    CHECK_EQ_INT(read_crafted(header, 88, nodes, 32, two_edges, 16, 1, &error), GB_ERROR_INVALID,
                 "rejects: a repeated edge");
}

static void test_corrupt_bytes(void)
{
    gb_skeleton s = sample(), back;
    gb_error error;
    const char *path = scratch_path("corrupt.skel");
    gb_skeleton_write(path, &s, &error);
    size_t size = 0;
    unsigned char *bytes = scratch_read(path, &size);
    int refused = 0, crashed_or_accepted = 0;
    for (size_t i = 0; i < size; ++i) {
        bytes[i] ^= 0x5a;
        gb_result result = gb_skeleton_parse(bytes, size, path, &back, &error);
        if (result)
            ++refused;
        else {
            ++crashed_or_accepted;
            gb_skeleton_free(&back);
        }
        bytes[i] ^= 0x5a;
    }
    CHECK_EQ_INT(crashed_or_accepted, 0, "corrupt: every flipped byte is refused");
    int truncated_accepted = 0;
    for (size_t cut = 0; cut < size; cut += 7)
        if (gb_skeleton_parse(bytes, cut, path, &back, &error) == GB_OK) {
            ++truncated_accepted;
            gb_skeleton_free(&back);
        }
    CHECK_EQ_INT(truncated_accepted, 0, "corrupt: every truncation is refused");
    CHECK(refused > 0, "corrupt: messages given");
    free(bytes);

    CHECK(gb_skeleton_read(scratch_path("missing.skel"), &back, &error) == GB_ERROR_IO &&
              strstr(error.message, "missing.skel") != NULL,
          "corrupt: a missing file names the path");
    gb_skeleton bad = sample();
    bad.edges = (uint32_t[]){0, 9};
    bad.edge_count = 1;
    CHECK_EQ_INT(gb_skeleton_write(scratch_path("bad.skel"), &bad, &error), GB_ERROR_INVALID,
                 "writer: refuses an edge out of range");
    CHECK(access(scratch_path("bad.skel"), F_OK) != 0, "writer: and writes nothing");
}

int main(void)
{
    scratch_create("skeleton");
    test_round_trip();
    test_rejections();
    test_corrupt_bytes();
    scratch_remove();
    return tap_done();
}
