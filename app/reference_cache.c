/* The ray-traced reference of a view and its cache (reference_cache.h). */
#include "reference_cache.h"

#include <cglm/cglm.h>
#include <cjson/cJSON.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <time.h>
#include <unistd.h>

int cli_view_frame_make(ob_renderer *r, const ob_camera *cam, int width, int height, cli_view_frame *f)
{
    memset(f, 0, sizeof *f);
    size_t px = (size_t)width * (size_t)height;
    f->width = width;
    f->height = height;
    f->depth = malloc(px * sizeof(float));
    f->normals = malloc(px * 3 * sizeof(float));
    if (!f->depth || !f->normals) {
        cli_view_frame_free(f);
        return cli_fail(EXIT_RUNTIME, "out of memory");
    }
    /* The G-buffer is the same for every method: take it from a `none` frame. */
    ob_settings s;
    ob_settings_init(&s, "none");
    if (ob_render_frame(r, cam, &s) != OB_OK) {
        cli_view_frame_free(f);
        return cli_fail_from_library();
    }
    ob_read_image(r, OB_IMAGE_DEPTH_F32, f->depth, px * sizeof(float));
    ob_read_image(r, OB_IMAGE_NORMAL_F32, f->normals, px * 3 * sizeof(float));
    /* The same camera matrices as the renderer (renderer.c): for the world points. */
    f->cam = *cam;
    if (f->cam.fov_y_deg <= 0.0f) f->cam.fov_y_deg = 60.0f;
    if (f->cam.up[0] == 0.0f && f->cam.up[1] == 0.0f && f->cam.up[2] == 0.0f) f->cam.up[1] = 1.0f;
    mat4 view, inv_view, proj;
    glm_lookat(f->cam.eye, f->cam.target, f->cam.up, view);
    glm_mat4_inv(view, inv_view);
    glm_perspective(glm_rad(f->cam.fov_y_deg), (float)width / (float)height, 1.0f, 2.0f, proj);
    proj[2][0] = f->cam.shift[0]; /* the lens shift, as ob_render_frame */
    proj[2][1] = f->cam.shift[1];
    f->proj_info[0] = 1.0f / proj[0][0];
    f->proj_info[1] = 1.0f / proj[1][1];
    f->proj_info[2] = proj[2][0];
    f->proj_info[3] = proj[2][1];
    memcpy(f->inv_view, inv_view, sizeof f->inv_view);
    return EXIT_OK;
}

void cli_view_frame_free(cli_view_frame *f)
{
    free(f->depth);
    free(f->normals);
    f->depth = f->normals = NULL;
}

/* ---- what an entry was traced from -----------------------------------------------------------
 * An entry (reference-HASH.pfm under the cache directory; the name of format 1, so that an old
 * entry is found, named once as older and replaced) is one file: a text header, then the payload.
 *
 *   obscura reference cache 2
 *   tool obscura 0.2.0
 *   view corner|default|v1                      the view key (escaped: %XX)
 *   sources model:SIZE:FNV,sidecar:SIZE:FNV     the scene's files, or "none (built in)"
 *   camera eye ... target ... up ... fov ... near ... far ... shift ...
 *   radius 0.25
 *   rays 512 seed 0                             the rays' seed (ob_reference_desc.seed)
 *   size 320x240
 *   geometry triangles ... vertices ... meshes ... materials ... bounds ...
 *   payload float32le ao,stderr BYTES fnv1a64 HASH
 *   <BYTES: AO and standard error per pixel, bottom row first>
 *
 * Every header line but the first and the last must read exactly as this run would write it: an
 * entry copied from another view, another size, another model or another obscura is foreign. The
 * checksum and the values (AO in [0, 1], standard error finite and >= 0) catch the rest: a cache
 * is a file anyone can truncate or overwrite, and a wrong reference grades every method wrongly
 * without a sign. */
enum { CACHE_FORMAT = 2, HEADER_MAX = 8192, PRINT_MEMO = 16 };
#define CACHE_MAGIC "obscura reference cache "
#define SOURCES_TAG "|src="
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
#define PAYLOAD_ENCODING "float32be"
#else
#define PAYLOAD_ENCODING "float32le"
#endif
#define FNV_OFFSET 1469598103934665603ull

static uint64_t fnv1a(const void *data, size_t n, uint64_t h)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
    return h;
}

/* A file's content hash, by (device, inode, size, mtime): a --path of 100 frames makes 100 keys of
 * the same model, and hashing it each time would cost more than the cached references save. */
