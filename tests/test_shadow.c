/* GPU tests of the shadow maps (SSDO thesis §2.1, §5.1, §6.1) on the real GLSL (llvmpipe in CI):
 * a unit box on a 20x20 floor, maps from ob_shadows_render, and ob_shadow() of shaders/shadow.glsl
 * evaluated at chosen world points by shaders/shadow_probe.glsl, without the lighting pass.
 *   (a) a directional light from +x and above shadows the floor on the box's -x side, and only
 *       there, for hard, PCF and VSM;
 *   (b) the penumbra across the shadow's far edge is wider for PCF and for VSM than for hard;
 *   (c) spot and point lights cast the shadow away from themselves, from four sides (the point
 *       light's cube faces +-X, +-Z and -Y all take part), several maps of mixed kinds at once;
 *   plus: method none, lights past OB_MAX_SHADOW_MAPS, GL state left as found, bad settings.
 * Timings (llvmpipe or GPU): the "shadow" pass per method at 2048^2 for one directional light and
 * one ob_shadow() per pixel of an 800x600 grid of floor points (480000 probes). */
#include <cglm/cglm.h>
#include <epoxy/gl.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "gpu/gpu.h"
#include "obscura/eval.h"
#include "passes/passes.h"
#include "scene/scene.h"

enum { MAP_SIZE = 2048 };

/* ---- the scene ----------------------------------------------------------------------------- */

static void add_quad(ob_mesh *m, uint32_t *v, uint32_t *i, const float p[4][3], const float n[3])
{
    for (int k = 0; k < 4; ++k) {
        memcpy(&m->positions[3 * (*v + (uint32_t)k)], p[k], 3 * sizeof(float));
        memcpy(&m->normals[3 * (*v + (uint32_t)k)], n, 3 * sizeof(float));
    }
    const uint32_t tri[6] = {0, 1, 2, 0, 2, 3};
    for (int k = 0; k < 6; ++k) m->indices[*i + (uint32_t)k] = *v + tri[k];
    *v += 4;
    *i += 6;
}

