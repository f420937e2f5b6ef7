/* fuzz_container.c — libFuzzer target for the container reader: any input
 * must give either a valid container or an error, never a crash or a read
 * out of bounds (run under ASan/UBSan by `make fuzz`). Every byte of every
 * section is touched, so a view that reaches past the input is caught.
 */
#include "container.h"

#include <stddef.h>
#include <stdint.h>
#include <string.h>

static volatile unsigned sink;

static unsigned touch_sections(const gb_container *container)
{
    unsigned sum = 0;
    for (uint32_t i = 0; i < container->section_count; ++i) {
        const gb_section *section = &container->sections[i];
        const unsigned char *bytes = section->data;
        for (uint64_t j = 0; j < section->size; ++j)
            sum += bytes[j];
        sum += (unsigned)strlen(section->name);
        if (gb_container_find(container, section->name) == NULL)
            __builtin_trap(); /* every listed section must be found */
    }
    return sum;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    gb_container container;
    gb_error error;
    if (gb_container_parse(data, size, "fuzz", NULL, &container, &error) == GB_OK) {
        sink += touch_sections(&container);
        sink += gb_container_check_version(&container, "fuzz", 1, &error);
        gb_container_close(&container);
    } else if (strncmp(error.message, "fuzz: ", 6) != 0) {
        __builtin_trap(); /* every failure has a "path: ..." message */
    }
    return 0;
}
