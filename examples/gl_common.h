/* gl_common.h - the OpenGL plumbing shared by the hairfur.h examples.
 *
 * One header, stb style: include it anywhere; in exactly one .c file
 *
 *     #define GLC_IMPLEMENTATION
 *     #include "gl_common.h"
 *
 * What it gives an example:
 *   - a GL 3.3 core context, either in a GLFW window (glc_open_window) or
 *     headless through EGL with no display at all (glc_open_headless:
 *     Mesa surfaceless platform, then an EGL device, then the default
 *     display; the context is made current with no surface).
 *   - in BOTH modes the example draws into an offscreen target of the
 *     requested size (RGBA8 + depth24/stencil8, 4x multisampled by default)
 *     so a render and its PNG are the same headless or in a window; in a
 *     window glc_swap() resolves it and blits it, letterboxed, to the screen.
 *   - shader compile/link with the info log printed on failure, readback to
 *     upright RGBA8, PNG writing (stb_image_write), a small column-major
 *     mat4 library, a frame loop (glc_should_close / glc_swap, with a frame
 *     limit and a deterministic clock headless), and glc_probe_headless()
 *     which says in words what is missing when headless GL 3.3 cannot work.
 *
 * Build (see the Makefile):
 *   glad --api gl:core=3.3 --reproducible --out-path build/glad c
 *   cc -Ibuild/glad/include -c build/glad/src/gl.c -o build/glad/gl.o
 *   cc -Ibuild/glad/include ex.c build/glad/gl.o -lglfw -lEGL -lm
 * Define GLC_NO_GLFW (before the implementation) to build without GLFW:
 * glc_open_window() then fails with a message and only -lEGL is needed.
 * Headless mode never calls into GLFW, so a GLFW-linked program runs
 * headless on a machine with no display.
 *
 * One context per process (the state is a single static struct): these
 * are example programs, not a library.
 *
 * Environment:
 *   GLC_EGL_PLATFORM=surfaceless|device|default  try only that EGL path
 *   (the default order is surfaceless, device, default).
 */
#ifndef GL_COMMON_H
#define GL_COMMON_H

#include <glad/gl.h> /* before anything that could pull in GL/gl.h */
#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* ---- context ---------------------------------------------------------- */

/* Open a GLFW window of w x h (screen units) with a GL 3.3 core context and
 * a w x h offscreen target with 4x MSAA. Returns 1 on success, 0 on failure
 * (the reason is in glc_error() and printed to stderr unless quiet). */
int glc_open_window(int w, int h, const char *title);

/* Headless GL 3.3 core context through EGL, no display and no surface,
 * drawing into a w x h target with 4x MSAA (clamped to GL_MAX_SAMPLES).
 * Returns 1 on success, 0 on failure (reason as above). */
int glc_open_headless(int w, int h);

/* Same with an explicit sample count: 0 or 1 = no multisampling. */
int glc_open_headless_ex(int w, int h, int samples);

/* Destroy the target, the context and the window/display. Safe to call
 * when nothing is open. */
void glc_close(void);

/* 1 when opened headless, 0 in a window (or when nothing is open). */
int glc_is_headless(void);

/* Size of the render target (the sizes given to glc_open_*). */
int glc_width(void);
int glc_height(void);
/* Samples of the target actually used (1 = not multisampled). */
int glc_samples(void);

/* The FBO the example draws into (the multisampled one if any). */
GLuint glc_target_fbo(void);

/* The GLFWwindow * of glc_open_window (for input callbacks), or NULL when
 * headless / built with GLC_NO_GLFW. void * so this header needs no GLFW. */
void *glc_window(void);

/* The last error message ("" if none). Owned by gl_common; valid until the
 * next gl_common call. */
const char *glc_error(void);

/* quiet != 0: do not print errors to stderr (they still go to
 * glc_error()). Shader info logs are printed unless quiet too. */
void glc_set_quiet(int quiet);

/* Check whether headless EGL + GL 3.3 core works here: opens a tiny
 * context, compiles a GLSL 330 program, draws and reads a pixel back, then
 * closes everything. Returns 1 if it works (info gets "RENDERER | VERSION"),
 * 0 if not (info gets the reason, e.g. "no EGL display: install
 * libegl-mesa0 libgl1-mesa-dri"). info may be NULL; it is always
 * NUL-terminated when info_size > 0. Must be called with nothing open. */
int glc_probe_headless(char *info, size_t info_size);

/* ---- frame loop ------------------------------------------------------- */

/* Bind the target FBO and set the viewport to it. Call at the start of
 * every frame (and after binding FBOs of your own). */
void glc_begin_frame(void);

/* Window: resolve, blit to the window, swap, poll events. Headless: no
 * drawing. Both count the frame. */
void glc_swap(void);

/* 1 when the loop should stop: the window was closed (or Escape pressed),
 * or the frame limit was reached. */
int glc_should_close(void);

/* Frames counted by glc_swap() stop the loop after `frames` frames;
 * 0 = no limit. Default: 1 headless, 0 in a window. */
void glc_set_frame_limit(long frames);

/* Frames swapped so far. */
long glc_frame_index(void);

/* Seconds: headless, frame_index / 60 (deterministic renders); in a
 * window, wall-clock time since the window opened. */
double glc_time(void);

/* ---- shaders ---------------------------------------------------------- */

/* Compile one shader stage. name labels error messages (may be NULL).
 * Returns the shader, or 0 after printing the info log. */
GLuint glc_compile_shader(GLenum type, const char *source, const char *name);

/* Compile and link a vertex + fragment program. Returns the program, or 0
 * after printing which stage failed and its info log. */
GLuint glc_program(const char *vs_source, const char *fs_source,
                   const char *name);

