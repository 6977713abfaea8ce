/* obscura merge: the N shards of one compare run (compare --shard K/N, each on its own machine)
 * into the report the unsharded run writes. A shard's report holds its views as any report does,
 * its results.json names the run (its command line) and which view went to which shard, and
 * REPORT/shard.bin holds what it found per view as the report writers take it (view_result and
 * method_result, compare.h). The merge checks that the shards are of one run and that each of
 * its N shards is there once, re-reads the run's command line with compare's own parser (the
 * rows, their labels and settings), orders the views as --scene gave them, copies each view's
 * images, and writes results.json and index.html with compare's writers: the same report, whose
 * numbers are the shards' (bit for bit where the work is deterministic: everything but timings). */
#include <cjson/cJSON.h>
#include <dirent.h>
#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "compare.h"
#include "suggest.h"

/* 2: each row carries its index among the run's rows (a shard of --shard-unit row has some). */
#define SHARD_MAGIC "obscura compare shard 2\n"

enum { MAX_MERGE_ROWS = 4096 }; /* rows of one view a shard may give */

typedef struct shard_header {
    uint32_t view_size, method_size, flicker_size, views, methods;
} shard_header;

/* A variant's per-frame RMSE curve: a flag, then flicker_ref.frames doubles when it has one. */
static bool write_curve(FILE *f, const double *curve, int frames)
{
    const uint8_t has = curve != NULL;
    return fwrite(&has, 1, 1, f) == 1 && (!has || fwrite(curve, sizeof *curve, (size_t)frames, f) == (size_t)frames);
}

/* --path/--orbit: a flag, then each row's flicker metrics (pointers cleared) and their curves. The
 * worst frames' images are in the view's directory already (STEM_temporal_worst.png). */
static bool write_flicker(FILE *f, const view_result *vr)
{
    const uint8_t has = vr->flicker != NULL;
    bool ok = fwrite(&has, 1, 1, f) == 1;
    for (int k = 0; has && ok && k < vr->method_count; ++k) {
        cli_flicker_row row = vr->flicker[k];
        row.config = NULL;
        row.off.rmse_frames = row.on.rmse_frames = NULL;
        row.off.worst_ao = row.on.worst_ao = NULL;
        ok = fwrite(&row, sizeof row, 1, f) == 1 && write_curve(f, vr->flicker[k].off.rmse_frames, vr->flicker_ref.frames) &&
             write_curve(f, vr->flicker[k].on.rmse_frames, vr->flicker_ref.frames);
    }
    return ok;
}

int compare_write_shard(const compare_opts *o, const cli_config *configs, const view_result *views, int count,
                        report_files *out)
{
    char path[900];
    snprintf(path, sizeof path, "%s/shard.bin", o->report);
    if (!compare_track_file(out, path)) return cli_fail(EXIT_RUNTIME, "out of memory");
    FILE *f = fopen(path, "wb");
    if (!f) return cli_fail(EXIT_OUTPUT, "cannot write %s: %s", path, strerror(errno));
    shard_header h = {(uint32_t)sizeof(view_result), (uint32_t)sizeof(method_result), (uint32_t)sizeof(cli_flicker_row),
                      (uint32_t)count, count > 0 ? (uint32_t)views[0].method_count : 0u};
    bool ok = fputs(SHARD_MAGIC, f) >= 0 && fprintf(f, "%s\n", OB_VERSION_STRING) > 0 && fwrite(&h, sizeof h, 1, f) == 1;
    for (int v = 0; v < count && ok; ++v) {
        /* Pointers mean nothing in another process: the reader sets them again. */
        view_result vr = views[v];
        vr.methods = NULL;
        vr.flicker = NULL;
        vr.set = NULL;
        ok = fwrite(&vr, sizeof vr, 1, f) == 1;
        for (int k = 0; k < views[v].method_count && ok; ++k) {
            method_result m = views[v].methods[k];
            const uint32_t row = (uint32_t)(m.config - configs); /* its index among the run's rows */
            m.config = NULL;
            ok = fwrite(&row, sizeof row, 1, f) == 1 && fwrite(&m, sizeof m, 1, f) == 1;
        }
        if (ok) ok = write_flicker(f, &views[v]);
    }
    int e = errno;
    if (fclose(f) != 0 && ok) {
        ok = false;
        e = errno;
    }
    return ok ? EXIT_OK : cli_fail(EXIT_OUTPUT, "cannot write %s: %s", path, strerror(e));
}

