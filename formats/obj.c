#include "obj.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "array_reserve.h"
#include "text.h"

/* ---- growable arrays ---------------------------------------------------- */

typedef struct array {
    char *data;
    size_t count, capacity, element;   /* count and capacity in elements */
} array;

/* Room for n more elements at the end; NULL when out of memory. */
static void *array_push(array *a, size_t n)
{
    if (n > SIZE_MAX - a->count ||
        !gb_array_reserve(&a->data, &a->capacity, a->count + n, a->element))
        return NULL;
    void *slot = a->data + a->count * a->element;
    a->count += n;
    return slot;
}

static void array_free(array *a)
{
    free(a->data);
    a->data = NULL;
    a->count = a->capacity = 0;
}

/* ---- materials ---------------------------------------------------------- */

static gb_material *material_list_push(gb_material_list *list)
{
    if (!gb_array_reserve(&list->items, &list->capacity, (size_t)list->count + 1,
                          sizeof *list->items))
        return NULL;
    gb_material *material = &list->items[list->count++];
    memset(material, 0, sizeof *material);
    return material;
}

void gb_material_list_free(gb_material_list *list)
{
    for (uint32_t i = 0; i < list->count; ++i) {
        free(list->items[i].map_Kd);
        free(list->items[i].texture.rgb);
    }
    free(list->items);
    memset(list, 0, sizeof *list);
}

/* Copies name into a material name, cut to fit (names are compared cut). */
static void copy_name(char out[64], gb_span name)
{
    size_t length = gb_span_length(name);
    if (length > 63)
        length = 63;
    memcpy(out, name.begin, length);
    out[length] = '\0';
}

static int key_is(gb_span key, const char *word)
{
    size_t length = strlen(word);
    return gb_span_length(key) == length && strncasecmp(key.begin, word, length) == 0;
}

/* ---- MTL ----------------------------------------------------------------- */

/* Kd/Ks/Ke: one value (grey) or three. */
static gb_result read_colour(const gb_text *text, gb_span *line, const char *key,
                             float colour[3], gb_error *error)
{
    char what[32];
    snprintf(what, sizeof what, "%s red", key);
    gb_result result = gb_text_float(text, line, what, &colour[0], error);
    if (result != GB_OK)
        return result;
    gb_span rest = *line, token;
    if (!gb_span_next_token(&rest, &token)) {
        colour[1] = colour[2] = colour[0];
        return GB_OK;
    }
    snprintf(what, sizeof what, "%s green", key);
    result = gb_text_float(text, line, what, &colour[1], error);
    if (result != GB_OK)
        return result;
    snprintf(what, sizeof what, "%s blue", key);
    return gb_text_float(text, line, what, &colour[2], error);
}

static int is_number(gb_span token)
{
    char *stop;
    strtof(token.begin, &stop);
    return stop == token.end;
}

/* How many arguments a map option takes: exactly *minimum, or up to the
 * returned number when they are numbers (-o, -s, -t take u [v [w]]). */
static int map_option_arguments(gb_span option, int *minimum)
{
    static const char *const one[] = {"-blendu", "-blendv", "-cc", "-clamp", "-bm", "-boost",
                                      "-texres", "-imfchan", "-type"};
    *minimum = 1;
    for (size_t i = 0; i < sizeof one / sizeof *one; ++i)
        if (key_is(option, one[i]))
            return 1;
    if (key_is(option, "-mm"))
        return *minimum = 2;
    return 3;   /* -o, -s, -t and options gibake does not know */
}

/* Skips map options such as "-s 1 1 1" or "-clamp on" before the file name. */
static void skip_map_options(gb_span *line)
{
    gb_span option;
    for (gb_span rest = *line; gb_span_next_token(&rest, &option) && option.begin[0] == '-'
                               && gb_span_length(option) > 1 && !is_number(option);) {
        int minimum, maximum = map_option_arguments(option, &minimum);
        for (int i = 0; i < maximum; ++i) {
            gb_span after = rest, argument;
            if (!gb_span_next_token(&after, &argument) || (i >= minimum && !is_number(argument)))
                break;
            rest = after;
        }
        *line = rest;
    }
}

