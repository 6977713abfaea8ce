/* Headless OpenGL 4.5 core context from EGL's device platform (EGL_EXT_platform_device), or the
 * caller's current context adopted as it is (ob_context_desc.use_current).
 *
 * No X server and no window: we enumerate EGL devices, pick a hardware one (NVIDIA through
 * EGL_NV_device_cuda, or a DRM render node) or Mesa's software device (EGL_MESA_device_software,
 * llvmpipe), and make a surfaceless context current. All rendering goes into FBOs/images. */
#include <dlfcn.h>
#include <epoxy/egl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "gpu/gpu.h"

#define MAX_DEVICES 16

static bool has_ext(const char *list, const char *ext)
{
    if (!list) return false;
    size_t n = strlen(ext);
    for (const char *p = list; (p = strstr(p, ext)) != NULL; p += n) {
        bool start = (p == list) || p[-1] == ' ';
        bool end = p[n] == '\0' || p[n] == ' ';
        if (start && end) return true;
    }
    return false;
}

static bool device_is_software(EGLDeviceEXT dev)
{
    const char *ext = eglQueryDeviceStringEXT(dev, EGL_EXTENSIONS);
    return has_ext(ext, "EGL_MESA_device_software");
}

static void describe_device(EGLDeviceEXT dev, int index, char *out, size_t len)
{
    const char *ext = eglQueryDeviceStringEXT(dev, EGL_EXTENSIONS);
    const char *drm = NULL;
    if (has_ext(ext, "EGL_EXT_device_drm")) drm = eglQueryDeviceStringEXT(dev, EGL_DRM_DEVICE_FILE_EXT);
    if (has_ext(ext, "EGL_MESA_device_software")) {
        snprintf(out, len, "device %d (software)", index);
    } else if (has_ext(ext, "EGL_NV_device_cuda")) {
        snprintf(out, len, "device %d (NVIDIA%s%s)", index, drm ? " " : "", drm ? drm : "");
    } else {
        snprintf(out, len, "device %d (%s)", index, drm ? drm : "hardware");
    }
}

/* Try one device; on failure append what went wrong to `tried`. */
static bool try_device(ob_context *ctx, EGLDeviceEXT dev, const char *label, char *tried, size_t tlen)
{
    char why[160] = "";
    EGLDisplay dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, dev, NULL);
    EGLint major = 0, minor = 0;
    if (dpy == EGL_NO_DISPLAY) {
        snprintf(why, sizeof why, "no display");
    } else if (!eglInitialize(dpy, &major, &minor)) {
        snprintf(why, sizeof why, "eglInitialize failed (0x%x)", (unsigned)eglGetError());
        dpy = EGL_NO_DISPLAY;
    } else if (!eglBindAPI(EGL_OPENGL_API)) {
        snprintf(why, sizeof why, "no desktop OpenGL API");
    } else {
        const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                         EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig config = NULL;
        EGLint n = 0;
        /* A surfaceless context needs no config; take one when offered for older drivers. */
        if (!eglChooseConfig(dpy, config_attribs, &config, 1, &n) || n < 1) config = EGL_NO_CONFIG_KHR;
        const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
        EGLContext glctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, ctx_attribs);
        if (glctx == EGL_NO_CONTEXT) {
            snprintf(why, sizeof why, "no OpenGL 4.5 core context (0x%x)", (unsigned)eglGetError());
        } else if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, glctx)) {
            snprintf(why, sizeof why, "surfaceless make-current failed (0x%x)", (unsigned)eglGetError());
            eglDestroyContext(dpy, glctx);
        } else {
            ctx->egl_display = dpy;
            ctx->egl_context = glctx;
            return true;
        }
    }
    if (dpy != EGL_NO_DISPLAY) eglTerminate(dpy);
    size_t used = strlen(tried);
    snprintf(tried + used, tlen - used, "%s%s: %s", used ? "; " : "", label, why);
    return false;
}

/* Whether this thread has a GLX context current. Asked through a libGL/libGLX already in the
 * process (RTLD_NOLOAD): if neither is loaded no GLX context can exist, and going through epoxy's
 * GLX dispatch instead would dlopen libGL and abort where it is missing. */
static bool glx_context_current(void)
{
    const char *libs[2] = {"libGLX.so.0", "libGL.so.1"};
    bool current = false;
    for (int i = 0; i < 2 && !current; ++i) {
        void *lib = dlopen(libs[i], RTLD_LAZY | RTLD_NOLOAD);
        if (!lib) continue;
        void *(*get_current)(void) = NULL;
        void *sym = dlsym(lib, "glXGetCurrentContext");
        memcpy(&get_current, &sym, sizeof sym); /* object to function pointer, as POSIX allows */
        if (get_current) current = get_current() != NULL;
        dlclose(lib);
    }
    return current;
}

/* Adopt the caller's current context (ob_context_desc.use_current). Any GL call without a
 * current context may crash (epoxy aborts when it cannot resolve a function), so first ask EGL
 * and GLX, the two ways a context can be current on Linux, whether there is one at all. */
