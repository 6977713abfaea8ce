/* Per-pass GPU time from GL_TIMESTAMP queries taken before and after each pass, kept in a ring of
 * OB_TIMER_RING frames and read a few frames late, and beside it the CPU time spent issuing the
 * pass (CLOCK_MONOTONIC between the two stamps, the stamps themselves left out): what the driver
 * costs the host's thread, which a GPU-bound frame hides and a CPU-bound one is made of.
 *
 * Why not GL_TIME_ELAPSED: Mesa's llvmpipe (22.3) records TIME_ELAPSED only for work that goes
 * through its rasteriser, so compute passes read 0 ms and a span that starts with a draw reads
 * garbage; timestamps bracket compute dispatches correctly there (a 566 ms dispatch read 566 ms)
 * and are equally exact on NVIDIA. Timestamps are also nestable-free: passes stay sequential.
 *
 * Why a ring: reading a query's result before the GPU has reached it makes the CPU wait for the
 * whole frame (the GPU then idles while the CPU records the next one). Each frame records into
 * its own slot, and a slot is read only once GL_QUERY_RESULT_AVAILABLE says all its queries have
 * landed; the newest such frame is what the renderer reports. A slot is waited for only when the
 * CPU comes round to it again with its results still out, that is with the GPU OB_TIMER_RING
 * frames behind, where a wait costs nothing that the driver's own frame queue would not.
 *
 * Why a glFinish after each timestamp on a software rasteriser: llvmpipe takes a timestamp when
 * its rasteriser threads run the current tile bins, that is at the next flush, whenever the
 * framebuffer it last drew into has a size, while a compute dispatch runs at once on the calling
 * thread. A stamp before a pass was then taken after the pass had run (at the barrier that ends
 * it), so every pass read its successor's time, work drawn earlier (the G-buffer's rasterisation)
 * landed in the next pass, and the frame's last pass, tonemap, whose two stamps were both taken at
 * the flush after it, read 0.000 ms. That is the case in obscura view and in any host that renders
 * to a window (framebuffer 0 has a size there); in a surfaceless EGL context (obscura render, the
 * tests) framebuffer 0 has none and llvmpipe takes the stamp at the call, which hid it. Finishing
 * after the stamp takes it where it stands. On a GPU, stamps are taken in command order and a
 * finish would stall it: the finish is for software rasterisers only, where the dispatches already
 * run on the CPU in order and it costs about a tenth of a millisecond per stamp. */
#include <string.h>
#include <time.h>

#include "gpu/gpu.h"

static double now_ms(void)
{
    struct timespec ts = {0, 0};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return 1e3 * (double)ts.tv_sec + 1e-6 * (double)ts.tv_nsec;
}

/* A timestamp into query q, taken in command order on every driver (see above). */
static void stamp(const ob_timer_set *t, GLuint q)
{
    glQueryCounter(q, GL_TIMESTAMP);
    if (t->finish_stamps) glFinish();
}

void ob_timers_init(ob_timer_set *t)
{
    memset(t, 0, sizeof *t);
    t->finish_stamps = ob_renderer_is_software((const char *)glGetString(GL_RENDERER));
    for (int s = 0; s < OB_TIMER_RING; ++s) {
        glCreateQueries(GL_TIMESTAMP, 2 * OB_MAX_TIMED_PASSES, t->ring[s].queries);
        t->ring[s].frame = -1;
    }
    t->open = -1;
    t->frame = -1;
}

void ob_timers_destroy(ob_timer_set *t)
{
    for (int s = 0; s < OB_TIMER_RING; ++s)
        if (t->ring[s].queries[0]) glDeleteQueries(2 * OB_MAX_TIMED_PASSES, t->ring[s].queries);
    memset(t, 0, sizeof *t);
    t->open = -1;
    t->frame = -1;
}

