#include "scene_warnings.h"

#include <stdio.h>

int gb_scene_warn(const char *tool, const gb_scene *scene, unsigned what)
{
    const char *path = scene->path ? scene->path : "scene";
    char text[512];
    int lines = 0;
    if ((what & GB_WARN_GEOMETRY) && gb_scene_dropped_warning(scene, text, sizeof text))
        lines += fprintf(stderr, "%s: %s: warning: %s\n", tool, path, text) > 0;
    if ((what & GB_WARN_GEOMETRY) && scene->undefined_material_count)
        lines += fprintf(stderr, "%s: %s: warning: %u material%s used but not defined (given "
                         "the default grey)\n", tool, path, scene->undefined_material_count,
                         scene->undefined_material_count == 1 ? "" : "s") > 0;
    if ((what & GB_WARN_LIGHT) && !gb_scene_has_light(scene, text, sizeof text))
        lines += fprintf(stderr, "%s: %s: warning: %s\n", tool, path, text) > 0;
    return lines;
}
