/* obscura list [--json]: the method registry (with every parameter), the filters, the views and
 * every scene with its camera presets. README.md's lists are checked against the JSON
 * (tests/test_readme.sh), so what this prints is what the docs may say. */
#include <cjson/cJSON.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "suggest.h"
#include "outputs.h"

static const char *type_name(ob_param_type t)
{
    return t == OB_PARAM_INT ? "int" : t == OB_PARAM_BOOL ? "bool" : t == OB_PARAM_ENUM ? "enum" : "float";
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

/* A scene's camera presets, loaded the way --scene loads it (sidecar presets and a model's own
 * cameras included: no other source knows them all). NULL, with the library's message in *why,
 * when the scene cannot be loaded (a named scene whose model is not installed). */
static ob_scene *load_for_cameras(const char *name, const char **why)
{
    ob_scene *scene = ob_load_scene(&(ob_scene_desc){.name = name});
    *why = NULL;
    if (!scene) ob_get_error(why);
    return scene;
}

static cJSON *cameras_json(const ob_scene *scene)
{
    cJSON *arr = cJSON_CreateArray();
    for (int c = 0; scene && c < ob_query_camera_count(scene); ++c)
        cJSON_AddItemToArray(arr, cJSON_CreateString(ob_query_camera(scene, c).name));
    return arr;
}

/* One entry of "scenes": name, kind, description (built-ins), cameras (or the load error). */
static void add_scene_json(cJSON *scenes, const char *name, const char *kind, const char *description)
{
    cJSON *js = cJSON_CreateObject();
    cJSON_AddStringToObject(js, "name", name);
    cJSON_AddStringToObject(js, "kind", kind);
    if (description) cJSON_AddStringToObject(js, "description", description);
    const char *why = NULL;
    ob_scene *scene = load_for_cameras(name, &why);
    if (scene) cJSON_AddItemToObject(js, "cameras", cameras_json(scene));
    else cJSON_AddStringToObject(js, "error", why ? why : "cannot be loaded");
    ob_destroy_scene(scene);
    cJSON_AddItemToArray(scenes, js);
}

static int list_json(void)
{
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "default_method", OB_DEFAULT_METHOD);
    add_tables_json(root, "methods", ob_method_count(), ob_method_at);
    add_tables_json(root, "filters", ob_filter_count(), ob_filter_at);
    cJSON *views = cJSON_AddArrayToObject(root, "views");
    for (int i = 0; i < OB_VIEW_COUNT; ++i) cJSON_AddItemToArray(views, cJSON_CreateString(ob_view_name((ob_view)i)));
    cJSON *builtin = cJSON_AddArrayToObject(root, "builtin_scenes");
    for (int i = 0; i < ob_builtin_scene_count(); ++i) {
        cJSON *js = cJSON_CreateObject();
        cJSON_AddStringToObject(js, "name", ob_builtin_scene_name(i));
        cJSON_AddStringToObject(js, "description", ob_builtin_scene_description(i));
        cJSON_AddItemToArray(builtin, js);
    }
    char names[64][64];
    int n = ob_named_scenes(names, 64);
    cJSON *named = cJSON_AddArrayToObject(root, "named_scenes");
    for (int i = 0; i < n; ++i) cJSON_AddItemToArray(named, cJSON_CreateString(names[i]));
    /* Every scene with its cameras; builtin_scenes and named_scenes above keep their old shape. */
    cJSON *scenes = cJSON_AddArrayToObject(root, "scenes");
    for (int i = 0; i < ob_builtin_scene_count(); ++i)
        add_scene_json(scenes, ob_builtin_scene_name(i), "builtin", ob_builtin_scene_description(i));
    for (int i = 0; i < n; ++i) add_scene_json(scenes, names[i], "named", NULL);
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

/* "cameras: a, b, c" after a scene's name (own_line: on a line of its own under the
 * description), or why there are none to show. */
static void print_cameras(const char *name, bool own_line)
{
    const char *why = NULL;
    ob_scene *scene = load_for_cameras(name, &why);
    printf("  %-16s cameras: ", own_line ? "" : name);
    if (!scene) {
        printf("(cannot load the scene: %s)\n", why ? why : "unknown error");
        return;
    }
    for (int c = 0; c < ob_query_camera_count(scene); ++c) printf("%s%s", c ? ", " : "", ob_query_camera(scene, c).name);
    printf("\n");
    ob_destroy_scene(scene);
}

static int list_human(void)
{
    printf("methods (--method NAME, default %s; --set NAME.PARAM=VALUE; the works in [brackets]:\n"
           "docs/references.md):\n", OB_DEFAULT_METHOD);
    print_tables(ob_method_count(), ob_method_at);
    printf("\n  every method:\n    %-14s %-5s default %-8g range [%g, %g] %-9s %s\n", "radius_scale", "float", 1.0,
           (double)OB_RADIUS_SCALE_MIN, (double)OB_RADIUS_SCALE_MAX, "x radius",
           "occluder radius = scale x R: a wider search, graded at the same R");
    printf("\nfilters (--filter NAME, --set NAME.PARAM=VALUE):\n");
    print_tables(ob_filter_count(), ob_filter_at);
    printf("\nviews (render --view NAME, the viewer's V):\n ");
    for (int i = 0; i < OB_VIEW_COUNT; ++i) printf(" %s", ob_view_name((ob_view)i));
    printf("\n\nbuilt-in scenes (--scene NAME, --camera NAME):\n");
    for (int i = 0; i < ob_builtin_scene_count(); ++i) {
        printf("  %-16s %s\n", ob_builtin_scene_name(i), ob_builtin_scene_description(i));
        print_cameras(ob_builtin_scene_name(i), true);
    }
    char names[64][64];
    int n = ob_named_scenes(names, 64);
    printf("\nnamed scenes (scenes/NAME.obscura.json, --camera NAME):\n");
    for (int i = 0; i < n; ++i) print_cameras(names[i], false);
    printf("\nor --scene PATH to any model Assimp reads (OBJ, glTF/GLB, PLY, 3DS, IFC, ...)\n");
    return EXIT_OK;
}

int cmd_list(int argc, char **argv)
{
    bool json = false;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--json")) json = true;
        else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            puts("usage: obscura list [--json]\n\nPrints every AO method and filter with its parameters (name, type,\n"
                 "default, range, unit, help), the views, and the built-in and named scenes with their\n"
                 "camera presets (a named scene whose model is missing says why).");
            return EXIT_OK;
        } else {
            static const char *const options[] = {"--json", "--help"};
            char hint[96];
            return cli_fail(EXIT_USAGE, "list: unknown option '%s'%s (see obscura list --help)", argv[i],
                            ob_suggest_text(argv[i], strlen(argv[i]), options, 2, hint, sizeof hint));
        }
    }
    return json ? list_json() : list_human();
}