/* Read a whole text file into a malloc'd NUL-terminated string (caller
 * frees), or NULL with the reason in glc_error(). */
char *glc_read_text_file(const char *path);

/* Print any pending GL errors, naming `where`; returns 1 if there were
 * none, 0 otherwise. */
int glc_check_gl(const char *where);

/* ---- readback and PNG ------------------------------------------------- */

/* Read the target (resolving MSAA first) into dst, which holds
 * glc_width() * glc_height() * 4 bytes, top row first (upright for PNG).
 * Rebinds the target FBO afterwards. Returns 1, or 0 if nothing is open
 * or dst is NULL. */
int glc_read_rgba(unsigned char *dst);

/* Write w x h RGBA8 pixels (top row first) as a PNG. Returns 1 or 0 (the
 * reason printed). */
int glc_write_png(const char *path, const unsigned char *rgba, int w, int h);

/* glc_read_rgba + glc_write_png of the whole target. */
int glc_save_png(const char *path);

/* ---- mat4: column-major float[16], as glUniformMatrix4fv(..., GL_FALSE)
 * expects. m[col * 4 + row]. Outputs may alias inputs. ------------------ */

void glc_mat4_identity(float out[16]);
/* out = a * b (b applied first to a column vector). */
void glc_mat4_mul(float out[16], const float a[16], const float b[16]);
/* OpenGL-style perspective (clip z in [-w, w]); fovy in radians. */
void glc_mat4_perspective(float out[16], float fovy, float aspect,
                          float znear, float zfar);
void glc_mat4_ortho(float out[16], float left, float right, float bottom,
                    float top, float znear, float zfar);
/* Right-handed view matrix: the camera at eye looks at center. */
void glc_mat4_look_at(float out[16], const float eye[3],
                      const float center[3], const float up[3]);
/* out = m * (v, 1), the full 4-vector. */
void glc_mat4_transform(float out[4], const float m[16], const float v[3]);

#ifdef __cplusplus
}
#endif
#endif /* GL_COMMON_H */

/* ======================================================================= */
#ifdef GLC_IMPLEMENTATION
#ifndef GLC_IMPLEMENTATION_DONE
#define GLC_IMPLEMENTATION_DONE

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <EGL/egl.h>
#include <EGL/eglext.h>

#ifndef GLC_NO_GLFW
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#endif

/* stb_image_write as static functions, so an example can still have its
 * own copy; its unused functions and pedantic warnings are not ours. */
#ifndef GLC_NO_STB_IMPLEMENTATION
#if defined(__GNUC__) || defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#if defined(__GNUC__) || defined(__clang__)
#pragma GCC diagnostic pop
#endif
#else
#include <stb/stb_image_write.h>
#endif

/* Tokens that older eglext.h may lack. */
#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif
#ifndef EGL_PLATFORM_DEVICE_EXT
#define EGL_PLATFORM_DEVICE_EXT 0x313F
#endif
#ifndef EGL_CONTEXT_MAJOR_VERSION
#define EGL_CONTEXT_MAJOR_VERSION 0x3098
#endif
#ifndef EGL_CONTEXT_MINOR_VERSION
#define EGL_CONTEXT_MINOR_VERSION 0x30FB
#endif
#ifndef EGL_CONTEXT_OPENGL_PROFILE_MASK
#define EGL_CONTEXT_OPENGL_PROFILE_MASK 0x30FD
#endif
#ifndef EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT
#define EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT 0x00000001
#endif
#ifndef EGL_OPENGL_BIT
#define EGL_OPENGL_BIT 0x0008
#endif

typedef EGLDisplay (*glc__get_platform_display_fn)(EGLenum platform,
                                                   void *native,
                                                   const EGLint *attribs);
typedef EGLBoolean (*glc__query_devices_fn)(EGLint max, void **devices,
                                            EGLint *count);

static struct {
    int open, headless, quiet;
    int w, h, samples;
    GLuint fbo, color_rb, depth_rb;     /* draw target */
    GLuint resolve_fbo, resolve_rb;     /* when samples > 1 */
    long frame, frame_limit;
    EGLDisplay dpy;
    EGLContext ctx;
    EGLSurface pbuf;                    /* only if surfaceless failed */
    const char *egl_path;               /* which display path worked */
    int egl_inited_any;                 /* some display initialised */
#ifndef GLC_NO_GLFW
    GLFWwindow *win;
    int glfw_inited;
#endif
    char err[1024];
} glc__s;

static void glc__fail(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(glc__s.err, sizeof glc__s.err, fmt, ap);
    va_end(ap);
    if (!glc__s.quiet)
        fprintf(stderr, "gl_common: %s\n", glc__s.err);
}

const char *glc_error(void) { return glc__s.err; }
void glc_set_quiet(int quiet) { glc__s.quiet = quiet; }
int glc_is_headless(void) { return glc__s.open && glc__s.headless; }
int glc_width(void) { return glc__s.w; }
int glc_height(void) { return glc__s.h; }
int glc_samples(void) { return glc__s.samples; }
GLuint glc_target_fbo(void) { return glc__s.fbo; }
long glc_frame_index(void) { return glc__s.frame; }
#ifndef GLC_NO_GLFW
void *glc_window(void) { return (void *)glc__s.win; }
#else
void *glc_window(void) { return NULL; }
#endif
void glc_set_frame_limit(long frames) { glc__s.frame_limit = frames; }

static const char *glc__egl_error_name(EGLint e)
{
    switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    default: return "unknown EGL error";
    }
}

static const char *glc__gl_error_name(GLenum e)
{
    switch (e) {
    case GL_NO_ERROR: return "GL_NO_ERROR";
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
        return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    default: return "unknown GL error";
    }
}

