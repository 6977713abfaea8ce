/* Opening untrusted models (issue 19).
 *
 * Confinement: the model and every file it refers to (glTF buffers and images, OBJ's MTL, the
 * textures import.c loads itself) are opened by ob_model_fs_open, which Assimp reaches through
 * its C file-system hooks (aiFileIO). A reference must resolve (realpath: ".." and symlinks) into
 * the model's directory tree and be a regular file; a model downloaded from anywhere then cannot
 * read ~/.ssh or /dev/zero by naming it.
 *
 * Bounds before allocation: Assimp sizes its arrays from the counts a file declares (a 431-byte
 * PLY declaring 10^9 vertices reached 11.7 GB before failing). The checks here compare each
 * declared count with the bytes that can hold it, and the memory an import would take with the
 * limit, before Assimp sees the file. Quake 3 maps (.pk3 zips and their .bsp) have a file of their
 * own: bsp_check.c. */
#include "eval/model_io.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cjson/cJSON.h>

#include "base/error.h"
#include "eval/bsp_check.h"
#include "io/file.h"

/* Peak bytes per element of an import, measured with Assimp 5.2.5 and our post-processing flags
 * (peak RSS over the raw-scene element counts): a 33 MB OBJ of 2.94 M face corners peaked at
 * 611 MB (208 B per corner, our copy not included); a binary PLY of 0.49 M vertices and 0.98 M
 * faces at 378 MB (Assimp's PLY reader keeps a DOM of every element: about 256 B each). Rounded
 * up, so that the estimate errs towards refusing. */
#define OB_BYTES_PER_VERTEX 256u
#define OB_BYTES_PER_INDEX 48u
#define OB_BYTES_PER_PLY_ELEMENT 256u
/* A format without a check of its own: the STL, OFF and OBJ cases above cost 15-20 bytes per file
 * byte; 24 leaves a margin. Compressed formats (FBX's zlib arrays, pk3) can exceed it: the check on
 * the raw scene in import.c catches those before post-processing. */
#define OB_BYTES_PER_FILE_BYTE 24u

static struct aiFile *ai_open(struct aiFileIO *io, const char *path, const char *mode);
static void ai_close(struct aiFileIO *io, struct aiFile *a);

/* ---- confinement ----------------------------------------------------------------------------- */

bool ob_model_fs_init(ob_model_fs *fs, const char *model, bool allow_external)
{
    memset(fs, 0, sizeof *fs);
    fs->model = model;
    fs->allow_external = allow_external;
    char real[PATH_MAX] = "";
    if (!realpath(model, real)) {
        ob_set_error(OB_ERR_IO, "%s: cannot resolve the model's path: %s", model, strerror(errno));
        return false;
    }
    char *slash = strrchr(real, '/');
    if (!slash || slash == real) {
        snprintf(fs->root, sizeof fs->root, "/");
    } else {
        *slash = '\0';
        snprintf(fs->root, sizeof fs->root, "%s", real);
    }
    fs->io.OpenProc = ai_open;
    fs->io.CloseProc = ai_close;
    fs->io.UserData = (aiUserData)fs;
    return true;
}

static bool inside_root(const ob_model_fs *fs, const char *real)
{
    size_t n = strlen(fs->root);
    if (n == 1 && fs->root[0] == '/') return true;
    return strncmp(real, fs->root, n) == 0 && (real[n] == '/' || real[n] == '\0');
}

static void refuse(ob_model_fs *fs, const char *reference, const char *why)
{
    if (fs->refused[0]) return; /* the first refusal is the one to fix first */
    snprintf(fs->refused, sizeof fs->refused, "'%s'%s", reference, why);
}

FILE *ob_model_fs_open(ob_model_fs *fs, const char *path, const char *reference)
{
    const char *ref = reference ? reference : path;
    struct stat st = {0};
    /* A missing file is no refusal: importers probe for optional companions (an OBJ's default
     * MTL), and nothing is read from a file that is not there. */
    if (!path || !*path || stat(path, &st) != 0) return NULL;
    char why[2 * PATH_MAX + 200] = ""; /* two paths and the words between them */
    if (!fs->allow_external) {
        char real[PATH_MAX] = "";
        if (reference && reference[0] == '/') {
            refuse(fs, ref, ", an absolute path (--allow-external-files allows it)");
            return NULL;
        }
        if (!realpath(path, real)) return NULL;
        if (!inside_root(fs, real)) {
            snprintf(why, sizeof why, ", which resolves to %s, outside the model's directory %s (--allow-external-files allows it)",
                     real, fs->root);
            refuse(fs, ref, why);
            return NULL;
        }
    }
    /* Never lifted: a FIFO would block the import, /dev/zero would fill the memory. */
    if (!S_ISREG(st.st_mode)) {
        snprintf(why, sizeof why, ", which is %s, not a regular file", ob_file_kind(st.st_mode));
        refuse(fs, ref, why);
        return NULL;
    }
    /* O_NONBLOCK: should the path have become a FIFO since the stat, open must not hang on it. */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) return NULL;
    struct stat st2 = {0};
    if (fstat(fd, &st2) != 0 || !S_ISREG(st2.st_mode) || st2.st_ino != st.st_ino || st2.st_dev != st.st_dev) {
        close(fd);
        refuse(fs, ref, ", which changed while it was being opened");
        return NULL;
    }
    int flags = fcntl(fd, F_GETFL);
    if (flags >= 0) (void)fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    FILE *f = fdopen(fd, "rb");
    if (!f) close(fd);
    return f;
}

/* ---- Assimp's file system -------------------------------------------------------------------- */

static size_t ai_read(struct aiFile *a, char *buf, size_t size, size_t count)
{
    return fread(buf, size, count, (FILE *)a->UserData);
}

static size_t ai_write(struct aiFile *a, const char *buf, size_t size, size_t count)
{
    (void)a;
    (void)buf;
    (void)size;
    (void)count;
    return 0; /* importers only read */
}

static size_t ai_tell(struct aiFile *a)
{
    off_t t = ftello((FILE *)a->UserData);
    return t < 0 ? 0 : (size_t)t;
}

static size_t ai_size(struct aiFile *a)
{
    struct stat st = {0};
    return fstat(fileno((FILE *)a->UserData), &st) == 0 ? (size_t)st.st_size : 0;
}

static enum aiReturn ai_seek(struct aiFile *a, size_t offset, enum aiOrigin origin)
{
    int whence = origin == aiOrigin_CUR ? SEEK_CUR : origin == aiOrigin_END ? SEEK_END : SEEK_SET;
    /* Assimp passes backward offsets as size_t: two's complement gives them back their sign. */
    return fseeko((FILE *)a->UserData, (off_t)(int64_t)offset, whence) == 0 ? aiReturn_SUCCESS : aiReturn_FAILURE;
}