/* ---- obscura merge ---------------------------------------------------------------------------- */

typedef struct shard_in {
    const char *dir;
    cJSON *json;       /* its results.json */
    int index, count;  /* K and N */
    char **args;       /* its command line without --shard K/N and --report DIR */
    int arg_count;
    bool has[MAX_VIEWS]; /* the views it ran (some of their rows, with --shard-unit row) */
} shard_in;

typedef struct merge_state {
    shard_in shards[CLI_MAX_SHARDS];
    int shard_count;
    const char *report;
    compare_opts o;          /* the run, as its command line says, with --report */
    cli_outputs outs;
    char **argv;             /* what o's parse read: the run's arguments and --report */
    int argc;
    cli_config *configs;
    int config_count;
    view_result views[MAX_VIEWS];
    bool *have[MAX_VIEWS];   /* per view, the rows read so far */
    int view_count;
    report_files out;
} merge_state;

static void merge_usage(FILE *f)
{
    fputs("usage: obscura merge SHARD_DIR... [--report DIR]\n"
          "\n"
          "The reports of the N shards of one compare run (obscura compare ... --shard K/N, K = 0..N-1,\n"
          "each with its own --report) into the report the run writes without --shard: DIR/index.html,\n"
          "DIR/results.json and every view's images, the views in the run's --scene order. The shards\n"
          "must come from one command line (apart from --shard and --report) and one obscura version,\n"
          "and each of the N must be given once: a missing or repeated shard is named.\n"
          "\n"
          "  --report DIR          where the merged report goes, put in place only when whole (default\n"
          "                        " CLI_DEFAULT_REPORT "; an existing DIR is replaced only when empty or\n"
          "                        holding nothing but what this tool wrote)\n",
          f);
}

/* The run's arguments from a shard's command line: everything but --shard and --report (each with
 * its value), which differ from shard to shard. */
static int run_args(shard_in *s, const cJSON *cmd)
{
    int n = cJSON_GetArraySize(cmd);
    s->args = calloc((size_t)(n > 0 ? n : 1), sizeof *s->args);
    if (!s->args) return cli_fail(EXIT_RUNTIME, "out of memory");
    for (int i = 0; i < n; ++i) {
        const char *a = cJSON_GetStringValue(cJSON_GetArrayItem(cmd, i));
        if (!a) return cli_fail(EXIT_INPUT, "%s/results.json: command_line[%d] is not a string", s->dir, i);
        if (i > 0 && (!strcmp(a, "--shard") || !strcmp(a, "--report"))) {
            ++i;
            continue;
        }
        s->args[s->arg_count++] = (char *)a;
    }
    if (s->arg_count == 0 || strcmp(s->args[0], "compare"))
        return cli_fail(EXIT_INPUT, "%s/results.json: not the report of an obscura compare run", s->dir);
    return EXIT_OK;
}