static const char *glc__fbo_status_name(GLenum s)
{
    switch (s) {
    case GL_FRAMEBUFFER_COMPLETE: return "complete";
    case GL_FRAMEBUFFER_UNDEFINED: return "GL_FRAMEBUFFER_UNDEFINED";
    case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT:
        return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
    case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT:
        return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
    case GL_FRAMEBUFFER_UNSUPPORTED: return "GL_FRAMEBUFFER_UNSUPPORTED";
    case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE:
        return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
    default: return "unknown framebuffer status";
    }
}

int glc_check_gl(const char *where)
{
    int ok = 1, n = 0;
    GLenum e;
    /* bounded: a lost context can report errors forever */
    while ((e = glGetError()) != GL_NO_ERROR && n++ < 16) {
        glc__fail("GL error %s (0x%04x) at %s", glc__gl_error_name(e),
                  (unsigned)e, where ? where : "?");
        ok = 0;
    }
    return ok;
}

/* Whole-word search in a space-separated extension string. */
static int glc__has_ext(const char *list, const char *name)
{
    size_t n = strlen(name);
    const char *p = list;
    if (!list) return 0;
    while ((p = strstr(p, name)) != NULL) {
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0'))
            return 1;
        p += n;
    }
    return 0;
}

/* ---- render target ---------------------------------------------------- */

static void glc__destroy_target(void)
{
    if (glc__s.fbo) glDeleteFramebuffers(1, &glc__s.fbo);
    if (glc__s.resolve_fbo) glDeleteFramebuffers(1, &glc__s.resolve_fbo);
    if (glc__s.color_rb) glDeleteRenderbuffers(1, &glc__s.color_rb);
    if (glc__s.depth_rb) glDeleteRenderbuffers(1, &glc__s.depth_rb);
    if (glc__s.resolve_rb) glDeleteRenderbuffers(1, &glc__s.resolve_rb);
    glc__s.fbo = glc__s.resolve_fbo = 0;
    glc__s.color_rb = glc__s.depth_rb = glc__s.resolve_rb = 0;
}

static int glc__create_target(int w, int h, int samples)
{
    GLint max_samples = 0, max_rb = 0;
    GLenum st;
    glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_rb);
    if (w > max_rb || h > max_rb) {
        glc__fail("target %dx%d is larger than GL_MAX_RENDERBUFFER_SIZE %d",
                  w, h, (int)max_rb);
        return 0;
    }
    if (samples < 1) samples = 1;
    if (samples > max_samples) samples = max_samples > 1 ? max_samples : 1;
    glc__s.samples = samples;

    glGenFramebuffers(1, &glc__s.fbo);
    glGenRenderbuffers(1, &glc__s.color_rb);
    glGenRenderbuffers(1, &glc__s.depth_rb);
    glBindFramebuffer(GL_FRAMEBUFFER, glc__s.fbo);
    glBindRenderbuffer(GL_RENDERBUFFER, glc__s.color_rb);
    if (samples > 1)
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8,
                                         w, h);
    else
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                              GL_RENDERBUFFER, glc__s.color_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, glc__s.depth_rb);
    if (samples > 1)
        glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples,
                                         GL_DEPTH24_STENCIL8, w, h);
    else
        glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT,
                              GL_RENDERBUFFER, glc__s.depth_rb);
    st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        glc__fail("render target %dx%d, %d samples: framebuffer incomplete "
                  "(%s)", w, h, samples, glc__fbo_status_name(st));
        glc__destroy_target();
        return 0;
    }
    if (samples > 1) {
        glGenFramebuffers(1, &glc__s.resolve_fbo);
        glGenRenderbuffers(1, &glc__s.resolve_rb);
        glBindFramebuffer(GL_FRAMEBUFFER, glc__s.resolve_fbo);
        glBindRenderbuffer(GL_RENDERBUFFER, glc__s.resolve_rb);
        glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
        glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0,
                                  GL_RENDERBUFFER, glc__s.resolve_rb);
        st = glCheckFramebufferStatus(GL_FRAMEBUFFER);
        if (st != GL_FRAMEBUFFER_COMPLETE) {
            glc__fail("resolve target %dx%d: framebuffer incomplete (%s)",
                      w, h, glc__fbo_status_name(st));
            glc__destroy_target();
            return 0;
        }
    }
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, glc__s.fbo);
    glViewport(0, 0, w, h);
    if (!glc_check_gl("creating the render target")) {
        glc__destroy_target();
        return 0;
    }
    return 1;
}

/* After gladLoadGL: the version really is 3.3+ core, then the target. */
static int glc__after_load(int glad_version, int w, int h, int samples)
{
    GLint mask = 0;
    if (!glad_version) {
        glc__fail("gladLoadGL failed: the GL loader returned no functions "
                  "(is the context current?)");
        return 0;
    }
    if (GLAD_VERSION_MAJOR(glad_version) * 10 +
        GLAD_VERSION_MINOR(glad_version) < 33) {
        glc__fail("got OpenGL %d.%d (%s), need 3.3 core",
                  GLAD_VERSION_MAJOR(glad_version),
                  GLAD_VERSION_MINOR(glad_version),
                  (const char *)glGetString(GL_RENDERER));
        return 0;
    }
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &mask);
    if (!(mask & GL_CONTEXT_CORE_PROFILE_BIT)) {
        glc__fail("the context is not a core profile (mask 0x%x)",
                  (unsigned)mask);
        return 0;
    }
    while (glGetError() != GL_NO_ERROR) {}
    return glc__create_target(w, h, samples);
}

static int glc__check_size(int w, int h)
{
    if (glc__s.open) {
        glc__fail("a context is already open (call glc_close first)");
        return 0;
    }
    if (w <= 0 || h <= 0 || w > 16384 || h > 16384) {
        glc__fail("bad size %dx%d (1..16384)", w, h);
        return 0;
    }
    return 1;
}

