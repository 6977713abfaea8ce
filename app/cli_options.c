/* The common options of the rendering commands (cli_options.h): parsing, usage, settings. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_options.h"

enum { ITEM_MAX = 64 }; /* longest element of a comma list (names are short; a long one is a typo) */

/* The --ao-scale spellings and their divisors: the AO grid is 1, 2 or 4 full pixels wide. */
static const struct {
    const char *text;
    int divisor;
} AO_SCALES[] = {{"1", 1}, {"0.5", 2}, {"0.25", 4}};

static const char *ao_scale_text(int divisor)
{
    for (size_t k = 0; k < sizeof AO_SCALES / sizeof AO_SCALES[0]; ++k)
        if (AO_SCALES[k].divisor == divisor) return AO_SCALES[k].text;
    return "?";
}

static bool takes(const cli_common *c, unsigned what) { return (c->takes & what) != 0; }

void cli_common_init(cli_common *c, const char *command, unsigned takes_mask)
{
    *c = (cli_common){.command = command, .takes = takes_mask, .default_method = OB_DEFAULT_METHOD, .width = 640,
                      .height = 480, .jitter = -1};
}

/* ---- comma lists ------------------------------------------------------------------------------ */

/* Split `text` at commas. An empty list, an empty element, one longer than ITEM_MAX - 1 or more
 * than `max` elements is one line naming the option and the value. */
static int split_list(const char *opt, const char *text, char items[][ITEM_MAX], int max, int *count)
{
    *count = 0;
    if (!*text) return cli_fail(EXIT_USAGE, "%s: expected a comma list, got ''", opt);
    const char *p = text;
    for (;;) {
        size_t len = strcspn(p, ",");
        if (len == 0) return cli_fail(EXIT_USAGE, "%s: empty element in '%s'", opt, text);
        if (len >= ITEM_MAX) return cli_fail(EXIT_USAGE, "%s: '%.*s' is too long", opt, (int)len, p);
        if (*count >= max) return cli_fail(EXIT_USAGE, "%s: more than %d elements in '%s'", opt, max, text);
        memcpy(items[*count], p, len);
        items[*count][len] = '\0';
        ++*count;
        if (p[len] == '\0') break;
        p += len + 1;
    }
    return EXIT_OK;
}

/* The elements of a list option, or the whole value as one element when the command takes no
 * lists (then a comma is part of a bad name, reported as such). */
static int elements(const cli_common *c, bool list, const char *opt, const char *text, char items[][ITEM_MAX], int *count)
{
    if (list && takes(c, CLI_TAKES_LISTS)) return split_list(opt, text, items, CLI_MAX_LIST, count);
    if (strlen(text) >= ITEM_MAX) return cli_fail(EXIT_USAGE, "%s: '%s' is too long", opt, text);
    snprintf(items[0], ITEM_MAX, "%s", text);
    *count = 1;
    return EXIT_OK;
}

/* The library's message for a failed call, behind the option's name. */
static int fail_option(const char *opt)
{
    const char *msg = NULL;
    ob_error err = ob_get_error(&msg);
    return cli_fail(EXIT_USAGE, "%s: %s", opt, msg && *msg ? msg : ob_error_name(err));
}

static int parse_methods(cli_common *c, bool list, const char *opt, const char *v)
{
    char items[CLI_MAX_LIST][ITEM_MAX] = {{0}};
    int n = 0, code = elements(c, list, opt, v, items, &n);
    if (code != EXIT_OK) return code;
    if (list && !strcmp(v, "all")) { /* every method: cli_common_finish fills them in */
        c->method_count = 0;
        c->default_method = NULL;
        return CLI_TAKEN;
    }
    for (int k = 0; k < n; ++k) {
        int m = ob_find_method(items[k]);
        if (m < 0) {
            ob_settings probe = {0};
            ob_settings_init(&probe, items[k]); /* the library's "unknown method (known: ...)" */
            return list ? fail_option(opt) : cli_fail_from_library_in(opt);
        }
        for (int j = 0; j < k; ++j)
            if (c->methods[j] == m) return cli_fail(EXIT_USAGE, "%s: '%s' is listed twice", opt, items[k]);
        c->methods[k] = m;
    }
    c->method_count = n;
    return CLI_TAKEN;
}

static int parse_filters(cli_common *c, bool list, const char *opt, const char *v)
{
    char items[CLI_MAX_LIST][ITEM_MAX] = {{0}};
    int n = 0, code = elements(c, list, opt, v, items, &n);
    if (code != EXIT_OK) return code;
    for (int k = 0; k < n; ++k) {
        int f = ob_find_filter(items[k]);
        if (f < 0) {
            ob_settings probe = {0};
            ob_settings_init(&probe, NULL);
            ob_settings_set_filter(&probe, items[k]); /* "unknown filter 'x' (known: ...)" */
            return fail_option(opt);
        }
        for (int j = 0; j < k; ++j)
            if (c->filters[j] == f) return cli_fail(EXIT_USAGE, "%s: '%s' is listed twice", opt, items[k]);
        c->filters[k] = f;
    }
    c->filter_count = n;
    return CLI_TAKEN;
}

static int parse_ao_scales(cli_common *c, bool list, const char *opt, const char *v)
{
    char items[CLI_MAX_LIST][ITEM_MAX] = {{0}};
    int n = 0, code = elements(c, list, opt, v, items, &n);
    if (code != EXIT_OK) return code;
    if (n > 3) return cli_fail(EXIT_USAGE, "%s: at most 3 scales (1, 0.5, 0.25), got '%s'", opt, v);
    for (int k = 0; k < n; ++k) {
        int d = 0;
        for (size_t s = 0; s < sizeof AO_SCALES / sizeof AO_SCALES[0]; ++s)
            if (!strcmp(items[k], AO_SCALES[s].text)) d = AO_SCALES[s].divisor;
        if (!d) return cli_fail(EXIT_USAGE, "%s: expected 1, 0.5 or 0.25, got '%s'", opt, items[k]);
        for (int j = 0; j < k; ++j)
            if (c->ao_divisors[j] == d) return cli_fail(EXIT_USAGE, "%s: '%s' is listed twice", opt, items[k]);
        c->ao_divisors[k] = d;
    }
    c->ao_count = n;
    return CLI_TAKEN;
}

/* --samples' bound: the most any method takes (gtao, vbao and vbgi: 2 x 32 slices x 32 steps).
 * Each method's own maximum (256 for the per-sample methods, 1024 for hbao) is checked by
 * ob_settings_set_samples, whose error names it. */
enum { CLI_MAX_SAMPLES = 2048 };

/* --quality and --samples: sample counts, each list free of repeats. */
static int parse_samples(cli_common *c, bool quality, const char *opt, const char *v)
{
    char items[CLI_MAX_LIST][ITEM_MAX] = {{0}};
    int n = 0, code = elements(c, true, opt, v, items, &n);
    if (code != EXIT_OK) return code;
    cli_samples *out = quality ? c->by_quality : c->by_number;
    for (int k = 0; k < n; ++k) {
        cli_samples s = {0, NULL};
        if (quality) {
            s.count = ob_quality_samples(items[k]);
            if (s.count < 0) {
                if (n == 1) return cli_fail(EXIT_USAGE, "%s: expected low, medium, high or ultra, got '%s'", opt, v);
                return cli_fail(EXIT_USAGE, "%s: expected low, medium, high or ultra, got '%s' in '%s'", opt, items[k], v);
            }
            /* The preset names are static strings of ours: keep the one argv spelled. */
            static const char *const names[] = {"low", "medium", "high", "ultra"};
            for (int q = 0; q < 4; ++q)
                if (!strcmp(items[k], names[q])) s.quality = names[q];
        } else {
            char *end = NULL;
            long x = strtol(items[k], &end, 10);
            if (end == items[k] || *end || x < 1 || x > CLI_MAX_SAMPLES) {
                if (takes(c, CLI_TAKES_LISTS))
                    return cli_fail(EXIT_USAGE, "%s: expected a comma list of 1..%d, got '%s'", opt, CLI_MAX_SAMPLES, v);
                return cli_fail(EXIT_USAGE, "%s: expected 1..%d, got '%s'", opt, CLI_MAX_SAMPLES, v);
            }
            s.count = (int)x;
        }
        for (int j = 0; j < k; ++j)
            if (out[j].count == s.count) return cli_fail(EXIT_USAGE, "%s: '%s' is listed twice", opt, items[k]);
        out[k] = s;
    }
    if (quality) c->by_quality_count = n;
    else c->by_number_count = n;
    return CLI_TAKEN;
}

/* ---- the numeric lighting, shadow and tone-mapping options ------------------------------------- */