static void ai_flush(struct aiFile *a) { (void)a; }

static struct aiFile *ai_open(struct aiFileIO *io, const char *path, const char *mode)
{
    ob_model_fs *fs = (ob_model_fs *)io->UserData;
    if (!mode || strpbrk(mode, "wa+")) {
        refuse(fs, path, ", opened for writing");
        return NULL;
    }
    FILE *f = ob_model_fs_open(fs, path, NULL);
    if (!f) return NULL;
    struct aiFile *a = calloc(1, sizeof *a);
    if (!a) {
        fclose(f);
        return NULL;
    }
    a->ReadProc = ai_read;
    a->WriteProc = ai_write;
    a->TellProc = ai_tell;
    a->FileSizeProc = ai_size;
    a->SeekProc = ai_seek;
    a->FlushProc = ai_flush;
    a->UserData = (aiUserData)f;
    return a;
}

static void ai_close(struct aiFileIO *io, struct aiFile *a)
{
    (void)io;
    if (!a) return;
    fclose((FILE *)a->UserData);
    free(a);
}


/* ---- memory ---------------------------------------------------------------------------------- */

uint64_t ob_model_estimate_peak(uint64_t vertices, uint64_t face_indices)
{
    return vertices * OB_BYTES_PER_VERTEX + face_indices * OB_BYTES_PER_INDEX;
}

/* "1.50 GiB", "20.0 MiB": for the messages. */
static const char *human(uint64_t bytes, char *buf, size_t n)
{
    if (bytes >= (1ull << 30)) snprintf(buf, n, "%.2f GiB", (double)bytes / (double)(1ull << 30));
    else snprintf(buf, n, "%.1f MiB", (double)bytes / (double)(1ull << 20));
    return buf;
}

/* ---- PLY ------------------------------------------------------------------------------------- */

/* Bytes of a PLY scalar type; 0 for an unknown one. */
static unsigned ply_type_size(const char *t)
{
    static const struct {
        const char *name;
        unsigned size;
    } types[] = {{"char", 1},   {"uchar", 1},  {"int8", 1},   {"uint8", 1},   {"short", 2},  {"ushort", 2},
                 {"int16", 2},  {"uint16", 2}, {"int", 4},    {"uint", 4},    {"int32", 4},  {"uint32", 4},
                 {"float", 4},  {"float32", 4}, {"double", 8}, {"float64", 8}};
    for (size_t k = 0; k < sizeof types / sizeof types[0]; ++k)
        if (!strcmp(t, types[k].name)) return types[k].size;
    return 0;
}

/* One header line (without the newline) into buf; false at EOF or for a line too long. */
static bool read_line(FILE *f, char *buf, size_t n)
{
    size_t len = 0;
    int c = 0;
    while ((c = getc(f)) != EOF && c != '\n') {
        if (len + 1 >= n) return false;
        buf[len++] = (char)c;
    }
    if (c == EOF && len == 0) return false;
    while (len > 0 && (buf[len - 1] == '\r' || buf[len - 1] == ' ')) --len;
    buf[len] = '\0';
    return true;
}

/* A PLY property as the body walk needs it: a scalar of value_size bytes, or a list whose count
 * takes count_size bytes and each value value_size. */
enum { PLY_MAX_PROPERTIES = 256 };
typedef struct ply_element {
    char name[64];
    uint64_t count, min_bytes;
} ply_element;
typedef struct ply_property {
    int element;
    bool list;
    unsigned count_size, value_size;
} ply_property;

/* The next whitespace-separated ASCII token as an unsigned count; false at the end of the file or
 * for anything that is not a number (a float count is read as its integer part, as Assimp does). */
static bool ply_ascii_token(FILE *f, uint64_t *value, bool want)
{
    int c = 0;
    while ((c = getc(f)) != EOF && (c == ' ' || c == '\t' || c == '\n' || c == '\r')) {}
    if (c == EOF) return false;
    uint64_t v = 0;
    bool past = false, negative = c == '-'; /* past: after the integer part ('.', 'e': ignored) */
    if (c == '-' || c == '+') c = getc(f);
    for (; c != EOF && c != ' ' && c != '\t' && c != '\n' && c != '\r'; c = getc(f)) {
        if (!want || past) continue;
        if (c >= '0' && c <= '9') v = v > UINT64_MAX / 10u - 9u ? UINT64_MAX / 10u : v * 10u + (uint64_t)(c - '0');
        else past = true;
    }
    if (want) *value = negative ? 0u : v; /* a negative count makes an empty list, nothing reserved */
    return true;
}

static uint64_t ply_binary_count(const unsigned char *b, unsigned size, bool big_endian)
{
    /* Read as unsigned: a negative count of a signed type comes out huge and is refused like one
     * (Assimp reads it into an unsigned size as well). */
    uint64_t v = 0;
    for (unsigned k = 0; k < size; ++k) v |= (uint64_t)b[big_endian ? size - 1u - k : k] << (8u * k);
    return v;
}

/* Walk the body: each list's count must fit in the bytes that follow it (2 bytes a value in
 * ASCII, a digit and a separator; value_size in binary). *values gets the lists' values in all.
 * A body shorter than its header says is left to Assimp's own message. */
static bool ply_check_lists(ob_model_fs *fs, FILE *f, uint64_t size, bool ascii, bool big_endian, const ply_element *el,
                            int elements, const ply_property *props, int np, uint64_t *values)
{
    *values = 0;
    bool any_list = false;
    for (int k = 0; k < np; ++k) any_list = any_list || props[k].list;
    if (!any_list) return true; /* nothing Assimp reserves from the body */
    for (int e = 0; e < elements; ++e) {
        const uint64_t count = el[e].count;
        bool has_list = false;
        uint64_t row = 0; /* binary: the bytes of a row without lists */
        for (int k = 0; k < np; ++k)
            if (props[k].element == e) {
                has_list = has_list || props[k].list;
                row += props[k].value_size;
            }
        if (!has_list && !ascii) {
            /* Binary rows of scalars: skipped whole (the header check showed they fit). */
            if (fseeko(f, (off_t)(count * row), SEEK_CUR) != 0) return true;
            continue;
        }
        for (uint64_t i = 0; i < count; ++i)
            for (int k = 0; k < np; ++k) {
                if (props[k].element != e) continue;
                uint64_t c = 0;
                if (ascii) {
                    if (!ply_ascii_token(f, &c, props[k].list)) return true; /* short: Assimp says so */
                } else if (props[k].list) {
                    unsigned char b[8] = {0};
                    if (fread(b, 1, props[k].count_size, f) != props[k].count_size) return true;
                    c = ply_binary_count(b, props[k].count_size, big_endian);
                } else {
                    if (fseeko(f, (off_t)props[k].value_size, SEEK_CUR) != 0) return true;
                    continue;
                }
                if (!props[k].list) continue;
                off_t at = ftello(f);
                uint64_t left = at >= 0 && (uint64_t)at <= size ? size - (uint64_t)at : 0;
                uint64_t per = ascii ? 2u : props[k].value_size;
                if (c > left / per) {
                    ob_set_error(OB_ERR_MODEL, "%s: PLY '%s' %llu declares a list of %llu values, which need at least "
                                 "%llu bytes; only %llu bytes follow (corrupt)", fs->model, el[e].name, (unsigned long long)i,
                                 (unsigned long long)c, (unsigned long long)(c > UINT64_MAX / per ? UINT64_MAX : c * per),
                                 (unsigned long long)left);
                    return false;
                }
                *values += c;
                if (ascii) {
                    for (uint64_t v = 0; v < c; ++v)
                        if (!ply_ascii_token(f, NULL, false)) return true;
                } else if (fseeko(f, (off_t)(c * per), SEEK_CUR) != 0) {
                    return true;
                }
            }
    }
    return true;
}