/* ---- headless: EGL ---------------------------------------------------- */

static void glc__egl_teardown(void)
{
    if (glc__s.dpy != EGL_NO_DISPLAY) {
        eglMakeCurrent(glc__s.dpy, EGL_NO_SURFACE, EGL_NO_SURFACE,
                       EGL_NO_CONTEXT);
        if (glc__s.pbuf != EGL_NO_SURFACE)
            eglDestroySurface(glc__s.dpy, glc__s.pbuf);
        if (glc__s.ctx != EGL_NO_CONTEXT)
            eglDestroyContext(glc__s.dpy, glc__s.ctx);
        eglTerminate(glc__s.dpy);
        eglReleaseThread();
    }
    glc__s.dpy = EGL_NO_DISPLAY;
    glc__s.ctx = EGL_NO_CONTEXT;
    glc__s.pbuf = EGL_NO_SURFACE;
}

/* Initialise dpy and make a 3.3 core context current on it. On failure
 * writes the reason to why and leaves dpy terminated. */
static int glc__egl_try(EGLDisplay dpy, const char *path, char *why,
                        size_t why_size)
{
    EGLint major = 0, minor = 0, nconf = 0;
    EGLConfig conf = (EGLConfig)0;
    const char *exts, *apis;
    int have_create_ctx, surfaceless;
    static const EGLint conf_attrs[] = {
        EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
        EGL_SURFACE_TYPE, 0,  /* any: we draw into an FBO */
        EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8,
        EGL_NONE
    };
    static const EGLint ctx_attrs[] = {
        EGL_CONTEXT_MAJOR_VERSION, 3,
        EGL_CONTEXT_MINOR_VERSION, 3,
        EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
        EGL_NONE
    };

    if (dpy == EGL_NO_DISPLAY) {
        snprintf(why, why_size, "%s: no EGL display", path);
        return 0;
    }
    if (!eglInitialize(dpy, &major, &minor)) {
        snprintf(why, why_size, "%s: eglInitialize failed (%s)", path,
                 glc__egl_error_name(eglGetError()));
        return 0;
    }
    glc__s.dpy = dpy;
    glc__s.egl_inited_any = 1;
    exts = eglQueryString(dpy, EGL_EXTENSIONS);
    apis = eglQueryString(dpy, EGL_CLIENT_APIS);
    if (!glc__has_ext(apis, "OpenGL")) {
        snprintf(why, why_size, "%s: EGL %d.%d offers no desktop OpenGL "
                 "(client APIs: %s)", path, (int)major, (int)minor,
                 apis ? apis : "?");
        goto fail;
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
        snprintf(why, why_size, "%s: eglBindAPI(EGL_OPENGL_API) failed (%s)",
                 path, glc__egl_error_name(eglGetError()));
        goto fail;
    }
    have_create_ctx = (major > 1 || minor >= 5) ||
                      glc__has_ext(exts, "EGL_KHR_create_context");
    if (!have_create_ctx) {
        snprintf(why, why_size, "%s: EGL %d.%d has neither EGL 1.5 nor "
                 "EGL_KHR_create_context: cannot ask for GL 3.3 core", path,
                 (int)major, (int)minor);
        goto fail;
    }
    surfaceless = glc__has_ext(exts, "EGL_KHR_surfaceless_context");
    if (!eglChooseConfig(dpy, conf_attrs, &conf, 1, &nconf) || nconf < 1) {
        if (surfaceless && glc__has_ext(exts, "EGL_KHR_no_config_context")) {
            conf = (EGLConfig)0; /* EGL_NO_CONFIG_KHR */
        } else {
            snprintf(why, why_size, "%s: no EGL config with OpenGL and "
                     "RGB8 (%s)", path, glc__egl_error_name(eglGetError()));
            goto fail;
        }
    }
    glc__s.ctx = eglCreateContext(dpy, conf, EGL_NO_CONTEXT, ctx_attrs);
    if (glc__s.ctx == EGL_NO_CONTEXT) {
        snprintf(why, why_size, "%s: eglCreateContext for OpenGL 3.3 core "
                 "failed (%s)", path,
                 glc__egl_error_name(eglGetError()));
        goto fail;
    }
    if (surfaceless && eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE,
                                      glc__s.ctx)) {
        return 1;
    }
    /* No surfaceless contexts: a 1x1 pbuffer only to be current; all
     * drawing still goes to the FBO. */
    if (conf != (EGLConfig)0) {
        static const EGLint pb_attrs[] = { EGL_WIDTH, 1, EGL_HEIGHT, 1,
                                           EGL_NONE };
        glc__s.pbuf = eglCreatePbufferSurface(dpy, conf, pb_attrs);
        if (glc__s.pbuf != EGL_NO_SURFACE &&
            eglMakeCurrent(dpy, glc__s.pbuf, glc__s.pbuf, glc__s.ctx))
            return 1;
    }
    snprintf(why, why_size, "%s: eglMakeCurrent failed (%s)%s", path,
             glc__egl_error_name(eglGetError()),
             surfaceless ? "" : "; no EGL_KHR_surfaceless_context and no "
                                "pbuffer fallback");
fail:
    glc__egl_teardown();
    return 0;
}

