/* CPU unit tests (run again under ASan + UBSan): settings validation against the registry,
 * sampling kernels, PNG/PFM files, shader-log mapping and the embedded shaders. */
#include <stb/stb_image.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "core/renderer.h"
#include "gpu/gpu.h"
#include "gpu/shaders_embedded.h"
#include "methods/method.h"
#include "passes/passes.h"
#include "obscura/eval.h"
#include "sampling/sampling.h"

static void test_registry_and_settings(void)
{
    CHECK(ob_method_count() >= 2, "methods: %d", ob_method_count());
    CHECK(ob_find_method("ssao") >= 0 && ob_find_method("none") >= 0, "ssao and none registered");
    CHECK(ob_find_method("nope") == -1, "unknown method index");
    for (int i = 0; i < ob_method_count(); ++i) {
        const ob_method_info *m = ob_method_at(i);
        CHECK(m->param_count <= OB_MAX_PARAMS, "%s has %d params", m->name, m->param_count);
        for (int p = 0; p < m->param_count; ++p) {
            const ob_param_info *pi = &m->params[p];
            CHECK(pi->min <= pi->def && pi->def <= pi->max, "%s.%s default %g in [%g,%g]", m->name, pi->name,
                  (double)pi->def, (double)pi->min, (double)pi->max);
            CHECK(pi->unit && pi->help && *pi->help, "%s.%s documented", m->name, pi->name);
        }
    }

    /* Every parameter of every method and filter is validated from its table. */
    for (int i = 0; i < ob_method_count() + ob_filter_count(); ++i) {
        bool is_filter = i >= ob_method_count();
        const ob_method_info *m = is_filter ? ob_filter_at(i - ob_method_count()) : ob_method_at(i);
        ob_settings t;
        CHECK(ob_settings_init(&t, is_filter ? "ssao" : m->name) == OB_OK, "init %s", m->name);
        if (is_filter) CHECK(ob_settings_set_filter(&t, m->name) == OB_OK, "filter %s", m->name);
        float *values = is_filter ? t.filter_params : t.params;
        for (int p = 0; p < m->param_count; ++p) {
            const ob_param_info *pi = &m->params[p];
            char text[128];
            struct bad_case { double v; const char *word; ob_error want; } cases[4] = {
                {(double)pi->min - fmax(1.0, fabs((double)pi->min)), NULL, OB_ERR_OUT_OF_RANGE},
                {(double)pi->max + fmax(1.0, fabs((double)pi->max)), NULL, OB_ERR_OUT_OF_RANGE},
                {0.0, "nan", OB_ERR_INVALID_ARGUMENT},
                {0.0, "bogus", OB_ERR_INVALID_ARGUMENT}};
            int ncases = 4;
            if (pi->type == OB_PARAM_ENUM || pi->type == OB_PARAM_BOOL) {
                /* Named values: an index past the last option and words are refused. */
                cases[0] = (struct bad_case){(double)pi->max + 1.0, NULL, OB_ERR_INVALID_ARGUMENT};
                cases[1] = (struct bad_case){-1.0, NULL, OB_ERR_INVALID_ARGUMENT};
            }
            for (int c = 0; c < ncases; ++c) {
                if (cases[c].word) snprintf(text, sizeof text, "%s.%s=%s", m->name, pi->name, cases[c].word);
                else snprintf(text, sizeof text, "%s.%s=%.9g", m->name, pi->name, cases[c].v);
                ob_error e = ob_settings_set(&t, text);
                CHECK(e == cases[c].want, "'%s' gave %s, want %s", text, ob_error_name(e), ob_error_name(cases[c].want));
            }
            /* The default itself, by value (or by name for enums), is accepted. */
            if (pi->type == OB_PARAM_ENUM) snprintf(text, sizeof text, "%s.%s=%s", m->name, pi->name, pi->options[(int)pi->def]);
            else snprintf(text, sizeof text, "%s.%s=%.9g", m->name, pi->name, (double)pi->def);
            CHECK(ob_settings_set(&t, text) == OB_OK, "'%s' refused", text);
            CHECK(values[p] == pi->def, "%s keeps its value", text);
        }
    }

    /* Quality presets: Belonogov 2018's 12/24/36/64, applied through each method's mapping. */
    CHECK(ob_quality_samples("low") == 12 && ob_quality_samples("medium") == 24 && ob_quality_samples("high") == 36 &&
              ob_quality_samples("ultra") == 64 && ob_quality_samples("extreme") == -1,
          "quality presets");
    {
        ob_settings q;
        ob_settings_init(&q, "ssao");
        CHECK(ob_settings_set_samples(&q, 36) == OB_OK && ob_settings_get(&q, "samples") == 36.0f, "ssao high = 36");
        CHECK(ob_settings_set_samples(&q, 100000) == OB_ERR_OUT_OF_RANGE, "ssao refuses 100000 samples");
        ob_settings_init(&q, "none");
        CHECK(ob_settings_set_samples(&q, 12) == OB_ERR_INVALID_ARGUMENT, "none takes no sample count");
        if (ob_settings_init(&q, "hbao") == OB_OK) {
            const int presets[4][3] = {{12, 4, 3}, {24, 6, 4}, {36, 6, 6}, {64, 8, 8}};
            for (int i = 0; i < 4; ++i) {
                CHECK(ob_settings_set_samples(&q, presets[i][0]) == OB_OK, "hbao %d samples", presets[i][0]);
                CHECK(ob_settings_get(&q, "directions") == (float)presets[i][1] &&
                          ob_settings_get(&q, "steps") == (float)presets[i][2],
                      "hbao %d = %d x %d, got %g x %g", presets[i][0], presets[i][1], presets[i][2],
                      (double)ob_settings_get(&q, "directions"), (double)ob_settings_get(&q, "steps"));
            }
        }
    }

    ob_settings s;
    CHECK(ob_settings_init(&s, "ssao") == OB_OK, "init ssao");
    CHECK(s.params_set == 0, "nothing set explicitly");
    CHECK(ob_settings_set(&s, "ssao.radius=0.25") == OB_OK, "set radius");
    CHECK_NEAR(ob_settings_get(&s, "radius"), 0.25, 0.0, "radius value");
    CHECK(s.params_set != 0, "radius marked as set");
    CHECK(ob_settings_get(&s, "radius_scale") == 1.0f, "radius_scale defaults to 1");
    CHECK(ob_settings_set(&s, "ssao.radius_scale=1.5") == OB_OK && s.radius_scale == 1.5f, "set radius_scale");
    CHECK(ob_settings_set(&s, "ssao.radius_scale=8") == OB_ERR_OUT_OF_RANGE, "radius_scale 8 is out of range");
    CHECK(ob_settings_set(&s, "ssao.radius_scale=x") == OB_ERR_INVALID_ARGUMENT, "radius_scale x is not a number");
    CHECK(s.radius_scale == 1.5f, "a refused radius_scale leaves the value");
    CHECK(ob_settings_set(&s, "samples=32") == OB_OK, "set samples without prefix");
    CHECK_NEAR(ob_settings_get(&s, "samples"), 32, 0.0, "samples value");

    const char *msg = NULL;
    struct { const char *text; ob_error want; } bad[] = {
        {"ssao.nope=1", OB_ERR_UNKNOWN_PARAM},     {"foo.radius=1", OB_ERR_UNKNOWN_METHOD},
        {"ssao.radius=-1", OB_ERR_OUT_OF_RANGE},   {"ssao.radius=nan", OB_ERR_INVALID_ARGUMENT},
        {"ssao.radius=inf", OB_ERR_INVALID_ARGUMENT}, {"ssao.radius=abc", OB_ERR_INVALID_ARGUMENT},
        {"ssao.radius=", OB_ERR_INVALID_ARGUMENT}, {"ssao.radius", OB_ERR_INVALID_ARGUMENT},
        {"ssao.samples=2.5", OB_ERR_INVALID_ARGUMENT}, {"ssao.samples=100000", OB_ERR_OUT_OF_RANGE},
        {"none.radius=1", OB_ERR_INVALID_ARGUMENT}, {"=3", OB_ERR_INVALID_ARGUMENT},
        {"ssao.radius=1e99", OB_ERR_OUT_OF_RANGE},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        ob_error e = ob_settings_set(&s, bad[i].text);
        ob_get_error(&msg);
        CHECK(e == bad[i].want, "'%s' gave %s (%s), want %s", bad[i].text, ob_error_name(e), msg,
              ob_error_name(bad[i].want));
        CHECK(msg && *msg && !strchr(msg, '\n'), "'%s' has a one-line message", bad[i].text);
    }
    /* Rejected values leave the previous ones alone. */
    CHECK_NEAR(ob_settings_get(&s, "radius"), 0.25, 0.0, "radius unchanged");
    CHECK(ob_settings_init(&s, "bogus") == OB_ERR_UNKNOWN_METHOD, "unknown method at init");
    ob_get_error(&msg);
    CHECK(strstr(msg, "ssao") != NULL, "message lists the known methods: %s", msg);
}

