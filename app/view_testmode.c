/* obscura view --test-mode (Puri 2024 §3.5): every camera preset x every method, each slot timed
 * for --seconds and repeated --cycles times: a table on stdout (a camera's row as soon as its last
 * cycle is measured), progress on stderr (base/progress.h), then a CSV log (one row per camera x
 * method: GPU ms per pass in frame order, the stereo columns, then CPU ms per pass) and one
 * screenshot per slot. The window is all picture: test mode shows no panel (view_layout). */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "progress.h"
#include "view.h"
#include "view_gui.h"

/* The passes the renderer can time, in frame order (temporal where it runs by default, before the
 * filter): the CSV's columns, GPU times and then CPU times. */
static const char *const pass_order[] = {"shadow",     "gbuffer",    "lighting",    "extra_view", "second_layer",
                                         "downsample", "edges",      "depth_mips",  "second_back", "ao",
                                         "temporal",   "filter",     "upsample",    "compose",    "luminance",
                                         "bloom",      "tonemap"};
enum { PASS_ORDER_COUNT = sizeof pass_order / sizeof pass_order[0] };

typedef struct test_cell {
    double fps[MAX_CYCLES];
    long frames;
    double seconds;
    double pass_ms[PASS_ORDER_COUNT];  /* GPU: sums over every measured frame */
    double pass_cpu[PASS_ORDER_COUNT]; /* CPU issuing it: the same */
    long pass_calls[PASS_ORDER_COUNT];
    double eye_ms[2];                  /* stereo: each eye's GPU sum of passes, summed over frames */
    long eye_frames;
} test_cell;

typedef struct test_run {
    int methods[MAX_METHODS];
    int method_count, camera_count;
    int cycle, camera, method;      /* the slot being measured */
    bool warmed;                    /* the slot's first frame (shader compiles, first use) is done */
    long long first_timed;          /* the slot's first frame whose timings count (after the warm one) */
    long long last_timed;           /* the last frame whose timings were counted */
    double slot_start;
    long slot_frames;
    test_cell *cells;               /* camera_count x method_count */
    char dir[4096];                 /* screenshots go here */
    bool done;
    ob_progress bar;                /* one unit per slot, on stderr */
} test_run;

static int pass_column(const char *name)
{
    for (int i = 0; i < PASS_ORDER_COUNT; ++i)
        if (!strcmp(pass_order[i], name)) return i;
    return -1;
}

static void safe_name(const char *in, char *out, size_t len)
{
    size_t n = 0;
    for (; *in && n + 1 < len; ++in)
        out[n++] = (isalnum((unsigned char)*in) || *in == '-' || *in == '_') ? *in : '_';
    out[n] = '\0';
}

static void test_apply_slot(viewer *v)
{
    test_run *t = v->test;
    use_camera(v, t->camera);
    if (v->s.method != t->methods[t->method]) select_method(v, t->methods[t->method]);
    t->warmed = false;
    t->slot_frames = 0;
}

/* The summary and the CSV, written when every slot is done (atomically: an aborted run leaves
 * no log). */