static gb_result read_map(const gb_text *text, gb_span *line, const char *texture_folder,
                          gb_material *material, gb_error *error)
{
    skip_map_options(line);
    gb_span file = gb_span_trim(*line);
    if (gb_span_length(file) == 0)
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: map_Kd names no file", text->name,
                       text->line);
    char *name = gb_span_dup(file);
    char *path = name && texture_folder ? gb_path_join(texture_folder, name) : name;
    if (path != name)
        free(name);
    if (!path)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s:%d: out of memory", text->name,
                       text->line);
    free(material->map_Kd);
    material->map_Kd = path;
    struct stat status;
    if (texture_folder && stat(path, &status) != 0)
        return gb_fail(error, GB_ERROR_IO, "%s:%d: texture %s: %s", text->name, text->line,
                       path, strerror(errno));
    if (texture_folder && !S_ISREG(status.st_mode))
        return gb_fail(error, GB_ERROR_IO, "%s:%d: texture %s: not a file", text->name,
                       text->line, path);
    return GB_OK;
}

static gb_result read_mtl_statement(const gb_text *text, gb_span key, gb_span *line,
                                    const char *texture_folder, gb_material_list *list,
                                    gb_error *error)
{
    if (key_is(key, "newmtl")) {
        gb_span name = gb_span_trim(*line);
        if (gb_span_length(name) == 0)
            return gb_fail(error, GB_ERROR_PARSE, "%s:%d: newmtl without a name", text->name,
                           text->line);
        gb_material *material = material_list_push(list);
        if (!material)
            return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s:%d: out of memory", text->name,
                           text->line);
        gb_material_set_default(material, "");
        copy_name(material->name, name);
        return GB_OK;
    }
    int known = key_is(key, "Kd") || key_is(key, "Ks") || key_is(key, "Ke")
             || key_is(key, "Ns") || key_is(key, "map_Kd");
    if (!known)
        return GB_OK;
    if (list->count == 0)
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: %.*s before any newmtl", text->name,
                       text->line, (int)gb_span_length(key), key.begin);
    gb_material *material = &list->items[list->count - 1];
    if (key_is(key, "Kd"))
        return read_colour(text, line, "Kd", material->Kd, error);
    if (key_is(key, "Ks"))
        return read_colour(text, line, "Ks", material->Ks, error);
    if (key_is(key, "Ke"))
        return read_colour(text, line, "Ke", material->Ke, error);
    if (key_is(key, "Ns"))
        return gb_text_float(text, line, "Ns", &material->Ns, error);
    return read_map(text, line, texture_folder, material, error);
}

static gb_result parse_mtl_terminated(const char *buffer, size_t size, const char *name,
                                      const char *texture_folder, gb_material_list *list,
                                      gb_error *error)
{
    gb_text text = gb_text_start(buffer, size, name);
    gb_span line, key;
    while (gb_text_next_line(&text, &line)) {
        if (!gb_span_next_token(&line, &key))
            continue;
        gb_result result = read_mtl_statement(&text, key, &line, texture_folder, list, error);
        if (result != GB_OK)
            return result;
    }
    return GB_OK;
}

gb_result gb_mtl_parse(const char *text, size_t size, const char *name,
                       const char *texture_folder, gb_material_list *materials,
                       gb_error *error)
{
    char *buffer;
    gb_result result = gb_text_copy(text, size, &buffer, error);
    if (result != GB_OK)
        return result;
    result = parse_mtl_terminated(buffer, size, name, texture_folder, materials, error);
    free(buffer);
    return result;
}

/* ---- OBJ ------------------------------------------------------------------ */

enum { NO_SLOT = UINT32_MAX };

typedef struct obj_parser {
    gb_text text;
    gb_obj_mtllib_reader read_mtllib;
    void *user;
    array positions, texcoords, normals;          /* float: 3, 2, 3 per element */
    array indices;                                /* uint32: 3 per triangle */
    array corner_texcoord, corner_normal;         /* int32: 3 per triangle, -1 none */
    array triangle_slot;                          /* uint32 per triangle: usemtl slot */
    array slot_names;                             /* char[64] per distinct usemtl */
    array face_v, face_vt, face_vn;               /* the corners of the current face */
    uint32_t slot;                                /* current usemtl, NO_SLOT before any */
    int has_texcoords, has_normals;
    gb_material_list materials;
} obj_parser;

