/* The shared helpers of the obscura subcommands (declared in cli.h): one-line failures with the
 * exit codes of README.md, the small value parsers every command shares, the GL context and the
 * output checks. The common scene/method/lighting options are in cli_options.c. */
#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <libgen.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cjson/cJSON.h>

#include "cli.h"
#include "suggest.h"

int cli_unknown_option(const char *command, const char *arg, void (*usage)(FILE *, const struct cli_common *),
                       const struct cli_common *c)
{
    char *text = NULL;
    size_t size = 0;
    FILE *f = usage ? open_memstream(&text, &size) : NULL;
    if (f) {
        usage(f, c);
        fclose(f);
    }
    /* Every "--word" of the help, once each. */
    enum { MOST = 160 };
    char words[MOST][32];
    const char *names[MOST];
    int n = 0;
    for (const char *p = text; p && (p = strstr(p, "--")) != NULL && n < MOST;) {
        size_t len = 2;
        while (p[len] && (isalnum((unsigned char)p[len]) || p[len] == '-')) ++len;
        bool seen = len <= 2 || len >= sizeof words[0];
        for (int k = 0; k < n && !seen; ++k) seen = strlen(words[k]) == len && !strncmp(words[k], p, len);
        if (!seen) {
            memcpy(words[n], p, len);
            words[n][len] = '\0';
            names[n] = words[n];
            ++n;
        }
        p += len;
    }
    char hint[96];
    ob_suggest_text(arg, strlen(arg), names, n, hint, sizeof hint);
    free(text);
    return cli_fail(EXIT_USAGE, "unknown option '%s'%s (see obscura %s --help)", arg, hint, command);
}

/* The last line cli_fail printed, as printed (tune_exchange.c passes it to the other shards). */
static char last_failure[1024];

const char *cli_last_failure(void) { return last_failure; }

/* text appended to last_failure while room is left (cut, never overrun: the line on stderr is whole). */
static void remember(size_t *at, const char *text)
{
    size_t n = strlen(text);
    if (*at + n < sizeof last_failure) {
        memcpy(last_failure + *at, text, n + 1);
        *at += n;
    }
}

int cli_fail(int code, const char *fmt, ...)
{
    char *buf = NULL;
    va_list ap;
    va_start(ap, fmt);
    int len = vasprintf(&buf, fmt, ap);
    va_end(ap);
    /* Messages name files, and a file name may hold a newline or a terminal's escape sequence:
     * control bytes are written as \n, \t or \xNN, so that the message stays one line and
     * shows the name as it is. */
    fputs("obscura: ", stderr);
    size_t at = 0;
    last_failure[0] = '\0';
    for (const unsigned char *p = (const unsigned char *)(len >= 0 ? buf : "out of memory"); *p; ++p) {
        char one[8] = {(char)*p, '\0'};
        if (*p == '\n') snprintf(one, sizeof one, "\\n");
        else if (*p == '\t') snprintf(one, sizeof one, "\\t");
        else if (*p < 0x20 || *p == 0x7f) snprintf(one, sizeof one, "\\x%02x", *p);
        fputs(one, stderr);
        remember(&at, one);
    }
    fputc('\n', stderr);
    if (len >= 0) free(buf);
    return code;
}

int cli_fail_from_library(void) { return cli_fail_from_library_in(NULL); }

int cli_fail_from_library_in(const char *where)
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
    const char *text = msg && *msg ? msg : ob_error_name(err);
    return where ? cli_fail(code, "%s: %s", where, text) : cli_fail(code, "%s", text);
}

int cli_fail_library_as(int code)
{
    const char *msg = NULL;
    ob_error err = ob_get_error(&msg);
    return cli_fail(code, "%s", msg && *msg ? msg : ob_error_name(err));
}

void cli_safe_name(char *out, size_t n, const char *in)
{
    size_t k = 0;
    for (; *in && k + 1 < n; ++in) {
        char c = *in;
        bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
        out[k++] = ok ? c : '_';
    }
    out[k] = '\0';
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

/* Mesa keeps its shader cache in a file it maps into memory (mesa_shader_cache/index, 1.3 MB made
 * with ftruncate, so it takes no blocks until written): on a file system with no room left, the
 * first store through the map is SIGBUS, and the command dies with no message. So, before the
 * first context, the directory Mesa would use (found as Mesa 22.3's disk_cache_generate_cache_dir
 * does) must be writable with room to spare; else Mesa's cache is off for this process. The
 * margin is a guess at what a few hundred shaders and that index take, not a Mesa number. */
enum { SHADER_CACHE_MARGIN = 64 << 20 };

void cli_guard_shader_cache(void)
{
    const char *off = getenv("MESA_SHADER_CACHE_DISABLE");
    if (off && (!strcmp(off, "true") || !strcmp(off, "1") || !strcmp(off, "yes"))) return;
    const char *env = getenv("MESA_SHADER_CACHE_DIR");
    if (!env || !*env) env = getenv("MESA_GLSL_CACHE_DIR"); /* the older name, which Mesa still reads */
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    char dir[4096] = "";
    if (env && *env) snprintf(dir, sizeof dir, "%s/mesa_shader_cache", env);
    else if (xdg && *xdg) snprintf(dir, sizeof dir, "%s/mesa_shader_cache", xdg);
    else if (home && *home) snprintf(dir, sizeof dir, "%s/.cache/mesa_shader_cache", home);
    else return; /* Mesa then asks getpwuid: a setup too unusual to second-guess */
    /* Mesa makes the directory when it is missing: its nearest existing ancestor holds the files. */
    char at[4096] = "";
    snprintf(at, sizeof at, "%s", dir);
    struct stat st = {0};
    while (stat(at, &st) != 0) {
        char *slash = strrchr(at, '/');
        if (!slash || slash == at) {
            snprintf(at, sizeof at, "%s", slash ? "/" : ".");
            if (stat(at, &st) != 0) return;
            break;
        }
        *slash = '\0';
    }
    struct statvfs vfs = {0};
    if (S_ISDIR(st.st_mode) && statvfs(at, &vfs) != 0) return;
    char why[200] = "";
    const unsigned long long free_bytes = (unsigned long long)vfs.f_bavail * vfs.f_frsize;
    if (!S_ISDIR(st.st_mode)) snprintf(why, sizeof why, "is not a directory");
    else if (vfs.f_flag & ST_RDONLY) snprintf(why, sizeof why, "is on a read-only file system");
    else if (access(at, W_OK | X_OK) != 0) snprintf(why, sizeof why, "cannot be written (%s)", strerror(errno));
    else if (vfs.f_files && !vfs.f_favail) snprintf(why, sizeof why, "is on a file system with no free inodes");
    else if (free_bytes < SHADER_CACHE_MARGIN)
        snprintf(why, sizeof why, "is on a file system with %llu KiB free, under the %d MiB it may need", free_bytes / 1024,
                 SHADER_CACHE_MARGIN >> 20);
    if (!why[0]) return;
    /* Both names: older Mesa reads only MESA_GLSL_CACHE_DISABLE. */
    setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);
    setenv("MESA_GLSL_CACHE_DISABLE", "true", 1);
    fprintf(stderr, "obscura: warning: Mesa's shader cache %s: %s %s; running with MESA_SHADER_CACHE_DISABLE=true\n",
            dir, strcmp(at, dir) ? at : "it", why);
}

