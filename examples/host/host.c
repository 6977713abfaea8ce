/* host: libobscura inside a renderer of its own, as an engine has one (docs/embedding.md).
 *
 * This program owns everything but the AO. It reads a triangle mesh itself (OFF or OBJ; default
 * the Stanford armadillo scan, the data directory's data/armadillo.off, which scripts/install-deps.sh
 * unpacks), puts it on a floor quad, and rasterises it with its own shaders into its own G-buffer:
 *   depth    GL_DEPTH_COMPONENT32F, reversed Z (glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE),
 *            cleared to 0, GL_GREATER) with an infinite far plane (or a finite one, --far);
 *   normals  GL_RG16F, WORLD-space unit normals, octahedral-encoded;
 *   albedo   GL_RGBA8, linear.
 * With --jitter on (the default) the projection moves by a Halton (2, 3) sub-pixel offset every
 * frame, as a TAA renderer's does. Each frame it hands depth and normals to ob_host_ao (the
 * library's defaults: vbao, crease filter, temporal accumulation when jittering), then lights the
 * frame in its own shader: albedo x (ambient x AO + a directional sun x n.l), accumulated over the
 * frames (a TAA resolve for its still camera) and written as sRGB.
 *
 * It runs headless on EGL's device platform (no display, no window system), or in a GLFW window
 * with --window when built with GLFW.
 *
 *   host [--model FILE.off|.obj] [--size WxH] [--frames N] [--jitter on|off] [--radius R]
 *        [--eye X,Y,Z] [--target X,Y,Z] [--fov DEG] [--near N] [--far F] [--floor-size S]
 *        [--method M] [--filter F] [--temporal on|off] [--guard PX] [--normals world|none]
 *        [--out FILE.png] [--out-ao FILE.pfm] [--gl-debug] [--timings] [--window]
 * exit: 0 ok, 1 failure, 2 bad argument */
#define _POSIX_C_SOURCE 200809L
#include <epoxy/egl.h>
#include <epoxy/gl.h>
#ifdef OB_HOST_GLFW
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#endif
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <obscura/obscura.h>
#include <obscura/eval.h> /* the image writers (ob_write_png, ob_write_pfm) and ob_data_dir's scene.h */

#define PI_F 3.14159265358979f

/* ---- options -------------------------------------------------------------------------------- */
typedef struct options {
    const char *model, *out, *out_ao, *method, *filter;
    int width, height, frames, guard;
    int temporal; /* -1: as jitter */
    bool jitter, window, gl_debug, timings, have_eye, have_target, no_normals;
    float eye[3], target[3], fov_deg, near_z, far_z, floor_size, radius;
} options;

static void usage(FILE *f)
{
    fprintf(f,
            "usage: host [options]\n"
            "  --model FILE      an OFF or OBJ mesh (default: the data directory's data/armadillo.off)\n"
            "  --size WxH        image size (default 640x480)\n"
            "  --frames N        frames to render (default 16; with --window 0 = until closed)\n"
            "  --jitter on|off   Halton (2,3) TAA jitter of the projection (default on)\n"
            "  --temporal on|off the library's temporal accumulation (default: as --jitter)\n"
            "  --radius R        the AO radius in world units (default 5%% of the model's bounding-box\n"
            "                    diagonal, docs/embedding.md \"Choosing R\")\n"
            "  --method M        AO method (default: the library's, vbao); --filter F (default crease)\n"
            "  --guard PX        guard band, pixels per side (default 0)\n"
            "  --normals world|none  hand the library the G-buffer's normals (default) or none: it\n"
            "                    rebuilds them from depth (flat-shaded; docs/embedding.md)\n"
            "  --eye X,Y,Z --target X,Y,Z --fov DEG   the camera (default: the model from the front left)\n"
            "  --near N          near plane (default: 1/1000 of the model's diagonal)\n"
            "  --far F           a finite far plane (default: infinite)\n"
            "  --floor-size S    the floor quad's side (default 4 x the model's larger horizontal extent)\n"
            "  --out FILE.png    the final image\n"
            "  --out-ao FILE.pfm the library's AO output read back (PFM floats, bottom row first; .png: 8-bit)\n"
            "  --gl-debug        a debug context: GL errors and the library's \"obscura\" debug groups on stderr\n"
            "  --timings         the GPU time of each of the library's passes in the last frame\n"
            "  --window          show the frames in a GLFW window\n");
}

static bool parse_vec3(const char *s, float v[3])
{
    char tail;
    return s && sscanf(s, "%f,%f,%f%c", &v[0], &v[1], &v[2], &tail) == 3 && isfinite(v[0]) && isfinite(v[1]) &&
           isfinite(v[2]);
}

static bool parse_float(const char *s, float *v, float lo, float hi)
{
    char *end;
    errno = 0;
    double d = s ? strtod(s, &end) : 0.0;
    if (!s || end == s || *end || errno || !(d >= lo && d <= hi)) return false;
    *v = (float)d;
    return true;
}

static bool parse_int(const char *s, int *v, int lo, int hi)
{
    char *end;
    errno = 0;
    long l = s ? strtol(s, &end, 10) : 0;
    if (!s || end == s || *end || errno || l < lo || l > hi) return false;
    *v = (int)l;
    return true;
}

static bool parse_onoff(const char *s, bool *v)
{
    if (s && !strcmp(s, "on")) return *v = true, true;
    if (s && !strcmp(s, "off")) return *v = false, true;
    return false;
}