static void parser_free(obj_parser *p)
{
    array *arrays[] = {&p->positions, &p->texcoords, &p->normals, &p->indices,
                       &p->corner_texcoord, &p->corner_normal, &p->triangle_slot,
                       &p->slot_names, &p->face_v, &p->face_vt, &p->face_vn};
    for (size_t i = 0; i < sizeof arrays / sizeof *arrays; ++i)
        array_free(arrays[i]);
    gb_material_list_free(&p->materials);
}

static gb_result out_of_memory(const obj_parser *p, gb_error *error)
{
    return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s:%d: out of memory", p->text.name,
                   p->text.line);
}

static const char *const vertex_names[3] = {"vertex x", "vertex y", "vertex z"};
static const char *const texcoord_names[3] = {"texture coordinate u", "texture coordinate v",
                                              "texture coordinate w"};
static const char *const normal_names[3] = {"normal x", "normal y", "normal z"};

/* n values named names[i], the first required of them; 0 for the others
 * when missing; values beyond n (w, vertex colours) are ignored. */
static gb_result read_vertex(obj_parser *p, gb_span *line, array *target, int n,
                             int required, const char *const names[3], gb_error *error)
{
    if (target->count / (size_t)n >= INT32_MAX)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s:%d: more than 2^31 elements",
                       p->text.name, p->text.line);
    float *values = array_push(target, (size_t)n);
    if (!values)
        return out_of_memory(p, error);
    for (int i = 0; i < n; ++i) {
        gb_span rest = *line, token;
        if (i >= required && !gb_span_next_token(&rest, &token)) {
            values[i] = 0.0f;
            continue;
        }
        gb_result result = gb_text_float(&p->text, line, names[i], &values[i], error);
        if (result != GB_OK)
            return result;
    }
    return GB_OK;
}

static gb_result malformed_corner(const obj_parser *p, gb_span corner, gb_error *error)
{
    int length = (int)(gb_span_length(corner) > 40 ? 40 : gb_span_length(corner));
    return gb_fail(error, GB_ERROR_PARSE, "%s:%d: malformed face corner '%.*s'", p->text.name,
                   p->text.line, length, corner.begin);
}

/* One index of a corner ("-3" or "12" at *cursor, which moves past it),
 * resolved against count elements: 1-based, or negative from the end. */
static gb_result read_index(const obj_parser *p, gb_span corner, const char **cursor,
                            const char *what, const char *plural, size_t count,
                            int32_t *index, gb_error *error)
{
    const char *c = *cursor, *end = corner.end;
    int negative = c < end && *c == '-';
    if (c < end && (*c == '-' || *c == '+'))
        ++c;
    if (c == end || *c < '0' || *c > '9')
        return malformed_corner(p, corner, error);
    long long value = 0;
    while (c < end && *c >= '0' && *c <= '9') {
        if (value < (long long)1 << 40)
            value = value * 10 + (*c - '0');
        ++c;
    }
    *cursor = c;
    long long resolved = negative ? (long long)count - value : value - 1;
    if (value == 0 || resolved < 0 || resolved >= (long long)count)
        return gb_fail(error, GB_ERROR_INVALID, "%s:%d: %s index %lld out of range (%zu %s)",
                       p->text.name, p->text.line, what, negative ? -value : value, count,
                       plural);
    *index = (int32_t)resolved;
    return GB_OK;
}

/* A corner token "v", "v/vt", "v//vn" or "v/vt/vn" into the face arrays. */
static gb_result read_corner(obj_parser *p, gb_span corner, gb_error *error)
{
    int32_t *v = array_push(&p->face_v, 1), *vt = array_push(&p->face_vt, 1),
            *vn = array_push(&p->face_vn, 1);
    if (!v || !vt || !vn)
        return out_of_memory(p, error);
    *vt = *vn = -1;
    const char *c = corner.begin, *end = corner.end;
    gb_result result = read_index(p, corner, &c, "vertex", "vertices", p->positions.count / 3,
                                  v, error);
    if (result == GB_OK && c < end && *c == '/') {
        ++c;
        if (c < end && *c != '/')
            result = read_index(p, corner, &c, "texture coordinate", "texture coordinates",
                                p->texcoords.count / 2, vt, error);
        if (result == GB_OK && c < end && *c == '/') {
            ++c;
            result = read_index(p, corner, &c, "normal", "normals", p->normals.count / 3, vn,
                                error);
        }
    }
    if (result == GB_OK && c != end)
        return malformed_corner(p, corner, error);
    return result;
}

