/* embed: libobscura inside a host that owns the GL context and the G-buffer, as an engine does.
 *
 * The host makes its own headless OpenGL 4.5 core context (EGL device platform, through epoxy),
 * ray-casts a sphere of radius 1 resting on a floor on the CPU into its own linear-depth (R32F,
 * positive view depth, 0 = sky) and view-normal (RGBA16F) textures, and hands them to
 * ob_compute_ao_filtered with the method and filter named on the command line (by default the
 * library's: OB_DEFAULT_METHOD, vbao, and its default filter, crease). It reads the AO back,
 * writes it (PFM) and checks that the floor is darker where the sphere meets it than far away.
 *
 *   embed [--method vbao] [--filter crease] [--size 320x240] [--radius 1] [--out ao.pfm]
 * exit: 0 ok, 1 failure, 2 bad argument, 3 the contact is not darker than the open floor */
#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <obscura/obscura.h>

static const float eye[3] = {0.0f, 2.2f, 4.0f}, target[3] = {0.0f, 0.6f, 0.0f};
static const float fov_y = 0.87266f, z_near = 0.1f, z_far = 100.0f; /* 50 degrees */

static int fail(int code, const char *what)
{
    const char *msg = "";
    bool from_library = ob_get_error(&msg) != OB_OK;
    fprintf(stderr, "embed: %s%s%s\n", what, from_library ? ": " : "", from_library ? msg : "");
    return code;
}

/* The host's context: the first EGL device that gives a surfaceless OpenGL 4.5 core context. */
static EGLDisplay make_gl_context(void)
{
    /* EGL_EXT_device_base is device_enumeration + device_query in one name: NVIDIA's EGL lists
     * only that one, Mesa's both. */
    if (!(epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration") ||
          epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_base")) ||
        !epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device"))
        return EGL_NO_DISPLAY;
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (!eglQueryDevicesEXT(16, devices, &count)) return EGL_NO_DISPLAY;
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    for (EGLint i = 0; i < count; ++i) {
        EGLDisplay dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], NULL);
        if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, NULL, NULL)) continue;
        EGLContext ctx = eglBindAPI(EGL_OPENGL_API) ? eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs)
                                                    : EGL_NO_CONTEXT;
        if (ctx != EGL_NO_CONTEXT && eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) return dpy;
        eglTerminate(dpy);
    }
    return EGL_NO_DISPLAY;
}

/* A greyscale PFM (Pf, little-endian: scale -1), rows bottom to top: the host's own writer, as the
 * core library writes no files (the evaluation library's ob_write_pfm does, atomically). */
static bool write_pfm(const char *path, int w, int h, const float *px)
{
    FILE *f = fopen(path, "wb");
    if (!f) return false;
    bool ok = fprintf(f, "Pf\n%d %d\n-1.0\n", w, h) > 0 && fwrite(px, sizeof(float), (size_t)w * (size_t)h, f) == (size_t)w * (size_t)h;
    return fclose(f) == 0 && ok;
}

static float dot3(const float a[3], const float b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void normalize3(float v[3])
{
    float l = sqrtf(dot3(v, v));
    for (int i = 0; i < 3; ++i) v[i] /= l;
}

/* Ray-cast the scene: per pixel (row 0 at the bottom, as GL stores textures) the view depth, the
 * view normal and the floor point's distance from the contact (-1 off the floor). */
static void ray_cast(int w, int h, float *depth, float *normal, float *floor_dist)
{
    float f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]}, up[3] = {0.0f, 1.0f, 0.0f};
    normalize3(f);
    float r[3] = {f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0]};
    normalize3(r);
    float u[3] = {r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]};
    const float t = tanf(fov_y * 0.5f), aspect = (float)w / (float)h, centre[3] = {0.0f, 1.0f, 0.0f};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float vx = (2.0f * ((float)x + 0.5f) / (float)w - 1.0f) * t * aspect;
            float vy = (2.0f * ((float)y + 0.5f) / (float)h - 1.0f) * t;
            float d[3], oc[3], p[3], n[3] = {0.0f, 1.0f, 0.0f};
            for (int i = 0; i < 3; ++i) d[i] = r[i] * vx + u[i] * vy + f[i], oc[i] = eye[i] - centre[i];
            /* |eye + s d - centre| = 1 (sphere), else eye.y + s d.y = 0 (floor); s is the view depth. */
            float b = dot3(oc, d), a = dot3(d, d), disc = b * b - a * (dot3(oc, oc) - 1.0f);
            float s = disc > 0.0f ? (-b - sqrtf(disc)) / a : -1.0f;
            bool sphere = s > 0.0f;
            if (!sphere) s = d[1] < 0.0f ? -eye[1] / d[1] : -1.0f;
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            floor_dist[i] = -1.0f;
            if (s <= 0.0f || s > z_far) { /* sky: depth 0, no normal */
                depth[i] = 0.0f;
                memset(&normal[4 * i], 0, 4 * sizeof(float));
                continue;
            }
            for (int k = 0; k < 3; ++k) p[k] = eye[k] + s * d[k];
            if (sphere) {
                for (int k = 0; k < 3; ++k) n[k] = p[k] - centre[k];
            } else {
                floor_dist[i] = sqrtf(p[0] * p[0] + p[2] * p[2]);
            }
            depth[i] = s;
            normal[4 * i + 0] = dot3(n, r), normal[4 * i + 1] = dot3(n, u), normal[4 * i + 2] = -dot3(n, f);
            normal[4 * i + 3] = 1.0f;
        }
}