typedef struct file_print {
    dev_t dev;
    ino_t ino;
    off_t size;
    struct timespec mtime;
    uint64_t hash;
} file_print;

static pthread_mutex_t memo_lock = PTHREAD_MUTEX_INITIALIZER;
static file_print memo[PRINT_MEMO];
static int memo_next = 0;

static bool same_print(const file_print *a, const struct stat *st)
{
    return a->dev == st->st_dev && a->ino == st->st_ino && a->size == st->st_size &&
           a->mtime.tv_sec == st->st_mtim.tv_sec && a->mtime.tv_nsec == st->st_mtim.tv_nsec;
}

/* "SIZE:HASH" of a file's bytes into out; "?" when it cannot be read. The scene loader has read it
 * already, so that is a file changed under us; the header's geometry line still guards the entry. */
static void print_file(const char *path, char *out, size_t n)
{
    snprintf(out, n, "?");
    /* A FIFO put in the model's place since the load must not hang the key (cli_open_regular). */
    struct stat st;
    char why[160];
    int fd = cli_open_regular(path, &st, why, sizeof why);
    if (fd < 0) return;
    uint64_t h = FNV_OFFSET;
    bool found = false;
    pthread_mutex_lock(&memo_lock);
    for (int i = 0; i < PRINT_MEMO && !found; ++i)
        if (memo[i].mtime.tv_sec && same_print(&memo[i], &st)) h = memo[i].hash, found = true;
    pthread_mutex_unlock(&memo_lock);
    if (!found) {
        enum { CHUNK = 1 << 16 };
        unsigned char *buf = malloc(CHUNK);
        long long total = 0;
        ssize_t r = buf ? 1 : -1;
        while (r > 0 || (r < 0 && errno == EINTR)) {
            r = read(fd, buf, CHUNK);
            if (r > 0) h = fnv1a(buf, (size_t)r, h), total += r;
        }
        free(buf);
        if (r < 0 || total != (long long)st.st_size) { /* unreadable, or it changed while we read it */
            close(fd);
            return;
        }
        pthread_mutex_lock(&memo_lock);
        memo[memo_next] = (file_print){.dev = st.st_dev, .ino = st.st_ino, .size = st.st_size, .mtime = st.st_mtim,
                                       .hash = h};
        memo_next = (memo_next + 1) % PRINT_MEMO;
        pthread_mutex_unlock(&memo_lock);
    }
    close(fd);
    snprintf(out, n, "%lld:%016llx", (long long)st.st_size, (unsigned long long)h);
}