/* Floor y = 0 over [-10, 10]^2 and a box [-0.5, 0.5] x [0, 1] x [-0.5, 0.5]. */
static ob_scene *box_on_plane(void)
{
    ob_scene *s = ob_scene_alloc("box-on-plane");
    int mat = ob_scene_add_material(s, "grey", 0.8f, 0.8f, 0.8f);
    ob_mesh *floor = ob_scene_add_mesh(s, 4, 6, false);
    if (!floor) return s;
    floor->material = mat;
    uint32_t v = 0, i = 0;
    const float fp[4][3] = {{-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}};
    const float up[3] = {0, 1, 0};
    add_quad(floor, &v, &i, fp, up);
    ob_mesh *box = ob_scene_add_mesh(s, 24, 36, false);
    if (!box) return s;
    box->material = mat;
    v = i = 0;
    const float a = 0.5f;
    const float faces[6][4][3] = {
        {{a, 0, -a}, {a, 1, -a}, {a, 1, a}, {a, 0, a}},     /* +x */
        {{-a, 0, a}, {-a, 1, a}, {-a, 1, -a}, {-a, 0, -a}}, /* -x */
        {{-a, 1, -a}, {-a, 1, a}, {a, 1, a}, {a, 1, -a}},   /* +y */
        {{-a, 0, -a}, {a, 0, -a}, {a, 0, a}, {-a, 0, a}},   /* -y */
        {{-a, 0, a}, {a, 0, a}, {a, 1, a}, {-a, 1, a}},     /* +z */
        {{a, 0, -a}, {-a, 0, -a}, {-a, 1, -a}, {a, 1, -a}}, /* -z */
    };
    const float normals[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (int f = 0; f < 6; ++f) add_quad(box, &v, &i, faces[f], normals[f]);
    ob_scene_finish(s);
    return s;
}

/* ---- the probe ------------------------------------------------------------------------------ */

typedef struct probe {
    GLuint program, ubo, frame_ubo, buffers[3];
    size_t capacity;
} probe;

static bool probe_init(probe *p)
{
    memset(p, 0, sizeof *p);
    p->program = ob_make_compute_program("shadow_probe.glsl", NULL);
    if (!p->program) {
        const char *msg = NULL;
        ob_get_error(&msg);
        fprintf(stderr, "shadow_probe.glsl: %s\n", msg);
        return false;
    }
    glCreateBuffers(1, &p->ubo);
    glNamedBufferStorage(p->ubo, sizeof(ob_lighting_constants), NULL, GL_DYNAMIC_STORAGE_BIT);
    /* The lights are the per-frame block's (frame_params.h), as in the lighting pass. */
    glCreateBuffers(1, &p->frame_ubo);
    glNamedBufferStorage(p->frame_ubo, sizeof(ob_frame_constants), NULL, GL_DYNAMIC_STORAGE_BIT);
    return true;
}

static void probe_destroy(probe *p)
{
    if (p->program) glDeleteProgram(p->program);
    if (p->ubo) glDeleteBuffers(1, &p->ubo);
    if (p->frame_ubo) glDeleteBuffers(1, &p->frame_ubo);
    if (p->capacity) glDeleteBuffers(3, p->buffers);
    memset(p, 0, sizeof *p);
}

/* The lights of the per-frame block, as the renderer fills them (src/core/frame.c). */
static void fill_lights(ob_frame_constants *c, const ob_light *lights, int n)
{
    memset(c, 0, sizeof *c);
    c->light_count = n;
    for (int i = 0; i < n; ++i) {
        vec3 d = {lights[i].direction[0], lights[i].direction[1], lights[i].direction[2]};
        glm_vec3_normalize(d);
        for (int k = 0; k < 3; ++k) {
            c->light_color[i][k] = lights[i].color[k] * lights[i].intensity;
            c->light_position[i][k] = lights[i].position[k];
            c->light_direction[i][k] = d[k];
        }
        c->light_color[i][3] = (float)lights[i].type;
        c->light_direction[i][3] = -1.0f;
        c->light_spot[i][0] = cosf(glm_rad(lights[i].spot_inner_deg));
        c->light_spot[i][1] = cosf(glm_rad(lights[i].spot_outer_deg));
    }
}

/* ob_shadow(light[i], points[i], normals[i]) for n points (xyz + light index in w). Returns the
 * GPU time of the dispatch in ms (timers: GL_TIMESTAMP, as the renderer measures passes). */
static double probe_run(probe *p, const ob_shadow_maps *maps, const ob_light *lights, int light_count,
                        const float *points, const float *normals, float *out, size_t n)
{
    if (n > p->capacity) {
        if (p->capacity) glDeleteBuffers(3, p->buffers);
        glCreateBuffers(3, p->buffers);
        glNamedBufferStorage(p->buffers[0], (GLsizeiptr)(n * 4 * sizeof(float)), NULL, GL_DYNAMIC_STORAGE_BIT);
        glNamedBufferStorage(p->buffers[1], (GLsizeiptr)(n * 4 * sizeof(float)), NULL, GL_DYNAMIC_STORAGE_BIT);
        glNamedBufferStorage(p->buffers[2], (GLsizeiptr)(n * sizeof(float)), NULL, GL_DYNAMIC_STORAGE_BIT);
        p->capacity = n;
    }
    glNamedBufferSubData(p->buffers[0], 0, (GLsizeiptr)(n * 4 * sizeof(float)), points);
    glNamedBufferSubData(p->buffers[1], 0, (GLsizeiptr)(n * 4 * sizeof(float)), normals);
    ob_lighting_constants c;
    memset(&c, 0, sizeof c);
    ob_frame_constants frame;
    fill_lights(&frame, lights, light_count);
    ob_shadows_fill(maps, &c, &frame);
    glNamedBufferSubData(p->ubo, 0, sizeof c, &c);
    glNamedBufferSubData(p->frame_ubo, 0, sizeof frame, &frame);
    glUseProgram(p->program);
    glBindBufferBase(GL_UNIFORM_BUFFER, OB_BINDING_PASS, p->ubo);
    glBindBufferBase(GL_UNIFORM_BUFFER, OB_BINDING_FRAME, p->frame_ubo);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 0, p->buffers[0], 0, (GLsizeiptr)(n * 4 * sizeof(float)));
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 1, p->buffers[1], 0, (GLsizeiptr)(n * 4 * sizeof(float)));
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, 2, p->buffers[2], 0, (GLsizeiptr)(n * sizeof(float)));
    ob_timer_set t;
    ob_timers_init(&t);
    ob_timers_frame_begin(&t);
    ob_timer_begin(&t, "probe");
    glDispatchCompute((GLuint)((n + 63) / 64), 1, 1);
    ob_timer_end(&t);
    ob_timers_frame_end(&t);
    ob_timers_wait(&t);
    double ms = t.ms[0];
    ob_timers_destroy(&t);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(p->buffers[2], 0, (GLsizeiptr)(n * sizeof(float)), out);
    return ms;
}

