/* obscura render: one scene, one method, one camera -> PNG (+ AO as PFM/PNG). */
#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static void render_usage(FILE *f)
{
    fputs("usage: obscura render [options]\n"
          "\n"
          "  --scene NAME|PATH     built-in (cornell, corner, sphere-on-plane), a named scene from\n"
          "                        scenes/ (bunny, fzk-haus, cornell-obj) or any model Assimp reads\n"
          "                        (default cornell)\n"
          "  --sidecar FILE        scene sidecar JSON (default: MODEL.obscura.json beside the model)\n"
          "  --up y|z              the model's up axis (overrides the sidecar)\n"
          "  --method NAME         AO method: see `obscura list` (default ssao)\n"
          "  --set M.P=V           set a method parameter, validated (repeatable), e.g. ssao.radius=0.5\n"
          "  --quality Q           low|medium|high|ultra = 12/24/36/64 samples per pixel (seed 000);\n"
          "                        HBAO takes them as directions x steps\n"
          "  --samples N           samples per pixel, overriding --quality\n"
          "  --filter NAME         denoising after the AO pass: none, box4, gaussian, bilateral,\n"
          "                        bilateral_sep, geometry (default); parameters with --set NAME.P=V\n"
          "  --ao-scale S          run the AO at 1, 0.5 or 0.25 of the size, then joint bilateral\n"
          "                        upsampling (default 1)\n"
          "  --adaptive on|off     per-pixel sample counts from an edge pre-pass (default off)\n"
          "  --view V              what --out shows: final (default), ao, normals, depth, shadow (the key\n"
          "                        light's visibility), radiance (direct light, tone mapped), samples\n"
          "                        (per pixel, grey, white = the most any pixel took), bounce (SSDO's\n"
          "                        one-bounce indirect light, sRGB; black for AO methods); for ssdo*\n"
          "                        ao shows the RGB modulation factor M\n"
          "  --light SPEC          replaces the scene's lights (repeatable, up to 8), e.g.\n"
          "                        'directional dir=0.3,1,0.2 color=1,0.9,0.8 intensity=2',\n"
          "                        'point pos=0,2,0 intensity=8 range=10',\n"
          "                        'spot pos=0,3,0 dir=0,-1,0 cone=20,30 intensity=20'\n"
          "  --ambient MODE        constant (default), hemisphere (sky/ground) or env (needs --env)\n"
          "  --ambient-color R,G,B the constant ambient radiance (default 0.3,0.3,0.3)\n"
          "  --env FILE.hdr        equirectangular environment map (Radiance .hdr)\n"
          "  --ao-light ambient|all  AO darkens the ambient term (default) or all light\n"
          "  --shadow none|hard|pcf|vsm  shadow maps for the lights (default pcf)\n"
          "  --shadow-size N       shadow map resolution (default 2048)\n"
          "  --shadow-bias B       constant bias in map texels; --shadow-slope-bias S slope-scaled\n"
          "  --pcf-radius R        PCF kernel taps each side (1 = 3x3); --vsm-blur SIGMA (texels);\n"
          "                        --vsm-bleed T (light-bleeding reduction, 0..1)\n"
          "  --hdr on|off          tone mapping (Reinhard, auto key, bloom) or a plain clamp (default on)\n"
          "  --exposure E          linear scale before tone mapping (default 1)\n"
          "  --key A               Reinhard key (0.045..0.9); default automatic from the log-average\n"
          "  --white L             L_white: the scaled luminance mapped to white (0 = eq. 2.3)\n"
          "  --bloom S             bloom strength (0 = off); --bloom-threshold T\n"
          "  --size WxH            image size (default 640x480)\n"
          "  --camera NAME|INDEX   a camera preset of the scene (default: 'default', which frames the\n"
          "                        scene's bounds unless its sidecar defines it)\n"
          "  --eye X,Y,Z --target X,Y,Z [--fov DEG]   an explicit camera (world units, degrees)\n"
          "  --out FILE.png        the final image (required)\n"
          "  --ao-out FILE.pfm     the AO map as exact floats (PFM, bottom row first)\n"
          "  --ao-png FILE.png     the AO map as an 8-bit grey PNG\n"
          "  --depth-out FILE.pfm  linear view depth; --normal-out FILE.pfm view-space normals\n"
          "  --frames N            render N frames (timings are medians over them; default 1)\n"
          "  --timings             print GPU time per pass (GL timestamp queries)\n"
          "  --gpu auto|hw|sw      hardware EGL device, Mesa llvmpipe, or hardware first (default auto)\n"
          "  -v                    print the GL renderer and device\n",
          f);
}