static bool check_ply(ob_model_fs *fs, FILE *f, uint64_t size, uint64_t *estimate)
{
    enum { MAX_ELEMENTS = 64, HEADER_MAX = 1 << 16 };
    ply_element el[MAX_ELEMENTS];
    int n = 0;
    bool ascii = true, big_endian = false;
    ply_property props[PLY_MAX_PROPERTIES];
    int np = 0;
    char line[1024] = "";
    /* Assimp's PLY reader loops forever on some malformed headers (a first line "ply\xff...",
     * found by tests/fuzz/fuzz_model.c): anything it would read as PLY must pass this stricter
     * reading of the header first. */
    bool has_format = false;
    if (!read_line(f, line, sizeof line) || strcmp(line, "ply") != 0) {
        ob_set_error(OB_ERR_MODEL, "%s: not a PLY file: its first line is not 'ply'", fs->model);
        return false;
    }
    for (;;) {
        if (ftello(f) > HEADER_MAX || !read_line(f, line, sizeof line)) {
            ob_set_error(OB_ERR_MODEL, "%s: PLY header has no end_header within %d bytes", fs->model, HEADER_MAX);
            return false;
        }
        for (const char *p = line; *p; ++p) {
            if ((unsigned char)*p < 0x20 && *p != '\t') {
                ob_set_error(OB_ERR_MODEL, "%s: PLY header holds control bytes (corrupt, or not PLY)", fs->model);
                return false;
            }
        }
        char kw[32] = "", a[64] = "", b[64] = "", c[64] = "";
        int got = sscanf(line, "%31s %63s %63s %63s", kw, a, b, c);
        if (got < 1) continue;
        if (!strcmp(kw, "end_header")) break;
        if (!strcmp(kw, "comment") || !strcmp(kw, "obj_info")) continue;
        if (!strcmp(kw, "format") && got >= 3) {
            ascii = !strcmp(a, "ascii");
            big_endian = !strcmp(a, "binary_big_endian");
            if (!ascii && strcmp(a, "binary_little_endian") != 0 && strcmp(a, "binary_big_endian") != 0) {
                ob_set_error(OB_ERR_MODEL, "%s: PLY format '%s' is none of ascii, binary_little_endian, binary_big_endian", fs->model, a);
                return false;
            }
            has_format = true;
        } else if (!strcmp(kw, "element") && got >= 3) {
            if (n == MAX_ELEMENTS) {
                ob_set_error(OB_ERR_MODEL, "%s: PLY header declares more than %d elements", fs->model, MAX_ELEMENTS);
                return false;
            }
            char *end = NULL;
            errno = 0;
            unsigned long long count = strtoull(b, &end, 10);
            if (b[0] == '-' || !end || *end || errno || count > UINT32_MAX) {
                ob_set_error(OB_ERR_MODEL, "%s: PLY element '%s' has a bad count '%s'", fs->model, a, b);
                return false;
            }
            snprintf(el[n].name, sizeof el[n].name, "%s", a);
            el[n].count = count;
            el[n].min_bytes = 0;
            ++n;
        } else if (!strcmp(kw, "property") && got >= 3 && n > 0) {
            /* The fewest bytes one value can take: its size in binary; a digit and a separator in
             * ASCII. A list may be empty: its count alone. */
            bool list = !strcmp(a, "list");
            unsigned sz = ply_type_size(a);
            if (list) sz = ply_type_size(b);
            if (sz == 0) {
                ob_set_error(OB_ERR_MODEL, "%s: PLY property '%s' has an unknown type", fs->model, line);
                return false;
            }
            if (el[n - 1].min_bytes < 4096u) el[n - 1].min_bytes += ascii ? 2u : sz;
            if (np == PLY_MAX_PROPERTIES) {
                ob_set_error(OB_ERR_MODEL, "%s: PLY header declares more than %d properties", fs->model, PLY_MAX_PROPERTIES);
                return false;
            }
            /* "property list COUNT_TYPE VALUE_TYPE name": sz is the count's size for a list. */
            props[np++] = (ply_property){.element = n - 1, .list = list, .count_size = list ? sz : 0u,
                                         .value_size = list ? ply_type_size(c) : sz};
            if (list && props[np - 1].value_size == 0) {
                ob_set_error(OB_ERR_MODEL, "%s: PLY property '%s' has an unknown type", fs->model, line);
                return false;
            }
        } else if (!strcmp(kw, "element") || !strcmp(kw, "property") || !strcmp(kw, "format")) {
            ob_set_error(OB_ERR_MODEL, "%s: PLY header line '%.60s' is incomplete", fs->model, line);
            return false;
        }
        /* Other text lines are skipped, as Assimp does: Blender 2.47 wrote its "Created by" line
         * without "comment" (assimp-testmodels' Wuson.ply). */
    }
    if (!has_format) {
        ob_set_error(OB_ERR_MODEL, "%s: PLY header has no format line", fs->model);
        return false;
    }
    off_t header = ftello(f);
    uint64_t left = header >= 0 && (uint64_t)header <= size ? size - (uint64_t)header : 0;
    uint64_t need = 0, est = size;
    for (int k = 0; k < n; ++k) {
        /* count <= 2^32 and min_bytes < 2^13: no overflow in 64 bits over 64 elements. */
        need += el[k].count * el[k].min_bytes;
        if (need > left) {
            ob_set_error(OB_ERR_MODEL,
                         "%s: PLY header declares %llu '%s' elements, which need at least %llu bytes; only %llu bytes follow the header (truncated or corrupt)",
                         fs->model, (unsigned long long)el[k].count, el[k].name, (unsigned long long)need,
                         (unsigned long long)left);
            return false;
        }
        est += el[k].count * OB_BYTES_PER_PLY_ELEMENT;
    }
    /* The header's counts fit; the lists' own counts are in the body, and Assimp reserves a list
     * before it reads it (a 681-byte ASCII PLY with a count of 10^9 took 7.8 GB before failing):
     * every list count is checked against the bytes left, in one pass over the body. */
    uint64_t list_values = 0;
    if (!ply_check_lists(fs, f, size, ascii, big_endian, el, n, props, np, &list_values)) return false;
    /* Each list value becomes an index (4 bytes) and, in Assimp's intermediate, a vertex reference
     * of its own: 16 bytes a value is the measured order of it. */
    *estimate = est + list_values * 16u;
    return true;
}