static int glc__egl_open(char *why, size_t why_size)
{
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    const char *only = getenv("GLC_EGL_PLATFORM");
    glc__get_platform_display_fn get_pd = NULL;
    char tried[768]; /* < why: room for the sentence around it */
    size_t used = 0;
    int n;

    tried[0] = '\0';
    glc__s.egl_inited_any = 0;
#define GLC__NOTE(msg) do { \
        n = snprintf(tried + used, sizeof tried - used, "%s%s", \
                     used ? "; " : "", (msg)); \
        if (n > 0) used += (size_t)n < sizeof tried - used \
                          ? (size_t)n : sizeof tried - used - 1; \
    } while (0)

    if (only && !*only) only = NULL;
    if (only && strcmp(only, "surfaceless") && strcmp(only, "device") &&
        strcmp(only, "default")) {
        snprintf(why, why_size, "GLC_EGL_PLATFORM=%s: expected surfaceless, "
                 "device or default", only);
        return 0;
    }
    if (glc__has_ext(client, "EGL_EXT_platform_base")) {
        /* a void* to function pointer conversion is not ISO C, so copy the
         * bits (eglGetProcAddress already returns a function pointer) */
        __eglMustCastToProperFunctionPointerType f =
            eglGetProcAddress("eglGetPlatformDisplayEXT");
        get_pd = (glc__get_platform_display_fn)f;
    }

    if (!only || !strcmp(only, "surfaceless")) {
        if (get_pd && glc__has_ext(client, "EGL_MESA_platform_surfaceless")) {
            EGLDisplay d = get_pd(EGL_PLATFORM_SURFACELESS_MESA,
                                  (void *)EGL_DEFAULT_DISPLAY, NULL);
            if (glc__egl_try(d, "surfaceless", why, why_size)) {
                glc__s.egl_path = "EGL_MESA_platform_surfaceless";
                return 1;
            }
            GLC__NOTE(why);
        } else {
            GLC__NOTE("surfaceless: no EGL_MESA_platform_surfaceless");
        }
    }
    if (!only || !strcmp(only, "device")) {
        if (get_pd && glc__has_ext(client, "EGL_EXT_platform_device") &&
            (glc__has_ext(client, "EGL_EXT_device_enumeration") ||
             glc__has_ext(client, "EGL_EXT_device_base"))) {
            void *devs[16];
            EGLint count = 0, i;
            __eglMustCastToProperFunctionPointerType f =
                eglGetProcAddress("eglQueryDevicesEXT");
            glc__query_devices_fn query = (glc__query_devices_fn)f;
            if (query && query(16, devs, &count) && count > 0) {
                for (i = 0; i < count; i++) {
                    EGLDisplay d = get_pd(EGL_PLATFORM_DEVICE_EXT, devs[i],
                                          NULL);
                    char path[32];
                    snprintf(path, sizeof path, "device %d", (int)i);
                    if (glc__egl_try(d, path, why, why_size)) {
                        glc__s.egl_path = "EGL_EXT_platform_device";
                        return 1;
                    }
                    GLC__NOTE(why);
                }
            } else {
                GLC__NOTE("device: eglQueryDevicesEXT found no device");
            }
        } else {
            GLC__NOTE("device: no EGL_EXT_platform_device");
        }
    }
    if (!only || !strcmp(only, "default")) {
        EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
        if (glc__egl_try(d, "default display", why, why_size)) {
            glc__s.egl_path = "eglGetDisplay(EGL_DEFAULT_DISPLAY)";
            return 1;
        }
        GLC__NOTE(why);
    }
#undef GLC__NOTE
    if (!client) {
        /* no client extensions at all: no vendor library (or pre-1.5 EGL) */
        snprintf(why, why_size, "no EGL display: install libegl-mesa0 "
                 "libgl1-mesa-dri (libEGL found no vendor; tried: %s)",
                 tried);
    } else if (glc__s.egl_inited_any) {
        snprintf(why, why_size, "EGL works but gives no OpenGL 3.3 core "
                 "context (Mesa's llvmpipe, libgl1-mesa-dri, does) (tried: "
                 "%s)", tried);
    } else {
        snprintf(why, why_size, "no EGL display: install libegl-mesa0 "
                 "libgl1-mesa-dri (tried: %s)", tried);
    }
    return 0;
}

int glc_open_headless_ex(int w, int h, int samples)
{
    char why[1024];
    int version;
    if (!glc__check_size(w, h)) return 0;
    glc__s.err[0] = '\0';
    glc__s.dpy = EGL_NO_DISPLAY;
    glc__s.ctx = EGL_NO_CONTEXT;
    glc__s.pbuf = EGL_NO_SURFACE;
    if (!glc__egl_open(why, sizeof why)) {
        glc__fail("%s", why);
        return 0;
    }
    version = gladLoadGL((GLADloadfunc)eglGetProcAddress);
    if (!glc__after_load(version, w, h, samples)) {
        glc__egl_teardown();
        return 0;
    }
    glc__s.open = 1;
    glc__s.headless = 1;
    glc__s.w = w;
    glc__s.h = h;
    glc__s.frame = 0;
    glc__s.frame_limit = 1;
    return 1;
}

int glc_open_headless(int w, int h) { return glc_open_headless_ex(w, h, 4); }

/* ---- window: GLFW ----------------------------------------------------- */

#ifndef GLC_NO_GLFW
/* Kept (not printed): glc_open_window folds it into its own message. */
static void glc__glfw_error(int code, const char *desc)
{
    snprintf(glc__s.err, sizeof glc__s.err, "GLFW error 0x%x: %s",
             (unsigned)code, desc ? desc : "?");
}

static void glc__glfw_key(GLFWwindow *w, int key, int scancode, int action,
                          int mods)
{
    (void)scancode;
    (void)mods;
    if (key == GLFW_KEY_ESCAPE && action == GLFW_PRESS)
        glfwSetWindowShouldClose(w, GLFW_TRUE);
}
#endif

