/* The window face: GLFW, OpenGL 4.5 core, libepoxy. */

#include <stdio.h>
#include <string.h>

#include <epoxy/gl.h>
#include <GLFW/glfw3.h>

#include "context.h"

/* GLFW reports errors through a process-wide callback: its last message is
 * kept here, in this file only, for the gb_error of the failing call. */
static char glfw_message[256];

static void keep_glfw_message(int code, const char *description)
{
    snprintf(glfw_message, sizeof glfw_message, "%s (0x%05x)", description, (unsigned)code);
}

static gb_result glfw_fail(gb_error *error, const char *what)
{
    return gb_fail(error, GB_ERROR_UNSUPPORTED, "GLFW: %s: %s", what,
                   glfw_message[0] ? glfw_message : "unknown error");
}

static void set_window_hints(void)
{
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
#ifndef NDEBUG
    glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, GLFW_TRUE);
#endif
}

gb_result gb_context_create_window(gb_context *context, const char *title, int width,
                                   int height, gb_error *error)
{
    memset(context, 0, sizeof *context);
    glfw_message[0] = '\0';
    glfwSetErrorCallback(keep_glfw_message);
    if (!glfwInit())
        return glfw_fail(error, "no display (set DISPLAY, or use --headless)");
    context->glfw_initialized = 1;
    set_window_hints();
    GLFWwindow *window = glfwCreateWindow(width, height, title, NULL, NULL);
    if (!window) {
        gb_result result = glfw_fail(error, "creating an OpenGL 4.5 core window");
        gb_context_destroy_window(context);
        return result;
    }
    context->window = window;
    glfwMakeContextCurrent(window);
    glfwSwapInterval(0);
    gb_result result = gb_gl_require_45(error);
    if (result != GB_OK) {
        gb_context_destroy_window(context);
        return result;
    }
    gb_gl_errors_install(&context->errors);
    return GB_OK;
}

void gb_context_destroy_window(gb_context *context)
{
    if (context->window)
        glfwDestroyWindow((GLFWwindow *)context->window);
    if (context->glfw_initialized)
        glfwTerminate();
    context->window = NULL;
    context->glfw_initialized = 0;
}