/* 0 ok, 1 --help, 2 bad. */
static int parse_options(int argc, char **argv, options *o)
{
    *o = (options){.width = 640, .height = 480, .frames = -1, .temporal = -1, .jitter = true, .fov_deg = 45.0f};
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        bool ok = true, flag = false;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) return 1;
        if (!strcmp(a, "--window")) o->window = flag = true;
        else if (!strcmp(a, "--gl-debug")) o->gl_debug = flag = true;
        else if (!strcmp(a, "--timings")) o->timings = flag = true;
        else if (!strcmp(a, "--model")) ok = (o->model = v) != NULL;
        else if (!strcmp(a, "--out")) ok = (o->out = v) != NULL;
        else if (!strcmp(a, "--out-ao")) ok = (o->out_ao = v) != NULL;
        else if (!strcmp(a, "--method")) ok = (o->method = v) != NULL;
        else if (!strcmp(a, "--filter")) ok = (o->filter = v) != NULL;
        else if (!strcmp(a, "--size")) {
            char tail;
            ok = v && sscanf(v, "%dx%d%c", &o->width, &o->height, &tail) == 2 && o->width > 0 && o->height > 0 &&
                 o->width <= 16384 && o->height <= 16384;
        } else if (!strcmp(a, "--frames")) ok = parse_int(v, &o->frames, 0, 1000000);
        else if (!strcmp(a, "--guard")) ok = parse_int(v, &o->guard, 0, 4096);
        else if (!strcmp(a, "--jitter")) ok = parse_onoff(v, &o->jitter);
        else if (!strcmp(a, "--normals")) {
            ok = v && (!strcmp(v, "world") || !strcmp(v, "none"));
            o->no_normals = ok && !strcmp(v, "none");
        }
        else if (!strcmp(a, "--temporal")) {
            bool t = false;
            ok = parse_onoff(v, &t);
            o->temporal = t;
        } else if (!strcmp(a, "--eye")) ok = o->have_eye = parse_vec3(v, o->eye);
        else if (!strcmp(a, "--target")) ok = o->have_target = parse_vec3(v, o->target);
        else if (!strcmp(a, "--fov")) ok = parse_float(v, &o->fov_deg, 1.0f, 170.0f);
        else if (!strcmp(a, "--near")) ok = parse_float(v, &o->near_z, 1e-30f, 1e30f);
        else if (!strcmp(a, "--far")) ok = parse_float(v, &o->far_z, 1e-30f, 1e30f);
        else if (!strcmp(a, "--floor-size")) ok = parse_float(v, &o->floor_size, 1e-30f, 1e30f);
        else if (!strcmp(a, "--radius")) ok = parse_float(v, &o->radius, 1e-30f, 1e30f);
        else {
            fprintf(stderr, "host: unknown option '%s'\n", a);
            return 2;
        }
        if (!ok) {
            fprintf(stderr, "host: %s: %s value '%s'\n", a, v ? "bad" : "missing", v ? v : "");
            return 2;
        }
        if (!flag) ++i;
    }
    if (o->frames < 0) o->frames = o->window ? 0 : 16;
    if (o->frames == 0 && !o->window) {
        fprintf(stderr, "host: --frames 0 (until the window closes) needs --window\n");
        return 2;
    }
    if (o->far_z > 0.0f && o->near_z > 0.0f && !(o->far_z > o->near_z)) {
        fprintf(stderr, "host: --far must be beyond --near\n");
        return 2;
    }
    return 0;
}

/* ---- the mesh: OFF and OBJ, read whole and parsed with bounds on everything ------------------- */
typedef struct mesh {
    float *pos;      /* 3 per vertex */
    uint32_t *tri;   /* 3 per triangle */
    size_t nv, nt, cap_v, cap_t;
} mesh;

static bool push_vertex(mesh *m, double x, double y, double z)
{
    if (!(fabs(x) <= 1e18 && fabs(y) <= 1e18 && fabs(z) <= 1e18)) return false; /* NaN and infinity too */
    if (m->nv == m->cap_v) {
        size_t cap = m->cap_v ? 2 * m->cap_v : 1024;
        if (cap > (size_t)UINT32_MAX) return false;
        float *p = realloc(m->pos, cap * 3 * sizeof(float));
        if (!p) return false;
        m->pos = p, m->cap_v = cap;
    }
    m->pos[3 * m->nv + 0] = (float)x, m->pos[3 * m->nv + 1] = (float)y, m->pos[3 * m->nv + 2] = (float)z;
    ++m->nv;
    return true;
}

static bool push_triangle(mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    if (m->nt == m->cap_t) {
        size_t cap = m->cap_t ? 2 * m->cap_t : 1024;
        if (cap > (size_t)UINT32_MAX / 3) return false;
        uint32_t *t = realloc(m->tri, cap * 3 * sizeof(uint32_t));
        if (!t) return false;
        m->tri = t, m->cap_t = cap;
    }
    m->tri[3 * m->nt + 0] = a, m->tri[3 * m->nt + 1] = b, m->tri[3 * m->nt + 2] = c;
    ++m->nt;
    return true;
}

/* A cursor over the NUL-terminated file text. */
typedef struct cursor {
    const char *p;
    int line;
} cursor;

/* Skip blanks and comments ('#' to the end of the line); newlines too when `lines`. */
static void skip(cursor *c, bool lines)
{
    for (;;) {
        while (*c->p == ' ' || *c->p == '\t' || *c->p == '\r') ++c->p;
        if (*c->p == '#')
            while (*c->p && *c->p != '\n') ++c->p;
        if (lines && *c->p == '\n') {
            ++c->p, ++c->line;
            continue;
        }
        return;
    }
}

static void next_line(cursor *c)
{
    while (*c->p && *c->p != '\n') ++c->p;
    if (*c->p) ++c->p, ++c->line;
}

static bool read_number(cursor *c, bool lines, double *v)
{
    skip(c, lines);
    char *end;
    *v = strtod(c->p, &end);
    if (end == c->p) return false;
    c->p = end;
    return true;
}

static bool read_count(cursor *c, bool lines, long max, long *v)
{
    skip(c, lines);
    char *end;
    errno = 0;
    *v = strtol(c->p, &end, 10);
    if (end == c->p || errno || *v < 0 || *v > max) return false;
    c->p = end;
    return true;
}

/* OFF: "OFF", then vertex, face and edge counts, the vertices (x y z, anything after them on the
 * line ignored) and the faces (n i0 .. i(n-1), colours after them ignored), polygons fanned. */
static bool parse_off(cursor *c, size_t file_size, mesh *m, char *why, size_t why_size)
{
    skip(c, true);
    if (strncmp(c->p, "OFF", 3) != 0) return snprintf(why, why_size, "no OFF header"), false;
    c->p += 3;
    long nv, nf, ne;
    /* Every vertex takes at least 6 bytes ("0 0 0\n") and every face 8: counts past what the file
     * can hold are refused before anything is allocated for them. */
    if (!read_count(c, true, (long)(file_size / 6), &nv) || !read_count(c, true, (long)(file_size / 8), &nf) ||
        !read_count(c, true, 1L << 40, &ne))
        return snprintf(why, why_size, "line %d: bad or impossible vertex/face/edge counts", c->line), false;
    next_line(c);
    for (long i = 0; i < nv; ++i) {
        double x, y, z;
        if (!read_number(c, true, &x) || !read_number(c, false, &y) || !read_number(c, false, &z))
            return snprintf(why, why_size, "line %d: vertex %ld: expected 3 numbers", c->line, i), false;
        if (!push_vertex(m, x, y, z))
            return snprintf(why, why_size, "line %d: vertex %ld is not finite or out of memory", c->line, i), false;
        next_line(c);
    }
    for (long f = 0; f < nf; ++f) {
        long n, first = 0, prev = 0;
        if (!read_count(c, true, 1 << 16, &n) || n < 3)
            return snprintf(why, why_size, "line %d: face %ld: expected a vertex count >= 3", c->line, f), false;
        for (long k = 0; k < n; ++k) {
            long idx;
            if (!read_count(c, false, nv - 1, &idx))
                return snprintf(why, why_size, "line %d: face %ld: index %ld missing or not below %ld", c->line, f, k,
                                nv), false;
            if (k == 0) first = idx;
            else if (k >= 2 && !push_triangle(m, (uint32_t)first, (uint32_t)prev, (uint32_t)idx))
                return snprintf(why, why_size, "out of memory"), false;
            prev = idx;
        }
        next_line(c);
    }
    return true;
}