static bool is_regular(const char *path)
{
    struct stat st = {0};
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

static void add_source(char *out, size_t n, const char *what, const char *path)
{
    char print[64] = "";
    print_file(path, print, sizeof print);
    size_t len = strlen(out);
    if (len < n) snprintf(out + len, n - len, "%s%s:%s", len ? "," : "", what, print);
}

/* The model a named scene's JSON names ("model", relative to the JSON), into path. */
static bool named_model(const char *json_path, char *path, size_t n)
{
    FILE *fp = fopen(json_path, "rb");
    if (!fp) return false;
    char text[65536];
    size_t len = fread(text, 1, sizeof text - 1, fp);
    fclose(fp);
    text[len] = '\0';
    cJSON *root = cJSON_Parse(text);
    const cJSON *model = cJSON_GetObjectItemCaseSensitive(root, "model");
    bool ok = cJSON_IsString(model) && model->valuestring[0];
    if (ok) {
        const char *slash = strrchr(json_path, '/');
        if (model->valuestring[0] == '/' || !slash)
            snprintf(path, n, "%s", model->valuestring);
        else
            snprintf(path, n, "%.*s/%s", (int)(slash - json_path), json_path, model->valuestring);
    }
    cJSON_Delete(root);
    return ok;
}

/* A model's own sidecar when none is named: MODEL_DIR/STEM.obscura.json, else the data
 * directory's scenes/STEM.obscura.json. */
static bool model_sidecar(const char *model, const char *data_dir, char *path, size_t n)
{
    const char *slash = strrchr(model, '/');
    const char *base = slash ? slash + 1 : model;
    const char *dot = strrchr(base, '.');
    int stem = (int)(dot && dot != base ? (size_t)(dot - base) : strlen(base));
    if (slash) snprintf(path, n, "%.*s/%.*s.obscura.json", (int)(slash - model), model, stem, base);
    else snprintf(path, n, "%.*s.obscura.json", stem, base);
    if (is_regular(path)) return true;
    if (!data_dir) return false;
    snprintf(path, n, "%s/scenes/%.*s.obscura.json", data_dir, stem, base);
    return is_regular(path);
}

/* The files a scene is read from, found as ob_load_scene finds them (src/scene/scene.c: built in;
 * a named scene's JSON and the model it names; a model path and its sidecar), each as
 * "what:SIZE:HASH": a model edited in place keeps its name, and its old reference must not
 * outlive it. Files a model itself refers to (glTF buffers) are not followed; the header's
 * geometry line (triangle and vertex counts, bounds) is the check for those. */
static void scene_sources(const cli_common *c, const char *name, char *out, size_t n)
{
    out[0] = '\0';
    bool builtin = false;
    for (int i = 0; i < ob_builtin_scene_count() && !builtin; ++i) builtin = !strcmp(ob_builtin_scene_name(i), name);
    const char *data_dir = ob_data_dir();
    char named[4096] = "", path[4096] = "";
    if (!builtin && !strchr(name, '/') && data_dir)
        snprintf(named, sizeof named, "%s/scenes/%s.obscura.json", data_dir, name);
    if (builtin) {
        /* no file: the tool's version in the header stands for its geometry */
    } else if (named[0] && is_regular(named)) {
        add_source(out, n, "scene", named);
        if (named_model(named, path, sizeof path)) add_source(out, n, "model", path);
    } else {
        add_source(out, n, "model", name);
        if ((!c->sidecar || !*c->sidecar) && model_sidecar(name, data_dir, path, sizeof path))
            add_source(out, n, "sidecar", path);
    }
    if (c->sidecar && *c->sidecar) add_source(out, n, "sidecar", c->sidecar);
}

void cli_reference_key(const cli_common *c, const char *scene_name, const char *camera_name, char *key, size_t n)
{
    /* The text before SOURCES_TAG is format 1's key, "v1" included: the entry's name hashes it, so
     * an old entry is found and replaced. --sidecar and --up are in it only when given. */
    int len = snprintf(key, n, "%s|%s|v1", scene_name, camera_name);
    if ((c->sidecar || c->up != OB_UP_DEFAULT) && len > 0 && (size_t)len < n)
        len += snprintf(key + len, n - (size_t)len, "|sidecar=%s|up=%d", c->sidecar ? c->sidecar : "", (int)c->up);
    /* The sources go last, after SOURCES_TAG: the entry's name leaves them out, so that an edited
     * model finds its old entry, names it stale and replaces it rather than leaving it behind. */
    char sources[600] = "";
    scene_sources(c, scene_name, sources, sizeof sources);
    if (sources[0] && len > 0 && (size_t)len < n) snprintf(key + len, n - (size_t)len, SOURCES_TAG "%s", sources);
}

/* The length of the key without its sources. */
static size_t view_part(const char *key)
{
    const char *last = NULL;
    for (const char *p = strstr(key, SOURCES_TAG); p; p = strstr(p + 1, SOURCES_TAG)) last = p;
    return last ? (size_t)(last - key) : strlen(key);
}

static const char *cache_dir(char *buf, size_t n)
{
    const char *xdg = getenv("XDG_CACHE_HOME");
    const char *home = getenv("HOME");
    if (xdg && *xdg) snprintf(buf, n, "%s/obscura", xdg);
    else if (home && *home) snprintf(buf, n, "%s/.cache/obscura", home);
    else return NULL;
    return buf;
}

/* The cache file of a view's reference: its name hashes (view key, camera, radius, spp, size,
 * geometry counts) exactly as format 1 did, so that a format-1 entry is found and replaced.
 * False when there is no cache directory ($XDG_CACHE_HOME and $HOME unset). */
static bool cache_path(const ob_scene *scene, const cli_view_frame *f, const char *view_key, float radius, int spp,
                       char *dir, size_t dn, char *path, size_t pn)
{
    int w = f->width, h = f->height;
    uint64_t key = fnv1a(view_key, view_part(view_key), FNV_OFFSET);
    key = fnv1a(&f->cam, sizeof f->cam, key);
    key = fnv1a(&radius, sizeof radius, key);
    key = fnv1a(&spp, sizeof spp, key);
    key = fnv1a(&w, sizeof w, key);
    key = fnv1a(&h, sizeof h, key);
    ob_scene_stats stats = ob_query_scene_stats(scene);
    key = fnv1a(&stats, sizeof stats, key);
    if (!cache_dir(dir, dn)) return false;
    snprintf(path, pn, "%s/reference-%016llx.pfm", dir, (unsigned long long)key);
    return true;
}

/* text[0..len) with '%', control bytes and DEL as %XX: one header line whatever a path holds. */
static void escape(char *out, size_t n, const char *text, size_t len)
{
    size_t o = 0;
    for (size_t i = 0; i < len && o + 4 < n; ++i) {
        unsigned char ch = (unsigned char)text[i];
        if (ch < 0x20 || ch == 0x7f || ch == '%') o += (size_t)snprintf(out + o, n - o, "%%%02X", ch);
        else out[o++] = (char)ch;
    }
    if (n) out[o < n ? o : n - 1] = '\0';
}

/* The header lines between the first and the payload line: what the entry was traced from. */
static int identity(const ob_scene *scene, const cli_view_frame *f, const char *key, float radius, int spp, char *out,
                    size_t n)
{
    size_t vlen = view_part(key);
    const char *src = key[vlen] ? key + vlen + strlen(SOURCES_TAG) : "";
    char view[3000] = "", sources[2000] = "";
    escape(view, sizeof view, key, vlen);
    escape(sources, sizeof sources, src, strlen(src));
    const ob_camera *c = &f->cam;
    ob_scene_stats st = ob_query_scene_stats(scene);
    return snprintf(out, n,
                    "tool obscura %s\n"
                    "view %s\n"
                    "sources %s\n"
                    "camera eye %.9g %.9g %.9g target %.9g %.9g %.9g up %.9g %.9g %.9g fov %.9g near %.9g far %.9g "
                    "shift %.9g %.9g\n"
                    "radius %.9g\n"
                    "rays %d seed %llu\n"
                    "size %dx%d\n"
                    "geometry triangles %u vertices %u meshes %u materials %u bounds %.9g %.9g %.9g %.9g %.9g %.9g\n",
                    OB_VERSION_STRING, view, sources[0] ? sources : "none (built in)", (double)c->eye[0],
                    (double)c->eye[1], (double)c->eye[2], (double)c->target[0], (double)c->target[1],
                    (double)c->target[2], (double)c->up[0], (double)c->up[1], (double)c->up[2], (double)c->fov_y_deg,
                    (double)c->near_z, (double)c->far_z, (double)c->shift[0], (double)c->shift[1], (double)radius, spp,
                    (unsigned long long)f->seed, f->width, f->height, (unsigned)st.triangles, (unsigned)st.vertices, (unsigned)st.meshes,
                    (unsigned)st.materials, (double)st.bounds_min[0], (double)st.bounds_min[1],
                    (double)st.bounds_min[2], (double)st.bounds_max[0], (double)st.bounds_max[1],
                    (double)st.bounds_max[2]);
}

/* The first line and the payload line take well under 256 bytes: the whole header then fits the
 * HEADER_MAX bytes the reader looks at. */
static bool identity_fits(int len) { return len >= 0 && len + 256 <= HEADER_MAX; }

/* ---- reading an entry ------------------------------------------------------------------------ */

typedef enum entry_state { ENTRY_GOOD, ENTRY_BAD, ENTRY_UNREAD } entry_state;

/* n bytes at offset into buf, as many as there are: fewer only at the end of the file or on an
 * error. */
static size_t read_at(int fd, off_t offset, void *buf, size_t n)
{
    size_t got = 0;
    while (got < n) {
        ssize_t r = pread(fd, (char *)buf + got, n - got, offset + (off_t)got);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) break;
        got += (size_t)r;
    }
    return got;
}

