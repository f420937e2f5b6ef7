/* topo_gate_openings.c — each visibility gate's disk fitted to the opening
 * it stands for. segment places the paper's disk (Noël & Biri 2014, §IV.C)
 * at the middle of the segmented edge, radius min(maxball(n1), maxball(n2)):
 * the inscribed ball of the narrowest end, often far smaller than the real
 * separation between the two clusters (a court cut at mid-height: the disk
 * has the radius of the court's half width, the opening is the whole court).
 * The paper names the result (darker images, §VI.B) and suggests matching
 * the shape of the separation better.
 *
 * The separation is known exactly once the voxels have their clusters
 * (gb_segmentation_voxel_clusters): the faces between an empty voxel of cluster a
 * and an empty voxel of cluster b. Each such face goes to the gate between a
 * and b whose centre (before fitting) is nearest; a gate's new disk has the
 * faces' centroid as centre, their mean normal (oriented from clusters[0]
 * to clusters[1]) as normal, and the radius of the disk with the same second
 * moment in its plane, sqrt(2 <r^2>) (exact for faces filling a disk),
 * never below the paper's radius. A gate without faces keeps the paper's
 * disk.
 *
 * Gates come from the segmented skeleton's edges, but the voxels decide
 * which clusters touch: the nearest-node partition often makes two clusters
 * meet with no edge between them (a room's corner near an opening belongs
 * to the skeleton outside). gb_topo_gates_add_openings gives every such
 * pair of clusters a gate of its own (edge UINT32_MAX), fitted the same way,
 * so that light crosses every opening the voxels show.
 *
 * The caller owns everything; the gates are changed in place. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "topo.h"

typedef struct opening {
    double count;
    double sum[3];              /* of face centres */
    double moment[6];           /* of face centres: xx yy zz xy xz yz */
    double normal[3];           /* sum of oriented face normals */
} opening;

static uint32_t other_side(const gb_visibility_gate *gate, uint32_t c)
{
    return gate->clusters[0] == c ? gate->clusters[1] : gate->clusters[0];
}

/* The gate between clusters a and b whose anchor (its centre before any
 * fitting) is nearest to x; UINT32_MAX: none. */
static uint32_t gate_between(const gb_segmentation *s, const gb_topo_gates *gates,
                             const float (*anchors)[3], uint32_t a, uint32_t b, const double x[3])
{
    uint32_t best = UINT32_MAX;
    double best_d2 = INFINITY;
    for (uint32_t k = gates->offsets[a]; k < gates->offsets[a + 1]; ++k) {
        const gb_visibility_gate *g = &s->gates[gates->gates[k]];
        if (other_side(g, a) != b)
            continue;
        const float *anchor = anchors[gates->gates[k]];
        double d2 = 0.0;
        for (int i = 0; i < 3; ++i)
            d2 += (x[i] - anchor[i]) * (x[i] - anchor[i]);
        if (d2 < best_d2) {
            best_d2 = d2;
            best = gates->gates[k];
        }
    }
    return best;
}

static void add_face(opening *o, const double x[3], const double n[3])
{
    o->count += 1.0;
    for (int i = 0; i < 3; ++i) {
        o->sum[i] += x[i];
        o->normal[i] += n[i];
    }
    o->moment[0] += x[0] * x[0];
    o->moment[1] += x[1] * x[1];
    o->moment[2] += x[2] * x[2];
    o->moment[3] += x[0] * x[1];
    o->moment[4] += x[0] * x[2];
    o->moment[5] += x[1] * x[2];
}

