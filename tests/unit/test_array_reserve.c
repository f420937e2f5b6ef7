/* gb_array_reserve (formats/array_reserve.h): pushing items one by one
 * keeps every item, the capacity doubles from 16 and always covers the
 * count, and a request past SIZE_MAX bytes fails with the array unchanged. */
#include <stdint.h>
#include <stdlib.h>

#include "array_reserve.h"
#include "tap.h"

typedef struct pair {
    uint32_t a;
    double b;
} pair;

int main(void)
{
    pair *items = NULL;
    size_t count = 0, capacity = 0;
    int kept = 1, covered = 1, powers = 1;
    for (uint32_t n = 0; n < 100000; ++n) {
        if (!gb_array_reserve(&items, &capacity, count + 1, sizeof *items))
            break;
        items[count++] = (pair){n, 0.5 * n};
        covered &= capacity >= count;
        powers &= capacity % 16 == 0 && ((capacity / 16) & (capacity / 16 - 1)) == 0;
    }
    CHECK_EQ_INT(count, 100000, "100 000 pushes succeed");
    for (uint32_t n = 0; n < count; ++n)
        kept &= items[n].a == n && items[n].b == 0.5 * n;
    CHECK(kept, "every item survives the reallocations");
    CHECK(covered, "the capacity covers the count after every push");
    CHECK(powers, "the capacity is 16 times a power of two");
    CHECK_EQ_INT(capacity, 131072, "100 000 items take the next power of two, 131 072");

    CHECK(gb_array_reserve(&items, &capacity, 10, sizeof *items), "a smaller need is met");
    CHECK_EQ_INT(capacity, 131072, "a smaller need leaves the capacity");

    pair *before = items;
    CHECK(!gb_array_reserve(&items, &capacity, SIZE_MAX / sizeof *items + 1, sizeof *items),
          "a need past SIZE_MAX bytes fails");
    CHECK(items == before && capacity == 131072, "a failure leaves the array and capacity");
    CHECK(!gb_array_reserve(&items, &capacity, SIZE_MAX, 1), "a need past SIZE_MAX / 2 fails");
    CHECK(items == before && items[99999].a == 99999, "the items are still there");
    free(items);

    char *bytes = NULL;
    size_t byte_capacity = 0;
    CHECK(gb_array_reserve(&bytes, &byte_capacity, 17, 1), "a first need above 16");
    CHECK_EQ_INT(byte_capacity, 32, "starts at 16 and doubles to cover it");
    free(bytes);
    return tap_done();
}