/* DIR/results.json: the shard's K, N and the run's arguments. */
static int read_shard(shard_in *s)
{
    char path[4200], why[256] = "";
    snprintf(path, sizeof path, "%s/results.json", s->dir);
    char *text = cli_read_regular(path, 64u << 20, NULL, why, sizeof why);
    if (!text) return cli_fail(EXIT_INPUT, "%s: cannot read results.json: %s", s->dir, why);
    s->json = cJSON_Parse(text);
    free(text);
    if (!s->json) return cli_fail(EXIT_INPUT, "%s/results.json: not valid JSON", s->dir);
    const cJSON *sh = cJSON_GetObjectItemCaseSensitive(s->json, "shard");
    const cJSON *k = cJSON_GetObjectItemCaseSensitive(sh, "index"), *n = cJSON_GetObjectItemCaseSensitive(sh, "count");
    if (!cJSON_IsNumber(k) || !cJSON_IsNumber(n))
        return cli_fail(EXIT_USAGE, "%s: not a shard (its results.json has no \"shard\": run compare with --shard K/N)",
                        s->dir);
    s->index = k->valueint;
    s->count = n->valueint;
    if (s->count < 2 || s->count > CLI_MAX_SHARDS || s->index < 0 || s->index >= s->count)
        return cli_fail(EXIT_INPUT, "%s/results.json: shard %d/%d is out of range", s->dir, s->index, s->count);
    const cJSON *version = cJSON_GetObjectItemCaseSensitive(s->json, "version");
    if (!cJSON_IsString(version) || strcmp(version->valuestring, OB_VERSION_STRING))
        return cli_fail(EXIT_USAGE, "%s: written by obscura %s, this is %s: merge with the version that ran it", s->dir,
                        cJSON_IsString(version) ? version->valuestring : "(unknown)", OB_VERSION_STRING);
    return run_args(s, cJSON_GetObjectItemCaseSensitive(s->json, "command_line"));
}

/* One run, and each of its N shards once. */
static int check_shards(merge_state *m)
{
    const shard_in *first = &m->shards[0];
    int seen[CLI_MAX_SHARDS];
    for (int k = 0; k < first->count; ++k) seen[k] = -1;
    for (int i = 0; i < m->shard_count; ++i) {
        const shard_in *s = &m->shards[i];
        bool same = s->count == first->count && s->arg_count == first->arg_count;
        for (int a = 0; same && a < s->arg_count; ++a) same = !strcmp(s->args[a], first->args[a]);
        if (!same)
            return cli_fail(EXIT_USAGE, "%s and %s are shards of different runs (their command lines differ apart from "
                                        "--shard and --report, or their N)",
                            first->dir, s->dir);
        if (seen[s->index] >= 0)
            return cli_fail(EXIT_USAGE, "shard %d/%d is given twice: %s and %s", s->index, s->count,
                            m->shards[seen[s->index]].dir, s->dir);
        seen[s->index] = i;
    }
    for (int k = 0; k < first->count; ++k)
        if (seen[k] < 0)
            return cli_fail(EXIT_USAGE, "shard %d/%d is missing (%d of %d given): run compare ... --shard %d/%d and add "
                                        "its report",
                            k, first->count, m->shard_count, first->count, k, first->count);
    return EXIT_OK;
}

/* The run's options through compare's parser, with --report: the rows and their settings. */
static int parse_run(merge_state *m)
{
    const shard_in *s = &m->shards[0];
    m->argc = s->arg_count + 2;
    m->argv = calloc((size_t)m->argc + 1, sizeof *m->argv);
    if (!m->argv) return cli_fail(EXIT_RUNTIME, "out of memory");
    for (int a = 0; a < s->arg_count; ++a) m->argv[a] = s->args[a];
    m->argv[s->arg_count] = "--report";
    m->argv[s->arg_count + 1] = (char *)m->report;
    int code = compare_parse(m->argc, m->argv, &m->o, &m->outs);
    if (code < 0) code = cli_fail(EXIT_INPUT, "%s/results.json: its command line asks for help, not a report", s->dir);
    /* Which shard ran each view, as the shards computed it; the merged report is no shard. */
    if (code == EXIT_OK) compare_assign_shards(&m->o, s->count);
    if (code == EXIT_OK) code = cli_common_configs(&m->o.common, &m->configs, &m->config_count);
    if (code == EXIT_OK && m->o.by_row) code = compare_assign_rows(&m->o, m->configs, m->config_count, s->count);
    const cJSON *r = cJSON_GetObjectItemCaseSensitive(s->json, "renderer");
    const cJSON *g = cJSON_GetObjectItemCaseSensitive(s->json, "gl_version");
    snprintf(m->o.renderer, sizeof m->o.renderer, "%s", cJSON_IsString(r) ? r->valuestring : "(unknown)");
    snprintf(m->o.gl_version, sizeof m->o.gl_version, "%s", cJSON_IsString(g) ? g->valuestring : "(unknown)");
    return code;
}