int main(int argc, char **argv)
{
    const char *method = NULL, *filter = NULL, *out = NULL, *radius = "1"; /* NULL: the library's default */
    int w = 320, h = 240;
    for (int i = 1; i < argc; ++i) {
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(argv[i], "--method") && v) method = argv[++i];
        else if (!strcmp(argv[i], "--filter") && v) filter = argv[++i];
        else if (!strcmp(argv[i], "--radius") && v) radius = argv[++i];
        else if (!strcmp(argv[i], "--out") && v) out = argv[++i];
        else if (!(!strcmp(argv[i], "--size") && v && sscanf(argv[++i], "%dx%d", &w, &h) == 2 && w > 0 && h > 0 &&
                   w <= 4096 && h <= 4096)) {
            fprintf(stderr, "usage: embed [--method M (default %s)] [--filter F (default: the library's)] "
                            "[--size WxH] [--radius R] [--out FILE.pfm]\n", OB_DEFAULT_METHOD);
            return 2;
        }
    }
    /* The radius is in world units, here the sphere's (the library knows no scene to take it
     * from). ob_compute_ao_filtered runs the method, then the filter, on our textures. */
    ob_settings settings;
    char set[64];
    snprintf(set, sizeof set, "radius=%s", radius);
    if (ob_settings_init(&settings, method) != OB_OK || (filter && ob_settings_set_filter(&settings, filter) != OB_OK) ||
        (!isnan(ob_settings_get(&settings, "radius")) && ob_settings_set(&settings, set) != OB_OK))
        return fail(2, "bad settings");

    EGLDisplay dpy = make_gl_context();
    if (dpy == EGL_NO_DISPLAY) return fail(1, "no EGL device gives an OpenGL 4.5 core context");
    ob_context *ctx = ob_make_context(&(ob_context_desc){.use_current = true});
    ob_renderer *renderer = ctx ? ob_make_renderer(ctx, &(ob_renderer_desc){.width = w, .height = h}) : NULL;
    if (!renderer) return fail(1, "libobscura");

    size_t n = (size_t)w * (size_t)h;
    float *depth = malloc(n * sizeof(float)), *normal = malloc(4 * n * sizeof(float));
    float *floor_dist = malloc(n * sizeof(float)), *ao = malloc(n * sizeof(float));
    if (!depth || !normal || !floor_dist || !ao) return fail(1, "out of memory");
    ray_cast(w, h, depth, normal, floor_dist);
    GLuint tex[3]; /* depth, normal, AO */
    const GLenum formats[3] = {GL_R32F, GL_RGBA16F, GL_R32F};
    glCreateTextures(GL_TEXTURE_2D, 3, tex);
    for (int i = 0; i < 3; ++i) glTextureStorage2D(tex[i], 1, formats[i], w, h);
    glTextureSubImage2D(tex[0], 0, 0, 0, w, h, GL_RED, GL_FLOAT, depth);
    glTextureSubImage2D(tex[1], 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, normal);

    /* OpenGL's perspective matrix, column-major: the one the rays above were cast through. */
    const float t = tanf(fov_y * 0.5f), aspect = (float)w / (float)h;
    const float proj[16] = {1.0f / (aspect * t), 0, 0, 0, 0, 1.0f / t, 0, 0,
                            0, 0, (z_far + z_near) / (z_near - z_far), -1.0f,
                            0, 0, 2.0f * z_far * z_near / (z_near - z_far), 0};
    if (ob_compute_ao_filtered(renderer, tex[0], tex[1], proj, &settings, tex[2]) != OB_OK)
        return fail(1, "ob_compute_ao_filtered");
    glGetTextureImage(tex[2], 0, GL_RED, GL_FLOAT, (GLsizei)(n * sizeof(float)), ao);

    /* The floor around the contact (the sphere within 0.3-0.6 above it) against the open floor. */
    double near_sum = 0.0, far_sum = 0.0;
    int near_n = 0, far_n = 0;
    for (size_t i = 0; i < n; ++i) {
        if (floor_dist[i] >= 0.3f && floor_dist[i] <= 0.6f) near_sum += ao[i], ++near_n;
        if (floor_dist[i] >= 2.5f && floor_dist[i] <= 4.0f) far_sum += ao[i], ++far_n;
    }
    double near_ao = near_n ? near_sum / near_n : NAN, far_ao = far_n ? far_sum / far_n : NAN;
    bool ok = near_n > 0 && far_n > 0 && near_ao < far_ao - 0.1;
    printf("embed: %s (filter %s) on %s, %dx%d: AO %.3f at the contact (%d px), %.3f on the open floor (%d px): %s\n",
           ob_method_at(settings.method)->name, ob_filter_at(settings.filter)->name, ob_query_renderer(ctx), w, h,
           near_ao, near_n, far_ao, far_n, ok ? "ok" : "FAIL: the contact is not darker");

    int rc = ok ? 0 : 3; /* PFM rows run bottom to top, as GL's do */
    if (out && !write_pfm(out, w, h, ao)) rc = fail(1, "writing the AO");
    glDeleteTextures(3, tex);
    ob_destroy_renderer(renderer);
    ob_destroy_context(ctx); /* adopted: the context stays ours */
    EGLContext glctx = eglGetCurrentContext();
    eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(dpy, glctx);
    eglTerminate(dpy);
    free(depth), free(normal), free(floor_dist), free(ao);
    return rc;
}
