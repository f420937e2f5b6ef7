#include "scene_file.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "text.h"

/* A named group of numbers in a statement ("position X Y Z"); each field of
 * a statement must be given exactly once, in any order. */
typedef struct field {
    const char *name;
    int count;
    float *floats;              /* count floats, or NULL when ints is used */
    int *ints;                  /* count integers in [1, 65536] */
    int line_seen;
} field;

static gb_result read_field(const gb_text *text, gb_span *line, field *f, gb_error *error)
{
    for (int i = 0; i < f->count; ++i) {
        char what[64];
        snprintf(what, sizeof what, f->count > 1 ? "%s value %d" : "%s value", f->name, i + 1);
        if (f->floats) {
            gb_result result = gb_text_float(text, line, what, &f->floats[i], error);
            if (result != GB_OK)
                return result;
        } else {
            long value;
            gb_result result = gb_text_int(text, line, what, 1, 65536, &value, error);
            if (result != GB_OK)
                return result;
            f->ints[i] = (int)value;
        }
    }
    return GB_OK;
}

static gb_result read_fields(const gb_text *text, gb_span *line, const char *statement,
                             field *fields, int n, gb_error *error)
{
    gb_span word;
    while (gb_span_next_token(line, &word)) {
        field *f = NULL;
        for (int i = 0; i < n && !f; ++i)
            if (gb_span_is(word, fields[i].name))
                f = &fields[i];
        if (!f)
            return gb_fail(error, GB_ERROR_PARSE, "%s:%d: unknown keyword '%.*s' in %s",
                           text->name, text->line, (int)(gb_span_length(word) > 40 ? 40
                           : gb_span_length(word)), word.begin, statement);
        if (f->line_seen)
            return gb_fail(error, GB_ERROR_PARSE, "%s:%d: %s given twice in %s", text->name,
                           text->line, f->name, statement);
        f->line_seen = 1;
        gb_result result = read_field(text, line, f, error);
        if (result != GB_OK)
            return result;
    }
    for (int i = 0; i < n; ++i)
        if (!fields[i].line_seen)
            return gb_fail(error, GB_ERROR_PARSE, "%s:%d: %s without %s", text->name,
                           text->line, statement, fields[i].name);
    return GB_OK;
}

static gb_result normalise(const gb_text *text, float v[3], const char *what, gb_error *error)
{
    double length = sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]);
    if (!(length > 0) || !isfinite(length))
        return gb_fail(error, GB_ERROR_INVALID, "%s:%d: %s is a zero vector", text->name,
                       text->line, what);
    for (int i = 0; i < 3; ++i)
        v[i] = (float)(v[i] / length);
    return GB_OK;
}

static gb_result check_colour(const gb_text *text, const float c[3], const char *what,
                              gb_error *error)
{
    if (c[0] < 0 || c[1] < 0 || c[2] < 0)
        return gb_fail(error, GB_ERROR_INVALID, "%s:%d: negative %s", text->name, text->line,
                       what);
    return GB_OK;
}

static gb_light *add_light(gb_scene_file *file)
{
    gb_light *lights = realloc(file->lights, (file->light_count + 1) * sizeof *lights);
    if (!lights)
        return NULL;
    file->lights = lights;
    gb_light *light = &lights[file->light_count++];
    memset(light, 0, sizeof *light);
    return light;
}

static gb_result read_point_light(const gb_text *text, gb_span *line, gb_light *light,
                                  gb_error *error)
{
    light->type = GB_LIGHT_POINT;
    field fields[] = {{"position", 3, light->position, NULL, 0},
                      {"intensity", 3, light->intensity, NULL, 0}};
    gb_result result = read_fields(text, line, "point light", fields, 2, error);
    return result != GB_OK ? result : check_colour(text, light->intensity, "intensity", error);
}

static gb_result read_spot_light(const gb_text *text, gb_span *line, gb_light *light,
                                 gb_error *error)
{
    light->type = GB_LIGHT_SPOT;
    field fields[] = {{"position", 3, light->position, NULL, 0},
                      {"direction", 3, light->direction, NULL, 0},
                      {"intensity", 3, light->intensity, NULL, 0},
                      {"cone", 1, &light->cone_angle, NULL, 0},
                      {"falloff", 1, &light->falloff_angle, NULL, 0}};
    gb_result result = read_fields(text, line, "spot light", fields, 5, error);
    if (result == GB_OK)
        result = normalise(text, light->direction, "spot light direction", error);
    if (result == GB_OK)
        result = check_colour(text, light->intensity, "intensity", error);
    if (result != GB_OK)
        return result;
    if (!(light->cone_angle > 0 && light->cone_angle <= 180))
        return gb_fail(error, GB_ERROR_INVALID, "%s:%d: cone %g is not in (0, 180] degrees",
                       text->name, text->line, light->cone_angle);
    if (!(light->falloff_angle >= 0 && light->falloff_angle <= light->cone_angle))
        return gb_fail(error, GB_ERROR_INVALID, "%s:%d: falloff %g is not in [0, cone %g] degrees",
                       text->name, text->line, light->falloff_angle, light->cone_angle);
    return GB_OK;
}

