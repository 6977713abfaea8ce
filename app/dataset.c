/* obscura dataset: the pairs people train learned AO on. Per view, the G-buffer a screen-space
 * method sees (linear depth, view-space normals, albedo) and the ray-traced ground truth AO_R (and
 * with --bounce the one-bounce reference), as PFM, with a JSON manifest that says what every file
 * holds. --shard K/N writes a deterministic share of the views (shard.h), so that N processes make
 * the whole set once; their manifests list the views each wrote.
 *
 *   DIR/manifest.json          the run, the conventions and one entry per view
 *   DIR/VIEW/depth.pfm         linear view depth, world units, 0 = sky (1 channel)
 *   DIR/VIEW/normal.pfm        view-space unit normal (3 channels; 0 on sky)
 *   DIR/VIEW/albedo.pfm        linear diffuse albedo (3 channels)
 *   DIR/VIEW/ao.pfm            AO_R at radius R (1 = open; 1 on sky)
 *   DIR/VIEW/ao_stderr.pfm     its per-pixel standard error
 *   DIR/VIEW/bounce.pfm        --bounce: direct light + one diffuse bounce + ambient x AO_R, linear RGB
 *
 * The reference is the one compare grades against (reference_cache.h): the same G-buffer points,
 * rays, seed and cache, so a dataset and a report of the same view hold the same AO_R. */
#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "cli.h"
#include "cli_options.h"
#include "outputs.h"
#include "reference_cache.h"
#include "run_program.h"
#include "shard.h"

#define DATASET_DEFAULT_OUT "obscura-dataset"
enum { DATASET_MAX_VIEWS = 256 };

typedef struct dataset_opts {
    cli_common common;
    const char *views[DATASET_MAX_VIEWS]; /* "scene" or "scene:camera" */
    int view_count;
    const char *out;
    int spp;
    float radius; /* 0 = each scene's suggested radius */
    bool no_cache, bounce;
    cli_shard shard;
    cli_outputs outs;
    int out_index;
    int argc;
    char **argv;
} dataset_opts;

static void dataset_usage(FILE *f, const cli_common *defaults)
{
    fputs("usage: obscura dataset --scene S[:CAMERA] [--scene ...] [--out DIR] [options]\n"
          "\n"
          "Writes, per view, the G-buffer a screen-space method reads and the ray-traced AO_R it is\n"
          "graded against, as PFM (32-bit floats, bottom row first), and DIR/manifest.json:\n"
          "VIEW/depth.pfm (linear view depth, 0 = sky), VIEW/normal.pfm (view-space normals),\n"
          "VIEW/albedo.pfm, VIEW/ao.pfm (AO_R, 1 = open) and VIEW/ao_stderr.pfm; with --bounce\n"
          "VIEW/bounce.pfm. docs/dataset.md has the conventions.\n"
          "\n"
          "  --scene S[:CAMERA]    a scene and optionally a camera preset; repeatable up to 256 times\n"
          "  --out DIR             the dataset's directory, put in place only when whole (default\n"
          "                        " DATASET_DEFAULT_OUT "); an existing DIR is replaced only when empty or\n"
          "                        holding nothing but what this tool wrote there\n"
          "  --spp N               reference rays per pixel (default 512)\n"
          "  --radius R            AO radius R in world units (default: each scene's suggested radius)\n"
          "  --bounce              also the one-bounce reference (a quarter of the rays, at least 16)\n"
          "  --no-cache            recompute the references even if cached\n"
          "  --shard K/N           only this process's share of the views: N processes with K = 0..N-1\n"
          "                        (a Slurm array's SLURM_ARRAY_TASK_ID) write every view once, each\n"
          "                        into its own DIR; balanced by rays (pixels x rays per view)\n"
          "\n",
          f);
    cli_common_usage(f, defaults);
}