int glc_open_window(int w, int h, const char *title)
{
#ifdef GLC_NO_GLFW
    (void)title;
    if (!glc__check_size(w, h)) return 0;
    glc__fail("glc_open_window: built with GLC_NO_GLFW; use "
              "glc_open_headless, or rebuild with GLFW (libglfw3-dev)");
    return 0;
#else
    int version;
    if (!glc__check_size(w, h)) return 0;
    glc__s.err[0] = '\0';
    glfwSetErrorCallback(glc__glfw_error);
    if (!glfwInit()) {
        const char *d = getenv("DISPLAY"), *wl = getenv("WAYLAND_DISPLAY");
        char prev[sizeof glc__s.err];
        memcpy(prev, glc__s.err, sizeof prev);
        glc__fail("glfwInit failed: cannot open a window%s (%s); run "
                  "headless instead", (!d || !*d) && (!wl || !*wl)
                  ? " because DISPLAY is not set" : "", prev[0] ? prev : "?");
        return 0;
    }
    glc__s.glfw_inited = 1;
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE); /* macOS */
    glfwWindowHint(GLFW_SAMPLES, 0); /* the FBO is multisampled instead */
    glfwWindowHint(GLFW_DEPTH_BITS, 0);
    glc__s.win = glfwCreateWindow(w, h, title ? title : "hairfur", NULL,
                                  NULL);
    if (!glc__s.win) {
        char prev[sizeof glc__s.err];
        memcpy(prev, glc__s.err, sizeof prev);
        glc__fail("glfwCreateWindow with OpenGL 3.3 core failed (%s)",
                  prev[0] ? prev : "?");
        glfwTerminate();
        glc__s.glfw_inited = 0;
        return 0;
    }
    glfwMakeContextCurrent(glc__s.win);
    glfwSwapInterval(1);
    glfwSetKeyCallback(glc__s.win, glc__glfw_key);
    version = gladLoadGL((GLADloadfunc)glfwGetProcAddress);
    if (!glc__after_load(version, w, h, 4)) {
        glfwDestroyWindow(glc__s.win);
        glc__s.win = NULL;
        glfwTerminate();
        glc__s.glfw_inited = 0;
        return 0;
    }
    glc__s.open = 1;
    glc__s.headless = 0;
    glc__s.w = w;
    glc__s.h = h;
    glc__s.frame = 0;
    glc__s.frame_limit = 0;
    glfwSetTime(0.0);
    return 1;
#endif
}

void glc_close(void)
{
    if (glc__s.open) glc__destroy_target();
    glc__egl_teardown(); /* no-op unless an EGL display is held */
#ifndef GLC_NO_GLFW
    if (glc__s.win) glfwDestroyWindow(glc__s.win);
    glc__s.win = NULL;
    if (glc__s.glfw_inited) glfwTerminate();
    glc__s.glfw_inited = 0;
#endif
    glc__s.open = 0;
    glc__s.headless = 0;
    glc__s.w = glc__s.h = glc__s.samples = 0;
    glc__s.egl_path = NULL;
}

/* ---- frame loop ------------------------------------------------------- */

void glc_begin_frame(void)
{
    if (!glc__s.open) return;
    glBindFramebuffer(GL_FRAMEBUFFER, glc__s.fbo);
    glViewport(0, 0, glc__s.w, glc__s.h);
}

/* Resolve the multisampled target into the single-sampled one (if any);
 * returns the FBO holding the final pixels. */
static GLuint glc__resolve(void)
{
    if (glc__s.samples <= 1) return glc__s.fbo;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, glc__s.fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, glc__s.resolve_fbo);
    glBlitFramebuffer(0, 0, glc__s.w, glc__s.h, 0, 0, glc__s.w, glc__s.h,
                      GL_COLOR_BUFFER_BIT, GL_NEAREST);
    return glc__s.resolve_fbo;
}

void glc_swap(void)
{
    if (!glc__s.open) return;
    glc__s.frame++;
#ifndef GLC_NO_GLFW
    if (!glc__s.headless && glc__s.win) {
        int fw = 0, fh = 0, x0, y0, dw, dh;
        GLuint src = glc__resolve();
        glfwGetFramebufferSize(glc__s.win, &fw, &fh);
        /* letterbox: keep the target's aspect ratio */
        if ((long)fw * glc__s.h <= (long)fh * glc__s.w) {
            dw = fw;
            dh = (int)((long)fw * glc__s.h / glc__s.w);
        } else {
            dh = fh;
            dw = (int)((long)fh * glc__s.w / glc__s.h);
        }
        x0 = (fw - dw) / 2;
        y0 = (fh - dh) / 2;
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
        glViewport(0, 0, fw, fh);
        glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, src);
        glBlitFramebuffer(0, 0, glc__s.w, glc__s.h, x0, y0, x0 + dw, y0 + dh,
                          GL_COLOR_BUFFER_BIT, GL_LINEAR);
        glfwSwapBuffers(glc__s.win);
        glfwPollEvents();
        glc_begin_frame();
    }
#endif
}

int glc_should_close(void)
{
    if (!glc__s.open) return 1;
    if (glc__s.frame_limit > 0 && glc__s.frame >= glc__s.frame_limit)
        return 1;
#ifndef GLC_NO_GLFW
    if (!glc__s.headless && glc__s.win)
        return glfwWindowShouldClose(glc__s.win) ? 1 : 0;
#endif
    return 0;
}

double glc_time(void)
{
#ifndef GLC_NO_GLFW
    if (glc__s.open && !glc__s.headless) return glfwGetTime();
#endif
    return (double)glc__s.frame / 60.0;
}

/* ---- shaders ---------------------------------------------------------- */

static const char *glc__stage_name(GLenum type)
{
    switch (type) {
    case GL_VERTEX_SHADER: return "vertex";
    case GL_FRAGMENT_SHADER: return "fragment";
    case GL_GEOMETRY_SHADER: return "geometry";
    default: return "unknown-stage";
    }
}