int test_finish(viewer *v)
{
    test_run *t = v->test;
    ob_progress_end(&t->bar);
    if (!t->done) return cli_fail(EXIT_RUNTIME, "test mode stopped before the end: no log written");
    size_t cap = 4096 + (size_t)t->camera_count * (size_t)t->method_count * 1024;
    char *csv = malloc(cap);
    if (!csv) return cli_fail(EXIT_RUNTIME, "out of memory writing the log");
    size_t n = 0;
    n += (size_t)snprintf(csv + n, cap - n, "scene,camera,method,width,height,cycles,frames,seconds,fps,fps_min,fps_max,frame_ms");
    for (int p = 0; p < PASS_ORDER_COUNT; ++p) n += (size_t)snprintf(csv + n, cap - n, ",%s_ms", pass_order[p]);
    /* Stereo (Belonogov 2018 §5.2): the pass columns above are both eyes summed; these are each eye's
     * GPU sum, both, and whether both fit the 11.1 ms of 90 Hz (empty in mono). */
    n += (size_t)snprintf(csv + n, cap - n, ",stereo,left_gpu_ms,right_gpu_ms,stereo_gpu_ms,within_90hz");
    /* Each pass's CPU time, the viewer's thread issuing it (the processor's tab of the profiler in
     * Belonogov 2018, Fig. 5.1), in the same order. */
    for (int p = 0; p < PASS_ORDER_COUNT; ++p) n += (size_t)snprintf(csv + n, cap - n, ",%s_cpu_ms", pass_order[p]);
    n += (size_t)snprintf(csv + n, cap - n, "\n");
    /* The table's rows went to stdout as each camera finished (print_row). */
    for (int c = 0; c < t->camera_count; ++c) {
        ob_camera cam = ob_query_camera(v->scene, c);
        for (int m = 0; m < t->method_count; ++m) {
            const test_cell *cell = &t->cells[(size_t)c * (size_t)t->method_count + (size_t)m];
            double lo = INFINITY, hi = 0.0;
            for (int k = 0; k < v->o.cycles; ++k) {
                lo = cell->fps[k] < lo ? cell->fps[k] : lo;
                hi = cell->fps[k] > hi ? cell->fps[k] : hi;
            }
            double fps = cell->seconds > 0.0 ? (double)cell->frames / cell->seconds : 0.0;
            n += (size_t)snprintf(csv + n, cap - n, "%s,%s,%s,%d,%d,%d,%ld,%.4f,%.3f,%.3f,%.3f,%.3f",
                                  ob_query_scene_name(v->scene), cam.name, ob_method_at(t->methods[m])->name,
                                  v->pic_w, v->pic_h, v->o.cycles, cell->frames, cell->seconds, fps, lo, hi,
                                  cell->frames > 0 ? 1000.0 * cell->seconds / (double)cell->frames : 0.0);
            for (int p = 0; p < PASS_ORDER_COUNT; ++p) {
                if (cell->pass_calls[p] > 0)
                    n += (size_t)snprintf(csv + n, cap - n, ",%.4f", cell->pass_ms[p] / (double)cell->pass_calls[p]);
                else
                    n += (size_t)snprintf(csv + n, cap - n, ",");
            }
            if (cell->eye_frames > 0) {
                double l = cell->eye_ms[0] / (double)cell->eye_frames, r = cell->eye_ms[1] / (double)cell->eye_frames;
                n += (size_t)snprintf(csv + n, cap - n, ",%s,%.4f,%.4f,%.4f,%d", view_stereo_names[v->stereo], l, r,
                                      l + r, l + r <= VIEW_VR_BUDGET_MS);
            } else {
                n += (size_t)snprintf(csv + n, cap - n, ",mono,,,,");
            }
            for (int p = 0; p < PASS_ORDER_COUNT; ++p) {
                if (cell->pass_calls[p] > 0)
                    n += (size_t)snprintf(csv + n, cap - n, ",%.4f", cell->pass_cpu[p] / (double)cell->pass_calls[p]);
                else
                    n += (size_t)snprintf(csv + n, cap - n, ",");
            }
            n += (size_t)snprintf(csv + n, cap - n, "\n");
        }
    }
    int code = EXIT_OK;
    if (ob_write_text(v->o.log, csv) != OB_OK) code = cli_fail_library_as(EXIT_OUTPUT);
    else printf("log: %s; screenshots: %s/\n", v->o.log, t->dir);
    free(csv);
    return code;
}

