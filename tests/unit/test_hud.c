/* test_hud.c — the HUD (runtime/hud.h) drawn into a cleared RGBA8
 * framebuffer on llvmpipe and read back, against what stb_easy_font says
 * of the text on the CPU:
 *
 *  1. At 1280x720 (scale 2), top left: gb_hud_box is the text's size
 *     (stb_easy_font_width, _height) times the scale, padded, at the
 *     margin; every pixel outside it keeps the clear colour; inside, the
 *     pixels that the font's quads cover, scaled and placed at the text's
 *     corner, are white and only they, the others the box's one darker
 *     grey. The text's pixels lie in the text's own rectangle.
 *  2. At 640x360 (scale 1), bottom left: the same, the box at the bottom.
 *  3. A string of spaces: the box alone, no white pixel. An empty string,
 *     NULL, line breaks alone: nothing.
 *  4. Characters the font lacks are drawn as '?'.
 *  5. The GL state: with the scissor test (a 1-pixel box), the depth test
 *     and additive blending on and another viewport, the same image, and
 *     that state as it was after.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../../runtime/context.h"
#include "../../runtime/hud.h"
#include "tap.h"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

static const float background[4] = {0.5f, 0.5f, 0.5f, 1.0f};

/* An RGBA8 framebuffer to draw into. */
typedef struct target {
    int width, height;
    GLuint texture, framebuffer;
} target;

static void target_create(target *t, int width, int height)
{
    t->width = width;
    t->height = height;
    glCreateTextures(GL_TEXTURE_2D, 1, &t->texture);
    glTextureStorage2D(t->texture, 1, GL_RGBA8, width, height);
    glCreateFramebuffers(1, &t->framebuffer);
    glNamedFramebufferTexture(t->framebuffer, GL_COLOR_ATTACHMENT0, t->texture, 0);
}

static void target_destroy(target *t)
{
    glDeleteFramebuffers(1, &t->framebuffer);
    glDeleteTextures(1, &t->texture);
}

/* The target's pixels, RGBA, row 0 at the top (the caller frees them). */
static unsigned char *read_pixels(const target *t)
{
    size_t row = 4 * (size_t)t->width;
    unsigned char *rows = malloc(row * t->height), *pixels = malloc(row * t->height);
    if (!rows || !pixels) {
        free(rows);
        free(pixels);
        return NULL;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, t->framebuffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, t->width, t->height, GL_RGBA, GL_UNSIGNED_BYTE, rows);
    for (int y = 0; y < t->height; ++y)
        memcpy(pixels + (size_t)y * row, rows + (size_t)(t->height - 1 - y) * row, row);
    free(rows);
    return pixels;
}

/* The target cleared, then text drawn on it; its pixels read back. */
static unsigned char *draw(gb_hud *hud, const target *t, const char *text, gb_hud_corner corner)
{
    glClearNamedFramebufferfv(t->framebuffer, GL_COLOR, 0, background);
    glBindFramebuffer(GL_FRAMEBUFFER, t->framebuffer);
    gb_hud_draw(hud, text, corner, t->width, t->height);
    return read_pixels(t);
}

/* 1 where the font's quads for text cover a pixel: its quads scaled and
 * placed with the text's top left corner at (x0, y0) (the caller frees
 * the mask); NULL when out of memory. */
static unsigned char *glyph_mask(const char *text, int scale, int x0, int y0, int width,
                                 int height)
{
    static char vertices[1 << 20];
    unsigned char *mask = calloc((size_t)width * height, 1);
    if (!mask)
        return NULL;
    int quads = stb_easy_font_print(0, 0, (char *)text, NULL, vertices, sizeof vertices);
    for (int q = 0; q < quads; ++q) {
        const float *a = (const float *)(vertices + 64 * q);        /* corner 0 */
        const float *b = (const float *)(vertices + 64 * q + 32);   /* corner 2 */
        for (int y = y0 + scale * (int)a[1]; y < y0 + scale * (int)b[1]; ++y)
            for (int x = x0 + scale * (int)a[0]; x < x0 + scale * (int)b[0]; ++x)
                if (x >= 0 && y >= 0 && x < width && y < height)
                    mask[(size_t)y * width + x] = 1;
    }
    return mask;
}

/* What the image shows against the clear colour. */
typedef struct tally {
    long outside_changed;       /* pixels outside the box not the clear colour */
    long glyph_wrong;           /* glyph pixels not white */
    long box_wrong;             /* box pixels off the glyphs not the box's grey */
    long white, white_outside_text; /* white pixels; of them outside the text's rectangle */
    int box_grey;               /* the box's grey (-1 when no box pixel is off the glyphs) */
} tally;

static int inside(const int rect[4], int x, int y)
{
    return x >= rect[0] && x < rect[0] + rect[2] && y >= rect[1] && y < rect[1] + rect[3];
}