/* A view's directory name as compare makes it: letters, digits, '-' and '_' (nothing that leaves
 * the report). */
static bool safe_dir(const char *d, size_t n)
{
    if (!memchr(d, '\0', n) || !*d) return false;
    for (; *d; ++d)
        if (!((*d >= 'a' && *d <= 'z') || (*d >= 'A' && *d <= 'Z') || (*d >= '0' && *d <= '9') || *d == '-' || *d == '_'))
            return false;
    return true;
}

static bool byte_bool(const bool *b)
{
    unsigned char c;
    memcpy(&c, b, 1);
    return c != 0;
}

/* A curve written by write_curve, into *curve (NULL when it had none). */
static int read_curve(FILE *f, double **curve, int frames, const char *path)
{
    uint8_t has = 0;
    if (fread(&has, 1, 1, f) != 1 || has > 1) return cli_fail(EXIT_INPUT, "%s: truncated", path);
    if (!has) return EXIT_OK;
    *curve = malloc((size_t)frames * sizeof **curve);
    if (!*curve) return cli_fail(EXIT_RUNTIME, "out of memory");
    return fread(*curve, sizeof **curve, (size_t)frames, f) == (size_t)frames ? EXIT_OK : cli_fail(EXIT_INPUT, "%s: truncated", path);
}

/* The view's flicker rows (write_flicker), which a --path/--orbit run has and no other: the
 * shard's rows, at their indices row[j] among the run's. */
static int read_flicker(merge_state *m, view_result *vr, const int *row, int rows, FILE *f, const char *path)
{
    uint8_t has = 0;
    if (fread(&has, 1, 1, f) != 1 || has > 1) return cli_fail(EXIT_INPUT, "%s: truncated", path);
    if ((has != 0) != cli_common_moves(&m->o.common))
        return cli_fail(EXIT_INPUT, "%s: flicker rows %s the run's --path/--orbit", path, has ? "without" : "missing for");
    if (!has) return EXIT_OK;
    if (vr->flicker_ref.frames < 1 || vr->flicker_ref.frames > 1 << 16)
        return cli_fail(EXIT_INPUT, "%s: %d path frames", path, vr->flicker_ref.frames);
    if (!vr->flicker) vr->flicker = calloc((size_t)m->config_count, sizeof *vr->flicker);
    if (!vr->flicker) return cli_fail(EXIT_RUNTIME, "out of memory");
    int code = EXIT_OK;
    for (int j = 0; j < rows && code == EXIT_OK; ++j) {
        cli_flicker_row *r = &vr->flicker[row[j]];
        if (fread(r, sizeof *r, 1, f) != 1) return cli_fail(EXIT_INPUT, "%s: truncated", path);
        r->config = &m->configs[row[j]];
        r->off.rmse_frames = r->on.rmse_frames = NULL;
        r->off.worst_ao = r->on.worst_ao = NULL;
        code = read_curve(f, &r->off.rmse_frames, vr->flicker_ref.frames, path);
        if (code == EXIT_OK) code = read_curve(f, &r->on.rmse_frames, vr->flicker_ref.frames, path);
    }
    return code;
}

/* A row of a view: its index among the run's rows, which this shard must own and no shard have
 * given before, then the row into vr->methods[*row]. */