static void test_kernel(void)
{
    enum { N = 64 };
    float k[N * 4];
    ob_hemisphere_kernel(k, N, OB_SAMPLING_RANDOM, OB_DIRECTIONS_UNIFORM, 7);
    float inner = 0.0f, outer = 0.0f;
    for (int i = 0; i < N; ++i) {
        float x = k[4 * i], y = k[4 * i + 1], z = k[4 * i + 2];
        float len = sqrtf(x * x + y * y + z * z);
        CHECK(z >= 0.0f, "sample %d below the tangent plane (z %g)", i, (double)z);
        CHECK(len <= 1.0f + 1e-5f && len >= 0.099f, "sample %d length %g outside [0.1, 1]", i, (double)len);
        if (i < N / 2) inner += len; else outer += len;
    }
    /* Puri 2024 §3.3: the accelerating scale puts the first half of the kernel nearer the centre. */
    CHECK(inner < outer * 0.6f, "first half mean length %g vs second half %g", (double)(inner / 32), (double)(outer / 32));
    float k2[N * 4];
    ob_hemisphere_kernel(k2, N, OB_SAMPLING_RANDOM, OB_DIRECTIONS_UNIFORM, 7);
    CHECK(memcmp(k, k2, sizeof k) == 0, "kernel is deterministic");

    float noise[32];
    ob_rotation_noise_4x4(noise, 3);
    int sectors = 0;
    for (int i = 0; i < 16; ++i) {
        float len = sqrtf(noise[2 * i] * noise[2 * i] + noise[2 * i + 1] * noise[2 * i + 1]);
        CHECK_NEAR(len, 1.0, 1e-5, "noise vector is unit length");
        float a = atan2f(noise[2 * i + 1], noise[2 * i]);
        if (a < 0.0f) a += 6.2831853f;
        sectors |= 1 << ((int)(a / (6.2831853f / 16.0f)) & 15);
    }
    CHECK(sectors == 0xFFFF, "the 16 rotations cover all 16 sectors (mask 0x%x)", (unsigned)sectors);
}