/* One probe point. */
typedef struct sample {
    float p[3], n[3];
    int light;
} sample;

static void visibility_of(probe *pr, const ob_shadow_maps *maps, const ob_light *lights, int light_count,
                          const sample *s, int count, float *vis)
{
    float *pts = calloc((size_t)count * 4, sizeof(float));
    float *nrm = calloc((size_t)count * 4, sizeof(float));
    for (int i = 0; i < count; ++i) {
        memcpy(&pts[4 * i], s[i].p, 3 * sizeof(float));
        pts[4 * i + 3] = (float)s[i].light;
        memcpy(&nrm[4 * i], s[i].n, 3 * sizeof(float));
    }
    probe_run(pr, maps, lights, light_count, pts, nrm, vis, (size_t)count);
    free(pts);
    free(nrm);
}

static const char *method_name(ob_shadow_method m)
{
    static const char *names[] = {"none", "hard", "pcf", "vsm"};
    return names[m];
}

static ob_shadow_settings settings_for(ob_shadow_method m)
{
    /* The defaults recommended to src/core/settings.c. */
    return (ob_shadow_settings){.method = m, .size = MAP_SIZE, .bias = 1.0f, .slope_bias = 0.75f, .pcf_radius = 1,
                                .vsm_blur = 2.0f, .vsm_bleed = 0.25f};
}

static ob_light directional(float x, float y, float z)
{
    return (ob_light){.direction = {x, y, z}, .color = {1, 1, 1}, .intensity = 1.0f, .type = OB_LIGHT_DIRECTIONAL};
}

static ob_light spot_at(float x, float y, float z)
{
    /* Aimed at the box's centre. */
    return (ob_light){.direction = {-x, 0.5f - y, -z}, .color = {1, 1, 1}, .intensity = 10.0f, .type = OB_LIGHT_SPOT,
                      .position = {x, y, z}, .spot_inner_deg = 30.0f, .spot_outer_deg = 40.0f};
}

static ob_light point_at(float x, float y, float z)
{
    return (ob_light){.color = {1, 1, 1}, .intensity = 10.0f, .type = OB_LIGHT_POINT, .position = {x, y, z}};
}

/* ---- tests ---------------------------------------------------------------------------------- */

typedef struct fixture {
    ob_gbuffer g;
    ob_shadow_maps maps;
    probe pr;
    float bmin[3], bmax[3];
} fixture;

static const float floor_n[3] = {0, 1, 0};

static sample floor_at(float x, float z, int light)
{
    return (sample){.p = {x, 0.0f, z}, .n = {floor_n[0], floor_n[1], floor_n[2]}, .light = light};
}

/* Width along x of the band 0.05 < v < 0.95 across the directional shadow's far edge (x = -1.5,
 * z = 0), sampled every 0.2 mm. */
static float penumbra_width(fixture *f, const ob_light *l)
{
    enum { N = 2001 };
    const float x0 = -1.7f, dx = 0.4f / (N - 1);
    sample *s = calloc(N, sizeof *s);
    float *vis = calloc(N, sizeof *vis);
    for (int i = 0; i < N; ++i) s[i] = floor_at(x0 + dx * (float)i, 0.0f, 0);
    visibility_of(&f->pr, &f->maps, l, 1, s, N, vis);
    int band = 0;
    for (int i = 0; i < N; ++i) band += vis[i] > 0.05f && vis[i] < 0.95f;
    bool shadow_left = vis[N - 1] < 0.05f, lit_right = vis[0] > 0.95f;
    CHECK(shadow_left && lit_right, "edge sampled: v(-1.7) = %.3f lit, v(-1.3) = %.3f shadowed", (double)vis[0],
          (double)vis[N - 1]);
    free(s);
    free(vis);
    return (float)band * dx;
}