static bool slot_available(const ob_timer_frame *f)
{
    /* Every query, not only the last: the spec orders nothing between query objects. */
    for (int i = 0; i < 2 * f->count; ++i) {
        GLuint ready = GL_FALSE;
        glGetQueryObjectuiv(f->queries[i], GL_QUERY_RESULT_AVAILABLE, &ready);
        if (!ready) return false;
    }
    return true;
}

/* Read a finished slot (waiting for it when `wait`) and report it if it is the newest so far. */
static void collect_unguarded(ob_timer_set *t, ob_timer_frame *f, bool wait);

/* A query buffer bound by a host would take the results at the pointers' values as offsets: it is
 * unbound for the reads and put back. */
static void collect(ob_timer_set *t, ob_timer_frame *f, bool wait)
{
    if (!f->pending) return;
    GLint query_buffer = 0;
    glGetIntegerv(GL_QUERY_BUFFER_BINDING, &query_buffer);
    if (query_buffer) glBindBuffer(GL_QUERY_BUFFER, 0);
    collect_unguarded(t, f, wait);
    if (query_buffer) glBindBuffer(GL_QUERY_BUFFER, (GLuint)query_buffer);
}

static void collect_unguarded(ob_timer_set *t, ob_timer_frame *f, bool wait)
{
    if (!f->pending || (!wait && !slot_available(f))) return;
    f->pending = false;
    if (f->frame < t->frame) return;
    t->frame = f->frame;
    t->count = f->count;
    for (int i = 0; i < f->count; ++i) {
        GLuint64 t0 = 0, t1 = 0;
        glGetQueryObjectui64v(f->queries[2 * i], GL_QUERY_RESULT, &t0);
        glGetQueryObjectui64v(f->queries[2 * i + 1], GL_QUERY_RESULT, &t1);
        t->names[i] = f->names[i];
        t->ms[i] = t1 > t0 ? (double)(t1 - t0) * 1e-6 : 0.0;
        t->cpu_ms[i] = f->cpu_ms[i];
    }
}

/* Every slot with results out, oldest frame first, so the newest finished one is reported last. */
static void collect_all(ob_timer_set *t, bool wait)
{
    for (long long k = t->frames - OB_TIMER_RING; k < t->frames; ++k) {
        if (k < 0) continue;
        ob_timer_frame *f = &t->ring[k % OB_TIMER_RING];
        if (f->frame == k) collect(t, f, wait);
    }
}

void ob_timers_frame_begin(ob_timer_set *t)
{
    if (t->open >= 0) ob_timer_end(t);
    ob_timer_frame *f = &t->ring[t->frames % OB_TIMER_RING];
    collect(t, f, true); /* the GPU is a whole ring behind: its results are due anyway */
    f->frame = t->frames++;
    f->count = 0;
    f->pending = false;
    t->current = f;
    t->open = -1;
}

void ob_timer_begin(ob_timer_set *t, const char *name)
{
    ob_timer_frame *f = t->current;
    if (!f) return;
    if (t->open >= 0) ob_timer_end(t);
    if (f->count >= OB_MAX_TIMED_PASSES) return;
    f->names[f->count] = name;
    f->cpu_ms[f->count] = 0.0;
    t->open = f->count++;
    stamp(t, f->queries[2 * t->open]);
    f->cpu_start = now_ms(); /* after the stamp: a software rasteriser's finish is not the pass's */
}

void ob_timer_end(ob_timer_set *t)
{
    if (t->open < 0 || !t->current) return;
    t->current->cpu_ms[t->open] = now_ms() - t->current->cpu_start;
    stamp(t, t->current->queries[2 * t->open + 1]);
    t->open = -1;
}

void ob_timers_frame_end(ob_timer_set *t)
{
    if (!t->current) return;
    ob_timer_end(t);
    t->current->pending = true;
    t->current = NULL;
    collect_all(t, false);
}

void ob_timers_wait(ob_timer_set *t)
{
    if (t->current) ob_timers_frame_end(t);
    collect_all(t, true);
}