typedef struct render_opts {
    const char *scene, *sidecar, *method, *filter, *view, *camera, *out, *ao_out, *ao_png, *depth_out, *normal_out;
    float ao_scale;
    bool adaptive;
    const char *lights[OB_MAX_LIGHTS];
    int light_count;
    const char *env;
    int ambient_mode;
    bool has_ambient_color, ao_all_light, hdr_off;
    float ambient_color[3];
    int shadow_method, shadow_size, pcf_radius;
    float shadow_bias, shadow_slope_bias, vsm_blur, vsm_bleed, exposure, key, white, bloom, bloom_threshold;
    unsigned set_mask; /* which of the optional numbers above were given */
    const char *sets[64];
    int set_count;
    ob_up_axis up;
    int width, height, frames, samples, quality_samples;
    bool timings, verbose, has_eye, has_target, has_fov;
    float eye[3], target[3], fov;
    ob_gpu_kind gpu;
} render_opts;

/* The numeric lighting/shadow/HDR options: validated ranges, one line each. Returns false with
 * *code set when the option is not one of them or its value is bad. */
static bool parse_number_option(render_opts *o, const char *a, const char *v, int *code)
{
    static const struct {
        const char *name;
        size_t offset;
        float min, max;
        bool integer;
        unsigned bit;
    } opts[] = {
        {"--shadow-size", offsetof(render_opts, shadow_size), 16.0f, 16384.0f, true, 1},
        {"--shadow-bias", offsetof(render_opts, shadow_bias), 0.0f, 100.0f, false, 2},
        {"--shadow-slope-bias", offsetof(render_opts, shadow_slope_bias), 0.0f, 100.0f, false, 3},
        {"--pcf-radius", offsetof(render_opts, pcf_radius), 1.0f, 8.0f, true, 4},
        {"--vsm-blur", offsetof(render_opts, vsm_blur), 0.0f, 16.0f, false, 5},
        {"--vsm-bleed", offsetof(render_opts, vsm_bleed), 0.0f, 0.99f, false, 6},
        {"--exposure", offsetof(render_opts, exposure), 1e-6f, 1e6f, false, 7},
        {"--key", offsetof(render_opts, key), 0.001f, 10.0f, false, 8},
        {"--white", offsetof(render_opts, white), 0.0f, 1e6f, false, 9},
        {"--bloom", offsetof(render_opts, bloom), 0.0f, 10.0f, false, 10},
        {"--bloom-threshold", offsetof(render_opts, bloom_threshold), 0.0f, 1e6f, false, 11},
    };
    for (size_t i = 0; i < sizeof opts / sizeof opts[0]; ++i) {
        if (strcmp(a, opts[i].name) != 0) continue;
        float x = 0.0f;
        if (!cli_parse_float(v, &x) || x < opts[i].min || x > opts[i].max || (opts[i].integer && x != floorf(x))) {
            *code = cli_fail(EXIT_USAGE, "%s: expected %s in [%g, %g], got '%s'", a, opts[i].integer ? "an integer" : "a number",
                             (double)opts[i].min, (double)opts[i].max, v);
            return false;
        }
        char *field = (char *)o + opts[i].offset;
        if (opts[i].integer) *(int *)field = (int)x;
        else *(float *)field = x;
        o->set_mask |= 1u << opts[i].bit;
        return true;
    }
    *code = cli_fail(EXIT_USAGE, "unknown option '%s' (see obscura render --help)", a);
    return false;
}

