/* obscura list [--json]: the method registry (with every parameter) and the scenes. */
#include <cjson/cJSON.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "outputs.h"

static const char *type_name(ob_param_type t)
{
    return t == OB_PARAM_INT ? "int" : t == OB_PARAM_BOOL ? "bool" : t == OB_PARAM_ENUM ? "enum" : "float";
}

/* Named scenes: scenes/NAME.obscura.json under the data directory. */
static int named_scenes(char names[][64], int max)
{
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/scenes", ob_data_dir());
    DIR *d = opendir(dir);
    if (!d) return 0;
    int n = 0;
    const char *suffix = ".obscura.json";
    for (struct dirent *e; (e = readdir(d)) != NULL && n < max;) {
        size_t len = strlen(e->d_name), sl = strlen(suffix);
        if (len <= sl || strcmp(e->d_name + len - sl, suffix) != 0 || len - sl >= 64) continue;
        snprintf(names[n], 64, "%.*s", (int)(len - sl), e->d_name);
        ++n;
    }
    closedir(d);
    qsort(names, (size_t)n, 64, (int (*)(const void *, const void *))strcmp);
    return n;
}

/* One registry (methods or filters) as a JSON array of tables. */
static void add_tables_json(cJSON *root, const char *key, int count, const ob_method_info *(*at)(int))
{
    cJSON *arr = cJSON_AddArrayToObject(root, key);
    for (int i = 0; i < count; ++i) {
        const ob_method_info *m = at(i);
        cJSON *jm = cJSON_CreateObject();
        cJSON_AddStringToObject(jm, "name", m->name);
        cJSON_AddStringToObject(jm, "description", m->description);
        cJSON_AddStringToObject(jm, "reference", m->reference);
        cJSON *params = cJSON_AddArrayToObject(jm, "params");
        for (int p = 0; p < m->param_count; ++p) {
            const ob_param_info *pi = &m->params[p];
            cJSON *jp = cJSON_CreateObject();
            cJSON_AddStringToObject(jp, "name", pi->name);
            cJSON_AddStringToObject(jp, "type", type_name(pi->type));
            cJSON_AddNumberToObject(jp, "min", pi->min);
            cJSON_AddNumberToObject(jp, "max", pi->max);
            cJSON_AddNumberToObject(jp, "default", pi->def);
            cJSON_AddStringToObject(jp, "unit", pi->unit);
            cJSON_AddStringToObject(jp, "help", pi->help);
            cJSON_AddBoolToObject(jp, "follows_scene_radius", pi->follows_scene_radius);
            if (pi->type == OB_PARAM_ENUM) {
                cJSON *opts = cJSON_AddArrayToObject(jp, "options");
                for (int o = 0; o <= (int)pi->max; ++o) cJSON_AddItemToArray(opts, cJSON_CreateString(pi->options[o]));
                cJSON_ReplaceItemInObject(jp, "default", cJSON_CreateString(pi->options[(int)pi->def]));
            }
            cJSON_AddItemToArray(params, jp);
        }
        cJSON_AddItemToArray(arr, jm);
    }
}

static int list_json(void)
{
    cJSON *root = cJSON_CreateObject();
    add_tables_json(root, "methods", ob_method_count(), ob_method_at);
    add_tables_json(root, "filters", ob_filter_count(), ob_filter_at);
    cJSON *builtin = cJSON_AddArrayToObject(root, "builtin_scenes");
    for (int i = 0; i < ob_builtin_scene_count(); ++i) {
        cJSON *js = cJSON_CreateObject();
        cJSON_AddStringToObject(js, "name", ob_builtin_scene_name(i));
        cJSON_AddStringToObject(js, "description", ob_builtin_scene_description(i));
        cJSON_AddItemToArray(builtin, js);
    }
    char names[64][64];
    int n = named_scenes(names, 64);
    cJSON *named = cJSON_AddArrayToObject(root, "named_scenes");
    for (int i = 0; i < n; ++i) cJSON_AddItemToArray(named, cJSON_CreateString(names[i]));
    char *printed = cJSON_Print(root);
    /* Names come from files (scene and camera names): valid UTF-8 for the JSON's readers. */
    char *text = printed ? cli_utf8_valid(printed) : NULL;
    free(printed);
    int code = text ? EXIT_OK : cli_fail(EXIT_RUNTIME, "out of memory");
    if (text) puts(text);
    free(text);
    cJSON_Delete(root);
    return code;
}

static void print_tables(int count, const ob_method_info *(*at)(int))
{
    for (int i = 0; i < count; ++i) {
        const ob_method_info *m = at(i);
        printf("\n  %-14s %s\n                 [%s]\n", m->name, m->description, m->reference);
        for (int p = 0; p < m->param_count; ++p) {
            const ob_param_info *pi = &m->params[p];
            if (pi->type == OB_PARAM_ENUM) {
                char opts[128] = "";
                for (int o = 0; o <= (int)pi->max; ++o) {
                    size_t n = strlen(opts);
                    snprintf(opts + n, sizeof opts - n, "%s%s", o ? "|" : "", pi->options[o]);
                }
                printf("    %-14s %-5s default %-8s %-30s %s\n", pi->name, type_name(pi->type), pi->options[(int)pi->def],
                       opts, pi->help);
                continue;
            }
            printf("    %-14s %-5s default %-8g range [%g, %g] %-9s %s\n", pi->name, type_name(pi->type),
                   (double)pi->def, (double)pi->min, (double)pi->max, pi->unit, pi->help);
        }
    }
}

static int list_human(void)
{
    printf("methods (--method NAME, --set NAME.PARAM=VALUE):\n");
    print_tables(ob_method_count(), ob_method_at);
    printf("\n  every method:\n    %-14s %-5s default %-8g range [%g, %g] %-9s %s\n", "radius_scale", "float", 1.0,
           (double)OB_RADIUS_SCALE_MIN, (double)OB_RADIUS_SCALE_MAX, "x radius",
           "occluder radius = scale x R: a wider search, graded at the same R");
    printf("\nfilters (--filter NAME, --set NAME.PARAM=VALUE):\n");
    print_tables(ob_filter_count(), ob_filter_at);
    printf("\nbuilt-in scenes (--scene NAME):\n");
    for (int i = 0; i < ob_builtin_scene_count(); ++i)
        printf("  %-16s %s\n", ob_builtin_scene_name(i), ob_builtin_scene_description(i));
    char names[64][64];
    int n = named_scenes(names, 64);
    printf("\nnamed scenes (scenes/NAME.obscura.json):\n");
    for (int i = 0; i < n; ++i) printf("  %s\n", names[i]);
    printf("\nor --scene PATH to any model Assimp reads (OBJ, glTF/GLB, PLY, 3DS, IFC, ...)\n");
    return EXIT_OK;
}

int cmd_list(int argc, char **argv)
{
    bool json = false;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--json")) json = true;
        else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            puts("usage: obscura list [--json]\n\nPrints every AO method with its parameters (name, type, default,\n"
                 "range, unit, help) and the built-in and named scenes.");
            return EXIT_OK;
        } else {
            return cli_fail(EXIT_USAGE, "list: unknown option '%s'", argv[i]);
        }
    }
    return json ? list_json() : list_human();
}