static int read_row(merge_state *m, const shard_in *s, int v, FILE *f, const char *path, int *row)
{
    uint32_t k = 0;
    if (fread(&k, sizeof k, 1, f) != 1) return cli_fail(EXIT_INPUT, "%s: truncated", path);
    if (k >= (uint32_t)m->config_count || compare_row_owner(&m->o, v, (int)k) != s->index)
        return cli_fail(EXIT_INPUT, "%s: a row that is not this run's shard %d's", path, s->index);
    if (m->have[v][k]) return cli_fail(EXIT_INPUT, "%s: view %d row %u twice", path, v, k);
    m->have[v][k] = true;
    method_result *mr = &m->views[v].methods[k];
    if (fread(mr, sizeof *mr, 1, f) != 1) return cli_fail(EXIT_INPUT, "%s: truncated", path);
    mr->config = &m->configs[k];
    mr->directional = byte_bool(&mr->directional);
    mr->pareto = byte_bool(&mr->pareto);
    mr->name[sizeof mr->name - 1] = mr->label[sizeof mr->label - 1] = mr->stem[sizeof mr->stem - 1] = '\0';
    /* The stem names the row's images in index.html: never a path out of the view's directory. */
    if (!mr->stem[0] || mr->stem[0] == '.' || strpbrk(mr->stem, "/\\"))
        return cli_fail(EXIT_INPUT, "%s: a row's image name leaves the report", path);
    *row = (int)k;
    return EXIT_OK;
}

/* One view of a shard's shard.bin: its rows into m->views[vr.index] at their indices. A view split
 * by rows comes from several shards; the first record of it gives the view's own fields (the same
 * G-buffer, reference and masks in each). */
static int read_view(merge_state *m, shard_in *s, FILE *f, const char *path)
{
    view_result vr;
    if (fread(&vr, sizeof vr, 1, f) != 1) return cli_fail(EXIT_INPUT, "%s: truncated", path);
    if (vr.index < 0 || vr.index >= m->o.view_count || vr.method_count < 1 || vr.method_count > m->config_count ||
        !safe_dir(vr.dir, sizeof vr.dir) || !memchr(vr.scene, '\0', sizeof vr.scene) ||
        !memchr(vr.camera, '\0', sizeof vr.camera))
        return cli_fail(EXIT_INPUT, "%s: a view that is not this run's shard %d's", path, s->index);
    const int v = vr.index;
    if (s->has[v]) return cli_fail(EXIT_INPUT, "%s: view %d twice", path, v);
    s->has[v] = true;
    view_result *into = &m->views[v];
    if (!into->methods) {
        /* A bool read from a file may hold any byte: only 0 and 1 are bools. */
        vr.ref_cached = byte_bool(&vr.ref_cached);
        vr.has_bounce = byte_bool(&vr.has_bounce);
        vr.flicker = NULL;
        vr.set = NULL;
        vr.methods = calloc((size_t)m->config_count, sizeof *vr.methods);
        m->have[v] = calloc((size_t)m->config_count, sizeof *m->have[v]);
        *into = vr;
        into->method_count = m->config_count; /* every row's place, filled by the shards that own them */
        if (!into->methods || !m->have[v]) return cli_fail(EXIT_RUNTIME, "out of memory");
    } else if (strcmp(into->dir, vr.dir)) {
        return cli_fail(EXIT_INPUT, "%s: view %d is %s here and %s in another shard", path, v, vr.dir, into->dir);
    }
    int row[MAX_MERGE_ROWS], code = EXIT_OK;
    if (vr.method_count > MAX_MERGE_ROWS) return cli_fail(EXIT_INPUT, "%s: %d rows in a view", path, vr.method_count);
    for (int j = 0; j < vr.method_count && code == EXIT_OK; ++j) code = read_row(m, s, v, f, path, &row[j]);
    return code == EXIT_OK ? read_flicker(m, into, row, vr.method_count, f, path) : code;
}