static int parse(int argc, char **argv, render_opts *o)
{
    int code = 0;
    *o = (render_opts){.scene = "cornell", .method = "ssao", .filter = "geometry", .view = "final", .ao_scale = 1.0f,
                       .width = 640, .height = 480, .frames = 1};
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            render_usage(stdout);
            return -1;
        }
        if (!strcmp(a, "-v")) { o->verbose = true; continue; }
        if (!strcmp(a, "--timings")) { o->timings = true; continue; }
        if (i + 1 >= argc) return cli_fail(EXIT_USAGE, "%s: missing value (see obscura render --help)", a);
        const char *v = argv[++i];
        if (!strcmp(a, "--scene")) o->scene = v;
        else if (!strcmp(a, "--sidecar")) o->sidecar = v;
        else if (!strcmp(a, "--method")) o->method = v;
        else if (!strcmp(a, "--camera")) o->camera = v;
        else if (!strcmp(a, "--out")) o->out = v;
        else if (!strcmp(a, "--ao-out")) o->ao_out = v;
        else if (!strcmp(a, "--ao-png")) o->ao_png = v;
        else if (!strcmp(a, "--depth-out")) o->depth_out = v;
        else if (!strcmp(a, "--normal-out")) o->normal_out = v;
        else if (!strcmp(a, "--quality")) {
            o->quality_samples = ob_quality_samples(v);
            if (o->quality_samples < 0) return cli_fail(EXIT_USAGE, "--quality: expected low, medium, high or ultra, got '%s'", v);
        } else if (!strcmp(a, "--samples")) {
            char *end = NULL;
            long n = strtol(v, &end, 10);
            if (end == v || *end || n < 1 || n > 4096) return cli_fail(EXIT_USAGE, "--samples: expected 1..4096, got '%s'", v);
            o->samples = (int)n;
        } else if (!strcmp(a, "--set")) {
            if (o->set_count >= 64) return cli_fail(EXIT_USAGE, "--set: too many");
            o->sets[o->set_count++] = v;
        } else if (!strcmp(a, "--up")) {
            if (!cli_parse_up(v, &o->up)) return cli_fail(EXIT_USAGE, "--up: expected y or z, got '%s'", v);
        } else if (!strcmp(a, "--filter")) {
            o->filter = v;
        } else if (!strcmp(a, "--view")) {
            const char *views[] = {"final", "ao", "normals", "depth", "shadow", "radiance", "samples", "bounce"};
            bool known = false;
            for (size_t k = 0; k < sizeof views / sizeof views[0]; ++k) known = known || !strcmp(v, views[k]);
            if (!known)
                return cli_fail(EXIT_USAGE, "--view: expected final, ao, normals, depth, shadow, radiance, samples or bounce, got '%s'", v);
            o->view = v;
        } else if (!strcmp(a, "--light")) {
            if (o->light_count >= OB_MAX_LIGHTS) return cli_fail(EXIT_USAGE, "--light: at most %d lights", OB_MAX_LIGHTS);
            o->lights[o->light_count++] = v;
        } else if (!strcmp(a, "--env")) {
            o->env = v;
        } else if (!strcmp(a, "--ambient")) {
            if (!strcmp(v, "constant")) o->ambient_mode = OB_AMBIENT_CONSTANT;
            else if (!strcmp(v, "hemisphere")) o->ambient_mode = OB_AMBIENT_HEMISPHERE;
            else if (!strcmp(v, "env")) o->ambient_mode = OB_AMBIENT_ENVIRONMENT;
            else return cli_fail(EXIT_USAGE, "--ambient: expected constant, hemisphere or env, got '%s'", v);
        } else if (!strcmp(a, "--ambient-color")) {
            if (!cli_parse_vec3(v, o->ambient_color) || o->ambient_color[0] < 0.0f || o->ambient_color[1] < 0.0f ||
                o->ambient_color[2] < 0.0f)
                return cli_fail(EXIT_USAGE, "--ambient-color: expected R,G,B >= 0, got '%s'", v);
            o->has_ambient_color = true;
        } else if (!strcmp(a, "--ao-light")) {
            if (!strcmp(v, "ambient")) o->ao_all_light = false;
            else if (!strcmp(v, "all")) o->ao_all_light = true;
            else return cli_fail(EXIT_USAGE, "--ao-light: expected ambient or all, got '%s'", v);
        } else if (!strcmp(a, "--shadow")) {
            ob_shadow_method m = OB_SHADOW_NONE;
            if (!cli_parse_shadow(v, &m)) return cli_fail(EXIT_USAGE, "--shadow: expected none, hard, pcf or vsm, got '%s'", v);
            o->shadow_method = (int)m;
            o->set_mask |= 1u << 0;
        } else if (!strcmp(a, "--hdr")) {
            bool on = true;
            if (!cli_parse_on_off(v, &on)) return cli_fail(EXIT_USAGE, "--hdr: expected on or off, got '%s'", v);
            o->hdr_off = !on;
        } else if (!strcmp(a, "--ao-scale")) {
            if (!cli_parse_ao_scale(v, &o->ao_scale))
                return cli_fail(EXIT_USAGE, "--ao-scale: expected 1, 0.5 or 0.25, got '%s'", v);
        } else if (!strcmp(a, "--adaptive")) {
            if (!cli_parse_on_off(v, &o->adaptive)) return cli_fail(EXIT_USAGE, "--adaptive: expected on or off, got '%s'", v);
        } else if (!strcmp(a, "--size")) {
            if (!cli_parse_size(v, &o->width, &o->height))
                return cli_fail(EXIT_USAGE, "--size: expected WIDTHxHEIGHT with positive integers, got '%s'", v);
        } else if (!strcmp(a, "--frames")) {
            char *end = NULL;
            long n = strtol(v, &end, 10);
            if (end == v || *end || n < 1 || n > 100000) return cli_fail(EXIT_USAGE, "--frames: expected 1..100000, got '%s'", v);
            o->frames = (int)n;
        } else if (!strcmp(a, "--eye")) {
            if (!cli_parse_vec3(v, o->eye)) return cli_fail(EXIT_USAGE, "--eye: expected X,Y,Z (finite numbers), got '%s'", v);
            o->has_eye = true;
        } else if (!strcmp(a, "--target")) {
            if (!cli_parse_vec3(v, o->target)) return cli_fail(EXIT_USAGE, "--target: expected X,Y,Z (finite numbers), got '%s'", v);
            o->has_target = true;
        } else if (!strcmp(a, "--fov")) {
            if (!cli_parse_float(v, &o->fov) || o->fov <= 0.0f || o->fov >= 179.0f)
                return cli_fail(EXIT_USAGE, "--fov: expected degrees in (0, 179), got '%s'", v);
            o->has_fov = true;
        } else if (!strcmp(a, "--gpu")) {
            if (!cli_parse_gpu(v, &o->gpu)) return cli_fail(EXIT_USAGE, "--gpu: expected auto, hw or sw, got '%s'", v);
        } else if (!parse_number_option(o, a, v, &code)) {
            return code;
        }
    }
    if (!o->out) return cli_fail(EXIT_USAGE, "--out FILE.png is required (see obscura render --help)");
    if (o->has_eye != o->has_target) return cli_fail(EXIT_USAGE, "--eye and --target go together");
    if (o->camera && o->has_eye) return cli_fail(EXIT_USAGE, "--camera and --eye/--target exclude each other");
    if (o->has_eye && o->eye[0] == o->target[0] && o->eye[1] == o->target[1] && o->eye[2] == o->target[2])
        return cli_fail(EXIT_USAGE, "--eye and --target are the same point");
    const char *outs[5] = {o->out, o->ao_out, o->ao_png, o->depth_out, o->normal_out};
    for (int i = 0; i < 5; ++i)
        if (outs[i] && !cli_output_writable(outs[i]))
            return cli_fail(EXIT_OUTPUT, "cannot write %s: its directory does not exist or is not writable", outs[i]);
    return 0;
}

