/* flc.h — Forward Light Cuts (Laurent, Delalandre, de La Rivière & Boubekeur
 * 2016) as a GI method of the runtime (indirect_method.h): the first bounce
 * of diffuse light, unshadowed, from VPLs made of the scene's triangles
 * themselves each frame, with no precomputation.
 *
 * Each frame, on the GPU:
 *   1. VPL generation (a compute pass over the VPL triangles of
 *      flc_decimation.h, divergent ones already subdivided): u_i from the
 *      per-frame u_rand and the triangle's v_rand (Alg. 2), the level by
 *      Alg. 1 (or discarded), the VPL centre y_i jittered uniformly over the
 *      triangle, and the direct irradiance E at y_i on each side of it from
 *      the runtime's lights and shadow maps (the light conventions of
 *      common/brdf.h);
 *   2. splatting (points → geometry shader → one screen-space quad a side
 *      around the ball of Eq. 13 that bounds the support of f^k, D_{k+1};
 *      the last level covers the screen): the fragment shader reads the
 *      G-buffer and adds H(t_i, x, n_x) S_k f^k(d(t_i, x)) (Eqs. 5, 7, 10,
 *      14, 16), without the receiver's albedo, into one of 4^tiling
 *      interleaved tiles picked at random per VPL (Sec. 6);
 *   3. untile + blur: each pixel averages its 2^tiling x 2^tiling block
 *      (one pixel of every tile) over the pixels of the same surface, times
 *      its albedo / pi, added into an accumulation buffer;
 *   4. the mean of the accumulated frames is added onto the output.
 * Progressive: a new u_rand and new jitter each frame; the accumulation
 * starts again when the view or the size changes, so frame K shows the mean
 * of K estimates.
 *
 * Departures from the paper, each for the reference's sake: the VPL emits as
 * a Lambertian surface (radiance rho E / pi, brdf.h's VPL) rather than Eq. 6's
 * 3/(2 pi) cos lobe, and from both sides of the triangle, each with its own
 * E (surfaces reflect on both sides in gibake); the last level's support
 * extends to infinity (flc_decimation.h); divergent triangles are
 * subdivided once on the CPU (the scene is static) rather than by the
 * tessellation stage; a textured VPL's albedo is its material's Kd times the
 * texture's mean.
 */
#ifndef GB_FLC_H
#define GB_FLC_H

#include "flc_decimation.h"
#include "indirect_method.h"

enum {
    GB_FLC_DEFAULT_N_AVG = 256,
    GB_FLC_DEFAULT_LEVELS = 6,      /* N = 5, as the paper's Fig. 10 */
    GB_FLC_MAX_TILING = 4,
};
#define GB_FLC_DEFAULT_MU 2.0f
#define GB_FLC_D_NEAR_FRACTION 0.2f /* D_near = 0.2 R_scene (Sec. 4) */
#define GB_FLC_EPSILON_FRACTION 0.01f

extern const gb_indirect_method gb_flc_method;

/* The levels of scene for parameters (zero fields: defaults), R_scene half
 * the diagonal of its bounds. */
void gb_flc_scene_levels(const gb_scene *scene, const gb_method_parameters *parameters,
                         gb_flc_levels *levels);

#endif
