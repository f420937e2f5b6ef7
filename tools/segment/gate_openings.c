/* gate_openings.c — the gates' disks fitted to the openings between the
 * clusters' voxels, and the opening gates (gate_openings.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "array_reserve.h"
#include "gate_openings.h"
#include "gate_pairs.h"

typedef struct opening {
    double count;
    double sum[3];              /* of face centres */
    double moment[6];           /* of face centres: xx yy zz xy xz yz */
    double normal[3];           /* sum of oriented face normals */
} opening;

/* The gate between clusters a and b whose anchor (its centre before any
 * fitting) is nearest to x, the smaller index on a tie; UINT32_MAX: none. */
static uint32_t gate_between(const gb_gate_pairs *pairs, const float (*anchors)[3], uint32_t a,
                             uint32_t b, const double x[3])
{
    uint32_t best = UINT32_MAX, first, count = gb_gate_pairs_find(pairs, a, b, &first);
    double best_d2 = INFINITY;
    for (uint32_t k = first; k < first + count; ++k) {
        uint32_t g = pairs->pairs[k].gate;
        double d2 = 0.0;
        for (int i = 0; i < 3; ++i)
            d2 += (x[i] - anchors[g][i]) * (x[i] - anchors[g][i]);
        if (d2 < best_d2) {
            best_d2 = d2;
            best = g;
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
    const gb_gate_pairs *pairs;
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
    uint32_t g = gate_between(f->pairs, f->anchors, (uint32_t)a, (uint32_t)b, centre);
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
    if (!gb_array_reserve(&list->pairs, &list->capacity, list->used + 1, sizeof *list->pairs)) {
        list->out_of_memory = 1;
        return 0;
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

/* Appends an opening gate for each touching pair that no gate joins. */
static void append_opening_gates(gb_segmentation *s, const gb_gate_pairs *joined,
                                 const uint64_t *pairs, size_t count)
{
    for (size_t i = 0; i < count; ++i) {
        uint32_t a = (uint32_t)(pairs[i] >> 32), b = (uint32_t)pairs[i], first;
        if (gb_gate_pairs_find(joined, a, b, &first))
            continue;
        /* centre, normal and radius come from the faces (fit_disk) */
        s->gates[s->gate_count++] = (gb_visibility_gate){.normal = {1.0f, 0.0f, 0.0f},
                                                         .radius = 0.0f,
                                                         .clusters = {a, b},
                                                         .edge = GB_SEGMENTATION_NO_EDGE};
    }
}

gb_result gb_gate_openings_add(gb_segmentation *s, const int32_t *voxel_clusters,
                               const uint8_t *surface, uint32_t *added, gb_error *error)
{
    *added = 0;
    size_t count = 0;
    gb_gate_pairs joined;
    gb_result result = gb_gate_pairs_build(s, &joined, error);
    if (result != GB_OK)
        return result;
    uint64_t *pairs = touching_pairs(s, voxel_clusters, surface, &count);
    gb_visibility_gate *gates =
        pairs ? realloc(s->gates, ((size_t)s->gate_count + count + 1) * sizeof *gates) : NULL;
    if (gates) {
        s->gates = gates;
        uint32_t old_count = s->gate_count;
        append_opening_gates(s, &joined, pairs, count);
        *added = s->gate_count - old_count;
    } else {
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "gate openings: out of memory");
    }
    free(pairs);
    gb_gate_pairs_free(&joined);
    return result;
}

/* The disks of the gates that have faces, from the openings gathered. */
static uint32_t fit_disks(gb_segmentation *s, const opening *openings)
{
    uint32_t fitted = 0;
    for (uint32_t g = 0; g < s->gate_count; ++g)
        if (openings[g].count > 0.0) {
            fit_disk(&openings[g], &s->gates[g]);
            ++fitted;
        }
    return fitted;
}

gb_result gb_gate_openings_fit(gb_segmentation *s, const int32_t *voxel_clusters,
                               const uint8_t *surface, uint32_t *fitted, gb_error *error)
{
    *fitted = 0;
    uint32_t count = s->gate_count;
    gb_gate_pairs pairs;
    gb_result result = gb_gate_pairs_build(s, &pairs, error);
    if (result != GB_OK)
        return result;
    opening *openings = calloc(count ? count : 1, sizeof *openings);
    float (*anchors)[3] = malloc((count ? count : 1) * sizeof *anchors);
    if (openings && anchors) {
        for (uint32_t g = 0; g < count; ++g)
            memcpy(anchors[g], s->gates[g].centre, sizeof anchors[g]);
        face_gathering gathering = {s, &pairs, (const float (*)[3])anchors, openings};
        visit_cluster_faces(s, voxel_clusters, surface, gather_face, &gathering);
        *fitted = fit_disks(s, openings);
    } else {
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "gate openings: out of memory");
    }
    free(openings);
    free(anchors);
    gb_gate_pairs_free(&pairs);
    return result;
}