/* The next line of buf[0..len) from *pos, without its newline; false when no newline is left. */
static bool take_line(const char *buf, size_t len, size_t *pos, const char **line, size_t *line_len)
{
    const char *start = buf + *pos;
    const char *nl = memchr(start, '\n', len - *pos);
    if (!nl) return false;
    *line = start;
    *line_len = (size_t)(nl - start);
    *pos += *line_len + 1;
    return true;
}

/* A header value for a message: printable bytes, cut at 100 with "...". */
static void quote(char *out, size_t n, const char *text, size_t len)
{
    size_t o = 0;
    for (size_t i = 0; i < len && o + 4 < n && i < 100; ++i) {
        unsigned char ch = (unsigned char)text[i];
        out[o++] = ch >= 0x20 && ch < 0x7f ? (char)ch : '?';
    }
    if (len > 100 && o + 4 <= n) memcpy(out + o, "...", 3), o += 3;
    out[o] = '\0';
}

/* Why a header line differs from the one expected (both without newlines). */
static void describe_mismatch(const char *want, size_t want_len, const char *found, size_t found_len, char *why,
                              size_t wn)
{
    const char *space = memchr(want, ' ', want_len);
    size_t field = space ? (size_t)(space - want) : want_len;
    char w[128] = "", f[128] = "", name[32] = "";
    quote(name, sizeof name, want, field);
    if (found_len <= field || memcmp(found, want, field + 1) != 0) {
        quote(f, sizeof f, found, found_len);
        snprintf(why, wn, "its header is damaged: expected a '%s' line, found '%s'", name, f);
        return;
    }
    quote(w, sizeof w, want + field + 1, want_len - field - 1);
    quote(f, sizeof f, found + field + 1, found_len - field - 1);
    if (!strcmp(name, "tool"))
        snprintf(why, wn, "written by %s, this is %s", f, w);
    else if (!strcmp(name, "sources"))
        snprintf(why, wn, "the scene's files changed since it was traced (sources %s, now %s)", f, w);
    else
        snprintf(why, wn, "traced for another view: %s is '%s', expected '%s'", name, f, w);
}

