/* All-or-nothing outputs (outputs.h): checked when added, written to temporary files beside their
 * targets, renamed only when every one of them was written. */
/* renameat2 and RENAME_EXCHANGE come with _GNU_SOURCE, which the build defines. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "outputs.h"

/* JPEG quality: 90 keeps the AO's smooth gradients free of visible blocking. */
enum { JPG_QUALITY = 90 };

/* ---- an interrupted run leaves nothing behind either ----------------------------------------
 * Ctrl-C (SIGINT), SIGTERM or SIGHUP during a long render or report: the temporary files and
 * directories of the sets in use are removed, then the signal is raised again with its default
 * action (the shell sees the usual 130/143). The handler uses only async-signal-safe calls:
 * unlinkat, openat, getdents64, close. A signal the process ignores (nohup) stays ignored. */
enum { MAX_ACTIVE = 4, MAX_DEPTH = 8 };
static cli_outputs *volatile active[MAX_ACTIVE];

static void unlink_tree_at(int parent, const char *name, int depth)
{
    if (unlinkat(parent, name, 0) == 0 || depth > MAX_DEPTH) return;
    int fd = openat(parent, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW);
    if (fd < 0) return;
    /* Entries removed while the directory is read may shift the ones not read yet: read it
     * again from the start until it is empty (a report tree is two levels of a few hundred
     * files). */
    for (int pass = 0; pass < 8 && unlinkat(parent, name, AT_REMOVEDIR) != 0; ++pass) {
        lseek(fd, 0, SEEK_SET);
        char buf[4096];
        ssize_t n = 0;
        while ((n = getdents64(fd, buf, sizeof buf)) > 0)
            for (ssize_t off = 0; off < n;) {
                const struct dirent64 *e = (const struct dirent64 *)(buf + off);
                off += e->d_reclen;
                if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0) unlink_tree_at(fd, e->d_name, depth + 1);
            }
    }
    close(fd);
}

static void on_signal(int sig)
{
    for (int k = 0; k < MAX_ACTIVE; ++k) {
        cli_outputs *s = active[k];
        for (int i = 0; s && i < s->count; ++i)
            if (s->items[i].tmp) unlink_tree_at(AT_FDCWD, s->items[i].tmp, 0);
    }
    signal(sig, SIG_DFL);
    raise(sig);
}

static void watch(cli_outputs *s)
{
    static bool installed = false;
    if (!installed) {
        installed = true;
        const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
        for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; ++i) {
            struct sigaction old;
            if (sigaction(sigs[i], NULL, &old) == 0 && old.sa_handler == SIG_DFL) {
                struct sigaction sa;
                memset(&sa, 0, sizeof sa);
                sa.sa_handler = on_signal;
                sigemptyset(&sa.sa_mask);
                sigaction(sigs[i], &sa, NULL);
            }
        }
    }
    for (int k = 0; k < MAX_ACTIVE; ++k)
        if (active[k] == s) return;
    for (int k = 0; k < MAX_ACTIVE; ++k)
        if (!active[k]) {
            active[k] = s;
            return;
        }
}

static void unwatch(cli_outputs *s)
{
    for (int k = 0; k < MAX_ACTIVE; ++k)
        if (active[k] == s) active[k] = NULL;
}

unsigned cli_format_of(const char *path)
{
    const char *dot = strrchr(path, '.'), *slash = strrchr(path, '/');
    if (!dot || (slash && dot < slash)) return 0;
    if (!strcasecmp(dot, ".png")) return CLI_FMT_PNG;
    if (!strcasecmp(dot, ".jpg") || !strcasecmp(dot, ".jpeg")) return CLI_FMT_JPG;
    if (!strcasecmp(dot, ".pfm")) return CLI_FMT_PFM;
    return 0;
}

static void format_list(unsigned formats, char *out, size_t n)
{
    static const struct { unsigned f; const char *names; } all[] = {
        {CLI_FMT_PNG, ".png"}, {CLI_FMT_JPG, ".jpg (or .jpeg)"}, {CLI_FMT_PFM, ".pfm"}};
    size_t len = 0;
    out[0] = '\0';
    for (size_t i = 0; i < sizeof all / sizeof all[0]; ++i)
        if ((formats & all[i].f) && len < n)
            len += (size_t)snprintf(out + len, n - len, "%s%s", len ? ", " : "", all[i].names);
}