static void test_directional(fixture *f)
{
    ob_light l = directional(1.0f, 1.0f, 0.0f); /* from +x, 45 degrees up */
    float width[4] = {0};
    for (ob_shadow_method m = OB_SHADOW_HARD; m <= OB_SHADOW_VSM; ++m) {
        ob_shadow_settings st = settings_for(m);
        ob_error err = ob_shadows_render(&f->maps, &f->g, &l, 1, f->bmin, f->bmax, &st, NULL);
        CHECK(err == OB_OK, "%s: render: %s", method_name(m), ob_error_name(err));
        /* The box's shadow on the floor spans x in [-1.5, -0.5], z in [-0.5, 0.5]. */
        const sample shadowed[] = {floor_at(-1.0f, 0.0f, 0), floor_at(-0.7f, 0.3f, 0), floor_at(-1.3f, -0.3f, 0),
                                   floor_at(-0.55f, 0.0f, 0)};
        const sample lit[] = {
            floor_at(1.0f, 0.0f, 0),  floor_at(0.6f, 0.3f, 0),  floor_at(6.0f, 6.0f, 0),
            floor_at(-6.0f, -6.0f, 0), floor_at(-1.0f, 1.5f, 0), floor_at(-3.0f, 0.0f, 0),
            floor_at(9.5f, -9.5f, 0), /* near the map's corner */
            {.p = {0.0f, 1.0f, 0.0f}, .n = {0, 1, 0}, .light = 0},   /* the box's top */
            {.p = {0.5f, 0.5f, 0.0f}, .n = {1, 0, 0}, .light = 0},   /* the face toward the light */
        };
        enum { LIT = sizeof lit / sizeof lit[0] };
        float vs[4] = {0}, vl[LIT] = {0};
        visibility_of(&f->pr, &f->maps, &l, 1, shadowed, 4, vs);
        visibility_of(&f->pr, &f->maps, &l, 1, lit, LIT, vl);
        for (int i = 0; i < 4; ++i)
            CHECK(vs[i] < 0.1f, "%s: floor (%.2f, %.2f) behind the box: visibility %.3f", method_name(m),
                  (double)shadowed[i].p[0], (double)shadowed[i].p[2], (double)vs[i]);
        for (int i = 0; i < LIT; ++i)
            CHECK(vl[i] > 0.9f, "%s: (%.2f, %.2f, %.2f) lit: visibility %.3f", method_name(m), (double)lit[i].p[0],
                  (double)lit[i].p[1], (double)lit[i].p[2], (double)vl[i]);
        width[m] = penumbra_width(f, &l);
        printf("directional %s: penumbra %.4f world units (0.05 < v < 0.95)\n", method_name(m), (double)width[m]);
    }
    CHECK(width[OB_SHADOW_PCF] > width[OB_SHADOW_HARD] + 0.005f, "pcf penumbra %.4f wider than hard %.4f",
          (double)width[OB_SHADOW_PCF], (double)width[OB_SHADOW_HARD]);
    CHECK(width[OB_SHADOW_VSM] > width[OB_SHADOW_HARD] + 0.005f, "vsm penumbra %.4f wider than hard %.4f",
          (double)width[OB_SHADOW_VSM], (double)width[OB_SHADOW_HARD]);
    /* Hard is one nearest-texel comparison: the edge is a step, at most a couple of samples. */
    CHECK(width[OB_SHADOW_HARD] < 0.002f, "hard edge is a step (band %.4f)", (double)width[OB_SHADOW_HARD]);
}

/* Lights on four sides of the box (and above): the floor 2 units beyond the box, away from each
 * light, is in shadow; the floor 2 units toward it and 3 units to the side is lit. All the lights of
 * one kind go into one ob_shadows_render (the first four get maps: layers / cubes 0..3). */
