#include "frame_budget.h"

#include <math.h>

/* The share of the budget an image is planned to take, leaving room for
 * presenting it and for the measure's error. */
static const double PLANNED_SHARE = 0.8;

static double image_ms(const gb_frame_budget *b, double pixels)
{
    return b->ms_per_pixel * pixels;
}

int gb_frame_budget_divisor(const gb_frame_budget *b, int width, int height)
{
    if (b->ms_per_pixel <= 0.0)
        return GB_FRAME_BUDGET_FIRST_DIVISOR;
    int d = 1;
    while (d < GB_FRAME_BUDGET_MAX_DIVISOR &&
           image_ms(b, (double)(width / d) * (double)(height / d)) >
               PLANNED_SHARE * b->budget_ms)
        d *= 2;
    return d;
}

int gb_frame_budget_parts(const gb_frame_budget *b, int width, int height)
{
    double parts = ceil(image_ms(b, (double)width * (double)height) /
                        (PLANNED_SHARE * b->budget_ms));
    if (!(parts >= 1.0))    /* also NaN: no measure, no budget */
        return 1;
    return parts < (double)height ? (int)parts : (height > 0 ? height : 1);
}

void gb_frame_budget_measure(gb_frame_budget *b, double ms, double pixels)
{
    if (pixels > 0.0 && ms >= 0.0)
        b->ms_per_pixel = ms / pixels;
}