/* The disk of the faces gathered in o (o->count > 0). */
static void fit_disk(const opening *o, gb_visibility_gate *gate)
{
    double c[3], n[3], length = 0.0;
    for (int i = 0; i < 3; ++i) {
        c[i] = o->sum[i] / o->count;
        length += o->normal[i] * o->normal[i];
    }
    length = sqrt(length);
    for (int i = 0; i < 3; ++i)
        n[i] = length > 0.0 ? o->normal[i] / length : gate->normal[i];
    /* covariance of the face centres */
    double m[6];
    for (int i = 0; i < 6; ++i)
        m[i] = o->moment[i] / o->count;
    double cov[3][3] = {
        {m[0] - c[0] * c[0], m[3] - c[0] * c[1], m[4] - c[0] * c[2]},
        {m[3] - c[0] * c[1], m[1] - c[1] * c[1], m[5] - c[1] * c[2]},
        {m[4] - c[0] * c[2], m[5] - c[1] * c[2], m[2] - c[2] * c[2]},
    };
    double trace = cov[0][0] + cov[1][1] + cov[2][2], along = 0.0;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            along += n[i] * cov[i][j] * n[j];
    double radius = sqrt(fmax(0.0, 2.0 * (trace - along)));
    for (int i = 0; i < 3; ++i) {
        gate->centre[i] = (float)c[i];
        if (length > 0.0)
            gate->normal[i] = (float)n[i];
    }
    gate->radius = fmaxf(gate->radius, (float)radius);
}

/* Calls face(user, ijk, axis, a, b) for every face between an empty voxel
 * of cluster a at ijk and one of another cluster b at ijk + 1 along axis
 * (surface voxels, when marked, are not empty); face returns 0 to stop. */
typedef int (*face_function)(void *user, const int32_t ijk[3], int axis, int32_t a, int32_t b);

static void visit_cluster_faces(const gb_segmentation *s, const int32_t *voxel_clusters,
                                const uint8_t *surface, face_function face, void *user)
{
    const int32_t *n = s->grid_size;
    size_t stride[3] = {1, (size_t)n[0], (size_t)n[0] * (size_t)n[1]};
    for (int32_t z = 0; z < n[2]; ++z)
        for (int32_t y = 0; y < n[1]; ++y)
            for (int32_t x = 0; x < n[0]; ++x) {
                size_t v = (size_t)x + (size_t)y * stride[1] + (size_t)z * stride[2];
                int32_t a = voxel_clusters[v], ijk[3] = {x, y, z};
                if (a < 0 || (surface && surface[v]))
                    continue;
                for (int axis = 0; axis < 3; ++axis) {
                    if (ijk[axis] + 1 >= n[axis])
                        continue;
                    size_t w = v + stride[axis];
                    int32_t b = voxel_clusters[w];
                    if (b < 0 || b == a || (surface && surface[w]))
                        continue;
                    if (!face(user, ijk, axis, a, b))
                        return;
                }
            }
}

typedef struct face_gathering {
    const gb_segmentation *s;
    const gb_topo_gates *gates;
    const float (*anchors)[3];
    opening *openings;
} face_gathering;

/* Adds the face to the opening of the nearest gate between its clusters. */
static int gather_face(void *user, const int32_t ijk[3], int axis, int32_t a, int32_t b)
{
    face_gathering *f = user;
    double centre[3], normal[3] = {0.0, 0.0, 0.0};
    for (int i = 0; i < 3; ++i)
        centre[i] = f->s->world_origin[i] +
                    (ijk[i] + 0.5 + (i == axis ? 0.5 : 0.0)) * f->s->voxel_size;
    uint32_t g = gate_between(f->s, f->gates, f->anchors, (uint32_t)a, (uint32_t)b, centre);
    if (g != UINT32_MAX) {
        normal[axis] = f->s->gates[g].clusters[0] == (uint32_t)a ? 1.0 : -1.0;
        add_face(&f->openings[g], centre, normal);
    }
    return 1;
}

typedef struct pair_list {
    uint64_t *pairs;            /* a < b, packed a << 32 | b */
    size_t used, capacity;
    int out_of_memory;
} pair_list;

