/* implicit_links.c — the hierarchical link structure (Dong 2007, 4.2):
 * CreateHierarchicalLinks links the root of all with itself (every pair of
 * children of implicit_hierarchy.c's tree, recursively) under the paper's
 * two rules of 4.2.2: (1) B is subdivided when it covers more than
 * GB_IMPLICIT_SPLIT of the bin its link falls in, (2) each bin keeps only
 * its shortest link. Links are stored at both ends; an open part's
 * element has bins on both sides of its plane (a link may see a front or a
 * back, implicit_closed_parts.h); a "mixed" pair, one end's front seeing
 * the other's back, keeps BACK_SHRINK of its disc and splits at
 * ONE_WAY_SPLIT. Beyond the paper, every link is also stored in each bin
 * its disc covers (implicit_disc_bins.h), so that no bin sees through a
 * surface. RefineHierarchicalLinks and PushdownLinks run as one
 * breadth-first pass (4.2.4).
 *
 * Threads: the recursion's first levels are unfolded into independent
 * pairs; a bin keeps the smallest packed (distance, node) word
 * (gb_implicit_pack_link), set by compare-and-swap, so the links do not
 * depend on the order of the stores or on the thread count.
 *
 * Why each rule and threshold is as it is, the cases the paper leaves open
 * ("Decided here") and what each measured: docs/methods.md, "How the links
 * are built", and docs/figures.md, "The link rules' thresholds".
 */
#include "implicit_links.h"

#include "array_reserve.h"
#include "brdf.h"
#include "huge_pages.h"
#include "implicit_disc_bins.h"
#include "implicit_link_lists.h"
#include "progress.h"
#include "vec3.h"
#include "work_queue.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* A disc covering fewer bins than COVER_EXACTLY is spread at points, at
 * most SPREAD_MAX (store_disc). */
enum { COVER_EXACTLY = 4, SPREAD_MAX = 3 * COVER_EXACTLY + 1 };
/* sqrt(pi / 2): the circle through the corners of a square of the disc's
 * area, over the disc's radius. */
#define DISC_WIDENING 1.2533141f
/* A disc of a mixed pair (see the top) is stored over this fraction of its
 * radius, so that past a convex edge it does not hide the sky beyond its
 * surface. Half keeps the disc's middle, where a near surface is seen
 * through most bins (measured: docs/figures.md, "The link rules'
 * thresholds"). */
#define BACK_SHRINK 0.5f

/* On several threads, unfolding stops at this many tasks: enough for two
 * threads to end together (the pairs differ in cost by orders of
 * magnitude). One thread runs the recursion as it is, a single task. */
enum { TASKS_WANTED = 4096 };

/* CreateHierarchicalLinks' share of the progress reported: it takes 87-95 %
 * of the links' time (docs/figures.md, bench/implicit.sh and
 * implicit_large.sh). */
#define CREATE_SHARE 0.9

/* Rule 1's threshold: B is subdivided when it covers more than this
 * fraction of a bin. With the paper's whole bin, a cluster's centre and a
 * smaller node in the same bin compete by centre distance, and an area
 * light just under the Cornell box's ceiling lost a fifth of its light to
 * the ceiling's clusters (docs/figures.md, "The link rules' thresholds"). */
#define GB_IMPLICIT_SPLIT 0.1f
/* The same for a mixed pair (see the top), which past a convex edge sees
 * little of the other: coarser than GB_IMPLICIT_SPLIT for speed, within
 * test_implicit's 2 % of brute force (docs/figures.md, "The link rules'
 * thresholds"). */
#define ONE_WAY_SPLIT 0.3f

/* What every pair test or link of a node would compute again, made once
 * (node_frames): its disc's radius (sqrt(area / pi)) and two unit
 * tangents, and the span of its box along its own normal (box_span). */
typedef struct node_frame {
    float radius;
    float tangent[2][3];
    float lowest, highest;
} node_frame;

