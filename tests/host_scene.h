/* The host of the host-path tests, shared by test_host_inputs.c, test_host_state.c and
 * test_host_ortho.c: its own EGL context (a surfaceless OpenGL 4.5 core context, as an engine
 * makes it), and its scene, a sphere on a floor against a wall with a box in the corner, ray-cast
 * on the CPU through a perspective or an orthographic camera into linear depth and view and world
 * normals, with the helpers that encode them as a host's depth and normal textures would hold them
 * (window depth through a projection, octahedral normals). */
#ifndef OB_TEST_HOST_SCENE_H
#define OB_TEST_HOST_SCENE_H

#include <epoxy/egl.h>
#include <epoxy/gl.h>
#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <string.h>

/* ---- the host's context ------------------------------------------------------------------------- */
static EGLDisplay host_dpy = EGL_NO_DISPLAY;
static EGLContext host_ctx = EGL_NO_CONTEXT;

/* A surfaceless OpenGL 4.5 core context of the first EGL device that gives one, as an engine
 * makes it (examples/embed/embed.c); a debug context when `debug` and the driver has one. */
static inline bool make_host_context(bool debug)
{
    /* EGL_EXT_device_base is device_enumeration + device_query in one name: NVIDIA's EGL lists
     * only that one, Mesa's both. */
    if (!(epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_enumeration") ||
          epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_device_base")) ||
        !epoxy_has_egl_extension(EGL_NO_DISPLAY, "EGL_EXT_platform_device"))
        return false;
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (!eglQueryDevicesEXT(16, devices, &count)) return false;
    for (int attempt = debug ? 0 : 1; attempt < 2; ++attempt) {
        const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                  EGL_CONTEXT_OPENGL_DEBUG, attempt == 0 ? EGL_TRUE : EGL_FALSE, EGL_NONE};
        for (EGLint i = 0; i < count; ++i) {
            EGLDisplay dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], NULL);
            if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, NULL, NULL)) continue;
            EGLContext c = eglBindAPI(EGL_OPENGL_API) ? eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs)
                                                      : EGL_NO_CONTEXT;
            if (c != EGL_NO_CONTEXT && eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) {
                host_dpy = dpy;
                host_ctx = c;
                return true;
            }
            if (c != EGL_NO_CONTEXT) eglDestroyContext(dpy, c);
            eglTerminate(dpy);
        }
    }
    return false;
}

/* The host's context made current (debug or not) and adopted by libobscura (*ctx), with a renderer
 * of w x h; NULL after one line on stderr naming why. */
static inline ob_renderer *make_host_renderer(bool debug, int w, int h, ob_context **ctx_out)
{
    if (!make_host_context(debug)) {
        fprintf(stderr, "no EGL device gives an OpenGL 4.5 core context\n");
        return NULL;
    }
    ob_context *ctx = ob_make_context(&(ob_context_desc){.use_current = true});
    ob_renderer *r = ctx ? ob_make_renderer(ctx, &(ob_renderer_desc){.width = w, .height = h}) : NULL;
    if (!r) {
        const char *msg = "";
        ob_get_error(&msg);
        fprintf(stderr, "libobscura: %s\n", msg);
    }
    *ctx_out = ctx;
    return r;
}

