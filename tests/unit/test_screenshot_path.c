/* test_screenshot_path — the window's screenshots take the first free
 * number and never an existing file's (runtime/screenshot_path.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../../runtime/screenshot_path.h"
#include "tap.h"

static void touch(const char *path)
{
    FILE *f = fopen(path, "w");
    if (f)
        fclose(f);
}

int main(void)
{
    char folder[] = "/tmp/gb-screenshot-XXXXXX";
    if (!mkdtemp(folder)) {
        CHECK(0, "a scratch folder");
        return tap_done();
    }
    char base[256], path[512], expected[512];
    snprintf(base, sizeof base, "%s/gbview.png", folder);
    gb_error error;
    unsigned next = 0;
    CHECK(gb_screenshot_path(base, &next, path, sizeof path, &error) == GB_OK, "a path");
    snprintf(expected, sizeof expected, "%s/gbview-000.png", folder);
    CHECK(strcmp(path, expected) == 0, "the first is NAME-000.EXT");
    touch(path);

    /* An earlier session left 001 and 003: 002, then 004. */
    snprintf(path, sizeof path, "%s/gbview-001.png", folder);
    touch(path);
    snprintf(path, sizeof path, "%s/gbview-003.png", folder);
    touch(path);
    next = 0;
    gb_screenshot_path(base, &next, path, sizeof path, &error);
    snprintf(expected, sizeof expected, "%s/gbview-002.png", folder);
    CHECK(strcmp(path, expected) == 0, "the first free number, past the taken ones");
    touch(path);
    gb_screenshot_path(base, &next, path, sizeof path, &error);
    snprintf(expected, sizeof expected, "%s/gbview-004.png", folder);
    CHECK(strcmp(path, expected) == 0, "then the next free one");
    CHECK_EQ_INT(next, 5, "next is past the one given");

    /* -o shot.exr: the number goes before the extension; none without one. */
    snprintf(base, sizeof base, "%s/shot.exr", folder);
    next = 0;
    gb_screenshot_path(base, &next, path, sizeof path, &error);
    snprintf(expected, sizeof expected, "%s/shot-000.exr", folder);
    CHECK(strcmp(path, expected) == 0, "-o FILE.EXT: FILE-000.EXT");
    next = 7;
    gb_screenshot_path("noext", &next, path, sizeof path, &error);
    CHECK(strcmp(path, "noext-007") == 0, "a name without an extension gets the number at its end");

    next = GB_SCREENSHOT_MAX_NUMBER + 1;
    CHECK(gb_screenshot_path(base, &next, path, sizeof path, &error) == GB_ERROR_IO,
          "no free number left: an error, not an overwrite");
    char small[8];
    next = 0;
    CHECK(gb_screenshot_path(base, &next, small, sizeof small, &error) == GB_ERROR_ARGUMENT,
          "a path that does not fit: an error");

    char command[600];
    snprintf(command, sizeof command, "rm -rf '%s'", folder);
    if (system(command) != 0)
        printf("# could not remove %s\n", folder);
    return tap_done();
}