/* Check the entry open on fd (a regular file of st) against what this run would write and read
 * its values into ref: ENTRY_BAD with why when it is not that, ENTRY_UNREAD when it could not be
 * judged (out of memory). */
static entry_state read_entry(int fd, const struct stat *st, const char *want, const cli_view_frame *f, float *ref,
                              double *stderr_mean, char *why, size_t wn)
{
    const size_t px = (size_t)f->width * (size_t)f->height;
    const size_t payload_bytes = px * 2 * sizeof(float);
    const unsigned long long size = (unsigned long long)st->st_size;
    if (size == 0) {
        snprintf(why, wn, "it is empty");
        return ENTRY_BAD;
    }
    char head[HEADER_MAX];
    size_t got = read_at(fd, 0, head, size < HEADER_MAX ? (size_t)size : HEADER_MAX);
    const size_t magic = strlen(CACHE_MAGIC);
    if (got >= 3 && head[0] == 'P' && (head[1] == 'F' || head[1] == 'f') && head[2] == '\n') {
        snprintf(why, wn, "written by an older obscura (cache format 1, a bare PFM image)");
        return ENTRY_BAD;
    }
    if (got < magic || memcmp(head, CACHE_MAGIC, magic) != 0) {
        snprintf(why, wn, "not an obscura reference cache entry (no '%s%d' header)", CACHE_MAGIC, CACHE_FORMAT);
        return ENTRY_BAD;
    }
    size_t pos = 0, len = 0;
    const char *line = NULL;
    const char *cut = got == size ? "it is truncated inside its header" : "its header is longer than any entry's";
    if (!take_line(head, got, &pos, &line, &len)) {
        snprintf(why, wn, "%s", cut);
        return ENTRY_BAD;
    }
    char number[32] = "";
    quote(number, sizeof number, line + magic, len - magic);
    char *end = NULL;
    long format = strtol(number, &end, 10);
    if (end == number || *end || format != CACHE_FORMAT) {
        if (end != number && !*end && format < CACHE_FORMAT)
            snprintf(why, wn, "written by an older obscura (cache format %ld)", format);
        else
            snprintf(why, wn, "written by another obscura (cache format '%s', this one reads %d)", number, CACHE_FORMAT);
        return ENTRY_BAD;
    }
    for (const char *w = want; *w;) {
        const char *nl = strchr(w, '\n');
        size_t wlen = nl ? (size_t)(nl - w) : strlen(w);
        if (!take_line(head, got, &pos, &line, &len)) {
            snprintf(why, wn, "%s", cut);
            return ENTRY_BAD;
        }
        if (len != wlen || memcmp(line, w, wlen) != 0) {
            describe_mismatch(w, wlen, line, len, why, wn);
            return ENTRY_BAD;
        }
        w += wlen + (nl ? 1 : 0);
    }
    if (!take_line(head, got, &pos, &line, &len)) {
        snprintf(why, wn, "%s", cut);
        return ENTRY_BAD;
    }
    char payload_line[160] = "", encoding[32] = "";
    unsigned long long bytes = 0, sum = 0;
    int used = 0;
    if (len < sizeof payload_line) memcpy(payload_line, line, len);
    if (len >= sizeof payload_line ||
        sscanf(payload_line, "payload %31s ao,stderr %llu fnv1a64 %16llx%n", encoding, &bytes, &sum, &used) != 3 ||
        (size_t)used != len) {
        char found[128] = "";
        quote(found, sizeof found, line, len);
        snprintf(why, wn, "its header is damaged: expected a 'payload' line, found '%s'", found);
        return ENTRY_BAD;
    }
    if (strcmp(encoding, PAYLOAD_ENCODING) != 0) {
        snprintf(why, wn, "its payload is %s, this machine reads %s", encoding, PAYLOAD_ENCODING);
        return ENTRY_BAD;
    }
    if (bytes != payload_bytes) {
        snprintf(why, wn, "traced for another view: a payload of %llu bytes, expected %zu", bytes, payload_bytes);
        return ENTRY_BAD;
    }
    if (size != pos + payload_bytes) {
        snprintf(why, wn, "%s: %llu bytes, expected %zu (a %zu-byte header and a %zu-byte payload)",
                 size < pos + payload_bytes ? "truncated" : "longer than its header says", size, pos + payload_bytes,
                 pos, payload_bytes);
        return ENTRY_BAD;
    }
    float *data = malloc(payload_bytes);
    if (!data) return ENTRY_UNREAD;
    entry_state state = ENTRY_GOOD;
    if (read_at(fd, (off_t)pos, data, payload_bytes) != payload_bytes) {
        snprintf(why, wn, "truncated: it ended while being read");
        state = ENTRY_BAD;
    } else if (fnv1a(data, payload_bytes, FNV_OFFSET) != sum) {
        snprintf(why, wn, "its payload does not match the checksum in its header (corrupt)");
        state = ENTRY_BAD;
    }
    double se = 0.0;
    size_t n = 0;
    for (size_t i = 0; i < px && state == ENTRY_GOOD; ++i) {
        const float ao = data[2 * i], e = data[2 * i + 1];
        /* Written so that NaN fails too. */
        if (!(ao >= 0.0f && ao <= 1.0f)) {
            snprintf(why, wn, "pixel (%zu, %zu) has AO %g, expected a value in [0, 1]", i % (size_t)f->width,
                     i / (size_t)f->width, (double)ao);
            state = ENTRY_BAD;
        } else if (!(e >= 0.0f && isfinite(e))) {
            snprintf(why, wn, "pixel (%zu, %zu) has standard error %g, expected a finite value >= 0",
                     i % (size_t)f->width, i / (size_t)f->width, (double)e);
            state = ENTRY_BAD;
        } else {
            ref[i] = ao;
            if (f->depth[i] > 0.0f) se += e, ++n;
        }
    }
    free(data);
    if (state == ENTRY_GOOD) *stderr_mean = n ? se / (double)n : 0.0;
    return state;
}