GLuint glc_compile_shader(GLenum type, const char *source, const char *name)
{
    GLuint sh;
    GLint ok = 0, len = 0;
    if (!source) {
        glc__fail("%s shader '%s': source is NULL", glc__stage_name(type),
                  name ? name : "");
        return 0;
    }
    sh = glCreateShader(type);
    if (!sh) {
        glc__fail("glCreateShader(%s) failed (no current context?)",
                  glc__stage_name(type));
        return 0;
    }
    glShaderSource(sh, 1, &source, NULL);
    glCompileShader(sh);
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char *log;
        glGetShaderiv(sh, GL_INFO_LOG_LENGTH, &len);
        log = (char *)malloc(len > 1 ? (size_t)len : 1);
        if (log) {
            log[0] = '\0';
            if (len > 1) glGetShaderInfoLog(sh, len, NULL, log);
        }
        glc__fail("%s shader '%s' failed to compile:\n%s",
                  glc__stage_name(type), name ? name : "",
                  log && log[0] ? log : "(empty info log)");
        free(log);
        glDeleteShader(sh);
        return 0;
    }
    return sh;
}

GLuint glc_program(const char *vs_source, const char *fs_source,
                   const char *name)
{
    GLuint vs, fs, prog;
    GLint ok = 0, len = 0;
    vs = glc_compile_shader(GL_VERTEX_SHADER, vs_source, name);
    if (!vs) return 0;
    fs = glc_compile_shader(GL_FRAGMENT_SHADER, fs_source, name);
    if (!fs) {
        glDeleteShader(vs);
        return 0;
    }
    prog = glCreateProgram();
    glAttachShader(prog, vs);
    glAttachShader(prog, fs);
    glLinkProgram(prog);
    glDeleteShader(vs); /* flagged; freed with the program */
    glDeleteShader(fs);
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char *log;
        glGetProgramiv(prog, GL_INFO_LOG_LENGTH, &len);
        log = (char *)malloc(len > 1 ? (size_t)len : 1);
        if (log) {
            log[0] = '\0';
            if (len > 1) glGetProgramInfoLog(prog, len, NULL, log);
        }
        glc__fail("program '%s' failed to link:\n%s", name ? name : "",
                  log && log[0] ? log : "(empty info log)");
        free(log);
        glDeleteProgram(prog);
        return 0;
    }
    return prog;
}

char *glc_read_text_file(const char *path)
{
    FILE *f;
    char *buf;
    long size;
    size_t got;
    if (!path) {
        glc__fail("glc_read_text_file: path is NULL");
        return NULL;
    }
    f = fopen(path, "rb");
    if (!f) {
        glc__fail("cannot open %s: %s", path, strerror(errno));
        return NULL;
    }
    if (fseek(f, 0, SEEK_END) != 0 || (size = ftell(f)) < 0 ||
        fseek(f, 0, SEEK_SET) != 0) {
        glc__fail("cannot size %s: %s", path, strerror(errno));
        fclose(f);
        return NULL;
    }
    buf = (char *)malloc((size_t)size + 1);
    if (!buf) {
        glc__fail("out of memory reading %s (%ld bytes)", path, size);
        fclose(f);
        return NULL;
    }
    got = fread(buf, 1, (size_t)size, f);
    fclose(f);
    if (got != (size_t)size) {
        glc__fail("short read on %s", path);
        free(buf);
        return NULL;
    }
    buf[size] = '\0';
    return buf;
}

/* ---- readback and PNG ------------------------------------------------- */

int glc_read_rgba(unsigned char *dst)
{
    GLuint src;
    int w = glc__s.w, h = glc__s.h, y;
    size_t row = (size_t)w * 4;
    unsigned char *tmp;
    if (!glc__s.open || !dst) {
        glc__fail("glc_read_rgba: %s", dst ? "nothing is open" : "dst is NULL");
        return 0;
    }
    src = glc__resolve();
    glBindFramebuffer(GL_READ_FRAMEBUFFER, src);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, dst);
    glBindFramebuffer(GL_FRAMEBUFFER, glc__s.fbo);
    /* GL's row 0 is the bottom; PNG's is the top */
    tmp = (unsigned char *)malloc(row);
    if (tmp) {
        for (y = 0; y < h / 2; y++) {
            unsigned char *a = dst + (size_t)y * row;
            unsigned char *b = dst + (size_t)(h - 1 - y) * row;
            memcpy(tmp, a, row);
            memcpy(a, b, row);
            memcpy(b, tmp, row);
        }
        free(tmp);
    } else {
        for (y = 0; y < h / 2; y++) {
            unsigned char *a = dst + (size_t)y * row;
            unsigned char *b = dst + (size_t)(h - 1 - y) * row;
            size_t i;
            for (i = 0; i < row; i++) {
                unsigned char t = a[i];
                a[i] = b[i];
                b[i] = t;
            }
        }
    }
    return glc_check_gl("glc_read_rgba");
}

int glc_write_png(const char *path, const unsigned char *rgba, int w, int h)
{
    if (!path || !rgba || w <= 0 || h <= 0) {
        glc__fail("glc_write_png: bad arguments");
        return 0;
    }
    errno = 0;
    if (!stbi_write_png(path, w, h, 4, rgba, w * 4)) {
        glc__fail("cannot write PNG %s: %s", path,
                  errno ? strerror(errno) : "stbi_write_png failed");
        return 0;
    }
    return 1;
}

int glc_save_png(const char *path)
{
    unsigned char *px;
    int ok;
    if (!glc__s.open) {
        glc__fail("glc_save_png: nothing is open");
        return 0;
    }
    px = (unsigned char *)malloc((size_t)glc__s.w * (size_t)glc__s.h * 4);
    if (!px) {
        glc__fail("glc_save_png: out of memory");
        return 0;
    }
    ok = glc_read_rgba(px) && glc_write_png(path, px, glc__s.w, glc__s.h);
    free(px);
    return ok;
}