/* ---- OBJ ------------------------------------------------------------------------------------- */

/* Assimp's OBJ reader makes one vertex per face corner: count them. Counts come from the text
 * itself, so they cannot exceed the file; the scan is for the memory estimate. */
static bool check_obj(FILE *f, uint64_t size, uint64_t *estimate)
{
    uint64_t corners = 0;
    int c = 0, prev = '\n';
    bool in_face = false, in_token = false;
    while ((c = getc(f)) != EOF) {
        if (prev == '\n' && c == 'f') {
            int next = getc(f);
            in_face = next == ' ' || next == '\t';
            if (next == EOF) break;
            c = next;
            in_token = false;
        } else if (c == '\n') {
            in_face = false;
        } else if (in_face) {
            bool space = c == ' ' || c == '\t' || c == '\r';
            if (!space && !in_token) ++corners;
            in_token = !space;
        }
        prev = c;
    }
    *estimate = size + ob_model_estimate_peak(corners, corners);
    return true;
}

/* ---- OFF ------------------------------------------------------------------------------------- */

/* Past blank space, line ends and comment lines, as Assimp's NextToken. */
static const char *off_skip(const char *p, const char *end)
{
    while (p < end && (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n' || *p == '#')) {
        if (*p == '#') {
            while (p < end && *p != '\n') ++p;
        } else {
            ++p;
        }
    }
    return p;
}

/* Assimp's OFF reader allocates its vertex, normal, colour and face arrays from the header's
 * counts before it reads a line (assimp-testmodels' invalid/OutOfMemory.off, 310 bytes declaring
 * 3.5e12 vertices, took 16 GB under the fuzzer). Each vertex and each face is one line of at
 * least one byte, so together they cannot outnumber the bytes that follow the counts. The header
 * is read as Assimp reads it: comments ('#'), an optional ST/C/N/4/n prefix before "OFF", an
 * optional "OFF" keyword, the dimension when 'n' is given. */
static bool check_off(ob_model_fs *fs, FILE *f, uint64_t size, uint64_t *estimate)
{
    enum { HEAD = 4096 };
    char head[HEAD + 1] = "";
    size_t n = fread(head, 1, HEAD, f);
    head[n] = '\0';
    const char *p = head, *end = head + n;
    p = off_skip(p, end);
    bool dimension = false;
    if (end - p > 2 && p[0] == 'S' && p[1] == 'T') p += 2;
    if (end - p > 1 && p[0] == 'C') ++p;
    if (end - p > 1 && p[0] == 'N') ++p;
    if (end - p > 1 && p[0] == '4') ++p;
    if (end - p > 1 && p[0] == 'n') {
        dimension = true;
        ++p;
    }
    if (end - p > 3 && !strncmp(p, "OFF", 3)) p += 3;
    uint64_t count[3] = {0, 0, 0}; /* [dimension,] vertices, faces */
    for (int k = dimension ? 0 : 1; k < 3; ++k) {
        p = off_skip(p, end);
        uint64_t v = 0;
        while (p < end && *p >= '0' && *p <= '9') {
            v = v * 10u + (uint64_t)(*p++ - '0');
            /* Assimp reads the counts as 32-bit and would wrap a larger one. */
            if (v > UINT32_MAX) {
                ob_set_error(OB_ERR_MODEL, "%s: OFF header declares a count over 2^32 (corrupt)", fs->model);
                return false;
            }
        }
        count[k] = v;
    }
    /* The edge count and the rest of its line: what follows is the vertex lines. */
    while (p < end && *p != '\n') ++p;
    uint64_t used = (uint64_t)(p - head);
    uint64_t left = size > used ? size - used : 0;
    if (count[1] + count[2] > left) {
        ob_set_error(OB_ERR_MODEL,
                     "%s: OFF header declares %llu vertices and %llu faces, a line each, but only %llu bytes follow (truncated or corrupt)",
                     fs->model, (unsigned long long)count[1], (unsigned long long)count[2], (unsigned long long)left);
        return false;
    }
    /* Up to four arrays of 12-16 bytes per vertex and a 16-byte face with its index array. */
    *estimate = size * OB_BYTES_PER_FILE_BYTE + ob_model_estimate_peak(count[1], 4u * count[2]);
    return true;
}

/* ---- Collada --------------------------------------------------------------------------------- */

/* Assimp 5.2.5's Collada reader sizes a data array by its count attribute (0 when there is none)
 * and then reads each accessor's offset + index * stride from it with no bound: an array whose
 * count is missing or smaller than an accessor of it needs is a read past the array (a SIGSEGV
 * on a null array, found by tests/fuzz/fuzz_model.c; garbage coordinates otherwise). So every
 * <accessor> must fit the array it names; counts and index lists are checked too (below). A text
 * scan, not an XML parser: tags inside comments count too, which can only refuse more. */
typedef struct dae_array {
    const char *id;
    size_t id_len;
    uint64_t count;
} dae_array;

/* Arrays by id (length, then bytes; no id first), for qsort and bsearch. */
static int dae_array_order(const void *a, const void *b)
{
    const dae_array *x = a, *y = b;
    if (!x->id || !y->id) return (x->id != NULL) - (y->id != NULL);
    if (x->id_len != y->id_len) return x->id_len < y->id_len ? -1 : 1;
    return memcmp(x->id, y->id, x->id_len);
}

/* The value of attribute `name` in the tag [tag, end): *val and *len; false when it has none. */
static bool dae_attr(const char *tag, const char *end, const char *name, const char **val, size_t *len)
{
    size_t n = strlen(name);
    for (const char *p = tag + 1; p + n + 2 < end; ++p) {
        if ((p[-1] != ' ' && p[-1] != '\t' && p[-1] != '\n' && p[-1] != '\r') || strncmp(p, name, n) != 0) continue;
        const char *q = p + n;
        while (q < end && (*q == ' ' || *q == '\t')) ++q;
        if (q >= end || *q != '=') continue;
        ++q;
        while (q < end && (*q == ' ' || *q == '\t')) ++q;
        if (q >= end || (*q != '"' && *q != '\'')) continue;
        const char *close = memchr(q + 1, *q, (size_t)(end - q - 1));
        if (!close) return false;
        *val = q + 1;
        *len = (size_t)(close - q - 1);
        return true;
    }
    return false;
}

/* An unsigned attribute as Assimp reads it (0 when missing or not a number); capped at 2^40. */
static uint64_t dae_uint(const char *tag, const char *end, const char *name, uint64_t missing)
{
    const char *v = NULL;
    size_t len = 0;
    if (!dae_attr(tag, end, name, &v, &len)) return missing;
    uint64_t x = 0;
    for (size_t k = 0; k < len && v[k] >= '0' && v[k] <= '9'; ++k)
        if (x < (1ull << 40)) x = x * 10u + (uint64_t)(v[k] - '0');
    return x;
}

static bool check_dae(ob_model_fs *fs, FILE *f, uint64_t size)
{
    static const char *const arrays[] = {"<float_array", "<int_array", "<Name_array", "<IDREF_array", "<bool_array"};
    char *text = malloc(size + 1u);
    if (!text) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: out of memory reading the Collada file", fs->model);
        return false;
    }
    size_t n = fread(text, 1, size, f);
    text[n] = '\0';
    const char *end = text + n;
    dae_array *list = NULL;
    size_t count = 0, cap = 0;
    bool ok = true;
    const char *gt = NULL;
    for (const char *p = memchr(text, '<', n); ok && p; p = memchr(p + 1, '<', (size_t)(end - p - 1))) {
        /* The tag ends at its '>' or at the next '<', whichever comes first (a '<' inside a tag
         * is no XML). The '>' found for an earlier '<' serves while it lies ahead. Both keep the
         * scan linear: a file of many '<' and one '>' would otherwise be read once per '<'. */
        if (!gt || gt < p) gt = memchr(p, '>', (size_t)(end - p));
        if (!gt) break;
        const char *lt = memchr(p + 1, '<', (size_t)(gt - p - 1));
        const char *close = lt ? lt : gt;
        /* Every count sizes a reservation (<triangles count> reserves 3 * count indices per
         * input); each thing counted takes at least a byte of the file. */
        uint64_t declared = dae_uint(p, close, "count", 0);
        if (declared > size) {
            char tag[33] = "";
            size_t t = 0;
            for (; t + 1 < sizeof tag && p + 1 + t < close && p[1 + t] > ' ' && p[1 + t] < 0x7f; ++t) tag[t] = p[1 + t];
            tag[t] = '\0';
            ob_set_error(OB_ERR_MODEL, "%s: Collada <%s> declares a count of %llu; the file's %llu bytes cannot hold that many (corrupt)",
                         fs->model, tag, (unsigned long long)declared, (unsigned long long)size);
            ok = false;
            break;
        }
        /* Index lists: Assimp 5.2.5 reads <p> with strtol10 until the text ends, and a byte that
         * is no digit, sign or space stops the reader without advancing it: an endless loop that
         * grows the index vector until memory runs out (found by fuzz_model). <vcount> and
         * <v> are read the same way. */
        if ((close - p == 2 && p[1] == 'p') || (close - p == 7 && !strncmp(p, "<vcount", 7)) || (close - p == 2 && p[1] == 'v')) {
            for (const char *c = close + 1; c < end && *c != '<'; ++c) {
                if ((*c >= '0' && *c <= '9') || *c == '-' || *c == '+' || *c == ' ' || *c == '\t' || *c == '\r' || *c == '\n')
                    continue;
                ob_set_error(OB_ERR_MODEL, "%s: Collada <%.*s> index list holds byte 0x%02x at offset %llu, not a digit (corrupt)",
                             fs->model, (int)(close - p - 1), p + 1, (unsigned)(unsigned char)*c, (unsigned long long)(c - text));
                ok = false;
                break;
            }
            if (!ok) break;
        }
        for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; ++k) {
            size_t len = strlen(arrays[k]);
            if ((size_t)(close - p) <= len || strncmp(p, arrays[k], len) != 0 || (p[len] != ' ' && p[len] != '\t' && p[len] != '\n' && p[len] != '\r'))
                continue;
            if (count == cap) {
                size_t grown = cap ? 2 * cap : 64;
                dae_array *bigger = realloc(list, grown * sizeof *bigger);
                if (!bigger) {
                    ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: out of memory checking the Collada file", fs->model);
                    ok = false;
                    break;
                }
                list = bigger;
                cap = grown;
            }
            dae_array *a = &list[count++];
            a->id = NULL;
            a->id_len = 0;
            (void)dae_attr(p, close, "id", &a->id, &a->id_len);
            a->count = dae_uint(p, close, "count", 0);
        }
    }
    /* By id, so each accessor finds its array in log time: a linear search per accessor would be
     * quadratic in a file of many arrays and accessors. */
    if (count > 1) qsort(list, count, sizeof *list, dae_array_order);
    gt = NULL;
    for (const char *p = strstr(text, "<accessor"); ok && p; p = strstr(p + 1, "<accessor")) {
        if (!gt || gt < p) gt = memchr(p, '>', (size_t)(end - p)); /* the tag's end, as above */
        if (!gt) break;
        const char *lt = memchr(p + 1, '<', (size_t)(gt - p - 1));
        const char *close = lt ? lt : gt;
        const char *src = NULL;
        size_t src_len = 0;
        if (!dae_attr(p, close, "source", &src, &src_len)) continue;
        if (src_len > 0 && src[0] == '#') {
            ++src;
            --src_len;
        }
        /* Each factor is capped at 2^40 (dae_uint): saturate rather than wrap past 2^64. */
        uint64_t per = dae_uint(p, close, "count", 0), stride = dae_uint(p, close, "stride", 1);
        uint64_t need = stride && per > UINT64_MAX / 2 / stride ? UINT64_MAX / 2 : per * stride;
        need += dae_uint(p, close, "offset", 0);
        const dae_array key = {src, src_len, 0};
        const dae_array *hit = count ? bsearch(&key, list, count, sizeof *list, dae_array_order) : NULL;
        if (!hit) continue;
        /* Two arrays of one id (invalid, but which one Assimp takes is its own affair): the
         * smallest must hold the accessor. */
        size_t k = (size_t)(hit - list), lo = k, hi = k;
        while (lo > 0 && dae_array_order(&list[lo - 1], &key) == 0) --lo;
        while (hi + 1 < count && dae_array_order(&list[hi + 1], &key) == 0) ++hi;
        uint64_t smallest = UINT64_MAX;
        for (k = lo; k <= hi; ++k) smallest = list[k].count < smallest ? list[k].count : smallest;
        if (need > smallest) {
            char id[81] = ""; /* printable ASCII: the message is one line */
            size_t m = 0;
            for (; m < src_len && m < 80; ++m) id[m] = src[m] >= 0x20 && src[m] < 0x7f ? src[m] : '?';
            id[m] = '\0';
            ob_set_error(OB_ERR_MODEL, "%s: Collada accessor of '%s' reads %llu values; the array declares %llu (corrupt)",
                         fs->model, id, (unsigned long long)need, (unsigned long long)smallest);
            ok = false;
        }
    }
    free(list);
    free(text);
    return ok;
}