/* SHARD/shard.bin: the views the shard ran. */
static int read_views(merge_state *m, shard_in *s)
{
    char path[4200], version[64] = "", magic[sizeof SHARD_MAGIC] = "";
    snprintf(path, sizeof path, "%s/shard.bin", s->dir);
    FILE *f = fopen(path, "rb");
    if (!f) return cli_fail(EXIT_INPUT, "%s: %s", path, strerror(errno));
    shard_header h = {0};
    int code = EXIT_OK;
    if (!fgets(magic, sizeof magic, f) || strcmp(magic, SHARD_MAGIC) || !fgets(version, sizeof version, f) ||
        strncmp(version, OB_VERSION_STRING, strlen(OB_VERSION_STRING)) || fread(&h, sizeof h, 1, f) != 1 ||
        h.view_size != sizeof(view_result) || h.method_size != sizeof(method_result) ||
        h.flicker_size != sizeof(cli_flicker_row))
        code = cli_fail(EXIT_INPUT, "%s: not a shard file of this obscura (%s) build", path, OB_VERSION_STRING);
    for (uint32_t v = 0; v < h.views && code == EXIT_OK; ++v) code = read_view(m, s, f, path);
    fclose(f);
    return code;
}

/* Every file of a view's directory, from its shard's report into the merged one. */
static int copy_view(merge_state *m, const char *from_root, const char *dir)
{
    char from[4400], to[1200];
    snprintf(from, sizeof from, "%s/%s", from_root, dir);
    snprintf(to, sizeof to, "%s/%s", m->o.report, dir);
    int code = compare_make_dir(&m->out, to);
    DIR *d = code == EXIT_OK ? opendir(from) : NULL;
    if (code == EXIT_OK && !d) return cli_fail(EXIT_INPUT, "%s: %s", from, strerror(errno));
    for (struct dirent *e; code == EXIT_OK && (e = readdir(d));) {
        if (e->d_name[0] == '.') continue;
        char src[4700], dst[1500], why[256] = "";
        snprintf(src, sizeof src, "%s/%s", from, e->d_name);
        snprintf(dst, sizeof dst, "%s/%s", to, e->d_name);
        size_t size = 0;
        char *bytes = cli_read_regular(src, 256u << 20, &size, why, sizeof why);
        if (!bytes) {
            code = cli_fail(EXIT_INPUT, "%s: %s", src, why);
            break;
        }
        FILE *f = compare_track_file(&m->out, dst) ? fopen(dst, "wb") : NULL;
        bool ok = f && fwrite(bytes, 1, size, f) == size;
        if (f && fclose(f) != 0) ok = false;
        free(bytes);
        if (!ok) code = cli_fail(EXIT_OUTPUT, "cannot write %s", dst);
    }
    if (d) closedir(d);
    return code;
}

static int merge_parse(int argc, char **argv, merge_state *m)
{
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            merge_usage(stdout);
            return -1;
        }
        if (!strcmp(a, "--report")) {
            if (i + 1 >= argc) return cli_fail(EXIT_USAGE, "--report: missing value (see obscura merge --help)");
            m->report = argv[++i];
        } else if (a[0] == '-' && a[1]) {
            char hint[96];
            static const char *const own[] = {"--report", "--help"};
            return cli_fail(EXIT_USAGE, "merge: unknown option '%s'%s (see obscura merge --help)", a,
                            ob_suggest_text(a, strlen(a), own, 2, hint, sizeof hint));
        } else if (m->shard_count >= CLI_MAX_SHARDS) {
            return cli_fail(EXIT_USAGE, "merge: at most %d shards", CLI_MAX_SHARDS);
        } else {
            m->shards[m->shard_count++].dir = a;
        }
    }
    if (m->shard_count == 0) return cli_fail(EXIT_USAGE, "merge: no shard directories (see obscura merge --help)");
    if (!m->report) {
        m->report = CLI_DEFAULT_REPORT;
        printf("merge: no --report: the report goes to %s/ (--report DIR to choose)\n", m->report);
    }
    return EXIT_OK;
}