/* OBJ: "v x y z" and "f a b c ..." (each corner "i", "i/t", "i/t/n" or "i//n"; negative = from the
 * end); everything else (normals, texture coordinates, groups, materials) is ignored. */
static bool parse_obj(cursor *c, mesh *m, char *why, size_t why_size)
{
    for (; *c->p; next_line(c)) {
        skip(c, false);
        if (c->p[0] == 'v' && (c->p[1] == ' ' || c->p[1] == '\t')) {
            c->p += 1;
            double x, y, z;
            if (!read_number(c, false, &x) || !read_number(c, false, &y) || !read_number(c, false, &z))
                return snprintf(why, why_size, "line %d: expected 3 numbers after v", c->line), false;
            if (!push_vertex(m, x, y, z))
                return snprintf(why, why_size, "line %d: vertex not finite or out of memory", c->line), false;
        } else if (c->p[0] == 'f' && (c->p[1] == ' ' || c->p[1] == '\t')) {
            c->p += 1;
            long k = 0, first = 0, prev = 0;
            for (;; ++k) {
                skip(c, false);
                if (!*c->p || *c->p == '\n') break;
                char *end;
                errno = 0;
                long idx = strtol(c->p, &end, 10);
                if (end == c->p || errno) return snprintf(why, why_size, "line %d: bad face corner", c->line), false;
                c->p = end;
                while (*c->p && *c->p != ' ' && *c->p != '\t' && *c->p != '\r' && *c->p != '\n') ++c->p; /* /t/n */
                long i = idx < 0 ? (long)m->nv + idx : idx - 1;
                if (idx == 0 || i < 0 || i >= (long)m->nv)
                    return snprintf(why, why_size, "line %d: face index %ld out of range (%zu vertices so far)",
                                    c->line, idx, m->nv), false;
                if (k == 0) first = i;
                else if (k >= 2 && !push_triangle(m, (uint32_t)first, (uint32_t)prev, (uint32_t)i))
                    return snprintf(why, why_size, "out of memory"), false;
                prev = i;
            }
            if (k < 3) return snprintf(why, why_size, "line %d: a face needs 3 corners", c->line), false;
        }
    }
    return true;
}

static bool load_mesh(const char *path, mesh *m)
{
    char why[256] = "";
    FILE *f = fopen(path, "rb");
    if (!f) return fprintf(stderr, "host: %s: %s\n", path, strerror(errno)), false;
    char *text = NULL;
    size_t size = 0, cap = 0;
    for (;;) { /* read whole: works for pipes too, and the size bounds the counts above */
        if (size + 65536 + 1 > cap) {
            cap = cap ? 2 * cap : 1 << 20;
            char *t = realloc(text, cap);
            if (!t) {
                free(text), fclose(f);
                return fprintf(stderr, "host: %s: out of memory\n", path), false;
            }
            text = t;
        }
        size_t got = fread(text + size, 1, 65536, f);
        size += got;
        if (got == 0) break;
    }
    bool read_error = ferror(f);
    fclose(f);
    if (read_error) return free(text), fprintf(stderr, "host: %s: read error\n", path), false;
    text[size] = '\0';
    if (strlen(text) != size) return free(text), fprintf(stderr, "host: %s: not a text file (NUL byte)\n", path), false;
    cursor c = {text, 1};
    size_t len = strlen(path);
    bool obj = len > 4 && path[len - 4] == '.' && (path[len - 3] | 0x20) == 'o' && (path[len - 2] | 0x20) == 'b' &&
               (path[len - 1] | 0x20) == 'j';
    bool ok = obj ? parse_obj(&c, m, why, sizeof why) : parse_off(&c, size, m, why, sizeof why);
    free(text);
    if (ok && m->nt == 0) ok = (snprintf(why, sizeof why, "no triangles"), false);
    if (!ok) {
        fprintf(stderr, "host: %s: %s\n", path, why);
        free(m->pos), free(m->tri);
        *m = (mesh){0};
    }
    return ok;
}

/* ---- vertex normals: what the library's import makes for a file without any --------------------
 * Each triangle corner gets the mean of the unit normals of the triangles around its vertex that
 * lie within 40 degrees of its own triangle (Assimp's GenSmoothNormals with the crease angle the
 * library imports with), so a smooth scan comes out smooth and a hard edge stays hard. The result
 * is one vertex per corner: position and normal, 6 floats. */