/* ---- glTF ------------------------------------------------------------------------------------ */

static bool json_u64(const cJSON *obj, const char *key, uint64_t *out, bool required)
{
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!v) {
        *out = 0;
        return !required;
    }
    /* 2^53: the largest count a JSON number holds exactly. */
    if (!cJSON_IsNumber(v) || !(v->valuedouble >= 0.0) || v->valuedouble > 9007199254740992.0 ||
        v->valuedouble != (double)(uint64_t)v->valuedouble)
        return false;
    *out = (uint64_t)v->valuedouble;
    return true;
}

static unsigned gltf_component_size(uint64_t type)
{
    switch (type) {
    case 5120: case 5121: return 1;
    case 5122: case 5123: return 2;
    case 5125: case 5126: return 4;
    default: return 0;
    }
}

static unsigned gltf_type_count(const char *t)
{
    static const struct {
        const char *name;
        unsigned n;
    } types[] = {{"SCALAR", 1}, {"VEC2", 2}, {"VEC3", 3}, {"VEC4", 4}, {"MAT2", 4}, {"MAT3", 9}, {"MAT4", 16}};
    for (size_t k = 0; t && k < sizeof types / sizeof types[0]; ++k)
        if (!strcmp(t, types[k].name)) return types[k].n;
    return 0;
}

