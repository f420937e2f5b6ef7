/* test_depfile.c — formats/depfile.h: the rule it writes, byte for byte,
 * against the escapes GNU make's manual gives for a file name in a rule
 * (a space, '#' and '\' before a space take a backslash; '$' is "$$"), one
 * empty rule per input, an input named twice listed once, and a newline in a
 * path refused with nothing written. */
#include "depfile.h"
#include "scratch.h"
#include "tap.h"

static void test_rule(void)
{
    const char *inputs[] = {"a/scene.scene", "my folder/mesh.obj", "cost$1#2.mtl",
                            "a/scene.scene"};
    gb_error error;
    const char *path = scratch_path("x.d");
    CHECK(gb_depfile_write(path, "bake/x.vdb", inputs, 4, &error) == GB_OK, "written");
    size_t size = 0;
    char *text = (char *)scratch_read(path, &size);
    const char expected[] = "bake/x.vdb: \\\n a/scene.scene \\\n my\\ folder/mesh.obj \\\n"
                            " cost$$1\\#2.mtl\n"
                            "a/scene.scene:\n"
                            "my\\ folder/mesh.obj:\n"
                            "cost$$1\\#2.mtl:\n";
    CHECK(text && size == sizeof expected - 1 && memcmp(text, expected, size) == 0,
          "the rule, escaped as make reads it, and an empty rule for each input once");
    if (text && (size != sizeof expected - 1 || memcmp(text, expected, size) != 0))
        printf("# got:\n%.*s", (int)size, text);
    free(text);
}

static void test_newline_refused(void)
{
    const char *inputs[] = {"fine.obj", "bad\nname.mtl"};
    gb_error error;
    const char *path = scratch_path("newline.d");
    CHECK(gb_depfile_write(path, "out.vdb", inputs, 2, &error) == GB_ERROR_ARGUMENT &&
              strstr(error.message, "newline"),
          "a path with a newline cannot be in a rule: refused, saying why");
    CHECK(access(path, F_OK) != 0, "and nothing is written");
}

int main(void)
{
    scratch_create("depfile");
    test_rule();
    test_newline_refused();
    scratch_remove();
    return tap_done();
}