typedef struct linker {
    const gb_implicit_model *model;
    const gb_implicit_bins *bins;
    uint64_t *slot;             /* node_count * bins: gb_implicit_pack_link, or
                                   GB_IMPLICIT_EMPTY_SLOT */
    float epsilon;              /* a length far below the element size */
    float spiral[SPREAD_MAX][2];/* cos, sin of the golden angle times i */
    float spiral_radius[SPREAD_MAX + 1][SPREAD_MAX];  /* [count][i]: sqrt((i + 1/2) / count),
                                   the i-th of count points' radius over the disc's */
    node_frame *frames;         /* node_count, made once (node_frames) */
    int depths;                 /* depth maps wanted (flc-iv): they only hide */
    int paper_rules;            /* rule 1 at a whole bin, no discs
                                   (gb_implicit_link_options.paper_rules) */
} linker;

static int is_leaf(const gb_implicit_node *node)
{
    return node->child_count == 0;
}

/* The min and max of dot(n, x) over the node's box (the comparisons
 * written out: fmaxf and fminf are library calls at -O2, a few % of link
 * time). */
static void box_span(const gb_implicit_node *node, const float n[3], float *lowest,
                     float *highest)
{
    float low = 0.0f, high = 0.0f;
    for (int k = 0; k < 3; ++k) {
        float a = n[k] * node->box_min[k], b = n[k] * node->box_max[k];
        low += a < b ? a : b;
        high += a > b ? a : b;
    }
    *lowest = low;
    *highest = high;
}

/* The sine of the angle between the unit normals of a and b: a disc of
 * either reaches its radius times it along the other's normal. */
static float normals_sine(const gb_implicit_node *a, const gb_implicit_node *b)
{
    float c = gb_dot3(b->normal, a->normal);
    float sine2 = 1.0f - c * c;
    return sine2 > 0.0f ? sqrtf(sine2) : 0.0f;
}

/* The sides of node a that some of node b (its box, widened by its disc)
 * may lie on: bit GB_IMPLICIT_FRONT set when b reaches in front of a's
 * plane, bit GB_IMPLICIT_BACK behind it when a has a back
 * (gb_implicit_node_two_sided); both for nodes of no side. */
enum { SEES_FRONT = 1 << GB_IMPLICIT_FRONT, SEES_BACK = 1 << GB_IMPLICIT_BACK };

/* sine: normals_sine(a, b), which the two ends share. */
static int sides_seen(const linker *l, uint32_t a, uint32_t b, float sine)
{
    const gb_implicit_node *na = &l->model->nodes[a], *nb = &l->model->nodes[b];
    if (!gb_implicit_node_has_side(na) || !gb_implicit_node_has_side(nb))
        return SEES_FRONT | SEES_BACK;
    float reach = l->frames[b].radius * sine, lowest, highest;
    box_span(nb, na->normal, &lowest, &highest);
    int front = highest + reach > l->frames[a].lowest + l->epsilon;
    int back = gb_implicit_node_two_sided(l->model, na) &&
               lowest - reach < l->frames[a].highest - l->epsilon;
    return (front ? SEES_FRONT : 0) | (back ? SEES_BACK : 0);
}

/* Rule 2: x keeps the link to y in bin when no shorter one is there (an
 * atomic minimum: other threads store into the same bins). */
static void store(linker *l, uint32_t x, int bin, uint32_t y, float distance)
{
    if (bin < 0)
        return;
    uint64_t *slot = &l->slot[(size_t)x * l->bins->count + (uint32_t)bin];
    uint64_t link = gb_implicit_pack_link(y, distance);
    uint64_t held = __atomic_load_n(slot, __ATOMIC_RELAXED);
    while (link < held && !__atomic_compare_exchange_n(slot, &held, link, 1, __ATOMIC_RELAXED,
                                                       __ATOMIC_RELAXED)) {
    }
}

static void tangents(const float n[3], float t[2][3])
{
    float helper[3] = {0, 0, 0};
    helper[fabsf(n[0]) < 0.6f ? 0 : 1] = 1.0f;
    t[0][0] = n[1] * helper[2] - n[2] * helper[1];
    t[0][1] = n[2] * helper[0] - n[0] * helper[2];
    t[0][2] = n[0] * helper[1] - n[1] * helper[0];
    float length = sqrtf(t[0][0] * t[0][0] + t[0][1] * t[0][1] + t[0][2] * t[0][2]);
    for (int k = 0; k < 3; ++k)
        t[0][k] /= length > 0.0f ? length : 1.0f;
    t[1][0] = n[1] * t[0][2] - n[2] * t[0][1];
    t[1][1] = n[2] * t[0][0] - n[0] * t[0][2];
    t[1][2] = n[0] * t[0][1] - n[1] * t[0][0];
}