static inline void destroy_host_context(void)
{
    if (host_dpy == EGL_NO_DISPLAY) return;
    eglMakeCurrent(host_dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(host_dpy, host_ctx);
    eglTerminate(host_dpy);
    host_dpy = EGL_NO_DISPLAY;
}

/* ---- the host's scene: a sphere on a floor against a wall, a box in the corner ------------------ */
typedef struct host_view {
    int w, h;
    float proj[16];         /* the projection rasterised with (jitter included), column-major */
    float view[16];         /* world -> view, column-major */
    float eye[3], r[3], u[3], f[3];
} host_view;

static inline float dot3(const float a[3], const float b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static inline void cross3(const float a[3], const float b[3], float o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1], o[1] = a[2] * b[0] - a[0] * b[2], o[2] = a[0] * b[1] - a[1] * b[0];
}
static inline void normalize3(float v[3])
{
    float l = sqrtf(dot3(v, v));
    for (int i = 0; i < 3; ++i) v[i] /= l;
}

/* A perspective projection: far 0 = infinite; reversed: near -> 1, far -> 0; zero_to_one: NDC z
 * in [0, 1] (glClipControl's GL_ZERO_TO_ONE) instead of [-1, 1]. */
static inline void perspective(float p[16], float fov_y, float aspect, double n, double f, bool reversed, bool zero_to_one)
{
    memset(p, 0, 16 * sizeof(float));
    double t = tan(0.5 * fov_y);
    p[0] = (float)(1.0 / (aspect * t));
    p[5] = (float)(1.0 / t);
    p[11] = -1.0f;
    double a, b; /* clip z = a z + b, clip w = -z */
    if (f > 0.0) {
        if (zero_to_one) a = f / (n - f), b = n * f / (n - f);            /* -n -> 0, -f -> 1 */
        else a = (f + n) / (n - f), b = 2.0 * f * n / (n - f);           /* -n -> -1, -f -> 1 */
    } else {
        if (zero_to_one) a = -1.0, b = -n;
        else a = -1.0, b = -2.0 * n;
    }
    if (reversed) { /* mirror the window depth: z' = 1 - z in [0, 1], -z in [-1, 1] */
        if (zero_to_one) a = -1.0 - a, b = -b;                           /* clip z' = clip w - clip z */
        else a = -a, b = -b;
    }
    p[10] = (float)a;
    p[14] = (float)b;
}

/* An orthographic projection of the box [-hw, hw] x [-hh, hh] around the view axis, depths n..f,
 * as glm_ortho makes it (P23 = 0, P33 = 1); reversed and zero_to_one as perspective's. */
static inline void orthographic(float p[16], double hw, double hh, double n, double f, bool reversed, bool zero_to_one)
{
    memset(p, 0, 16 * sizeof(float));
    p[0] = (float)(1.0 / hw);
    p[5] = (float)(1.0 / hh);
    p[15] = 1.0f;
    double a, b; /* ndc z = a z + b (w = 1) */
    if (zero_to_one) a = -1.0 / (f - n), b = -n / (f - n);             /* -n -> 0, -f -> 1 */
    else a = -2.0 / (f - n), b = -(f + n) / (f - n);                   /* -n -> -1, -f -> 1 */
    if (reversed) {
        if (zero_to_one) a = -a, b = 1.0 - b;                            /* z' = 1 - z */
        else a = -a, b = -b;
    }
    p[10] = (float)a;
    p[14] = (float)b;
}

static inline bool is_orthographic(const float p[16]) { return p[11] == 0.0f && p[15] == 1.0f; }

static inline void make_view(host_view *v, int w, int h, const float proj[16], const float eye[3], const float target[3])
{
    v->w = w, v->h = h;
    memcpy(v->proj, proj, sizeof v->proj);
    memcpy(v->eye, eye, sizeof v->eye);
    const float up[3] = {0.0f, 1.0f, 0.0f};
    for (int i = 0; i < 3; ++i) v->f[i] = target[i] - eye[i];
    normalize3(v->f);
    cross3(v->f, up, v->r);
    normalize3(v->r);
    cross3(v->r, v->f, v->u);
    memset(v->view, 0, sizeof v->view);
    for (int i = 0; i < 3; ++i) {
        v->view[4 * i + 0] = v->r[i];
        v->view[4 * i + 1] = v->u[i];
        v->view[4 * i + 2] = -v->f[i];
    }
    v->view[12] = -dot3(v->r, eye), v->view[13] = -dot3(v->u, eye), v->view[14] = dot3(v->f, eye);
    v->view[15] = 1.0f;
}

/* The nearest hit of eye + t d, t > 0: the floor y = 0 (|x| < 8, -3 < z < 8), the wall z = -3
 * (|x| < 8, y < 3), a unit sphere at (-0.6, 1, 0) and a box [0.9, 2.4] x [0, 1.2] x [-3, -1.7]
 * standing in the corner. Returns t (-1: none) and the world normal. */
static inline float scene_hit(const float o[3], const float d[3], float n[3])
{
    float best = INFINITY;
    float s = d[1] < 0.0f ? -o[1] / d[1] : -1.0f; /* floor */
    if (s > 0.0f) {
        float x = o[0] + s * d[0], z = o[2] + s * d[2];
        if (fabsf(x) < 8.0f && z > -3.0f && z < 8.0f) best = s, n[0] = 0, n[1] = 1, n[2] = 0;
    }
    s = d[2] < 0.0f ? (-3.0f - o[2]) / d[2] : -1.0f; /* wall */
    if (s > 0.0f && s < best) {
        float x = o[0] + s * d[0], y = o[1] + s * d[1];
        if (fabsf(x) < 8.0f && y > 0.0f && y < 3.0f) best = s, n[0] = 0, n[1] = 0, n[2] = 1;
    }
    const float c[3] = {-0.6f, 1.0f, 0.0f}; /* sphere */
    float oc[3] = {o[0] - c[0], o[1] - c[1], o[2] - c[2]};
    float a = dot3(d, d), b = dot3(oc, d), disc = b * b - a * (dot3(oc, oc) - 1.0f);
    if (disc > 0.0f) {
        s = (-b - sqrtf(disc)) / a;
        if (s > 0.0f && s < best) {
            best = s;
            for (int k = 0; k < 3; ++k) n[k] = o[k] + s * d[k] - c[k];
            normalize3(n);
        }
    }
    const float lo[3] = {0.9f, 0.0f, -3.0f}, hi[3] = {2.4f, 1.2f, -1.7f}; /* box */
    float t0 = -INFINITY, t1 = INFINITY;
    int axis = -1;
    for (int k = 0; k < 3; ++k) {
        if (fabsf(d[k]) < 1e-12f) {
            if (o[k] < lo[k] || o[k] > hi[k]) t0 = INFINITY;
            continue;
        }
        float ta = (lo[k] - o[k]) / d[k], tb = (hi[k] - o[k]) / d[k];
        if (ta > tb) { float tmp = ta; ta = tb; tb = tmp; }
        if (ta > t0) t0 = ta, axis = k;
        if (tb < t1) t1 = tb;
    }
    if (t0 <= t1 && t0 > 0.0f && t0 < best && axis >= 0) {
        best = t0;
        n[0] = n[1] = n[2] = 0.0f;
        n[axis] = d[axis] > 0.0f ? -1.0f : 1.0f;
    }
    return isfinite(best) ? best : -1.0f;
}

/* The ray of pixel (x, y) (row 0 at the bottom): from o along d, with a forward component 1, so
 * that its parameter is the linear depth. Perspective: from the eye through the projection (P20,
 * P21 included), d = r dx + u dy + f. Orthographic: from the eye's plane at
 * o = eye + r (ndc.x - P30) / P00 + u (ndc.y - P31) / P11, along d = f. */
static inline void pixel_ray(const host_view *v, int x, int y, float o[3], float d[3])
{
    float nx = 2.0f * ((float)x + 0.5f) / (float)v->w - 1.0f, ny = 2.0f * ((float)y + 0.5f) / (float)v->h - 1.0f;
    if (is_orthographic(v->proj)) {
        float ox = (nx - v->proj[12]) / v->proj[0], oy = (ny - v->proj[13]) / v->proj[5];
        for (int k = 0; k < 3; ++k) o[k] = v->eye[k] + v->r[k] * ox + v->u[k] * oy, d[k] = v->f[k];
        return;
    }
    float dx = (nx + v->proj[8]) / v->proj[0], dy = (ny + v->proj[9]) / v->proj[5];
    for (int k = 0; k < 3; ++k) o[k] = v->eye[k], d[k] = v->r[k] * dx + v->u[k] * dy + v->f[k];
}

/* Per pixel (row 0 at the bottom): linear view depth (0 = sky), the view and world normals (4
 * floats each, zeros for sky), along pixel_ray. */
static inline void raycast(const host_view *v, float *depth, float *view_n, float *world_n)
{
    for (int y = 0; y < v->h; ++y)
        for (int x = 0; x < v->w; ++x) {
            size_t i = (size_t)y * (size_t)v->w + (size_t)x;
            float o[3], d[3], n[3] = {0, 0, 0};
            pixel_ray(v, x, y, o, d);
            float t = scene_hit(o, d, n);
            depth[i] = t > 0.0f ? t : 0.0f;
            float vn[4] = {dot3(n, v->r), dot3(n, v->u), -dot3(n, v->f), 0.0f};
            for (int k = 0; k < 4; ++k) {
                if (view_n) view_n[4 * i + k] = t > 0.0f ? (k < 3 ? vn[k] : 1.0f) : 0.0f;
                if (world_n) world_n[4 * i + k] = t > 0.0f ? (k < 3 ? n[k] : 1.0f) : 0.0f;
            }
        }
}

/* Window depth of linear depth t through the projection (sky: `sky`). */
static inline float window_depth(const float p[16], float t, bool zero_to_one, float sky)
{
    if (t <= 0.0f) return sky;
    double cz = (double)p[10] * -(double)t + (double)p[14], cw = (double)p[11] * -(double)t + (double)p[15];
    double ndc = cz / cw;
    return (float)(zero_to_one ? ndc : ndc * 0.5 + 0.5);
}

/* Octahedral encoding (Cigolle et al. 2014) of a unit vector into [-1, 1]^2. */
static inline void oct_encode(const float n[3], float e[2])
{
    float s = fabsf(n[0]) + fabsf(n[1]) + fabsf(n[2]);
    float x = n[0] / s, y = n[1] / s;
    if (n[2] < 0.0f) {
        float ox = (1.0f - fabsf(y)) * (x >= 0.0f ? 1.0f : -1.0f), oy = (1.0f - fabsf(x)) * (y >= 0.0f ? 1.0f : -1.0f);
        x = ox, y = oy;
    }
    e[0] = x, e[1] = y;
}

static inline GLuint make_tex(GLenum format, int w, int h)
{
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, format, w, h);
    return t;
}

#endif
