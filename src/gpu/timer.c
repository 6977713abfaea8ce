/* Per-pass GPU time from GL_TIMESTAMP queries taken before and after each pass.
 *
 * Why not GL_TIME_ELAPSED: Mesa's llvmpipe (22.3) records TIME_ELAPSED only for work that goes
 * through its rasteriser, so compute passes read 0 ms and a span that starts with a draw reads
 * garbage; timestamps bracket compute dispatches correctly there (a 566 ms dispatch read 566 ms)
 * and are equally exact on NVIDIA. Timestamps are also nestable-free: passes stay sequential. */
#include <string.h>

#include "gpu/gpu.h"

void ob_timers_init(ob_timer_set *t)
{
    memset(t, 0, sizeof *t);
    glCreateQueries(GL_TIMESTAMP, 2 * OB_MAX_TIMED_PASSES, t->queries);
    t->open = -1;
}

void ob_timers_destroy(ob_timer_set *t)
{
    if (t->queries[0]) glDeleteQueries(2 * OB_MAX_TIMED_PASSES, t->queries);
    memset(t, 0, sizeof *t);
    t->open = -1;
}

void ob_timers_frame_begin(ob_timer_set *t)
{
    t->count = 0;
    t->open = -1;
}

void ob_timer_begin(ob_timer_set *t, const char *name)
{
    if (t->open >= 0) ob_timer_end(t);
    if (t->count >= OB_MAX_TIMED_PASSES) return;
    t->names[t->count] = name;
    t->open = t->count++;
    glQueryCounter(t->queries[2 * t->open], GL_TIMESTAMP);
}

void ob_timer_end(ob_timer_set *t)
{
    if (t->open < 0) return;
    glQueryCounter(t->queries[2 * t->open + 1], GL_TIMESTAMP);
    t->open = -1;
}

void ob_timers_frame_end(ob_timer_set *t)
{
    ob_timer_end(t);
    for (int i = 0; i < t->count; ++i) {
        GLuint64 t0 = 0, t1 = 0;
        glGetQueryObjectui64v(t->queries[2 * i], GL_QUERY_RESULT, &t0);
        glGetQueryObjectui64v(t->queries[2 * i + 1], GL_QUERY_RESULT, &t1);
        t->ms[i] = t1 > t0 ? (double)(t1 - t0) * 1e-6 : 0.0;
    }
}