/* Name a bad entry in one line and remove it, if the name still holds what was judged (another
 * process may have renamed a good entry over it since). The name is ours: a symbolic link is
 * removed, never followed, and so is a FIFO, socket or device; a directory is left alone (its
 * contents are not ours to judge), and storing over it will fail with a warning of its own. */
static void discard(const char *path, const struct stat *judged, const char *why)
{
    fprintf(stderr, "obscura: warning: reference cache entry %s: %s%s; recomputing\n", path, why,
            S_ISDIR(judged->st_mode) ? " (left in place)" : "");
    struct stat now = {0};
    if (!S_ISDIR(judged->st_mode) && lstat(path, &now) == 0 && now.st_dev == judged->st_dev &&
        now.st_ino == judged->st_ino)
        unlink(path);
}

bool cli_reference_cache_load(const ob_scene *scene, const cli_view_frame *f, const char *view_key, float radius,
                              int spp, float *ref, double *stderr_mean)
{
    char dir[512], path[700], want[HEADER_MAX], why[512] = "";
    if (!cache_path(scene, f, view_key, radius, spp, dir, sizeof dir, path, sizeof path)) return false;
    int wl = identity(scene, f, view_key, radius, spp, want, sizeof want);
    if (!identity_fits(wl)) return false; /* store refuses such a view too */
    /* lstat first: a device in the entry's place is never opened (opening one may do something). */
    struct stat st = {0};
    if (lstat(path, &st) != 0) {
        /* No entry, or no cache directory yet (store says why it cannot make one). */
        if (errno != ENOENT && errno != ENOTDIR)
            fprintf(stderr, "obscura: warning: reference cache entry %s: %s; recomputing\n", path, strerror(errno));
        return false;
    }
    if (!S_ISREG(st.st_mode)) {
        snprintf(why, sizeof why, "it is %s, not a cache file", cli_file_kind(st.st_mode));
        discard(path, &st, why);
        return false;
    }
    /* O_NOFOLLOW and O_NONBLOCK: whatever the name holds by now, a link is not followed and a FIFO
     * does not block; fstat says what was opened. */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC);
    if (fd < 0) {
        if (errno == ENOENT) return false; /* removed meanwhile: a miss */
        if (errno == ELOOP && lstat(path, &st) == 0) {
            snprintf(why, sizeof why, "it is %s, not a cache file", cli_file_kind(st.st_mode));
            discard(path, &st, why);
        } else {
            fprintf(stderr, "obscura: warning: reference cache entry %s: %s; recomputing\n", path, strerror(errno));
        }
        return false;
    }
    entry_state state = ENTRY_BAD;
    if (fstat(fd, &st) != 0) snprintf(why, sizeof why, "%s", strerror(errno));
    else if (!S_ISREG(st.st_mode)) snprintf(why, sizeof why, "it is %s, not a cache file", cli_file_kind(st.st_mode));
    else state = read_entry(fd, &st, want, f, ref, stderr_mean, why, sizeof why);
    close(fd);
    if (state == ENTRY_BAD) discard(path, &st, why);
    return state == ENTRY_GOOD;
}

