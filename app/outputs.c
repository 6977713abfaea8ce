/* All-or-nothing outputs (outputs.h): checked when added, each written into a directory of its
 * own beside its target, and put in place by one commit that replaces every one of them or none. */
/* renameat2, RENAME_EXCHANGE and RENAME_NOREPLACE come with _GNU_SOURCE, which the build defines. */
#include <cjson/cJSON.h>
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <ftw.h>
#include <limits.h>
#include <math.h>
#include <signal.h>
#include <stdatomic.h>
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

/* What an output's directory (PATH.tmp-XXXXXX) holds: the new file, the library writer's own
 * temporary file while it writes it (the writers are atomic: NEW.tmp-XXXXXX, then a rename), and
 * at the commit a hard link to the old file. Short names, so that the directory's name is the
 * only one that grows with PATH. */
#define STAGE_SUFFIX ".tmp-XXXXXX"
#define NEW_LEAF "new"
#define OLD_LEAF "old"
/* The longest path under a stage: "/new.tmp-XXXXXX". */
#define STAGE_INNER "/" NEW_LEAF ".tmp-XXXXXX"
/* The list of what obscura wrote into a report directory (CLI_FMT_DIR), written last. */
#define MANIFEST ".obscura-report"
enum { MANIFEST_VERSION = 1, MANIFEST_MAX_BYTES = 64 << 20 };

/* ---- signals: an interrupted run leaves nothing behind, an interrupted commit nothing changed ----
 * Ctrl-C (SIGINT), SIGTERM or SIGHUP during a long render or report: the temporary directories of
 * the sets in use are removed, then the signal is raised again with its default action (the shell
 * sees the usual 130/143). The handler uses only async-signal-safe calls: unlinkat, openat,
 * getdents64, close. A signal the process ignores (nohup) stays ignored.
 *
 * What changes the sets or the files (making a temporary directory and recording it, the commit,
 * the abort) runs held: the three signals blocked in this thread, and a handler that runs in
 * another thread meanwhile (llvmpipe's, Embree's: a signal sent to the process goes to any thread
 * that does not block it) only records the signal. On release the signal takes its course. The
 * commit looks for one between its steps and then undoes what it did, so that an interrupted
 * commit, like an interrupted render, leaves every output as it was. */
enum { MAX_ACTIVE = 4, MAX_DEPTH = 8 };
enum { SIG_IDLE, SIG_HOLDING, SIG_DYING };
static cli_outputs *volatile active[MAX_ACTIVE];
static atomic_int sig_state = SIG_IDLE;
static atomic_int held_signal = 0;
static const int term_signals[] = {SIGINT, SIGTERM, SIGHUP};
static sigset_t handled = {0}; /* those of term_signals whose handler is on_signal */
static int hold_depth = 0;
static sigset_t hold_before = {0}; /* the mask before the outermost hold */

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
    int expected = SIG_IDLE;
    if (!atomic_compare_exchange_strong(&sig_state, &expected, SIG_DYING)) {
        /* Held: release() raises it again. Dying: another thread is already on its way out. */
        if (expected == SIG_HOLDING) atomic_store(&held_signal, sig);
        return;
    }
    for (int k = 0; k < MAX_ACTIVE; ++k) {
        cli_outputs *s = active[k];
        for (int i = 0; s && i < s->count; ++i)
            if (s->items[i].tmp) unlink_tree_at(AT_FDCWD, s->items[i].tmp, 0);
    }
    signal(sig, SIG_DFL);
    raise(sig);
}

static void hold(void)
{
    if (hold_depth++ > 0) return;
    sigset_t block;
    sigemptyset(&block);
    for (size_t i = 0; i < sizeof term_signals / sizeof term_signals[0]; ++i) sigaddset(&block, term_signals[i]);
    sigprocmask(SIG_BLOCK, &block, &hold_before);
    int expected = SIG_IDLE;
    if (!atomic_compare_exchange_strong(&sig_state, &expected, SIG_HOLDING))
        for (;;) pause(); /* another thread's handler is removing the files and ends the process */
}

static void release(void)
{
    if (--hold_depth > 0) return;
    atomic_store(&sig_state, SIG_IDLE);
    /* A signal sent while held is delivered here, in this thread, or was taken by another one. */
    sigprocmask(SIG_SETMASK, &hold_before, NULL);
    int sig = atomic_exchange(&held_signal, 0);
    if (sig) raise(sig);
}