static node_frame *node_frames(const gb_implicit_model *model)
{
    node_frame *frames = malloc((size_t)model->node_count * sizeof *frames + 1);
    for (uint32_t n = 0; frames && n < model->node_count; ++n) {
        const gb_implicit_node *node = &model->nodes[n];
        frames[n].radius = sqrtf(node->area / GB_PI);
        tangents(node->normal, frames[n].tangent);
        box_span(node, node->normal, &frames[n].lowest, &frames[n].highest);
    }
    return frames;
}

/* Whether direction d from a lies on the side of a's plane facing
 * (1 front, -1 back; 0: either). */
static int on_side(const gb_implicit_node *na, const float d[3], float facing)
{
    return facing == 0.0f || !gb_implicit_node_has_side(na) ||
           facing * gb_dot3(d, na->normal) > 0.0f;
}

/* A bin of a's through which a sees b's disc (gb_implicit_disc_bins). */
typedef struct covered_bin_link {
    linker *l;
    uint32_t a, b;
    float facing;
} covered_bin_link;

static void store_covered_bin(void *user, int bin, float distance)
{
    covered_bin_link *c = user;
    if (on_side(&c->l->model->nodes[c->a], &c->l->bins->directions[3 * bin], c->facing))
        store(c->l, c->a, bin, c->b, distance);
}

/* b stored in every bin of a's side facing whose centre direction meets
 * b's disc, none when a lies in its plane (it is seen edge on). */
static void cover_near_disc(linker *l, uint32_t a, uint32_t b, float radius, float facing)
{
    const gb_implicit_node *na = &l->model->nodes[a], *nb = &l->model->nodes[b];
    float offset[3] = {na->position[0] - nb->position[0], na->position[1] - nb->position[1],
                       na->position[2] - nb->position[2]};
    if (fabsf(gb_dot3(offset, nb->normal)) <= l->epsilon)
        return;
    covered_bin_link c = {l, a, b, facing};
    gb_implicit_disc_bins(l->bins, na->position, nb->position, nb->normal,
                          DISC_WIDENING * radius, store_covered_bin, &c);
}

/* b stored in the bins of points spread over its disc, as seen from a, on
 * its side facing. */
static void spread_far_disc(linker *l, uint32_t a, uint32_t b, float radius, float covered_bins,
                            float facing)
{
    const gb_implicit_node *na = &l->model->nodes[a], *nb = &l->model->nodes[b];
    const node_frame *disc = &l->frames[b];
    int count = covered_bins < 1.0f ? 3 : (int)ceilf(3.0f * covered_bins + 1.0f);
    const float(*t)[3] = disc->tangent;
    for (int i = 0; i < count; ++i) {
        float r = radius * l->spiral_radius[count][i];
        float d[3];
        for (int k = 0; k < 3; ++k)
            d[k] = nb->position[k] + r * (l->spiral[i][0] * t[0][k] + l->spiral[i][1] * t[1][k]) -
                   na->position[k];
        if (on_side(na, d, facing))
            store(l, a, gb_implicit_bin(l->bins->n, d), b, sqrtf(gb_dot3(d, d)));
    }
}

/* b stored in the bins its disc covers as seen from a (see the top), on
 * a's side facing (1 front, -1 back, 0 both). */
static void store_disc(linker *l, uint32_t a, uint32_t b, float radius, float covered_bins,
                       float facing)
{
    if (covered_bins >= COVER_EXACTLY)
        cover_near_disc(l, a, b, radius, facing);
    else
        spread_far_disc(l, a, b, radius, covered_bins, facing);
}

static void link_nodes(linker *l, uint32_t a, uint32_t b);

static void link_children(linker *l, uint32_t parent, uint32_t other)
{
    const gb_implicit_node *p = &l->model->nodes[parent];
    for (uint32_t c = 0; c < p->child_count; ++c)
        link_nodes(l, l->model->children[p->first_child + c], other);
}

