/* #include expansion of the GLSL sources (see shader_expand.h). Errors go back as a message, not
 * exit(): the library uses this at run time for ob_set_shader_directory. */
#include "gpu/shader_expand.h"

#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_DEPTH 16

typedef struct text_buf {
    char *data;
    size_t len, cap;
    bool failed; /* out of memory: later puts are dropped, the caller reports it once */
} text_buf;

typedef struct expander {
    const char *dir;
    const char *const *files;
    int file_count;
    char *seen; /* per file id: already expanded into this shader (include-once) */
    text_buf out;
    char *err;
    size_t err_len;
} expander;

static void put(text_buf *b, const char *s, size_t n)
{
    if (b->failed) return;
    if (b->len + n + 1 > b->cap) {
        size_t cap = (b->len + n + 1) * 2;
        char *grown = realloc(b->data, cap);
        if (!grown) {
            b->failed = true;
            return;
        }
        b->data = grown;
        b->cap = cap;
    }
    memcpy(b->data + b->len, s, n);
    b->len += n;
    b->data[b->len] = '\0';
}

static void put_line_marker(text_buf *b, int line, int id)
{
    char tmp[64] = "";
    int n = snprintf(tmp, sizeof tmp, "#line %d\n", id * OB_SHADER_LINE_STRIDE + line);
    put(b, tmp, (size_t)n);
}

static bool fail(expander *e, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->err, e->err_len, fmt, ap);
    va_end(ap);
    return false;
}

static int file_id(const expander *e, const char *name)
{
    for (int i = 0; i < e->file_count; ++i)
        if (strcmp(e->files[i], name) == 0) return i + 1;
    return 0;
}

static char *slurp(const char *dir, const char *name)
{
    char path[4096] = "";
    int n = snprintf(path, sizeof path, "%s/%s", dir, name);
    if (n < 0 || (size_t)n >= sizeof path) return NULL;
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    long size = -1;
    if (fseek(f, 0, SEEK_END) == 0) size = ftell(f);
    char *s = size >= 0 && fseek(f, 0, SEEK_SET) == 0 ? malloc((size_t)size + 1) : NULL;
    if (!s || fread(s, 1, (size_t)size, f) != (size_t)size) {
        fclose(f);
        free(s);
        return NULL;
    }
    s[size] = '\0';
    fclose(f);
    return s;
}

static bool expand(expander *e, const char *name, int depth, const char *from, int from_line)
{
    int id = file_id(e, name);
    if (!id) {
        if (depth == 0) return fail(e, "shaders/%s: error: not one of this build's shader files", name);
        return fail(e, "shaders/%s:%d: error: #include \"%s\" is not a shader file", from, from_line, name);
    }
    if (e->seen[id]) return true;
    e->seen[id] = 1;
    if (depth > MAX_DEPTH) return fail(e, "shaders/%s: error: includes nest too deep", name);
    char *text = slurp(e->dir, name);
    if (!text) return fail(e, "shaders/%s: error: cannot read %s/%s", name, e->dir, name);
    int line = 1;
    bool ok = true;
    /* The #version line must stay first: top-level files re-sync with #line right after it. */
    if (depth > 0) put_line_marker(&e->out, 1, id);
    for (char *p = text; *p && ok;) {
        char *eol = strchr(p, '\n');
        size_t n = eol ? (size_t)(eol - p) : strlen(p);
        const char *q = p;
        while (*q == ' ' || *q == '\t') ++q;
        if (strncmp(q, "#include", 8) == 0) {
            const char *a = strchr(q, '"');
            const char *b = a ? strchr(a + 1, '"') : NULL;
            if (!a || !b || b > p + n) {
                ok = fail(e, "shaders/%s:%d: error: malformed #include", name, line);
                break;
            }
            char inc[256] = "";
            snprintf(inc, sizeof inc, "%.*s", (int)(b - a - 1), a + 1);
            ok = expand(e, inc, depth + 1, name, line);
            put_line_marker(&e->out, line + 1, id);
        } else {
            put(&e->out, p, n);
            put(&e->out, "\n", 1);
            if (depth == 0 && line == 1 && strncmp(q, "#version", 8) == 0) put_line_marker(&e->out, 2, id);
        }
        if (ok && ++line >= OB_SHADER_LINE_STRIDE)
            ok = fail(e, "shaders/%s: error: more than %d lines", name, OB_SHADER_LINE_STRIDE - 1);
        p = eol ? eol + 1 : p + n;
    }
    free(text);
    return ok;
}

char *ob_shader_expand(const char *dir, const char *const *files, int file_count, const char *name, char *err,
                       size_t err_len)
{
    char scratch[8] = "";
    if (!err || err_len == 0) {
        err = scratch;
        err_len = sizeof scratch;
    }
    err[0] = '\0';
    if (!dir || !files || file_count < 0 || !name) {
        snprintf(err, err_len, "shaders: error: bad arguments to the include expander");
        return NULL;
    }
    expander e = {.dir = dir, .files = files, .file_count = file_count, .err = err, .err_len = err_len};
    e.seen = calloc((size_t)file_count + 1, 1);
    if (!e.seen) {
        snprintf(err, err_len, "shaders/%s: error: out of memory", name);
        return NULL;
    }
    put(&e.out, "", 0);
    bool ok = expand(&e, name, 0, name, 0);
    free(e.seen);
    if (ok && e.out.failed) ok = fail(&e, "shaders/%s: error: out of memory", name);
    if (!ok) {
        free(e.out.data);
        return NULL;
    }
    return e.out.data;
}