static void test_local_lights(fixture *f, ob_light_type type)
{
    const char *kind = type == OB_LIGHT_POINT ? "point" : "spot";
    /* (light x, y, z), unit direction on the floor from the box toward the light */
    const float where[4][5] = {
        {3.0f, 1.5f, 0.0f, 1.0f, 0.0f},   /* +x, low: the shadow side is seen through -X */
        {0.0f, 1.5f, 3.0f, 0.0f, 1.0f},   /* +z: -Z face */
        {-3.0f, 1.5f, 0.0f, -1.0f, 0.0f}, /* -x: +X face */
        {0.0f, 1.5f, -3.0f, 0.0f, -1.0f}, /* -z: +Z face */
    };
    ob_light lights[5];
    for (int i = 0; i < 4; ++i)
        lights[i] = type == OB_LIGHT_POINT ? point_at(where[i][0], where[i][1], where[i][2])
                                           : spot_at(where[i][0], where[i][1], where[i][2]);
    /* A fifth light (high above +x) gets no map: only OB_MAX_SHADOW_MAPS are shadowed. */
    lights[4] = type == OB_LIGHT_POINT ? point_at(2.5f, 4.0f, 0.0f) : spot_at(2.5f, 4.0f, 0.0f);
    for (ob_shadow_method m = OB_SHADOW_HARD; m <= OB_SHADOW_VSM; ++m) {
        ob_shadow_settings st = settings_for(m);
        st.size = 1024;
        ob_error err = ob_shadows_render(&f->maps, &f->g, lights, 5, f->bmin, f->bmax, &st, NULL);
        CHECK(err == OB_OK, "%s %s: render: %s", kind, method_name(m), ob_error_name(err));
        sample s[4 * 4];
        for (int i = 0; i < 4; ++i) {
            float dx = where[i][3], dz = where[i][4];
            s[4 * i + 0] = floor_at(-2.0f * dx, -2.0f * dz, i);                        /* behind the box */
            s[4 * i + 1] = floor_at(-1.0f * dx, -1.0f * dz, i);                        /* right behind it */
            s[4 * i + 2] = floor_at(2.0f * dx, 2.0f * dz, i);                          /* toward the light */
            s[4 * i + 3] = floor_at(-2.0f * dx + 2.0f * dz, -2.0f * dz + 2.0f * dx, i); /* beside the shadow */
        }
        float vis[16] = {0};
        visibility_of(&f->pr, &f->maps, lights, 5, s, 16, vis);
        for (int i = 0; i < 4; ++i) {
            for (int k = 0; k < 2; ++k)
                CHECK(vis[4 * i + k] < 0.1f, "%s %s light %d at (%g, %g, %g): floor (%.1f, %.1f) shadowed, got %.3f",
                      kind, method_name(m), i, (double)where[i][0], (double)where[i][1], (double)where[i][2],
                      (double)s[4 * i + k].p[0], (double)s[4 * i + k].p[2], (double)vis[4 * i + k]);
            for (int k = 2; k < 4; ++k)
                CHECK(vis[4 * i + k] > 0.9f, "%s %s light %d: floor (%.1f, %.1f) lit, got %.3f", kind,
                      method_name(m), i, (double)s[4 * i + k].p[0], (double)s[4 * i + k].p[2],
                      (double)vis[4 * i + k]);
        }
        /* From high above +x (light 4, unshadowed): the same floor point behind the box reads 1. */
        sample s4 = floor_at(-1.0f, 0.0f, 4);
        float v4 = 0.0f;
        visibility_of(&f->pr, &f->maps, lights, 5, &s4, 1, &v4);
        CHECK(v4 == 1.0f, "%s %s: a fifth light has no map (visibility %.3f)", kind, method_name(m), (double)v4);
        CHECK(f->maps.light_map[4] == -1 && f->maps.light_map[3] == 3, "%s: maps of lights 3, 4: %d, %d", kind,
              f->maps.light_map[3], f->maps.light_map[4]);
    }
    /* The same light alone, from high above (-Y face / a steep spot): shadow beyond -x. */
    ob_light high = lights[4];
    ob_shadow_settings st = settings_for(OB_SHADOW_PCF);
    st.size = 1024;
    CHECK(ob_shadows_render(&f->maps, &f->g, &high, 1, f->bmin, f->bmax, &st, NULL) == OB_OK, "%s high", kind);
    const sample s[3] = {floor_at(-1.0f, 0.0f, 0), floor_at(1.5f, 0.0f, 0), floor_at(-1.0f, 1.5f, 0)};
    float vis[3] = {0};
    visibility_of(&f->pr, &f->maps, &high, 1, s, 3, vis);
    CHECK(vis[0] < 0.1f && vis[1] > 0.9f && vis[2] > 0.9f, "%s from (2.5, 4, 0): behind %.3f, front %.3f, side %.3f",
          kind, (double)vis[0], (double)vis[1], (double)vis[2]);
}