static void link_within(linker *l, uint32_t a)
{
    const gb_implicit_node *n = &l->model->nodes[a];
    for (uint32_t i = 0; i < n->child_count; ++i)
        for (uint32_t j = i; j < n->child_count; ++j)
            link_nodes(l, l->model->children[n->first_child + i],
                       l->model->children[n->first_child + j]);
}

/* What link_nodes does with two different nodes: nothing (they cannot see
 * each other), subdivide one of them (rule 1), or link them. */
typedef enum { PAIR_UNSEEN, PAIR_SPLIT_A, PAIR_SPLIT_B, PAIR_LINKED } pair_step;

typedef struct pair_geometry {
    float d[3], back[3], r2;    /* a to b, b to a, squared distance */
    int bin_a, bin_b;           /* the bins of d at a and of back at b */
    float omega_a, omega_b;     /* their solid angles */
    int matched;                /* the boxes see the same side both ways */
    float sine;                 /* normals_sine(a, b): a disc of either reaches
                                   its radius times it along the other's normal */
} pair_geometry;

static pair_step pair_step_of(const linker *l, uint32_t a, uint32_t b, pair_geometry *g)
{
    const gb_implicit_node *na = &l->model->nodes[a], *nb = &l->model->nodes[b];
    /* A node of no area (degenerate triangles only) neither sends nor hides. */
    if (!(na->area > 0.0f) || !(nb->area > 0.0f))
        return PAIR_UNSEEN;
    g->sine = normals_sine(na, nb);
    int at_a = sides_seen(l, a, b, g->sine), at_b = sides_seen(l, b, a, g->sine);
    if (!at_a && !at_b)
        return PAIR_UNSEEN;
    /* front to front or back to back: a pair that is not mixed (see the top) */
    int matched = at_a & at_b;
    g->matched = matched;
    float split = l->paper_rules ? 1.0f : matched ? GB_IMPLICIT_SPLIT : ONE_WAY_SPLIT;
    g->r2 = 0.0f;
    for (int k = 0; k < 3; ++k) {
        g->d[k] = nb->position[k] - na->position[k];
        g->back[k] = -g->d[k];
        g->r2 += g->d[k] * g->d[k];
    }
    g->bin_a = gb_implicit_bin(l->bins->n, g->d);
    g->bin_b = gb_implicit_bin(l->bins->n, g->back);
    g->omega_a = g->bin_a < 0 ? 0.0f : l->bins->solid_angles[g->bin_a];
    g->omega_b = g->bin_b < 0 ? 0.0f : l->bins->solid_angles[g->bin_b];
    int split_b = !is_leaf(nb) && nb->area > split * g->omega_a * g->r2;
    int split_a = !is_leaf(na) && na->area > split * g->omega_b * g->r2;
    if (split_a && (!split_b || na->area >= nb->area))
        return PAIR_SPLIT_A;
    return split_b ? PAIR_SPLIT_B : PAIR_LINKED;
}

/* b linked at a on a's side facing (1 front, -1 back), when some of b's
 * disc lies on that side: height_b is b's centre's height over a's plane,
 * height_a a's over b's (positive: a sees b's front). */
static void link_side(linker *l, uint32_t a, uint32_t b, const pair_geometry *g, int bin,
                      float omega, float height_b, float height_a, float facing)
{
    const gb_implicit_node *na = &l->model->nodes[a], *nb = &l->model->nodes[b];
    if (facing * height_b + l->frames[b].radius * g->sine <= 0.0f)
        return;
    if (facing * height_b > 0.0f)
        store(l, a, bin, b, sqrtf(g->r2));
    /* B's centre in front of A with A's box reaching in front of B: A is
     * an element of a surface that runs on past B (under a wall), not
     * past a convex edge; B's whole disc hides, as before the shrink */
    if (l->paper_rules)
        return;
    int mixed = facing * height_a < 0.0f &&
                !(l->depths && g->matched && facing * height_b > 0.0f);
    store_disc(l, a, b, l->frames[b].radius * (mixed ? BACK_SHRINK : 1.0f),
               nb->area / (omega * g->r2), gb_implicit_node_has_side(na) ? facing : 0.0f);
}

/* The link between a and b in the bins their discs cover, at each end on
 * each side that has the other (some of its disc) out of its plane. A
 * node of no side has one, facing every way; a node of a closed part one,
 * its front (gb_implicit_node_two_sided). */
