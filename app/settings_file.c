/* Tuned settings files (settings_file.h). */
#include "settings_file.h"

#include <cjson/cJSON.h>
#include <dirent.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"

/* One file into *t: the method, and each parameter as an assignment checked on fresh settings. */
static int load_file(const char *path, cli_tuned *t)
{
    memset(t, 0, sizeof *t);
    if (strlen(path) >= sizeof t->path)
        return cli_fail(EXIT_USAGE, "--settings %s: a path of %zu bytes; expected at most %zu", path, strlen(path),
                        sizeof t->path - 1);
    snprintf(t->path, sizeof t->path, "%s", path);
    /* A settings file is a few hundred bytes; 1 MiB is far beyond any real one. A FIFO or a
     * device in its place is refused before a byte is read (it would block or never end). */
    char why[200] = "";
    char *text = cli_read_regular(path, 1u << 20, NULL, why, sizeof why);
    if (!text) return cli_fail(EXIT_USAGE, "--settings %s: cannot read it: %s", path, why);
    const char *end = NULL;
    cJSON *root = cJSON_ParseWithOpts(text, &end, 1);
    int line = 1, col = 1; /* where the parse stopped, for the message */
    for (const char *ch = text; !root && end && ch < end && *ch; ++ch) {
        col = *ch == '\n' ? 1 : col + 1;
        line += *ch == '\n';
    }
    free(text);
    int code = EXIT_OK;
    const cJSON *method = root ? cJSON_GetObjectItemCaseSensitive(root, "method") : NULL;
    const cJSON *params = root ? cJSON_GetObjectItemCaseSensitive(root, "params") : NULL;
    if (!root) {
        code = cli_fail(EXIT_USAGE, "--settings %s: not valid JSON (error near line %d, column %d); expected an object "
                        "{\"method\": ..., \"params\": {...}}", path, line, col);
    } else if (!cJSON_IsObject(root)) {
        code = cli_fail(EXIT_USAGE, "--settings %s: expected a JSON object {\"method\": ..., \"params\": {...}}, got %s", path,
                        cJSON_IsArray(root) ? "an array" : cJSON_IsString(root) ? "a string" : cJSON_IsNumber(root) ? "a number" : "a literal");
    } else if (!cJSON_IsString(method) || (t->method = ob_find_method(method->valuestring)) < 0) {
        code = cli_fail(EXIT_USAGE, "--settings %s: \"method\" must name a method (see obscura list), got %s", path,
                        cJSON_IsString(method) ? method->valuestring : "no string");
    } else if (!cJSON_IsObject(params)) {
        code = cli_fail(EXIT_USAGE, "--settings %s: \"params\" must be an object of parameter values", path);
    }
    ob_settings check;
    if (code == EXIT_OK) ob_settings_init(&check, method->valuestring);
    const cJSON *p = NULL;
    if (code == EXIT_OK) cJSON_ArrayForEach(p, params)
    {
        if (t->count >= CLI_MAX_TUNED_PARAMS) {
            code = cli_fail(EXIT_USAGE, "--settings %s: more than %d parameters", path, CLI_MAX_TUNED_PARAMS);
            break;
        }
        char value[64];
        int vlen = 0;
        if (cJSON_IsNumber(p)) vlen = snprintf(value, sizeof value, "%.9g", p->valuedouble);
        else if (cJSON_IsString(p)) vlen = snprintf(value, sizeof value, "%s", p->valuestring);
        else if (cJSON_IsBool(p)) vlen = snprintf(value, sizeof value, "%s", cJSON_IsTrue(p) ? "on" : "off");
        else {
            code = cli_fail(EXIT_USAGE, "--settings %s: %s.%s must be a number, an option name or on/off", path,
                            method->valuestring, p->string);
            break;
        }
        /* Cut to fit, a value or a name could turn into another one: refused whole instead. */
        if (vlen < 0 || (size_t)vlen >= sizeof value) {
            code = cli_fail(EXIT_USAGE, "--settings %s: %s.%s: a value of %d characters; expected a number, an option "
                            "name or on/off (at most %zu characters)", path, method->valuestring, p->string, vlen,
                            sizeof value - 1);
            break;
        }
        char *a = t->assignments[t->count];
        int alen = snprintf(a, sizeof t->assignments[0], "%s.%s=%s", method->valuestring, p->string, value);
        if (alen < 0 || (size_t)alen >= sizeof t->assignments[0]) {
            code = cli_fail(EXIT_USAGE, "--settings %s: parameter name '%.40s...' of %zu characters: %s has no "
                            "parameter that long (see obscura list)", path, p->string, strlen(p->string),
                            method->valuestring);
            break;
        }
        if (ob_settings_set(&check, a) != OB_OK) {
            const char *msg = NULL;
            ob_get_error(&msg);
            code = cli_fail(EXIT_USAGE, "--settings %s: %s", path, msg ? msg : a);
            break;
        }
        ++t->count;
    }
    cJSON_Delete(root);
    return code;
}

static int by_name(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

int cli_tuned_load(const char *path, cli_tuned *out, int max, int *count)
{
    *count = 0;
    struct stat st;
    if (stat(path, &st) != 0)
        return cli_fail(EXIT_USAGE, "--settings %s: cannot read it: %s", path, errno == ENOENT ? "no such file" : strerror(errno));
    if (!S_ISDIR(st.st_mode)) {
        int code = load_file(path, &out[0]);
        if (code == EXIT_OK) *count = 1;
        return code;
    }
    DIR *d = opendir(path);
    if (!d) return cli_fail(EXIT_USAGE, "--settings %s: %s", path, strerror(errno));
    char *names[CLI_MAX_TUNED_FILES];
    int n = 0, code = EXIT_OK;
    for (struct dirent *e; (e = readdir(d)) != NULL;) {
        size_t len = strlen(e->d_name);
        if (len <= 5 || strcmp(e->d_name + len - 5, ".json") != 0) continue;
        if (n >= max || n >= CLI_MAX_TUNED_FILES) {
            code = cli_fail(EXIT_USAGE, "--settings %s: more than %d settings files", path, max);
            break;
        }
        names[n++] = strdup(e->d_name);
    }
    closedir(d);
    qsort(names, (size_t)n, sizeof names[0], by_name);
    if (code == EXIT_OK && n == 0) code = cli_fail(EXIT_USAGE, "--settings %s: no *.json settings in the directory", path);
    for (int i = 0; i < n && code == EXIT_OK; ++i) {
        char file[1024];
        if (snprintf(file, sizeof file, "%s/%s", path, names[i]) >= (int)sizeof file) {
            code = cli_fail(EXIT_USAGE, "--settings %s: %s: a path longer than %zu bytes", path, names[i], sizeof file - 1);
            break;
        }
        code = load_file(file, &out[i]);
        for (int j = 0; j < i && code == EXIT_OK; ++j)
            if (out[j].method == out[i].method)
                code = cli_fail(EXIT_USAGE, "--settings %s: %s and %s both tune %s", path, out[j].path, out[i].path,
                                ob_method_at(out[i].method)->name);
    }
    for (int i = 0; i < n; ++i) free(names[i]);
    if (code == EXIT_OK) *count = n;
    return code;
}

int cli_tuned_apply(const cli_tuned *t, ob_settings *s)
{
    for (int i = 0; i < t->count; ++i)
        if (ob_settings_set(s, t->assignments[i]) != OB_OK) return cli_fail_from_library();
    return EXIT_OK;
}
