/* The per-pass GPU timers (src/gpu/timer.c) through the public API: a ring of query sets read a
 * few frames late. Structure and consistency only, never speed: timings arrive after a few frames
 * without ob_wait_timings, they name the frame they describe, every pass that ran in that frame is
 * there once with a time >= 0 and a CPU time > 0, a pass that did not run (cached shadow maps) is
 * absent, no frame's passes (GPU or CPU times) add up to more than the wall-clock time from its
 * submission to its completion, and a framebuffer with a size bound (a window's, as in obscura
 * view) does not shift the times. */
#include <math.h>
#include <string.h>
#include <time.h>

#include "check.h"
#include "gpu/gpu.h"
#include "obscura/eval.h"

enum { W = 64, H = 48, MAXP = 32 };

static ob_camera cam;
static ob_scene *scene;

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return 1e3 * (double)ts.tv_sec + 1e-6 * (double)ts.tv_nsec;
}

static int find(const ob_pass_timing *t, int n, const char *name)
{
    int hits = 0;
    for (int i = 0; i < n; ++i) hits += !strcmp(t[i].name, name);
    return hits;
}

/* Every time finite and >= 0, every name once, something measured. */
static void check_set(const ob_pass_timing *t, int n, const char *what)
{
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        CHECK(isfinite(t[i].ms) && t[i].ms >= 0.0, "%s: %s %.6g ms", what, t[i].name, t[i].ms);
        CHECK(isfinite(t[i].cpu_ms) && t[i].cpu_ms > 0.0, "%s: %s took %.6g ms of CPU to issue", what, t[i].name,
              t[i].cpu_ms);
        CHECK(find(t, n, t[i].name) == 1, "%s: %s listed once", what, t[i].name);
        sum += t[i].ms;
    }
    CHECK(sum > 0.0, "%s: the passes add up to %.6g ms", what, sum);
}

static void test_ring(ob_context *ctx, const ob_settings *s)
{
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    CHECK(r && ob_renderer_set_scene(r, scene) == OB_OK, "renderer");
    if (!r) return;
    ob_pass_timing t[MAXP];
    long long timed = 7, rendered = 7;
    ob_query_timings_frame(r, &timed, &rendered);
    CHECK(timed == -1 && rendered == -1, "before any frame: timed %lld, rendered %lld", timed, rendered);
    CHECK(ob_query_timings(r, t, MAXP) == 0, "before any frame: no timings");
    /* One more frame than the ring holds, never waiting: the newest finished frame is reported,
     * one of the last OB_TIMER_RING (the slot's reuse collects the oldest at the latest). */
    for (int f = 0; f <= OB_TIMER_RING; ++f) CHECK(ob_render_frame(r, &cam, s) == OB_OK, "frame %d", f);
    ob_query_timings_frame(r, &timed, &rendered);
    CHECK(rendered == OB_TIMER_RING, "rendered %lld, want %d", rendered, OB_TIMER_RING);
    CHECK(timed >= rendered - OB_TIMER_RING && timed <= rendered, "timings of frame %lld after frame %lld", timed,
          rendered);
    int n = ob_query_timings(r, t, MAXP);
    CHECK(n > 0, "timings without waiting after %d frames", OB_TIMER_RING + 1);
    check_set(t, n, "ring");
    static const char *const always[] = {"gbuffer", "lighting", "ao", "filter", "compose", "tonemap"};
    for (size_t k = 0; k < sizeof always / sizeof always[0]; ++k)
        CHECK(find(t, n, always[k]) == 1, "ring: %s present", always[k]);
    /* max smaller than the count: the first max, in frame order. */
    ob_pass_timing two[2];
    CHECK(ob_query_timings(r, two, 2) == 2 && !strcmp(two[0].name, t[0].name) && !strcmp(two[1].name, t[1].name),
          "max 2 gives the first two");
    CHECK(ob_query_timings(r, two, 0) == 0 && ob_query_timings(r, two, -3) == 0, "max 0 or negative: none written");
    /* Waiting makes the last frame the timed one. */
    CHECK(ob_wait_timings(r) == OB_OK, "ob_wait_timings");
    ob_query_timings_frame(r, &timed, &rendered);
    CHECK(timed == rendered, "after the wait: timed %lld, rendered %lld", timed, rendered);
    ob_destroy_renderer(r);
}

