/* obscura view's per-pass profiler (seed 000 Figure 5.1: current, average, minimum, maximum and
 * calls per pass): the renderer's GPU timings and the wall-clock frame time, gathered every frame
 * and shown as a table in the panel. */
#include <math.h>
#include <string.h>

#include "view.h"
#include "view_gui.h"

void profiler_reset(profiler *p) { memset(p, 0, sizeof *p); }

void profiler_add(profiler *p, const ob_pass_timing *t, int n, double frame_ms)
{
    for (int i = 0; i < n; ++i) {
        pass_stats *s = NULL;
        for (int k = 0; k < p->count && !s; ++k)
            if (!strcmp(p->pass[k].name, t[i].name)) s = &p->pass[k];
        if (!s && p->count < MAX_PASSES) {
            s = &p->pass[p->count++];
            *s = (pass_stats){.name = t[i].name, .min = INFINITY};
        }
        if (!s) continue;
        s->current = t[i].ms;
        s->sum += t[i].ms;
        s->min = t[i].ms < s->min ? t[i].ms : s->min;
        s->max = t[i].ms > s->max ? t[i].ms : s->max;
        ++s->calls;
    }
    if (p->frames == 0) p->frame_min = INFINITY;
    p->frame_sum += frame_ms;
    p->frame_min = frame_ms < p->frame_min ? frame_ms : p->frame_min;
    p->frame_max = frame_ms > p->frame_max ? frame_ms : p->frame_max;
    ++p->frames;
}

void panel_profiler(viewer *v)
{
    const profiler *p = &v->prof;
    gui_text("%.1f FPS, %.2f ms per frame (wall clock)", v->fps, v->last_frame_ms);
    static const char *const headers[] = {"pass", "current", "average", "min", "max", "calls"};
    if (gui_begin_table("passes", 6, headers)) {
        double total = 0.0;
        for (int i = 0; i < p->count; ++i) {
            const pass_stats *s = &p->pass[i];
            if (s->calls == 0) continue;
            gui_table_row();
            gui_table_cell("%s", s->name);
            gui_table_cell("%.3f", s->current);
            gui_table_cell("%.3f", s->sum / (double)s->calls);
            gui_table_cell("%.3f", s->min);
            gui_table_cell("%.3f", s->max);
            gui_table_cell("%ld", s->calls);
            total += s->sum / (double)s->calls;
        }
        if (p->frames > 0) {
            gui_table_row();
            gui_table_cell("GPU sum");
            gui_table_cell(" ");
            gui_table_cell("%.3f", total);
            gui_table_cell(" ");
            gui_table_cell(" ");
            gui_table_cell(" ");
            gui_table_row();
            gui_table_cell("frame");
            gui_table_cell("%.3f", v->last_frame_ms);
            gui_table_cell("%.3f", p->frame_sum / (double)p->frames);
            gui_table_cell("%.3f", p->frame_min);
            gui_table_cell("%.3f", p->frame_max);
            gui_table_cell("%ld", p->frames);
        }
        gui_end_table();
    }
    if (gui_button("reset")) profiler_reset(&v->prof);
    gui_tooltip("statistics since the last reset (a change of method, filter or size also resets)");
}