static const struct {
    const char *name;
    size_t offset;
    float min, max;
    bool integer;
    unsigned bit;
} NUMBERS[] = {
    {"--shadow-size", offsetof(cli_common, shadow_size), 16.0f, 16384.0f, true, CLI_GIVEN_SHADOW_SIZE},
    {"--shadow-bias", offsetof(cli_common, shadow_bias), 0.0f, 100.0f, false, CLI_GIVEN_SHADOW_BIAS},
    {"--shadow-slope-bias", offsetof(cli_common, slope_bias), 0.0f, 100.0f, false, CLI_GIVEN_SLOPE_BIAS},
    {"--pcf-radius", offsetof(cli_common, pcf_radius), 1.0f, 8.0f, true, CLI_GIVEN_PCF_RADIUS},
    {"--vsm-blur", offsetof(cli_common, vsm_blur), 0.0f, 16.0f, false, CLI_GIVEN_VSM_BLUR},
    {"--vsm-bleed", offsetof(cli_common, vsm_bleed), 0.0f, 0.99f, false, CLI_GIVEN_VSM_BLEED},
    {"--exposure", offsetof(cli_common, exposure), 1e-6f, 1e6f, false, CLI_GIVEN_EXPOSURE},
    {"--key", offsetof(cli_common, key), 0.001f, 10.0f, false, CLI_GIVEN_KEY},
    {"--white", offsetof(cli_common, white), 0.0f, 1e6f, false, CLI_GIVEN_WHITE},
    {"--bloom", offsetof(cli_common, bloom), 0.0f, 10.0f, false, CLI_GIVEN_BLOOM},
    {"--bloom-threshold", offsetof(cli_common, bloom_threshold), 0.0f, 1e6f, false, CLI_GIVEN_BLOOM_THRESHOLD},
};

static int parse_number(cli_common *c, size_t k, const char *v)
{
    float x = 0.0f;
    if (!cli_parse_float(v, &x) || x < NUMBERS[k].min || x > NUMBERS[k].max || (NUMBERS[k].integer && x != floorf(x)))
        return cli_fail(EXIT_USAGE, "%s: expected %s in [%g, %g], got '%s'", NUMBERS[k].name,
                        NUMBERS[k].integer ? "an integer" : "a number", (double)NUMBERS[k].min, (double)NUMBERS[k].max, v);
    char *field = (char *)c + NUMBERS[k].offset;
    if (NUMBERS[k].integer) *(int *)field = (int)x;
    else *(float *)field = x;
    c->given |= NUMBERS[k].bit;
    return CLI_TAKEN;
}

/* --guard PX (whole pixels) or F% (a percentage of the larger image dimension, resolved in
 * cli_common_finish once --size is known). */
static int parse_guard(cli_common *c, const char *v)
{
    size_t len = strlen(v);
    bool percent = len > 0 && v[len - 1] == '%';
    char number[ITEM_MAX] = "";
    if (len == 0 || len >= sizeof number) return cli_fail(EXIT_USAGE, "--guard: expected PX or F%%, got '%s'", v);
    memcpy(number, v, percent ? len - 1 : len);
    float x = 0.0f;
    if (!cli_parse_float(number, &x) || x < 0.0f)
        return cli_fail(EXIT_USAGE, "--guard: expected pixels >= 0 or a percentage like 10%%, got '%s'", v);
    if (percent) {
        if (x > 100.0f) return cli_fail(EXIT_USAGE, "--guard: %s is more than 100%% of the image", v);
        c->guard_percent = x;
    } else {
        if (x != floorf(x)) return cli_fail(EXIT_USAGE, "--guard: expected whole pixels, got '%s'", v);
        if (x > (float)OB_GUARD_MAX) return cli_fail(EXIT_USAGE, "--guard: %s px is more than %d", v, OB_GUARD_MAX);
        c->guard_px = (int)x;
    }
    c->guard_is_percent = percent;
    return CLI_TAKEN;
}

/* ---- the parser ------------------------------------------------------------------------------- */

/* The options with a value, each with what the command must take for it (0 = every command). */
static const struct {
    const char *name;
    unsigned needs;
} WITH_VALUE[] = {
    {"--scene", CLI_TAKES_SCENE},  {"--sidecar", 0},     {"--up", 0},          {"--max-memory", 0},
    {"--camera", CLI_TAKES_CAMERA}, {"--eye", CLI_TAKES_CAMERA}, {"--target", CLI_TAKES_CAMERA},
    {"--fov", CLI_TAKES_CAMERA},   {"--size", 0},        {"--method", 0},
    {"--methods", CLI_TAKES_LISTS}, {"--set", 0},        {"--quality", 0},
    {"--samples", 0},              {"--filter", 0},      {"--filters", CLI_TAKES_LISTS},
    {"--ao-scale", 0},             {"--ao-scales", CLI_TAKES_LISTS}, {"--adaptive", 0},
    {"--light", 0},                {"--env", 0},         {"--ambient", 0},
    {"--ambient-color", 0},        {"--ao-light", 0},    {"--shadow", 0},
    {"--multibounce", 0},          {"--settings", 0},    {"--textures", 0},
    {"--vsm-bits", 0},             {"--guard", 0},       {"--temporal", 0},
    {"--temporal-at", 0},          {"--temporal-frames", 0}, {"--temporal-detail", 0}, {"--upsample", 0},
    {"--path", CLI_TAKES_PATH},    {"--orbit", CLI_TAKES_PATH}, {"--path-frames", CLI_TAKES_PATH},
    {"--jitter", CLI_TAKES_PATH},
    {"--hdr", 0},                  {"--gpu", CLI_TAKES_GPU}, {"--shader-dir", CLI_TAKES_GPU},
};