static gb_result read_directional_light(const gb_text *text, gb_span *line, gb_light *light,
                                        gb_error *error)
{
    light->type = GB_LIGHT_DIRECTIONAL;
    field fields[] = {{"direction", 3, light->direction, NULL, 0},
                      {"irradiance", 3, light->intensity, NULL, 0}};
    gb_result result = read_fields(text, line, "directional light", fields, 2, error);
    if (result == GB_OK)
        result = normalise(text, light->direction, "directional light direction", error);
    return result != GB_OK ? result : check_colour(text, light->intensity, "irradiance", error);
}

static gb_result read_light(const gb_text *text, gb_span *line, gb_scene_file *file,
                            gb_error *error)
{
    gb_span kind;
    if (!gb_span_next_token(line, &kind))
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: light without a kind (point, spot, "
                       "directional)", text->name, text->line);
    int point = gb_span_is(kind, "point"), spot = gb_span_is(kind, "spot"),
        directional = gb_span_is(kind, "directional");
    if (!point && !spot && !directional)
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: unknown light kind '%.*s' (point, spot, "
                       "directional)", text->name, text->line,
                       (int)(gb_span_length(kind) > 40 ? 40 : gb_span_length(kind)), kind.begin);
    gb_light *light = add_light(file);
    if (!light)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s:%d: out of memory", text->name,
                       text->line);
    if (point)
        return read_point_light(text, line, light, error);
    if (spot)
        return read_spot_light(text, line, light, error);
    return read_directional_light(text, line, light, error);
}

static gb_result check_camera(const gb_text *text, gb_camera *camera, gb_error *error)
{
    float view[3];
    for (int i = 0; i < 3; ++i)
        view[i] = camera->target[i] - camera->position[i];
    gb_result result = normalise(text, view, "camera view (target - position)", error);
    if (result == GB_OK)
        result = normalise(text, camera->up, "camera up", error);
    if (result != GB_OK)
        return result;
    double along = (double)view[0] * camera->up[0] + (double)view[1] * camera->up[1]
                 + (double)view[2] * camera->up[2];
    if (fabs(along) > 0.9999)
        return gb_fail(error, GB_ERROR_INVALID, "%s:%d: camera up is parallel to its view",
                       text->name, text->line);
    if (!(camera->fov_y > 0 && camera->fov_y < 180))
        return gb_fail(error, GB_ERROR_INVALID, "%s:%d: fov %g is not in (0, 180) degrees",
                       text->name, text->line, camera->fov_y);
    return GB_OK;
}

static gb_result read_camera(const gb_text *text, gb_span *line, gb_scene_file *file,
                             gb_error *error)
{
    gb_camera *cameras = realloc(file->cameras, (file->camera_count + 1) * sizeof *cameras);
    if (!cameras)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s:%d: out of memory", text->name,
                       text->line);
    file->cameras = cameras;
    gb_camera *camera = &cameras[file->camera_count++];
    memset(camera, 0, sizeof *camera);
    int resolution[2] = {0, 0};
    field fields[] = {{"position", 3, camera->position, NULL, 0},
                      {"target", 3, camera->target, NULL, 0},
                      {"up", 3, camera->up, NULL, 0},
                      {"fov", 1, &camera->fov_y, NULL, 0},
                      {"resolution", 2, NULL, resolution, 0}};
    gb_result result = read_fields(text, line, "camera", fields, 5, error);
    camera->width = resolution[0];
    camera->height = resolution[1];
    return result != GB_OK ? result : check_camera(text, camera, error);
}