ob_context *cli_make_context(ob_gpu_kind gpu, bool verbose)
{
    cli_guard_shader_cache();
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

double cli_json_round(double v)
{
    /* 2^53: beyond it every double is whole, and "%.6g" would drop a count's digits. */
    if (!isfinite(v) || (v == trunc(v) && fabs(v) < 9007199254740992.0)) return v;
    char text[32];
    snprintf(text, sizeof text, "%.6g", v);
    return strtod(text, NULL);
}

cJSON *cli_json_add_number(cJSON *object, const char *name, double v)
{
    return cJSON_AddNumberToObject(object, name, cli_json_round(v));
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

bool cli_hdr_dimensions(const char *path, long long *width, long long *height)
{
    struct stat st;
    char why[160];
    int fd = cli_open_regular(path, &st, why, sizeof why); /* anything else is reported when it loads */
    if (fd < 0) return false;
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        close(fd);
        return false;
    }
    /* Radiance: "#?" first, header lines up to an empty one, then "-Y H +X W" (the orientation
     * the loader takes; another one fails there). */
    char line[512] = "";
    bool ok = false;
    long long w = 0, h = 0;
    if (fgets(line, sizeof line, f) && !strncmp(line, "#?", 2))
        for (int k = 0; k < 257 && fgets(line, sizeof line, f); ++k)
            if (line[0] == '\n') {
                char ya[3] = "", xa[3] = "";
                ok = fgets(line, sizeof line, f) && sscanf(line, "%2s %lld %2s %lld", ya, &h, xa, &w) == 4;
                break;
            }
    fclose(f);
    if (!ok || w <= 0 || h <= 0) return false;
    *width = w;
    *height = h;
    return true;
}

const char *cli_file_kind(unsigned mode)
{
    mode_t m = (mode_t)mode;
    if (S_ISREG(m)) return "a regular file";
    if (S_ISDIR(m)) return "a directory";
    if (S_ISFIFO(m)) return "a FIFO";
    if (S_ISCHR(m)) return "a character device";
    if (S_ISBLK(m)) return "a block device";
    if (S_ISSOCK(m)) return "a socket";
    if (S_ISLNK(m)) return "a symbolic link"; /* from lstat */
    return "not a regular file";
}

int cli_open_regular(const char *path, struct stat *st, char *why, size_t n)
{
    if (n) why[0] = '\0';
    /* O_NONBLOCK: open() on a FIFO with no writer would wait forever; fstat then says what it is. */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        snprintf(why, n, "%s", errno == ENOENT ? "no such file" : strerror(errno));
        return -1;
    }
    *st = (struct stat){0};
    if (fstat(fd, st) != 0 || !S_ISREG(st->st_mode)) {
        snprintf(why, n, "it is %s, not a regular file", cli_file_kind(st->st_mode));
        close(fd);
        return -1;
    }
    int flags = fcntl(fd, F_GETFL);
    if (flags >= 0) (void)fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    return fd;
}

char *cli_read_regular(const char *path, size_t limit, size_t *size, char *why, size_t n)
{
    if (size) *size = 0;
    struct stat st;
    int fd = cli_open_regular(path, &st, why, n);
    if (fd < 0) return NULL;
    if ((unsigned long long)st.st_size > (unsigned long long)limit) {
        snprintf(why, n, "it holds %lld bytes, more than the %zu a file of this kind can mean", (long long)st.st_size, limit);
        close(fd);
        return NULL;
    }
    /* What fstat said, and no more: a file growing while it is read is read as it was. */
    const size_t want = (size_t)st.st_size;
    char *buf = malloc(want + 1);
    size_t got = 0;
    while (buf && got < want) {
        ssize_t r = read(fd, buf + got, want - got);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) break;
        got += (size_t)r;
    }
    const int err = errno;
    close(fd);
    if (!buf) {
        snprintf(why, n, "out of memory");
        return NULL;
    }
    if (got < want) {
        snprintf(why, n, "%s", got == 0 && err ? strerror(err) : "it shrank while it was read");
        free(buf);
        return NULL;
    }
    buf[got] = '\0';
    if (size) *size = got;
    return buf;
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