static void link_pair(linker *l, uint32_t a, uint32_t b, const pair_geometry *g)
{
    const gb_implicit_node *na = &l->model->nodes[a], *nb = &l->model->nodes[b];
    float r = sqrtf(g->r2);
    float height_b = gb_implicit_node_has_side(na) ? gb_dot3(g->d, na->normal) : r;
    float height_a = gb_implicit_node_has_side(nb) ? gb_dot3(g->back, nb->normal) : r;
    if (g->bin_a < 0)
        return;
    /* the slots of the two centres' bins, far apart in memory: b's is
     * stored into after all of a's work (a cache miss each, the largest
     * single cost of a link's stores) */
    __builtin_prefetch(&l->slot[(size_t)a * l->bins->count + (uint32_t)g->bin_a], 1);
    if (g->bin_b >= 0)
        __builtin_prefetch(&l->slot[(size_t)b * l->bins->count + (uint32_t)g->bin_b], 1);
    for (int side = 0; side < GB_IMPLICIT_SIDES; ++side) {
        float facing = side == GB_IMPLICIT_FRONT ? 1.0f : -1.0f;
        if (side == GB_IMPLICIT_FRONT || gb_implicit_node_two_sided(l->model, na))
            link_side(l, a, b, g, g->bin_a, g->omega_a, height_b, height_a, facing);
        if (side == GB_IMPLICIT_FRONT || gb_implicit_node_two_sided(l->model, nb))
            link_side(l, b, a, g, g->bin_b, g->omega_b, height_a, height_b, facing);
    }
}

/* The link between a and b, or between their children (rule 1). */
static void link_nodes(linker *l, uint32_t a, uint32_t b)
{
    if (a == b) {
        link_within(l, a);
        return;
    }
    pair_geometry g;
    switch (pair_step_of(l, a, b, &g)) {
    case PAIR_SPLIT_A:
        link_children(l, a, b);
        break;
    case PAIR_SPLIT_B:
        link_children(l, b, a);
        break;
    case PAIR_LINKED:
        link_pair(l, a, b, &g);
        break;
    case PAIR_UNSEEN:
        break;
    }
}

/* ---- the recursion's first levels as tasks for the threads ---- */

typedef struct link_task {
    uint32_t a, b;              /* link_nodes(a, b) */
} link_task;

typedef struct task_list {
    link_task *items;
    size_t count, capacity;
} task_list;

static int push_task(task_list *list, uint32_t a, uint32_t b)
{
    if (!gb_array_reserve(&list->items, &list->capacity, list->count + 1, sizeof *list->items))
        return 0;
    list->items[list->count++] = (link_task){a, b};
    return 1;
}

/* The calls link_nodes(t.a, t.b) makes one level down, in its order,
 * appended to next (a pair to be linked stays as it is); *grew is set when
 * it made any. Returns 0 when out of memory. */
static int unfold_task(const linker *l, link_task t, task_list *next, int *grew)
{
    const gb_implicit_node *nodes = l->model->nodes;
    const uint32_t *children = l->model->children;
    if (t.a == t.b) {
        const gb_implicit_node *n = &nodes[t.a];
        for (uint32_t i = 0; i < n->child_count; ++i)
            for (uint32_t j = i; j < n->child_count; ++j)
                if (!push_task(next, children[n->first_child + i], children[n->first_child + j]))
                    return 0;
        *grew = 1;
        return 1;
    }
    pair_geometry g;
    pair_step step = pair_step_of(l, t.a, t.b, &g);
    if (step == PAIR_LINKED)
        return push_task(next, t.a, t.b);
    if (step == PAIR_UNSEEN)
        return 1;
    uint32_t split = step == PAIR_SPLIT_A ? t.a : t.b, other = step == PAIR_SPLIT_A ? t.b : t.a;
    const gb_implicit_node *p = &nodes[split];
    for (uint32_t c = 0; c < p->child_count; ++c)
        if (!push_task(next, children[p->first_child + c], other))
            return 0;
    *grew = 1;
    return 1;
}