/* Mixed kinds in one call: directional + spot + point + point share 2D layers and cubes. */
static void test_mixed(fixture *f)
{
    ob_light lights[4] = {point_at(3.0f, 1.5f, 0.0f), directional(1.0f, 1.0f, 0.0f), point_at(0.0f, 1.5f, 3.0f),
                          spot_at(-3.0f, 1.5f, 0.0f)};
    ob_shadow_settings st = settings_for(OB_SHADOW_PCF);
    st.size = 512;
    CHECK(ob_shadows_render(&f->maps, &f->g, lights, 4, f->bmin, f->bmax, &st, NULL) == OB_OK, "mixed render");
    CHECK(f->maps.layers_2d == 2 && f->maps.cubes == 2, "mixed: %d 2D layers, %d cubes", f->maps.layers_2d,
          f->maps.cubes);
    const sample s[8] = {floor_at(-2.0f, 0.0f, 0), floor_at(2.0f, 0.0f, 0), floor_at(-1.0f, 0.0f, 1),
                         floor_at(1.0f, 0.0f, 1),  floor_at(0.0f, -2.0f, 2), floor_at(0.0f, 2.0f, 2),
                         floor_at(2.0f, 0.0f, 3),  floor_at(-2.0f, 0.0f, 3)};
    float vis[8] = {0};
    visibility_of(&f->pr, &f->maps, lights, 4, s, 8, vis);
    for (int i = 0; i < 8; i += 2)
        CHECK(vis[i] < 0.1f && vis[i + 1] > 0.9f, "mixed light %d: behind %.3f, toward %.3f", s[i].light,
              (double)vis[i], (double)vis[i + 1]);
}

static void test_none_and_state(fixture *f)
{
    ob_light l = directional(1.0f, 1.0f, 0.0f);
    glViewport(3, 4, 50, 60);
    glDisable(GL_DEPTH_TEST);
    ob_shadow_settings st = settings_for(OB_SHADOW_PCF);
    CHECK(ob_shadows_render(&f->maps, &f->g, &l, 1, f->bmin, f->bmax, &st, NULL) == OB_OK, "render");
    GLint fb = -1, vp[4] = {0};
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &fb);
    glGetIntegerv(GL_VIEWPORT, vp);
    CHECK(fb == 0, "framebuffer 0 bound after the shadow pass (%d)", fb);
    CHECK(vp[0] == 3 && vp[1] == 4 && vp[2] == 50 && vp[3] == 60, "viewport restored (%d %d %d %d)", vp[0], vp[1],
          vp[2], vp[3]);
    CHECK(!glIsEnabled(GL_DEPTH_TEST) && !glIsEnabled(GL_POLYGON_OFFSET_FILL) && !glIsEnabled(GL_DEPTH_CLAMP),
          "depth test, polygon offset and depth clamp as found");
    CHECK(glGetError() == GL_NO_ERROR, "no GL error");

    st.method = OB_SHADOW_NONE;
    CHECK(ob_shadows_render(&f->maps, &f->g, &l, 1, f->bmin, f->bmax, &st, NULL) == OB_OK, "render none");
    ob_lighting_constants c;
    memset(&c, 0, sizeof c);
    ob_frame_constants frame;
    fill_lights(&frame, &l, 1);
    frame.light_direction[0][3] = 7.0f;
    ob_shadows_fill(&f->maps, &c, &frame);
    CHECK(frame.light_direction[0][3] == -1.0f && c.shadow_method == 0, "none: unshadowed (%g, %d)",
          (double)frame.light_direction[0][3], c.shadow_method);
    const sample s = floor_at(-1.0f, 0.0f, 0);
    float v = 0.0f;
    visibility_of(&f->pr, &f->maps, &l, 1, &s, 1, &v);
    CHECK(v == 1.0f, "none: the shadowed point reads 1 (%.3f)", (double)v);

    st = settings_for(OB_SHADOW_PCF);
    st.size = 4;
    CHECK(ob_shadows_render(&f->maps, &f->g, &l, 1, f->bmin, f->bmax, &st, NULL) == OB_ERR_OUT_OF_RANGE, "size 4");
    st = settings_for(OB_SHADOW_PCF);
    st.pcf_radius = 0;
    CHECK(ob_shadows_render(&f->maps, &f->g, &l, 1, f->bmin, f->bmax, &st, NULL) == OB_ERR_OUT_OF_RANGE, "radius 0");
    st = settings_for(OB_SHADOW_VSM);
    st.vsm_bleed = 1.0f;
    CHECK(ob_shadows_render(&f->maps, &f->g, &l, 1, f->bmin, f->bmax, &st, NULL) == OB_ERR_OUT_OF_RANGE, "bleed 1");
    st = settings_for(OB_SHADOW_HARD);
    st.bias = -1.0f;
    CHECK(ob_shadows_render(&f->maps, &f->g, &l, 1, f->bmin, f->bmax, &st, NULL) == OB_ERR_OUT_OF_RANGE, "bias < 0");
}

