/* vpl.c — the VPL set file (formats/vpl.h, formats/FORMATS.md "VPL set").
 * Fields are encoded little-endian byte by byte, whatever the host. */
#include "vpl.h"
#include "little_endian.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "container.h"
#include "container_kind.h"

enum {
    HEADER_SIZE = 16,           /* count u32, reserved u32, scene hash u64 */
    VPL_SIZE = 36,              /* 9 float32: position, normal, power */
};

static int is_unit(const float v[3])
{
    double length = sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]);
    return fabs(length - 1.0) <= 1e-3;
}

gb_result gb_vpl_check(const gb_vpl_set *set, const char *path, gb_error *error)
{
    if (set->count && !set->vpls)
        return gb_fail(error, GB_ERROR_ARGUMENT, "%s: %u VPLs without an array", path,
                       (unsigned)set->count);
    for (uint32_t i = 0; i < set->count; ++i) {
        const gb_vpl *vpl = &set->vpls[i];
        for (int k = 0; k < 3; ++k) {
            if (!isfinite(vpl->position[k]) || !isfinite(vpl->normal[k]))
                return gb_fail(error, GB_ERROR_INVALID, "%s: VPL %u: coordinate is not finite",
                               path, (unsigned)i);
            if (!isfinite(vpl->power[k]) || vpl->power[k] < 0.0f)
                return gb_fail(error, GB_ERROR_INVALID,
                               "%s: VPL %u: power must be finite and non-negative", path,
                               (unsigned)i);
        }
        if (!is_unit(vpl->normal))
            return gb_fail(error, GB_ERROR_INVALID, "%s: VPL %u: normal is not unit", path,
                           (unsigned)i);
    }
    return GB_OK;
}

static void encode_vpl(unsigned char *p, const gb_vpl *vpl)
{
    for (int k = 0; k < 3; ++k) {
        gb_put_f32(p + 4 * k, vpl->position[k]);
        gb_put_f32(p + 12 + 4 * k, vpl->normal[k]);
        gb_put_f32(p + 24 + 4 * k, vpl->power[k]);
    }
}

static void decode_vpl(const unsigned char *p, gb_vpl *vpl)
{
    for (int k = 0; k < 3; ++k) {
        vpl->position[k] = gb_get_f32(p + 4 * k);
        vpl->normal[k] = gb_get_f32(p + 12 + 4 * k);
        vpl->power[k] = gb_get_f32(p + 24 + 4 * k);
    }
}

static gb_result commit(const char *path, const unsigned char *header,
                        const unsigned char *payload, uint64_t payload_size, gb_error *error)
{
    const gb_container_array arrays[] = {
        {"header", 1, HEADER_SIZE, header},
        {"vpls", 1, payload_size, payload},
    };
    return gb_container_write_arrays(path, "VPLS", GB_VPL_VERSION, arrays, 2, error);
}

gb_result gb_vpl_write(const char *path, const gb_vpl_set *set, gb_error *error)
{
    gb_result result = gb_vpl_check(set, path, error);
    if (result != GB_OK)
        return result;
    unsigned char header[HEADER_SIZE];
    gb_put_u32(header, set->count);
    gb_put_u32(header + 4, 0);
    gb_put_u32(header + 8, (uint32_t)set->scene_hash);
    gb_put_u32(header + 12, (uint32_t)(set->scene_hash >> 32));
    uint64_t payload_size = (uint64_t)set->count * VPL_SIZE;
    unsigned char *payload = malloc(payload_size ? payload_size : 1);
    if (!payload)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    for (uint32_t i = 0; i < set->count; ++i)
        encode_vpl(payload + (size_t)i * VPL_SIZE, &set->vpls[i]);
    result = commit(path, header, payload, payload_size, error);
    free(payload);
    return result;
}

static gb_result read_header(const gb_container *container, const char *path, gb_vpl_set *set,
                             gb_error *error)
{
    const gb_section *header;
    gb_result result = gb_container_find_array(container, "header", 1, HEADER_SIZE, 1, path,
                                               &header, error);
    if (result != GB_OK)
        return result;
    const unsigned char *bytes = header->data;
    if (gb_get_u32(bytes + 4) != 0)
        return gb_fail(error, GB_ERROR_FORMAT, "%s: reserved header field is not zero", path);
    set->count = gb_get_u32(bytes);
    set->scene_hash = (uint64_t)gb_get_u32(bytes + 8) | (uint64_t)gb_get_u32(bytes + 12) << 32;
    return GB_OK;
}

static gb_result read_vpls(const gb_container *container, const char *path, gb_vpl_set *set,
                           gb_error *error)
{
    const gb_section *vpls;
    gb_result result = gb_container_find_array(container, "vpls", set->count, VPL_SIZE, 1, path,
                                               &vpls, error);
    if (result != GB_OK)
        return result;
    set->vpls = malloc(set->count ? (size_t)set->count * sizeof *set->vpls : 1);
    if (!set->vpls)
        return gb_fail(error, GB_ERROR_OUT_OF_MEMORY, "%s: out of memory", path);
    const unsigned char *bytes = vpls->data;
    for (uint32_t i = 0; i < set->count; ++i)
        decode_vpl(bytes + (size_t)i * VPL_SIZE, &set->vpls[i]);
    return GB_OK;
}

/* Fills the set from a checked VPLS container (container_kind.h). */
static gb_result read_container(const gb_container *container, const char *path, void *object,
                                gb_error *error)
{
    gb_vpl_set *set = object;
    gb_result result = read_header(container, path, set, error);
    if (result == GB_OK)
        result = read_vpls(container, path, set, error);
    if (result == GB_OK)
        result = gb_vpl_check(set, path, error);
    if (result != GB_OK)
        gb_vpl_free(set);
    return result;
}

static const gb_container_kind vpl_kind = {
    "VPLS", GB_VPL_VERSION, sizeof(gb_vpl_set), read_container, 0};

gb_result gb_vpl_read(const char *path, gb_vpl_set *set, gb_error *error)
{
    return gb_container_kind_read(path, &vpl_kind, set, error);
}

gb_result gb_vpl_parse(const void *bytes, size_t size, const char *path, gb_vpl_set *set,
                       gb_error *error)
{
    return gb_container_kind_parse(bytes, size, path, &vpl_kind, set, error);
}

gb_result gb_vpl_check_scene(const gb_vpl_set *set, uint64_t scene_hash, const char *path,
                             gb_error *error)
{
    if (set->scene_hash != scene_hash)
        return gb_fail(error, GB_ERROR_STALE, "%s: made from another scene (hash %016llx, the "
                       "scene's is %016llx)", path, (unsigned long long)set->scene_hash,
                       (unsigned long long)scene_hash);
    return GB_OK;
}

void gb_vpl_free(gb_vpl_set *set)
{
    free(set->vpls);
    *set = (gb_vpl_set){0};
}