static void test_halton(void)
{
    /* SSDO thesis Table 3.1: Phi_2 and Phi_3 of 1..6, exactly. */
    const double phi2[6] = {0.5, 0.25, 0.75, 0.125, 0.625, 0.375};
    const double phi3[6] = {1.0 / 3.0, 2.0 / 3.0, 1.0 / 9.0, 4.0 / 9.0, 7.0 / 9.0, 2.0 / 9.0};
    for (uint32_t i = 1; i <= 6; ++i) {
        CHECK(ob_radical_inverse(i, 2) == phi2[i - 1], "Phi_2(%u) = %.17g", i, ob_radical_inverse(i, 2));
        CHECK(fabs(ob_radical_inverse(i, 3) - phi3[i - 1]) < 1e-15, "Phi_3(%u) = %.17g", i, ob_radical_inverse(i, 3));
    }
    /* SSDO thesis §3.4's periodicity example, exactly. */
    CHECK(ob_radical_inverse(50, 2) == 0.296875, "Phi_2(50)");
    CHECK(ob_radical_inverse(66, 2) == 0.2578125, "Phi_2(66)");
    CHECK(ob_radical_inverse(82, 2) == 0.2890625, "Phi_2(82)");
    CHECK(ob_radical_inverse(114, 2) == 0.3046875, "Phi_2(114)");
    CHECK(ob_radical_inverse(0, 7) == 0.0 && ob_radical_inverse(1, 7) == 1.0 / 7.0, "base 7");

    /* Period 10 of bases 2 x 5 (SSDO thesis §4.1): points 1..10 fall in 10 different cells of
     * (halves of Phi_2) x (fifths of Phi_5), i.e. they split the hemisphere evenly. */
    int cells = 0;
    for (uint32_t i = 1; i <= 10; ++i)
        cells |= 1 << ((int)(ob_radical_inverse(i, 2) * 2.0) * 5 + (int)(ob_radical_inverse(i, 5) * 5.0));
    CHECK(cells == 0x3FF, "the first 10 Halton points cover all 10 cells (mask 0x%x)", (unsigned)cells);

    /* Directions: unit, in the hemisphere; mean cos(theta) = 2/3 (cosine) and 1/2 (uniform). */
    enum { M = 3000 };
    double mean_cos = 0.0, mean_uni = 0.0;
    int bad = 0;
    for (uint32_t i = 1; i <= M; ++i) {
        float c[3], u[3];
        ob_direction_cosine(ob_radical_inverse(i, 5), ob_radical_inverse(i, 2), c);
        ob_direction_uniform(ob_radical_inverse(i, 5), ob_radical_inverse(i, 2), u);
        double lc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]), lu = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
        bad += fabs(lc - 1.0) > 1e-6 || fabs(lu - 1.0) > 1e-6 || c[2] < 0.0f || u[2] < 0.0f;
        mean_cos += c[2];
        mean_uni += u[2];
    }
    CHECK(bad == 0, "%d directions not unit or below the horizon", bad);
    CHECK_NEAR(mean_cos / M, 2.0 / 3.0, 2e-3, "cosine-weighted mean cos(theta)");
    CHECK_NEAR(mean_uni / M, 0.5, 2e-3, "uniform solid-angle mean cos(theta)");

    /* Halton kernels: deterministic, in the hemisphere (or the sphere for Crytek). */
    float k[64 * 4], sphere[64 * 4];
    ob_hemisphere_kernel(k, 64, OB_SAMPLING_HALTON, OB_DIRECTIONS_COSINE, 1);
    ob_sphere_kernel(sphere, 64, OB_SAMPLING_HALTON, 1);
    int below = 0, above = 0, too_long = 0;
    for (int i = 0; i < 64; ++i) {
        below += k[4 * i + 2] < 0.0f;
        above += sphere[4 * i + 2] > 0.0f;
        float l = sqrtf(sphere[4 * i] * sphere[4 * i] + sphere[4 * i + 1] * sphere[4 * i + 1] + sphere[4 * i + 2] * sphere[4 * i + 2]);
        too_long += l > 1.0f + 1e-5f;
    }
    CHECK(below == 0, "hemisphere kernel has %d points below", below);
    CHECK(above >= 24 && above <= 40 && too_long == 0, "sphere kernel: %d of 64 above, %d too long", above, too_long);
}