static int is_white(const unsigned char *p)
{
    return p[0] == 255 && p[1] == 255 && p[2] == 255;
}

static tally count(const unsigned char *pixels, const unsigned char *mask, const int box[4],
                   const int text_rect[4], int width, int height, int clear)
{
    tally t = {.box_grey = -1};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const unsigned char *p = pixels + 4 * ((size_t)y * width + x);
            int white = is_white(p), glyph = mask[(size_t)y * width + x];
            t.white += white;
            t.white_outside_text += white && !inside(text_rect, x, y);
            if (!inside(box, x, y)) {
                t.outside_changed += p[0] != clear || p[1] != clear || p[2] != clear;
            } else if (glyph) {
                t.glyph_wrong += !white;
            } else {
                if (t.box_grey < 0)
                    t.box_grey = p[0];
                t.box_wrong += p[0] != t.box_grey || p[1] != t.box_grey || p[2] != t.box_grey;
            }
        }
    return t;
}

/* Draws text at corner of t and checks the image against the font's own
 * quads (checks 1 and 2); `what` names the case. */
static void check_text(gb_hud *hud, const target *t, const char *text, gb_hud_corner corner,
                       int scale, const char *what)
{
    char message[256];
    int w = stb_easy_font_width((char *)text), h = stb_easy_font_height((char *)text);
    int m = GB_HUD_MARGIN * scale, p = GB_HUD_PADDING * scale;
    int box_height = (h + 2 * GB_HUD_PADDING) * scale;
    int expected[4] = {m, corner == GB_HUD_TOP_LEFT ? m : t->height - m - box_height,
                       (w + 2 * GB_HUD_PADDING) * scale, box_height};
    int box[4];
    gb_hud_box(text, corner, t->height, box);
    snprintf(message, sizeof message, "%s: the box is the font's size times %d, padded, at the margin",
             what, scale);
    CHECK(memcmp(box, expected, sizeof box) == 0, message);
    const int text_rect[4] = {box[0] + p, box[1] + p, w * scale, h * scale};
    unsigned char *pixels = draw(hud, t, text, corner);
    unsigned char *mask = glyph_mask(text, scale, text_rect[0], text_rect[1], t->width, t->height);
    if (!CHECK(pixels && mask, "memory for the images")) {
        free(pixels);
        free(mask);
        return;
    }
    int clear = pixels[0];      /* the corner pixel, outside any box */
    tally c = count(pixels, mask, box, text_rect, t->width, t->height, clear);
    printf("# %s: box %d,%d %dx%d; %ld white pixels (%ld outside the text's rectangle), "
           "%ld glyph pixels not white, %ld box pixels off the glyphs not its grey %d, "
           "%ld pixels outside the box changed (clear %d)\n",
           what, box[0], box[1], box[2], box[3], c.white, c.white_outside_text, c.glyph_wrong,
           c.box_wrong, c.box_grey, c.outside_changed, clear);
    snprintf(message, sizeof message, "%s: no pixel outside the box changed", what);
    CHECK(c.outside_changed == 0, message);
    snprintf(message, sizeof message, "%s: the font's quads, scaled, are white", what);
    CHECK(c.white > 0 && c.glyph_wrong == 0, message);
    snprintf(message, sizeof message,
             "%s: the rest of the box is one grey, darker than the clear colour", what);
    CHECK(c.box_wrong == 0 && c.box_grey >= 0 && c.box_grey < clear, message);
    snprintf(message, sizeof message, "%s: white only inside the text's rectangle", what);
    CHECK(c.white_outside_text == 0, message);
    free(pixels);
    free(mask);
}

static const char lines[] = "gibake  octree, atlas 37 %\n"
                            "frame 12.5 ms (budget 16 ms)\n"
                            "{[(|gjpqy_~)]}";

static void test_spaces_and_nothing(gb_hud *hud, const target *t)
{
    int box[4];
    gb_hud_box("     ", GB_HUD_TOP_LEFT, t->height, box);
    unsigned char *pixels = draw(hud, t, "     ", GB_HUD_TOP_LEFT);
    unsigned char *mask = calloc((size_t)t->width * t->height, 1);
    if (CHECK(pixels && mask, "spaces: drawn and read back")) {
        int p = GB_HUD_PADDING * gb_hud_scale(t->height);
        const int text_rect[4] = {box[0] + p, box[1] + p, box[2] - 2 * p, box[3] - 2 * p};
        tally c = count(pixels, mask, box, text_rect, t->width, t->height, pixels[0]);
        CHECK(box[2] > 0 && c.white == 0 && c.outside_changed == 0 && c.box_wrong == 0 &&
                  c.box_grey >= 0 && c.box_grey < pixels[0],
              "spaces: the box alone, one grey, nothing else changed");
    }
    free(pixels);
    free(mask);
    const char *nothing[3] = {"", NULL, "\n\n"};
    for (int i = 0; i < 3; ++i) {
        gb_hud_box(nothing[i], GB_HUD_TOP_LEFT, t->height, box);
        pixels = draw(hud, t, nothing[i], GB_HUD_TOP_LEFT);
        long changed = 0;
        for (size_t k = 0; pixels && k < (size_t)t->width * t->height; ++k)
            changed += memcmp(pixels + 4 * k, pixels, 4) != 0;
        CHECK(pixels && changed == 0 && box[2] == 0 && box[3] == 0,
              i == 0 ? "empty text: nothing drawn, no box"
                     : i == 1 ? "NULL text: nothing drawn, no box"
                              : "line breaks alone: nothing drawn, no box");
        free(pixels);
    }
}

