/* gl_util.h — what every GPU pass of the runtime shares: the one place GL
 * errors are collected, shader programs built from their GLSL, and
 * textures and the empty vertex array of full-screen passes.
 *
 * Shaders: each stage is a file beside the pass's C file, PASS.STAGE.glsl,
 * which the Makefile embeds as a C string literal (its "Shaders" rule;
 * snippets that several stages share, NAME.glsl, spliced in where a stage
 * says #include "PATH"); the pass takes it as a source:
 *     static const char present_shader[] =
 *     #include "runtime/output_present.frag.glsl.inc"
 *         ;
 *
 * Errors: gb_gl_errors_install turns on KHR_debug output (core since 4.3)
 * with a callback that keeps the first error message and counts them; it is
 * synchronous in debug builds (without NDEBUG), so a debugger stops on the
 * faulty call. Passes do not check after each call: the renderer calls
 * gb_gl_check once per frame (and after setup), which also drains
 * glGetError, and turns whatever was collected into a gb_error.
 *
 * The caller owns the gb_gl_errors (the context keeps it) and every GL
 * object made here.
 */
#ifndef GB_GL_UTIL_H
#define GB_GL_UTIL_H

#include <epoxy/gl.h>

#include "result.h"

typedef struct gb_gl_errors {
    unsigned count;             /* errors since the last gb_gl_check */
    char first[512];            /* the first one's message */
} gb_gl_errors;

/* Needs a current context; errors must stay at the same address while it is. */
void gb_gl_errors_install(gb_gl_errors *errors);
/* GB_OK when no error was collected since the last call; otherwise
 * GB_ERROR_INVALID with "OpenGL: <where>: <first message> (and N more)". */
gb_result gb_gl_check(gb_gl_errors *errors, const char *where, gb_error *error);

/* Fails (GB_ERROR_UNSUPPORTED) below OpenGL 4.5. */
gb_result gb_gl_require_45(gb_error *error);

/* One stage of a program: its type (GL_VERTEX_SHADER, GL_COMPUTE_SHADER,
 * ...) and its GLSL source in pieces, NULL-ended (the "#version 450 core"
 * line first), concatenated by the compiler. */
typedef struct gb_gl_stage {
    GLenum type;
    const char *const *parts;
} gb_gl_stage;

/* The one program builder: compiles and links count stages. name is used in
 * messages (GB_ERROR_INVALID), which carry the compiler's or linker's log. */
gb_result gb_gl_program_stages(const char *name, const gb_gl_stage *stages, int count,
                               GLuint *program, gb_error *error);
/* A vertex + fragment program, each from one source. */
gb_result gb_gl_program(const char *name, const char *vertex, const char *fragment,
                        GLuint *program, gb_error *error);
/* A compute program from one source. */
gb_result gb_gl_compute_program(const char *name, const char *source, GLuint *program,
                                gb_error *error);

/* A storage buffer holding size bytes of data (GL_DYNAMIC_DRAW); an empty
 * array still gets a 16-byte buffer to bind, uninitialised, since data may
 * hold fewer than 16 bytes. */
GLuint gb_gl_buffer(const void *data, GLsizeiptr size);

/* A 2-D texture of internal format, one level, nearest filtering, clamped. */
GLuint gb_gl_texture_2d(GLenum internal_format, int width, int height);

/* A pass's own render target: a framebuffer with one colour texture and a
 * 32-bit float depth texture of its own, width x height. Zeroed: none yet.
 * The caller owns it, and releases it with gb_gl_target_release. */
typedef struct gb_gl_target {
    GLuint framebuffer, color, depth;
    int width, height;
    int drawn;                  /* gb_gl_target_stale: drawn from view, projection */
    float view[16], projection[16];
} gb_gl_target;

/* Makes target width x height with a colour texture of color_format,
 * unless it is that size already; returns 1 when it made it (its contents
 * are then undefined), 0 when it kept it. */
int gb_gl_target_resize(gb_gl_target *target, GLenum color_format, int width, int height);
void gb_gl_target_release(gb_gl_target *target);
/* For a target that shows the static scene from a view: makes it as
 * gb_gl_target_resize does, and returns 1 when it must be drawn (it was
 * just made, or it was last drawn from another view or projection, which it
 * then records as its own), 0 when what it holds is still right. */
int gb_gl_target_stale(gb_gl_target *target, GLenum color_format, int width, int height,
                       const float view[16], const float projection[16]);

/* Binds target for a pass that draws geometry into it: its depth cleared to
 * far (0: the runtime's depth is reversed), the viewport its size, blending
 * off, the depth test GL_GREATER and written. The caller clears the colour
 * and turns the depth test off after. */
void gb_gl_target_begin_geometry(const gb_gl_target *target);

/* The uniforms "view" and "projection" of program. */
void gb_gl_set_view_projection(GLuint program, const float view[16], const float projection[16]);

/* The state a pass changes when it draws somewhere else than its caller
 * (its own target, a texture) or otherwise than its caller set up, and puts
 * back before it returns: the draw and read framebuffers, the viewport, the
 * scissor test and box, blending and its functions, the depth test, its
 * function and mask, and face culling. */
typedef struct gb_gl_state {
    GLint draw_framebuffer, read_framebuffer;
    GLint viewport[4], scissor_box[4];
    GLboolean scissor_test, blend, depth_test, depth_mask, cull_face;
    GLint blend_functions[4];   /* source RGB, destination RGB, source and
                                   destination alpha */
    GLint depth_function;
} gb_gl_state;

void gb_gl_state_save(gb_gl_state *state);
void gb_gl_state_restore(const gb_gl_state *state);

/* The full-screen triangle (fullscreen.vert.glsl): a vertex shader that needs
 * no attribute; draw with gb_gl_draw_fullscreen and an empty vertex array. */
extern const char gb_gl_fullscreen_vertex_shader[];
void gb_gl_draw_fullscreen(GLuint empty_vertex_array);

#endif