/* ---- writing an entry ------------------------------------------------------------------------ */

/* A cache that cannot be written (read-only, full, not a directory) is one warning per process,
 * not an error and not a line per view: the command runs as it would with --no-cache. */
static atomic_bool store_warned = false;

static void store_failed(const char *path, const char *why, bool verbose)
{
    if (atomic_exchange(&store_warned, true) && !verbose) return;
    fprintf(stderr, "obscura: warning: cannot write the reference cache entry %s: %s; going on without caching\n",
            path, why);
}

static bool write_all(int fd, const void *data, size_t n)
{
    const char *p = data;
    while (n) {
        ssize_t w = write(fd, p, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) return false;
        p += w;
        n -= (size_t)w;
    }
    return true;
}

/* A process killed while it wrote an entry (SIGKILL, a crash, a signal taken on another thread)
 * leaves its reference-*.tmp-XXXXXX behind: each store removes those an hour old, far longer
 * than any write takes, so another process's entry in flight is never touched. */
static void remove_stale_temporaries(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    const time_t now = time(NULL);
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        if (strncmp(e->d_name, "reference-", 10) != 0 || !strstr(e->d_name, ".tmp-")) continue;
        struct stat st = {0};
        if (fstatat(dirfd(d), e->d_name, &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISREG(st.st_mode) &&
            now - st.st_mtime > 3600)
            (void)unlinkat(dirfd(d), e->d_name, 0);
    }
    closedir(d);
}