/* Fan-triangulates the corners read into face_v/vt/vn. */
static gb_result emit_face(obj_parser *p, gb_error *error)
{
    size_t n = p->face_v.count;
    const int32_t *v = (const int32_t *)p->face_v.data, *vt = (const int32_t *)p->face_vt.data,
                  *vn = (const int32_t *)p->face_vn.data;
    size_t triangles = n - 2;
    uint32_t *indices = array_push(&p->indices, 3 * triangles);
    int32_t *texcoords = array_push(&p->corner_texcoord, 3 * triangles);
    int32_t *normals = array_push(&p->corner_normal, 3 * triangles);
    uint32_t *slots = array_push(&p->triangle_slot, triangles);
    if (!indices || !texcoords || !normals || !slots)
        return out_of_memory(p, error);
    for (size_t t = 0; t < triangles; ++t) {
        size_t corner[3] = {0, t + 1, t + 2};
        for (int k = 0; k < 3; ++k) {
            indices[3 * t + k] = (uint32_t)v[corner[k]];
            texcoords[3 * t + k] = vt[corner[k]];
            normals[3 * t + k] = vn[corner[k]];
            p->has_texcoords |= vt[corner[k]] >= 0;
            p->has_normals |= vn[corner[k]] >= 0;
        }
        slots[t] = p->slot;
    }
    return GB_OK;
}

static gb_result read_face(obj_parser *p, gb_span *line, gb_error *error)
{
    p->face_v.count = p->face_vt.count = p->face_vn.count = 0;
    gb_span token;
    while (gb_span_next_token(line, &token)) {
        gb_result result = read_corner(p, token, error);
        if (result != GB_OK)
            return result;
    }
    if (p->face_v.count < 3)
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: face with %zu corners (at least 3 needed)",
                       p->text.name, p->text.line, p->face_v.count);
    if (p->indices.count / 3 + p->face_v.count > UINT32_MAX / 4)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s:%d: too many triangles", p->text.name,
                       p->text.line);
    return emit_face(p, error);
}

static gb_result use_material(obj_parser *p, gb_span *line, gb_error *error)
{
    gb_span name = gb_span_trim(*line);
    if (gb_span_length(name) == 0)
        return gb_fail(error, GB_ERROR_PARSE, "%s:%d: usemtl without a name", p->text.name,
                       p->text.line);
    char cut[64];
    copy_name(cut, name);
    const char (*names)[64] = (const char (*)[64])p->slot_names.data;
    for (size_t i = 0; i < p->slot_names.count; ++i)
        if (strcmp(names[i], cut) == 0) {
            p->slot = (uint32_t)i;
            return GB_OK;
        }
    char *slot = array_push(&p->slot_names, 1);
    if (!slot)
        return out_of_memory(p, error);
    memcpy(slot, cut, 64);
    p->slot = (uint32_t)(p->slot_names.count - 1);
    return GB_OK;
}

static gb_result read_mtllibs(obj_parser *p, gb_span *line, gb_error *error)
{
    gb_span token;
    while (gb_span_next_token(line, &token)) {
        if (!p->read_mtllib)
            continue;
        char *name = gb_span_dup(token);
        if (!name)
            return out_of_memory(p, error);
        gb_result result = p->read_mtllib(p->user, name, p->text.name, p->text.line,
                                          &p->materials, error);
        free(name);
        if (result != GB_OK)
            return result;
    }
    return GB_OK;
}

