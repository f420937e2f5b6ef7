/* packed_texture.h — the diffuse textures of a scene in 4 bytes a texel
 * instead of 12, so that more of them stay in cache while paths wander.
 *
 * The scene loader decodes 8-bit files (PNG, JPEG) to linear floats; each
 * channel value then comes from one of 256 codes. Packing finds the code of
 * every value and keeps, per texture, the 256 floats the loader produced, so
 * a packed lookup returns exactly the loader's floats. A texture whose values
 * do not come from 256 sRGB codes (an EXR, say) is not packed and is read
 * as floats. Packed texels are stored in 4x4 tiles of one cache line each,
 * so the 2x2 texels of a bilinear lookup mostly share a line. Lookups are
 * bilinear and repeat (common/brdf.h).
 */
#ifndef GB_PACKED_TEXTURE_H
#define GB_PACKED_TEXTURE_H

#include <stdint.h>

#include "scene.h"
#include "vec3.h"

typedef struct gb_packed_texture {
    const gb_texture *source;   /* the loader's floats */
    uint32_t *codes;            /* R | G << 8 | B << 16 in 4x4 tiles, or NULL */
    int tiles_x;                /* tiles in a row of tiles */
    int owns_codes;             /* 0 when shared with another material's */
    float decode[256];          /* code -> the loader's linear value */
} gb_packed_texture;

/* Packs texture if it can; otherwise leaves codes NULL (and reads floats). */
gb_result gb_packed_texture_make(const gb_texture *texture, gb_packed_texture *packed,
                                 gb_error *error);
void gb_packed_texture_free(gb_packed_texture *packed);

/* The same texture for another material (same file): shares the codes. */
void gb_packed_texture_share(const gb_packed_texture *from, const gb_texture *texture,
                             gb_packed_texture *packed);

/* The 2x2 texels of a bilinear lookup and their weights. */
typedef struct gb_texture_footprint {
    int x0, y0;                 /* top-left texel, -1..size - 1 (wrapped when read) */
    float ax, ay;               /* weights of the right column and the lower row */
} gb_texture_footprint;

/* The footprint of texture coordinates (s, t) (t = 0 is the bottom row),
 * whose texels are asked of the memory system now so that
 * gb_packed_texture_read, a little later, finds them in cache. The texture
 * must have pixels. */
gb_texture_footprint gb_packed_texture_prefetch(const gb_packed_texture *packed, float s,
                                                float t);

/* The bilinear, repeating value over a footprint. */
gb_vec3 gb_packed_texture_read(const gb_packed_texture *packed, gb_texture_footprint f);

/* Both at once. */
gb_vec3 gb_packed_texture_lookup(const gb_packed_texture *packed, float s, float t);

#endif
