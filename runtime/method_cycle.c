#include "method_cycle.h"

#include <stdio.h>

gb_method gb_method_cycle_next(gb_method_cycle *cycle, gb_renderer *renderer,
                               void (*report)(void *user, const char *message), void *user)
{
    gb_method current = renderer->options.method;
    for (int step = 1; step < GB_METHOD_COUNT; ++step) {
        gb_method next = (gb_method)((current + step) % GB_METHOD_COUNT);
        gb_error error;
        if (gb_renderer_set_method(renderer, next, &error) == GB_OK)
            return next;
        if (!cycle->told[next] && report) {
            char message[sizeof error.message + 64];
            snprintf(message, sizeof message, "%s skipped: %s", gb_method_name(next),
                     error.message);
            report(user, message);
        }
        cycle->told[next] = 1;
    }
    return current;
}