static gb_result read_obj_statement(obj_parser *p, gb_span key, gb_span *line,
                                    gb_error *error)
{
    if (gb_span_is(key, "v"))
        return read_vertex(p, line, &p->positions, 3, 3, vertex_names, error);
    if (gb_span_is(key, "vt"))
        return read_vertex(p, line, &p->texcoords, 2, 1, texcoord_names, error);
    if (gb_span_is(key, "vn"))
        return read_vertex(p, line, &p->normals, 3, 3, normal_names, error);
    if (gb_span_is(key, "f"))
        return read_face(p, line, error);
    if (gb_span_is(key, "usemtl"))
        return use_material(p, line, error);
    if (gb_span_is(key, "mtllib"))
        return read_mtllibs(p, line, error);
    return GB_OK;   /* o, g, s, l, p and statements gibake does not use */
}

/* ---- OBJ to scene ---------------------------------------------------------- */

static uint32_t find_material(const gb_material_list *list, const char *name)
{
    for (uint32_t i = 0; i < list->count; ++i)
        if (strcmp(list->items[i].name, name) == 0)
            return i;
    return NO_SLOT;
}

/* Maps each usemtl slot (and NO_SLOT, last) to a material, adding defaults
 * for names no MTL defines and for faces before any usemtl. */
static gb_result resolve_slots(obj_parser *p, uint32_t *slot_material, gb_scene *scene,
                               gb_error *error)
{
    const char (*names)[64] = (const char (*)[64])p->slot_names.data;
    size_t slots = p->slot_names.count;
    for (size_t i = 0; i < slots; ++i) {
        slot_material[i] = find_material(&p->materials, names[i]);
        if (slot_material[i] != NO_SLOT)
            continue;
        gb_material *material = material_list_push(&p->materials);
        if (!material)
            return out_of_memory(p, error);
        gb_material_set_default(material, names[i]);
        slot_material[i] = p->materials.count - 1;
        ++scene->undefined_material_count;
    }
    slot_material[slots] = NO_SLOT;
    const uint32_t *triangle_slot = (const uint32_t *)p->triangle_slot.data;
    for (size_t t = 0; t < p->triangle_slot.count; ++t)
        if (triangle_slot[t] == NO_SLOT) {
            gb_material *material = material_list_push(&p->materials);
            if (!material)
                return out_of_memory(p, error);
            gb_material_set_default(material, "default");
            slot_material[slots] = p->materials.count - 1;
            break;
        }
    return GB_OK;
}

static gb_result store_triangle_materials(obj_parser *p, gb_scene *scene, gb_error *error)
{
    size_t slots = p->slot_names.count;
    uint32_t *slot_material = malloc((slots + 1) * sizeof *slot_material);
    if (!slot_material)
        return out_of_memory(p, error);
    gb_result result = resolve_slots(p, slot_material, scene, error);
    const uint32_t *triangle_slot = (const uint32_t *)p->triangle_slot.data;
    for (size_t t = 0; result == GB_OK && t < scene->triangle_count; ++t) {
        uint32_t slot = triangle_slot[t];
        scene->triangle_material[t] = slot_material[slot == NO_SLOT ? slots : slot];
    }
    free(slot_material);
    return result;
}

/* Corner attributes: count floats per element, 0 where a corner has none. */
static float *gather_corners(const array *values, const array *corner_index, int count)
{
    const float *source = (const float *)values->data;
    const int32_t *index = (const int32_t *)corner_index->data;
    float *out = calloc(corner_index->count * (size_t)count, sizeof *out);
    if (!out)
        return NULL;
    for (size_t c = 0; c < corner_index->count; ++c)
        if (index[c] >= 0)
            memcpy(out + c * (size_t)count, source + (size_t)index[c] * (size_t)count,
                   (size_t)count * sizeof *out);
    return out;
}