/* The table's header on stdout, before the first slot: the rows follow as each camera finishes. */
static void print_header(const viewer *v)
{
    const test_run *t = v->test;
    printf("obscura view --test-mode: %s, %dx%d, %d cycle(s) of %.2f s per camera x method, %s\n",
           ob_query_scene_name(v->scene), v->pic_w, v->pic_h, v->o.cycles, (double)v->o.seconds,
           ob_query_renderer(v->ctx));
    if (v->stereo != VIEW_MONO)
        printf("stereo %s, %dx%d per eye: FPS (both eyes' GPU ms, * = over the 11.1 ms of 90 Hz)\n",
               view_stereo_names[v->stereo], v->eye_width, v->eye_height);
    printf("%-16s", "FPS");
    for (int m = 0; m < t->method_count; ++m) printf(" %12s", ob_method_at(t->methods[m])->name);
    printf("\n");
    fflush(stdout);
}

/* Camera c's row, once its last cycle is measured (average FPS over the cycles). */
static void print_row(viewer *v, int c)
{
    test_run *t = v->test;
    ob_progress_break(&t->bar);
    printf("%-16.16s", ob_query_camera(v->scene, c).name);
    for (int m = 0; m < t->method_count; ++m) {
        const test_cell *cell = &t->cells[(size_t)c * (size_t)t->method_count + (size_t)m];
        printf(" %12.2f", cell->seconds > 0.0 ? (double)cell->frames / cell->seconds : 0.0);
        if (cell->eye_frames > 0) {
            double l = cell->eye_ms[0] / (double)cell->eye_frames, r = cell->eye_ms[1] / (double)cell->eye_frames;
            printf(" (%.2f ms%s)", l + r, l + r <= VIEW_VR_BUDGET_MS ? "" : "*");
        }
    }
    printf("\n");
    fflush(stdout);
}

/* One timed frame's passes into the slot's cell, once per frame and only a frame of this slot: the
 * timings arrive a few frames late, so the first ones after a switch are the previous slot's. */
static void count_timings(viewer *v, test_cell *cell, bool wait)
{
    test_run *t = v->test;
    ob_pass_timing timings[MAX_PASSES];
    double eye_ms[2] = {0.0, 0.0};
    long long timed = -1, rendered = -1;
    int n = view_timings(v, wait, timings, eye_ms, &timed, &rendered);
    if (timed < t->first_timed || timed == t->last_timed) return;
    t->last_timed = timed;
    for (int i = 0; i < n; ++i) {
        int col = pass_column(timings[i].name);
        if (col < 0) continue;
        cell->pass_ms[col] += timings[i].ms;
        cell->pass_cpu[col] += timings[i].cpu_ms;
        ++cell->pass_calls[col];
    }
    if (v->stereo != VIEW_MONO) {
        cell->eye_ms[0] += eye_ms[0];
        cell->eye_ms[1] += eye_ms[1];
        ++cell->eye_frames;
    }
}

/* After each frame: count it into the slot, and move on when the slot's time is up. */
void test_step(viewer *v)
{
    test_run *t = v->test;
    double now = glfwGetTime();
    if (!t->warmed) {
        /* The slot's first frame pays for shader compiles and first-use allocations. */
        long long rendered = -1;
        ob_query_timings_frame(v->r, NULL, &rendered);
        t->warmed = true;
        t->slot_start = now;
        t->first_timed = rendered + 1;
        return;
    }
    test_cell *cell = &t->cells[(size_t)t->camera * (size_t)t->method_count + (size_t)t->method];
    ++t->slot_frames;
    double elapsed = now - t->slot_start;
    const bool last = elapsed >= (double)v->o.seconds;
    /* The slot's last frame waits for the GPU, so that even a short slot has its own timings (one
     * stall per slot, outside the measured time). */
    count_timings(v, cell, last);
    if (!last) return;
    cell->fps[t->cycle] = (double)t->slot_frames / elapsed;
    cell->frames += t->slot_frames;
    cell->seconds += elapsed;
    if (t->cycle == v->o.cycles - 1) {
        /* One screenshot per camera x method, of the image alone (the panel would hide it). */
        /* Stereo: the left eye's image. */
        size_t bytes = ob_image_size(v->r, OB_IMAGE_FINAL_RGBA8);
        unsigned char *px = malloc(bytes);
        char cam[80], path[4400];
        safe_name(ob_query_camera(v->scene, t->camera).name, cam, sizeof cam);
        snprintf(path, sizeof path, "%s/%s_%s_%s.png", t->dir, ob_query_scene_name(v->scene), cam,
                 ob_method_at(t->methods[t->method])->name);
        if (!px || ob_read_image(v->r, OB_IMAGE_FINAL_RGBA8, px, bytes) != OB_OK ||
            ob_write_png(path, v->eye_width, v->eye_height, 4, px) != OB_OK) {
            const char *msg = "";
            ob_get_error(&msg);
            fprintf(stderr, "obscura view: screenshot %s failed: %s\n", path, msg);
            v->exit_code = EXIT_OUTPUT;
            v->quit = true;
        }
        free(px);
    }
    char what[160];
    snprintf(what, sizeof what, "%.63s %.64s", ob_query_camera(v->scene, t->camera).name,
             ob_method_at(t->methods[t->method])->name);
    ob_progress_advance(&t->bar, 1, what);
    if (++t->method == t->method_count) {
        t->method = 0;
        if (t->cycle == v->o.cycles - 1) print_row(v, t->camera);
        if (++t->camera == t->camera_count) {
            t->camera = 0;
            if (++t->cycle == v->o.cycles) {
                t->done = true;
                v->quit = true;
                return;
            }
        }
    }
    test_apply_slot(v);
}