/* path = the model's directory (as given) + "/" + uri. */
static bool beside_model(const char *model, const char *uri, char *out, size_t n)
{
    const char *slash = strrchr(model, '/');
    int len = slash ? snprintf(out, n, "%.*s/%s", (int)(slash - model), model, uri) : snprintf(out, n, "%s", uri);
    return len >= 0 && (size_t)len < n;
}

/* Open an external glTF file through the confinement: -1 = refused (error set), 0 = missing
 * (Assimp will say so), 1 = *bytes set. */
static int gltf_external(ob_model_fs *fs, const char *what, int index, const char *uri, uint64_t *bytes)
{
    char path[OB_MODEL_PATH_MAX] = "";
    /* Assimp would join an absolute URI to the model's directory (and miss it); what the author
     * meant is the absolute path, so that is what gets refused. */
    if (!strncmp(uri, "file://", 7)) uri += 7;
    if (uri[0] == '/') snprintf(path, sizeof path, "%s", uri);
    else if (!beside_model(fs->model, uri, path, sizeof path)) {
        ob_set_error(OB_ERR_MODEL, "%s: %s %d has a URI too long", fs->model, what, index);
        return -1;
    }
    FILE *f = ob_model_fs_open(fs, path, uri);
    if (!f) {
        if (!fs->refused[0]) return 0;
        ob_set_error(OB_ERR_MODEL, "%s: %s %d refers to %s", fs->model, what, index, fs->refused);
        return -1;
    }
    struct stat st = {0};
    *bytes = fstat(fileno(f), &st) == 0 ? (uint64_t)st.st_size : 0;
    fclose(f);
    return 1;
}