static int parse_value(dataset_opts *o, const char *a, const char *v)
{
    if (!strcmp(a, "--scene")) {
        if (o->view_count >= DATASET_MAX_VIEWS) return cli_fail(EXIT_USAGE, "--scene: at most %d", DATASET_MAX_VIEWS);
        o->views[o->view_count++] = v;
    } else if (!strcmp(a, "--out")) {
        o->out = v;
    } else if (!strcmp(a, "--shard")) {
        return cli_shard_parse("--shard", v, &o->shard);
    } else if (!strcmp(a, "--spp")) {
        char *end = NULL;
        long n = strtol(v, &end, 10);
        if (end == v || *end || n < 2 || n > 1 << 20) return cli_fail(EXIT_USAGE, "--spp: expected 2..1048576, got '%s'", v);
        o->spp = (int)n;
    } else if (!cli_parse_float(v, &o->radius) || !(o->radius > 0.0f) || !isfinite(o->radius)) {
        return cli_fail(EXIT_USAGE, "--radius: expected a positive number, got '%s'", v);
    }
    return EXIT_OK;
}

static int parse(int argc, char **argv, dataset_opts *o)
{
    *o = (dataset_opts){.spp = 512, .shard = {0, 1}, .out_index = -1, .argc = argc, .argv = argv};
    cli_common_init(&o->common, "dataset", CLI_TAKES_CAMERA | CLI_TAKES_GPU);
    o->common.width = 320;
    o->common.height = 240;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            dataset_usage(stdout, &o->common);
            return -1;
        }
        if (!strcmp(a, "--no-cache") || !strcmp(a, "--bounce")) {
            *(a[2] == 'n' ? &o->no_cache : &o->bounce) = true;
            continue;
        }
        int taken = cli_common_option(&o->common, argc, argv, &i);
        if (taken == CLI_TAKEN) continue;
        if (taken != CLI_NOT_MINE) return taken;
        static const char *const own[] = {"--scene", "--out", "--spp", "--radius", "--shard"};
        bool known = false;
        for (size_t k = 0; k < sizeof own / sizeof own[0]; ++k) known = known || !strcmp(a, own[k]);
        if (!known) return cli_unknown_option("dataset", a, dataset_usage, &o->common);
        if (i + 1 >= argc) return cli_fail(EXIT_USAGE, "%s: missing value (see obscura dataset --help)", a);
        int code = parse_value(o, a, argv[++i]);
        if (code != EXIT_OK) return code;
    }
    if (o->view_count == 0) return cli_fail(EXIT_USAGE, "--scene is required (see obscura dataset --help)");
    if (!o->out) {
        o->out = DATASET_DEFAULT_OUT;
        printf("dataset: no --out: the dataset goes to %s/ (--out DIR to choose)\n", o->out);
    }
    if (!*o->out) return cli_fail(EXIT_USAGE, "--out: expected a directory, got ''");
    int code = cli_common_finish(&o->common);
    if (code != EXIT_OK) return code;
    return cli_outputs_add(&o->outs, "--out", o->out, CLI_FMT_DIR, &o->out_index);
}

/* One view's buffers, bottom row first as ob_read_image gives them. */
typedef struct view_images {
    cli_view_frame frame; /* depth, normals, the camera's matrices */
    float *albedo, *ao, *se, *bounce;
} view_images;

static void images_free(view_images *v)
{
    cli_view_frame_free(&v->frame);
    free(v->albedo);
    free(v->ao);
    free(v->se);
    free(v->bounce);
}

static int write_pfm(const char *dir, const char *name, int w, int h, int channels, const float *px)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    return ob_write_pfm(path, w, h, channels, px) == OB_OK ? EXIT_OK : cli_fail_library_as(EXIT_OUTPUT);
}

/* The one-bounce reference with the run's lights and constant ambient (as compare's). */
static int trace_bounce(const dataset_opts *o, const ob_scene *scene, const ob_settings *lit, float radius, view_images *v)
{
    const cli_view_frame *f = &v->frame;
    const size_t px = (size_t)f->width * (size_t)f->height;
    float *pos = malloc(px * 3 * sizeof(float)), *nrm = malloc(px * 3 * sizeof(float));
    v->bounce = malloc(px * 3 * sizeof(float));
    bool ok = pos && nrm && v->bounce &&
              ob_reference_points(f->depth, f->normals, f->width, f->height, f->proj_info, f->inv_view, pos, nrm) == OB_OK &&
              ob_reference_bounce(scene, lit->light_count > 0 ? lit->lights : NULL, lit->light_count, lit->ambient, pos, nrm,
                                  v->albedo, px,
                                  &(ob_reference_desc){.spp = o->spp / 4 > 16 ? o->spp / 4 : 16, .radius = radius,
                                                       .progress = true},
                                  v->bounce) == OB_OK;
    bool memory = pos && nrm && v->bounce;
    free(pos);
    free(nrm);
    return ok ? EXIT_OK : memory ? cli_fail_from_library() : cli_fail(EXIT_RUNTIME, "out of memory");
}

