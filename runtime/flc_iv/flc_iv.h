/* flc_iv.h — Forward Light Cuts with implicit visibility (--method flc-iv):
 * FLC's VPLs (runtime/flc/, Laurent 2016), each one's light on a pixel
 * kept only where implicit visibility's bins (runtime/implicit/, Dong 2007)
 * say nothing nearer lies between: indirect shadows with no bake. No seed
 * paper combines them; this folder is the one method built on two others,
 * and includes both.
 *
 * At create, on the CPU: implicit visibility's elements, hierarchy and
 * links (Algorithm 1, steps 1-7) with each element's depth map kept (for
 * each filled bin of its 6 x N x N cube map, the distance of the bin's
 * shortest link: the nearest surface seen that way, "a variant of
 * omni-directional shadow mapping", section 3). It goes to the GPU dense,
 * one 16-bit depth a bin and element in steps of the scene's diagonal /
 * GB_FLC_IV_DEPTH_FAR, rounded up (GB_FLC_IV_DEPTH_FAR + 1: an empty bin),
 * with the elements' centres. Dense rather than the links' sparse lists:
 * a binary search in them made the frame 1.5x slower (Cornell, 96x96,
 * N_avg 64: 30.8 against 20.0 ms; FLC alone 14.7).
 *
 * Each frame: the finer mesh is drawn with each triangle's element id into
 * the method's own target (with its own depth test) when the view changed,
 * then FLC draws as
 * ever, its splatting multiplied by flc_iv_visibility.frag.glsl: for the
 * pixel's element e and the VPL at y, with d = y - centre(e), r = |d|,
 * the bin of d holds the depth D; the VPL is seen when
 *     r <= D (1 + GB_FLC_IV_BIAS_BIN / N) + GB_FLC_IV_BIAS_ELEMENT x element size
 * (the bin's width and the element's own extent: a VPL on the surface the
 * bin sees is not its own occluder), and an empty bin sees everything.
 * The bilinear filter (the default, percentage-closer style) weighs the
 * test in the four bins nearest d by their distance to it, so that the
 * bins' edges do not show as blocks; nearest takes d's bin alone.
 */
#ifndef GB_FLC_IV_H
#define GB_FLC_IV_H

#include "indirect_method.h"

#define GB_FLC_IV_BIAS_BIN 2.0f
#define GB_FLC_IV_BIAS_ELEMENT 1.0f
#define GB_FLC_IV_DEPTH_FAR 65534.0f

enum { GB_FLC_IV_BILINEAR = 0, GB_FLC_IV_NEAREST = 1 };

extern const gb_indirect_method gb_flc_iv_method;

/* flc-iv's own gbview option (flc_iv_options.c); it reads flc's and
 * implicit's parameters besides. */
typedef struct gb_flc_iv_parameters {
    int bin_filter;             /* GB_FLC_IV_BILINEAR (0) or _NEAREST (--bin-filter) */
} gb_flc_iv_parameters;
extern const gb_method_option gb_flc_iv_options[];

#endif