static const char *kind_of(mode_t m)
{
    if (S_ISDIR(m)) return "a directory";
    if (S_ISFIFO(m)) return "a FIFO";
    if (S_ISCHR(m)) return "a character device";
    if (S_ISBLK(m)) return "a block device";
    if (S_ISSOCK(m)) return "a socket";
    if (S_ISREG(m)) return "a regular file";
    return "not a regular file";
}

/* A report directory is replaced only when it is empty or an earlier report: replacing one that
 * holds anything else (a mistyped --report $HOME) would delete it. */
static bool replaceable_dir(const char *path)
{
    char probe[4200];
    for (int k = 0; k < 2; ++k) {
        snprintf(probe, sizeof probe, "%s/%s", path, k ? "results.json" : "index.html");
        if (access(probe, F_OK) == 0) return true;
    }
    DIR *d = opendir(path);
    if (!d) return false;
    bool empty = true;
    for (struct dirent *e; empty && (e = readdir(d)) != NULL;)
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) empty = false;
    closedir(d);
    return empty;
}

/* Whether the directory of path takes a new file (or directory) of a name as long as the
 * temporary ones: made and removed again. access() alone misses read-only file systems and
 * names too long for the directory. */
static bool dir_takes(const char *path, bool dir, int *err)
{
    /* As long as the longest name written: the library's atomic writers put their own temporary
     * file (".tmp-XXXXXX") beside ours, so a name that fits only once would fail after the render. */
    char tmp[4200];
    if (snprintf(tmp, sizeof tmp, "%s.tmp-000000.tmp-XXXXXX", path) >= (int)sizeof tmp) {
        *err = ENAMETOOLONG;
        return false;
    }
    /* The probe exists for microseconds, before the outputs are watched (watch): a SIGINT, SIGTERM
     * or SIGHUP then would kill the process with the probe left behind (test_hostile_outputs.sh
     * caught one). Held back until it is gone, the signal then takes its course. */
    sigset_t term, old;
    sigemptyset(&term);
    sigaddset(&term, SIGINT);
    sigaddset(&term, SIGTERM);
    sigaddset(&term, SIGHUP);
    sigprocmask(SIG_BLOCK, &term, &old);
    bool made = false;
    if (dir) {
        made = mkdtemp(tmp) != NULL;
        if (made) rmdir(tmp);
    } else {
        int fd = mkstemp(tmp);
        made = fd >= 0;
        if (made) {
            close(fd);
            unlink(tmp);
        }
    }
    if (!made) *err = errno;
    sigprocmask(SIG_SETMASK, &old, NULL);
    return made;
}

