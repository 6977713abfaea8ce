/* The shards of one tune run in step (tune_exchange.h has the protocol and the folder's files). */
#include "tune_exchange.h"

#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"

#define RECORD_MAGIC "obscura tune exchange 1"

enum { RECORD_LIMIT = 1 << 20, NAMED_MOST = 8 };

void tune_run_id(int argc, char **argv, char out[TUNE_RUN_ID_LEN + 1])
{
    static const char *const own[] = {"--shard", "--exchange", "--exchange-timeout", "--out"};
    uint64_t h = 14695981039346656037ull;
    for (int i = 1; i < argc; ++i) {
        bool skip = false;
        for (size_t k = 0; k < sizeof own / sizeof own[0]; ++k) skip = skip || !strcmp(argv[i], own[k]);
        if (skip) {
            ++i; /* and its value */
            continue;
        }
        for (const unsigned char *p = (const unsigned char *)argv[i];; ++p) {
            h = (h ^ *p) * 1099511628211ull;
            if (!*p) break;
        }
    }
    snprintf(out, TUNE_RUN_ID_LEN + 1, "%016llx", (unsigned long long)h);
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void sleep_s(double s)
{
    struct timespec t = {(time_t)s, (long)((s - floor(s)) * 1e9)};
    while (nanosleep(&t, &t) != 0 && errno == EINTR) {
    }
}

static bool exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* ---- writing ---------------------------------------------------------------------------------- */

static void write_header(FILE *f, const tune_exchange *x)
{
    fprintf(f, RECORD_MAGIC "\nversion %s\nrun %s\nshard %d/%d\n", OB_VERSION_STRING, x->run, x->shard.index,
            x->shard.count);
}

/* What follows a record's header: an evaluation's values of this shard's views, or a failure. */
typedef struct record_body {
    const char *set, *failed;
    int evaluation, first, count;
    const double *mse;
    const float *radius;
} record_body;

static bool write_body(FILE *f, const tune_exchange *x, const record_body *b)
{
    write_header(f, x);
    if (b->failed) return fprintf(f, "failed %s\nend\n", b->failed) > 0 && !ferror(f);
    int mine = 0;
    for (int i = 0; i < b->count; ++i) mine += x->owner[b->first + i] == x->shard.index;
    fprintf(f, "evaluation %d\nset %s\nviews %d\n", b->evaluation, b->set, mine);
    for (int i = 0; i < b->count; ++i)
        if (x->owner[b->first + i] == x->shard.index)
            fprintf(f, "view %d %a %a\n", b->first + i, b->mse[i], (double)b->radius[i]);
    return fputs("end\n", f) >= 0 && !ferror(f); /* a short write of any line shows here or at fclose */
}

/* DIR/RUN/name whole or not at all: written into .name.tmp-XXXXXX beside it and renamed over it
 * (the rename is atomic, so a reader polling for name never sees half of it). false with *err the
 * errno when it cannot be written. */
static bool write_file(const tune_exchange *x, const char *name, const record_body *b, int *err)
{
    char path[4400], tmp[4400];
    snprintf(path, sizeof path, "%s/%s", x->dir, name);
    snprintf(tmp, sizeof tmp, "%s/.%s.tmp-XXXXXX", x->dir, name);
    int fd = mkstemp(tmp);
    if (fd < 0) {
        *err = errno;
        return false;
    }
    (void)fchmod(fd, 0644); /* mkstemp's 0600 would keep the record from shards run as another user */
    FILE *f = fdopen(fd, "w");
    bool ok = f && write_body(f, x, b);
    *err = errno;
    if (f ? fclose(f) != 0 : close(fd) != 0) ok = false, *err = errno;
    if (ok && rename(tmp, path) != 0) ok = false, *err = errno;
    if (!ok) unlink(tmp);
    if (!ok && !*err) *err = EIO;
    return ok;
}

static int write_record(const tune_exchange *x, const char *name, const record_body *b)
{
    int err = 0;
    if (write_file(x, name, b, &err)) return EXIT_OK;
    return cli_fail(EXIT_OUTPUT, "cannot write %s/%s: %s", x->dir, name, strerror(err));
}

void tune_exchange_fail(tune_exchange *x, const char *message)
{
    if (!x->open) return;
    char name[64];
    snprintf(name, sizeof name, "failed.shard-%d", x->shard.index);
    record_body b = {.failed = message && *message ? message : "(no message)"};
    int err = 0;
    (void)write_file(x, name, &b, &err); /* already failing: a second line about the record would bury the first */
}

/* ---- reading ---------------------------------------------------------------------------------- */

/* The next line of *p (its '\n' cut), or NULL at the end or on a last line without one (a record
 * ends with "end\n"). */
static char *next_line(char **p)
{
    char *line = *p, *nl = line ? strchr(line, '\n') : NULL;
    if (!nl) return NULL;
    *nl = '\0';
    *p = nl + 1;
    return line;
}

/* "KEY VALUE": VALUE, or NULL when the line is not KEY's. */
static const char *value_of(const char *line, const char *key)
{
    size_t n = strlen(key);
    return line && !strncmp(line, key, n) && line[n] == ' ' ? line + n + 1 : NULL;
}

/* The header of a record read into text (cut line by line from *p): NULL when it is this run's
 * and shard M's, else why not (into why). */
static const char *check_header(const tune_exchange *x, char **p, int m, char *why, size_t n)
{
    const char *magic = next_line(p);
    if (!magic || strcmp(magic, RECORD_MAGIC)) return "not a tune exchange record (the folder is obscura tune's)";
    const char *version = value_of(next_line(p), "version");
    if (!version) return "not whole (no version line)";
    if (strcmp(version, OB_VERSION_STRING)) {
        snprintf(why, n, "written by obscura %.40s, this shard is %s: every shard must run one build", version,
                 OB_VERSION_STRING);
        return why;
    }
    const char *run = value_of(next_line(p), "run");
    if (!run) return "not whole (no run line)";
    if (strcmp(run, x->run)) {
        snprintf(why, n, "a record of another run (%.40s; this run is %s)", run, x->run);
        return why;
    }
    const char *shard = value_of(next_line(p), "shard");
    int k = -1, count = -1;
    char tail = '\0';
    if (!shard || sscanf(shard, "%d/%d%c", &k, &count, &tail) != 2) return "not whole (no shard line)";
    if (k != m || count != x->shard.count) {
        snprintf(why, n, "shard %d/%d's record where shard %d/%d's belongs (were the shards given different N?)", k,
                 count, m, x->shard.count);
        return why;
    }
    return NULL;
}

/* One view line of shard m's record: "view U MSE RADIUS" with U the next of m's views. */
static const char *read_view(const char *line, int want, double *mse, float *radius)
{
    const char *v = value_of(line, "view");
    if (!v) return "not whole (fewer view lines than it counts)";
    char *end = NULL;
    long u = strtol(v, &end, 10);
    if (end == v || *end != ' ' || u != want) return "holds views that are not that shard's in this evaluation";
    const char *s = end + 1;
    double m = strtod(s, &end);
    if (end == s || *end != ' ' || !isfinite(m) || m < 0.0) return "holds an MSE that is not a number >= 0";
    s = end + 1;
    double r = strtod(s, &end);
    if (end == s || *end || !isfinite(r)) return "holds a radius that is not a number";
    *mse = m;
    *radius = (float)r;
    return NULL;
}

/* Evaluation i's record of shard m: its views' values into mse and radius (indexed from first). */
static const char *parse_eval(const tune_exchange *x, char *text, int m, int i, const char *set, int first,
                              int count, double *mse, float *radius, char *why, size_t n)
{
    char *p = text;
    const char *bad = check_header(x, &p, m, why, n);
    if (bad) return bad;
    const char *ev = value_of(next_line(&p), "evaluation");
    if (!ev) return "not whole (no evaluation line)";
    if (atoi(ev) != i || strspn(ev, "0123456789") != strlen(ev)) {
        snprintf(why, n, "evaluation %.20s where evaluation %d belongs", ev, i);
        return why;
    }
    const char *s = value_of(next_line(&p), "set");
    if (!s || strcmp(s, set)) {
        snprintf(why, n, "the %.20s views where the %s views belong", s ? s : "(no set)", set);
        return why;
    }
    int mine = 0;
    for (int k = 0; k < count; ++k) mine += x->owner[first + k] == m;
    const char *views = value_of(next_line(&p), "views");
    if (!views || atoi(views) != mine) return "holds views that are not that shard's in this evaluation";
    for (int k = 0; k < count; ++k) {
        if (x->owner[first + k] != m) continue;
        if ((bad = read_view(next_line(&p), first + k, &mse[k], &radius[k]))) return bad;
    }
    const char *end = next_line(&p);
    if (!end || strcmp(end, "end") || *p) return "not whole (no end line where it should end)";
    return NULL;
}

/* A failed.shard-M record: one line naming the shard and its message, exit 3. */
static int report_failure(const tune_exchange *x, int m, const char *path)
{
    char why[256];
    char *text = cli_read_regular(path, RECORD_LIMIT, NULL, why, sizeof why);
    char *p = text, *line = NULL;
    const char *message = NULL;
    if (text && !check_header(x, &p, m, why, sizeof why) && (line = next_line(&p))) message = value_of(line, "failed");
    int code = cli_fail(EXIT_INPUT, "shard %d/%d failed: %s (%s)", m, x->shard.count,
                        message ? message : "(its record does not say why)", path);
    free(text);
    return code;
}

/* ---- the folder --------------------------------------------------------------------------------- */

/* mkdir that takes a folder already there (another shard may have made it a moment ago). */
static int make_dir(const char *path)
{
    if (mkdir(path, 0777) == 0 || (errno == EEXIST && exists(path))) {
        struct stat st;
        if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) return EXIT_OK;
        return cli_fail(EXIT_OUTPUT, "--exchange: %s is %s, not a folder", path, cli_file_kind(st.st_mode));
    }
    return cli_fail(EXIT_OUTPUT, "--exchange: cannot create %s: %s", path, strerror(errno));
}