static float *corner_vertices(const mesh *m)
{
    const float cos_limit = cosf(40.0f * PI_F / 180.0f);
    float *fn = malloc(m->nt * 3 * sizeof(float)), *out = malloc(m->nt * 18 * sizeof(float));
    uint32_t *start = calloc(m->nv + 1, sizeof(uint32_t)), *adj = malloc(m->nt * 3 * sizeof(uint32_t));
    if (!fn || !out || !start || !adj) {
        free(fn), free(out), free(start), free(adj);
        return NULL;
    }
    for (size_t t = 0; t < m->nt; ++t) {
        const uint32_t *v = &m->tri[3 * t];
        const float *a = &m->pos[3 * v[0]], *b = &m->pos[3 * v[1]], *c = &m->pos[3 * v[2]];
        float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3; ++k) fn[3 * t + k] = len > 0.0f ? n[k] / len : 0.0f; /* degenerate: zero */
        for (int k = 0; k < 3; ++k) ++start[m->tri[3 * t + k] + 1];
    }
    for (size_t v = 0; v < m->nv; ++v) start[v + 1] += start[v]; /* triangles of vertex v: adj[start[v] ..] */
    uint32_t *fill = malloc(m->nv * sizeof(uint32_t));
    if (!fill) {
        free(fn), free(out), free(start), free(adj);
        return NULL;
    }
    memcpy(fill, start, m->nv * sizeof(uint32_t));
    for (size_t t = 0; t < m->nt; ++t)
        for (int k = 0; k < 3; ++k) adj[fill[m->tri[3 * t + k]]++] = (uint32_t)t;
    free(fill);
    for (size_t t = 0; t < m->nt; ++t) {
        const float *own = &fn[3 * t];
        bool flat = own[0] == 0.0f && own[1] == 0.0f && own[2] == 0.0f;
        for (int k = 0; k < 3; ++k) {
            uint32_t v = m->tri[3 * t + k];
            float sum[3] = {0.0f, 0.0f, 0.0f};
            for (uint32_t j = start[v]; j < start[v + 1]; ++j) {
                const float *o = &fn[3 * adj[j]];
                if (flat || own[0] * o[0] + own[1] * o[1] + own[2] * o[2] >= cos_limit)
                    sum[0] += o[0], sum[1] += o[1], sum[2] += o[2];
            }
            float len = sqrtf(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
            float *dst = &out[18 * t + 6 * k];
            memcpy(dst, &m->pos[3 * v], 3 * sizeof(float));
            for (int i = 0; i < 3; ++i) dst[3 + i] = len > 0.0f ? sum[i] / len : (i == 1 ? 1.0f : 0.0f);
        }
    }
    free(fn), free(start), free(adj);
    return out;
}

/* ---- matrices: column-major, OpenGL's conventions -------------------------------------------- */
static void normalize3(float v[3])
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0.0f) v[0] /= l, v[1] /= l, v[2] /= l;
}

static void cross3(const float a[3], const float b[3], float out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1], out[1] = a[2] * b[0] - a[0] * b[2], out[2] = a[0] * b[1] - a[1] * b[0];
}

/* World -> view: the camera at eye looking at target, +Y up (gluLookAt). */
static bool look_at(const float eye[3], const float target[3], float m[16])
{
    float f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]}, up[3] = {0.0f, 1.0f, 0.0f}, s[3], u[3];
    normalize3(f);
    cross3(f, up, s);
    if (!(s[0] * s[0] + s[1] * s[1] + s[2] * s[2] > 1e-12f)) return false; /* looking straight up or down */
    normalize3(s);
    cross3(s, f, u);
    const float m2[16] = {s[0], u[0], -f[0], 0.0f, s[1], u[1], -f[1], 0.0f, s[2], u[2], -f[2], 0.0f,
                          -(s[0] * eye[0] + s[1] * eye[1] + s[2] * eye[2]),
                          -(u[0] * eye[0] + u[1] * eye[1] + u[2] * eye[2]),
                          f[0] * eye[0] + f[1] * eye[1] + f[2] * eye[2], 1.0f};
    memcpy(m, m2, sizeof m2);
    return true;
}

/* Reversed-Z perspective for glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE): depth 1 at the near
 * plane, 0 at the far one (far_z 0: at infinity, P22 = 0, P32 = near, so depth = near / view depth). */
static void reversed_z_perspective(float fov_y_deg, float aspect, float near_z, float far_z, float p[16])
{
    float f = 1.0f / tanf(0.5f * fov_y_deg * PI_F / 180.0f);
    memset(p, 0, 16 * sizeof(float));
    p[0] = f / aspect;
    p[5] = f;
    p[11] = -1.0f;
    p[10] = far_z > 0.0f ? near_z / (far_z - near_z) : 0.0f;
    p[14] = far_z > 0.0f ? far_z * near_z / (far_z - near_z) : near_z;
}

static void mat_mul(const float a[16], const float b[16], float out[16])
{
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) {
            float s = 0.0f;
            for (int k = 0; k < 4; ++k) s += a[4 * k + r] * b[4 * c + k];
            out[4 * c + r] = s;
        }
}

/* The radical inverse of i in base b: Halton's sequence, the usual TAA sub-pixel pattern. */
static float halton(int i, int b)
{
    float f = 1.0f, r = 0.0f;
    for (; i > 0; i /= b) f /= (float)b, r += f * (float)(i % b);
    return r;
}

/* ---- the host's shaders ---------------------------------------------------------------------- */
static const char *gbuffer_vs =
    "#version 450 core\n"
    "layout(location = 0) in vec3 a_position;\n"
    "layout(location = 1) in vec3 a_normal;\n"
    "layout(location = 0) uniform mat4 u_view_proj; /* jittered projection x view */\n"
    "out vec3 v_normal;\n"
    "void main() { v_normal = a_normal; gl_Position = u_view_proj * vec4(a_position, 1.0); }\n";

static const char *gbuffer_fs =
    "#version 450 core\n"
    "layout(location = 1) uniform vec3 u_albedo;\n"
    "in vec3 v_normal;\n"
    "layout(location = 0) out vec2 o_normal; /* GL_RG16F: world-space normal, octahedral */\n"
    "layout(location = 1) out vec4 o_albedo; /* GL_RGBA8: linear albedo, alpha 1 = geometry */\n"
    "/* Cigolle et al. 2014, 'A Survey of Efficient Representations for Independent Unit Vectors'. */\n"
    "vec2 octahedral_encode(vec3 n) {\n"
    "    n /= abs(n.x) + abs(n.y) + abs(n.z);\n"
    "    vec2 s = vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);\n"
    "    return n.z >= 0.0 ? n.xy : (1.0 - abs(n.yx)) * s;\n"
    "}\n"
    "void main() {\n"
    "    vec3 n = normalize(v_normal);\n"
    "    if (!gl_FrontFacing) n = -n; /* two-sided: a sheet seen from behind faces the viewer */\n"
    "    o_normal = octahedral_encode(n);\n"
    "    o_albedo = vec4(u_albedo, 1.0);\n"
    "}\n";

static const char *fullscreen_vs =
    "#version 450 core\n"
    "void main() {\n"
    "    gl_Position = vec4(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0, 0.0, 1.0);\n"
    "}\n";

/* The host's lighting: its ambient term times the library's AO, plus a sun without shadows,
 * blended into the previous frames' (the TAA resolve of a still camera), and sRGB-encoded. */