static int same_image(gb_hud *hud, const target *t, const char *a, const char *b)
{
    unsigned char *first = draw(hud, t, a, GB_HUD_TOP_LEFT);
    unsigned char *second = draw(hud, t, b, GB_HUD_TOP_LEFT);
    int same = first && second && memcmp(first, second, 4 * (size_t)t->width * t->height) == 0;
    free(first);
    free(second);
    return same;
}

/* The state gb_hud_draw promises to put back. */
typedef struct state {
    GLboolean scissor, depth, blend;
    GLint scissor_box[4], viewport[4], source, destination;
} state;

static state get_state(void)
{
    state s;
    memset(&s, 0, sizeof s);  /* its padding too: the states are compared with memcmp */
    s.scissor = glIsEnabled(GL_SCISSOR_TEST);
    s.depth = glIsEnabled(GL_DEPTH_TEST);
    s.blend = glIsEnabled(GL_BLEND);
    glGetIntegerv(GL_SCISSOR_BOX, s.scissor_box);
    glGetIntegerv(GL_VIEWPORT, s.viewport);
    glGetIntegerv(GL_BLEND_SRC_RGB, &s.source);
    glGetIntegerv(GL_BLEND_DST_RGB, &s.destination);
    return s;
}

static void test_gl_state(gb_hud *hud, const target *t)
{
    unsigned char *plain = draw(hud, t, lines, GB_HUD_TOP_LEFT);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, 0, 1, 1);
    glEnable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glViewport(3, 5, 17, 19);
    state before = get_state();
    glBindFramebuffer(GL_FRAMEBUFFER, t->framebuffer);
    glDisable(GL_SCISSOR_TEST);     /* the clear covers the whole target */
    glClearNamedFramebufferfv(t->framebuffer, GL_COLOR, 0, background);
    glEnable(GL_SCISSOR_TEST);
    gb_hud_draw(hud, lines, GB_HUD_TOP_LEFT, t->width, t->height);
    state after = get_state();
    unsigned char *drawn = read_pixels(t);
    CHECK(plain && drawn && memcmp(plain, drawn, 4 * (size_t)t->width * t->height) == 0,
          "scissor, depth test, additive blending and a viewport set: the same image");
    CHECK(memcmp(&before, &after, sizeof before) == 0,
          "the scissor, depth test, blending and viewport as they were");
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    free(plain);
    free(drawn);
}

int main(void)
{
    gb_context context;
    gb_error error;
    memset(&context, 0, sizeof context);
    if (!CHECK(gb_context_create_headless(&context, &error) == GB_OK, "a headless context")) {
        printf("# %s\n", error.message);
        return tap_done();
    }
    gb_hud hud;
    if (CHECK(gb_hud_create(&hud, &error) == GB_OK, "the HUD created")) {
        CHECK(gb_hud_scale(720) == 2 && gb_hud_scale(1080) == 3 && gb_hud_scale(360) == 1 &&
                  gb_hud_scale(100) == 1,
              "scale: 2 at 720 rows, 3 at 1080, 1 at 360 and below");
        target large, small;
        target_create(&large, 1280, 720);
        target_create(&small, 640, 360);
        check_text(&hud, &large, lines, GB_HUD_TOP_LEFT, 2, "1280x720, top left");
        check_text(&hud, &small, lines, GB_HUD_BOTTOM_LEFT, 1, "640x360, bottom left");
        test_spaces_and_nothing(&hud, &large);
        CHECK(same_image(&hud, &small, "tab\there \x01\x7f\xe9", "tab?here ???"),
              "characters the font lacks are drawn as '?'");
        test_gl_state(&hud, &large);
        target_destroy(&large);
        target_destroy(&small);
        CHECK(gb_gl_check(&context.errors, "hud", &error) == GB_OK, "no GL error");
    } else {
        printf("# %s\n", error.message);
    }
    gb_hud_destroy(&hud);
    gb_hud zeroed = {0};
    gb_hud_destroy(&zeroed);
    gb_context_destroy(&context);
    return tap_done();
}