/* "eval-I.shard-M" and "failed.shard-M" into I and M (I = -1 for a failure); false for any other
 * name. */
static bool record_name(const char *name, int *i, int *m)
{
    char tail = '\0';
    *i = -1;
    if (sscanf(name, "eval-%d.shard-%d%c", i, m, &tail) == 2) return *i >= 0 && *m >= 0;
    return sscanf(name, "failed.shard-%d%c", m, &tail) == 1 && *m >= 0;
}

/* What this attempt may find when it starts: the other shards' records of evaluation 0 and
 * failures, and files being written (dot names). Anything else is an earlier attempt's. */
static int check_folder(tune_exchange *x)
{
    DIR *d = opendir(x->dir);
    if (!d) return cli_fail(EXIT_OUTPUT, "--exchange: cannot read %s: %s", x->dir, strerror(errno));
    char stale[300] = "";
    int failed = -1;
    for (struct dirent *e; (e = readdir(d));) {
        if (e->d_name[0] == '.') continue;
        int i = -1, m = -1;
        bool ours = record_name(e->d_name, &i, &m) && m != x->shard.index && m < x->shard.count;
        if (ours && i < 0 && failed < 0) failed = m;
        if (!ours || i > 0) snprintf(stale, sizeof stale, "%.250s", e->d_name);
        if (*stale) break;
    }
    closedir(d);
    if (*stale)
        return cli_fail(EXIT_OUTPUT, "--exchange: %s holds an earlier run's records (%s); remove it", x->dir, stale);
    if (failed >= 0) {
        char path[4400];
        snprintf(path, sizeof path, "%s/failed.shard-%d", x->dir, failed);
        return report_failure(x, failed, path);
    }
    return EXIT_OK;
}