static ob_context *adopt_current_context(void)
{
    bool egl = eglGetCurrentContext() != EGL_NO_CONTEXT;
    if (!egl && !glx_context_current()) {
        ob_set_error(OB_ERR_NO_CONTEXT,
                     "no current OpenGL context to adopt (use_current): make the window's or engine's "
                     "context current on this thread first");
        return NULL;
    }
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    const char *version = (const char *)glGetString(GL_VERSION);
    if (!renderer || !version) {
        ob_set_error(OB_ERR_NO_CONTEXT, "the current context (use_current) answers no GL_RENDERER/GL_VERSION");
        return NULL;
    }
    if (!epoxy_is_desktop_gl() || epoxy_gl_version() < 45) {
        ob_set_error(OB_ERR_NO_CONTEXT, "the current context (use_current): %s offers %sOpenGL %s, need desktop 4.5",
                     renderer, epoxy_is_desktop_gl() ? "" : "not desktop ", version);
        return NULL;
    }
    ob_context *ctx = calloc(1, sizeof *ctx);
    if (!ctx) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory making the context");
        return NULL;
    }
    ctx->adopted = true;
    snprintf(ctx->renderer, sizeof ctx->renderer, "%s", renderer);
    snprintf(ctx->version, sizeof ctx->version, "%s", version);
    snprintf(ctx->device, sizeof ctx->device, "the caller's context");
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &ctx->max_texture_size);
    ctx->software = ob_renderer_is_software(renderer);
    return ctx;
}

bool ob_renderer_is_software(const char *renderer)
{
    /* Mesa's software rasterisers name themselves in GL_RENDERER. */
    return renderer && (strstr(renderer, "llvmpipe") || strstr(renderer, "softpipe") || strstr(renderer, "SWR"));
}

ob_context *ob_make_context(const ob_context_desc *desc)
{
    ob_context_desc d = desc ? *desc : (ob_context_desc){0};
    if (d.use_current) return adopt_current_context();
    const char *kind = d.gpu == OB_GPU_HW ? "hw" : d.gpu == OB_GPU_SW ? "sw" : "auto";
    const char *client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    /* EGL_EXT_device_base is device_enumeration + device_query in one name: NVIDIA's driver
     * advertises only that one, Mesa both. */
    bool enumeration = has_ext(client, "EGL_EXT_device_enumeration") || has_ext(client, "EGL_EXT_device_base");
    if (!has_ext(client, "EGL_EXT_platform_device") || !enumeration) {
        ob_set_error(OB_ERR_NO_CONTEXT,
                     "no GPU context (--gpu %s): EGL lacks EGL_EXT_platform_device/device_enumeration "
                     "(is libegl1 with Mesa or the NVIDIA driver installed?)", kind);
        return NULL;
    }
    EGLDeviceEXT devices[MAX_DEVICES] = {0};
    EGLint count = 0;
    if (!eglQueryDevicesEXT(MAX_DEVICES, devices, &count) || count < 1) {
        ob_set_error(OB_ERR_NO_CONTEXT, "no GPU context (--gpu %s): EGL lists no devices", kind);
        return NULL;
    }
    ob_context *ctx = calloc(1, sizeof *ctx);
    if (!ctx) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory making the context");
        return NULL;
    }
    char tried[768] = "";
    bool made = false;
    /* Hardware devices first (auto, hw), then software (auto, sw). */
    for (int pass = 0; pass < 2 && !made; ++pass) {
        bool want_sw = pass == 1;
        if (want_sw && d.gpu == OB_GPU_HW) break;
        if (!want_sw && d.gpu == OB_GPU_SW) continue;
        for (EGLint i = 0; i < count && !made; ++i) {
            char label[192] = "";
            describe_device(devices[i], (int)i, label, sizeof label);
            if (device_is_software(devices[i]) != want_sw) {
                if (d.gpu == OB_GPU_HW) { /* say why the only devices there are were not used */
                    size_t used = strlen(tried);
                    snprintf(tried + used, sizeof tried - used, "%s%s: not hardware", used ? "; " : "", label);
                }
                continue;
            }
            if (try_device(ctx, devices[i], label, tried, sizeof tried)) {
                made = true;
                ctx->software = want_sw;
                snprintf(ctx->device, sizeof ctx->device, "%s", label);
            }
        }
    }
    if (!made) {
        ob_set_error(OB_ERR_NO_CONTEXT, "no GPU context (--gpu %s) from %d EGL device(s): %s", kind,
                     (int)count, tried[0] ? tried : (d.gpu == OB_GPU_HW ? "no hardware device" : "no software device"));
        free(ctx);
        return NULL;
    }
    snprintf(ctx->renderer, sizeof ctx->renderer, "%s", (const char *)glGetString(GL_RENDERER));
    snprintf(ctx->version, sizeof ctx->version, "%s", (const char *)glGetString(GL_VERSION));
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &ctx->max_texture_size);
    if (epoxy_gl_version() < 45) {
        ob_set_error(OB_ERR_NO_CONTEXT, "no GPU context: %s offers OpenGL %s, need 4.5", ctx->renderer, ctx->version);
        ob_destroy_context(ctx);
        return NULL;
    }
    return ctx;
}

void ob_destroy_context(ob_context *ctx)
{
    if (!ctx) return;
    /* An adopted context is the caller's: no EGL calls, it stays current and alive. */
    if (!ctx->adopted && ctx->egl_display) {
        eglMakeCurrent(ctx->egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (ctx->egl_context) eglDestroyContext(ctx->egl_display, ctx->egl_context);
        eglTerminate(ctx->egl_display);
    }
    free(ctx);
}

const char *ob_query_renderer(const ob_context *ctx) { return ctx ? ctx->renderer : ""; }
const char *ob_query_gl_version(const ob_context *ctx) { return ctx ? ctx->version : ""; }
const char *ob_query_device(const ob_context *ctx) { return ctx ? ctx->device : ""; }
bool ob_query_is_software(const ob_context *ctx) { return ctx && ctx->software; }
int ob_query_max_texture_size(const ob_context *ctx) { return ctx ? ctx->max_texture_size : 0; }