/* link_nodes(top, top) unfolded into about wanted tasks. */
static gb_result unfold_tasks(const linker *l, size_t wanted, task_list *tasks, gb_error *error)
{
    if (!push_task(tasks, l->model->top, l->model->top))
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    task_list next = {0};
    int grew = 1;
    while (grew && tasks->count < wanted) {
        grew = 0;
        next.count = 0;
        for (size_t i = 0; i < tasks->count; ++i)
            if (!unfold_task(l, tasks->items[i], &next, &grew)) {
                free(next.items);
                return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
            }
        task_list swap = *tasks;
        *tasks = next;
        next = swap;
    }
    free(next.items);
    return GB_OK;
}

typedef struct task_run {
    linker *linker;
    const link_task *tasks;
} task_run;

static int run_task(void *context, uint64_t item)
{
    task_run *run = context;
    link_nodes(run->linker, run->tasks[item].a, run->tasks[item].b);
    return 0;
}

/* CreateHierarchicalLinks: the root of all with itself, on threads (or
 * every pair of elements, on one), reporting the fraction of its tasks
 * started to options' progress, as CREATE_SHARE of the whole. */
static gb_result create_hierarchical_links(linker *l, int hierarchical, int threads,
                                           const gb_implicit_link_options *options,
                                           gb_error *error)
{
    const gb_implicit_model *m = l->model;
    if (!hierarchical) {
        for (uint32_t i = 0; i < m->element_count; ++i)
            for (uint32_t j = i + 1; j < m->element_count; ++j)
                link_nodes(l, i, j);
        return GB_OK;
    }
    task_list tasks = {0};
    gb_result result = unfold_tasks(l, threads > 1 ? TASKS_WANTED : 1, &tasks, error);
    if (result == GB_OK) {
        task_run run = {l, tasks.items};
        gb_progress_span span = {options ? options->progress : NULL,
                                 options ? options->progress_user : NULL, 0.0, CREATE_SHARE};
        gb_work_queue queue = {.item_count = tasks.count, .threads = threads,
                               .progress = gb_progress_span_report, .progress_user = &span};
        if (gb_work_queue_run(&queue, run_task, &run, NULL) != GB_OK)
            result = gb_fail(error, GB_ERROR_INTERRUPTED, "implicit: links interrupted");
    }
    free(tasks.items);
    return result;
}

/* RefineHierarchicalLinks + PushdownLinks, breadth first from the top. */
static gb_result refine_and_push_down(linker *l, gb_error *error)
{
    const gb_implicit_model *m = l->model;
    uint32_t *queue = malloc(((size_t)m->node_count + 1) * sizeof *queue), head = 0, tail = 0;
    if (!queue)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    queue[tail++] = m->top;
    uint32_t count = l->bins->count;
    while (head < tail) {
        const gb_implicit_node *parent = &m->nodes[queue[head]];
        const uint64_t *parent_slot = &l->slot[(size_t)queue[head] * count];
        ++head;
        for (uint32_t c = 0; c < parent->child_count; ++c) {
            uint32_t child = m->children[parent->first_child + c];
            uint64_t *slot = &l->slot[(size_t)child * count];
            /* a strictly shorter link (an empty slot's distance bits are all
             * ones: the longest) */
            for (uint32_t b = 0; b < count; ++b)
                if ((parent_slot[b] >> 32) < (slot[b] >> 32))
                    slot[b] = parent_slot[b];
            queue[tail++] = child;
        }
    }
    free(queue);
    return GB_OK;
}

/* The node of every slot, in a new array. */
static gb_result slot_nodes(const uint64_t *slot, size_t count, uint32_t **nodes,
                            gb_error *error)
{
    *nodes = malloc(count * sizeof **nodes + 1);
    if (!*nodes)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    for (size_t i = 0; i < count; ++i)
        (*nodes)[i] = gb_implicit_slot_node(slot[i]);
    return GB_OK;
}

/* The slot array, in huge pages where the kernel gives them on request
 * (huge_pages.h), aligned to them so that all of it can be. It is nodes x
 * bins x 8 bytes (65 MB for Table 1's model at 6x12x12), filled and then
 * written all over: in 4 KiB pages, a page fault and a TLB entry each.
 * Table 1's CreateHierarchicalLinks takes 0.83-0.88x the time with it
 * (bench/implicit_steps.c built with and without, alternating). Freed with
 * free. */