/* Median of the "shadow" pass over a few frames, and one ob_shadow() per point of an 800x600 grid
 * over the floor around the box. Printed, not checked: llvmpipe's times say little about a GPU. */
static double wall_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static void sort5(double *v, int n)
{
    for (int a = 1; a < n; ++a)
        for (int b = a; b > 0 && v[b] < v[b - 1]; --b) {
            double tmp = v[b];
            v[b] = v[b - 1];
            v[b - 1] = tmp;
        }
}

static void timings(fixture *f)
{
    enum { W = 800, H = 600, FRAMES = 5 };
    ob_light l = directional(1.0f, 1.0f, 0.0f);
    float *pts = calloc((size_t)W * H * 4, sizeof(float));
    float *nrm = calloc((size_t)W * H * 4, sizeof(float));
    float *vis = calloc((size_t)W * H, sizeof(float));
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            size_t i = (size_t)y * W + (size_t)x;
            pts[4 * i + 0] = -4.0f + 8.0f * ((float)x + 0.5f) / W;
            pts[4 * i + 2] = -3.0f + 6.0f * ((float)y + 0.5f) / H;
            nrm[4 * i + 1] = 1.0f;
        }
    for (ob_shadow_method m = OB_SHADOW_HARD; m <= OB_SHADOW_VSM; ++m) {
        ob_shadow_settings st = settings_for(m);
        double shadow_ms[FRAMES] = {0}, probe_ms[FRAMES] = {0}, wall[FRAMES] = {0};
        for (int k = 0; k < FRAMES; ++k) {
            ob_timer_set t;
            ob_timers_init(&t);
            glFinish();
            double t0 = wall_ms();
            ob_timers_frame_begin(&t);
            ob_shadows_render(&f->maps, &f->g, &l, 1, f->bmin, f->bmax, &st, &t);
            ob_timers_frame_end(&t);
            ob_timers_wait(&t);
            glFinish();
            wall[k] = wall_ms() - t0;
            shadow_ms[k] = t.count > 0 ? t.ms[0] : -1.0;
            CHECK(t.count == 1 && strcmp(t.names[0], "shadow") == 0, "timed as \"shadow\"");
            ob_timers_destroy(&t);
            probe_ms[k] = probe_run(&f->pr, &f->maps, &l, 1, pts, nrm, vis, (size_t)W * H);
        }
        sort5(shadow_ms, FRAMES);
        sort5(probe_ms, FRAMES);
        sort5(wall, FRAMES);
        double mean = 0.0;
        for (size_t i = 0; i < (size_t)W * H; ++i) mean += vis[i];
        printf("timing %s: shadow pass %.2f ms (%dx%d, directional; %.2f ms wall with glFinish), ob_shadow x %d = "
               "%.2f ms (medians of %d); mean visibility %.4f\n",
               method_name(m), shadow_ms[FRAMES / 2], MAP_SIZE, MAP_SIZE, wall[FRAMES / 2], W * H,
               probe_ms[FRAMES / 2], FRAMES, mean / (double)(W * H));
    }
    free(pts);
    free(nrm);
    free(vis);
}

/* ob_shadow_settings.reuse: the maps are kept (no "shadow" timing, the same visibility) while
 * the light, the settings and the scene stay; any change of one renders them again. */
static int timed_render(fixture *f, const ob_light *l, const ob_shadow_settings *st)
{
    ob_timer_set t;
    ob_timers_init(&t);
    ob_timers_frame_begin(&t);
    ob_error err = ob_shadows_render(&f->maps, &f->g, l, 1, f->bmin, f->bmax, st, &t);
    ob_timers_frame_end(&t);
    ob_timers_wait(&t);
    int count = err == OB_OK ? t.count : -1;
    ob_timers_destroy(&t);
    return count;
}