void cli_reference_cache_store(const ob_scene *scene, const cli_view_frame *f, const char *view_key, float radius,
                               int spp, const float *ref, const float *se, bool verbose)
{
    char dir[512], path[700], want[HEADER_MAX], header[HEADER_MAX], why[256] = "";
    if (!cache_path(scene, f, view_key, radius, spp, dir, sizeof dir, path, sizeof path)) return;
    int wl = identity(scene, f, view_key, radius, spp, want, sizeof want);
    if (!identity_fits(wl)) {
        store_failed(path, "the view's description does not fit an entry's header", verbose);
        return;
    }
    const size_t px = (size_t)f->width * (size_t)f->height;
    const size_t payload_bytes = px * 2 * sizeof(float);
    float *data = malloc(payload_bytes);
    if (!data) {
        store_failed(path, "out of memory", verbose);
        return;
    }
    for (size_t i = 0; i < px; ++i) {
        data[2 * i] = ref[i];
        data[2 * i + 1] = se[i];
    }
    int hl = snprintf(header, sizeof header, CACHE_MAGIC "%d\n%spayload " PAYLOAD_ENCODING " ao,stderr %zu fnv1a64 %016llx\n",
                      CACHE_FORMAT, want, payload_bytes, (unsigned long long)fnv1a(data, payload_bytes, FNV_OFFSET));
    char parent[520];
    snprintf(parent, sizeof parent, "%s", dir);
    char *slash = strrchr(parent, '/');
    if (slash) {
        *slash = '\0';
        (void)mkdir(parent, 0777); /* $XDG_CACHE_HOME itself may not exist yet; the next mkdir says why */
    }
    const bool made = mkdir(dir, 0777) == 0 || errno == EEXIST;
    const int made_errno = errno;
    if (made) remove_stale_temporaries(dir);
    struct statvfs vfs = {0};
    const bool have_vfs = made && statvfs(dir, &vfs) == 0;
    const unsigned long long free_bytes = have_vfs ? (unsigned long long)vfs.f_bavail * vfs.f_frsize : 0;
    const unsigned long long need = (unsigned long long)hl + payload_bytes + (1u << 20);
    char tmp[720] = "";
    int fd = -1;
    /* Full or read-only is said as such before a byte is written: a write that fails half way
     * says only ENOSPC, and a read-only cache EROFS on whichever call comes first. */
    if (!made) {
        snprintf(why, sizeof why, "cannot make its directory: %s", strerror(made_errno));
    } else if (have_vfs && (vfs.f_flag & ST_RDONLY)) {
        snprintf(why, sizeof why, "its file system is read-only");
    } else if (have_vfs && free_bytes < need) {
        snprintf(why, sizeof why, "its file system has %llu KiB free, under the %llu KiB an entry and a 1 MiB margin "
                 "need", free_bytes / 1024, need / 1024);
    } else if (snprintf(tmp, sizeof tmp, "%s.tmp-XXXXXX", path) >= (int)sizeof tmp || (fd = mkstemp(tmp)) < 0) {
        snprintf(why, sizeof why, "cannot make a temporary file beside it: %s", strerror(errno));
        tmp[0] = '\0';
    } else if (!write_all(fd, header, (size_t)hl) || !write_all(fd, data, payload_bytes)) {
        snprintf(why, sizeof why, "%s", strerror(errno));
    } else {
        /* mkstemp's 0600 is kept: a cache is the user's own. The temporary name is unique, so two
         * processes tracing the same view each write their own and the second rename wins whole. */
        int closed = close(fd);
        fd = -1;
        if (closed != 0) snprintf(why, sizeof why, "%s", strerror(errno));
        else if (rename(tmp, path) != 0) snprintf(why, sizeof why, "%s", strerror(errno));
        else tmp[0] = '\0';
    }
    if (fd >= 0) close(fd);
    if (tmp[0]) unlink(tmp);
    if (why[0]) store_failed(path, why, verbose);
    free(data);
}

int cli_reference_ao(const ob_scene *scene, const cli_view_frame *f, const char *view_key, float radius, int spp,
                     bool no_cache, bool verbose, float *ref, cli_reference_info *info)
{
    memset(info, 0, sizeof *info);
    int w = f->width, h = f->height;
    size_t px = (size_t)w * (size_t)h;
    if (!no_cache && cli_reference_cache_load(scene, f, view_key, radius, spp, ref, &info->stderr_mean)) {
        info->cached = true;
        return EXIT_OK;
    }
    float *pos = malloc(px * 3 * sizeof(float)), *nrm = malloc(px * 3 * sizeof(float));
    float *se = malloc(px * sizeof(float));
    if (!pos || !nrm || !se) {
        free(pos);
        free(nrm);
        free(se);
        return cli_fail(EXIT_RUNTIME, "out of memory for the reference");
    }
    int code = EXIT_OK;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    if (ob_reference_points(f->depth, f->normals, w, h, f->proj_info, f->inv_view, pos, nrm) != OB_OK ||
        ob_reference_ao(scene, pos, nrm, px, &(ob_reference_desc){.spp = spp, .radius = radius, .progress = true, .seed = f->seed}, ref,
                        se) != OB_OK) {
        code = cli_fail_from_library();
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    info->seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    if (code == EXIT_OK) {
        double sum = 0.0;
        size_t n = 0;
        for (size_t i = 0; i < px; ++i)
            if (f->depth[i] > 0.0f) sum += se[i], ++n;
        info->stderr_mean = n ? sum / (double)n : 0.0;
        /* Cache: a failure to cache is not a failure of the command. */
        cli_reference_cache_store(scene, f, view_key, radius, spp, ref, se, verbose);
    }
    free(pos);
    free(nrm);
    free(se);
    return code;
}