int cli_outputs_add(cli_outputs *s, const char *option, const char *path, unsigned formats, int *index)
{
    if (!path || !*path) return cli_fail(EXIT_USAGE, "%s: expected a %s name, got ''", option,
                                         formats & CLI_FMT_DIR ? "directory" : "file");
    size_t len = strlen(path);
    /* A directory without its trailing '/': its temporary twin goes beside it, not into it. */
    while ((formats & CLI_FMT_DIR) && len > 1 && path[len - 1] == '/') --len;
    char *p = strndup(path, len);
    if (!p) return cli_fail(EXIT_RUNTIME, "out of memory");
    int code = EXIT_OK;
    struct stat st;
    if (code == EXIT_OK && stat(p, &st) == 0) {
        /* stat follows a link: a link to /dev/null is refused like /dev/null. */
        if (formats & CLI_FMT_DIR) {
            if (!S_ISDIR(st.st_mode))
                code = cli_fail(EXIT_OUTPUT, "%s %s: exists and is %s, not a directory", option, p, kind_of(st.st_mode));
            else if (!replaceable_dir(p))
                code = cli_fail(EXIT_OUTPUT, "%s %s: exists and is not an earlier report (no index.html or results.json) "
                                "nor empty: it would be replaced as a whole, so give a new directory", option, p);
        } else if (!S_ISREG(st.st_mode)) {
            code = cli_fail(EXIT_OUTPUT, "%s %s: exists and is %s, not a regular file: refusing to replace it", option, p,
                            kind_of(st.st_mode));
        }
    }
    for (int i = 0; i < s->count && code == EXIT_OK; ++i)
        if (!strcmp(s->items[i].path, p))
            code = cli_fail(EXIT_USAGE, "%s and %s both name %s", s->items[i].option, option, p);
    const char *base = strrchr(p, '/');
    base = base ? base + 1 : p;
    if (code == EXIT_OK && (!strcmp(base, ".") || !strcmp(base, "..") || !strcmp(p, "/")))
        code = cli_fail(EXIT_USAGE, "%s %s: expected a new or replaceable %s, not the current, parent or root directory",
                        option, p, formats & CLI_FMT_DIR ? "directory" : "file");
    unsigned format = formats & (CLI_FMT_TEXT | CLI_FMT_DIR);
    if (code == EXIT_OK && (formats & CLI_FMT_IMAGE)) {
        format = cli_format_of(p) & formats;
        if (!format) {
            char list[96];
            format_list(formats, list, sizeof list);
            const char *dot = strrchr(p, '.'), *slash = strrchr(p, '/');
            bool has_ext = dot && !(slash && dot < slash);
            code = cli_fail(EXIT_USAGE, "%s %s: %s%s%s; the format follows the extension: %s", option, p,
                            has_ext ? "unsupported extension '" : "no extension", has_ext ? dot : "", has_ext ? "'" : "",
                            list);
        }
    }
    int err = 0;
    if (code == EXIT_OK && !dir_takes(p, formats & CLI_FMT_DIR, &err))
        code = cli_fail(EXIT_OUTPUT, "%s %s: cannot write a new %s in its directory: %s", option, p,
                        formats & CLI_FMT_DIR ? "directory" : "file", strerror(err));
    if (code == EXIT_OK && s->count == s->cap) {
        int cap = s->cap ? 2 * s->cap : 8;
        unwatch(s); /* the handler must not read the items while realloc moves them */
        cli_output *items = realloc(s->items, (size_t)cap * sizeof *items);
        if (!items) code = cli_fail(EXIT_RUNTIME, "out of memory");
        else {
            s->items = items;
            s->cap = cap;
        }
    }
    char *opt = code == EXIT_OK ? strdup(option) : NULL;
    if (code == EXIT_OK && !opt) code = cli_fail(EXIT_RUNTIME, "out of memory");
    if (code != EXIT_OK) {
        if (s->count) watch(s);
        free(p);
        return code;
    }
    s->items[s->count] = (cli_output){.option = opt, .path = p, .tmp = NULL, .format = format};
    *index = s->count++;
    watch(s);
    return EXIT_OK;
}

/* The output's temporary file, made (empty) on first use: the library's writers replace it
 * atomically. NULL with the line printed. */
/* "PATH.tmp-XXXXXX", the template mkstemp/mkdtemp fill in; NULL with the line printed. */
static char *tmp_template(const cli_output *o)
{
    size_t n = strlen(o->path) + 16;
    char *t = malloc(n);
    if (!t) {
        cli_fail(EXIT_RUNTIME, "out of memory");
        return NULL;
    }
    snprintf(t, n, "%s.tmp-XXXXXX", o->path);
    return t;
}

static const char *tmp_file(cli_outputs *s, int index)
{
    cli_output *o = &s->items[index];
    if (o->tmp) return o->tmp;
    char *t = tmp_template(o);
    if (!t) return NULL;
    int fd = mkstemp(t);
    if (fd < 0) {
        cli_fail(EXIT_OUTPUT, "%s %s: cannot write it: %s", o->option, o->path, strerror(errno));
        free(t);
        return NULL;
    }
    close(fd);
    o->tmp = t;
    return t;
}

static int write_failed(const cli_output *o)
{
    const char *msg = NULL;
    ob_get_error(&msg);
    /* The library names the temporary file ("cannot write X.tmp-abc: why"): the reason alone. */
    const char *why = msg && *msg ? msg : "write failed";
    if (!strncmp(why, "cannot write ", 13) && strstr(why, ": ")) why = strstr(why, ": ") + 2;
    return cli_fail(EXIT_OUTPUT, "%s %s: cannot write it: %s", o->option, o->path, why);
}

