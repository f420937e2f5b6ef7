/* hud.h — a heads-up display: lines of text drawn over the window's image
 * (the method, the frame times, the key help), with stb_easy_font (Debian's
 * libstb-dev), whose glyphs are quads, no texture. runtime/hud.c;
 * hud.vert.glsl, hud.frag.glsl.
 *
 * Layout, in pixels of the bound framebuffer, origin at its top left: the
 * font's pixels (a line 12 high, stb_easy_font_width/height) times an
 * integer scale, gb_hud_scale(height) (2 at 720 rows, 3 at 1080); the text
 * on a translucent dark box (GB_HUD_PADDING font pixels around it), so that
 * white text reads on bright and dark images alike; the box
 * GB_HUD_MARGIN font pixels from the framebuffer's left edge and from its
 * top (GB_HUD_TOP_LEFT) or bottom (GB_HUD_BOTTOM_LEFT) edge. gb_hud_box
 * gives the box's rectangle. Text is ASCII; lines split at '\n'; any other
 * character outside ' '..'~' is drawn as '?'.
 *
 * The caller owns the gb_hud: create → draw, each frame, after the image is
 * in the framebuffer → destroy (also on a zeroed one). Needs a current
 * context.
 */
#ifndef GB_HUD_H
#define GB_HUD_H

#include <epoxy/gl.h>

#include "result.h"

typedef enum gb_hud_corner {
    GB_HUD_TOP_LEFT,
    GB_HUD_BOTTOM_LEFT,
} gb_hud_corner;

enum {
    GB_HUD_MARGIN = 4,          /* font pixels from the framebuffer's edges to the box */
    GB_HUD_PADDING = 2,         /* font pixels from the box's edges to the text */
};

typedef struct gb_hud {
    GLuint program, vertex_array, vertex_buffer, index_buffer;
    char *vertices;             /* the quads of the last text: stb_easy_font's
                                   16-byte vertices, the box's quad first */
    size_t vertex_bytes;        /* allocated */
    char *text;                 /* the last text, its characters made printable */
    size_t text_bytes;          /* allocated */
    GLsizei index_quads;        /* quads the index buffer holds */
} gb_hud;

gb_result gb_hud_create(gb_hud *hud, gb_error *error);

/* The scale of the font in a framebuffer height pixels high: height / 360,
 * at least 1. */
int gb_hud_scale(int height);

/* The box text is drawn on at corner of a framebuffer height pixels high
 * (whatever its width): box[0], box[1] its top left pixel (from the top
 * left), box[2], box[3] its width and height in pixels; all 0 when text
 * draws nothing (NULL, empty, or only line breaks). */
void gb_hud_box(const char *text, gb_hud_corner corner, int height, int box[4]);

/* Draws text at corner of the bound framebuffer, width x height pixels,
 * over what it holds (alpha blending). Turns off the depth test, the
 * scissor test and face culling for its draw and sets its own viewport
 * and blending, then restores all of them; it leaves its program and vertex
 * array bound. Draws nothing when out of memory. */
void gb_hud_draw(gb_hud *hud, const char *text, gb_hud_corner corner, int width, int height);

void gb_hud_destroy(gb_hud *hud);

#endif