int tune_exchange_open(tune_exchange *x, const char *root, const cli_shard *shard, const char *run,
                       const int *owner, int units, double timeout_s)
{
    *x = (tune_exchange){.shard = *shard, .owner = owner, .units = units, .timeout_s = timeout_s};
    snprintf(x->run, sizeof x->run, "%s", run);
    if (strlen(root) + TUNE_RUN_ID_LEN + 2 > sizeof x->dir - 64)
        return cli_fail(EXIT_USAGE, "--exchange: a path of %zu bytes; at most %zu", strlen(root), sizeof x->dir - 96);
    snprintf(x->dir, sizeof x->dir, "%s/%s", root, run);
    x->have = calloc((size_t)shard->count, sizeof *x->have);
    if (!x->have) return cli_fail(EXIT_RUNTIME, "out of memory");
    int code = make_dir(root);
    if (code == EXIT_OK) code = make_dir(x->dir);
    if (code != EXIT_OK) return code;
    x->open = true;
    return check_folder(x);
}

void tune_exchange_close(tune_exchange *x)
{
    free(x->have);
    x->have = NULL;
}

/* ---- one evaluation ----------------------------------------------------------------------------- */

/* Shard m's record of evaluation i, read and checked, into mse and radius. */
static int read_eval(tune_exchange *x, const char *path, int m, int i, const char *set, int first, int count,
                     double *mse, float *radius)
{
    char why[512];
    char *text = cli_read_regular(path, RECORD_LIMIT, NULL, why, sizeof why);
    const char *bad = text ? parse_eval(x, text, m, i, set, first, count, mse, radius, why, sizeof why) : why;
    int code = bad ? cli_fail(EXIT_INPUT, "%s: %s", path, bad) : EXIT_OK;
    free(text);
    return code;
}