int cli_outputs_write_rgb8(cli_outputs *s, int index, int w, int h, int channels, const uint8_t *px)
{
    const cli_output *o = &s->items[index];
    const char *t = tmp_file(s, index);
    if (!t) return EXIT_OUTPUT;
    ob_error e = OB_OK;
    if (o->format == CLI_FMT_PNG) e = ob_write_png(t, w, h, channels, px);
    else if (o->format == CLI_FMT_JPG) e = ob_write_jpg(t, w, h, channels, px, JPG_QUALITY);
    else {
        /* PFM: grey or RGB floats, bottom row first. */
        const int c = channels == 1 ? 1 : 3;
        float *f = malloc((size_t)w * (size_t)h * (size_t)c * sizeof(float));
        if (!f) return cli_fail(EXIT_RUNTIME, "out of memory writing %s", o->path);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int k = 0; k < c; ++k)
                    f[((size_t)(h - 1 - y) * (size_t)w + (size_t)x) * (size_t)c + (size_t)k] =
                        (float)px[((size_t)y * (size_t)w + (size_t)x) * (size_t)channels + (size_t)k] / 255.0f;
        e = ob_write_pfm(t, w, h, c, f);
        free(f);
    }
    return e == OB_OK ? EXIT_OK : write_failed(o);
}

int cli_outputs_write_f32(cli_outputs *s, int index, int w, int h, int channels, const float *px)
{
    const cli_output *o = &s->items[index];
    const char *t = tmp_file(s, index);
    if (!t) return EXIT_OUTPUT;
    if (o->format == CLI_FMT_PFM) return ob_write_pfm(t, w, h, channels, px) == OB_OK ? EXIT_OK : write_failed(o);
    uint8_t *b = malloc((size_t)w * (size_t)h * (size_t)channels);
    if (!b) return cli_fail(EXIT_RUNTIME, "out of memory writing %s", o->path);
    for (int y = 0; y < h; ++y)
        for (size_t x = 0; x < (size_t)w * (size_t)channels; ++x) {
            float v = px[(size_t)(h - 1 - y) * (size_t)w * (size_t)channels + x];
            v = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; /* NaN -> 0 */
            b[(size_t)y * (size_t)w * (size_t)channels + x] = (uint8_t)lrintf(v * 255.0f);
        }
    ob_error e = o->format == CLI_FMT_PNG ? ob_write_png(t, w, h, channels, b)
                                          : ob_write_jpg(t, w, h, channels, b, JPG_QUALITY);
    free(b);
    return e == OB_OK ? EXIT_OK : write_failed(o);
}

int cli_outputs_write_text(cli_outputs *s, int index, const char *text)
{
    const cli_output *o = &s->items[index];
    const char *t = tmp_file(s, index);
    if (!t) return EXIT_OUTPUT;
    char *valid = cli_utf8_valid(text);
    if (!valid) return cli_fail(EXIT_RUNTIME, "out of memory writing %s", o->path);
    ob_error e = ob_write_text(t, valid);
    free(valid);
    return e == OB_OK ? EXIT_OK : write_failed(o);
}

const char *cli_outputs_dir(cli_outputs *s, int index)
{
    cli_output *o = &s->items[index];
    if (o->tmp) return o->tmp;
    char *t = tmp_template(o);
    if (!t) return NULL;
    if (!mkdtemp(t)) {
        cli_fail(EXIT_OUTPUT, "%s %s: cannot create a directory beside it: %s", o->option, o->path, strerror(errno));
        free(t);
        return NULL;
    }
    /* mkdtemp makes it 0700; a report is as readable as any directory the user makes. */
    mode_t mask = umask(0);
    umask(mask);
    chmod(t, 0777 & ~mask);
    o->tmp = t;
    return t;
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st;
    (void)flag;
    (void)ftw;
    remove(path);
    return 0;
}