int cli_common_option(cli_common *c, int argc, char **argv, int *i)
{
    const char *a = argv[*i];
    if (!strcmp(a, "-v") && takes(c, CLI_TAKES_GPU)) {
        c->verbose = true;
        return CLI_TAKEN;
    }
    if (!strcmp(a, "--allow-empty")) {
        c->allow_empty = true;
        return CLI_TAKEN;
    }
    if (!strcmp(a, "--allow-external-files")) {
        c->allow_external_files = true;
        return CLI_TAKEN;
    }
    bool mine = false;
    for (size_t k = 0; k < sizeof WITH_VALUE / sizeof WITH_VALUE[0] && !mine; ++k)
        mine = !strcmp(a, WITH_VALUE[k].name) && (WITH_VALUE[k].needs == 0 || takes(c, WITH_VALUE[k].needs));
    size_t number = sizeof NUMBERS / sizeof NUMBERS[0];
    for (size_t k = 0; k < sizeof NUMBERS / sizeof NUMBERS[0] && !mine; ++k)
        if (!strcmp(a, NUMBERS[k].name)) {
            mine = true;
            number = k;
        }
    if (!mine) return CLI_NOT_MINE;
    if (*i + 1 >= argc) return cli_fail(EXIT_USAGE, "%s: missing value (see obscura %s --help)", a, c->command);
    const char *v = argv[++*i];
    if (number < sizeof NUMBERS / sizeof NUMBERS[0]) return parse_number(c, number, v);

    if (!strcmp(a, "--scene")) c->scene = v;
    else if (!strcmp(a, "--sidecar")) c->sidecar = v;
    else if (!strcmp(a, "--max-memory")) {
        /* BYTES, or a number with K, M or G (binary units; "GiB" and "GB" read the same). */
        char *end = NULL;
        double n = strtod(v, &end);
        double unit = 1.0;
        if (end && (*end == 'K' || *end == 'k')) unit = 1024.0, ++end;
        else if (end && (*end == 'M' || *end == 'm')) unit = 1024.0 * 1024.0, ++end;
        else if (end && (*end == 'G' || *end == 'g')) unit = 1024.0 * 1024.0 * 1024.0, ++end;
        if (end && unit > 1.0 && (!strcmp(end, "iB") || !strcmp(end, "B"))) end += strlen(end);
        double bytes = n * unit;
        if (end == v || !end || *end || !(bytes >= 1024.0 * 1024.0) || bytes > 1e18)
            return cli_fail(EXIT_USAGE, "--max-memory: expected a size of at least 1M such as 512M or 4G, got '%s'", v);
        c->max_memory = (uint64_t)bytes;
        c->max_memory_text = v;
    }
    else if (!strcmp(a, "--up")) {
        if (!cli_parse_up(v, &c->up)) return cli_fail(EXIT_USAGE, "--up: expected y or z, got '%s'", v);
    } else if (!strcmp(a, "--camera")) c->camera = v;
    else if (!strcmp(a, "--eye")) {
        if (!cli_parse_vec3(v, c->eye)) return cli_fail(EXIT_USAGE, "--eye: expected X,Y,Z (finite numbers), got '%s'", v);
        c->has_eye = true;
    } else if (!strcmp(a, "--target")) {
        if (!cli_parse_vec3(v, c->target))
            return cli_fail(EXIT_USAGE, "--target: expected X,Y,Z (finite numbers), got '%s'", v);
        c->has_target = true;
    } else if (!strcmp(a, "--fov")) {
        if (!cli_parse_float(v, &c->fov) || c->fov < OB_MIN_FOV_DEG || c->fov >= 179.0f)
            return cli_fail(EXIT_USAGE, "--fov: expected degrees in [%g, 179), got '%s'", (double)OB_MIN_FOV_DEG, v);
        c->has_fov = true;
    } else if (!strcmp(a, "--size")) {
        if (!cli_parse_size(v, &c->width, &c->height))
            return cli_fail(EXIT_USAGE, "--size: expected WIDTHxHEIGHT with positive integers, got '%s'", v);
        c->has_size = true;
    } else if (!strcmp(a, "--method") || !strcmp(a, "--methods")) {
        return parse_methods(c, !strcmp(a, "--methods"), a, v);
    } else if (!strcmp(a, "--filter") || !strcmp(a, "--filters")) {
        return parse_filters(c, !strcmp(a, "--filters"), a, v);
    } else if (!strcmp(a, "--ao-scale") || !strcmp(a, "--ao-scales")) {
        return parse_ao_scales(c, !strcmp(a, "--ao-scales"), a, v);
    } else if (!strcmp(a, "--quality") || !strcmp(a, "--samples")) {
        return parse_samples(c, !strcmp(a, "--quality"), a, v);
    } else if (!strcmp(a, "--settings")) {
        c->settings_path = v;
    } else if (!strcmp(a, "--set")) {
        if (c->set_count >= CLI_MAX_SETS) return cli_fail(EXIT_USAGE, "--set: more than %d", CLI_MAX_SETS);
        c->sets[c->set_count++] = v;
    } else if (!strcmp(a, "--guard")) {
        return parse_guard(c, v);
    } else if (!strcmp(a, "--path")) {
        if (!v[0]) return cli_fail(EXIT_USAGE, "--path: expected the name of one of the scene's paths");
        c->path = v;
    } else if (!strcmp(a, "--orbit")) {
        if (!cli_parse_float(v, &c->orbit_deg) || fabsf(c->orbit_deg) > 3600.0f)
            return cli_fail(EXIT_USAGE, "--orbit: expected degrees in [-3600, 3600], got '%s'", v);
        c->has_orbit = true;
    } else if (!strcmp(a, "--path-frames")) {
        char *end = NULL;
        long n = strtol(v, &end, 10);
        if (end == v || *end != '\0' || n < 2 || n > CLI_MAX_PATH_FRAMES)
            return cli_fail(EXIT_USAGE, "--path-frames: expected 2..%d frames, got '%s'", CLI_MAX_PATH_FRAMES, v);
        c->path_frames = (int)n;
    } else if (!strcmp(a, "--temporal")) {
        if (!cli_parse_on_off(v, &c->temporal)) return cli_fail(EXIT_USAGE, "--temporal: expected on or off, got '%s'", v);
    } else if (!strcmp(a, "--jitter")) {
        char *end = NULL;
        long n = !strcmp(v, "on") ? OB_JITTER_POSITIONS_DEFAULT : !strcmp(v, "off") ? 0 : strtol(v, &end, 10);
        if ((end && (end == v || *end != '\0')) || n < 0 || n > OB_JITTER_POSITIONS_MAX)
            return cli_fail(EXIT_USAGE, "--jitter: expected on, off or 0..%d sub-pixel positions, got '%s'",
                            OB_JITTER_POSITIONS_MAX, v);
        c->jitter = (int)n;
    } else if (!strcmp(a, "--upsample")) {
        int n = 0;
        while (n < OB_UPSAMPLE_PROGRAM_COUNT && strcmp(v, ob_upsample_program_name((ob_upsample_program)n))) ++n;
        if (n == OB_UPSAMPLE_PROGRAM_COUNT) return cli_fail(EXIT_USAGE, "--upsample: expected auto, plain or block, got '%s'", v);
        c->upsample = n;
    } else if (!strcmp(a, "--temporal-at")) {
        if (!strcmp(v, "before")) c->temporal_at = OB_TEMPORAL_BEFORE_FILTER;
        else if (!strcmp(v, "after")) c->temporal_at = OB_TEMPORAL_AFTER_FILTER;
        else return cli_fail(EXIT_USAGE, "--temporal-at: expected before or after (the spatial filter), got '%s'", v);
    } else if (!strcmp(a, "--temporal-frames")) {
        char *end = NULL;
        long n = strtol(v, &end, 10);
        if (end == v || *end != '\0' || n < 1 || n > OB_TEMPORAL_FRAMES_MAX)
            return cli_fail(EXIT_USAGE, "--temporal-frames: expected a history length of 1..%d frames, got '%s'",
                            OB_TEMPORAL_FRAMES_MAX, v);
        c->temporal_frames = (int)n;
    } else if (!strcmp(a, "--temporal-detail")) {
        char *end = NULL;
        float x = strtof(v, &end);
        if (end == v || *end != '\0' || !(x >= 0.0f && x < 1.0f))
            return cli_fail(EXIT_USAGE, "--temporal-detail: expected a share of one-pixel detail in [0, 1), got '%s'",
                            v);
        c->temporal_detail = x;
    } else if (!strcmp(a, "--adaptive")) {
        if (!cli_parse_on_off(v, &c->adaptive)) return cli_fail(EXIT_USAGE, "--adaptive: expected on or off, got '%s'", v);
    } else if (!strcmp(a, "--light")) {
        if (c->light_count >= OB_MAX_LIGHTS) return cli_fail(EXIT_USAGE, "--light: at most %d lights", OB_MAX_LIGHTS);
        ob_light probe = {0};
        if (ob_parse_light(v, &probe) != OB_OK) return fail_option(a);
        c->lights[c->light_count++] = v;
    } else if (!strcmp(a, "--env")) {
        c->env = v;
    } else if (!strcmp(a, "--ambient")) {
        if (!strcmp(v, "constant")) c->ambient_mode = OB_AMBIENT_CONSTANT;
        else if (!strcmp(v, "hemisphere")) c->ambient_mode = OB_AMBIENT_HEMISPHERE;
        else if (!strcmp(v, "env")) c->ambient_mode = OB_AMBIENT_ENVIRONMENT;
        else return cli_fail(EXIT_USAGE, "--ambient: expected constant, hemisphere or env, got '%s'", v);
    } else if (!strcmp(a, "--ambient-color")) {
        if (!cli_parse_vec3(v, c->ambient_color) || c->ambient_color[0] < 0.0f || c->ambient_color[1] < 0.0f ||
            c->ambient_color[2] < 0.0f)
            return cli_fail(EXIT_USAGE, "--ambient-color: expected R,G,B >= 0, got '%s'", v);
        c->given |= CLI_GIVEN_AMBIENT_COLOR;
    } else if (!strcmp(a, "--ao-light")) {
        if (!strcmp(v, "ambient")) c->ao_all_light = false;
        else if (!strcmp(v, "all")) c->ao_all_light = true;
        else return cli_fail(EXIT_USAGE, "--ao-light: expected ambient or all, got '%s'", v);
    } else if (!strcmp(a, "--vsm-bits")) {
        if (strcmp(v, "16") && strcmp(v, "32")) return cli_fail(EXIT_USAGE, "--vsm-bits: expected 16 or 32, got '%s'", v);
        c->vsm_bits = atoi(v);
        c->given |= CLI_GIVEN_VSM_BITS;
    } else if (!strcmp(a, "--textures")) {
        bool on = true;
        if (!cli_parse_on_off(v, &on)) return cli_fail(EXIT_USAGE, "--textures: expected on or off, got '%s'", v);
        c->textures_off = !on;
    } else if (!strcmp(a, "--multibounce")) {
        if (!cli_parse_on_off(v, &c->multibounce))
            return cli_fail(EXIT_USAGE, "--multibounce: expected on or off, got '%s'", v);
    } else if (!strcmp(a, "--shadow")) {
        if (!cli_parse_shadow(v, &c->shadow)) return cli_fail(EXIT_USAGE, "--shadow: expected none, hard, pcf or vsm, got '%s'", v);
        c->given |= CLI_GIVEN_SHADOW;
    } else if (!strcmp(a, "--hdr")) {
        bool on = true;
        if (!cli_parse_on_off(v, &on)) return cli_fail(EXIT_USAGE, "--hdr: expected on or off, got '%s'", v);
        c->hdr_off = !on;
    } else if (!strcmp(a, "--gpu")) {
        if (!cli_parse_gpu(v, &c->gpu)) return cli_fail(EXIT_USAGE, "--gpu: expected auto, hw or sw, got '%s'", v);
    } else if (!strcmp(a, "--shader-dir")) {
        /* Process-wide and before any program is made: every renderer of the run compiles from it. */
        if (ob_set_shader_directory(v) != OB_OK) return cli_fail(EXIT_INPUT, "--shader-dir: '%s' is not a readable directory", v);
    }
    return CLI_TAKEN;
}