/* After the timeout: every shard still missing named (the first few), one line. */
static int report_timeout(const tune_exchange *x, int i)
{
    char list[400] = "";
    int missing = 0, first = -1;
    for (int m = 0; m < x->shard.count; ++m) {
        if (m == x->shard.index || x->have[m]) continue;
        if (first < 0) first = m;
        size_t len = strlen(list);
        if (missing < NAMED_MOST)
            snprintf(list + len, sizeof list - len, "%s%d/%d", missing ? ", " : "", m, x->shard.count);
        ++missing;
    }
    if (missing > NAMED_MOST) {
        size_t len = strlen(list);
        snprintf(list + len, sizeof list - len, " and %d more", missing - NAMED_MOST);
    }
    if (missing == 1)
        return cli_fail(EXIT_INPUT, "shard %s never wrote evaluation %d within --exchange-timeout %g s (no %s/eval-%d.shard-%d)",
                        list, i, x->timeout_s, x->dir, i, first);
    return cli_fail(EXIT_INPUT, "shards %s never wrote evaluation %d within --exchange-timeout %g s (in %s)", list, i,
                    x->timeout_s, x->dir);
}

/* Waits until every other shard's record of evaluation i has been read. */
static int wait_all(tune_exchange *x, int i, const char *set, int first, int count, double *mse, float *radius)
{
    const double deadline = now_s() + x->timeout_s;
    double delay = 0.01;
    memset(x->have, 0, (size_t)x->shard.count * sizeof *x->have);
    for (;;) {
        int missing = 0;
        for (int m = 0; m < x->shard.count; ++m) {
            if (m == x->shard.index || x->have[m]) continue;
            char path[4400];
            snprintf(path, sizeof path, "%s/eval-%d.shard-%d", x->dir, i, m);
            if (exists(path)) {
                int code = read_eval(x, path, m, i, set, first, count, mse, radius);
                if (code != EXIT_OK) return code;
                x->have[m] = true;
                continue;
            }
            ++missing;
            snprintf(path, sizeof path, "%s/failed.shard-%d", x->dir, m);
            if (exists(path)) return report_failure(x, m, path);
        }
        if (!missing) return EXIT_OK;
        if (now_s() >= deadline) return report_timeout(x, i);
        sleep_s(delay);
        delay = fmin(delay * 1.5, 0.2);
    }
}

int tune_exchange_share(tune_exchange *x, const char *set, int first, int count, double *mse, float *radius)
{
    const int i = x->next++;
    char name[64];
    snprintf(name, sizeof name, "eval-%d.shard-%d", i, x->shard.index);
    record_body b = {.set = set, .evaluation = i, .first = first, .count = count, .mse = mse, .radius = radius};
    int code = write_record(x, name, &b);
    if (code == EXIT_OK) code = wait_all(x, i, set, first, count, mse, radius);
    if (code == EXIT_OK && i > 0) {
        /* Every shard has written evaluation i, so has read every record of i - 1: ours can go. */
        char path[4400];
        snprintf(path, sizeof path, "%s/eval-%d.shard-%d", x->dir, i - 1, x->shard.index);
        unlink(path);
    }
    return code;
}
