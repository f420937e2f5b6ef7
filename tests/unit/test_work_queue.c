/* The work queue (common/work_queue.c): every item runs exactly once on any
 * thread count, and an item or the progress callback stops it. */
#include <stdatomic.h>
#include <string.h>

#include "tap.h"
#include "work_queue.h"

enum { ITEMS = 1000 };

typedef struct counts {
    atomic_int runs[ITEMS];
    int stop_at;                /* an item that asks to stop, or -1 */
} counts;

static int count_item(void *context, uint64_t item)
{
    counts *c = context;
    atomic_fetch_add(&c->runs[item], 1);
    return (int)item == c->stop_at;
}

/* Counts the calls whose fraction is not in [0, 1] (0/0 was one). */
static int count_bad_fraction(void *user, double fraction)
{
    int *bad = user;
    *bad += !(fraction >= 0.0 && fraction <= 1.0);
    return 0;
}

static int stop_at_half(void *user, double fraction)
{
    int *calls = user;
    ++*calls;
    return fraction >= 0.5;
}

/* Items 0 .. first_not_run-1 ran once each, the rest never. */
static int ran_up_to(const counts *c, int first_not_run)
{
    for (int i = 0; i < ITEMS; ++i)
        if (atomic_load(&c->runs[i]) != (i < first_not_run))
            return 0;
    return 1;
}

static int runs_once_each(const counts *c)
{
    for (int i = 0; i < ITEMS; ++i)
        if (atomic_load(&c->runs[i]) != 1)
            return 0;
    return 1;
}

int main(void)
{
    static counts c;
    for (int threads = 1; threads <= 4; ++threads) {
        memset(&c, 0, sizeof c);
        c.stop_at = -1;
        gb_work_queue queue = {.item_count = ITEMS, .threads = threads};
        int used = 0;
        CHECK(gb_work_queue_run(&queue, count_item, &c, &used) == GB_OK, "the run completes");
        CHECK_EQ_INT(used, threads, "the threads asked for are used");
        CHECK(runs_once_each(&c), "every item ran exactly once");
    }

    memset(&c, 0, sizeof c);
    c.stop_at = 10;
    gb_work_queue one = {.item_count = ITEMS, .threads = 1};
    CHECK(gb_work_queue_run(&one, count_item, &c, NULL) == GB_ERROR_INTERRUPTED,
          "an item returning nonzero stops the queue");
    CHECK(atomic_load(&c.runs[10]) == 1 && atomic_load(&c.runs[11]) == 0,
          "no item starts after the stop (one thread)");

    /* The callback sees the fraction started before each item is handed
     * out; it asks to stop when item ITEMS/2 is next: exactly the first half
     * runs, on any thread count and any scheduling. */
    for (int threads = 1; threads <= 4; ++threads) {
        memset(&c, 0, sizeof c);
        c.stop_at = -1;
        int calls = 0;
        gb_work_queue stopped = {.item_count = ITEMS, .threads = threads,
                                 .progress = stop_at_half, .progress_user = &calls};
        CHECK(gb_work_queue_run(&stopped, count_item, &c, NULL) == GB_ERROR_INTERRUPTED,
              "progress asking to stop interrupts the run");
        CHECK_EQ_INT(calls, ITEMS / 2 + 1, "progress is called before each item and once to stop");
        CHECK(ran_up_to(&c, ITEMS / 2), "the items before the stop ran once, none after");
    }

    int bad = 0;
    gb_work_queue empty = {.item_count = 0, .progress = count_bad_fraction, .progress_user = &bad};
    int used = 0;
    CHECK(gb_work_queue_run(&empty, count_item, &c, &used) == GB_OK && used == 1,
          "no items: success on the calling thread");
    CHECK_EQ_INT(bad, 0, "... and the progress callback never sees a fraction outside [0, 1]");
    return tap_done();
}
