/* test_frame_budget — the divisor and the parts the window draws to keep to
 * its budget, against the sums worked by hand from their definitions
 * (runtime/frame_budget.h: an image costs ms_per_pixel x its pixels, and
 * is planned to take 0.8 of the budget). */
#include "../../runtime/frame_budget.h"
#include "tap.h"

int main(void)
{
    gb_frame_budget b = {.budget_ms = 50.0};
    CHECK_EQ_INT(gb_frame_budget_divisor(&b, 512, 512), GB_FRAME_BUDGET_FIRST_DIVISOR,
                 "no measure yet: the first divisor");
    CHECK_EQ_INT(gb_frame_budget_parts(&b, 512, 512), 1, "no measure yet: one part");

    /* 512x512 in 400 ms: 400 / d^2 <= 40 first at d = 4 (d = 2: 100 ms). */
    gb_frame_budget_measure(&b, 400.0, 512.0 * 512.0);
    CHECK_EQ_INT(gb_frame_budget_divisor(&b, 512, 512), 4, "400 ms at 50: a quarter of the side");
    CHECK_EQ_INT(gb_frame_budget_parts(&b, 512, 512), 10, "400 ms at 40 a part: ten parts");
    CHECK_EQ_INT(gb_frame_budget_parts(&b, 256, 256), 3, "100 ms: three parts (ceil 2.5)");
    CHECK_EQ_INT(gb_frame_budget_divisor(&b, 100, 100), 1, "a small image fits whole");

    /* Exactly at the planned share: 40 ms fits, one part. */
    gb_frame_budget_measure(&b, 40.0, 100.0 * 100.0);
    CHECK_EQ_INT(gb_frame_budget_parts(&b, 100, 100), 1, "exactly 0.8 of the budget: one part");
    CHECK_EQ_INT(gb_frame_budget_divisor(&b, 100, 100), 1, "exactly 0.8 of the budget: whole");

    /* A minute an image: the divisor stops at its largest, the parts at a row each. */
    gb_frame_budget_measure(&b, 60000.0, 64.0 * 64.0);
    CHECK_EQ_INT(gb_frame_budget_divisor(&b, 1280, 720), GB_FRAME_BUDGET_MAX_DIVISOR,
                 "a slow method: the largest divisor");
    CHECK_EQ_INT(gb_frame_budget_parts(&b, 64, 64), 64, "at most one row a part");

    gb_frame_budget_measure(&b, 10.0, 0.0);
    CHECK_EQ_INT(gb_frame_budget_parts(&b, 64, 64), 64, "a measure of no pixels is ignored");
    return tap_done();
}