static int add_pair(void *user, const int32_t ijk[3], int axis, int32_t a, int32_t b)
{
    (void)ijk;
    (void)axis;
    pair_list *list = user;
    if (list->used == list->capacity) {
        uint64_t *grown = realloc(list->pairs, 2 * list->capacity * sizeof *grown);
        if (!grown) {
            list->out_of_memory = 1;
            return 0;
        }
        list->pairs = grown;
        list->capacity *= 2;
    }
    uint64_t lo = (uint64_t)(a < b ? a : b), hi = (uint64_t)(a < b ? b : a);
    list->pairs[list->used++] = lo << 32 | hi;
    return 1;
}

static int compare_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* The pairs (a < b, packed a << 32 | b) of clusters whose empty voxels share
 * a face, sorted, each once; *count of them. NULL when out of memory. */
static uint64_t *touching_pairs(const gb_segmentation *s, const int32_t *voxel_clusters,
                                const uint8_t *surface, size_t *count)
{
    pair_list list = {malloc(1024 * sizeof *list.pairs), 0, 1024, 0};
    if (!list.pairs)
        return NULL;
    visit_cluster_faces(s, voxel_clusters, surface, add_pair, &list);
    if (list.out_of_memory) {
        free(list.pairs);
        return NULL;
    }
    qsort(list.pairs, list.used, sizeof *list.pairs, compare_u64);
    size_t unique = 0;
    for (size_t i = 0; i < list.used; ++i)
        if (unique == 0 || list.pairs[unique - 1] != list.pairs[i])
            list.pairs[unique++] = list.pairs[i];
    *count = unique;
    return list.pairs;
}

static int has_gate(const gb_segmentation *s, uint32_t a, uint32_t b)
{
    for (uint32_t g = 0; g < s->gate_count; ++g) {
        const uint32_t *c = s->gates[g].clusters;
        if ((c[0] == a && c[1] == b) || (c[0] == b && c[1] == a))
            return 1;
    }
    return 0;
}

gb_result gb_topo_gates_add_openings(gb_segmentation *s, const int32_t *voxel_clusters,
                                     const uint8_t *surface, uint32_t *added, gb_error *error)
{
    *added = 0;
    size_t count = 0;
    uint64_t *pairs = touching_pairs(s, voxel_clusters, surface, &count);
    if (!pairs)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "gate openings: out of memory");
    gb_visibility_gate *gates = realloc(s->gates, ((size_t)s->gate_count + count + 1) *
                                                      sizeof *gates);
    if (!gates) {
        free(pairs);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "gate openings: out of memory");
    }
    s->gates = gates;
    uint32_t old_count = s->gate_count;
    for (size_t i = 0; i < count; ++i) {
        uint32_t a = (uint32_t)(pairs[i] >> 32), b = (uint32_t)pairs[i];
        if (has_gate(s, a, b))
            continue;
        /* centre, normal and radius come from the faces (fit_disk) */
        s->gates[s->gate_count++] = (gb_visibility_gate){
            .normal = {1.0f, 0.0f, 0.0f}, .radius = 0.0f, .clusters = {a, b}, .edge = UINT32_MAX};
    }
    *added = s->gate_count - old_count;
    free(pairs);
    return GB_OK;
}

gb_result gb_topo_gates_fit_openings(gb_segmentation *s, const gb_topo_gates *gates,
                                     const int32_t *voxel_clusters, const uint8_t *surface,
                                     gb_error *error)
{
    uint32_t count = s->gate_count;
    opening *openings = calloc(count ? count : 1, sizeof *openings);
    float (*anchors)[3] = malloc((count ? count : 1) * sizeof *anchors);
    if (!openings || !anchors) {
        free(openings);
        free(anchors);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "gate openings: out of memory");
    }
    for (uint32_t g = 0; g < count; ++g)
        memcpy(anchors[g], s->gates[g].centre, sizeof anchors[g]);
    face_gathering gathering = {s, gates, (const float (*)[3])anchors, openings};
    visit_cluster_faces(s, voxel_clusters, surface, gather_face, &gathering);
    for (uint32_t g = 0; g < count; ++g)
        if (openings[g].count > 0.0)
            fit_disk(&openings[g], &s->gates[g]);
    free(openings);
    free(anchors);
    return GB_OK;
}