/* Shadow maps kept from the first frame: "shadow" in that frame's timings, absent afterwards, and
 * each frame's sum within its own wall-clock time. */
static void test_present_passes(ob_context *ctx, const ob_settings *base)
{
    ob_settings s = *base;
    s.shadow.reuse = true;
    ob_renderer *r = ob_make_renderer(ctx, &(ob_renderer_desc){.width = W, .height = H});
    CHECK(r && ob_renderer_set_scene(r, scene) == OB_OK, "renderer");
    if (!r) return;
    for (int f = 0; f < 3; ++f) {
        const double t0 = now_ms();
        CHECK(ob_render_frame(r, &cam, &s) == OB_OK && ob_wait_timings(r) == OB_OK, "frame %d", f);
        const double wall = now_ms() - t0;
        ob_pass_timing t[MAXP];
        int n = ob_query_timings(r, t, MAXP);
        long long timed = -1;
        ob_query_timings_frame(r, &timed, NULL);
        CHECK(timed == f, "frame %d timed as %lld", f, timed);
        check_set(t, n, f == 0 ? "first frame" : "cached-shadow frame");
        CHECK(find(t, n, "shadow") == (f == 0), "frame %d: shadow %s", f, f == 0 ? "rendered" : "cached, absent");
        /* The passes run one after another between the call and the wait's return: their sum
         * cannot exceed that span (5 % and 1 ms for the two clocks' rounding). */
        double sum = 0.0, cpu = 0.0;
        for (int i = 0; i < n; ++i) sum += t[i].ms, cpu += t[i].cpu_ms;
        CHECK(sum <= 1.05 * wall + 1.0, "frame %d: passes %.3f ms in a %.3f ms frame", f, sum, wall);
        /* The CPU times are spans of the same call on the same clock: within it with no rounding. */
        CHECK(cpu <= wall, "frame %d: passes issued in %.3f ms of CPU in a %.3f ms frame", f, cpu, wall);
    }
    ob_destroy_renderer(r);
}

/* The internal set: a frame with no pass reports none, and a slot reused before it was read is
 * read then (the GPU a whole ring behind), so the numbering never skips backwards. */
static void test_timer_set(void)
{
    ob_timer_set t;
    ob_timers_init(&t);
    CHECK(t.frame == -1 && t.count == 0, "fresh set: frame %lld, %d passes", t.frame, t.count);
    ob_timers_frame_begin(&t);
    ob_timers_frame_end(&t);
    ob_timers_wait(&t);
    CHECK(t.frame == 0 && t.count == 0, "an empty frame: frame %lld, %d passes", t.frame, t.count);
    for (int f = 1; f <= 2 * OB_TIMER_RING; ++f) {
        ob_timers_frame_begin(&t);
        ob_timer_begin(&t, "a");
        ob_timer_begin(&t, "b");
        ob_timers_frame_end(&t);
        CHECK(t.frame <= f && t.frame >= f - OB_TIMER_RING, "frame %d reports frame %lld", f, t.frame);
    }
    ob_timers_wait(&t);
    CHECK(t.frame == 2 * OB_TIMER_RING && t.count == 2 && !strcmp(t.names[0], "a") && !strcmp(t.names[1], "b"),
          "after the wait: frame %lld, %d passes", t.frame, t.count);
    ob_timers_destroy(&t);
}

/* A compute pass that keeps the device busy for a while: every invocation a long dependent chain
 * of arithmetic, its result stored so that nothing is optimised away. */
static GLuint busy_program(void)
{
    static const char *const src = "#version 450 core\n"
                                   "layout(local_size_x = 64) in;\n"
                                   "layout(std430, binding = 0) buffer Out { float v[]; };\n"
                                   "uniform int steps;\n"
                                   "void main() {\n"
                                   "    float x = float(gl_GlobalInvocationID.x);\n"
                                   "    for (int i = 0; i < steps; ++i) x = fract(x * 1.0001 + 0.37);\n"
                                   "    v[gl_GlobalInvocationID.x] = x;\n"
                                   "}\n";
    GLuint p = glCreateShaderProgramv(GL_COMPUTE_SHADER, 1, &src);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        glDeleteProgram(p);
        return 0;
    }
    return p;
}

