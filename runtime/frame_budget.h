/* frame_budget.h — how the window keeps to its frame budget (renderer.h's
 * gb_renderer_refine): the resolution divisor of an image drawn while the
 * view moves, and the number of parts a still image is cut into, both from
 * the cost of the last image measured. The cost is taken as proportional
 * to the pixels drawn (every pass of the runtime is per pixel or cheaper);
 * a measure at a small size, where the per-view work weighs more, errs on
 * the side of smaller images and more parts.
 *
 * A plain value: zero it, set budget_ms, then measure and ask.
 */
#ifndef GB_FRAME_BUDGET_H
#define GB_FRAME_BUDGET_H

enum {
    GB_FRAME_BUDGET_MAX_DIVISOR = 64,   /* 1280x720 / 64 is 20x11 pixels */
    GB_FRAME_BUDGET_FIRST_DIVISOR = 4,  /* before any measure */
};

typedef struct gb_frame_budget {
    double budget_ms;           /* what a frame may take, > 0 */
    double ms_per_pixel;        /* of the last image measured; 0: none yet */
} gb_frame_budget;

/* The least power-of-two divisor d, 1 to GB_FRAME_BUDGET_MAX_DIVISOR, such
 * that an image of (width / d) x (height / d) fits the budget. */
int gb_frame_budget_divisor(const gb_frame_budget *budget, int width, int height);
/* The parts (1 to height: one row a part at most) an image of width x height
 * is cut into so that each fits the budget. */
int gb_frame_budget_parts(const gb_frame_budget *budget, int width, int height);
/* An image of pixels took ms. */
void gb_frame_budget_measure(gb_frame_budget *budget, double ms, double pixels);

#endif