/* The memory the options make the run take, against --max-memory (below, with the settings). */
static int check_run_memory(cli_common *c);

int cli_common_finish(cli_common *c)
{
    if (c->has_eye != c->has_target) return cli_fail(EXIT_USAGE, "--eye and --target go together");
    if (c->camera && c->has_eye) return cli_fail(EXIT_USAGE, "--camera and --eye/--target exclude each other");
    if (c->has_eye && c->eye[0] == c->target[0] && c->eye[1] == c->target[1] && c->eye[2] == c->target[2])
        return cli_fail(EXIT_USAGE, "--eye and --target are the same point");
    if (c->ambient_mode == OB_AMBIENT_ENVIRONMENT && !c->env) return cli_fail(EXIT_USAGE, "--ambient env needs --env FILE.hdr");
    if (c->path && c->has_orbit) return cli_fail(EXIT_USAGE, "--path and --orbit exclude each other");
    if (c->path && (c->camera || c->has_eye))
        return cli_fail(EXIT_USAGE, "--path gives the camera: it excludes --camera and --eye/--target");
    if (c->path_frames && !cli_common_moves(c)) return cli_fail(EXIT_USAGE, "--path-frames needs --path or --orbit");
    if (!c->path_frames) c->path_frames = CLI_PATH_FRAMES;
    if (c->guard_is_percent) {
        int larger = c->width > c->height ? c->width : c->height;
        c->guard_px = (int)ceilf(c->guard_percent * 0.01f * (float)larger);
        if (c->guard_px > OB_GUARD_MAX)
            return cli_fail(EXIT_USAGE, "--guard %g%%: %d px per side at %dx%d is more than %d", (double)c->guard_percent,
                            c->guard_px, c->width, c->height, OB_GUARD_MAX);
    }
    if (c->settings_path) {
        int code = cli_tuned_load(c->settings_path, c->tuned, CLI_MAX_TUNED_FILES, &c->tuned_count);
        if (code != EXIT_OK) return code;
        /* One method's file names the method when no --method does. */
        if (c->method_count == 0 && c->tuned_count == 1 && !takes(c, CLI_TAKES_LISTS)) {
            c->methods[0] = c->tuned[0].method;
            c->method_count = 1;
        }
    }
    if (c->method_count == 0) {
        if (c->default_method) {
            c->methods[0] = ob_find_method(c->default_method);
            c->method_count = c->methods[0] >= 0 ? 1 : 0;
        } else {
            for (int m = 0; m < ob_method_count() && c->method_count < CLI_MAX_LIST; ++m) c->methods[c->method_count++] = m;
        }
    }
    if (c->filter_count == 0) {
        c->filters[0] = ob_find_filter("crease");
        c->filter_count = 1;
    }
    if (c->ao_count == 0) {
        c->ao_divisors[0] = 1;
        c->ao_count = 1;
    }
    /* Lists: one sample dimension, so both spellings at once would be ambiguous. A single-value
     * command keeps render's rule: --samples overrides --quality. */
    if (takes(c, CLI_TAKES_LISTS) && c->by_quality_count > 0 && c->by_number_count > 0)
        return cli_fail(EXIT_USAGE, "--quality and --samples exclude each other (both give the sample counts)");
    const cli_samples *from = c->by_number_count > 0 ? c->by_number : c->by_quality;
    c->sample_count = c->by_number_count > 0 ? c->by_number_count : c->by_quality_count;
    memcpy(c->samples, from, (size_t)c->sample_count * sizeof *from);
    return check_run_memory(c);
}

/* ---- usage ------------------------------------------------------------------------------------ */

void cli_common_usage(FILE *f, const cli_common *c)
{
    bool lists = takes(c, CLI_TAKES_LISTS);
    fputs("\ncommon options (one parser for render, sheet, compare, bench and view):\n", f);
    if (takes(c, CLI_TAKES_SCENE)) {
        fputs("  --scene NAME|PATH     built-in (cornell, corner, sphere-on-plane, slab, grille, bleed),\n"
              "                        a named scene from scenes/ (bunny, fzk-haus, cornell-obj) or any\n"
              "                        model Assimp reads\n",
              f);
        if (c->scene) fprintf(f, "                        (default %s)\n", c->scene);
        else fputs("                        (required)\n", f);
    }
    fputs("  --sidecar FILE        scene sidecar JSON (default: MODEL.obscura.json beside the model)\n"
          "  --up y|z              the model's up axis (overrides the sidecar)\n"
          "  --allow-external-files  let the model read files outside its directory (absolute paths,\n"
          "                        '..'; off: untrusted models are confined, README 'Untrusted models')\n"
          "  --max-memory SIZE     the most memory the run may take, e.g. 512M, 8G: the model, its\n"
          "                        textures, the render targets for --size/--guard, path frames kept;\n"
          "                        estimated before allocating (default: 4G or half the physical\n"
          "                        memory, whichever is less)\n",
          f);
    if (takes(c, CLI_TAKES_CAMERA))
        fputs("  --camera NAME|INDEX   a camera preset of the scene (default: 'default', which frames the\n"
              "                        scene's bounds unless its sidecar defines it)\n"
              "  --eye X,Y,Z --target X,Y,Z [--fov DEG]   an explicit camera (world units, degrees)\n",
              f);
    if (takes(c, CLI_TAKES_PATH))
        fputs("  --path NAME           move the camera along the scene's sidecar path NAME (docs/temporal.md)\n"
              "  --orbit DEG           or turn it DEG about the vertical through its target\n"
              "  --path-frames N       frames along the path or orbit, 2..10000 (default 32)\n"
              "  --jitter J|on|off     sub-pixel jitter of the G-buffer over J Halton points (on = 8), as\n"
              "                        TAA does: with --temporal on the history averages each pixel's\n"
              "                        footprint (docs/temporal.md, \"Jitter\"); compare's path rows\n"
              "                        are graded against AO_R averaged over the same points (default:\n"
              "                        on for compare's path rows, off otherwise)\n",
              f);
    fprintf(f, "  --size WxH            image size (default %dx%d)\n", c->width, c->height);
    fputs("  --allow-empty         write a frame that covers no pixel (else: \"nothing visible from this\n"
          "                        camera\", exit 2 for --eye/--target, 3 for a scene's camera)\n",
          f);
    if (lists) {
        fprintf(f, "  --methods all|A,B     AO methods, see `obscura list` (default %s); --method A for one\n",
                c->default_method ? c->default_method : "all");
        fputs("  --filters A,B         denoising filters after the AO pass: none, box4, gaussian, bilateral,\n"
              "                        bilateral_sep, geometry, crease (default crease); --filter A for one\n"
              "  --ao-scales S,S       AO at 1, 0.5 and/or 0.25 of the size, then joint bilateral\n"
              "                        upsampling (default 1); --ao-scale S for one\n"
              "  --quality Q,Q         low|medium|high|ultra = 12/24/36/64 samples per pixel (Belonogov 2018);\n"
              "                        HBAO as directions x steps, gtao as 2 x slices x steps; vbao and\n"
              "                        vbgi keep 6 steps over 1/2/3/5 slices (ultra 60), so the presets\n"
              "                        change their noise and not their mean AO\n"
              "  --samples N,N         samples per pixel (instead of --quality), 1..2048; each method stops\n"
              "                        at its own maximum: 256 (ssao, crytek, alchemy, ssdo*), 1024 (hbao)\n"
              "                        Each combination of these lists is one row, labelled with the\n"
              "                        values that vary (e.g. 'hbao · filter none · ao 0.5'); a method\n"
              "                        that takes no sample count runs once\n",
              f);
    } else {
        fprintf(f, "  --method NAME         AO method: see `obscura list` (default %s)\n",
                c->default_method ? c->default_method : "all");
        fputs("  --filter NAME         denoising after the AO pass: none, box4, gaussian, bilateral,\n"
              "                        bilateral_sep, geometry, crease (default)\n"
              "  --ao-scale S          run the AO at 1, 0.5 or 0.25 of the size, then joint bilateral\n"
              "                        upsampling (default 1)\n"
              "  --quality Q           low|medium|high|ultra = 12/24/36/64 samples per pixel (Belonogov 2018);\n"
              "                        HBAO as directions x steps, gtao as 2 x slices x steps; vbao and\n"
              "                        vbgi keep 6 steps over 1/2/3/5 slices (ultra 60), so the presets\n"
              "                        change their noise and not their mean AO\n"
              "  --samples N           samples per pixel, overriding --quality, 1..2048; each method stops\n"
              "                        at its own maximum: 256 (ssao, crytek, alchemy, ssdo*), 1024 (hbao)\n",
              f);
    }
    fputs("  --set M.P=V           set a parameter of method or filter M, validated (repeatable; after\n"
          "                        --quality), e.g. ssao.radius=0.5 or geometry.radius=7\n"
          "  --settings FILE|DIR   tuned parameters (obscura tune --out): one method's FILE.json or a\n"
          "                        directory of them; lists show each tuned method at its defaults\n"
          "                        and tuned ('hbao · tuned'), single runs use it tuned (a lone FILE\n"
          "                        also picks the method); --set still wins\n"
          "  --guard PX|F%         guard band (Belonogov 2018 §3.2.2): render the G-buffer and the AO chain\n"
          "                        PX pixels (or F% of the larger dimension) beyond each side of the\n"
          "                        frame, so occluders just outside it darken the border; cropped at\n"
          "                        compose (default 0 = off; rounded up to a multiple of 4 x the AO\n"
          "                        divisor; the AO chain costs about (W+2g)(H+2g)/WH)\n"
          "  --temporal on|off     temporal accumulation (docs/temporal.md): reproject last frame's AO\n"
          "                        through depth and the last camera, reject disocclusions, clamp to\n"
          "                        the 4x4 neighbourhood, blend over --temporal-frames; turns every\n"
          "                        method's noise with the frame index (default off)\n"
          "  --temporal-at before|after  accumulate before (default) or after the spatial filter\n"
          "  --temporal-frames N   history length, 1..256 (default 16)\n"
          "  --temporal-detail A   keep at least this share (0..1) of one-pixel detail while the\n"
          "                        camera moves: sharper against the reference, more flicker\n"
          "                        (docs/temporal.md, \"Thin detail under motion\"; default 0 = off)\n"
          "  --upsample auto|plain|block  the upsampler's program at --ao-scale 0.5 or 0.25 (the same\n"
          "                        bits): block reads the AO grid once per k x k pixels, plain once\n"
          "                        per pixel (the baseline); auto (default): block on a software\n"
          "                        rasteriser, plain on a GPU\n"
          "  --adaptive on|off     per-pixel sample counts from an edge pre-pass (default off; every\n"
          "                        method takes them, see docs/filters.md)\n"
          "  --light SPEC          replaces the scene's lights (repeatable, up to 8), e.g.\n"
          "                        'directional dir=0.3,1,0.2 color=1,0.9,0.8 intensity=2',\n"
          "                        'point pos=0,2,0 intensity=8 range=10',\n"
          "                        'spot pos=0,3,0 dir=0,-1,0 cone=20,30 intensity=20'\n"
          "  --ambient MODE        constant (default), hemisphere (sky/ground) or env (needs --env)\n"
          "  --ambient-color R,G,B the constant ambient radiance (default 0.3,0.3,0.3)\n"
          "  --env FILE.hdr        equirectangular environment map (Radiance .hdr)\n"
          "  --ao-light ambient|all  AO darkens the ambient term (default) or all light\n"
          "  --multibounce on|off  AO through Jimenez et al. 2016's multi-bounce fit with the albedo\n"
          "                        (bright surfaces lift their occlusion; default off)\n"
          "  --textures on|off     the models' diffuse textures (default on); off draws each material in\n"
          "                        its diffuse colour, which shows the AO alone (Puri 2024 §3.6)\n"
          "  --shadow none|hard|pcf|vsm  shadow maps for the lights (default pcf)\n"
          "  --shadow-size N       shadow map resolution (default 2048)\n"
          "  --shadow-bias B       constant bias in map texels; --shadow-slope-bias S slope-scaled\n"
          "  --pcf-radius R        PCF kernel taps each side (1 = 3x3); --vsm-blur SIGMA (texels);\n"
          "                        --vsm-bleed T (light-bleeding reduction, 0..1); --vsm-bits 16|32\n"
          "                        (the moments' precision, default 32; SSDO thesis Fig. 6.5)\n"
          "  --hdr on|off          tone mapping (Reinhard, auto key, bloom) or a plain clamp (default on)\n"
          "  --exposure E          linear scale before tone mapping (default 1)\n"
          "  --key A               Reinhard key, 0.001..10 (0.18 = middle grey); default automatic from\n"
          "                        the log-average (0.03 for black, toward 1.03 for bright)\n"
          "  --white L             L_white: the scaled luminance mapped to white (0 = eq. 2.3)\n"
          "  --bloom S             bloom strength (0 = off); --bloom-threshold T\n",
          f);
    if (takes(c, CLI_TAKES_GPU))
        fputs("  --gpu auto|hw|sw      hardware EGL device, Mesa llvmpipe, or hardware first (default auto)\n"
              "  -v                    print the GL renderer and device\n"
              "  --shader-dir DIR      compile the shaders from DIR (a copy of the source tree's shaders/,\n"
              "                        edited) instead of the built-in ones: A/B a shader edit without a\n"
              "                        rebuild, e.g. bench --shader-dir old/shaders against the built-in\n",
              f);
}

