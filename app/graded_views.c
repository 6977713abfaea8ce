/* scenes/views.json: the choose and check views (graded_views.h). */
#include "graded_views.h"

#include <cjson/cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "obscura/scene.h"

static int read_set(const cli_view_sets *s, const cJSON *root, const char *name, char (*out)[128], int *count)
{
    const cJSON *a = cJSON_GetObjectItemCaseSensitive(root, name);
    if (!cJSON_IsArray(a)) return cli_fail(EXIT_INPUT, "%s: \"%s\" is missing or not an array of views", s->path, name);
    int n = 0;
    for (const cJSON *e = a->child; e; e = e->next) {
        const char *v = cJSON_IsString(e) ? e->valuestring : NULL;
        if (!v || !*v || !strchr(v, ':') || strlen(v) >= sizeof out[0])
            return cli_fail(EXIT_INPUT, "%s: \"%s\"[%d] is not a \"scene:camera\" string of at most %zu bytes", s->path,
                            name, n, sizeof out[0] - 1);
        if (n >= CLI_VIEW_SET_MAX) return cli_fail(EXIT_INPUT, "%s: \"%s\" holds more than %d views", s->path, name, CLI_VIEW_SET_MAX);
        for (int k = 0; k < n; ++k)
            if (!strcmp(out[k], v)) return cli_fail(EXIT_INPUT, "%s: \"%s\" names %s twice", s->path, name, v);
        snprintf(out[n++], sizeof out[0], "%s", v);
    }
    *count = n;
    return EXIT_OK;
}

int cli_view_sets_load(cli_view_sets *out, bool required)
{
    memset(out, 0, sizeof *out);
    snprintf(out->path, sizeof out->path, "%s/scenes/views.json", ob_data_dir());
    char why[256] = "";
    char *text = cli_read_regular(out->path, 1u << 20, NULL, why, sizeof why);
    if (!text && !required) return EXIT_OK;
    if (!text) return cli_fail(EXIT_INPUT, "%s: cannot read the project's view sets: %s", out->path, why);
    cJSON *root = cJSON_Parse(text);
    free(text);
    if (!cJSON_IsObject(root)) {
        cJSON_Delete(root);
        return cli_fail(EXIT_INPUT, "%s: not a JSON object", out->path);
    }
    int code = read_set(out, root, "choose", out->choose, &out->choose_count);
    if (code == EXIT_OK) code = read_set(out, root, "check", out->check, &out->check_count);
    cJSON_Delete(root);
    for (int i = 0; code == EXIT_OK && i < out->check_count; ++i)
        for (int k = 0; k < out->choose_count; ++k)
            if (!strcmp(out->check[i], out->choose[k]))
                code = cli_fail(EXIT_INPUT, "%s: %s is both a choose and a check view", out->path, out->check[i]);
    return code;
}

const char *cli_view_set_of(const cli_view_sets *s, const char *view)
{
    for (int i = 0; i < s->check_count; ++i)
        if (!strcmp(s->check[i], view)) return "check";
    for (int i = 0; i < s->choose_count; ++i)
        if (!strcmp(s->choose[i], view)) return "choose";
    return NULL;
}