int test_init(viewer *v)
{
    test_run *t = calloc(1, sizeof *t);
    if (!t) return cli_fail(EXIT_RUNTIME, "out of memory");
    v->test = t;
    if (v->o.methods) {
        char list[1024];
        snprintf(list, sizeof list, "%s", v->o.methods);
        for (char *save = NULL, *tok = strtok_r(list, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
            int m = ob_find_method(tok);
            if (m < 0) return cli_fail(EXIT_USAGE, "--methods: unknown method '%s' (see obscura list)", tok);
            if (t->method_count >= MAX_METHODS) return cli_fail(EXIT_USAGE, "--methods: too many");
            t->methods[t->method_count++] = m;
        }
    } else {
        for (int m = 0; m < ob_method_count() && m < MAX_METHODS; ++m) t->methods[t->method_count++] = m;
    }
    if (t->method_count == 0) return cli_fail(EXIT_USAGE, "--methods: no method given");
    t->camera_count = ob_query_camera_count(v->scene);
    if (t->camera_count > MAX_CAMERAS) t->camera_count = MAX_CAMERAS;
    t->cells = calloc((size_t)t->camera_count * (size_t)t->method_count, sizeof *t->cells);
    if (!t->cells) return cli_fail(EXIT_RUNTIME, "out of memory");
    /* Screenshots beside the log, unless --shots says where. */
    if (v->o.shots) {
        snprintf(t->dir, sizeof t->dir, "%s", v->o.shots);
    } else {
        snprintf(t->dir, sizeof t->dir, "%s", v->o.log);
        char *slash = strrchr(t->dir, '/');
        if (slash) *slash = '\0';
        else snprintf(t->dir, sizeof t->dir, ".");
    }
    struct stat st;
    if (stat(t->dir, &st) != 0 || !S_ISDIR(st.st_mode))
        return cli_fail(EXIT_OUTPUT, "cannot write screenshots to %s: not a directory", t->dir);
    v->vsync = false; /* frame rates, not the display's refresh */
    print_header(v);
    ob_progress_begin(&t->bar, "test mode", (long long)v->o.cycles * t->camera_count * t->method_count);
    test_apply_slot(v);
    return 0;
}

void test_overlay(const viewer *v)
{
    const test_run *t = v->test;
    gui_text_colored(1.0f, 0.85f, 0.3f, "test mode: cycle %d/%d, camera %d/%d, method %d/%d", t->cycle + 1,
                     v->o.cycles, t->camera + 1, t->camera_count, t->method + 1, t->method_count);
}

void test_free(test_run *t)
{
    if (t) ob_progress_end(&t->bar);
    if (t) free(t->cells);
    free(t);
}