/* The timers with a framebuffer that has a size bound, as a window's is whenever obscura view
 * renders (in a surfaceless context, framebuffer 0 has none). Mesa's llvmpipe then takes a
 * timestamp only when its rasteriser runs the tile bins, at the next flush, while a compute
 * dispatch runs at once: the pass after a stamp ran before the stamp was taken, and the frame's
 * last pass, whose two stamps were both taken at the flush after it, read 0.000 ms (tonemap in the
 * viewer). Each pass's time must cover its own dispatch: on llvmpipe the dispatch call returns
 * when the work is done, so its wall time is the work's. */
static void test_sized_framebuffer(bool software)
{
    GLuint prog = busy_program();
    CHECK(prog != 0, "the busy compute program links");
    if (!prog) return;
    GLuint out = 0, tex = 0, fbo = 0;
    glCreateBuffers(1, &out);
    glNamedBufferData(out, 4096 * sizeof(float), NULL, GL_DYNAMIC_COPY);
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, GL_RGBA8, 512, 512);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, tex, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, 512, 512);
    glClearColor(0.2f, 0.3f, 0.4f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT); /* the driver now draws into it, as into a window after a present */
    glUseProgram(prog);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, out);
    glUniform1i(glGetUniformLocation(prog, "steps"), 20000);
    static const char *const names[] = {"first", "second", "last"};
    double wall[3] = {0.0, 0.0, 0.0};
    ob_timer_set t;
    ob_timers_init(&t);
    ob_timers_frame_begin(&t);
    for (int i = 0; i < 3; ++i) {
        ob_timer_begin(&t, names[i]);
        const double t0 = now_ms();
        glDispatchCompute(4096 / 64, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT); /* as every pass of the frame ends */
        wall[i] = now_ms() - t0;
    }
    ob_timers_frame_end(&t);
    ob_timers_wait(&t);
    CHECK(t.count == 3, "three passes timed, got %d", t.count);
    for (int i = 0; i < t.count && i < 3; ++i) {
        /* A GPU returns from the dispatch at once (wall ~0): only a wall time long enough to be the
         * work itself says what the pass must at least read. */
        const double least = wall[i] >= 2.0 ? 0.5 * wall[i] : 0.0;
        CHECK(t.ms[i] > 0.0 && t.ms[i] >= least, "framebuffer with a size bound: %s reads %.3f ms, its dispatch "
              "took %.3f ms of wall time", t.names[i], t.ms[i], wall[i]);
        /* The CPU time is the issuing of the dispatch and its barrier: within their wall time, and on a
         * software rasteriser, which runs the dispatch in the call, most of it. */
        CHECK(t.cpu_ms[i] > 0.0 && t.cpu_ms[i] <= wall[i] + 0.05 && (!software || t.cpu_ms[i] >= 0.5 * wall[i]),
              "%s: %.3f ms of CPU to issue a dispatch of %.3f ms wall time (%s)", t.names[i], t.cpu_ms[i], wall[i],
              software ? "software" : "GPU");
    }
    ob_timers_destroy(&t);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glUseProgram(0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(1, &tex);
    glDeleteBuffers(1, &out);
    glDeleteProgram(prog);
}

int main(void)
{
    CHECK(ob_wait_timings(NULL) == OB_ERR_INVALID_ARGUMENT, "ob_wait_timings(NULL) refused");
    ob_clear_error();
    ob_context *ctx = check_context();
    if (!ctx) return 1;
    scene = ob_load_scene(&(ob_scene_desc){.name = "cornell"});
    CHECK(scene != NULL, "cornell loads");
    if (!scene) return check_finish("test_timers");
    CHECK(ob_find_camera(scene, "front", &cam) == OB_OK, "camera front");
    ob_settings s;
    ob_settings_init(&s, "ssao");
    test_timer_set();
    test_ring(ctx, &s);
    test_present_passes(ctx, &s);
    test_sized_framebuffer(ob_query_is_software(ctx));
    ob_destroy_scene(scene);
    ob_destroy_context(ctx);
    return check_finish("test_timers");
}