static void test_reuse(fixture *f, const ob_scene *scene)
{
    enum { N = 64 };
    float pts[N * 4] = {0}, nrm[N * 4] = {0}, fresh[N] = {0}, kept[N] = {0}, moved[N] = {0};
    for (int i = 0; i < N; ++i) { /* a line across the box's shadow on the floor */
        pts[4 * i + 0] = -4.0f + 8.0f * ((float)i + 0.5f) / N;
        nrm[4 * i + 1] = 1.0f;
    }
    ob_light l = directional(1.0f, 1.0f, 0.0f);
    ob_shadow_settings st = settings_for(OB_SHADOW_PCF);
    CHECK(timed_render(f, &l, &st) == 1, "reuse off: rendered");
    probe_run(&f->pr, &f->maps, &l, 1, pts, nrm, fresh, N);
    st.reuse = true;
    /* The maps just rendered hold for these inputs (reuse itself is not part of the key). */
    CHECK(timed_render(f, &l, &st) == 0, "reuse: the next frame keeps the maps, untimed");
    probe_run(&f->pr, &f->maps, &l, 1, pts, nrm, kept, N);
    CHECK(memcmp(fresh, kept, sizeof fresh) == 0, "reuse: the kept maps give the same visibility");
    ob_light l2 = directional(-1.0f, 1.0f, 0.0f);
    CHECK(timed_render(f, &l2, &st) == 1, "reuse: a new light direction renders again");
    probe_run(&f->pr, &f->maps, &l2, 1, pts, nrm, moved, N);
    CHECK(memcmp(fresh, moved, sizeof fresh) != 0, "reuse: and the shadow moved");
    CHECK(timed_render(f, &l2, &st) == 0, "reuse: then it is kept again");
    st.pcf_radius = 2;
    CHECK(timed_render(f, &l2, &st) == 1, "reuse: a new PCF radius renders again");
    CHECK(ob_gbuffer_set_scene(&f->g, scene) == OB_OK && timed_render(f, &l2, &st) == 1,
          "reuse: a new scene upload renders again");
    st.method = OB_SHADOW_NONE;
    CHECK(timed_render(f, &l2, &st) == 0 && f->maps.method == OB_SHADOW_NONE, "reuse: none draws no maps");
    st.method = OB_SHADOW_PCF;
    CHECK(timed_render(f, &l2, &st) == 1, "reuse: after none the maps are rendered again");
}

int main(void)
{
    ob_context *ctx = ob_make_context(&(ob_context_desc){.gpu = OB_GPU_AUTO});
    if (!ctx) {
        const char *msg = NULL;
        ob_get_error(&msg);
        fprintf(stderr, "no context: %s\n", msg);
        return 1;
    }
    printf("renderer: %s (%s)\n", ob_query_renderer(ctx), ob_query_device(ctx));
    ob_scene *scene = box_on_plane();
    fixture f;
    memset(&f, 0, sizeof f);
    memcpy(f.bmin, scene->bounds_min, sizeof f.bmin);
    memcpy(f.bmax, scene->bounds_max, sizeof f.bmax);
    CHECK(scene->mesh_count == 2 && f.bmin[0] == -10.0f && f.bmax[1] == 1.0f, "box-on-plane built");
    bool ok = ob_gbuffer_init(&f.g, 64, 64) == OB_OK && ob_gbuffer_set_scene(&f.g, scene) == OB_OK;
    CHECK(ok, "G-buffer with the scene");
    ob_error err = ob_shadows_init(&f.maps);
    CHECK(err == OB_OK, "ob_shadows_init: %s", ob_error_name(err));
    bool probe_ok = probe_init(&f.pr);
    CHECK(probe_ok, "shadow_probe.glsl builds");
    if (ok && err == OB_OK && probe_ok) {
        test_directional(&f);
        test_local_lights(&f, OB_LIGHT_SPOT);
        test_local_lights(&f, OB_LIGHT_POINT);
        test_mixed(&f);
        test_none_and_state(&f);
        test_reuse(&f, scene);
        timings(&f);
    }
    probe_destroy(&f.pr);
    ob_shadows_destroy(&f.maps);
    ob_gbuffer_destroy(&f.g);
    ob_destroy_scene(scene);
    ob_destroy_context(ctx);
    return check_finish("test_shadow");
}
