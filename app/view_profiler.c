/* obscura view's per-pass profiler (Belonogov 2018 Figure 5.1: current, average, minimum, maximum and
 * calls per pass, and, as its profiler's CPU tab, the processor's time beside the graphics card's):
 * the renderer's GPU and CPU timings and the wall-clock frame time, gathered every frame and shown
 * as a table in the panel. */
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

static void time_reset(time_stats *t) { *t = (time_stats){.current = NAN, .min = INFINITY}; }

static void time_add(time_stats *t, double ms)
{
    t->current = ms;
    t->sum += ms;
    t->min = ms < t->min ? ms : t->min;
    t->max = ms > t->max ? ms : t->max;
}

/* Why per timed frame and not per call: the renderer's timings arrive a few frames late (a ring of
 * queries, never a stall), so the same frame is reported until a newer one lands (counting it twice
 * would weigh it twice), and the frames just before a reset (a change of method) still arrive after
 * it. The first frame after a reset is left out too: it pays for the new shaders' compiles. The CPU
 * times come with the GPU times of the same frame, so both describe one frame. */
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
    for (int k = 0; k < p->count; ++k) p->pass[k].gpu.current = p->pass[k].cpu.current = NAN;
    double gpu = 0.0, cpu = 0.0;
    for (int i = 0; i < n; ++i) {
        pass_stats *s = NULL;
        for (int k = 0; k < p->count && !s; ++k)
            if (!strcmp(p->pass[k].name, t[i].name)) s = &p->pass[k];
        if (!s && p->count < MAX_PASSES) {
            s = &p->pass[p->count++];
            *s = (pass_stats){.name = t[i].name};
            time_reset(&s->gpu);
            time_reset(&s->cpu);
        }
        gpu += t[i].ms;
        cpu += t[i].cpu_ms;
        if (!s) continue;
        time_add(&s->gpu, t[i].ms);
        time_add(&s->cpu, t[i].cpu_ms);
        ++s->calls;
    }
    if (p->gpu_frames == 0) {
        time_reset(&p->gpu);
        time_reset(&p->cpu);
    }
    time_add(&p->gpu, gpu);
    time_add(&p->cpu, cpu);
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
    /* Short lines: the panel's column is about 40 characters wide at 1024 px. */
    gui_text("stereo (%s), GPU ms, average of %ld frames:", view_stereo_names[v->stereo], p->stereo_frames);
    gui_text("  left %.3f + right %.3f", left, right);
    gui_text("  = both %.3f (now %.3f)", both, p->eye_current[0] + p->eye_current[1]);
    gui_text_colored(within ? 0.4f : 1.0f, within ? 1.0f : 0.4f, 0.4f, "  %s the %.1f ms budget (90 Hz): %.0f %%",
                     within ? "within" : "over", VIEW_VR_BUDGET_MS, 100.0 * both / VIEW_VR_BUDGET_MS);
    gui_text_colored(within ? 0.4f : 1.0f, within ? 1.0f : 0.4f, 0.4f, "  over it in %ld of the frames", p->over_budget);
    gui_tooltip("Belonogov 2018 §5.2: the HTC Vive refreshes at 90 Hz, so both eyes must render in 11.1 ms; the pass rows "
                "below are both eyes summed");
}

/* The table's columns: each statistic as a GPU | CPU pair, side by side, the average first (the
 * metric Belonogov 2018 §5.1 evaluates with). Narrower than the panel, the pass column stays while
 * the others scroll sideways (view_gui.h); the headers are short and say the rest when hovered. */