/* n floats as a JSON array of numbers at 6 significant digits (cli_json_round, as results.json). */
static void add_floats(cJSON *obj, const char *name, const float *v, int n)
{
    cJSON *a = cJSON_AddArrayToObject(obj, name);
    for (int i = 0; i < n; ++i) cJSON_AddItemToArray(a, cJSON_CreateNumber(cli_json_round(v[i])));
}

/* The manifest's entry of one view. */
static void view_entry(cJSON *views, const char *spec, const char *dir, const ob_scene *scene, const view_images *v,
                       float radius, int spp, const cli_reference_info *info, bool bounce)
{
    const cli_view_frame *f = &v->frame;
    cJSON *e = cJSON_CreateObject();
    cJSON_AddItemToArray(views, e);
    cJSON_AddStringToObject(e, "view", spec);
    cJSON_AddStringToObject(e, "scene", ob_query_scene_name(scene));
    cJSON_AddStringToObject(e, "camera", f->cam.name);
    cJSON_AddStringToObject(e, "dir", dir);
    cli_json_add_number(e, "width", f->width);
    cli_json_add_number(e, "height", f->height);
    cli_json_add_number(e, "radius", radius);
    cli_json_add_number(e, "reference_spp", spp);
    cJSON_AddBoolToObject(e, "reference_cached", info->cached);
    cli_json_add_number(e, "reference_mean_standard_error", info->stderr_mean);
    cJSON *cam = cJSON_AddObjectToObject(e, "camera_pose");
    add_floats(cam, "eye", f->cam.eye, 3);
    add_floats(cam, "target", f->cam.target, 3);
    add_floats(cam, "up", f->cam.up, 3);
    cli_json_add_number(cam, "fov_y_deg", f->cam.fov_y_deg);
    add_floats(cam, "proj_info", f->proj_info, 4);
    add_floats(cam, "camera_to_world", f->inv_view, 16);
    cJSON *files = cJSON_AddObjectToObject(e, "files");
    cJSON_AddStringToObject(files, "depth", "depth.pfm");
    cJSON_AddStringToObject(files, "normal", "normal.pfm");
    cJSON_AddStringToObject(files, "albedo", "albedo.pfm");
    cJSON_AddStringToObject(files, "ao", "ao.pfm");
    cJSON_AddStringToObject(files, "ao_stderr", "ao_stderr.pfm");
    if (bounce) cJSON_AddStringToObject(files, "bounce", "bounce.pfm");
}

/* One view: its G-buffer from a `none` frame, AO_R (and the bounce), the files and its entry. */
/* The scene the last view loaded: consecutive views of one scene (its cameras) load it once, as
 * compare's views share theirs. */
typedef struct loaded_scene {
    char name[256];
    ob_scene *scene;
} loaded_scene;