static void test_files(void)
{
    char dir[] = "/tmp/obscura-test-XXXXXX";
    CHECK(mkdtemp(dir) != NULL, "temp dir");
    char pfm[256], png[256];
    snprintf(pfm, sizeof pfm, "%s/a.pfm", dir);
    snprintf(png, sizeof png, "%s/a.png", dir);

    enum { W = 5, H = 3 };
    float px[W * H * 3];
    for (int i = 0; i < W * H * 3; ++i) px[i] = (float)i * 0.37f - 2.0f;
    for (int c = 1; c <= 3; c += 2) {
        CHECK(ob_write_pfm(pfm, W, H, c, px) == OB_OK, "write pfm");
        int w = 0, h = 0, ch = 0;
        float *back = NULL;
        CHECK(ob_read_pfm(pfm, &w, &h, &ch, &back) == OB_OK, "read pfm");
        CHECK(w == W && h == H && ch == c, "pfm header %dx%dx%d", w, h, ch);
        CHECK(back && memcmp(back, px, sizeof(float) * W * H * (size_t)c) == 0, "pfm values exact");
        free(back);
    }
    uint8_t rgba[W * H * 4];
    for (int i = 0; i < W * H * 4; ++i) rgba[i] = (uint8_t)(i * 7);
    CHECK(ob_write_png(png, W, H, 4, rgba) == OB_OK, "write png");
    int w = 0, h = 0, n = 0;
    unsigned char *dec = stbi_load(png, &w, &h, &n, 4);
    CHECK(dec && w == W && h == H && memcmp(dec, rgba, sizeof rgba) == 0, "png decodes to the same pixels");
    stbi_image_free(dec);

    /* Failures leave nothing behind: an unwritable path, and no temporary files. */
    CHECK(ob_write_png("/nonexistent-dir/x.png", W, H, 4, rgba) == OB_ERR_IO, "unwritable png path");
    CHECK(ob_read_pfm(png, &w, &h, &n, &(float *){NULL}) == OB_ERR_IO, "a PNG is not a PFM");
    unlink(pfm);
    unlink(png);
    CHECK(rmdir(dir) == 0, "no temporary files left in %s", dir);
}

static void test_shader_log(void)
{
    char out[512];
    /* Mesa: "0:LINE(COL): error: ...", NVIDIA "0(LINE) : error ...", LINE = file id * 10000 + line. */
    int id = 0;
    for (int i = 0; i < ob_shader_file_count; ++i)
        if (!strcmp(ob_shader_file_names[i], "ssao.glsl")) id = i + 1;
    CHECK(id > 0, "ssao.glsl is embedded");
    char log[256];
    snprintf(log, sizeof log, "0:%d(7): error: `foo' undeclared\n0:%d(1): warning: x\n", id * 10000 + 42, id * 10000 + 43);
    ob_format_shader_log(log, "x.glsl", out, sizeof out);
    CHECK(strcmp(out, "shaders/ssao.glsl:42: error: `foo' undeclared") == 0, "mesa log -> '%s'", out);
    snprintf(log, sizeof log, "0(%d) : error C1008: undefined variable \"bar\"\n", id * 10000 + 12);
    ob_format_shader_log(log, "x.glsl", out, sizeof out);
    CHECK(strcmp(out, "shaders/ssao.glsl:12: error C1008: undefined variable \"bar\"") == 0, "nvidia log -> '%s'", out);

    /* Includes are resolved at build time and #line markers keep file positions. */
    const char *src = ob_shader_source("ssao.glsl");
    CHECK(src && !strstr(src, "#include"), "no #include left in the embedded ssao.glsl");
    CHECK(src && strncmp(src, "#version 450", 12) == 0, "#version stays first");
    CHECK(src && strstr(src, "ob_view_position") && strstr(src, "OB_SSAO_MAX_SAMPLES"), "includes expanded");
}