static const char *resolve_fs =
    "#version 450 core\n"
    "layout(binding = 0) uniform sampler2D g_depth;\n"
    "layout(binding = 1) uniform sampler2D g_normal;\n"
    "layout(binding = 2) uniform sampler2D g_albedo;\n"
    "layout(binding = 3) uniform sampler2D u_ao;      /* ob_host_ao's output, the visible size */\n"
    "layout(binding = 4) uniform sampler2D u_history; /* the accumulated linear colour */\n"
    "layout(location = 0) uniform ivec2 u_guard;      /* the visible frame's corner in the G-buffer */\n"
    "layout(location = 1) uniform vec3 u_sun_dir;     /* world, towards the sun, unit */\n"
    "layout(location = 2) uniform vec3 u_sun;\n"
    "layout(location = 3) uniform vec3 u_ambient;\n"
    "layout(location = 4) uniform vec3 u_sky;\n"
    "layout(location = 5) uniform float u_weight;     /* this frame's share: 1 = no history */\n"
    "layout(location = 0) out vec4 o_linear;          /* GL_RGBA16F, the next frame's history */\n"
    "layout(location = 1) out vec4 o_display;         /* GL_RGBA8, sRGB-encoded */\n"
    "vec3 octahedral_decode(vec2 e) {\n"
    "    vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));\n"
    "    if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * vec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);\n"
    "    return normalize(n);\n"
    "}\n"
    "vec3 srgb(vec3 c) {\n"
    "    c = clamp(c, 0.0, 1.0);\n"
    "    return mix(12.92 * c, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));\n"
    "}\n"
    "void main() {\n"
    "    ivec2 p = ivec2(gl_FragCoord.xy), g = p + u_guard;\n"
    "    vec3 c = u_sky;\n"
    "    if (texelFetch(g_depth, g, 0).r > 0.0) { /* reversed Z: the cleared 0 is the sky */\n"
    "        vec3 n = octahedral_decode(texelFetch(g_normal, g, 0).xy);\n"
    "        vec3 albedo = texelFetch(g_albedo, g, 0).rgb;\n"
    "        float ao = texelFetch(u_ao, p, 0).r;\n"
    "        c = albedo * (u_ambient * ao + u_sun * max(dot(n, u_sun_dir), 0.0));\n"
    "    }\n"
    "    c = mix(texelFetch(u_history, p, 0).rgb, c, u_weight);\n"
    "    o_linear = vec4(c, 1.0);\n"
    "    o_display = vec4(srgb(c), 1.0);\n"
    "}\n";

static GLuint compile_program(const char *vs, const char *fs)
{
    const char *src[2] = {vs, fs};
    const GLenum kind[2] = {GL_VERTEX_SHADER, GL_FRAGMENT_SHADER};
    GLuint prog = glCreateProgram();
    char log[2048];
    for (int i = 0; i < 2; ++i) {
        GLuint sh = glCreateShader(kind[i]);
        glShaderSource(sh, 1, &src[i], NULL);
        glCompileShader(sh);
        GLint ok = 0;
        glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            glGetShaderInfoLog(sh, sizeof log, NULL, log);
            fprintf(stderr, "host: the host's own %s shader: %s\n", i ? "fragment" : "vertex", log);
            glDeleteShader(sh), glDeleteProgram(prog);
            return 0;
        }
        glAttachShader(prog, sh);
        glDeleteShader(sh);
    }
    glLinkProgram(prog);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        glGetProgramInfoLog(prog, sizeof log, NULL, log);
        fprintf(stderr, "host: the host's own program: %s\n", log);
        glDeleteProgram(prog);
        return 0;
    }
    return prog;
}

/* ---- contexts -------------------------------------------------------------------------------- */
/* Headless: the first EGL device that gives a surfaceless OpenGL 4.5 core context. */
static EGLDisplay make_egl_context(bool debug)
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
                              EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                              EGL_CONTEXT_OPENGL_DEBUG, debug ? EGL_TRUE : EGL_FALSE, EGL_NONE};
    for (EGLint i = 0; i < count; ++i) {
        EGLDisplay dpy = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], NULL);
        if (dpy == EGL_NO_DISPLAY || !eglInitialize(dpy, NULL, NULL)) continue;
        EGLContext ctx = eglBindAPI(EGL_OPENGL_API) && epoxy_has_egl_extension(dpy, "EGL_KHR_no_config_context") &&
                                 epoxy_has_egl_extension(dpy, "EGL_KHR_surfaceless_context")
                             ? eglCreateContext(dpy, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs)
                             : EGL_NO_CONTEXT;
        if (ctx != EGL_NO_CONTEXT && eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) return dpy;
        if (ctx != EGL_NO_CONTEXT) eglDestroyContext(dpy, ctx);
        eglTerminate(dpy);
    }
    return EGL_NO_DISPLAY;
}

typedef struct debug_counts {
    int errors, obscura_groups;
} debug_counts;

/* --gl-debug: the host's debug callback. The library's commands arrive inside a debug group named
 * "obscura", so a host can tell whose message it is. */