/* Whether, while held, one of the signals this process dies of arrived. */
static bool interrupted(void)
{
    if (atomic_load(&held_signal)) return true;
    sigset_t pending;
    sigemptyset(&pending);
    sigpending(&pending);
    for (size_t i = 0; i < sizeof term_signals / sizeof term_signals[0]; ++i) {
        const int sig = term_signals[i];
        /* One blocked since before (by whoever started us) is theirs to deliver, not a Ctrl-C. */
        if (sigismember(&pending, sig) == 1 && sigismember(&handled, sig) == 1 && sigismember(&hold_before, sig) != 1)
            return true;
    }
    return false;
}

/* Held: the handler reads active[] and the items. */
static void watch(cli_outputs *s)
{
    static bool installed = false;
    if (!installed) {
        installed = true;
        sigemptyset(&handled);
        for (size_t i = 0; i < sizeof term_signals / sizeof term_signals[0]; ++i) {
            struct sigaction old;
            if (sigaction(term_signals[i], NULL, &old) == 0 && old.sa_handler == SIG_DFL) {
                struct sigaction sa;
                memset(&sa, 0, sizeof sa);
                sa.sa_handler = on_signal;
                sigemptyset(&sa.sa_mask);
                if (sigaction(term_signals[i], &sa, NULL) == 0) sigaddset(&handled, term_signals[i]);
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


/* ---- report directories: replaced only when obscura wrote everything in them -------------------
 * A report directory is replaced as a whole, so replacing one that holds anything else (notes
 * beside the report, a mistyped --report $HOME) would delete it. At the commit the report gets a
 * manifest, MANIFEST, listing every file and directory in it ("img/" for a directory); an existing
 * directory is replaced only when it is empty or when its manifest lists every entry it holds. */

typedef struct name_list {
    char **v;
    int n, cap;
} name_list;

static void names_free(name_list *l)
{
    for (int i = 0; i < l->n; ++i) free(l->v[i]);
    free(l->v);
    *l = (name_list){0};
}

/* a followed by b, appended; false when out of memory. */
static bool names_push(name_list *l, const char *a, const char *b)
{
    if (l->n == l->cap) {
        int cap = l->cap ? 2 * l->cap : 32;
        char **v = realloc(l->v, (size_t)cap * sizeof *v);
        if (!v) return false;
        l->v = v;
        l->cap = cap;
    }
    size_t na = strlen(a), nb = strlen(b);
    char *s = malloc(na + nb + 1);
    if (!s) return false;
    memcpy(s, a, na);
    memcpy(s + na, b, nb + 1);
    l->v[l->n++] = s;
    return true;
}

static int compare_names(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

static bool names_has(const name_list *l, const char *name)
{
    return l->n > 0 && bsearch(&name, l->v, (size_t)l->n, sizeof l->v[0], compare_names) != NULL;
}

/* The entries of directory fd but . and .., sorted (the messages name the same one every time);
 * false with errno set. */
static bool dir_entries(int fd, name_list *out)
{
    int own = dup(fd); /* closedir closes it; fd stays the caller's */
    DIR *d = own >= 0 ? fdopendir(own) : NULL;
    if (!d) {
        int e = errno;
        if (own >= 0) close(own);
        errno = e;
        return false;
    }
    rewinddir(d);
    bool ok = true;
    errno = 0;
    for (struct dirent *e = NULL; ok && (e = readdir(d)) != NULL; errno = 0)
        if (strcmp(e->d_name, ".") && strcmp(e->d_name, "..")) ok = names_push(out, e->d_name, "");
    int e = ok ? errno : ENOMEM;
    closedir(d);
    if (ok && e == 0 && out->n > 1) qsort(out->v, (size_t)out->n, sizeof out->v[0], compare_names);
    errno = e;
    return ok && e == 0;
}

/* Every regular file and directory under fd as prefix + name, a directory's with a trailing '/',
 * the manifest itself left out; false with errno set. Only what obscura writes is listed:
 * anything else (a link) stays unlisted, so a later run refuses to replace the directory. */
static bool list_tree(int fd, const char *prefix, int depth, name_list *out)
{
    name_list here = {0};
    if (!dir_entries(fd, &here)) return false;
    bool ok = true;
    for (int i = 0; i < here.n && ok; ++i) {
        const char *name = here.v[i];
        struct stat st = {0};
        if (depth == 0 && !strcmp(name, MANIFEST)) continue;
        if (fstatat(fd, name, &st, AT_SYMLINK_NOFOLLOW) != 0) {
            ok = false;
            break;
        }
        if (!S_ISDIR(st.st_mode) && !S_ISREG(st.st_mode)) continue;
        char rel[PATH_MAX] = "";
        if (snprintf(rel, sizeof rel, "%s%s%s", prefix, name, S_ISDIR(st.st_mode) ? "/" : "") >= (int)sizeof rel) {
            errno = ENAMETOOLONG;
            ok = false;
        } else if (!names_push(out, rel, "")) {
            errno = ENOMEM;
            ok = false;
        } else if (S_ISDIR(st.st_mode)) {
            int sub = depth < MAX_DEPTH ? openat(fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC) : -1;
            if (depth >= MAX_DEPTH) errno = ELOOP;
            ok = sub >= 0 && list_tree(sub, rel, depth + 1, out);
            if (sub >= 0) {
                int e = errno;
                close(sub);
                errno = e;
            }
        }
    }
    int e = errno;
    names_free(&here);
    errno = e;
    return ok;
}

/* The first entry under fd (in sorted order, depth first) that `listed` does not name, as
 * prefix + name (a directory's with '/') into found; false when there is none. An entry that
 * cannot be read counts as not listed: what cannot be seen cannot be shown to be obscura's. */
static bool first_unlisted(int fd, const char *prefix, int depth, const name_list *listed, char *found, size_t n)
{
    name_list here = {0};
    if (!dir_entries(fd, &here)) {
        snprintf(found, n, "%s", *prefix ? prefix : "./");
        return true;
    }
    bool hit = false;
    for (int i = 0; i < here.n && !hit; ++i) {
        const char *name = here.v[i];
        if (depth == 0 && !strcmp(name, MANIFEST)) continue;
        struct stat st = {0};
        const bool seen = fstatat(fd, name, &st, AT_SYMLINK_NOFOLLOW) == 0;
        const bool is_dir = seen && S_ISDIR(st.st_mode), is_reg = seen && S_ISREG(st.st_mode);
        char rel[PATH_MAX] = "";
        snprintf(rel, sizeof rel, "%s%s%s", prefix, name, is_dir ? "/" : "");
        if ((!is_dir && !is_reg) || !names_has(listed, rel) || (is_dir && depth >= MAX_DEPTH)) {
            snprintf(found, n, "%s", rel);
            hit = true;
        } else if (is_dir) {
            int sub = openat(fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
            if (sub < 0) {
                snprintf(found, n, "%s", rel);
                hit = true;
            } else {
                hit = first_unlisted(sub, rel, depth + 1, listed, found, n);
                close(sub);
            }
        }
    }
    names_free(&here);
    return hit;
}

/* The manifest in directory fd: the names it lists, sorted. false with *why (a static string)
 * when it is missing (*why NULL, errno ENOENT), unreadable or not one obscura writes. */
static bool read_manifest(int fd, name_list *listed, const char **why)
{
    *why = NULL;
    int mf = openat(fd, MANIFEST, O_RDONLY | O_NOFOLLOW | O_CLOEXEC);
    if (mf < 0) {
        if (errno != ENOENT) *why = errno == ELOOP ? "a link" : strerror(errno);
        return false;
    }
    struct stat st = {0};
    char *text = NULL;
    bool ok = fstat(mf, &st) == 0 && S_ISREG(st.st_mode) && st.st_size < MANIFEST_MAX_BYTES;
    if (ok) ok = (text = malloc((size_t)st.st_size + 1)) != NULL;
    size_t got = 0;
    while (ok && got < (size_t)st.st_size) {
        ssize_t r = read(mf, text + got, (size_t)st.st_size - got);
        if (r <= 0) ok = false;
        else got += (size_t)r;
    }
    close(mf);
    if (!ok) {
        free(text);
        *why = "unreadable";
        return false;
    }
    text[got] = '\0';
    cJSON *root = cJSON_Parse(text);
    free(text);
    const cJSON *version = cJSON_GetObjectItemCaseSensitive(root, "obscura_report");
    const cJSON *entries = cJSON_GetObjectItemCaseSensitive(root, "written");
    ok = cJSON_IsNumber(version) && version->valuedouble == MANIFEST_VERSION && cJSON_IsArray(entries);
    for (const cJSON *e = ok ? entries->child : NULL; e && ok; e = e->next)
        ok = cJSON_IsString(e) && names_push(listed, e->valuestring, "");
    cJSON_Delete(root);
    if (!ok) {
        names_free(listed);
        *why = "not a list obscura wrote";
        return false;
    }
    if (listed->n > 1) qsort(listed->v, (size_t)listed->n, sizeof listed->v[0], compare_names);
    return true;
}

/* Why the existing directory path may not be replaced by a report, into why (after "OPTION PATH: "):
 * false when it may, being empty or holding nothing but what its manifest lists. Run when the
 * output is added (before any work), again at the commit (a file may have come meanwhile) and on
 * the old report once it is swapped out (one may have come during the commit). */
static bool report_dir_refused(const char *path, char *why, size_t n)
{
    int fd = open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) {
        snprintf(why, n, "cannot read it: %s", strerror(errno));
        return true;
    }
    name_list top = {0}, listed = {0};
    bool refused = true;
    const char *bad = NULL;
    char found[PATH_MAX] = "";
    if (!dir_entries(fd, &top)) {
        snprintf(why, n, "cannot read it: %s", strerror(errno));
    } else if (top.n == 0) {
        refused = false;
    } else if (!read_manifest(fd, &listed, &bad)) {
        if (bad)
            snprintf(why, n, "its %s is %s: refusing to replace it; give a new directory", MANIFEST, bad);
        else if (names_has(&top, "index.html") || names_has(&top, "results.json"))
            snprintf(why, n, "a report of an earlier obscura, which did not list the files it wrote (no %s): it may "
                     "hold files of yours, so it is not replaced; remove it or give a new directory", MANIFEST);
        else if (first_unlisted(fd, "", 0, &listed, found, sizeof found))
            snprintf(why, n, "holds %s, which obscura did not write: refusing to replace it; give a new directory", found);
        else
            snprintf(why, n, "cannot read it");
    } else if (first_unlisted(fd, "", 0, &listed, found, sizeof found)) {
        snprintf(why, n, "holds %s, which obscura did not write: refusing to replace it; give a new directory", found);
    } else {
        refused = false;
    }
    names_free(&top);
    names_free(&listed);
    close(fd);
    return refused;
}

/* MANIFEST in the report's temporary directory, listing what is in it now: the last file written. */
static int write_manifest(const cli_output *o)
{
    int fd = open(o->tmp, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    name_list all = {0};
    bool ok = fd >= 0 && list_tree(fd, "", 0, &all);
    int err = ok ? 0 : errno;
    cJSON *root = ok ? cJSON_CreateObject() : NULL;
    cJSON *list = NULL;
    ok = ok && root && cJSON_AddNumberToObject(root, "obscura_report", MANIFEST_VERSION) &&
         cJSON_AddStringToObject(root, "about", "every file and directory obscura wrote here: obscura replaces this "
                                                "directory only while it holds nothing else") &&
         (list = cJSON_AddArrayToObject(root, "written")) != NULL;
    for (int i = 0; i < all.n && ok; ++i) {
        cJSON *name = cJSON_CreateString(all.v[i]);
        ok = name && cJSON_AddItemToArray(list, name);
    }
    char *text = ok ? cJSON_Print(root) : NULL;
    if (!err && !text) err = ENOMEM;
    cJSON_Delete(root);
    names_free(&all);
    int mf = text ? openat(fd, MANIFEST, O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666) : -1;
    if (text && mf < 0) err = errno;
    size_t len = text ? strlen(text) : 0, done = 0;
    while (mf >= 0 && done < len) {
        ssize_t w = write(mf, text + done, len - done);
        if (w <= 0) {
            err = w < 0 ? errno : EIO;
            break;
        }
        done += (size_t)w;
    }
    if (mf >= 0 && !err && write(mf, "\n", 1) != 1) err = errno ? errno : EIO;
    if (mf >= 0 && close(mf) != 0 && !err) err = errno;
    free(text);
    if (fd >= 0) close(fd);
    if (!err) return EXIT_OK;
    if (err == ENOMEM) return cli_fail(EXIT_RUNTIME, "out of memory");
    return cli_fail(EXIT_OUTPUT, "%s %s: cannot write its %s: %s", o->option, o->path, MANIFEST, strerror(err));
}

/* Whether the directory of path takes a new directory of a name as long as an output's stage,
 * and whether the longest path written under that stage fits: made and removed again. access()
 * alone misses read-only file systems and names too long for the directory. */
static bool dir_takes(const char *path, int *err)
{
    char tmp[PATH_MAX] = "";
    if (strlen(path) + strlen(STAGE_SUFFIX STAGE_INNER) >= sizeof tmp) {
        *err = ENAMETOOLONG;
        return false;
    }
    snprintf(tmp, sizeof tmp, "%s" STAGE_SUFFIX, path);
    /* Held (the handler is not installed yet, or does not know the probe): a SIGINT, SIGTERM or
     * SIGHUP between mkdtemp and rmdir would leave the probe behind (test_hostile_outputs.sh
     * caught one). It takes its course once the probe is gone. */
    hold();
    bool made = mkdtemp(tmp) != NULL;
    if (made) rmdir(tmp);
    else *err = errno;
    release();
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
    struct stat st = {0};
    char why[PATH_MAX + 256] = "";
    if (code == EXIT_OK && stat(p, &st) == 0) {
        /* stat follows a link: a link to /dev/null is refused like /dev/null. */
        if (formats & CLI_FMT_DIR) {
            if (!S_ISDIR(st.st_mode))
                code = cli_fail(EXIT_OUTPUT, "%s %s: exists and is %s, not a directory", option, p, cli_file_kind(st.st_mode));
            else if (report_dir_refused(p, why, sizeof why))
                code = cli_fail(EXIT_OUTPUT, "%s %s: %s", option, p, why);
        } else if (!S_ISREG(st.st_mode)) {
            code = cli_fail(EXIT_OUTPUT, "%s %s: exists and is %s, not a regular file: refusing to replace it", option, p,
                            cli_file_kind(st.st_mode));
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
    if (code == EXIT_OK && !dir_takes(p, &err))
        code = cli_fail(EXIT_OUTPUT, "%s %s: cannot write a new %s in its directory: %s", option, p,
                        formats & CLI_FMT_DIR ? "directory" : "file", strerror(err));
    char *opt = code == EXIT_OK ? strdup(option) : NULL;
    if (code == EXIT_OK && !opt) code = cli_fail(EXIT_RUNTIME, "out of memory");
    hold(); /* the handler must not read the items while realloc moves them */
    if (code == EXIT_OK && s->count == s->cap) {
        int cap = s->cap ? 2 * s->cap : 8;
        cli_output *items = realloc(s->items, (size_t)cap * sizeof *items);
        if (!items) code = cli_fail(EXIT_RUNTIME, "out of memory");
        else {
            s->items = items;
            s->cap = cap;
        }
    }
    if (code == EXIT_OK) {
        s->items[s->count] = (cli_output){.option = opt, .path = p, .tmp = NULL, .format = format, .ready = false};
        *index = s->count++;
        watch(s);
    }
    release();
    if (code != EXIT_OK) {
        free(opt);
        free(p);
    }
    return code;
}

/* The output's directory beside it, PATH.tmp-XXXXXX, made on first use. Everything temporary of
 * the output goes in it, so removing it undoes them all: for a file the new file (NEW_LEAF), the
 * library writer's own temporary file while it writes that one, and at the commit a link to the
 * old file (OLD_LEAF); for a directory output the new directory's contents. NULL with the line
 * printed. */
static const char *stage(cli_output *o)
{
    if (o->tmp) return o->tmp;
    size_t n = strlen(o->path) + sizeof STAGE_SUFFIX;
    char *t = malloc(n);
    if (!t) {
        cli_fail(EXIT_RUNTIME, "out of memory");
        return NULL;
    }
    snprintf(t, n, "%s" STAGE_SUFFIX, o->path);
    /* Made and recorded as one step: the handler removes only what is recorded. */
    hold();
    bool made = mkdtemp(t) != NULL;
    int e = errno;
    if (made) o->tmp = t;
    release();
    if (!made) {
        if (o->format == CLI_FMT_DIR)
            cli_fail(EXIT_OUTPUT, "%s %s: cannot create a directory beside it: %s", o->option, o->path, strerror(e));
        else
            cli_fail(EXIT_OUTPUT, "%s %s: cannot write it: %s", o->option, o->path, strerror(e));
        free(t);
        return NULL;
    }
    return t;
}

/* "STAGE/leaf" into out (n >= PATH_MAX + 16: dir_takes checked that the stage's paths fit). */
static void stage_leaf(const cli_output *o, const char *leaf, char *out, size_t n)
{
    snprintf(out, n, "%s/%s", o->tmp, leaf);
}

/* The path the library writes the new file to: STAGE/new. NULL with the line printed. */
static const char *new_file(cli_outputs *s, int index, char *out, size_t n)
{
    cli_output *o = &s->items[index];
    if (!stage(o)) return NULL;
    stage_leaf(o, NEW_LEAF, out, n);
    return out;
}

static int written(cli_output *o, ob_error e)
{
    if (e == OB_OK) {
        o->ready = true;
        return EXIT_OK;
    }
    const char *msg = NULL;
    ob_get_error(&msg);
    /* The library names the file in the stage ("cannot write X.tmp-abc/new: why"): the reason alone. */
    const char *why = msg && *msg ? msg : "write failed";
    if (!strncmp(why, "cannot write ", 13) && strstr(why, ": ")) why = strstr(why, ": ") + 2;
    return cli_fail(EXIT_OUTPUT, "%s %s: cannot write it: %s", o->option, o->path, why);
}

int cli_outputs_write_rgb8(cli_outputs *s, int index, int w, int h, int channels, const uint8_t *px)
{
    cli_output *o = &s->items[index];
    char path[PATH_MAX + 16] = "";
    if (!new_file(s, index, path, sizeof path)) return EXIT_OUTPUT;
    ob_error e = OB_OK;
    if (o->format == CLI_FMT_PNG) e = ob_write_png(path, w, h, channels, px);
    else if (o->format == CLI_FMT_JPG) e = ob_write_jpg(path, w, h, channels, px, JPG_QUALITY);
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
        e = ob_write_pfm(path, w, h, c, f);
        free(f);
    }
    return written(o, e);
}

int cli_outputs_write_f32(cli_outputs *s, int index, int w, int h, int channels, const float *px)
{
    cli_output *o = &s->items[index];
    char path[PATH_MAX + 16] = "";
    if (!new_file(s, index, path, sizeof path)) return EXIT_OUTPUT;
    if (o->format == CLI_FMT_PFM) return written(o, ob_write_pfm(path, w, h, channels, px));
    uint8_t *b = malloc((size_t)w * (size_t)h * (size_t)channels);
    if (!b) return cli_fail(EXIT_RUNTIME, "out of memory writing %s", o->path);
    for (int y = 0; y < h; ++y)
        for (size_t x = 0; x < (size_t)w * (size_t)channels; ++x) {
            float v = px[(size_t)(h - 1 - y) * (size_t)w * (size_t)channels + x];
            v = v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; /* NaN -> 0 */
            b[(size_t)y * (size_t)w * (size_t)channels + x] = (uint8_t)lrintf(v * 255.0f);
        }
    ob_error e = o->format == CLI_FMT_PNG ? ob_write_png(path, w, h, channels, b)
                                          : ob_write_jpg(path, w, h, channels, b, JPG_QUALITY);
    free(b);
    return written(o, e);
}

int cli_outputs_write_text(cli_outputs *s, int index, const char *text)
{
    cli_output *o = &s->items[index];
    char path[PATH_MAX + 16] = "";
    if (!new_file(s, index, path, sizeof path)) return EXIT_OUTPUT;
    char *valid = cli_utf8_valid(text);
    if (!valid) return cli_fail(EXIT_RUNTIME, "out of memory writing %s", o->path);
    ob_error e = ob_write_text(path, valid);
    free(valid);
    return written(o, e);
}

const char *cli_outputs_dir(cli_outputs *s, int index)
{
    cli_output *o = &s->items[index];
    if (o->tmp) return o->tmp;
    const char *t = stage(o);
    if (!t) return NULL;
    /* mkdtemp makes it 0700; a report is as readable as any directory the user makes. */
    mode_t mask = umask(0);
    umask(mask);
    chmod(t, 0777 & ~mask);
    o->ready = true;
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

/* Held. */
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
    hold();
    for (int i = 0; i < s->count; ++i)
        if (s->items[i].tmp) remove_tree(s->items[i].tmp);
    clear(s);
    release();
}

/* ---- the commit ----------------------------------------------------------------------------------
 * One transaction over every output of the set, held (no signal acts until it is over):
 *   1. each target checked again (a directory may have come where a file goes, a file of the user
 *      into a report), and each report given its manifest: nothing outside the stages changes;
 *   2. each existing file hard-linked into its stage (OLD_LEAF): the old file stays in place;
 *   3. each new file renamed over its target, each report exchanged with the old one
 *      (renameat2 RENAME_EXCHANGE: the old report is then at the stage's name).
 * An old report, once swapped out, is checked once more: a file of the user's that came in after
 * step 1 fails the commit instead of going with it. A step that fails, or a signal that arrived by
 * the end of step 3, undoes steps 3 and 2 in reverse (the old file renamed back over the new one,
 * the reports exchanged back, a target that did not exist removed again). Then the stages go, with
 * the old copies in them; an output that could not be put back keeps its stage, and the message
 * says where its old copy is. */

typedef struct commit_step {
    bool had_old;   /* the target existed: for a file, its copy is STAGE/old */
    bool aside;     /* no hard links here: the old file was renamed to STAGE/old, its name is free */
    bool installed; /* step 3 done */
    bool keep;      /* the stage holds an old copy that could not be put back */
} commit_step;

/* Step 1 for one output; EXIT_OK or the code of the one line printed. */
static int check_again(const cli_output *o)
{
    struct stat st = {0};
    if (o->format == CLI_FMT_DIR) {
        if (stat(o->path, &st) == 0) {
            if (!S_ISDIR(st.st_mode))
                return cli_fail(EXIT_OUTPUT, "%s %s: exists and is %s, not a directory", o->option, o->path,
                                cli_file_kind(st.st_mode));
            char why[PATH_MAX + 256] = "";
            if (report_dir_refused(o->path, why, sizeof why)) return cli_fail(EXIT_OUTPUT, "%s %s: %s", o->option, o->path, why);
        }
        return write_manifest(o);
    }
    if (stat(o->path, &st) == 0 && !S_ISREG(st.st_mode))
        return cli_fail(EXIT_OUTPUT, "%s %s: exists and is %s, not a regular file: refusing to replace it", o->option,
                        o->path, cli_file_kind(st.st_mode));
    return EXIT_OK;
}

/* Step 2 for one output; 0 or errno. An old report needs nothing here: the exchange keeps it. */
static int keep_old(const cli_output *o, commit_step *st)
{
    struct stat now = {0};
    if (o->format == CLI_FMT_DIR) {
        st->had_old = stat(o->path, &now) == 0;
        return 0;
    }
    char old[PATH_MAX + 16] = "";
    stage_leaf(o, OLD_LEAF, old, sizeof old);
    /* link does not follow a symbolic link: a link given as the output is kept as a link. */
    if (link(o->path, old) == 0) {
        st->had_old = true;
        return 0;
    }
    if (errno == ENOENT) return 0;
    if (errno != EPERM && errno != ENOTSUP && errno != EOPNOTSUPP && errno != EMLINK) return errno;
    /* A file system without hard links (FAT): the old file is moved instead, its name free until
     * the new file takes it. */
    if (rename(o->path, old) == 0) {
        st->had_old = st->aside = true;
        return 0;
    }
    return errno == ENOENT ? 0 : errno;
}

/* from renamed to a name that does not exist (and stays so: not onto a file that came meanwhile);
 * 0 or errno. */
static int rename_new(const char *from, const char *to)
{
    if (renameat2(AT_FDCWD, from, AT_FDCWD, to, RENAME_NOREPLACE) == 0) return 0;
    if (errno != EINVAL && errno != ENOSYS) return errno;
    /* A file system without RENAME_NOREPLACE. */
    return rename(from, to) == 0 ? 0 : errno;
}

/* Step 3 for one output; 0 or errno. */
static int install(const cli_output *o, const commit_step *st)
{
    if (o->format == CLI_FMT_DIR) {
        if (!st->had_old) return rename_new(o->tmp, o->path);
        return renameat2(AT_FDCWD, o->tmp, AT_FDCWD, o->path, RENAME_EXCHANGE) == 0 ? 0 : errno;
    }
    char fresh[PATH_MAX + 16] = "";
    stage_leaf(o, NEW_LEAF, fresh, sizeof fresh);
    if (st->had_old && !st->aside) return rename(fresh, o->path) == 0 ? 0 : errno;
    return rename_new(fresh, o->path);
}

/* Steps 2 and 3 for one output undone; 0 or errno. */
static int put_back(const cli_output *o, const commit_step *st)
{
    if (o->format == CLI_FMT_DIR) {
        if (!st->installed) return 0;
        if (st->had_old) return renameat2(AT_FDCWD, o->tmp, AT_FDCWD, o->path, RENAME_EXCHANGE) == 0 ? 0 : errno;
        return rename(o->path, o->tmp) == 0 ? 0 : errno;
    }
    char old[PATH_MAX + 16] = "";
    stage_leaf(o, OLD_LEAF, old, sizeof old);
    if (st->had_old && (st->installed || st->aside)) return rename(old, o->path) == 0 ? 0 : errno;
    if (st->installed) return unlink(o->path) == 0 || errno == ENOENT ? 0 : errno;
    return 0;
}

int cli_outputs_commit(cli_outputs *s)
{
    hold();
    int code = EXIT_OK;
    commit_step *steps = calloc((size_t)(s->count > 0 ? s->count : 1), sizeof *steps);
    if (!steps) code = cli_fail(EXIT_RUNTIME, "out of memory");
    for (int i = 0; i < s->count && code == EXIT_OK; ++i)
        if (s->items[i].ready) code = check_again(&s->items[i]);
    /* From here nothing is printed until the outcome is known: one line for the whole commit. */
    bool signalled = false;
    int failed = -1;
    char why[PATH_MAX + 256] = "";
    for (int i = 0; i < s->count && code == EXIT_OK && failed < 0 && !signalled; ++i) {
        const cli_output *o = &s->items[i];
        int e = o->ready ? keep_old(o, &steps[i]) : 0;
        if (e) {
            failed = i;
            snprintf(why, sizeof why, "cannot keep the existing file aside: %s", strerror(e));
        }
        signalled = interrupted();
    }
    for (int i = 0; i < s->count && code == EXIT_OK && failed < 0 && !signalled; ++i) {
        const cli_output *o = &s->items[i];
        int e = o->ready ? install(o, &steps[i]) : 0;
        if (e) {
            failed = i;
            snprintf(why, sizeof why, "%s: %s", o->format == CLI_FMT_DIR && steps[i].had_old ? "cannot replace it"
                                                                                             : "cannot write it", strerror(e));
        } else if (o->ready) {
            steps[i].installed = true;
            /* The old report, swapped out, once more: a file that came into it since the check
             * would go with it. */
            if (o->format == CLI_FMT_DIR && steps[i].had_old && report_dir_refused(o->tmp, why, sizeof why)) failed = i;
        }
        signalled = interrupted();
    }
    int lost = -1, lost_err = 0;
    if (code == EXIT_OK && (failed >= 0 || signalled))
        for (int i = s->count - 1; i >= 0; --i) {
            const cli_output *o = &s->items[i];
            int e = o->ready ? put_back(o, &steps[i]) : 0;
            if (e) {
                steps[i].keep = true;
                if (lost < 0) {
                    lost = i;
                    lost_err = e;
                }
            }
        }
    if (failed >= 0 || lost >= 0) {
        char what[2 * PATH_MAX + 512] = "interrupted";
        if (failed >= 0) snprintf(what, sizeof what, "%s %s: %s", s->items[failed].option, s->items[failed].path, why);
        if (lost >= 0) {
            const cli_output *l = &s->items[lost];
            char old[PATH_MAX + 16] = "";
            if (l->format == CLI_FMT_DIR) snprintf(old, sizeof old, "%s", l->tmp);
            else stage_leaf(l, OLD_LEAF, old, sizeof old);
            code = cli_fail(EXIT_OUTPUT, "%s; and %s %s could not be put back (%s): its old %s is %s", what, l->option,
                            l->path, strerror(lost_err), l->format == CLI_FMT_DIR ? "report" : "file", old);
        } else {
            code = cli_fail(EXIT_OUTPUT, "%s", what);
        }
    }
    for (int i = 0; i < s->count; ++i)
        if (s->items[i].tmp && !(steps && steps[i].keep)) remove_tree(s->items[i].tmp);
    clear(s);
    free(steps);
    release(); /* a signal that came during the commit ends the process here */
    if (signalled && code == EXIT_OK) code = cli_fail(EXIT_OUTPUT, "interrupted: no output was replaced");
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
