/* implicit_environment.h — a lat-long environment map into the bins (4.4;
 * implicit_environment.c). */
#ifndef GB_IMPLICIT_ENVIRONMENT_H
#define GB_IMPLICIT_ENVIRONMENT_H

#include "implicit_bins.h"
#include "result.h"
#include "scene.h"

/* Section 4.4 with a map (implicit_environment.c): the mean radiance of a
 * lat-long RGB map (formats/environment.h: its convention and lookup) over
 * each bin, times scale, into radiance (bins->count * 3, the caller's).
 * Each bin is sampled on a GB_IMPLICIT_MAP_SAMPLES^2 grid over its face
 * square, each sample weighted by its solid angle. */
#define GB_IMPLICIT_MAP_SAMPLES 8
gb_result gb_implicit_environment_bins(const gb_implicit_bins *bins, const gb_texture *map,
                                       float scale, float *radiance, gb_error *error);

#endif
