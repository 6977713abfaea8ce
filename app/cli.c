/* The shared helpers of the obscura subcommands (declared in cli.h): one-line failures with the
 * exit codes of README.md, the small value parsers every command shares, the GL context and the
 * output checks. The common scene/method/lighting options are in cli_options.c. */
#include <errno.h>
#include <libgen.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"

int cli_fail(int code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("obscura: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
    return code;
}

int cli_fail_from_library(void)
{
    const char *msg = NULL;
    ob_error err = ob_get_error(&msg);
    int code = EXIT_RUNTIME;
    switch (err) {
    case OB_ERR_INVALID_ARGUMENT:
    case OB_ERR_OUT_OF_RANGE:
    case OB_ERR_UNKNOWN_SCENE:
    case OB_ERR_UNKNOWN_METHOD:
    case OB_ERR_UNKNOWN_PARAM:
    case OB_ERR_UNKNOWN_CAMERA:
    case OB_ERR_BAD_SIZE: code = EXIT_USAGE; break;
    case OB_ERR_MODEL:
    case OB_ERR_SIDECAR:
    case OB_ERR_IO: code = EXIT_INPUT; break; /* reading: writes go through cli_fail_library_as */
    case OB_ERR_NO_CONTEXT: code = EXIT_NO_GPU; break;
    default: code = EXIT_RUNTIME; break;
    }
    return cli_fail(code, "%s", msg && *msg ? msg : ob_error_name(err));
}

int cli_fail_library_as(int code)
{
    const char *msg = NULL;
    ob_error err = ob_get_error(&msg);
    return cli_fail(code, "%s", msg && *msg ? msg : ob_error_name(err));
}

bool cli_parse_size(const char *text, int *w, int *h)
{
    char *end = NULL;
    errno = 0;
    long a = strtol(text, &end, 10);
    if (end == text || (*end != 'x' && *end != 'X') || errno) return false;
    const char *second = end + 1;
    long b = strtol(second, &end, 10);
    if (end == second || *end != '\0' || errno) return false;
    if (a <= 0 || b <= 0 || a > 1000000 || b > 1000000) return false;
    *w = (int)a;
    *h = (int)b;
    return true;
}

bool cli_parse_float(const char *text, float *out)
{
    char *end = NULL;
    errno = 0;
    double d = strtod(text, &end);
    /* Finite as a float too: 1e39 is a finite double and an infinite float. */
    if (end == text || *end != '\0' || errno || !isfinite(d) || !isfinite((float)d)) return false;
    *out = (float)d;
    return true;
}

ob_context *cli_make_context(ob_gpu_kind gpu, bool verbose)
{
    ob_context *ctx = ob_make_context(&(ob_context_desc){.gpu = gpu});
    if (ctx && verbose)
        fprintf(stderr, "obscura: GL_RENDERER %s | GL_VERSION %s | EGL %s\n", ob_query_renderer(ctx),
                ob_query_gl_version(ctx), ob_query_device(ctx));
    return ctx;
}

bool cli_parse_gpu(const char *text, ob_gpu_kind *out)
{
    if (!strcmp(text, "auto")) *out = OB_GPU_AUTO;
    else if (!strcmp(text, "hw")) *out = OB_GPU_HW;
    else if (!strcmp(text, "sw")) *out = OB_GPU_SW;
    else return false;
    return true;
}

bool cli_parse_on_off(const char *text, bool *out)
{
    if (strcmp(text, "on") != 0 && strcmp(text, "off") != 0) return false;
    *out = !strcmp(text, "on");
    return true;
}

bool cli_parse_up(const char *text, ob_up_axis *out)
{
    if (strcmp(text, "y") != 0 && strcmp(text, "z") != 0) return false;
    *out = !strcmp(text, "y") ? OB_UP_Y : OB_UP_Z;
    return true;
}

bool cli_parse_ao_scale(const char *text, float *out)
{
    /* Exactly these spellings: the AO grid is 1, 2 or 4 full pixels wide. */
    static const struct { const char *name; float scale; } scales[] = {{"1", 1.0f}, {"0.5", 0.5f}, {"0.25", 0.25f}};
    for (size_t i = 0; i < sizeof scales / sizeof scales[0]; ++i)
        if (!strcmp(text, scales[i].name)) {
            *out = scales[i].scale;
            return true;
        }
    return false;
}

bool cli_parse_shadow(const char *text, ob_shadow_method *out)
{
    static const char *const names[] = {"none", "hard", "pcf", "vsm"}; /* ob_shadow_method order */
    for (int i = 0; i < 4; ++i)
        if (!strcmp(text, names[i])) {
            *out = (ob_shadow_method)i;
            return true;
        }
    return false;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double cli_median(double *v, int n)
{
    if (n <= 0) return NAN;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double cli_frame_log_average(ob_renderer *r, float *rgb, size_t px)
{
    if (ob_read_image(r, OB_IMAGE_HDR_F32, rgb, px * 3 * sizeof(float)) != OB_OK) {
        ob_clear_error();
        return NAN;
    }
    /* Rec. 709 luminance, in place: as shaders/hdr_shared.h's ob_luminance. */
    for (size_t i = 0; i < px; ++i) rgb[i] = 0.2126f * rgb[3 * i] + 0.7152f * rgb[3 * i + 1] + 0.0722f * rgb[3 * i + 2];
    return ob_hdr_log_average(rgb, px);
}

int cli_exposure_begin(cli_exposure *e, ob_renderer *r, const ob_camera *cam, const ob_settings *like, size_t px)
{
    memset(e, 0, sizeof *e);
    if (!like->hdr.enabled) return EXIT_OK;
    e->scratch = malloc(px * 3 * sizeof(float));
    if (!e->scratch) return cli_fail(EXIT_RUNTIME, "out of memory");
    e->px = px;
    /* `like` with no AO: everything else (lights, ambient, shadows, HDR, textures) as it is. */
    ob_settings s = *like;
    s.method = ob_find_method("none");
    memset(s.params, 0, sizeof s.params);
    s.params_set = 0;
    s.temporal = false;
    if (ob_render_frame(r, cam, &s) != OB_OK) return cli_fail_from_library();
    e->log_average = cli_frame_log_average(r, e->scratch, px);
    e->key = like->hdr.key > 0.0f ? like->hdr.key : ob_hdr_auto_key((float)e->log_average);
    e->exposure = like->hdr.exposure;
    e->active = e->log_average > 0.0;
    return EXIT_OK;
}

int cli_exposure_apply(cli_exposure *e, ob_renderer *r, const ob_camera *cam, const ob_settings *s)
{
    if (!e->active || !s->hdr.enabled) return EXIT_OK;
    const double l = cli_frame_log_average(r, e->scratch, e->px);
    if (!(l > 0.0)) return EXIT_OK; /* a black frame: its own exposure is as good as any */
    /* The frame's own scale exposure x key / L_avg already the anchor's (the none row, or a frame
     * AO leaves alone): nothing to render again. */
    const double key = s->hdr.key > 0.0f ? s->hdr.key : ob_hdr_auto_key((float)l);
    const double own = s->hdr.exposure * key / l, anchor = e->exposure * e->key / e->log_average;
    if (fabs(own - anchor) <= 1e-6 * anchor) return EXIT_OK;
    ob_settings shared = *s;
    shared.hdr.key = e->key;
    shared.hdr.exposure = (float)(e->exposure * l / e->log_average);
    return ob_render_frame(r, cam, &shared) == OB_OK ? EXIT_OK : cli_fail_from_library();
}

void cli_exposure_free(cli_exposure *e)
{
    free(e->scratch);
    memset(e, 0, sizeof *e);
}

bool cli_parse_vec3(const char *text, float out[3])
{
    const char *p = text;
    for (int i = 0; i < 3; ++i) {
        char *end = NULL;
        errno = 0;
        double d = strtod(p, &end);
        if (end == p || errno || !isfinite(d) || !isfinite((float)d)) return false;
        out[i] = (float)d;
        if (i < 2) {
            if (*end != ',') return false;
            p = end + 1;
        } else if (*end != '\0') {
            return false;
        }
    }
    return true;
}

bool cli_output_writable(const char *path)
{
    char *copy = strdup(path);
    if (!copy) return false;
    const char *dir = dirname(copy);
    bool ok = access(dir, W_OK | X_OK) == 0;
    free(copy);
    return ok;
}

int cli_check_visible(ob_renderer *r, int w, int h, const char *scene, const char *camera, bool allow_empty, int code)
{
    if (allow_empty) return EXIT_OK;
    /* Linear depth is 0 where no geometry is: one float per pixel read back, far less than the
     * frame it checks. */
    size_t px = (size_t)w * (size_t)h;
    float *depth = malloc(px * sizeof(float));
    if (!depth) return cli_fail(EXIT_RUNTIME, "out of memory");
    if (ob_read_image(r, OB_IMAGE_DEPTH_F32, depth, px * sizeof(float)) != OB_OK) {
        free(depth);
        return cli_fail_from_library();
    }
    size_t covered = 0;
    for (size_t i = 0; i < px && !covered; ++i) covered += depth[i] > 0.0f;
    free(depth);
    if (covered) return EXIT_OK;
    return cli_fail(code, "nothing visible from this camera (%s:%s): the frame covers no pixel; check the camera "
                    "(or --allow-empty to write it anyway)", scene, camera);
}