/* ---- settings --------------------------------------------------------------------------------- */

/* What an --set assignment names: "M.P=V" a method and/or filter M (none is both), "P=V" the
 * method in use. */
typedef struct set_target {
    bool prefixed;
    int method, filter; /* registry indices, -1 when M is not one */
    int prefix_len;
} set_target;

static set_target set_target_of(const char *a)
{
    set_target t = {false, -1, -1, 0};
    const char *eq = strchr(a, '=');
    size_t key_len = eq ? (size_t)(eq - a) : strlen(a);
    const char *dot = memchr(a, '.', key_len);
    if (!dot) return t;
    t.prefixed = true;
    t.prefix_len = (int)(dot - a);
    char name[ITEM_MAX] = "";
    snprintf(name, sizeof name, "%.*s", t.prefix_len, a);
    t.method = ob_find_method(name);
    t.filter = ob_find_filter(name);
    return t;
}

static bool set_applies(const set_target *t, const cli_config *cfg)
{
    return !t->prefixed || t->method == cfg->method || t->filter == cfg->filter;
}

static void append(char *out, size_t n, const char *fmt, const char *a, const char *b)
{
    size_t len = strlen(out);
    if (len < n) snprintf(out + len, n - len, fmt, a, b);
}

void cli_config_label(const cli_common *c, const cli_config *cfg, const char *sep, char *out, size_t n)
{
    snprintf(out, n, "%s", ob_method_at(cfg->method)->name);
    if (c->filter_count > 1) append(out, n, "%sfilter %s", sep, ob_filter_at(cfg->filter)->name);
    if (c->ao_count > 1) append(out, n, "%sao %s", sep, ao_scale_text(cfg->ao_divisor));
    if (c->sample_count > 1 && cfg->samples.count > 0) {
        char count[16] = "";
        snprintf(count, sizeof count, "%d", cfg->samples.count);
        if (cfg->samples.quality) append(out, n, "%squality %s", sep, cfg->samples.quality);
        else append(out, n, "%ssamples %s", sep, count);
    }
    if (cfg->tuned) append(out, n, "%s%s", sep, "tuned");
}

/* The label as a file name: letters, digits, '-' and '_' ("hbao_filter-none_ao-0_5"). */
static void make_stem(const cli_common *c, const cli_config *cfg, char *out, size_t n)
{
    char raw[CLI_MAX_LABEL] = "";
    snprintf(raw, sizeof raw, "%s", ob_method_at(cfg->method)->name);
    if (c->filter_count > 1) append(raw, sizeof raw, "%sfilter-%s", "_", ob_filter_at(cfg->filter)->name);
    if (c->ao_count > 1) append(raw, sizeof raw, "%sao-%s", "_", ao_scale_text(cfg->ao_divisor));
    if (c->sample_count > 1 && cfg->samples.count > 0) {
        char count[16] = "";
        snprintf(count, sizeof count, "%d", cfg->samples.count);
        append(raw, sizeof raw, "%s%s", "_", cfg->samples.quality ? "quality-" : "samples-");
        append(raw, sizeof raw, "%s%s", cfg->samples.quality ? cfg->samples.quality : count, "");
    }
    if (cfg->tuned) append(raw, sizeof raw, "%s%s", "_", "tuned");
    size_t k = 0;
    for (const char *p = raw; *p && k + 1 < n; ++p) {
        char ch = *p;
        bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '-' || ch == '_';
        out[k++] = ok ? ch : '_';
    }
    out[k] = '\0';
}