enum { PROFILER_COLUMNS = 10 };
#define GPU_TINT {0.55f, 0.95f, 0.55f}
#define CPU_TINT {0.55f, 0.8f, 1.0f}
static const gui_column profiler_columns[PROFILER_COLUMNS] = {
    {"pass", "the passes, in the order they ran; sum: each timed frame's passes added up (what the GPU spent on "
             "the frame, and the CPU issuing it); frame: the wall clock from one frame to the next, in the CPU "
             "columns", {0}},
    {"GPU avg", "average GPU time, ms, over the timed frames the pass ran in: GL timestamp queries around the "
                "pass, read a few frames late (never a stall)", GPU_TINT},
    {"CPU avg", "average CPU time, ms: the viewer's thread issuing the pass (a monotonic clock around its "
                "calls). On a GPU mostly the driver's cost; llvmpipe runs compute work in the call, so there "
                "it is close to the GPU time", CPU_TINT},
    {"GPU now", "GPU time in the newest timed frame, ms ('-': the pass did not run in it)", GPU_TINT},
    {"CPU now", "CPU time in the newest timed frame, ms", CPU_TINT},
    {"GPU min", "shortest GPU time since the last reset, ms", GPU_TINT},
    {"CPU min", "shortest CPU time since the last reset, ms", CPU_TINT},
    {"GPU max", "longest GPU time since the last reset, ms", GPU_TINT},
    {"CPU max", "longest CPU time since the last reset, ms", CPU_TINT},
    {"calls", "timed frames the pass ran in since the last reset (shadow maps then cached: one)", {0}},
};

/* The four statistics of a GPU and a CPU time, paired as the columns are. */
static void time_cells(const time_stats *gpu, const time_stats *cpu, long count)
{
    const double n = count > 0 ? (double)count : 1.0;
    gui_table_cell("%.3f", gpu->sum / n);
    gui_table_cell("%.3f", cpu->sum / n);
    if (isnan(gpu->current)) gui_table_cell("-");
    else gui_table_cell("%.3f", gpu->current);
    if (isnan(cpu->current)) gui_table_cell("-");
    else gui_table_cell("%.3f", cpu->current);
    gui_table_cell("%.3f", gpu->min);
    gui_table_cell("%.3f", cpu->min);
    gui_table_cell("%.3f", gpu->max);
    gui_table_cell("%.3f", cpu->max);
}

void panel_profiler(viewer *v)
{
    const profiler *p = &v->prof;
    gui_text("%.1f FPS, %.2f ms per frame (wall clock)", v->fps, v->last_frame_ms);
    panel_stereo(v);
    int rows = (p->gpu_frames > 0 ? 1 : 0) + (p->frames > 0 ? 1 : 0);
    for (int i = 0; i < p->count; ++i) rows += p->pass[i].calls > 0;
    if (gui_begin_wide_table("passes", PROFILER_COLUMNS, profiler_columns, rows)) {
        /* average and calls per pass: over the timed frames it ran in (a pass that ran once, like
         * shadow maps then cached, is one call); the sums: each timed frame's passes added up. */
        for (int i = 0; i < p->count; ++i) {
            const pass_stats *s = &p->pass[i];
            if (s->calls == 0) continue;
            gui_table_row();
            gui_table_cell("%s", s->name);
            time_cells(&s->gpu, &s->cpu, s->calls);
            gui_table_cell("%ld", s->calls);
        }
        if (p->gpu_frames > 0) {
            gui_table_row();
            gui_table_cell("sum");
            time_cells(&p->gpu, &p->cpu, p->gpu_frames);
            gui_table_cell("%ld", p->gpu_frames);
        }
        if (p->frames > 0) {
            /* The wall clock is the CPU's: its cells are the CPU columns'. */
            const time_stats wall = {.current = v->last_frame_ms, .sum = p->frame_sum, .min = p->frame_min,
                                     .max = p->frame_max};
            gui_table_row();
            gui_table_cell("frame");
            gui_table_cell(" ");
            gui_table_cell("%.3f", wall.sum / (double)p->frames);
            gui_table_cell(" ");
            gui_table_cell("%.3f", wall.current);
            gui_table_cell(" ");
            gui_table_cell("%.3f", wall.min);
            gui_table_cell(" ");
            gui_table_cell("%.3f", wall.max);
            gui_table_cell("%ld", p->frames);
        }
        gui_end_table();
    }
    if (gui_button("reset")) profiler_reset(&v->prof);
    gui_tooltip("statistics since the last reset (a change of method, filter or size also resets); GPU times arrive "
                "a few frames late (never a stall), 'calls' counts the timed frames a pass ran in, '-' a pass that "
                "did not run in the newest one; hover a column's header for what it measures");
}