static float sh_eval(float sh[9][3], int c, float x, float y, float z)
{
    return sh[0][c] + sh[1][c] * y + sh[2][c] * z + sh[3][c] * x + sh[4][c] * x * y + sh[5][c] * y * z +
           sh[6][c] * (3.0f * z * z - 1.0f) + sh[7][c] * x * z + sh[8][c] * (x * x - y * y);
}

static void test_environment_sh(void)
{
    enum { EW = 128, EH = 64 };
    static float env[EW * EH * 3];
    /* A constant environment of radiance L gives irradiance / pi = L in every direction. */
    for (int i = 0; i < EW * EH * 3; ++i) env[i] = 0.7f;
    float sh[9][3];
    ob_environment_sh(env, EW, EH, sh);
    CHECK_NEAR(sh_eval(sh, 0, 0.0f, 1.0f, 0.0f), 0.7, 2e-3, "constant environment, up");
    CHECK_NEAR(sh_eval(sh, 1, 1.0f, 0.0f, 0.0f), 0.7, 2e-3, "constant environment, side");
    CHECK_NEAR(sh_eval(sh, 2, 0.0f, -1.0f, 0.0f), 0.7, 2e-3, "constant environment, down");
    /* A sky of radiance max(0, y): irradiance / pi is 2/3 facing up (the integral of cos^2 over the
     * hemisphere, 2 pi / 3, over pi) and 0 facing down; 9 terms approximate it within a few %. */
    for (int j = 0; j < EH; ++j)
        for (int i = 0; i < EW; ++i) {
            float y = cosf(((float)j + 0.5f) / (float)EH * 3.14159265f);
            for (int c = 0; c < 3; ++c) env[3 * (j * EW + i) + c] = y > 0.0f ? y : 0.0f;
        }
    ob_environment_sh(env, EW, EH, sh);
    float up = sh_eval(sh, 0, 0.0f, 1.0f, 0.0f), down = sh_eval(sh, 0, 0.0f, -1.0f, 0.0f);
    CHECK(fabsf(up - 2.0f / 3.0f) < 0.03f, "sky irradiance facing up %g, want 0.667", (double)up);
    CHECK(fabsf(down) < 0.03f, "sky irradiance facing down %g, want 0", (double)down);
}

static void test_lights(void)
{
    ob_light l;
    CHECK(ob_parse_light("directional dir=0,2,0 color=1,0.5,0.25 intensity=3", &l) == OB_OK, "directional");
    CHECK(l.type == OB_LIGHT_DIRECTIONAL && l.direction[1] == 1.0f && l.intensity == 3.0f && l.color[2] == 0.25f,
          "directional parsed and normalised");
    CHECK(ob_parse_light("point pos=1,2,3 intensity=8 range=10", &l) == OB_OK && l.type == OB_LIGHT_POINT &&
              l.position[2] == 3.0f && l.range == 10.0f,
          "point");
    CHECK(ob_parse_light("spot pos=0,3,0 dir=0,-1,0 cone=15,25", &l) == OB_OK && l.type == OB_LIGHT_SPOT &&
              l.spot_inner_deg == 15.0f && l.spot_outer_deg == 25.0f,
          "spot");
    const char *bad[] = {"", "laser dir=0,1,0", "directional", "directional dir=0,0,0", "point intensity=2",
                         "spot pos=0,1,0", "spot pos=0,1,0 dir=0,-1,0 cone=30,20", "point pos=1,2 intensity=1",
                         "point pos=0,0,0 intensity=-1", "point pos=0,0,0 colour=1,1,1", "point pos=0,0,0 range=0"};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        const char *msg = NULL;
        ob_error e = ob_parse_light(bad[i], &l);
        ob_get_error(&msg);
        CHECK(e == OB_ERR_INVALID_ARGUMENT && msg && *msg, "'%s' refused (%s)", bad[i], ob_error_name(e));
    }
}

/* The per-frame block (src/core/frame.c): at every AO divisor, AO pixel i reconstructs, through
 * ao_proj_info and ao_inv_size, the view position the full-resolution frame gives its full pixel
 * k i + o (the grid projection is exact); and the lights arrive as lighting.glsl reads them. */