int cli_common_apply(const cli_common *c, cli_config *cfg)
{
    ob_settings *s = &cfg->settings;
    if (ob_settings_init(s, ob_method_at(cfg->method)->name) != OB_OK) return cli_fail_from_library();
    if (ob_settings_set_filter(s, ob_filter_at(cfg->filter)->name) != OB_OK ||
        ob_settings_set_ao_divisor(s, cfg->ao_divisor) != OB_OK)
        return cli_fail_from_library();
    s->adaptive = c->adaptive;
    s->guard = c->guard_px;
    s->temporal = c->temporal;
    s->temporal_at = c->temporal_at;
    s->upsample = c->upsample;
    s->jitter = c->jitter > 0 ? c->jitter : 0;
    s->temporal_frames = c->temporal_frames;
    s->temporal_detail = c->temporal_detail;
    /* Every method adapts today; a new one that does not is named here rather than silently
     * ignoring the option. none takes no samples at all: nothing to say (bench's baseline frames
     * are none). */
    if (c->adaptive && !ob_method_at(cfg->method)->adapts && strcmp(ob_method_at(cfg->method)->name, "none") != 0) {
        /* Once per method and run: lists repeat a method in many rows. */
        static bool told[64];
        if (cfg->method < 64 && !told[cfg->method]) {
            char which[256] = "";
            for (int m = 0; m < ob_method_count(); ++m)
                if (ob_method_at(m)->adapts)
                    snprintf(which + strlen(which), sizeof which - strlen(which), "%s%s", which[0] ? ", " : "",
                             ob_method_at(m)->name);
            fprintf(stderr, "obscura: note: --adaptive: %s has no adaptive sample count (%s have); it runs its fixed "
                            "count and no edge pass\n",
                    ob_method_at(cfg->method)->name, which);
        }
        if (cfg->method < 64) told[cfg->method] = true;
    }
    for (int i = 0; i < c->light_count; ++i)
        if (ob_parse_light(c->lights[i], &s->lights[i]) != OB_OK) return cli_fail_from_library();
    s->light_count = c->light_count;
    s->ambient_mode = c->ambient_mode;
    if (c->given & CLI_GIVEN_AMBIENT_COLOR) memcpy(s->ambient, c->ambient_color, sizeof s->ambient);
    s->ao_all_light = c->ao_all_light;
    s->multibounce = c->multibounce;
    s->textures_off = c->textures_off;
    ob_shadow_settings *sh = &s->shadow;
    if (c->given & CLI_GIVEN_SHADOW) sh->method = c->shadow;
    if (c->given & CLI_GIVEN_SHADOW_SIZE) sh->size = c->shadow_size;
    if (c->given & CLI_GIVEN_SHADOW_BIAS) sh->bias = c->shadow_bias;
    if (c->given & CLI_GIVEN_SLOPE_BIAS) sh->slope_bias = c->slope_bias;
    if (c->given & CLI_GIVEN_PCF_RADIUS) sh->pcf_radius = c->pcf_radius;
    if (c->given & CLI_GIVEN_VSM_BLUR) sh->vsm_blur = c->vsm_blur;
    if (c->given & CLI_GIVEN_VSM_BLEED) sh->vsm_bleed = c->vsm_bleed;
    if (c->given & CLI_GIVEN_VSM_BITS) sh->vsm_bits = c->vsm_bits;
    ob_hdr_settings *hdr = &s->hdr;
    hdr->enabled = !c->hdr_off;
    if (c->given & CLI_GIVEN_EXPOSURE) hdr->exposure = c->exposure;
    if (c->given & CLI_GIVEN_KEY) hdr->key = c->key;
    if (c->given & CLI_GIVEN_WHITE) hdr->l_white = c->white;
    if (c->given & CLI_GIVEN_BLOOM) hdr->bloom_strength = c->bloom;
    if (c->given & CLI_GIVEN_BLOOM_THRESHOLD) hdr->bloom_threshold = c->bloom_threshold;
    /* A method with no sample count (none) ignores --quality/--samples; anything else that the
     * method refuses (beyond its table) is an error. */
    if (cfg->samples.count > 0) {
        ob_error err = ob_settings_set_samples(s, cfg->samples.count);
        if (err == OB_ERR_INVALID_ARGUMENT) {
            ob_clear_error();
            cfg->samples = (cli_samples){0, NULL};
        } else if (err != OB_OK) {
            return cli_fail_from_library();
        }
    }
    if (cfg->tuned) {
        int code = cli_tuned_apply(cfg->tuned, s);
        if (code != EXIT_OK) return code;
    }
    for (int k = 0; k < c->set_count; ++k) {
        set_target t = set_target_of(c->sets[k]);
        if (set_applies(&t, cfg) && ob_settings_set(s, c->sets[k]) != OB_OK) {
            char where[ITEM_MAX + 16];
            snprintf(where, sizeof where, "--set %.*s", ITEM_MAX - 1, c->sets[k]);
            return cli_fail_from_library_in(where);
        }
    }
    /* After the samples: a method that took none is labelled without them. */
    cli_config_label(c, cfg, " \xc2\xb7 ", cfg->label, sizeof cfg->label); /* U+00B7 middle dot */
    make_stem(c, cfg, cfg->stem, sizeof cfg->stem);
    return EXIT_OK;
}

/* ---- memory (--max-memory) --------------------------------------------------------------------- */

/* What each command holds on the CPU besides the renderer, per visible pixel: its read-backs and
 * output buffers (render.c write_outputs, cli.c's exposure and visibility checks, outputs.c's
 * encoders; compare.c's per-view images, masks and references, flicker.c's running sums; sheet.c's
 * frame buffers), per row of a sheet (its part of the sheet image), and per path frame that
 * compare keeps for the flicker measure (flicker.c: each frame's depth, normals and reference, 20
 * bytes a pixel). Rounded up: an estimate, not a ledger. */
static const struct {
    const char *command;
    unsigned per_pixel, per_row, per_path_frame;
    bool path_temporal; /* its path frames run with temporal accumulation whatever --temporal says */
} HOLDS[] = {
    {"render", 48, 0, 0, false}, {"sheet", 24, 8, 0, false}, {"compare", 192, 0, 20, true},
    {"bench", 32, 0, 0, false},  {"tune", 64, 0, 0, false},  {"view", 32, 0, 0, false},
};

/* "1.50 GiB", "20.0 MiB", "12 KiB". */
static const char *human(uint64_t bytes, char *buf, size_t n)
{
    if (bytes >= (1ull << 30)) snprintf(buf, n, "%.2f GiB", (double)bytes / (double)(1ull << 30));
    else if (bytes >= (1ull << 20)) snprintf(buf, n, "%.1f MiB", (double)bytes / (double)(1ull << 20));
    else snprintf(buf, n, "%llu KiB", (unsigned long long)((bytes + 1023u) / 1024u));
    return buf;
}

typedef struct memory_item {
    uint64_t bytes;
    char text[192];
} memory_item;

