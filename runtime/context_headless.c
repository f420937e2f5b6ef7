/* The headless face: EGL, Mesa surfaceless platform, OpenGL 4.5 core. */

#include <string.h>

#include <epoxy/egl.h>

#include "context.h"

static const char *egl_error_name(EGLint code)
{
    switch (code) {
    case EGL_NOT_INITIALIZED: return "EGL not initialized";
    case EGL_BAD_ACCESS: return "bad access";
    case EGL_BAD_ALLOC: return "bad alloc";
    case EGL_BAD_ATTRIBUTE: return "bad attribute";
    case EGL_BAD_CONFIG: return "bad config";
    case EGL_BAD_CONTEXT: return "bad context";
    case EGL_BAD_DISPLAY: return "bad display";
    case EGL_BAD_MATCH: return "bad match (is OpenGL 4.5 core available?)";
    case EGL_BAD_PARAMETER: return "bad parameter";
    default: return "error";
    }
}

static gb_result egl_fail(gb_error *error, const char *what)
{
    EGLint code = eglGetError();
    return gb_fail(error, GB_ERROR_UNSUPPORTED, "EGL: %s: %s (0x%04x)", what,
                   egl_error_name(code), (unsigned)code);
}

static int has_client_extension(const char *name)
{
    const char *list = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    size_t length = strlen(name);
    for (const char *p = list; p && (p = strstr(p, name)); p += length)
        if ((p == list || p[-1] == ' ') && (p[length] == ' ' || p[length] == '\0'))
            return 1;
    return 0;
}

/* The surfaceless platform through EGL_EXT_platform_base (libepoxy cannot
 * resolve the EGL 1.5 eglGetPlatformDisplay before a display exists), or
 * the default display when Mesa was built surfaceless by default. */
static EGLDisplay surfaceless_display(void)
{
    if (has_client_extension("EGL_MESA_platform_surfaceless") &&
        has_client_extension("EGL_EXT_platform_base"))
        return eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY,
                                        NULL);
    return eglGetDisplay(EGL_DEFAULT_DISPLAY);
}

static gb_result create_core_context(gb_context *context, gb_error *error)
{
    static const EGLint config_attributes[] = {
        EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE,
    };
    static const EGLint context_attributes[] = {
        EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
#ifndef NDEBUG
        EGL_CONTEXT_OPENGL_DEBUG, EGL_TRUE,
#endif
        EGL_NONE,
    };
    if (!eglBindAPI(EGL_OPENGL_API))
        return egl_fail(error, "no desktop OpenGL");
    EGLConfig config = NULL;
    EGLint config_count = 0;
    if (!eglChooseConfig(context->egl_display, config_attributes, &config, 1, &config_count))
        return egl_fail(error, "choosing a configuration");
    context->egl_context = eglCreateContext(context->egl_display,
                                            config_count ? config : EGL_NO_CONFIG_KHR,
                                            EGL_NO_CONTEXT, context_attributes);
    if (context->egl_context == EGL_NO_CONTEXT)
        return egl_fail(error, "creating an OpenGL 4.5 core context");
    if (!eglMakeCurrent(context->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE,
                        context->egl_context))
        return egl_fail(error, "making the context current (surfaceless)");
    return GB_OK;
}

gb_result gb_context_create_headless(gb_context *context, gb_error *error)
{
    memset(context, 0, sizeof *context);
    EGLDisplay display = surfaceless_display();
    if (display == EGL_NO_DISPLAY)
        return egl_fail(error, "no surfaceless display (is Mesa's libEGL installed?)");
    context->egl_display = display;
    EGLint major, minor;
    if (!eglInitialize(display, &major, &minor)) {
        context->egl_display = NULL;
        return egl_fail(error, "initializing the display");
    }
    gb_result result = create_core_context(context, error);
    if (result == GB_OK)
        result = gb_gl_require_45(error);
    if (result != GB_OK) {
        gb_context_destroy_headless(context);
        return result;
    }
    gb_gl_errors_install(&context->errors);
    return GB_OK;
}

/* The display is left initialized: an EGL display is one per process, the
 * next headless context reuses it, and eglTerminate would unload Mesa's
 * driver, whose few allocations it never frees then show up under
 * LeakSanitizer with stacks in an unloaded module, which no suppression can
 * match. */
void gb_context_destroy_headless(gb_context *context)
{
    if (!context->egl_display)
        return;
    eglMakeCurrent(context->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context->egl_context)
        eglDestroyContext(context->egl_display, context->egl_context);
    eglReleaseThread();
    context->egl_display = context->egl_context = NULL;
}

void gb_context_destroy(gb_context *context)
{
    gb_context_destroy_headless(context);
    gb_context_destroy_window(context);
}
