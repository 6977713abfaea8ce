/* obscura view's per-pass profiler (Belonogov 2018 Figure 5.1: current, average, minimum, maximum and
 * calls per pass): the renderer's GPU timings and the wall-clock frame time, gathered every frame
 * and shown as a table in the panel. */
#include <math.h>
#include <string.h>

#include "view.h"
#include "view_gui.h"

void profiler_reset(profiler *p)
{
    memset(p, 0, sizeof *p);
    p->gpu_frame = -1;
    p->first_frame = -1;
}

/* Why per timed frame and not per call: the renderer's timings arrive a few frames late (a ring of
 * queries, never a stall), so the same frame is reported until a newer one lands (counting it twice
 * would weigh it twice), and the frames just before a reset (a change of method) still arrive after
 * it. The first frame after a reset is left out too: it pays for the new shaders' compiles. */
bool profiler_add_frame(profiler *p, const ob_pass_timing *t, int n, long long timed, long long rendered,
                        double frame_ms)
{
    if (p->first_frame < 0) p->first_frame = rendered + 1;
    if (frame_ms > 0.0) {
        if (p->frames == 0) p->frame_min = INFINITY;
        p->frame_sum += frame_ms;
        p->frame_min = frame_ms < p->frame_min ? frame_ms : p->frame_min;
        p->frame_max = frame_ms > p->frame_max ? frame_ms : p->frame_max;
        ++p->frames;
    }
    if (timed < p->first_frame || timed == p->gpu_frame) return false;
    p->gpu_frame = timed;
    for (int k = 0; k < p->count; ++k) p->pass[k].current = NAN;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        pass_stats *s = NULL;
        for (int k = 0; k < p->count && !s; ++k)
            if (!strcmp(p->pass[k].name, t[i].name)) s = &p->pass[k];
        if (!s && p->count < MAX_PASSES) {
            s = &p->pass[p->count++];
            *s = (pass_stats){.name = t[i].name, .min = INFINITY};
        }
        sum += t[i].ms;
        if (!s) continue;
        s->current = t[i].ms;
        s->sum += t[i].ms;
        s->min = t[i].ms < s->min ? t[i].ms : s->min;
        s->max = t[i].ms > s->max ? t[i].ms : s->max;
        ++s->calls;
    }
    if (p->gpu_frames == 0) p->gpu_min = INFINITY;
    p->gpu_current = sum;
    p->gpu_sum += sum;
    p->gpu_min = sum < p->gpu_min ? sum : p->gpu_min;
    p->gpu_max = sum > p->gpu_max ? sum : p->gpu_max;
    ++p->gpu_frames;
    return true;
}

void profiler_add_eyes(profiler *p, const double eye_ms[2])
{
    const double both = eye_ms[0] + eye_ms[1];
    for (int e = 0; e < 2; ++e) {
        p->eye_current[e] = eye_ms[e];
        p->eye_sum[e] += eye_ms[e];
    }
    p->stereo_max = both > p->stereo_max ? both : p->stereo_max;
    if (both > VIEW_VR_BUDGET_MS) ++p->over_budget;
    ++p->stereo_frames;
}

/* The stereo frame (Belonogov 2018 §5.2): both eyes' GPU time against the headset's 11.1 ms at 90 Hz. */
static void panel_stereo(const viewer *v)
{
    const profiler *p = &v->prof;
    if (v->stereo == VIEW_MONO || p->stereo_frames == 0) return;
    const double n = (double)p->stereo_frames;
    const double left = p->eye_sum[0] / n, right = p->eye_sum[1] / n, both = left + right;
    const bool within = both <= VIEW_VR_BUDGET_MS;
    gui_text("stereo (%s), GPU ms, average of %ld frames:", view_stereo_names[v->stereo], p->stereo_frames);
    gui_text("  left %.3f + right %.3f = both %.3f (now %.3f)", left, right, both, p->eye_current[0] + p->eye_current[1]);
    gui_text_colored(within ? 0.4f : 1.0f, within ? 1.0f : 0.4f, 0.4f, "  %s the %.1f ms budget (90 Hz): %.0f %% of it; "
                     "over in %ld frames", within ? "within" : "over", VIEW_VR_BUDGET_MS, 100.0 * both / VIEW_VR_BUDGET_MS,
                     p->over_budget);
    gui_tooltip("Belonogov 2018 §5.2: the HTC Vive refreshes at 90 Hz, so both eyes must render in 11.1 ms; the pass rows "
                "below are both eyes summed");
}

void panel_profiler(viewer *v)
{
    const profiler *p = &v->prof;
    gui_text("%.1f FPS, %.2f ms per frame (wall clock)", v->fps, v->last_frame_ms);
    panel_stereo(v);
    static const char *const headers[] = {"pass", "current", "average", "min", "max", "calls"};
    if (gui_begin_table("passes", 6, headers)) {
        /* average and calls per pass: over the timed frames it ran in (a pass that ran once, like
         * shadow maps then cached, is one call); GPU sum: each timed frame's passes added up. */
        for (int i = 0; i < p->count; ++i) {
            const pass_stats *s = &p->pass[i];
            if (s->calls == 0) continue;
            gui_table_row();
            gui_table_cell("%s", s->name);
            if (isnan(s->current)) gui_table_cell("-");
            else gui_table_cell("%.3f", s->current);
            gui_table_cell("%.3f", s->sum / (double)s->calls);
            gui_table_cell("%.3f", s->min);
            gui_table_cell("%.3f", s->max);
            gui_table_cell("%ld", s->calls);
        }
        if (p->gpu_frames > 0) {
            gui_table_row();
            gui_table_cell("GPU sum");
            gui_table_cell("%.3f", p->gpu_current);
            gui_table_cell("%.3f", p->gpu_sum / (double)p->gpu_frames);
            gui_table_cell("%.3f", p->gpu_min);
            gui_table_cell("%.3f", p->gpu_max);
            gui_table_cell("%ld", p->gpu_frames);
        }
        if (p->frames > 0) {
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
    gui_tooltip("statistics since the last reset (a change of method, filter or size also resets); GPU times arrive "
                "a few frames late (never a stall), 'calls' counts the timed frames a pass ran in, '-' a pass that "
                "did not run in the newest one");
}