static int run_view(const dataset_opts *o, ob_renderer *r, const ob_settings *lit, const char *spec, const char *root,
                    cJSON *views, loaded_scene *loaded)
{
    const cli_common *c = &o->common;
    char name[256];
    if (strlen(spec) >= sizeof name) return cli_fail(EXIT_USAGE, "--scene %.80s...: too long", spec);
    snprintf(name, sizeof name, "%s", spec);
    const char *camera = NULL;
    char *colon = strrchr(name, ':');
    if (colon && !strchr(colon, '/')) {
        *colon = '\0';
        camera = colon + 1;
    }
    int code = EXIT_OK;
    ob_scene *previous = NULL; /* destroyed once the renderer holds the new one */
    if (!loaded->scene || strcmp(loaded->name, name)) {
        previous = loaded->scene;
        loaded->scene = NULL;
        snprintf(loaded->name, sizeof loaded->name, "%s", name);
        code = cli_common_load_scene(c, name, &loaded->scene);
    }
    ob_scene *scene = loaded->scene;
    ob_camera cam;
    if (code == EXIT_OK) code = cli_common_camera(c, scene, camera, &cam);
    if (code == EXIT_OK && ob_renderer_set_scene(r, scene) != OB_OK) code = cli_fail_from_library();
    if (code == EXIT_OK) {
        ob_destroy_scene(previous);
    } else if (previous) {
        /* The renderer may still hold it: destroyed at the end, after the renderer. */
        ob_destroy_scene(loaded->scene);
        loaded->scene = previous;
    }
    view_images v = {0};
    if (code == EXIT_OK) code = cli_view_frame_make(r, &cam, c->width, c->height, &v.frame);
    const size_t px = (size_t)c->width * (size_t)c->height;
    if (code == EXIT_OK) {
        v.albedo = malloc(px * 3 * sizeof(float));
        v.ao = malloc(px * sizeof(float));
        v.se = malloc(px * sizeof(float));
        if (!v.albedo || !v.ao || !v.se) code = cli_fail(EXIT_RUNTIME, "out of memory");
        else if (ob_read_image(r, OB_IMAGE_ALBEDO_F32, v.albedo, px * 3 * sizeof(float)) != OB_OK) code = cli_fail_from_library();
    }
    const float radius = o->radius > 0.0f ? o->radius : (scene ? ob_query_scene_ao_radius(scene) : 0.0f);
    cli_reference_info info = {0};
    char key[1024];
    if (code == EXIT_OK) {
        cli_reference_key(c, name, cam.name, key, sizeof key);
        code = cli_reference_ao(scene, &v.frame, key, radius, o->spp, o->no_cache, c->verbose, v.ao, &info);
    }
    /* The per-pixel standard error of a mean of n visibility samples: the cache keeps only the
     * mean, so it is recomputed from the estimate as sqrt(p (1 - p) / (n - 1)) (as the tracer). */
    for (size_t i = 0; code == EXIT_OK && i < px; ++i)
        v.se[i] = v.frame.depth[i] > 0.0f ? sqrtf(fmaxf(v.ao[i] * (1.0f - v.ao[i]), 0.0f) / (float)(o->spp - 1)) : 0.0f;
    if (code == EXIT_OK && o->bounce) code = trace_bounce(o, scene, lit, radius, &v);
    char safe_scene[128], safe_cam[64], dir[200], path[1000];
    cli_safe_name(safe_scene, sizeof safe_scene, scene ? ob_query_scene_name(scene) : "");
    cli_safe_name(safe_cam, sizeof safe_cam, cam.name);
    snprintf(dir, sizeof dir, "%s_%s", safe_scene, safe_cam);
    snprintf(path, sizeof path, "%s/%s", root, dir);
    if (code == EXIT_OK && mkdir(path, 0777) != 0)
        code = cli_fail(EXIT_OUTPUT, "--out: cannot make %s (two --scene give the same view?): %s", dir, strerror(errno));
    const int w = c->width, h = c->height;
    if (code == EXIT_OK) code = write_pfm(path, "depth.pfm", w, h, 1, v.frame.depth);
    if (code == EXIT_OK) code = write_pfm(path, "normal.pfm", w, h, 3, v.frame.normals);
    if (code == EXIT_OK) code = write_pfm(path, "albedo.pfm", w, h, 3, v.albedo);
    if (code == EXIT_OK) code = write_pfm(path, "ao.pfm", w, h, 1, v.ao);
    if (code == EXIT_OK) code = write_pfm(path, "ao_stderr.pfm", w, h, 1, v.se);
    if (code == EXIT_OK && o->bounce) code = write_pfm(path, "bounce.pfm", w, h, 3, v.bounce);
    if (code == EXIT_OK) view_entry(views, spec, dir, scene, &v, radius, o->spp, &info, o->bounce);
    images_free(&v);
    return code;
}