/* Every row of view v, each from the shard that owns it (read_row placed them). */
static int check_rows(merge_state *m, int v)
{
    for (int k = 0; k < m->config_count; ++k)
        if (!m->have[v][k])
            return cli_fail(EXIT_INPUT, "view %d (%s) row %d (%s) is in none of the shards' shard.bin (shard %d should "
                                        "have run it)",
                            v, m->o.views[v], k, m->configs[k].label, compare_row_owner(&m->o, v, k));
    return EXIT_OK;
}

static int merge_checked(merge_state *m)
{
    int code = EXIT_OK;
    for (int i = 0; i < m->shard_count && code == EXIT_OK; ++i) code = read_shard(&m->shards[i]);
    if (code == EXIT_OK) code = check_shards(m);
    if (code == EXIT_OK) code = parse_run(m);
    for (int i = 0; i < m->shard_count && code == EXIT_OK; ++i) code = read_views(m, &m->shards[i]);
    for (int v = 0; v < m->o.view_count && code == EXIT_OK; ++v)
        if (!m->views[v].methods)
            code = cli_fail(EXIT_INPUT, "view %d (%s) is in none of the shards' shard.bin (shard %d should have run it)", v,
                            m->o.views[v], compare_row_owner(&m->o, v, 0));
        else
            code = check_rows(m, v);
    m->view_count = m->o.view_count;
    const char *root = code == EXIT_OK ? cli_outputs_dir(m->o.outs, m->o.report_index) : NULL;
    if (code == EXIT_OK && !root) code = EXIT_OUTPUT;
    if (code == EXIT_OK) m->o.report = root;
    /* Each view's directory from every shard that ran some of it: the view's own images are the
     * same in each, the rows' images each shard's own. */
    for (int v = 0; v < m->view_count && code == EXIT_OK; ++v)
        for (int i = 0; i < m->shard_count && code == EXIT_OK; ++i)
            if (m->shards[i].has[v]) code = copy_view(m, m->shards[i].dir, m->views[v].dir);
    /* Split by rows, no shard saw a whole view: its Pareto front and chart are drawn here, from
     * every row, as the unsharded run draws them. */
    for (int v = 0; v < m->view_count && code == EXIT_OK && m->o.by_row; ++v) {
        compare_mark_pareto(&m->views[v]);
        code = compare_write_chart(&m->o, &m->views[v], &m->out);
    }
    if (code == EXIT_OK) code = compare_label_sets(m->views, m->view_count);
    if (code == EXIT_OK) code = compare_write_json(&m->o, m->views, m->view_count, &m->out);
    if (code == EXIT_OK) code = compare_write_html(&m->o, m->views, m->view_count, &m->out);
    return code;
}

static void merge_free(merge_state *m, bool failed)
{
    compare_files_finish(&m->out, failed);
    for (int v = 0; v < MAX_VIEWS; ++v) {
        free(m->have[v]);
        free(m->views[v].methods);
        cli_flicker_free(m->views[v].flicker, m->views[v].method_count);
        free(m->views[v].flicker);
    }
    for (int i = 0; i < m->shard_count; ++i) {
        free(m->shards[i].args);
        cJSON_Delete(m->shards[i].json);
    }
    free(m->configs);
    free(m->argv);
    free(m->o.row_owner);
}

int cmd_merge(int argc, char **argv)
{
    merge_state *m = calloc(1, sizeof *m);
    if (!m) return cli_fail(EXIT_RUNTIME, "out of memory");
    int code = merge_parse(argc, argv, m);
    const bool help = code < 0;
    m->o.outs = &m->outs;
    if (code == EXIT_OK) code = merge_checked(m);
    merge_free(m, code > 0);
    code = cli_outputs_finish(&m->outs, help ? EXIT_OK : code);
    if (code == EXIT_OK && !help) printf("report: %s/index.html\n", m->report);
    free(m);
    return code;
}