/* printf at the end of out (n bytes in all), cut to fit. */
static void appendf(char *out, size_t n, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void appendf(char *out, size_t n, const char *fmt, ...)
{
    size_t len = strlen(out);
    if (len + 1 >= n) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(out + len, n - len, fmt, ap);
    va_end(ap);
}

/* The settings each combination's renderer is made for, as far as memory goes: every method with
 * every AO scale, the guard band, temporal accumulation, the shadows and --light's lights, and the
 * --set assignments that reach the method (a "guard=" among them). *count 0 when none can be
 * made (an unknown name: reported later by cli_common_configs). */
static ob_settings *memory_probes(const cli_common *c, bool temporal, int *count)
{
    *count = 0;
    ob_settings *probes = calloc((size_t)(c->method_count * c->ao_count) + 1, sizeof *probes);
    if (!probes) return NULL;
    for (int m = 0; m < c->method_count; ++m)
        for (int a = 0; a < c->ao_count; ++a) {
            ob_settings *s = &probes[*count];
            if (ob_settings_init(s, ob_method_at(c->methods[m])->name) != OB_OK ||
                ob_settings_set_ao_divisor(s, c->ao_divisors[a]) != OB_OK) {
                ob_clear_error();
                continue;
            }
            s->guard = c->guard_px;
            s->temporal = temporal;
            if (c->given & CLI_GIVEN_SHADOW) s->shadow.method = c->shadow;
            if (c->given & CLI_GIVEN_SHADOW_SIZE) s->shadow.size = c->shadow_size;
            if (c->given & CLI_GIVEN_VSM_BITS) s->shadow.vsm_bits = c->vsm_bits;
            for (int i = 0; i < c->light_count; ++i)
                if (ob_parse_light(c->lights[i], &s->lights[s->light_count]) == OB_OK) ++s->light_count;
            const cli_config cfg = {.method = c->methods[m], .filter = c->filters[0]};
            for (int k = 0; k < c->set_count; ++k) {
                set_target t = set_target_of(c->sets[k]);
                if (set_applies(&t, &cfg) && ob_settings_set(s, c->sets[k]) != OB_OK) ob_clear_error(); /* reported later */
            }
            ++*count;
        }
    return probes;
}

/* What the run takes besides the scene, by item (largest first), into c->run_memory and
 * c->run_memory_what; over the limit, one line naming the largest items and EXIT_USAGE. */
static int check_run_memory(cli_common *c)
{
    unsigned per_pixel = 64, per_row = 0, per_path_frame = 0;
    bool path_temporal = false;
    for (size_t k = 0; k < sizeof HOLDS / sizeof HOLDS[0]; ++k)
        if (!strcmp(c->command, HOLDS[k].command)) {
            per_pixel = HOLDS[k].per_pixel;
            per_row = HOLDS[k].per_row;
            per_path_frame = HOLDS[k].per_path_frame;
            path_temporal = HOLDS[k].path_temporal && cli_common_moves(c);
        }
    int count = 0;
    ob_settings *probes = memory_probes(c, c->temporal || path_temporal, &count);
    if (!probes) return cli_fail(EXIT_RUNTIME, "out of memory");
    uint64_t with_shadows = 0, targets = 0;
    int guard = 0; /* --guard, or a --set guard= that reaches a method */
    for (int k = 0; k < count; ++k)
        if (probes[k].guard > guard) guard = probes[k].guard;
    const int rw = c->memory_width > 0 ? c->memory_width : c->width;
    const int rh = c->memory_height > 0 ? c->memory_height : c->height;
    const uint64_t renderers = c->renderers > 1 ? (uint64_t)c->renderers : 1u;
    if (count > 0) {
        with_shadows = renderers * ob_estimate_renderer_memory(rw, rh, probes, count);
        for (int k = 0; k < count; ++k) probes[k].shadow.method = OB_SHADOW_NONE;
        targets = renderers * ob_estimate_renderer_memory(rw, rh, probes, count);
    }
    free(probes);
    const uint64_t px = (uint64_t)c->width * (uint64_t)c->height;
    const int rows = c->method_count * c->filter_count * c->ao_count * (c->sample_count > 0 ? c->sample_count : 1);
    const int frames = cli_common_moves(c) ? c->path_frames : 0;
    char a[32] = "";
    enum { ITEMS = 5 };
    memory_item items[ITEMS] = {{0, ""}, {0, ""}, {0, ""}, {0, ""}, {0, ""}};
    items[0].bytes = targets;
    char *t = items[0].text;
    const size_t tn = sizeof items[0].text;
    appendf(t, tn, "render targets %s (", human(targets, a, sizeof a));
    if (renderers > 1) appendf(t, tn, "%d renderers of ", c->renderers);
    appendf(t, tn, "%s %dx%d", rw == c->width && rh == c->height ? "--size" : "--sizes up to", rw, rh);
    if (guard > 0) appendf(t, tn, ", %s %d", guard == c->guard_px ? "--guard" : "guard band", guard);
    if (c->temporal || path_temporal) appendf(t, tn, ", temporal history");
    if (c->method_count > 1) appendf(t, tn, ", %d methods", c->method_count);
    if (c->ao_count > 1) appendf(t, tn, ", %d AO scales", c->ao_count);
    appendf(t, tn, ")");
    items[1].bytes = with_shadows - targets;
    snprintf(items[1].text, sizeof items[1].text, "shadow maps %s (--shadow-size %d)", human(items[1].bytes, a, sizeof a),
             (c->given & CLI_GIVEN_SHADOW_SIZE) ? c->shadow_size : 2048);
    items[2].bytes = px * ((uint64_t)per_pixel + (uint64_t)per_row * (uint64_t)rows);
    snprintf(items[2].text, sizeof items[2].text, "image buffers %s", human(items[2].bytes, a, sizeof a));
    items[3].bytes = px * (uint64_t)per_path_frame * (uint64_t)frames;
    snprintf(items[3].text, sizeof items[3].text, "path frames %s (--path-frames %d x %dx%d)",
             human(items[3].bytes, a, sizeof a), frames, c->width, c->height);
    /* --env: decoded as RGB floats (12 bytes a pixel) while its RGBA16F texture and MIP chain
     * (8 x 4/3) are made, and stb's scanline buffers: 24 bytes a pixel at the peak, rounded up.
     * Sized from the file's header, never decoded here; an unreadable map is reported when it
     * loads. */
    long long ew = 0, eh = 0;
    if (c->env && cli_hdr_dimensions(c->env, &ew, &eh)) {
        items[4].bytes = (uint64_t)ew * (uint64_t)eh * 24u;
        snprintf(items[4].text, sizeof items[4].text, "environment map %s (%.80s %lldx%lld)",
                 human(items[4].bytes, a, sizeof a), c->env, ew, eh);
    }
    c->run_memory = 0;
    c->run_memory_what[0] = '\0';
    for (int i = 0; i < ITEMS; ++i) {
        int best = i;
        for (int j = i + 1; j < ITEMS; ++j)
            if (items[j].bytes > items[best].bytes) best = j;
        memory_item keep = items[i];
        items[i] = items[best];
        items[best] = keep;
        c->run_memory += items[i].bytes;
        if (items[i].bytes == 0) continue;
        appendf(c->run_memory_what, sizeof c->run_memory_what, "%s%s", c->run_memory_what[0] ? ", " : "", items[i].text);
    }
    const uint64_t limit = c->max_memory ? c->max_memory : ob_default_max_memory();
    if (c->run_memory <= limit) return EXIT_OK;
    char b[32] = "";
    if (c->max_memory_text)
        return cli_fail(EXIT_USAGE, "--max-memory %s: this run needs about %s before any model: %s", c->max_memory_text,
                        human(c->run_memory, a, sizeof a), c->run_memory_what);
    return cli_fail(EXIT_USAGE, "--max-memory (default %s): this run needs about %s before any model: %s",
                    human(limit, b, sizeof b), human(c->run_memory, a, sizeof a), c->run_memory_what);
}

/* Whether the method takes a sample count: ob_settings_set_samples refuses with
 * OB_ERR_INVALID_ARGUMENT when it does not. */
static bool takes_samples(int method, int count)
{
    ob_settings probe = {0};
    if (ob_settings_init(&probe, ob_method_at(method)->name) != OB_OK) return false;
    ob_error err = ob_settings_set_samples(&probe, count);
    if (err != OB_OK) ob_clear_error(); /* an out-of-range count is reported by cli_common_apply */
    return err != OB_ERR_INVALID_ARGUMENT;
}

/* Each --set must reach at least one combination; the reasons it does not, one line each. */
static int check_sets(const cli_common *c, cli_config *configs, int count)
{
    for (int k = 0; k < c->set_count; ++k) {
        const char *a = c->sets[k];
        set_target t = set_target_of(a);
        if (!t.prefixed && c->method_count > 1)
            return cli_fail(EXIT_USAGE, "--set %s: expected METHOD.PARAM=VALUE with more than one method", a);
        if (t.prefixed && t.method < 0 && t.filter < 0)
            return cli_fail(EXIT_USAGE, "--set %s: unknown method '%.*s' (nor a filter; see obscura list)", a, t.prefix_len, a);
        bool reached = false;
        for (int i = 0; i < count && !reached; ++i) reached = set_applies(&t, &configs[i]);
        if (reached) continue;
        if (t.method >= 0 && takes(c, CLI_TAKES_LISTS))
            return cli_fail(EXIT_USAGE, "--set %s: method '%.*s' is not in --methods", a, t.prefix_len, a);
        if (t.filter >= 0 && c->filter_count > 1)
            return cli_fail(EXIT_USAGE, "--set %s: filter '%.*s' is not in --filters", a, t.prefix_len, a);
        /* One method and one filter: the library says which it is ("... but the filter is geometry"). */
        ob_settings s = {0};
        if (ob_settings_init(&s, ob_method_at(configs[0].method)->name) != OB_OK ||
            ob_settings_set_filter(&s, ob_filter_at(configs[0].filter)->name) != OB_OK || ob_settings_set(&s, a) != OB_OK) {
            char where[ITEM_MAX + 16];
            snprintf(where, sizeof where, "--set %.*s", ITEM_MAX - 1, a);
            return cli_fail_from_library_in(where);
        }
    }
    return EXIT_OK;
}

/* The --settings entry for a method, or NULL. */
const cli_tuned *cli_common_tuned(const cli_common *c, int method)
{
    for (int i = 0; i < c->tuned_count; ++i)
        if (c->tuned[i].method == method) return &c->tuned[i];
    return NULL;
}

/* Rows per combination: with lists, a tuned method runs at its defaults and tuned. */
static int runs_of(const cli_common *c, int method)
{
    return takes(c, CLI_TAKES_LISTS) && cli_common_tuned(c, method) ? 2 : 1;
}

int cli_common_configs(const cli_common *c, cli_config **configs, int *count)
{
    *configs = NULL;
    *count = 0;
    int total = 0;
    for (int m = 0; m < c->method_count; ++m) {
        bool counted = c->sample_count > 0 && takes_samples(c->methods[m], c->samples[0].count);
        total += c->filter_count * c->ao_count * (counted ? c->sample_count : 1) * runs_of(c, c->methods[m]);
    }
    if (total > CLI_MAX_CONFIGS)
        return cli_fail(EXIT_USAGE, "%d combinations of the lists (methods x filters x ao scales x samples), more than %d",
                        total, CLI_MAX_CONFIGS);
    if (total == 0) return cli_fail(EXIT_USAGE, "no method to run");
    cli_config *out = calloc((size_t)total, sizeof *out);
    if (!out) return cli_fail(EXIT_RUNTIME, "out of memory");
    int n = 0, code = EXIT_OK;
    for (int m = 0; m < c->method_count; ++m) {
        bool counted = c->sample_count > 0 && takes_samples(c->methods[m], c->samples[0].count);
        for (int f = 0; f < c->filter_count; ++f)
            for (int a = 0; a < c->ao_count; ++a)
                for (int q = 0; q < (counted ? c->sample_count : 1); ++q)
                    for (int t = 0; t < runs_of(c, c->methods[m]); ++t) {
                        /* With lists, run 0 is the defaults and run 1 the tuned settings; without,
                         * the one run is tuned when a file tunes the method. */
                        const cli_tuned *tuned = cli_common_tuned(c, c->methods[m]);
                        cli_config *cfg = &out[n++];
                        *cfg = (cli_config){.method = c->methods[m], .filter = c->filters[f],
                                            .ao_divisor = c->ao_divisors[a],
                                            .samples = counted ? c->samples[q] : (cli_samples){0, NULL},
                                            .tuned = takes(c, CLI_TAKES_LISTS) && t == 0 ? NULL : tuned};
                    }
    }
    /* Whom each --set is for before any is applied: a misdirected one gets its own message. */
    code = check_sets(c, out, n);
    for (int i = 0; i < n && code == EXIT_OK; ++i) code = cli_common_apply(c, &out[i]);
    if (code != EXIT_OK) {
        free(out);
        return code;
    }
    *configs = out;
    *count = n;
    return EXIT_OK;
}

/* ---- scene, camera, renderer ------------------------------------------------------------------ */

/* The shadow maps the scene's own lights add to the key light's, which check_run_memory counted
 * (with no --light a frame takes the scene's lights: a sidecar may give eight point lights, six
 * layers each). The same settings as the estimate's, with and without the lights. */
static uint64_t scene_light_memory(const cli_common *c, const ob_scene *scene, int *lights)
{
    *lights = ob_query_scene_light_count(scene);
    if (c->light_count > 0 || *lights <= 1 || c->method_count < 1) return 0;
    ob_settings s = {0};
    if (ob_settings_init(&s, ob_method_at(c->methods[0])->name) != OB_OK) {
        ob_clear_error();
        return 0;
    }
    if (c->given & CLI_GIVEN_SHADOW) s.shadow.method = c->shadow;
    if (c->given & CLI_GIVEN_SHADOW_SIZE) s.shadow.size = c->shadow_size;
    if (c->given & CLI_GIVEN_VSM_BITS) s.shadow.vsm_bits = c->vsm_bits;
    const int rw = c->memory_width > 0 ? c->memory_width : c->width;
    const int rh = c->memory_height > 0 ? c->memory_height : c->height;
    const uint64_t key_only = ob_estimate_renderer_memory(rw, rh, &s, 1);
    for (int i = 0; i < *lights && i < OB_MAX_LIGHTS; ++i) s.lights[s.light_count++] = ob_query_scene_light(scene, i);
    const uint64_t all = ob_estimate_renderer_memory(rw, rh, &s, 1);
    const uint64_t renderers = c->renderers > 1 ? (uint64_t)c->renderers : 1u;
    return all > key_only ? renderers * (all - key_only) : 0;
}

int cli_common_load_scene(const cli_common *c, const char *name, ob_scene **out)
{
    *out = ob_load_scene(&(ob_scene_desc){.name = name ? name : c->scene, .sidecar = c->sidecar, .up = c->up,
                                          .allow_external_files = c->allow_external_files,
                                          .max_memory = c->max_memory, .reserved_memory = c->run_memory,
                                          .reserved_what = c->run_memory_what, .automatic_ground = true});
    if (!*out) return cli_fail_from_library();
    /* A model without a sidecar stands on a ground the loader added: say so, once per load. */
    for (int i = ob_query_scene_material_count(*out) - 1; i >= 0; --i)
        if (!strcmp(ob_query_scene_material(*out, i).name, OB_AUTOMATIC_GROUND_MATERIAL)) {
            printf("note: %s has no sidecar: it stands on a ground added under it (a sidecar MODEL.obscura.json "
                   "chooses; docs/scenes.md)\n",
                   ob_query_scene_name(*out));
            break;
        }
    int lights = 0;
    const uint64_t extra = scene_light_memory(c, *out, &lights);
    const uint64_t limit = c->max_memory ? c->max_memory : ob_default_max_memory();
    if (extra == 0 || c->run_memory + extra <= limit) return EXIT_OK;
    char a[32] = "", b[32] = "", l[32] = "";
    const char *scene = ob_query_scene_name(*out);
    int code = cli_fail(EXIT_INPUT, "--max-memory %s%s: scene '%s' has %d lights, whose shadow maps take %s more than its "
                        "key light's: this run needs about %s (%s); --shadow-size, --shadow none or --light lower it",
                        c->max_memory_text ? c->max_memory_text : human(limit, l, sizeof l),
                        c->max_memory_text ? "" : " (the default)", scene, lights, human(extra, a, sizeof a),
                        human(c->run_memory + extra, b, sizeof b), c->run_memory_what);
    ob_destroy_scene(*out);
    *out = NULL;
    return code;
}

int cli_common_camera(const cli_common *c, const ob_scene *scene, const char *preset, ob_camera *cam)
{
    if (c->has_eye) {
        memset(cam, 0, sizeof *cam);
        memcpy(cam->eye, c->eye, sizeof cam->eye);
        memcpy(cam->target, c->target, sizeof cam->target);
        cam->fov_y_deg = c->has_fov ? c->fov : 60.0f;
        snprintf(cam->name, sizeof cam->name, "explicit");
        /* The check every camera passes (ob_check_camera), named by the options that gave it. */
        if (ob_check_camera(cam) != OB_OK) {
            const char *why = NULL;
            ob_get_error(&why);
            return cli_fail(EXIT_USAGE, "--eye/--target%s: %s", c->has_fov ? "/--fov" : "", why ? why : "invalid");
        }
        return EXIT_OK;
    }
    const char *name = preset ? preset : c->camera ? c->camera : "default";
    if (ob_find_camera(scene, name, cam) != OB_OK) return cli_fail_from_library();
    if (c->has_fov) cam->fov_y_deg = c->fov;
    if (ob_check_camera(cam) != OB_OK) {
        const char *why = NULL;
        ob_get_error(&why);
        return cli_fail(c->has_fov ? EXIT_USAGE : EXIT_INPUT, "camera %s:%s: %s", ob_query_scene_name(scene), cam->name,
                        why ? why : "invalid");
    }
    return EXIT_OK;
}

bool cli_common_moves(const cli_common *c) { return c->path || c->has_orbit; }

int cli_common_path_jitter(const cli_common *c) { return c->jitter >= 0 ? c->jitter : OB_JITTER_POSITIONS_DEFAULT; }

const char *cli_common_temporal_at(const cli_common *c)
{
    return c->temporal_at == OB_TEMPORAL_AFTER_FILTER ? "after" : "before";
}

int cli_common_temporal_frames(const cli_common *c)
{
    return c->temporal_frames > 0 ? c->temporal_frames : OB_TEMPORAL_FRAMES_DEFAULT;
}

void cli_common_temporal_json(const cli_common *c, cJSON *root)
{
    cJSON *t = cJSON_AddObjectToObject(root, "temporal_settings");
    cJSON_AddStringToObject(t, "at", cli_common_temporal_at(c));
    cli_json_add_number(t, "frames", cli_common_temporal_frames(c));
    cli_json_add_number(t, "detail", c->temporal_detail);
    if (cli_common_moves(c)) cli_json_add_number(t, "jitter_positions", cli_common_path_jitter(c));
}

int cli_common_path_camera(const cli_common *c, const ob_scene *scene, const ob_camera *base, int f, ob_camera *out)
{
    const int n = c->path_frames > 1 ? c->path_frames : CLI_PATH_FRAMES;
    const float u = (float)f / (float)(n - 1);
    if (c->path) {
        char where[160];
        snprintf(where, sizeof where, "--path %.63s: frame %d of %d", c->path, f, n);
        if (ob_camera_on_path(scene, c->path, u, out) != OB_OK) return cli_fail_from_library_in(where);
        if (c->has_fov) out->fov_y_deg = c->fov;
        /* Every key passed the camera check; a camera between them can still fail it (the spline
         * overshooting onto its target): said with the path and frame, not as a bare camera. */
        if (ob_check_camera(out) != OB_OK) return cli_fail_from_library_in(where);
        return EXIT_OK;
    }
    *out = c->has_orbit ? ob_camera_orbit(base, c->orbit_deg * u) : *base;
    return EXIT_OK;
}

int cli_common_prepare(const cli_common *c, ob_renderer *r)
{
    if (c->env && ob_renderer_set_environment(r, c->env) != OB_OK) return cli_fail_from_library();
    return EXIT_OK;
}