static uint64_t *allocate_slots(size_t count)
{
    size_t bytes = (count * sizeof(uint64_t) / GB_HUGE_PAGE_BYTES + 1) * GB_HUGE_PAGE_BYTES;
    uint64_t *slots = aligned_alloc(GB_HUGE_PAGE_BYTES, bytes);
    gb_advise_huge_pages(slots, bytes);
    return slots;
}

static float smallest_extent(const gb_implicit_model *m)
{
    float size = 0.0f;
    for (uint32_t i = 0; i < m->root_count; ++i)
        for (int k = 0; k < 3; ++k)
            size = fmaxf(size, m->nodes[m->roots[i]].box_max[k] - m->nodes[m->roots[i]].box_min[k]);
    return 1e-5f * size;
}

gb_result gb_implicit_create_links(const gb_implicit_model *model, const gb_implicit_bins *bins,
                                   const gb_implicit_link_options *options,
                                   gb_implicit_links *links, uint32_t **bin_targets,
                                   gb_error *error)
{
    memset(links, 0, sizeof *links);
    if (bin_targets)
        *bin_targets = NULL;
    size_t slots = (size_t)model->node_count * bins->count;
    if (slots > ((size_t)1 << 27))     /* 1 GiB of bins */
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY,
                       "implicit: %u nodes x %u bins is too many (at most 2^27): "
                       "use fewer --bins", model->node_count, bins->count);
    linker l = {.model = model, .bins = bins, .epsilon = smallest_extent(model)};
    for (int i = 0; i < SPREAD_MAX; ++i) {
        double angle = 2.39996322972865332 * i;     /* the golden angle */
        l.spiral[i][0] = (float)cos(angle);
        l.spiral[i][1] = (float)sin(angle);
        for (int count = i + 1; count <= SPREAD_MAX; ++count)
            l.spiral_radius[count][i] = sqrtf(((float)i + 0.5f) / (float)count);
    }
    l.slot = allocate_slots(slots);
    l.frames = node_frames(model);
    l.depths = options && options->depths;
    l.paper_rules = options && options->paper_rules;
    gb_result result = GB_OK;
    if (!l.slot || !l.frames)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "implicit: out of memory");
    int hierarchical = !options || options->hierarchical;
    int threads = options && options->thread_count > 0 ? options->thread_count
                                                       : GB_IMPLICIT_LINK_THREADS;
    double wall = gb_seconds(), cpu = gb_cpu_seconds();
    if (result == GB_OK) {
        memset(l.slot, 0xff, slots * sizeof *l.slot);
        result = create_hierarchical_links(&l, hierarchical, threads, options, error);
    }
    if (result == GB_OK) {
        links->wall.create = gb_seconds() - wall;
        links->cpu.create = gb_cpu_seconds() - cpu;
        double created_wall = gb_seconds(), created_cpu = gb_cpu_seconds();
        if (hierarchical)
            result = refine_and_push_down(&l, error);
        links->wall.refine = gb_seconds() - created_wall;
        links->cpu.refine = gb_cpu_seconds() - created_cpu;
    }
    if (result == GB_OK) {
        double wall = gb_seconds(), cpu = gb_cpu_seconds();
        gb_implicit_slots filled = {model, bins, l.slot, options ? options->lights : NULL,
                                    options ? options->environment : NULL};
        result = gb_implicit_link_lists(&filled, options && options->depths, links, error);
        links->wall.compact = gb_seconds() - wall;
        links->cpu.compact = gb_cpu_seconds() - cpu;
    }
    if (result == GB_OK && bin_targets)
        result = slot_nodes(l.slot, slots, bin_targets, error);
    if (result == GB_OK && options && options->progress)
        options->progress(options->progress_user, 1.0);
    free(l.slot);
    free(l.frames);
    if (result != GB_OK)
        gb_implicit_links_free(links);
    return result;
}

void gb_implicit_links_free(gb_implicit_links *links)
{
    free(links->first);
    free(links->source);
    free(links->weight);
    free(links->environment_weight);
    free(links->environment_irradiance);
    free(links->light_visible);
    free(links->depth_first);
    free(links->depth_bin);
    free(links->depth);
    memset(links, 0, sizeof *links);
}