static bool check_gltf_json(ob_model_fs *fs, const cJSON *root, uint64_t bin_bytes, bool glb, uint64_t size,
                            uint64_t *estimate)
{
    const cJSON *asset = cJSON_GetObjectItemCaseSensitive(root, "asset");
    const cJSON *version = asset ? cJSON_GetObjectItemCaseSensitive(asset, "version") : NULL;
    /* glTF 1 says "1.0", but writers of its day also wrote the number 1 (collada2gltf: assimp's
     * CesiumMilkTruck) or left the version out; its buffers and bufferViews are objects keyed by
     * id, where glTF 2's are arrays. */
    const bool gltf1 = cJSON_IsString(version)   ? version->valuestring[0] == '1'
                       : cJSON_IsNumber(version) ? version->valuedouble >= 1.0 && version->valuedouble < 2.0
                                                 : cJSON_IsObject(cJSON_GetObjectItemCaseSensitive(root, "buffers")) ||
                                                       cJSON_IsObject(cJSON_GetObjectItemCaseSensitive(root, "bufferViews"));
    if (gltf1) {
        /* glTF 1: Assimp's older importer, with its own layout; the generic estimate only. */
        *estimate = size * OB_BYTES_PER_FILE_BYTE;
        return true;
    }
    const cJSON *buffers = cJSON_GetObjectItemCaseSensitive(root, "buffers");
    const cJSON *views = cJSON_GetObjectItemCaseSensitive(root, "bufferViews");
    const cJSON *accessors = cJSON_GetObjectItemCaseSensitive(root, "accessors");
    const cJSON *images = cJSON_GetObjectItemCaseSensitive(root, "images");
    int nb = cJSON_GetArraySize(buffers), nv = cJSON_GetArraySize(views);
    uint64_t *buf_len = calloc((size_t)nb + 1u, sizeof *buf_len);
    uint64_t *view_len = calloc((size_t)nv + 1u, sizeof *view_len);
    bool ok = buf_len && view_len;
    if (!ok) ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: out of memory checking the glTF", fs->model);
    uint64_t est = size;

    for (int i = 0; ok && i < nb; ++i) {
        const cJSON *b = cJSON_GetArrayItem(buffers, i);
        const cJSON *uri = cJSON_GetObjectItemCaseSensitive(b, "uri");
        uint64_t declared = 0, have = 0;
        if (!json_u64(b, "byteLength", &declared, true)) {
            ok = false;
            ob_set_error(OB_ERR_MODEL, "%s: buffer %d has no valid byteLength", fs->model, i);
            break;
        }
        bool known = true;
        if (!cJSON_IsString(uri)) {
            have = glb && i == 0 ? bin_bytes : 0;
        } else if (!strncmp(uri->valuestring, "data:", 5)) {
            const char *comma = strchr(uri->valuestring, ',');
            have = comma ? (uint64_t)strlen(comma + 1) * 3u / 4u : 0;
        } else {
            int r = gltf_external(fs, "buffer", i, uri->valuestring, &have);
            if (r < 0) {
                ok = false;
                break;
            }
            known = r > 0;
        }
        if (known && declared > have) {
            ok = false;
            ob_set_error(OB_ERR_MODEL, "%s: buffer %d declares %llu bytes, but its data holds %llu (truncated or corrupt)",
                         fs->model, i, (unsigned long long)declared, (unsigned long long)have);
            break;
        }
        buf_len[i] = declared;
        est += declared;
    }
    for (int i = 0; ok && i < nv; ++i) {
        const cJSON *v = cJSON_GetArrayItem(views, i);
        uint64_t buffer = 0, offset = 0, length = 0;
        if (!json_u64(v, "buffer", &buffer, true) || buffer >= (uint64_t)nb || !json_u64(v, "byteOffset", &offset, false) ||
            !json_u64(v, "byteLength", &length, true) || offset + length > buf_len[buffer]) {
            ok = false;
            ob_set_error(OB_ERR_MODEL, "%s: bufferView %d lies outside its buffer (or names none)", fs->model, i);
            break;
        }
        view_len[i] = length;
    }
    for (int i = 0; ok && i < cJSON_GetArraySize(accessors); ++i) {
        const cJSON *a = cJSON_GetArrayItem(accessors, i);
        uint64_t count = 0, ctype = 0, view = 0, offset = 0, stride = 0;
        const cJSON *type = cJSON_GetObjectItemCaseSensitive(a, "type");
        unsigned comp = json_u64(a, "componentType", &ctype, true) ? gltf_component_size(ctype) : 0;
        unsigned n = gltf_type_count(cJSON_IsString(type) ? type->valuestring : NULL);
        if (!json_u64(a, "count", &count, true) || comp == 0 || n == 0 || !json_u64(a, "byteOffset", &offset, false)) {
            ok = false;
            ob_set_error(OB_ERR_MODEL, "%s: accessor %d has no valid count, componentType or type", fs->model, i);
            break;
        }
        uint64_t elem = (uint64_t)comp * n;
        const cJSON *has_view = cJSON_GetObjectItemCaseSensitive(a, "bufferView");
        if (has_view) {
            if (!json_u64(a, "bufferView", &view, true) || view >= (uint64_t)nv) {
                ok = false;
                ob_set_error(OB_ERR_MODEL, "%s: accessor %d names a bufferView that does not exist", fs->model, i);
                break;
            }
            const cJSON *v = cJSON_GetArrayItem(views, (int)view);
            if (!json_u64(v, "byteStride", &stride, false) || stride == 0) stride = elem;
            /* count < 2^53 but stride may be up to 2^53 too: compare by division, not product. */
            uint64_t room = view_len[view] > offset ? view_len[view] - offset : 0;
            if (count > 0 && (room < elem || (count - 1u) > (room - elem) / stride)) {
                ok = false;
                ob_set_error(OB_ERR_MODEL,
                             "%s: accessor %d declares %llu elements of %llu bytes, more than bufferView %llu holds (%llu bytes)",
                             fs->model, i, (unsigned long long)count, (unsigned long long)elem, (unsigned long long)view,
                             (unsigned long long)view_len[view]);
                break;
            }
        }
        /* Without a bufferView the accessor is zeros that Assimp allocates: only the limit
         * bounds it. 8: Assimp's copy, post-processing's and ours, at float size. */
        if (count > (UINT64_MAX / 64u) / elem) count = (UINT64_MAX / 64u) / elem;
        est += 8u * count * elem;
    }
    for (int i = 0; ok && i < cJSON_GetArraySize(images); ++i) {
        const cJSON *uri = cJSON_GetObjectItemCaseSensitive(cJSON_GetArrayItem(images, i), "uri");
        uint64_t bytes = 0;
        if (cJSON_IsString(uri) && strncmp(uri->valuestring, "data:", 5) != 0 &&
            gltf_external(fs, "image", i, uri->valuestring, &bytes) < 0)
            ok = false;
    }
    free(buf_len);
    free(view_len);
    *estimate = est;
    return ok;
}

static uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static bool check_gltf(ob_model_fs *fs, FILE *f, uint64_t size, bool glb, uint64_t *estimate)
{
    uint64_t json_at = 0, json_len = size, bin_len = 0;
    if (glb) {
        unsigned char h[20] = {0};
        if (size < 20 || fread(h, 1, 20, f) != 20 || memcmp(h, "glTF", 4) != 0) return true; /* Assimp says */
        uint32_t version = le32(h + 4), length = le32(h + 8);
        if (version != 2) {
            /* Assimp 5.2 reads glTF 1 only as .gltf text; its answer here would be "No suitable
             * reader found". */
            ob_set_error(OB_ERR_MODEL, "%s: a glTF %u binary (.glb version %u); only glTF 2 .glb files can be read",
                         fs->model, version, version);
            return false;
        }
        json_len = le32(h + 12);
        if (length > size || le32(h + 16) != 0x4E4F534Au || json_len > (uint64_t)length - 20u) {
            ob_set_error(OB_ERR_MODEL, "%s: glb header declares %u bytes and a %llu-byte JSON chunk; the file has %llu (truncated or corrupt)",
                         fs->model, length, (unsigned long long)json_len, (unsigned long long)size);
            return false;
        }
        json_at = 20;
        uint64_t bin_at = 20u + ((json_len + 3u) & ~3ull);
        unsigned char c[8] = {0};
        if (bin_at + 8u <= length && fseeko(f, (off_t)bin_at, SEEK_SET) == 0 && fread(c, 1, 8, f) == 8 &&
            le32(c + 4) == 0x004E4942u) {
            bin_len = le32(c);
            if (bin_len > (uint64_t)length - bin_at - 8u) {
                ob_set_error(OB_ERR_MODEL, "%s: glb BIN chunk declares %llu bytes; only %llu follow (truncated or corrupt)",
                             fs->model, (unsigned long long)bin_len, (unsigned long long)(length - bin_at - 8u));
                return false;
            }
        }
    }
    char *text = malloc(json_len + 1u);
    if (!text) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: out of memory reading the glTF JSON", fs->model);
        return false;
    }
    bool read = fseeko(f, (off_t)json_at, SEEK_SET) == 0 && fread(text, 1, json_len, f) == json_len;
    text[read ? json_len : 0] = '\0';
    cJSON *root = read ? cJSON_ParseWithLength(text, json_len) : NULL;
    free(text);
    bool ok = true;
    if (root) ok = check_gltf_json(fs, root, bin_len, glb, size, estimate);
    else *estimate = size * OB_BYTES_PER_FILE_BYTE; /* not JSON: Assimp's message names the fault */
    cJSON_Delete(root);
    return ok;
}

