#include "depfile.h"

#include <stdlib.h>
#include <string.h>

#include "array_reserve.h"
#include "output_file.h"

typedef struct text {
    char *bytes;
    size_t size, capacity;
} text;

static int append(text *t, const char *bytes, size_t size)
{
    if (!gb_array_reserve(&t->bytes, &t->capacity, t->size + size + 1, 1))
        return -1;
    memcpy(t->bytes + t->size, bytes, size);
    t->size += size;
    return 0;
}

/* path as make reads it in a rule: ' ', '#', '\' escaped, '$' doubled. */
static int append_path(text *t, const char *path)
{
    for (const char *c = path; *c; ++c) {
        int failed = 0;
        if (*c == ' ' || *c == '#' || *c == '\\' || *c == '\t')
            failed = append(t, "\\", 1);
        else if (*c == '$')
            failed = append(t, "$", 1);
        if (failed || append(t, c, 1))
            return -1;
    }
    return 0;
}

static int listed_before(const char *const *inputs, uint32_t i)
{
    for (uint32_t j = 0; j < i; ++j)
        if (strcmp(inputs[j], inputs[i]) == 0)
            return 1;
    return 0;
}

static gb_result check_paths(const char *path, const char *target, const char *const *inputs,
                             uint32_t input_count, gb_error *error)
{
    if (strchr(target, '\n'))
        return gb_fail(error, GB_ERROR_ARGUMENT, "%s: a make rule cannot name '%s' (a newline)",
                       path, target);
    for (uint32_t i = 0; i < input_count; ++i)
        if (strchr(inputs[i], '\n'))
            return gb_fail(error, GB_ERROR_ARGUMENT,
                           "%s: a make rule cannot name '%s' (a newline)", path, inputs[i]);
    return GB_OK;
}

/* "target: a \\\n b\n" then "a:\n" "b:\n". */
static int compose(text *t, const char *target, const char *const *inputs, uint32_t count)
{
    int failed = append_path(t, target) || append(t, ":", 1);
    for (uint32_t i = 0; !failed && i < count; ++i)
        if (!listed_before(inputs, i))
            failed = append(t, " \\\n ", 4) || append_path(t, inputs[i]);
    failed = failed || append(t, "\n", 1);
    for (uint32_t i = 0; !failed && i < count; ++i)
        if (!listed_before(inputs, i))
            failed = append_path(t, inputs[i]) || append(t, ":\n", 2);
    return failed;
}

gb_result gb_depfile_write(const char *path, const char *target, const char *const *inputs,
                           uint32_t input_count, gb_error *error)
{
    gb_result result = check_paths(path, target, inputs, input_count, error);
    if (result != GB_OK)
        return result;
    text t = {0};
    if (compose(&t, target, inputs, input_count)) {
        free(t.bytes);
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    }
    result = gb_output_file_write_bytes(path, t.bytes, t.size, error);
    free(t.bytes);
    return result;
}

gb_result gb_depfile_write_scene(const char *path, const char *target, const gb_scene *scene,
                                 const char *other, gb_error *error)
{
    uint32_t count = scene->input_count + (other != NULL);
    const char **inputs = malloc((count + 1u) * sizeof *inputs);
    if (!inputs)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    for (uint32_t i = 0; i < scene->input_count; ++i)
        inputs[i] = scene->inputs[i];
    if (other)
        inputs[count - 1] = other;
    gb_result result = gb_depfile_write(path, target, inputs, count, error);
    free(inputs);
    return result;
}
