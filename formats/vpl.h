/* vpl.h — a set of virtual point lights (VPLs) on disk: the file kind "VPLS"
 * (formats/FORMATS.md, "VPL set"). The runtime writes the VPLs it renders
 * with; `reference --vpl FILE` renders the same VPLs with exact visibility.
 *
 * A VPL is a one-sided diffuse emitter (common/brdf.h): position p, unit
 * normal m, power P (W, RGB); it sends intensity P max(0, dot(m, w)) / pi
 * toward w. The set records the hash of the scene it was made from
 * (gb_scene.hash) so that a reader can refuse a stale set.
 *
 *   gb_vpl_set set = {.scene_hash = scene.hash, .count = n, .vpls = array};
 *   gb_vpl_write("out.vpls", &set, &error);      // temp file, rename
 *   gb_vpl_read("out.vpls", &set, &error);       // checks every byte
 *   gb_vpl_free(&set);
 *
 * A set filled by gb_vpl_read or gb_vpl_parse owns its array (a copy) and is
 * released with gb_vpl_free; gb_vpl_write does not take ownership.
 */
#ifndef GB_VPL_H
#define GB_VPL_H

#include <stddef.h>
#include <stdint.h>

#include "result.h"

enum { GB_VPL_VERSION = 1 };

typedef struct gb_vpl {
    float position[3];
    float normal[3];            /* unit */
    float power[3];             /* W, >= 0 */
} gb_vpl;

typedef struct gb_vpl_set {
    uint64_t scene_hash;
    uint32_t count;
    gb_vpl *vpls;
} gb_vpl_set;

/* Checks a set (finite positions, unit normals within 1e-3, finite
 * non-negative powers). path names the set in messages. */
gb_result gb_vpl_check(const gb_vpl_set *set, const char *path, gb_error *error);

gb_result gb_vpl_write(const char *path, const gb_vpl_set *set, gb_error *error);

/* On failure *set is zeroed and needs no freeing. */
gb_result gb_vpl_read(const char *path, gb_vpl_set *set, gb_error *error);

/* The same on a buffer in memory (tests, fuzzing); path names it in messages. */
gb_result gb_vpl_parse(const void *bytes, size_t size, const char *path, gb_vpl_set *set,
                       gb_error *error);

/* GB_ERROR_STALE unless the set was made from the scene of this hash. */
gb_result gb_vpl_check_scene(const gb_vpl_set *set, uint64_t scene_hash, const char *path,
                             gb_error *error);

void gb_vpl_free(gb_vpl_set *set);

#endif