/* A path statement: the rest of the line (it may hold spaces), given once. */
static gb_result read_path(const gb_text *text, gb_span *line, const char *statement,
                           char **path_out, int *line_out, gb_error *error)
{
    if (*path_out)
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: a second %s (the first is on line %d)",
                       text->name, text->line, statement, *line_out);
    gb_span path = gb_span_trim(*line);
    if (gb_span_length(path) == 0)
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: %s without a path", text->name,
                       text->line, statement);
    if (memchr(path.begin, '\0', gb_span_length(path)))
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: %s path holds a NUL byte", text->name,
                       text->line, statement);
    *path_out = gb_span_dup(path);
    *line_out = text->line;
    if (!*path_out)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s:%d: out of memory", text->name,
                       text->line);
    return GB_OK;
}

static gb_result read_environment(const gb_text *text, gb_span *line, gb_scene_file *file,
                                  gb_error *error)
{
    file->environment_line = text->line;
    gb_result result = gb_text_floats(text, line, "environment", file->environment, 3, error);
    if (result == GB_OK)
        result = gb_text_expect_end(text, line, error);
    return result != GB_OK ? result : check_colour(text, file->environment, "environment", error);
}

static gb_result read_header(const gb_text *text, gb_span key, gb_span *line, gb_error *error)
{
    if (!gb_span_is(key, "gibake-scene"))
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: not a scene file (it must start with "
                       "'gibake-scene 1')", text->name, text->line);
    long version;
    gb_result result = gb_text_int(text, line, "scene file version", 1, 1, &version, error);
    return result != GB_OK ? result : gb_text_expect_end(text, line, error);
}

static gb_result read_statement(const gb_text *text, gb_span key, gb_span *line,
                                gb_scene_file *file, gb_error *error)
{
    if (gb_span_is(key, "mesh"))
        return read_path(text, line, "mesh", &file->mesh, &file->mesh_line, error);
    if (gb_span_is(key, "environment-map"))
        return read_path(text, line, "environment-map", &file->environment_map,
                         &file->environment_map_line, error);
    if (gb_span_is(key, "environment"))
        return read_environment(text, line, file, error);
    if (gb_span_is(key, "light"))
        return read_light(text, line, file, error);
    if (gb_span_is(key, "camera"))
        return read_camera(text, line, file, error);
    if (gb_span_is(key, "gibake-scene"))
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: a second gibake-scene line", text->name,
                       text->line);
    return gb_fail(error, GB_ERROR_PARSE, "%s:%d: unknown keyword '%.*s'", text->name,
                   text->line, (int)(gb_span_length(key) > 40 ? 40 : gb_span_length(key)),
                   key.begin);
}

static gb_result parse_terminated(const char *buffer, size_t size, const char *name,
                                  gb_scene_file *file, gb_error *error)
{
    memset(file, 0, sizeof *file);
    gb_text text = gb_text_start(buffer, size, name);
    gb_span line, key;
    int header_seen = 0;
    while (gb_text_next_line(&text, &line)) {
        if (!gb_span_next_token(&line, &key))
            continue;
        gb_result result = header_seen ? read_statement(&text, key, &line, file, error)
                                       : read_header(&text, key, &line, error);
        if (result != GB_OK)
            return result;
        header_seen = 1;
    }
    if (!header_seen)
        return gb_fail(error, GB_ERROR_PARSE, "%s: empty scene file (it must start with "
                       "'gibake-scene 1')", name);
    if (!file->mesh)
        return gb_fail(error, GB_ERROR_PARSE, "%s: no mesh statement", name);
    if (file->environment_map && file->environment_line)
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: environment colour and environment-map on "
                       "line %d: give one of the two", name, file->environment_line,
                       file->environment_map_line);
    return GB_OK;
}

gb_result gb_scene_file_parse(const char *text, size_t size, const char *name,
                              gb_scene_file *file, gb_error *error)
{
    char *buffer;
    memset(file, 0, sizeof *file);
    gb_result result = gb_text_copy(text, size, &buffer, error);
    if (result != GB_OK)
        return result;
    result = parse_terminated(buffer, size, name, file, error);
    free(buffer);
    return result;
}

gb_result gb_scene_file_read(const char *path, gb_scene_file *file, gb_error *error)
{
    char *buffer;
    size_t size;
    memset(file, 0, sizeof *file);
    gb_result result = gb_text_load(path, &buffer, &size, error);
    if (result != GB_OK)
        return result;
    result = parse_terminated(buffer, size, path, file, error);
    free(buffer);
    return result;
}

void gb_scene_file_free(gb_scene_file *file)
{
    free(file->mesh);
    free(file->environment_map);
    free(file->lights);
    free(file->cameras);
    memset(file, 0, sizeof *file);
}