static gb_result build_scene(obj_parser *p, gb_scene *scene, gb_error *error)
{
    if (p->positions.count / 3 > UINT32_MAX / 2)
        return gb_fail(error, GB_ERROR_UNSUPPORTED, "%s: too many vertices", p->text.name);
    scene->vertex_count = (uint32_t)(p->positions.count / 3);
    scene->positions = (float *)p->positions.data;
    p->positions.data = NULL;
    scene->triangle_count = (uint32_t)(p->indices.count / 3);
    scene->indices = (uint32_t *)p->indices.data;
    p->indices.data = NULL;
    scene->triangle_material = calloc(scene->triangle_count + 1, sizeof(uint32_t));
    if (!scene->triangle_material)
        return out_of_memory(p, error);
    if (p->has_normals && !(scene->corner_normals = gather_corners(&p->normals,
                                                                   &p->corner_normal, 3)))
        return out_of_memory(p, error);
    if (p->has_texcoords && !(scene->corner_texcoords = gather_corners(&p->texcoords,
                                                                       &p->corner_texcoord, 2)))
        return out_of_memory(p, error);
    gb_result result = store_triangle_materials(p, scene, error);
    if (result != GB_OK)
        return result;
    scene->material_count = p->materials.count;
    scene->materials = p->materials.items;
    memset(&p->materials, 0, sizeof p->materials);
    free(scene->path);
    if (!(scene->path = strdup(p->text.name)))
        return out_of_memory(p, error);
    return GB_OK;
}

/* Parses a NUL-terminated buffer of size bytes. */
static gb_result parse_obj_terminated(const char *buffer, size_t size, const char *name,
                                      gb_obj_mtllib_reader read_mtllib, void *user,
                                      gb_scene *scene, gb_error *error)
{
    obj_parser p = {0};
    p.text = gb_text_start(buffer, size, name);
    p.read_mtllib = read_mtllib;
    p.user = user;
    p.slot = NO_SLOT;
    p.positions.element = p.texcoords.element = p.normals.element = sizeof(float);
    p.indices.element = p.triangle_slot.element = sizeof(uint32_t);
    p.corner_texcoord.element = p.corner_normal.element = sizeof(int32_t);
    p.face_v.element = p.face_vt.element = p.face_vn.element = sizeof(int32_t);
    p.slot_names.element = 64;
    gb_result result = GB_OK;
    gb_span line, key;
    while (result == GB_OK && gb_text_next_line(&p.text, &line))
        if (gb_span_next_token(&line, &key))
            result = read_obj_statement(&p, key, &line, error);
    if (result == GB_OK)
        result = build_scene(&p, scene, error);
    parser_free(&p);
    return result;
}

gb_result gb_obj_parse(const char *text, size_t size, const char *name,
                       gb_obj_mtllib_reader read_mtllib, void *user,
                       gb_scene *scene, gb_error *error)
{
    char *buffer;
    gb_result result = gb_text_copy(text, size, &buffer, error);
    if (result != GB_OK)
        return result;
    result = parse_obj_terminated(buffer, size, name, read_mtllib, user, scene, error);
    free(buffer);
    return result;
}

/* ---- files ------------------------------------------------------------------ */

/* What read_mtllib_file needs: the OBJ's folder, and the scene whose
 * inputs get each MTL file read. */
typedef struct mtllib_context {
    const char *folder;
    gb_scene *scene;
} mtllib_context;

/* The gb_obj_mtllib_reader of gb_obj_read: user is a mtllib_context. */
static gb_result read_mtllib_file(void *user, const char *mtllib, const char *obj_name,
                                  int obj_line, gb_material_list *materials, gb_error *error)
{
    mtllib_context *context = user;
    char *path = gb_path_join(context->folder, mtllib);
    if (!path)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s:%d: out of memory", obj_name,
                       obj_line);
    char *buffer = NULL, *folder = NULL;
    size_t size;
    gb_error reason;
    gb_result result = gb_text_load(path, &buffer, &size, &reason);
    if (result != GB_OK)
        gb_fail(error, result, "%s:%d: mtllib %s", obj_name, obj_line, reason.message);
    else if (!(folder = gb_path_folder(path)))
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    else
        result = parse_mtl_terminated(buffer, size, path, folder, materials, error);
    if (result == GB_OK)
        result = gb_scene_add_input(context->scene, path, error);
    free(folder);
    free(buffer);
    free(path);
    return result;
}

gb_result gb_obj_read(const char *path, gb_scene *scene, gb_error *error)
{
    char *buffer;
    size_t size;
    gb_result result = gb_text_load(path, &buffer, &size, error);
    if (result != GB_OK)
        return result;
    char *folder = gb_path_folder(path);
    if (!folder)
        result = gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    else
        result = parse_obj_terminated(buffer, size, path, read_mtllib_file,
                                      &(mtllib_context){folder, scene}, scene, error);
    free(folder);
    free(buffer);
    return result;
}