static void test_frame_constants(void)
{
    const int w = 101, h = 67;
    float view[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0.5f, -1, -3, 1};
    float proj[16] = {0};
    const float f = 1.0f / tanf(0.5f), aspect = (float)w / (float)h, n = 0.1f, far = 50.0f;
    proj[0] = f / aspect;
    proj[5] = f;
    proj[8] = 0.03f; /* an off-centre frustum too */
    proj[9] = -0.02f;
    proj[10] = (far + n) / (n - far);
    proj[11] = -1.0f;
    proj[14] = 2.0f * far * n / (n - far);
    ob_light light = {.direction = {0, 2, 0}, .color = {1, 0.5f, 0.25f}, .intensity = 4, .type = OB_LIGHT_SPOT,
                      .position = {1, 2, 3}, .range = 9, .spot_inner_deg = 20, .spot_outer_deg = 30};
    ob_settings s;
    CHECK(ob_settings_init(&s, "ssao") == OB_OK, "settings");
    for (int k = 1; k <= 4; k *= 2) {
        ob_ao_grid g = ob_ao_grid_make(w, h, k);
        ob_frame_constants c;
        ob_frame_constants_fill(&c, &(ob_frame_desc){.view = view, .proj = proj, .grid = &g, .near_z = n, .far_z = far,
                                                     .frame_index = 7, .lights = &light, .light_count = 1,
                                                     .settings = &s});
        CHECK(c.ao_k == k && c.ao_o == g.o && c.ao_size[0] == (float)g.width && c.ao_size[1] == (float)g.height &&
                  c.size[0] == (float)w && c.frame_index == 7,
              "k %d: grid and sizes", k);
        double worst = 0.0;
        for (int j = 0; j < g.height; ++j)
            for (int i = 0; i < g.width; ++i) {
                /* common.glsl ob_view_position at depth 1, on the grid and at full resolution. */
                float fx = (float)(k * i + g.o), fy = (float)(k * j + g.o);
                if (fx >= (float)w || fy >= (float)h) continue;
                float gx = ((float)i + 0.5f) * c.ao_inv_size[0] * 2.0f - 1.0f;
                float gy = ((float)j + 0.5f) * c.ao_inv_size[1] * 2.0f - 1.0f;
                float ux = (fx + 0.5f) * c.inv_size[0] * 2.0f - 1.0f;
                float uy = (fy + 0.5f) * c.inv_size[1] * 2.0f - 1.0f;
                double dx = (gx + c.ao_proj_info[2]) * c.ao_proj_info[0] - (ux + c.proj_info[2]) * c.proj_info[0];
                double dy = (gy + c.ao_proj_info[3]) * c.ao_proj_info[1] - (uy + c.proj_info[3]) * c.proj_info[1];
                worst = fmax(worst, fmax(fabs(dx), fabs(dy)));
            }
        CHECK(worst < 1e-5, "k %d: AO pixels reconstruct their full pixel's position (off by %.2g)", k, worst);
        CHECK(c.light_count == 1 && c.light_color[0][0] == 4.0f && c.light_color[0][1] == 2.0f &&
                  c.light_color[0][3] == (float)OB_LIGHT_SPOT && c.light_direction[0][1] == 1.0f &&
                  c.light_direction[0][3] == -1.0f && c.light_position[0][3] == 9.0f &&
                  fabsf(c.light_spot[0][0] - cosf(20.0f * 0.01745329252f)) < 1e-6f,
              "k %d: the light as lighting.glsl reads it", k);
        CHECK(c.inv_view[12] == -0.5f && c.inv_view[13] == 1.0f && c.inv_view[14] == 3.0f, "k %d: inverse view", k);
        CHECK(c.ambient_mode == OB_AMBIENT_CONSTANT && c.ambient[0] == s.ambient[0], "k %d: ambient", k);
    }
}

/* Reading the error clears it, as glfwGetError does; the callback sees each error as it happens. */
typedef struct seen_errors { int count; ob_error last; char message[256]; } seen_errors;

static void on_error(ob_error err, const char *message, void *user)
{
    seen_errors *seen = user;
    seen->count++;
    seen->last = err;
    snprintf(seen->message, sizeof seen->message, "%s", message);
}