/* ---- ASCII FBX ------------------------------------------------------------------------------- */

/* Assimp 5.2.5 decodes an ASCII FBX's embedded texture (a Video's "Content", base64 strings) into
 * a buffer sized from the strings' lengths; when the decoded length differs (a byte outside the
 * alphabet, '=' inside a string) it deletes the buffer without clearing its pointer and the
 * Video's destructor deletes it again: a 177-byte file aborts the process (double free), and a
 * padded string whose length is not a multiple of 4 writes a byte past it. Every token of a
 * "Content" element must therefore be a quoted string of the base64 alphabet, padded (one or two
 * '=' at its end) only at a length that is a multiple of 4: for those both lengths agree
 * (unpadded strings of any length too, as the SDK may split the text). The scan follows Assimp's ASCII tokenizer (FBXTokenizer.cpp): ';' comments to the end of
 * the line, strings in double quotes (across lines), a token right before ':' is a key, '{' and '}' end an element, and the text ends at its first NUL. Binary FBX
 * ("Kaydara FBX Binary") bounds its arrays in its own tokenizer. */
static bool fbx_base64_char(int c)
{
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '+' || c == '/';
}

static bool fbx_is_blank(int c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

static bool check_fbx_ascii(ob_model_fs *fs, FILE *f)
{
    char token[16] = ""; /* the unquoted token being read, cut: only "Content" matters */
    size_t token_len = 0;
    bool in_token = false, in_content = false, comment = false;
    unsigned line = 1, bad_line = 0;
    int c = 0;
    while (!bad_line && (c = getc(f)) != EOF && c != '\0') {
        if (c == '\n') {
            ++line;
            comment = false;
        }
        if (comment) continue;
        if (c == '"') {
            /* A string token: in a Content element it is checked as base64. */
            if (in_token) break; /* Assimp refuses the file: "unexpected double-quote" */
            unsigned start = line;
            size_t len = 0, pad = 0;
            bool ok = true;
            while ((c = getc(f)) != EOF && c != '\0' && c != '"') {
                if (c == '\n') ++line;
                if (c == '=') ++pad;
                else if (pad > 0 || !fbx_base64_char(c)) ok = false;
                ++len;
            }
            if (c != '"') break; /* unterminated: Assimp reads no token from it */
            if (in_content && (!ok || (pad > 0 && (pad > 2 || len % 4 != 0)))) bad_line = start;
            continue;
        }
        if (c == ';' || c == '{' || c == '}' || c == ',' || c == ':' || fbx_is_blank(c)) {
            /* A key is a token right before ':' (Assimp refuses "Content :" as an unexpected colon). */
            if (in_token && c == ':') in_content = token_len == 7 && !memcmp(token, "Content", 7);
            else if (in_token && in_content) bad_line = line; /* an unquoted token of Content */
            in_token = false;
            token_len = 0;
            if (c == '{' || c == '}') in_content = false;
            if (c == ';') comment = true;
            continue;
        }
        if (!in_token) in_token = true;
        if (token_len < sizeof token) token[token_len] = (char)c;
        ++token_len;
    }
    if (bad_line) {
        ob_set_error(OB_ERR_MODEL, "%s: line %u: FBX embedded content (\"Content\") is not base64 text; refused: "
                     "Assimp would free the texture twice", fs->model, bad_line);
        return false;
    }
    return true;
}

/* Whether Assimp may read the file as an ASCII FBX: its extension, or "fbx" in any case among the
 * first 200 bytes (NULs dropped), which is how Assimp's FBX importer claims a file of any name. */
static bool maybe_ascii_fbx(FILE *f, bool by_ext)
{
    char head[201] = "";
    size_t got = fread(head, 1, 200, f), n = 0;
    rewind(f);
    if (got >= 18 && !memcmp(head, "Kaydara FBX Binary", 18)) return false;
    if (by_ext) return true;
    for (size_t i = 0; i < got; ++i)
        if (head[i] != '\0') head[n++] = (char)tolower((unsigned char)head[i]);
    head[n] = '\0';
    return strstr(head, "fbx") != NULL;
}

/* ---- entry ----------------------------------------------------------------------------------- */

static bool has_ext(const char *path, const char *ext)
{
    const char *dot = strrchr(path, '.');
    const char *slash = strrchr(path, '/');
    return dot && (!slash || dot > slash) && !strcasecmp(dot, ext);
}

bool ob_model_precheck(ob_model_fs *fs, uint64_t max_memory)
{
    FILE *f = ob_model_fs_open(fs, fs->model, NULL);
    if (!f) {
        if (fs->refused[0]) ob_set_error(OB_ERR_IO, "%s: cannot read the model: %s", fs->model, fs->refused);
        else ob_set_error(OB_ERR_IO, "%s: cannot open the model: %s", fs->model, strerror(errno));
        return false;
    }
    struct stat st = {0};
    uint64_t size = fstat(fileno(f), &st) == 0 ? (uint64_t)st.st_size : 0;
    char magic[4] = {0};
    size_t got = fread(magic, 1, 4, f);
    rewind(f);
    uint64_t estimate = size * OB_BYTES_PER_FILE_BYTE;
    bool ok = true;
    /* First: Assimp picks its Quake 3 importer by these extensions before it looks at content. */
    if (has_ext(fs->model, ".pk3") || has_ext(fs->model, ".bsp")) ok = ob_q3_check(fs->model, f, size, max_memory, &estimate);
    else if ((got >= 3 && !memcmp(magic, "ply", 3)) || has_ext(fs->model, ".ply")) ok = check_ply(fs, f, size, &estimate);
    else if (got == 4 && !memcmp(magic, "glTF", 4)) ok = check_gltf(fs, f, size, true, &estimate);
    else if (has_ext(fs->model, ".gltf")) ok = check_gltf(fs, f, size, false, &estimate);
    else if (has_ext(fs->model, ".obj")) ok = check_obj(f, size, &estimate);
    else if (has_ext(fs->model, ".off")) ok = check_off(fs, f, size, &estimate);
    else if (has_ext(fs->model, ".dae")) ok = check_dae(fs, f, size);
    /* Any file Assimp may read as ASCII FBX, whatever its other checks were. */
    if (ok) {
        rewind(f);
        if (maybe_ascii_fbx(f, has_ext(fs->model, ".fbx"))) ok = check_fbx_ascii(fs, f);
    }
    fclose(f);
    if (ok && estimate > max_memory) {
        char a[32] = "", b[32] = "";
        ob_set_error(OB_ERR_MODEL, "%s: importing it would take about %s, more than the limit of %s (--max-memory)", fs->model,
                     human(estimate, a, sizeof a), human(max_memory, b, sizeof b));
        return false;
    }
    return ok;
}
