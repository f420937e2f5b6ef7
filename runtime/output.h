/* output.h — the frame's linear HDR radiance (RGBA32F) and what leaves the
 * GPU from it:
 *   read back  glReadPixels into a gb_image (RGB, linear, row 0 at the top),
 *              which gb_image_write stores as linear EXR (to compare with
 *              the reference) or sRGB PNG (image.h converts);
 *   present    a full-screen pass that encodes sRGB (clamped) into the
 *              window's framebuffer.
 * Passes draw into it after gb_output_bind; a GI method adds its indirect
 * light with additive blending on top of the direct pass.
 *
 * Create → resize / bind / read / present → destroy (also on a zeroed one).
 */
#ifndef GB_OUTPUT_H
#define GB_OUTPUT_H

#include <epoxy/gl.h>

#include "image.h"
#include "result.h"

typedef struct gb_output {
    int width, height;
    GLuint radiance, framebuffer;
    GLuint present_program, empty_vertex_array;
} gb_output;

gb_result gb_output_create(int width, int height, gb_output *output, gb_error *error);
gb_result gb_output_resize(gb_output *output, int width, int height, gb_error *error);
/* Binds the framebuffer and sets the viewport to it. */
void gb_output_bind(const gb_output *output);
/* Clears the radiance to black. */
void gb_output_clear(const gb_output *output);
/* image is allocated here (RGB); the caller frees it. */
gb_result gb_output_read(const gb_output *output, gb_image *image, gb_error *error);
/* Draws the radiance, sRGB-encoded, into the default framebuffer of
 * width x height pixels (scaled when the sizes differ). */
void gb_output_present(const gb_output *output, int width, int height);
void gb_output_destroy(gb_output *output);

#endif
