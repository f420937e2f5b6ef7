/* flc.h — Forward Light Cuts (Laurent, Delalandre, de La Rivière & Boubekeur
 * 2016) as a GI method of the runtime (indirect_method.h): the first bounce
 * of diffuse light, unshadowed, from VPLs made of the scene's triangles
 * themselves each frame, with no precomputation.
 *
 * Each frame, on the GPU, without a CPU wait:
 *   1. VPL generation, in two pipelines (Sec. 6). The regular one: a compute
 *      pass over the scene's triangles (flc_decimation.h's list, regular ones
 *      first): u_i from the per-frame u_rand and the triangle's v_rand (Alg.
 *      2), the level by Alg. 1 (or discarded), the VPL centre y_i jittered
 *      uniformly over the triangle, and the direct irradiance E at y_i on
 *      each side of it from the runtime's lights and shadow maps (the light
 *      conventions of common/brdf.h). The same pass appends each divergent
 *      triangle (area > S̄_N) to the divergent buffer, as patches, and counts
 *      them in an indirect draw command; the divergent pipeline draws them
 *      (glDrawArraysIndirect, rasterizer off) through the tessellation stage,
 *      which subdivides them in model space (flc_decimation.h), and a
 *      geometry shader that makes each sub-triangle's VPL as above (u_i from
 *      the base v_rand XOR the sub-vertices' v_rand_tess, Alg. 2, Fig. 8) and
 *      appends it, counted in a second indirect command;
 *   2. splatting, of each pipeline's VPLs (the divergent ones by the second
 *      indirect draw) (points → geometry shader → one screen-space quad a side
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
 * of K estimates. A frame (an image of indirect_method.h) is one sample,
 * drawn in parts cut by VPLs: part 0 clears the splat target and runs the
 * regular generation, each part splats its share of the regular VPLs in
 * order, the last part runs the divergent pipeline and passes 3 and 4, so
 * that the image is the same bytes whatever the number of parts. draw says
 * the image is final at GB_FLC_CONVERGED_SAMPLES.
 *
 * Departures from the paper. For the reference's sake: the VPL emits as
 * a Lambertian surface (radiance rho E / pi, brdf.h's VPL) rather than Eq. 6's
 * 3/(2 pi) cos lobe, and from both sides of the triangle, each with its own
 * E (surfaces reflect on both sides in gibake); the last level's support
 * extends to infinity (flc_decimation.h). Otherwise: v_rand_tess is a hash of the
 * sub-vertex's barycentric coordinates rather than a noise texture's texel;
 * the divergent triangles are split from the regular ones once, on the CPU
 * (the scene is static: the list is sorted), and the compute pass, not a
 * geometry shader, appends them; a textured VPL's albedo is its material's
 * Kd times the texture's mean.
 */
#ifndef GB_FLC_H
#define GB_FLC_H

#include "flc_decimation.h"
#include "indirect_method.h"

enum {
    GB_FLC_NO_DECIMATION = -1,      /* flc_levels: keep every VPL triangle (keep_all of
                                       flc_decimation.h) over the default levels' list */
    GB_FLC_DEFAULT_N_AVG = 256,
    GB_FLC_DEFAULT_LEVELS = 6,      /* N = 5, as the paper's Fig. 10 */
    GB_FLC_MAX_TILING = 4,
};
/* The samples after which gb_flc_draw says its image is final: the noise
 * of a mean of 256 is 1/16 of one sample's. */
enum { GB_FLC_CONVERGED_SAMPLES = 256 };
#define GB_FLC_DEFAULT_MU 2.0f
#define GB_FLC_D_NEAR_FRACTION 0.2f /* D_near = 0.2 R_scene (Sec. 4) */
#define GB_FLC_EPSILON_FRACTION 0.01f

extern const gb_indirect_method gb_flc_method;

/* flc's gbview options (flc_options.c); zero fields: the defaults. */
typedef struct gb_flc_parameters {
    float mu;                   /* mu > 1 of S_k = S0 mu^k, Eq. 17 (--mu; 2) */
    float n_avg;                /* N_avg of Eq. 1 (--navg; 256) */
    float epsilon;              /* the distance clamp epsilon, world units
                                   (--epsilon; 0.01 x the scene's radius) */
    int tiling;                 /* 4^tiling interleaved tiles (--tiling; 0) */
    int levels;                 /* N + 1, the number of levels (--levels; 6), or
                                   GB_FLC_NO_DECIMATION (--no-decimation) */
} gb_flc_parameters;
extern const gb_method_option gb_flc_options[];

/* A visibility term for the splatting, for methods built on FLC
 * (runtime/flc_iv/): glsl defines
 *   float flc_visibility(ivec2 pixel, vec3 x, vec3 y)
 * the fraction of the VPL at y that the receiver x of the full-frame pixel
 * sees, and may declare the buffers and textures it reads; bind, when not
 * NULL, binds them and sets its uniforms, called each frame with the splat
 * program in use. Both are borrowed: they outlive the FLC state. */
typedef struct gb_flc_visibility {
    const char *glsl;
    void (*bind)(void *context, GLuint splat_program);
    void *context;
} gb_flc_visibility;

/* gb_flc_method's create with a visibility term (NULL: unshadowed, as
 * gb_flc_method); draw and destroy are gb_flc_method's. */
gb_result gb_flc_create(const gb_indirect_setup *setup, const gb_flc_visibility *visibility,
                        void **state, gb_error *error);
int gb_flc_draw(void *state, const gb_indirect_frame *frame);
void gb_flc_destroy(void *state);

/* The levels of scene for parameters (zero fields: defaults), R_scene half
 * the diagonal of its bounds; flc_levels GB_FLC_NO_DECIMATION: the default
 * count of levels with keep_all set. */
void gb_flc_scene_levels(const gb_scene *scene, const gb_flc_parameters *parameters,
                         gb_flc_levels *levels);

/* Per-pass times (the paper's Table 1), summed over the frames drawn while
 * measuring: each pass is closed by glFinish and timed by the wall clock,
 * which costs some parallelism, so only benchmarks turn it on. The regular
 * pipeline is VPL generation and splatting of the regular triangles, the
 * divergent one the appending, tessellation, VPL generation and splatting of
 * the divergent ones; resolve is the untiling, blur and accumulation, and
 * the composite. */
typedef struct gb_flc_pass_times {
    double regular_ms, divergent_ms, resolve_ms;
    double cpu_ms;                  /* the process's CPU time over the same passes
                                       (llvmpipe's threads included): less
                                       sensitive to other jobs than the wall clock */
    uint32_t frames;
    uint32_t regular_triangles, divergent_triangles;   /* scene triangles of each */
    uint64_t divergent_vpls;        /* VPLs the tessellation made, over the frames */
} gb_flc_pass_times;

/* On a state gb_flc_method.create made: measure (1) or not (0, the default)
 * the frames drawn from now on. */
void gb_flc_measure(void *state, int on);
void gb_flc_times(const void *state, gb_flc_pass_times *times);

#endif