/* The manifest's head: the tool, the command line, the shard, the conventions. */
static cJSON *manifest_head(const dataset_opts *o, ob_context *ctx, const int *owner)
{
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "version", OB_VERSION_STRING);
    cli_json_commit_and_command(root, o->argc, o->argv);
    cJSON_AddStringToObject(root, "renderer", ob_query_renderer(ctx));
    cli_shard_json(root, &o->shard, o->views, owner, o->view_count);
    cJSON *conv = cJSON_AddObjectToObject(root, "conventions");
    cJSON_AddStringToObject(conv, "pfm", "32-bit little-endian floats, rows bottom first (PFM's own order)");
    cJSON_AddStringToObject(conv, "depth", "linear view depth along -Z in world units; 0 where no geometry (sky)");
    cJSON_AddStringToObject(conv, "normal", "view-space unit normal, right-handed, camera looking down -Z; 0 on sky");
    cJSON_AddStringToObject(conv, "albedo", "linear diffuse albedo of the material (textures included where sampled)");
    cJSON_AddStringToObject(conv, "ao", "AO_R: the cosine-weighted fraction of the hemisphere whose rays leave a "
                                        "sphere of radius R unblocked, ray traced from the G-buffer's points; 1 on sky");
    cJSON_AddStringToObject(conv, "bounce", "direct light (shadow rays) + one diffuse bounce within R + ambient x AO_R, "
                                            "linear RGB, the scene's lights");
    return root;
}

static int dataset_checked(dataset_opts *o)
{
    const cli_common *c = &o->common;
    /* Every view costs pixels x rays (the size and spp are the run's): balanced by that. */
    double cost[DATASET_MAX_VIEWS];
    int owner[DATASET_MAX_VIEWS];
    for (int v = 0; v < o->view_count; ++v) cost[v] = (double)c->width * (double)c->height * (double)o->spp;
    cli_shard_assign(cost, o->view_count, o->shard.count, owner);
    cli_config *configs = NULL;
    int count = 0;
    int code = cli_common_configs(c, &configs, &count);
    ob_context *ctx = code == EXIT_OK ? cli_make_context(c->gpu, c->verbose) : NULL;
    if (code == EXIT_OK && !ctx) code = cli_fail_from_library();
    ob_renderer *r = ctx ? ob_make_renderer(ctx, &(ob_renderer_desc){.width = c->width, .height = c->height}) : NULL;
    if (code == EXIT_OK && !r) code = cli_fail_from_library();
    if (code == EXIT_OK) code = cli_common_prepare(c, r);
    const char *root = code == EXIT_OK ? cli_outputs_dir(&o->outs, o->out_index) : NULL;
    if (code == EXIT_OK && !root) code = EXIT_OUTPUT;
    cJSON *manifest = code == EXIT_OK ? manifest_head(o, ctx, owner) : NULL;
    cJSON *views = manifest ? cJSON_AddArrayToObject(manifest, "views") : NULL;
    int mine = 0;
    loaded_scene loaded = {"", NULL};
    for (int v = 0; v < o->view_count && code == EXIT_OK; ++v) {
        if (owner[v] != o->shard.index) continue;
        code = run_view(o, r, &configs[0].settings, o->views[v], root, views, &loaded);
        ++mine;
    }
    if (code == EXIT_OK) {
        char path[1200];
        snprintf(path, sizeof path, "%s/manifest.json", root);
        char *text = cJSON_Print(manifest);
        if (!text) code = cli_fail(EXIT_RUNTIME, "out of memory");
        else if (ob_write_text(path, text) != OB_OK) code = cli_fail_library_as(EXIT_OUTPUT);
        free(text);
        printf("dataset: %d of %d views (shard %d/%d) in %s\n", mine, o->view_count, o->shard.index, o->shard.count,
               o->out);
    }
    cJSON_Delete(manifest);
    free(configs);
    ob_destroy_renderer(r);
    ob_destroy_scene(loaded.scene); /* after the renderer that held it */
    ob_destroy_context(ctx);
    return code;
}

int cmd_dataset(int argc, char **argv)
{
    dataset_opts o;
    int code = parse(argc, argv, &o);
    if (code == 0) code = dataset_checked(&o);
    return cli_outputs_finish(&o.outs, code < 0 ? EXIT_OK : code);
}