static void test_errors(void)
{
    ob_clear_error();
    seen_errors seen = {0, OB_OK, ""};
    ob_set_error_callback(on_error, &seen);
    ob_settings s;
    CHECK(ob_settings_init(&s, "no-such-method") == OB_ERR_UNKNOWN_METHOD, "unknown method refused");
    CHECK(seen.count == 1 && seen.last == OB_ERR_UNKNOWN_METHOD && strstr(seen.message, "no-such-method"),
          "the callback saw it (%d calls, %s: %s)", seen.count, ob_error_name(seen.last), seen.message);
    const char *msg = NULL;
    CHECK(ob_get_error(&msg) == OB_ERR_UNKNOWN_METHOD && strstr(msg, "no-such-method"), "first read: %s", msg);
    CHECK(ob_get_error(NULL) == OB_OK, "a second read finds no error");
    CHECK(ob_get_error(&msg) == OB_OK && strstr(msg, "no-such-method"), "the message stays for a log line: %s", msg);
    ob_set_error_callback(NULL, NULL);
    CHECK(ob_settings_init(&s, "ssao") == OB_OK && ob_settings_set(&s, "ssao.nope=1") == OB_ERR_UNKNOWN_PARAM,
          "unknown parameter refused");
    CHECK(seen.count == 1, "no callback once removed (%d calls)", seen.count);
    CHECK(ob_get_error(NULL) == OB_ERR_UNKNOWN_PARAM, "the error is there without a callback");
    ob_clear_error();
    CHECK(ob_get_error(&msg) == OB_OK && msg && *msg == '\0', "ob_clear_error forgets the message too");
}

/* ob_method_kernel: the kernel a method's shader gets, for the viewer's kernel view. */
static void test_method_kernel(void)
{
    float k[4 * 64];
    ob_settings s;
    CHECK(ob_settings_init(&s, "ssao") == OB_OK && ob_settings_set(&s, "ssao.sampling=halton") == OB_OK &&
              ob_settings_set(&s, "ssao.samples=20") == OB_OK,
          "ssao, Halton, 20");
    int n = ob_method_kernel(&s, k, 64);
    CHECK(n == 20, "ssao: 20 entries (%d)", n);
    int outside = 0;
    for (int i = 0; i < n; ++i) {
        float len = sqrtf(k[4 * i] * k[4 * i] + k[4 * i + 1] * k[4 * i + 1] + k[4 * i + 2] * k[4 * i + 2]);
        outside += !(k[4 * i + 2] >= 0.0f && len <= 1.0f + 1e-5f);
    }
    CHECK(outside == 0, "ssao: every entry in the unit hemisphere (%d outside)", outside);
    /* Halton kernels are prefixes of each other (what adaptive counts and the kernel view rely
     * on); random ones are not (their lengths depend on the count). */
    float k10[4 * 10];
    ob_settings_set(&s, "ssao.samples=10");
    CHECK(ob_method_kernel(&s, k10, 10) == 10 && memcmp(k10, k, sizeof k10) == 0, "Halton: 10 entries = the first 10 of 20");
    ob_settings_set(&s, "ssao.sampling=random");
    ob_method_kernel(&s, k10, 10);
    ob_settings_set(&s, "ssao.samples=20");
    ob_method_kernel(&s, k, 64);
    CHECK(memcmp(k10, k, sizeof k10) != 0, "random: 10 entries are not the first 10 of 20");
    CHECK(ob_method_kernel(&s, k, 5) == 5, "at most max entries");
    ob_settings_init(&s, "crytek");
    n = ob_method_kernel(&s, k, 64);
    int below = 0;
    for (int i = 0; i < n; ++i) below += k[4 * i + 2] < 0.0f;
    CHECK(n == 16 && below > 0, "crytek: 16 entries over the whole sphere (%d, %d below)", n, below);
    ob_settings_init(&s, "gtao");
    CHECK(ob_method_kernel(&s, k, 64) == 0, "gtao marches: no kernel");
    CHECK(ob_method_kernel(NULL, k, 64) == -1 && ob_get_error(NULL) == OB_ERR_INVALID_ARGUMENT, "NULL settings");
}

/* Roles (methods/method.h ob_param_role): the renderer, the settings and the memory estimate find
 * a method's radius, sample count, temporal switch... through the role its entry declares, never
 * by name. So a parameter that has a role's usual name but no role would be silently ignored (a
 * `temporal` switch that temporal accumulation never turns on), and one with the wrong type would
 * be misread: every declared role has a type it may have, and every parameter named as a role's
 * usual name is that role's. */