/* ---- probe ------------------------------------------------------------ */

int glc_probe_headless(char *info, size_t info_size)
{
    static const char *vs =
        "#version 330 core\n"
        "void main() {\n"
        "    vec2 p = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1));\n"
        "    gl_Position = vec4(p * 4.0 - 1.0, 0.0, 1.0);\n"
        "}\n";
    static const char *fs =
        "#version 330 core\n"
        "out vec4 o;\n"
        "void main() { o = vec4(1.0, 0.5, 0.0, 1.0); }\n";
    int quiet = glc__s.quiet, ok = 0;
    GLuint prog = 0, vao = 0;
    unsigned char px[4 * 4 * 4];
    if (info && info_size) info[0] = '\0';
    if (glc__s.open) {
        if (info && info_size)
            snprintf(info, info_size, "glc_probe_headless: a context is "
                     "already open");
        return 0;
    }
    glc__s.quiet = 1;
    if (!glc_open_headless_ex(4, 4, 1)) goto done;
    prog = glc_program(vs, fs, "probe");
    if (!prog) goto done;
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glc_begin_frame();
    glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glUseProgram(prog);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    if (!glc_read_rgba(px)) goto done;
    if (px[0] != 255 || px[1] < 126 || px[1] > 129 || px[2] != 0) {
        glc__fail("headless GL draws wrong pixels: got %u,%u,%u expected "
                  "255,128,0", px[0], px[1], px[2]);
        goto done;
    }
    ok = 1;
done:
    if (info && info_size) {
        if (ok)
            snprintf(info, info_size, "%s | %s | %s",
                     (const char *)glGetString(GL_RENDERER),
                     (const char *)glGetString(GL_VERSION),
                     glc__s.egl_path ? glc__s.egl_path : "?");
        else
            snprintf(info, info_size, "%s", glc__s.err);
    }
    if (glc__s.open) {
        if (vao) glDeleteVertexArrays(1, &vao);
        if (prog) glDeleteProgram(prog);
    }
    glc_close();
    glc__s.quiet = quiet;
    return ok;
}

/* ---- mat4 ------------------------------------------------------------- */

void glc_mat4_identity(float out[16])
{
    int i;
    for (i = 0; i < 16; i++) out[i] = (i % 5 == 0) ? 1.0f : 0.0f;
}

void glc_mat4_mul(float out[16], const float a[16], const float b[16])
{
    float r[16];
    int c, row, k;
    for (c = 0; c < 4; c++)
        for (row = 0; row < 4; row++) {
            float s = 0.0f;
            for (k = 0; k < 4; k++) s += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = s;
        }
    memcpy(out, r, sizeof r);
}

void glc_mat4_perspective(float out[16], float fovy, float aspect,
                          float znear, float zfar)
{
    float f = 1.0f / (float)tan(0.5 * (double)fovy);
    int i;
    for (i = 0; i < 16; i++) out[i] = 0.0f;
    out[0] = f / aspect;
    out[5] = f;
    out[10] = (zfar + znear) / (znear - zfar);
    out[11] = -1.0f;
    out[14] = 2.0f * zfar * znear / (znear - zfar);
}

void glc_mat4_ortho(float out[16], float left, float right, float bottom,
                    float top, float znear, float zfar)
{
    int i;
    for (i = 0; i < 16; i++) out[i] = 0.0f;
    out[0] = 2.0f / (right - left);
    out[5] = 2.0f / (top - bottom);
    out[10] = -2.0f / (zfar - znear);
    out[12] = -(right + left) / (right - left);
    out[13] = -(top + bottom) / (top - bottom);
    out[14] = -(zfar + znear) / (zfar - znear);
    out[15] = 1.0f;
}

static void glc__normalize3(float v[3])
{
    float l = (float)sqrt((double)(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    if (l > 0.0f) {
        v[0] /= l;
        v[1] /= l;
        v[2] /= l;
    }
}

void glc_mat4_look_at(float out[16], const float eye[3],
                      const float center[3], const float up[3])
{
    float f[3], s[3], u[3];
    f[0] = center[0] - eye[0];
    f[1] = center[1] - eye[1];
    f[2] = center[2] - eye[2];
    glc__normalize3(f);
    s[0] = f[1] * up[2] - f[2] * up[1];
    s[1] = f[2] * up[0] - f[0] * up[2];
    s[2] = f[0] * up[1] - f[1] * up[0];
    glc__normalize3(s);
    u[0] = s[1] * f[2] - s[2] * f[1];
    u[1] = s[2] * f[0] - s[0] * f[2];
    u[2] = s[0] * f[1] - s[1] * f[0];
    out[0] = s[0]; out[4] = s[1]; out[8] = s[2];
    out[1] = u[0]; out[5] = u[1]; out[9] = u[2];
    out[2] = -f[0]; out[6] = -f[1]; out[10] = -f[2];
    out[3] = 0.0f; out[7] = 0.0f; out[11] = 0.0f;
    out[12] = -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]);
    out[13] = -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]);
    out[14] = f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2];
    out[15] = 1.0f;
}

void glc_mat4_transform(float out[4], const float m[16], const float v[3])
{
    float r[4];
    int row;
    for (row = 0; row < 4; row++)
        r[row] = m[row] * v[0] + m[4 + row] * v[1] + m[8 + row] * v[2] +
                 m[12 + row];
    memcpy(out, r, sizeof r);
}

#endif /* GLC_IMPLEMENTATION_DONE */
#endif /* GLC_IMPLEMENTATION */