static void flip_rows_to_grey(const float *ao, int w, int h, unsigned char *out)
{
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            float v = ao[(size_t)(h - 1 - y) * (size_t)w + (size_t)x];
            v = v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v;
            out[(size_t)y * (size_t)w + (size_t)x] = (unsigned char)lrintf(v * 255.0f);
        }
}

static unsigned char to_byte(float v)
{
    v = v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v;
    return (unsigned char)lrintf(v * 255.0f);
}

static float srgb(float c)
{
    c = c < 0.0f ? 0.0f : c > 1.0f ? 1.0f : c;
    return c <= 0.0031308f ? 12.92f * c : 1.055f * powf(c, 1.0f / 2.4f) - 0.055f;
}

/* The debug views as an RGB image (top row first): ao (RGB: SSDO's M per channel, AO methods
 * grey), shadow and samples as grey, normals as n * 0.5 + 0.5, depth as grey from near (white)
 * to far (black), radiance and bounce clamped to [0,1] and sRGB-encoded. buf holds 3 floats per
 * pixel. */
static ob_error view_image(ob_renderer *r, const render_opts *o, float *buf, unsigned char *rgb)
{
    int w = o->width, h = o->height;
    size_t px = (size_t)w * (size_t)h;
    const char *v = o->view;
    ob_image_kind kind = !strcmp(v, "ao") ? OB_IMAGE_AO_RGB_F32 : !strcmp(v, "samples") ? OB_IMAGE_SAMPLES_F32
                         : !strcmp(v, "bounce") ? OB_IMAGE_BOUNCE_F32
                         : !strcmp(v, "normals") ? OB_IMAGE_NORMAL_F32 : !strcmp(v, "depth") ? OB_IMAGE_DEPTH_F32
                         : !strcmp(v, "shadow") ? OB_IMAGE_SHADOW_F32 : OB_IMAGE_RADIANCE_F32;
    ob_error err = ob_read_image(r, kind, buf, ob_image_size(r, kind));
    if (err != OB_OK) return err;
    int channels = kind == OB_IMAGE_NORMAL_F32 || kind == OB_IMAGE_RADIANCE_F32 || kind == OB_IMAGE_AO_RGB_F32 ||
                           kind == OB_IMAGE_BOUNCE_F32
                       ? 3
                       : 1;
    float most = 0.0f;
    for (size_t i = 0; i < px && channels == 1; ++i) most = buf[i] > most ? buf[i] : most;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            size_t src = (size_t)(h - 1 - y) * (size_t)w + (size_t)x, dst = 3 * ((size_t)y * (size_t)w + (size_t)x);
            for (int c = 0; c < 3; ++c) {
                float value = buf[src * (size_t)channels + (size_t)(channels == 3 ? c : 0)];
                if (kind == OB_IMAGE_NORMAL_F32) value = value * 0.5f + 0.5f;
                else if (kind == OB_IMAGE_RADIANCE_F32 || kind == OB_IMAGE_BOUNCE_F32) value = srgb(value);
                else if (kind == OB_IMAGE_SAMPLES_F32) value = most > 0.0f ? value / most : 0.0f;
                else if (kind == OB_IMAGE_DEPTH_F32) value = value > 0.0f && most > 0.0f ? 1.0f - value / most : 0.0f;
                rgb[dst + (size_t)c] = to_byte(value);
            }
        }
    return OB_OK;
}