static void test_method_roles(void)
{
    enum { F = 1 << OB_PARAM_FLOAT, I = 1 << OB_PARAM_INT, B = 1 << OB_PARAM_BOOL, E = 1 << OB_PARAM_ENUM };
    static const struct { const char *name; int types; } roles[OB_ROLE_COUNT] = {
        [OB_ROLE_RADIUS] = {"radius", F},
        [OB_ROLE_MAX_RADIUS_PX] = {"max_radius_px", F},
        [OB_ROLE_SAMPLES] = {"samples", I},
        [OB_ROLE_TEMPORAL] = {"temporal", B},
        [OB_ROLE_INTENSITY] = {"intensity", F},
        [OB_ROLE_THICKNESS] = {"thickness", F},
        [OB_ROLE_FALLOFF] = {"falloff", F},
        [OB_ROLE_BENT_NORMALS] = {"bent_normals", B},
        [OB_ROLE_LAYERS] = {"layers", I | E},
        [OB_ROLE_PACKED] = {"packed", E},
        [OB_ROLE_DEINTERLEAVE] = {"deinterleave", E},
    };
    for (int r = 0; r < OB_ROLE_COUNT; ++r) CHECK(roles[r].name != NULL, "role %d has a usual name in this test", r);
    int declared = 0;
    for (int i = 0; i < ob_method_count(); ++i) {
        const ob_method_impl *m = ob_method_impl_at(i);
        const char *name = m->info.name;
        CHECK(ob_method_role(m, OB_ROLE_COUNT) == -1 && ob_method_role(m, (ob_param_role)-1) == -1,
              "%s: a role out of range has no parameter", name);
        for (int r = 0; r < OB_ROLE_COUNT; ++r) {
            CHECK(m->roles[r] >= 0 && m->roles[r] <= m->info.param_count, "%s: role %s names parameter %d of %d", name,
                  roles[r].name, m->roles[r] - 1, m->info.param_count);
            const int p = ob_method_role(m, (ob_param_role)r);
            if (p < 0) continue;
            ++declared;
            const ob_param_info *pi = &m->info.params[p];
            CHECK((roles[r].types >> pi->type) & 1, "%s: role %s is %s, of type %d", name, roles[r].name, pi->name,
                  (int)pi->type);
            if (r == OB_ROLE_RADIUS)
                CHECK(pi->follows_scene_radius, "%s: the radius %s follows the scene's radius", name, pi->name);
            if (r == OB_ROLE_BENT_NORMALS)
                CHECK(m->writes & OB_WRITES_BENT_NORMAL, "%s: a bent-normal switch, and it writes bent normals", name);
            if (r == OB_ROLE_LAYERS)
                CHECK(m->reads & OB_READS_SECOND_LAYER, "%s: a layers parameter, and it reads the second layer", name);
            if (r == OB_ROLE_SAMPLES)
                CHECK(!m->count_samples && !m->set_samples, "%s: samples is %s, or count_samples/set_samples, not both",
                      name, pi->name);
        }
        for (int p = 0; p < m->info.param_count; ++p) {
            const ob_param_info *pi = &m->info.params[p];
            for (int r = 0; r < OB_ROLE_COUNT; ++r)
                if (!strcmp(pi->name, roles[r].name))
                    CHECK(ob_method_role(m, (ob_param_role)r) == p,
                          "%s.%s: declared under its role in the method's .roles (OB_ROLE_PARAM)", name, pi->name);
            if (pi->follows_scene_radius)
                CHECK(ob_method_role(m, OB_ROLE_RADIUS) == p, "%s.%s follows the scene's radius: OB_ROLE_RADIUS", name,
                      pi->name);
        }
        /* The sample count comes from the role: what --samples sets is what the method reports. */
        ob_settings s;
        if (ob_method_role(m, OB_ROLE_SAMPLES) >= 0 && ob_settings_init(&s, name) == OB_OK) {
            const int p = ob_method_role(m, OB_ROLE_SAMPLES);
            const int n = (int)m->info.params[p].min + 1;
            CHECK(ob_settings_set_samples(&s, n) == OB_OK && ob_method_samples(m, s.params) == n &&
                      (s.params_set >> p & 1u),
                  "%s: --samples %d sets %s", name, n, m->info.params[p].name);
        }
    }
    CHECK(declared > 0, "some method declares a role (%d)", declared);
}

/* The library's version is the header's (obscura.h "version"). */
static void test_version(void)
{
    int major = -1, minor = -1, patch = -1;
    const char *v = ob_version(&major, &minor, &patch);
    char want[32];
    snprintf(want, sizeof want, "%d.%d.%d", OB_VERSION_MAJOR, OB_VERSION_MINOR, OB_VERSION_PATCH);
    CHECK(major == OB_VERSION_MAJOR && minor == OB_VERSION_MINOR && patch == OB_VERSION_PATCH,
          "ob_version numbers %d.%d.%d", major, minor, patch);
    CHECK(v && !strcmp(v, want) && !strcmp(v, OB_VERSION_STRING), "ob_version \"%s\", header %s", v ? v : "(null)",
          want);
    CHECK(ob_version(NULL, NULL, NULL) == v, "ob_version with NULL pointers");
}

int main(void)
{
    test_version();
    test_errors();
    test_frame_constants();
    test_registry_and_settings();
    test_method_roles();
    test_kernel();
    test_method_kernel();
    test_halton();
    test_files();
    test_shader_log();
    test_environment_sh();
    test_lights();
    return check_finish("test_cpu");
}