/* Depth first, links not followed: only what is inside the tree goes. */
static void remove_tree(const char *path)
{
    nftw(path, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

static void clear(cli_outputs *s)
{
    unwatch(s); /* before the items go: the handler reads them */
    for (int i = 0; i < s->count; ++i) {
        free(s->items[i].option);
        free(s->items[i].path);
        free(s->items[i].tmp);
    }
    free(s->items);
    *s = (cli_outputs){0};
}

void cli_outputs_abort(cli_outputs *s)
{
    for (int i = 0; i < s->count; ++i)
        if (s->items[i].tmp) {
            if (s->items[i].format == CLI_FMT_DIR) remove_tree(s->items[i].tmp);
            else unlink(s->items[i].tmp);
        }
    clear(s);
}

int cli_outputs_commit(cli_outputs *s)
{
    /* Renames in one directory do not fail for want of space; what can still fail (the target
     * made a directory since the check) fails before any later output is renamed, and the
     * temporary files of those are removed. */
    int code = EXIT_OK;
    for (int i = 0; i < s->count; ++i) {
        cli_output *o = &s->items[i];
        if (!o->tmp) continue; /* never written: a failed run does not get here */
        if (code != EXIT_OK) {
            if (o->format == CLI_FMT_DIR) remove_tree(o->tmp);
            else unlink(o->tmp);
            continue;
        }
        struct stat st;
        if (o->format == CLI_FMT_DIR && stat(o->path, &st) == 0 && S_ISDIR(st.st_mode)) {
            /* Swap the new report with the old one, then remove the old one from the temporary
             * name: the report's name is never missing, nor ever half of each. */
            if (renameat2(AT_FDCWD, o->tmp, AT_FDCWD, o->path, RENAME_EXCHANGE) != 0) {
                code = cli_fail(EXIT_OUTPUT, "%s %s: cannot replace it: %s", o->option, o->path, strerror(errno));
                remove_tree(o->tmp);
                continue;
            }
            remove_tree(o->tmp);
        } else if (rename(o->tmp, o->path) != 0) {
            code = cli_fail(EXIT_OUTPUT, "%s %s: cannot write it: %s", o->option, o->path, strerror(errno));
            if (o->format == CLI_FMT_DIR) remove_tree(o->tmp);
            else unlink(o->tmp);
        }
    }
    clear(s);
    return code;
}

int cli_outputs_finish(cli_outputs *s, int code)
{
    if (code == EXIT_OK) return cli_outputs_commit(s);
    cli_outputs_abort(s);
    return code;
}

/* Length of the well-formed UTF-8 sequence at s (RFC 3629, table 3-7 of the Unicode standard),
 * or 0. */
static int sequence_length(const unsigned char *s)
{
    unsigned char c = s[0];
    if (c < 0x80) return 1;
    int n = 0;
    unsigned char lo = 0x80, hi = 0xBF;
    if (c >= 0xC2 && c <= 0xDF) n = 2;
    else if (c >= 0xE0 && c <= 0xEF) {
        n = 3;
        if (c == 0xE0) lo = 0xA0; /* overlong */
        if (c == 0xED) hi = 0x9F; /* surrogates */
    } else if (c >= 0xF0 && c <= 0xF4) {
        n = 4;
        if (c == 0xF0) lo = 0x90; /* overlong */
        if (c == 0xF4) hi = 0x8F; /* past U+10FFFF */
    } else {
        return 0;
    }
    if (s[1] < lo || s[1] > hi) return 0;
    for (int k = 2; k < n; ++k)
        if (s[k] < 0x80 || s[k] > 0xBF) return 0;
    return n;
}

char *cli_utf8_valid(const char *text)
{
    const unsigned char *s = (const unsigned char *)text;
    size_t len = strlen(text);
    /* Each bad byte (1) becomes 3 bytes at most. */
    char *out = malloc(3 * len + 1);
    if (!out) return NULL;
    size_t k = 0;
    while (*s) {
        int n = sequence_length(s);
        if (n == 0) {
            memcpy(out + k, "\xEF\xBF\xBD", 3);
            k += 3;
            ++s;
        } else {
            memcpy(out + k, s, (size_t)n);
            k += (size_t)n;
            s += n;
        }
    }
    out[k] = '\0';
    return out;
}