/* Outputs written so far in this run: removed again if a later one fails, so a failed run
 * leaves no partial set of files behind. */
static const char *written[8];
static int written_count;

static ob_error track(ob_error err, const char *path)
{
    if (err == OB_OK && written_count < 8) written[written_count++] = path;
    return err;
}

static int write_outputs_tracked(ob_renderer *r, const render_opts *o);

static int write_outputs(ob_renderer *r, const render_opts *o)
{
    written_count = 0;
    int code = write_outputs_tracked(r, o);
    if (code != EXIT_OK)
        for (int i = 0; i < written_count; ++i) remove(written[i]);
    return code;
}

static int write_outputs_tracked(ob_renderer *r, const render_opts *o)
{
    size_t px = (size_t)o->width * (size_t)o->height;
    int code = EXIT_OK;
    unsigned char *rgba = malloc(px * 4);
    float *buf = malloc(px * 3 * sizeof(float));
    unsigned char *grey = malloc(px);
    if (!rgba || !buf || !grey) {
        code = cli_fail(EXIT_RUNTIME, "out of memory for %dx%d outputs", o->width, o->height);
        goto done;
    }
    if (!strcmp(o->view, "final")) {
        if (ob_read_image(r, OB_IMAGE_FINAL_RGBA8, rgba, px * 4) != OB_OK ||
            track(ob_write_png(o->out, o->width, o->height, 4, rgba), o->out) != OB_OK) {
            code = cli_fail_library_as(EXIT_OUTPUT);
            goto done;
        }
    } else {
        if (view_image(r, o, buf, rgba) != OB_OK ||
            track(ob_write_png(o->out, o->width, o->height, 3, rgba), o->out) != OB_OK) {
            code = cli_fail_library_as(EXIT_OUTPUT);
            goto done;
        }
    }
    if (o->ao_out || o->ao_png) {
        if (ob_read_image(r, OB_IMAGE_AO_F32, buf, px * sizeof(float)) != OB_OK) {
            code = cli_fail_library_as(EXIT_OUTPUT);
            goto done;
        }
        if (o->ao_out && track(ob_write_pfm(o->ao_out, o->width, o->height, 1, buf), o->ao_out) != OB_OK) {
            code = cli_fail_library_as(EXIT_OUTPUT);
            goto done;
        }
        if (o->ao_png) {
            flip_rows_to_grey(buf, o->width, o->height, grey);
            if (track(ob_write_png(o->ao_png, o->width, o->height, 1, grey), o->ao_png) != OB_OK) {
                code = cli_fail_library_as(EXIT_OUTPUT);
                goto done;
            }
        }
    }
    if (o->depth_out && (ob_read_image(r, OB_IMAGE_DEPTH_F32, buf, px * sizeof(float)) != OB_OK ||
                         track(ob_write_pfm(o->depth_out, o->width, o->height, 1, buf), o->depth_out) != OB_OK)) {
        code = cli_fail_library_as(EXIT_OUTPUT);
        goto done;
    }
    if (o->normal_out && (ob_read_image(r, OB_IMAGE_NORMAL_F32, buf, px * 3 * sizeof(float)) != OB_OK ||
                          track(ob_write_pfm(o->normal_out, o->width, o->height, 3, buf), o->normal_out) != OB_OK)) {
        code = cli_fail_library_as(EXIT_OUTPUT);
        goto done;
    }
done:
    free(rgba);
    free(buf);
    free(grey);
    return code;
}