static void GLAPIENTRY on_gl_debug(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                   const GLchar *message, const void *user)
{
    (void)source, (void)id;
    debug_counts *d = (debug_counts *)user;
    if (type == GL_DEBUG_TYPE_PUSH_GROUP) {
        if (length == 7 && !strncmp(message, "obscura", 7)) ++d->obscura_groups;
        return;
    }
    if (type == GL_DEBUG_TYPE_POP_GROUP || severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    if (type == GL_DEBUG_TYPE_ERROR) ++d->errors;
    fprintf(stderr, "host: GL debug: %.*s\n", (int)length, message);
}

/* ---- the program ----------------------------------------------------------------------------- */
static int fail(int code, const char *what)
{
    const char *msg = "";
    bool from_library = ob_get_error(&msg) != OB_OK;
    fprintf(stderr, "host: %s%s%s\n", what, from_library ? ": " : "", from_library ? msg : "");
    return code;
}

static bool write_outputs(const options *o, int w, int h, GLuint ao_tex, GLuint display_tex)
{
    size_t n = (size_t)w * (size_t)h;
    bool ok = true;
    if (o->out_ao) {
        float *ao = malloc(n * sizeof(float));
        uint8_t *grey = malloc(n);
        size_t len = strlen(o->out_ao);
        bool png = len > 4 && !strcmp(o->out_ao + len - 4, ".png");
        ok = ao && grey;
        if (ok) {
            glGetTextureImage(ao_tex, 0, GL_RED, GL_FLOAT, (GLsizei)(n * sizeof(float)), ao); /* bottom row first */
            if (png) { /* top row first for PNG */
                for (int y = 0; y < h; ++y)
                    for (int x = 0; x < w; ++x) {
                        float v = ao[(size_t)(h - 1 - y) * (size_t)w + (size_t)x];
                        grey[(size_t)y * (size_t)w + (size_t)x] = (uint8_t)lrintf(255.0f * fminf(fmaxf(v, 0.0f), 1.0f));
                    }
                ok = ob_write_png(o->out_ao, w, h, 1, grey) == OB_OK;
            } else {
                ok = ob_write_pfm(o->out_ao, w, h, 1, ao) == OB_OK; /* PFM rows run bottom to top too */
            }
            if (!ok) fail(1, "writing --out-ao");
        }
        free(ao), free(grey);
    }
    if (ok && o->out) {
        uint8_t *px = malloc(4 * n), *flipped = malloc(4 * n);
        ok = px && flipped;
        if (ok) {
            glGetTextureImage(display_tex, 0, GL_RGBA, GL_UNSIGNED_BYTE, (GLsizei)(4 * n), px);
            const size_t row = 4 * (size_t)w;
            for (int y = 0; y < h; ++y) memcpy(&flipped[(size_t)y * row], &px[(size_t)(h - 1 - y) * row], row);
            ok = ob_write_png(o->out, w, h, 4, flipped) == OB_OK;
            if (!ok) fail(1, "writing --out");
        }
        free(px), free(flipped);
    }
    return ok;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return 1e3 * (double)ts.tv_sec + 1e-6 * (double)ts.tv_nsec;
}

int main(int argc, char **argv)
{
    options o;
    int parsed = parse_options(argc, argv, &o);
    if (parsed == 1) return usage(stdout), 0;
    if (parsed) return usage(stderr), 2;
#ifndef OB_HOST_GLFW
    if (o.window) return fprintf(stderr, "host: built without GLFW: no --window\n"), 2;
#endif

    /* The scene: the mesh on a floor quad under its lowest point. */
    char default_model[4096];
    if (!o.model) {
        snprintf(default_model, sizeof default_model, "%s/data/armadillo.off", ob_data_dir());
        o.model = default_model;
    }
    mesh m = {0};
    if (!load_mesh(o.model, &m)) return 1;
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < m.nv; ++i)
        for (int k = 0; k < 3; ++k) lo[k] = fminf(lo[k], m.pos[3 * i + k]), hi[k] = fmaxf(hi[k], m.pos[3 * i + k]);
    float ext[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
    float diag = sqrtf(ext[0] * ext[0] + ext[1] * ext[1] + ext[2] * ext[2]);
    if (!(diag > 0.0f) || !isfinite(diag)) {
        free(m.pos), free(m.tri);
        return fprintf(stderr, "host: %s: the model has no extent\n", o.model), 1;
    }
    float centre[3] = {0.5f * (lo[0] + hi[0]), 0.5f * (lo[1] + hi[1]), 0.5f * (lo[2] + hi[2])};
    float floor_half = 0.5f * (o.floor_size > 0.0f ? o.floor_size : 4.0f * fmaxf(ext[0], ext[2]));

    /* The camera: by default the model from the front (-Z), left and above, whole in view. */
    if (!o.have_target) memcpy(o.target, centre, sizeof centre);
    if (!o.have_eye) {
        float dir[3] = {-0.4f, 0.25f, -1.0f}, dist = 0.45f * diag / sinf(0.5f * o.fov_deg * PI_F / 180.0f);
        normalize3(dir);
        for (int k = 0; k < 3; ++k) o.eye[k] = o.target[k] + dist * dir[k];
    }
    float view[16];
    float near_z = o.near_z > 0.0f ? o.near_z : 1e-3f * diag;
    int bad = 0;
    if (!look_at(o.eye, o.target, view))
        bad = 2, fprintf(stderr, "host: --eye and --target: looking straight up or down, or eye = target\n");
    else if (o.far_z > 0.0f && !(o.far_z > near_z))
        bad = 2, fprintf(stderr, "host: --far must be beyond the near plane (%g)\n", (double)near_z);

    /* The library's settings: its defaults but for R, the world units' business of the host. */
    float radius = o.radius > 0.0f ? o.radius : 0.05f * diag;
    bool temporal = o.temporal < 0 ? o.jitter : o.temporal != 0;
    ob_host_settings hs = {
        .method = o.method, .filter = o.filter, .radius = radius, .temporal = temporal, .guard = o.guard};
    ob_settings settings;
    const ob_method_info *method = NULL;
    if (!bad && ob_settings_from_host(&settings, &hs) != OB_OK) bad = fail(2, "settings");
    if (!bad && (method = ob_method_at(settings.method))->directional)
        bad = 2, fprintf(stderr, "host: %s needs the host's direct light; this example composes AO only\n",
                         method->name);
    if (bad) {
        free(m.pos), free(m.tri);
        return bad;
    }

    /* The scene's vertices: the mesh's corners with their normals, then the floor quad. */
    float *corners = corner_vertices(&m);
    GLsizei model_vertices = (GLsizei)(3 * m.nt);
    free(m.pos), free(m.tri);
    if (!corners) return fprintf(stderr, "host: out of memory\n"), 1;
    {
        float x0 = centre[0] - floor_half, x1 = centre[0] + floor_half, z0 = centre[2] - floor_half,
              z1 = centre[2] + floor_half, y = lo[1];
        const float floor_quad[6][6] = {{x0, y, z0, 0, 1, 0}, {x0, y, z1, 0, 1, 0}, {x1, y, z1, 0, 1, 0},
                                        {x0, y, z0, 0, 1, 0}, {x1, y, z1, 0, 1, 0}, {x1, y, z0, 0, 1, 0}};
        float *all = realloc(corners, ((size_t)model_vertices + 6) * 6 * sizeof(float));
        if (!all) return free(corners), fprintf(stderr, "host: out of memory\n"), 1;
        corners = all;
        memcpy(&corners[(size_t)model_vertices * 6], floor_quad, sizeof floor_quad);
    }

    /* The host's context: headless EGL, or a window's. */
    EGLDisplay dpy = EGL_NO_DISPLAY;
#ifdef OB_HOST_GLFW
    GLFWwindow *window = NULL;
    if (o.window) {
        if (!glfwInit()) return fprintf(stderr, "host: GLFW could not start (no display?)\n"), 1;
        glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
        glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
        glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
        glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
        glfwWindowHint(GLFW_OPENGL_DEBUG_CONTEXT, o.gl_debug ? GLFW_TRUE : GLFW_FALSE);
        glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);
        window = glfwCreateWindow(o.width, o.height, "host: libobscura in a renderer of its own", NULL, NULL);
        if (!window) return glfwTerminate(), fprintf(stderr, "host: no OpenGL 4.5 core window\n"), 1;
        glfwMakeContextCurrent(window);
        glfwSwapInterval(1);
    } else
#endif
    {
        dpy = make_egl_context(o.gl_debug);
        if (dpy == EGL_NO_DISPLAY) return fprintf(stderr, "host: no EGL device gives an OpenGL 4.5 core context\n"), 1;
    }
    debug_counts debug = {0, 0};
    if (o.gl_debug) {
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(on_gl_debug, &debug);
        glDebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, NULL, GL_TRUE);
    }

    /* libobscura on the host's context: a renderer of the visible size; the input textures are of
     * ob_host_input_size (larger by the guard band on each side). */
    ob_context *ctx = ob_make_context(&(ob_context_desc){.use_current = true});
    ob_renderer *r = ctx ? ob_make_renderer(ctx, &(ob_renderer_desc){.width = o.width, .height = o.height}) : NULL;
    if (!r) return fail(1, "libobscura");
    int w = o.width, h = o.height, iw = 0, ih = 0, guard = 0;
    ob_host_input_size(r, &settings, &iw, &ih, &guard);

    /* The projection: reversed Z, widened for the guard band (identity without one). */
    float proj[16];
    reversed_z_perspective(o.fov_deg, (float)w / (float)h, near_z, o.far_z, proj);
    ob_guard_projection(proj, w, h, guard);

    /* The host's GL objects. */
    GLuint vbo, vao, empty_vao, tex[4], hdr[2], display, gfbo, rfbo[2];
    glCreateBuffers(1, &vbo);
    glNamedBufferStorage(vbo, ((GLsizeiptr)model_vertices + 6) * 6 * (GLsizeiptr)sizeof(float), corners, 0);
    free(corners);
    glCreateVertexArrays(1, &vao);
    glVertexArrayVertexBuffer(vao, 0, vbo, 0, 6 * sizeof(float));
    for (GLuint a = 0; a < 2; ++a) {
        glEnableVertexArrayAttrib(vao, a);
        glVertexArrayAttribFormat(vao, a, 3, GL_FLOAT, GL_FALSE, a * 3 * sizeof(float));
        glVertexArrayAttribBinding(vao, a, 0);
    }
    glCreateVertexArrays(1, &empty_vao);
    /* tex: G-buffer depth, normals, albedo (the input size) and the AO (the visible size). */
    const GLenum formats[4] = {GL_DEPTH_COMPONENT32F, GL_RG16F, GL_RGBA8, GL_R16F};
    glCreateTextures(GL_TEXTURE_2D, 4, tex);
    glCreateTextures(GL_TEXTURE_2D, 2, hdr);
    glCreateTextures(GL_TEXTURE_2D, 1, &display);
    for (int i = 0; i < 4; ++i) glTextureStorage2D(tex[i], 1, formats[i], i < 3 ? iw : w, i < 3 ? ih : h);
    for (int i = 0; i < 2; ++i) glTextureStorage2D(hdr[i], 1, GL_RGBA16F, w, h);
    glTextureStorage2D(display, 1, GL_RGBA8, w, h);
    for (int i = 0; i < 2; ++i) glClearTexImage(hdr[i], 0, GL_RGBA, GL_FLOAT, NULL); /* no NaN in a history */
    const GLenum draw2[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glCreateFramebuffers(1, &gfbo);
    glNamedFramebufferTexture(gfbo, GL_DEPTH_ATTACHMENT, tex[0], 0);
    glNamedFramebufferTexture(gfbo, GL_COLOR_ATTACHMENT0, tex[1], 0);
    glNamedFramebufferTexture(gfbo, GL_COLOR_ATTACHMENT1, tex[2], 0);
    glNamedFramebufferDrawBuffers(gfbo, 2, draw2);
    glCreateFramebuffers(2, rfbo);
    for (int i = 0; i < 2; ++i) {
        glNamedFramebufferTexture(rfbo[i], GL_COLOR_ATTACHMENT0, hdr[i], 0);
        glNamedFramebufferTexture(rfbo[i], GL_COLOR_ATTACHMENT1, display, 0);
        glNamedFramebufferDrawBuffers(rfbo[i], 2, draw2);
        glNamedFramebufferReadBuffer(rfbo[i], GL_COLOR_ATTACHMENT1);
    }
    GLuint gprog = compile_program(gbuffer_vs, gbuffer_fs), rprog = compile_program(fullscreen_vs, resolve_fs);
    if (!gprog || !rprog) return 1;
    if (glCheckNamedFramebufferStatus(gfbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE ||
        glCheckNamedFramebufferStatus(rfbo[0], GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return fprintf(stderr, "host: the G-buffer or the resolve target is not complete on this GL\n"), 1;

    /* Reversed Z: [0, 1] clip depth, cleared to 0 (the far plane, at infinity), nearer is greater. */
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glDepthFunc(GL_GREATER);
    const float sun_dir[3] = {-0.3f / 1.3153f, 1.0f / 1.3153f, -0.8f / 1.3153f}, sun[3] = {0.75f, 0.73f, 0.69f};
    const float ambient[3] = {0.35f, 0.35f, 0.35f}, sky[3] = {0.42f, 0.52f, 0.66f};
    const float model_albedo[3] = {0.8f, 0.78f, 0.74f}, floor_albedo[3] = {0.7f, 0.7f, 0.7f};

    /* Everything the settings will use compiled and allocated before the first frame. */
    if (ob_host_prepare(r, &settings) != OB_OK) return fail(1, "ob_host_prepare");

    double start = now_ms(), first_ms = 0.0;
    int frame = 0, cur = 0;
    for (; o.frames == 0 || frame < o.frames; ++frame, cur ^= 1) {
#ifdef OB_HOST_GLFW
        if (window && glfwWindowShouldClose(window)) break;
#endif
        /* TAA: this frame's sub-pixel offset (Halton 2, 3 over 16 frames), in pixels of the input
         * size: the rasterised projection moves by 2 jitter / size in P20, P21, as the library
         * expects; ob_host_frame.projection stays the unjittered one. */
        float jitter[2] = {0.0f, 0.0f}, jproj[16], view_proj[16];
        if (o.jitter) jitter[0] = halton(frame % 16 + 1, 2) - 0.5f, jitter[1] = halton(frame % 16 + 1, 3) - 0.5f;
        memcpy(jproj, proj, sizeof proj);
        jproj[8] += 2.0f * jitter[0] / (float)iw;
        jproj[9] += 2.0f * jitter[1] / (float)ih;
        mat_mul(jproj, view, view_proj);

        /* 1. The host's G-buffer. */
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f}, far_depth = 0.0f;
        glBindFramebuffer(GL_FRAMEBUFFER, gfbo);
        glViewport(0, 0, iw, ih);
        glEnable(GL_DEPTH_TEST);
        glDepthMask(GL_TRUE);
        glDisable(GL_CULL_FACE);
        glClearNamedFramebufferfv(gfbo, GL_COLOR, 0, zero);
        glClearNamedFramebufferfv(gfbo, GL_COLOR, 1, zero);
        glClearNamedFramebufferfv(gfbo, GL_DEPTH, 0, &far_depth);
        glUseProgram(gprog);
        glUniformMatrix4fv(0, 1, GL_FALSE, view_proj);
        glBindVertexArray(vao);
        glUniform3fv(1, 1, model_albedo);
        glDrawArrays(GL_TRIANGLES, 0, model_vertices);
        glUniform3fv(1, 1, floor_albedo);
        glDrawArrays(GL_TRIANGLES, model_vertices, 6);

        /* 2. The library's AO on it. */
        ob_host_frame in = {.depth = tex[0], .normal = o.no_normals ? 0 : tex[1], .normal_space = OB_NORMALS_WORLD,
                            .jitter = {jitter[0], jitter[1]}, .depth_zero_to_one = true};
        memcpy(in.projection, proj, sizeof proj);
        memcpy(in.view, view, sizeof view);
        if (ob_host_ao(r, &in, &settings, &(ob_host_outputs){.ao = tex[3]}) != OB_OK) return fail(1, "ob_host_ao");

        /* 3. The host's lighting with the AO in its ambient term, and the resolve. */
        glBindFramebuffer(GL_FRAMEBUFFER, rfbo[cur]);
        glViewport(0, 0, w, h);
        glDisable(GL_DEPTH_TEST);
        glUseProgram(rprog);
        glUniform2i(0, guard, guard);
        glUniform3fv(1, 1, sun_dir);
        glUniform3fv(2, 1, sun);
        glUniform3fv(3, 1, ambient);
        glUniform3fv(4, 1, sky);
        glUniform1f(5, o.jitter ? 1.0f / (float)(frame < 16 ? frame + 1 : 16) : 1.0f);
        GLuint bound[5] = {tex[0], tex[1], tex[2], tex[3], hdr[cur ^ 1]};
        glBindTextures(0, 5, bound);
        glBindVertexArray(empty_vao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
#ifdef OB_HOST_GLFW
        if (window) {
            int fw, fh;
            glfwGetFramebufferSize(window, &fw, &fh);
            glBlitNamedFramebuffer(rfbo[cur], 0, 0, 0, w, h, 0, 0, fw, fh, GL_COLOR_BUFFER_BIT, GL_NEAREST);
            glfwSwapBuffers(window);
            glfwPollEvents();
        }
#endif
        if (frame == 0) glFinish(), first_ms = now_ms() - start;
    }
    glFinish();
    double total_ms = now_ms() - start;

    /* What the frame came to: the mean AO over the geometry. */
    size_t n = (size_t)w * (size_t)h;
    float *ao = malloc(n * sizeof(float));
    uint8_t *albedo = malloc(4 * n);
    double sum = 0.0;
    size_t covered = 0;
    if (ao && albedo && frame > 0) {
        glGetTextureImage(tex[3], 0, GL_RED, GL_FLOAT, (GLsizei)(n * sizeof(float)), ao);
        glGetTextureSubImage(tex[2], 0, guard, guard, 0, w, h, 1, GL_RGBA, GL_UNSIGNED_BYTE, (GLsizei)(4 * n), albedo);
        for (size_t i = 0; i < n; ++i)
            if (albedo[4 * i + 3]) sum += ao[i], ++covered;
    }
    free(ao), free(albedo);
    printf("host: %s (filter %s%s), R %g, on %s: %dx%d (input %dx%d, guard %d), %d frame%s, jitter %s: "
           "mean AO %.4f over %zu px; first frame %.1f ms, then %.1f ms a frame\n",
           method->name, ob_filter_at(settings.filter)->name, settings.temporal ? ", temporal" : "", (double)radius,
           ob_query_renderer(ctx), w, h, iw, ih, guard, frame, frame == 1 ? "" : "s", o.jitter ? "on" : "off",
           covered ? sum / (double)covered : 1.0, covered, first_ms,
           frame > 1 ? (total_ms - first_ms) / (frame - 1) : first_ms);
    if (o.gl_debug)
        printf("host: GL debug: %d error(s), %d \"obscura\" debug group(s)\n", debug.errors, debug.obscura_groups);
    if (o.timings && frame > 0 && ob_wait_timings(r) == OB_OK) { /* the last ob_host_ao's passes */
        ob_pass_timing t[32];
        int count = ob_query_timings(r, t, 32);
        double total = 0.0;
        for (int i = 0; i < count; ++i) printf("host: pass %-10s %8.3f ms\n", t[i].name, t[i].ms), total += t[i].ms;
        printf("host: ob_host_ao   %8.3f ms (GPU, %d passes)\n", total, count);
    }

    int rc = frame > 0 && write_outputs(&o, w, h, tex[3], display) ? 0 : 1;
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) fprintf(stderr, "host: GL error 0x%x\n", e), rc = 1;
    ob_destroy_renderer(r);
    ob_destroy_context(ctx); /* adopted: the GL context stays the host's */
    glDeleteFramebuffers(1, &gfbo), glDeleteFramebuffers(2, rfbo);
    glDeleteTextures(4, tex), glDeleteTextures(2, hdr), glDeleteTextures(1, &display);
    glDeleteVertexArrays(1, &vao), glDeleteVertexArrays(1, &empty_vao), glDeleteBuffers(1, &vbo);
    glDeleteProgram(gprog), glDeleteProgram(rprog);
#ifdef OB_HOST_GLFW
    if (window) {
        glfwDestroyWindow(window);
        glfwTerminate();
    }
#endif
    if (dpy != EGL_NO_DISPLAY) {
        EGLContext glctx = eglGetCurrentContext();
        eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(dpy, glctx);
        eglTerminate(dpy);
    }
    return rc;
}