int cmd_render(int argc, char **argv)
{
    render_opts o;
    int code = parse(argc, argv, &o);
    if (code != 0) return code < 0 ? EXIT_OK : code;

    /* Everything that can be checked without a GPU is checked first. */
    ob_settings settings;
    if (ob_settings_init(&settings, o.method) != OB_OK) return cli_fail_from_library();
    if (ob_settings_set_filter(&settings, o.filter) != OB_OK || ob_settings_set_ao_scale(&settings, o.ao_scale) != OB_OK)
        return cli_fail_from_library();
    settings.adaptive = o.adaptive;
    for (int i = 0; i < o.light_count; ++i)
        if (ob_parse_light(o.lights[i], &settings.lights[i]) != OB_OK) return cli_fail_from_library();
    settings.light_count = o.light_count;
    settings.ambient_mode = (ob_ambient_mode)o.ambient_mode;
    if (o.has_ambient_color) memcpy(settings.ambient, o.ambient_color, sizeof settings.ambient);
    if (settings.ambient_mode == OB_AMBIENT_ENVIRONMENT && !o.env)
        return cli_fail(EXIT_USAGE, "--ambient env needs --env FILE.hdr");
    settings.ao_all_light = o.ao_all_light;
    ob_shadow_settings *sh = &settings.shadow;
    if (o.set_mask & (1u << 0)) sh->method = (ob_shadow_method)o.shadow_method;
    if (o.set_mask & (1u << 1)) sh->size = o.shadow_size;
    if (o.set_mask & (1u << 2)) sh->bias = o.shadow_bias;
    if (o.set_mask & (1u << 3)) sh->slope_bias = o.shadow_slope_bias;
    if (o.set_mask & (1u << 4)) sh->pcf_radius = o.pcf_radius;
    if (o.set_mask & (1u << 5)) sh->vsm_blur = o.vsm_blur;
    if (o.set_mask & (1u << 6)) sh->vsm_bleed = o.vsm_bleed;
    ob_hdr_settings *hdr = &settings.hdr;
    hdr->enabled = !o.hdr_off;
    if (o.set_mask & (1u << 7)) hdr->exposure = o.exposure;
    if (o.set_mask & (1u << 8)) hdr->key = o.key;
    if (o.set_mask & (1u << 9)) hdr->l_white = o.white;
    if (o.set_mask & (1u << 10)) hdr->bloom_strength = o.bloom;
    if (o.set_mask & (1u << 11)) hdr->bloom_threshold = o.bloom_threshold;
    /* A method with no sample count (none) ignores --quality/--samples; anything else that the
     * method refuses (out of its range) is an error. */
    int sample_count = o.samples > 0 ? o.samples : o.quality_samples;
    ob_error samples_err = sample_count > 0 ? ob_settings_set_samples(&settings, sample_count) : OB_OK;
    if (samples_err != OB_OK && samples_err != OB_ERR_INVALID_ARGUMENT) return cli_fail_from_library();
    for (int i = 0; i < o.set_count; ++i)
        if (ob_settings_set(&settings, o.sets[i]) != OB_OK) return cli_fail_from_library();

    ob_scene *scene = ob_load_scene(&(ob_scene_desc){.name = o.scene, .sidecar = o.sidecar, .up = o.up});
    if (!scene) return cli_fail_from_library();
    ob_camera cam;
    if (o.has_eye) {
        memset(&cam, 0, sizeof cam);
        memcpy(cam.eye, o.eye, sizeof cam.eye);
        memcpy(cam.target, o.target, sizeof cam.target);
        cam.fov_y_deg = o.has_fov ? o.fov : 60.0f;
        snprintf(cam.name, sizeof cam.name, "explicit");
    } else if (ob_find_camera(scene, o.camera ? o.camera : "default", &cam) != OB_OK) {
        code = cli_fail_from_library();
        ob_destroy_scene(scene);
        return code;
    } else if (o.has_fov) {
        cam.fov_y_deg = o.fov;
    }

    ob_context *ctx = cli_make_context(o.gpu, o.verbose);
    if (!ctx) {
        code = cli_fail_from_library();
        ob_destroy_scene(scene);
        return code;
    }
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = o.width, .height = o.height});
    if (!r || ob_renderer_set_scene(r, scene) != OB_OK) {
        code = cli_fail_from_library();
        goto cleanup;
    }
    if (o.env && ob_renderer_set_environment(r, o.env) != OB_OK) {
        code = cli_fail_from_library();
        goto cleanup;
    }
    enum { MAX_PASSES = 16 };
    double *samples = calloc((size_t)o.frames * MAX_PASSES, sizeof(double));
    const char *names[MAX_PASSES] = {0};
    int pass_count = 0;
    if (!samples) {
        code = cli_fail(EXIT_RUNTIME, "out of memory");
        goto cleanup;
    }
    for (int f = 0; f < o.frames && code == EXIT_OK; ++f) {
        if (ob_render_frame(r, &cam, &settings) != OB_OK) {
            code = cli_fail_from_library();
            break;
        }
        ob_pass_timing t[MAX_PASSES];
        pass_count = ob_query_timings(r, t, MAX_PASSES);
        for (int p = 0; p < pass_count; ++p) {
            names[p] = t[p].name;
            samples[(size_t)p * (size_t)o.frames + (size_t)f] = t[p].ms;
        }
    }
    if (code == EXIT_OK && o.timings) {
        const ob_scene_stats st = ob_query_scene_stats(scene);
        printf("%s, %s, %dx%d, %u triangles, %d frame(s), %s\n", ob_query_scene_name(scene),
               ob_method_at(settings.method)->name, o.width, o.height, st.triangles, o.frames, ob_query_renderer(ctx));
        printf("%-10s %10s %10s %10s\n", "pass", "median ms", "min ms", "max ms");
        double total = 0.0;
        for (int p = 0; p < pass_count; ++p) {
            double *s = samples + (size_t)p * (size_t)o.frames;
            double med = cli_median(s, o.frames);
            total += med;
            printf("%-10s %10.3f %10.3f %10.3f\n", names[p], med, s[0], s[o.frames - 1]);
        }
        printf("%-10s %10.3f\n", "total", total);
    }
    free(samples);
    if (code == EXIT_OK) code = write_outputs(r, &o);
cleanup:
    ob_destroy_renderer(r);
    ob_destroy_context(ctx);
    ob_destroy_scene(scene);
    return code;
}
