/* obscura view: the interactive viewer (seed 004 §2.7, §3.5; seed 000 §5.1's profiler).
 *
 * A GLFW window whose GL 4.5 context the library adopts (ob_context_desc.use_current), so every
 * frame goes through the very ob_render_frame the CLI and the tests use; ob_present blits the
 * result (or a debug view) into the window and Dear ImGui draws the panel over it. The panel is
 * generated from the method and filter registries' parameter tables, like `obscura list` and
 * `--set`.
 *
 * Three ways to drive it: a person (keys, mouse, panel), a script of timed input events
 * (--script, replayed on a simulated clock so it runs the same on any machine) and the automatic
 * test mode (--test-mode: every camera preset x every method, timed, logged to CSV with a
 * screenshot each). */
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "cli.h"
#include "view_gui.h"

enum { MAX_METHODS = 32, MAX_PASSES = 16, MAX_CAMERAS = 64, MAX_EVENTS = 4096, MAX_CYCLES = 100 };

/* The passes the renderer can time, in frame order: the CSV's columns. */
static const char *const pass_order[] = {"shadow", "gbuffer", "lighting", "downsample", "edges", "ao",
                                         "filter", "upsample", "compose", "luminance", "bloom", "tonemap"};
enum { PASS_ORDER_COUNT = sizeof pass_order / sizeof pass_order[0] };

static void view_usage(FILE *f)
{
    fputs("usage: obscura view [options]\n"
          "\n"
          "An interactive window: fly the camera, switch methods, tune every parameter live and\n"
          "watch the GPU time of each pass. Needs a display (on a server: xvfb-run -a obscura view).\n"
          "\n"
          "  --scene NAME|PATH     as for render (default fzk-haus)\n"
          "  --sidecar FILE        scene sidecar JSON; --up y|z the model's up axis\n"
          "  --camera NAME|INDEX   the preset to start from (default: the first)\n"
          "  --method NAME         the method to start with (default ssao)\n"
          "  --filter NAME         the filter to start with (default geometry)\n"
          "  --quality Q           low|medium|high|ultra, applied to each method picked\n"
          "  --set M.P=V           a parameter, validated (repeatable)\n"
          "  --ao-scale S          1, 0.5 or 0.25; --adaptive on|off\n"
          "  --shadow none|hard|pcf|vsm   --shadow-size N   --hdr on|off   --env FILE.hdr\n"
          "  --size WxH            the window's size (default 1280x720)\n"
          "  --vsync on|off        (default on; test mode turns it off)\n"
          "  --gui on|off          show the panel at start (default on)\n"
          "  --shots DIR           where screenshots go (default screenshots/; test mode: beside --log)\n"
          "  --script FILE         replay timed input events (see below), then keep running\n"
          "  --test-mode           cycle every camera preset x every method, then exit:\n"
          "    --seconds S         time per camera x method (default 5)\n"
          "    --cycles N          times through the whole set (default 3)\n"
          "    --methods A,B,..    the methods to cycle (default all, none included)\n"
          "    --log FILE.csv      one row per camera x method: average FPS and ms per pass\n"
          "                        (required), and a screenshot each in FILE's directory\n"
          "\n"
          "keys: W A S D move, Q E down/up, Shift 4x faster, right mouse button held: look,\n"
          "      scroll: zoom (field of view), 1-9 camera presets, Tab next preset, L lock the\n"
          "      camera, M / Shift+M next / previous method, V / Shift+V next / previous view,\n"
          "      F1 or H panel on/off, F3 vsync, P or F12 screenshot, R reload shaders (development\n"
          "      builds), Esc quit\n"
          "\n"
          "script lines: TIME EVENT ARGS, TIME in seconds on a clock that advances 1/30 s per frame\n"
          "  key NAME down|up|press       NAME: A-Z, 0-9, TAB, ESCAPE, SPACE, LEFT_SHIFT, F1-F12\n"
          "  mouse left|right down|up     move X Y (cursor, pixels)    scroll DY\n"
          "  method NAME   filter NAME   set M.P=V   camera NAME|INDEX   view NAME\n"
          "  resize W H   screenshot FILE.png   quit (as Esc)   close (as the window's close button)\n",
          f);
}

/* ---- options ----------------------------------------------------------------------------- */
typedef struct view_opts {
    const char *scene, *sidecar, *camera, *method, *filter, *env, *shots, *script, *log, *methods;
    const char *sets[64];
    int set_count;
    ob_up_axis up;
    int quality_samples;
    float ao_scale;
    bool adaptive, vsync, gui, hdr_off, test_mode;
    int shadow_method, shadow_size; /* -1 = the default */
    int width, height, cycles;
    float seconds;
} view_opts;

static int parse_view_opts(int argc, char **argv, view_opts *o)
{
    *o = (view_opts){.scene = "fzk-haus", .method = "ssao", .filter = "geometry", .ao_scale = 1.0f, .vsync = true,
                     .gui = true, .shadow_method = -1, .shadow_size = -1, .width = 1280, .height = 720,
                     .cycles = 3, .seconds = 5.0f};
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            view_usage(stdout);
            return -1;
        }
        if (!strcmp(a, "--test-mode")) {
            o->test_mode = true;
            continue;
        }
        static const char *const with_value[] = {"--scene", "--sidecar", "--camera", "--method", "--filter", "--env",
                                                 "--shots", "--script", "--log", "--methods", "--set", "--up",
                                                 "--quality", "--ao-scale", "--adaptive", "--vsync", "--gui", "--hdr",
                                                 "--shadow", "--shadow-size", "--size", "--seconds", "--cycles"};
        bool known = false;
        for (size_t k = 0; k < sizeof with_value / sizeof with_value[0]; ++k) known = known || !strcmp(a, with_value[k]);
        if (!known) return cli_fail(EXIT_USAGE, "unknown option '%s' (see obscura view --help)", a);
        if (i + 1 >= argc) return cli_fail(EXIT_USAGE, "%s: missing value (see obscura view --help)", a);
        const char *v = argv[++i];
        if (!strcmp(a, "--scene")) o->scene = v;
        else if (!strcmp(a, "--sidecar")) o->sidecar = v;
        else if (!strcmp(a, "--camera")) o->camera = v;
        else if (!strcmp(a, "--method")) o->method = v;
        else if (!strcmp(a, "--filter")) o->filter = v;
        else if (!strcmp(a, "--env")) o->env = v;
        else if (!strcmp(a, "--shots")) o->shots = v;
        else if (!strcmp(a, "--script")) o->script = v;
        else if (!strcmp(a, "--log")) o->log = v;
        else if (!strcmp(a, "--methods")) o->methods = v;
        else if (!strcmp(a, "--set")) {
            if (o->set_count >= 64) return cli_fail(EXIT_USAGE, "--set: too many");
            o->sets[o->set_count++] = v;
        } else if (!strcmp(a, "--up")) {
            if (!cli_parse_up(v, &o->up)) return cli_fail(EXIT_USAGE, "--up: expected y or z, got '%s'", v);
        } else if (!strcmp(a, "--quality")) {
            o->quality_samples = ob_quality_samples(v);
            if (o->quality_samples < 0) return cli_fail(EXIT_USAGE, "--quality: expected low, medium, high or ultra, got '%s'", v);
        } else if (!strcmp(a, "--ao-scale")) {
            if (!cli_parse_ao_scale(v, &o->ao_scale))
                return cli_fail(EXIT_USAGE, "--ao-scale: expected 1, 0.5 or 0.25, got '%s'", v);
        } else if (!strcmp(a, "--adaptive")) {
            if (!cli_parse_on_off(v, &o->adaptive)) return cli_fail(EXIT_USAGE, "--adaptive: expected on or off, got '%s'", v);
        } else if (!strcmp(a, "--vsync")) {
            if (!cli_parse_on_off(v, &o->vsync)) return cli_fail(EXIT_USAGE, "--vsync: expected on or off, got '%s'", v);
        } else if (!strcmp(a, "--gui")) {
            if (!cli_parse_on_off(v, &o->gui)) return cli_fail(EXIT_USAGE, "--gui: expected on or off, got '%s'", v);
        } else if (!strcmp(a, "--hdr")) {
            bool on = true;
            if (!cli_parse_on_off(v, &on)) return cli_fail(EXIT_USAGE, "--hdr: expected on or off, got '%s'", v);
            o->hdr_off = !on;
        } else if (!strcmp(a, "--shadow")) {
            ob_shadow_method m = OB_SHADOW_NONE;
            if (!cli_parse_shadow(v, &m)) return cli_fail(EXIT_USAGE, "--shadow: expected none, hard, pcf or vsm, got '%s'", v);
            o->shadow_method = (int)m;
        } else if (!strcmp(a, "--shadow-size")) {
            char *end = NULL;
            long n = strtol(v, &end, 10);
            if (end == v || *end || n < 16 || n > 16384) return cli_fail(EXIT_USAGE, "--shadow-size: expected 16..16384, got '%s'", v);
            o->shadow_size = (int)n;
        } else if (!strcmp(a, "--size")) {
            if (!cli_parse_size(v, &o->width, &o->height) || o->width < 16 || o->height < 16 || o->width > 16384 ||
                o->height > 16384)
                return cli_fail(EXIT_USAGE, "--size: expected WIDTHxHEIGHT, each 16..16384, got '%s'", v);
        } else if (!strcmp(a, "--seconds")) {
            if (!cli_parse_float(v, &o->seconds) || !(o->seconds >= 0.0f) || o->seconds > 3600.0f)
                return cli_fail(EXIT_USAGE, "--seconds: expected 0..3600, got '%s'", v);
        } else if (!strcmp(a, "--cycles")) {
            char *end = NULL;
            long n = strtol(v, &end, 10);
            if (end == v || *end || n < 1 || n > MAX_CYCLES) return cli_fail(EXIT_USAGE, "--cycles: expected 1..%d, got '%s'", MAX_CYCLES, v);
            o->cycles = (int)n;
        } else {
            return cli_fail(EXIT_USAGE, "unknown option '%s' (see obscura view --help)", a);
        }
    }
    if (o->test_mode && !o->log) return cli_fail(EXIT_USAGE, "--test-mode needs --log FILE.csv");
    if (!o->test_mode && (o->log || o->methods))
        return cli_fail(EXIT_USAGE, "--log and --methods belong to --test-mode");
    if (o->test_mode && o->script) return cli_fail(EXIT_USAGE, "--test-mode and --script exclude each other");
    if (o->log && !cli_output_writable(o->log))
        return cli_fail(EXIT_OUTPUT, "cannot write %s: its directory does not exist or is not writable", o->log);
    return 0;
}

/* ---- script: timed input events ------------------------------------------------------------ */
typedef enum event_kind {
    EV_KEY, EV_MOUSE, EV_MOVE, EV_SCROLL, EV_METHOD, EV_FILTER, EV_SET, EV_CAMERA, EV_VIEW, EV_SCREENSHOT, EV_QUIT, EV_CLOSE, EV_RESIZE
} event_kind;

typedef struct script_event {
    double t;
    event_kind kind;
    int code;    /* GLFW key or mouse button */
    int action;  /* GLFW_PRESS, GLFW_RELEASE, or 2 = press and release */
    double x, y;
    char arg[256];
} script_event;

static int key_from_name(const char *name)
{
    if (strlen(name) == 1) {
        char c = (char)toupper((unsigned char)name[0]);
        if (c >= 'A' && c <= 'Z') return GLFW_KEY_A + (c - 'A');
        if (c >= '0' && c <= '9') return GLFW_KEY_0 + (c - '0');
    }
    static const struct { const char *name; int key; } named[] = {
        {"TAB", GLFW_KEY_TAB}, {"ESCAPE", GLFW_KEY_ESCAPE}, {"SPACE", GLFW_KEY_SPACE},
        {"LEFT_SHIFT", GLFW_KEY_LEFT_SHIFT}, {"RIGHT_SHIFT", GLFW_KEY_RIGHT_SHIFT}, {"ENTER", GLFW_KEY_ENTER},
    };
    for (size_t i = 0; i < sizeof named / sizeof named[0]; ++i)
        if (!strcmp(name, named[i].name)) return named[i].key;
    if (name[0] == 'F' && isdigit((unsigned char)name[1])) {
        int n = atoi(name + 1);
        if (n >= 1 && n <= 12) return GLFW_KEY_F1 + n - 1;
    }
    return -1;
}

/* Reads the whole script up front, so a bad line fails before a window opens. Lines must be in
 * time order. */
static int load_script(const char *path, script_event **out, int *count)
{
    FILE *f = fopen(path, "r");
    if (!f) return cli_fail(EXIT_INPUT, "cannot read script %s", path);
    script_event *ev = calloc(MAX_EVENTS, sizeof *ev);
    if (!ev) {
        fclose(f);
        return cli_fail(EXIT_RUNTIME, "out of memory reading %s", path);
    }
    char line[512];
    int n = 0, lineno = 0, code = 0;
    double last_t = 0.0;
    while (fgets(line, sizeof line, f) && code == 0) {
        ++lineno;
        char *p = line;
        while (isspace((unsigned char)*p)) ++p;
        if (!*p || *p == '#') continue;
        p[strcspn(p, "\r\n")] = '\0';
        if (n >= MAX_EVENTS) {
            code = cli_fail(EXIT_INPUT, "%s:%d: more than %d events", path, lineno, MAX_EVENTS);
            break;
        }
        script_event *e = &ev[n];
        char kind[32] = "", a1[256] = "", a2[64] = "";
        int used = 0;
        if (sscanf(p, "%lf %31s%n", &e->t, kind, &used) < 2 || !isfinite(e->t) || e->t < 0.0 || e->t < last_t) {
            code = cli_fail(EXIT_INPUT, "%s:%d: expected 'TIME EVENT ...' with times >= 0 in order, got '%s'", path, lineno, p);
            break;
        }
        last_t = e->t;
        const char *rest = p + used;
        while (isspace((unsigned char)*rest)) ++rest;
        int fields = sscanf(rest, "%255s %63s", a1, a2);
        bool ok = true;
        if (!strcmp(kind, "key")) {
            e->kind = EV_KEY;
            e->code = key_from_name(a1);
            e->action = !strcmp(a2, "down") ? GLFW_PRESS : !strcmp(a2, "up") ? GLFW_RELEASE : !strcmp(a2, "press") ? 2 : -1;
            ok = fields == 2 && e->code >= 0 && e->action >= 0;
        } else if (!strcmp(kind, "mouse")) {
            e->kind = EV_MOUSE;
            e->code = !strcmp(a1, "left") ? GLFW_MOUSE_BUTTON_LEFT : !strcmp(a1, "right") ? GLFW_MOUSE_BUTTON_RIGHT : -1;
            e->action = !strcmp(a2, "down") ? GLFW_PRESS : !strcmp(a2, "up") ? GLFW_RELEASE : -1;
            ok = fields == 2 && e->code >= 0 && e->action >= 0;
        } else if (!strcmp(kind, "move")) {
            e->kind = EV_MOVE;
            ok = sscanf(rest, "%lf %lf", &e->x, &e->y) == 2 && isfinite(e->x) && isfinite(e->y);
        } else if (!strcmp(kind, "scroll")) {
            e->kind = EV_SCROLL;
            ok = sscanf(rest, "%lf", &e->y) == 1 && isfinite(e->y);
        } else if (!strcmp(kind, "quit")) {
            e->kind = EV_QUIT;
        } else if (!strcmp(kind, "close")) {
            e->kind = EV_CLOSE;
        } else if (!strcmp(kind, "resize")) {
            e->kind = EV_RESIZE;
            ok = sscanf(rest, "%lf %lf", &e->x, &e->y) == 2 && e->x >= 16.0 && e->y >= 16.0 && e->x <= 16384.0 &&
                 e->y <= 16384.0;
        } else {
            static const struct { const char *name; event_kind kind; } with_arg[] = {
                {"method", EV_METHOD}, {"filter", EV_FILTER}, {"set", EV_SET}, {"camera", EV_CAMERA},
                {"view", EV_VIEW}, {"screenshot", EV_SCREENSHOT}};
            ok = false;
            for (size_t k = 0; k < sizeof with_arg / sizeof with_arg[0]; ++k)
                if (!strcmp(kind, with_arg[k].name) && fields >= 1) {
                    e->kind = with_arg[k].kind;
                    snprintf(e->arg, sizeof e->arg, "%s", a1);
                    ok = true;
                }
        }
        if (!ok) {
            code = cli_fail(EXIT_INPUT, "%s:%d: cannot read '%s' (see obscura view --help for the events)", path, lineno, p);
            break;
        }
        ++n;
    }
    fclose(f);
    if (code != 0) {
        free(ev);
        return code;
    }
    *out = ev;
    *count = n;
    return 0;
}

/* ---- profiler (seed 000 Figure 5.1: current, average, minimum, maximum and calls) -------------- */
typedef struct pass_stats {
    const char *name;
    double current, sum, min, max;
    long calls;
} pass_stats;

typedef struct profiler {
    pass_stats pass[MAX_PASSES];
    int count;
    double frame_sum, frame_min, frame_max; /* wall-clock frame time, ms */
    long frames;
} profiler;

static void profiler_reset(profiler *p) { memset(p, 0, sizeof *p); }

static void profiler_add(profiler *p, const ob_pass_timing *t, int n, double frame_ms)
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

/* ---- test mode (seed 004 §3.5) -------------------------------------------------------------- */
typedef struct test_cell {
    double fps[MAX_CYCLES];
    long frames;
    double seconds;
    double pass_ms[PASS_ORDER_COUNT]; /* sums over every measured frame */
    long pass_calls[PASS_ORDER_COUNT];
} test_cell;

typedef struct test_run {
    int methods[MAX_METHODS];
    int method_count, camera_count;
    int cycle, camera, method;      /* the slot being measured */
    bool warmed;                    /* the slot's first frame (shader compiles, first use) is done */
    double slot_start;
    long slot_frames;
    test_cell *cells;               /* camera_count x method_count */
    char dir[4096];                 /* screenshots go here */
    bool done;
} test_run;

/* ---- the viewer ---------------------------------------------------------------------------- */
typedef struct viewer {
    view_opts o;
    GLFWwindow *window;
    ob_context *ctx;
    ob_renderer *r;
    ob_scene *scene;
    ob_settings s;
    float method_params[MAX_METHODS][OB_MAX_PARAMS]; /* each method keeps its own values */
    uint32_t method_set[MAX_METHODS];
    int quality;            /* 0 = the methods' defaults, 1..4 = low..ultra */
    ob_view view;
    /* camera: eye, unit forward and world up; presets from the scene */
    int camera_index;
    float eye[3], fwd[3], up[3];
    float fov, speed, scene_size;
    bool camera_locked, gui_visible, vsync;
    bool keys[GLFW_KEY_LAST + 1];
    bool look;              /* right button held */
    double mouse_x, mouse_y;
    bool mouse_known;
    int fb_width, fb_height;
    /* clock: wall time, or simulated in a script run */
    double clock, last_frame_ms, fps, fps_window_start;
    int fps_window_frames;
    profiler prof;
    char message[512];
    double message_until;
    bool message_error;
    bool quit;
    int exit_code;
    const char *shot_dir;
    script_event *events;
    int event_count, next_event;
    test_run *test;
    char title[256];
} viewer;

static char glfw_message[512];

static void on_glfw_error(int code, const char *description)
{
    snprintf(glfw_message, sizeof glfw_message, "%s (GLFW error 0x%x)", description ? description : "?", code);
}

static void say(viewer *v, bool error, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void say(viewer *v, bool error, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(v->message, sizeof v->message, fmt, ap);
    va_end(ap);
    v->message_error = error;
    v->message_until = v->clock + 4.0;
    /* Also on stderr: a script or test run has no one watching the window. */
    fprintf(stderr, "obscura view: %s\n", v->message);
}

static float vlen(const float a[3]) { return sqrtf(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

static void vnorm(float a[3])
{
    float l = vlen(a);
    if (l > 0.0f)
        for (int i = 0; i < 3; ++i) a[i] /= l;
}

static void vcross(const float a[3], const float b[3], float out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

/* Rotate v about the unit axis k by angle (Rodrigues). */
static void vrotate(float v[3], const float k[3], float angle)
{
    float c = cosf(angle), s = sinf(angle), kxv[3], d = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
    vcross(k, v, kxv);
    for (int i = 0; i < 3; ++i) v[i] = v[i] * c + kxv[i] * s + k[i] * d * (1.0f - c);
}

static void use_camera(viewer *v, int index)
{
    int count = ob_query_camera_count(v->scene);
    if (count < 1) return;
    v->camera_index = ((index % count) + count) % count;
    ob_camera c = ob_query_camera(v->scene, v->camera_index);
    memcpy(v->eye, c.eye, sizeof v->eye);
    for (int i = 0; i < 3; ++i) v->fwd[i] = c.target[i] - c.eye[i];
    vnorm(v->fwd);
    memcpy(v->up, c.up, sizeof v->up);
    if (vlen(v->up) == 0.0f) v->up[1] = 1.0f;
    vnorm(v->up);
    v->fov = c.fov_y_deg > 0.0f ? c.fov_y_deg : 60.0f;
}

static ob_camera current_camera(const viewer *v)
{
    ob_camera c;
    memset(&c, 0, sizeof c);
    memcpy(c.eye, v->eye, sizeof c.eye);
    for (int i = 0; i < 3; ++i) c.target[i] = v->eye[i] + v->fwd[i];
    memcpy(c.up, v->up, sizeof c.up);
    c.fov_y_deg = v->fov;
    return c;
}

static void update_title(viewer *v)
{
    char title[256];
    snprintf(title, sizeof title, "Obscura - %s - %s%s", ob_query_scene_name(v->scene), ob_method_at(v->s.method)->name,
             v->view == OB_VIEW_FINAL ? "" : " (debug view)");
    if (strcmp(title, v->title) != 0) {
        snprintf(v->title, sizeof v->title, "%s", title);
        glfwSetWindowTitle(v->window, title);
    }
}

/* Switching methods keeps each method's own parameter values; a quality preset other than the
 * methods' defaults is applied to every method picked, as --quality is. */
static void select_method(viewer *v, int index)
{
    int n = ob_method_count();
    index = ((index % n) + n) % n;
    memcpy(v->method_params[v->s.method], v->s.params, sizeof v->s.params);
    v->method_set[v->s.method] = v->s.params_set;
    v->s.method = index;
    memcpy(v->s.params, v->method_params[index], sizeof v->s.params);
    v->s.params_set = v->method_set[index];
    static const char *const presets[] = {"", "low", "medium", "high", "ultra"};
    if (v->quality > 0) {
        ob_settings_set_samples(&v->s, ob_quality_samples(presets[v->quality]));
        ob_clear_error(); /* none takes no sample count: nothing to set */
    }
    profiler_reset(&v->prof);
    update_title(v);
}

static bool select_method_by_name(viewer *v, const char *name)
{
    int index = ob_find_method(name);
    if (index < 0) {
        say(v, true, "unknown method '%s'", name);
        return false;
    }
    select_method(v, index);
    return true;
}

static void set_view(viewer *v, int index)
{
    v->view = (ob_view)(((index % OB_VIEW_COUNT) + OB_VIEW_COUNT) % OB_VIEW_COUNT);
    update_title(v);
}

static void save_screenshot(viewer *v, const char *path);

static void default_shot_path(viewer *v, char *out, size_t len)
{
    time_t now = time(NULL);
    struct tm tm;
    localtime_r(&now, &tm);
    char stamp[32];
    strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", &tm);
    static int serial = 0;
    snprintf(out, len, "%s/obscura-%s-%s-%s-%d.png", v->shot_dir, ob_query_scene_name(v->scene), stamp,
             ob_method_at(v->s.method)->name, ++serial);
}

static void reload_shaders(viewer *v);

/* Discrete actions on key press; continuous ones (movement) read v->keys every frame. */
static void handle_key(viewer *v, int key, int action, int mods)
{
    if (key < 0 || key > GLFW_KEY_LAST) return;
    if (action == GLFW_PRESS) v->keys[key] = true;
    else if (action == GLFW_RELEASE) v->keys[key] = false;
    if (action != GLFW_PRESS) return;
    bool shift = (mods & GLFW_MOD_SHIFT) != 0;
    if (key == GLFW_KEY_ESCAPE) v->quit = true;
    else if (key == GLFW_KEY_F1 || key == GLFW_KEY_H) v->gui_visible = !v->gui_visible;
    else if (key == GLFW_KEY_L) {
        v->camera_locked = !v->camera_locked;
        v->look = false;
        say(v, false, "camera %s", v->camera_locked ? "locked" : "unlocked");
    } else if (key == GLFW_KEY_TAB) use_camera(v, v->camera_index + (shift ? -1 : 1));
    else if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9) {
        if (key - GLFW_KEY_1 < ob_query_camera_count(v->scene)) use_camera(v, key - GLFW_KEY_1);
    } else if (key == GLFW_KEY_M) select_method(v, v->s.method + (shift ? -1 : 1));
    else if (key == GLFW_KEY_V) set_view(v, (int)v->view + (shift ? -1 : 1));
    else if (key == GLFW_KEY_F3) {
        v->vsync = !v->vsync;
        glfwSwapInterval(v->vsync ? 1 : 0);
    } else if (key == GLFW_KEY_P || key == GLFW_KEY_F12) {
        char path[4200];
        default_shot_path(v, path, sizeof path);
        save_screenshot(v, path);
    } else if (key == GLFW_KEY_R) reload_shaders(v);
}

static void handle_mouse_button(viewer *v, int button, int action)
{
    if (button != GLFW_MOUSE_BUTTON_RIGHT) return;
    v->look = action == GLFW_PRESS && !v->camera_locked;
}

static void handle_cursor(viewer *v, double x, double y)
{
    if (v->look && v->mouse_known) {
        /* 0.2 degrees per pixel; pitch stops short of the poles so forward never meets up. */
        const float rad_per_px = 0.2f * 3.14159265f / 180.0f;
        float dx = (float)(x - v->mouse_x), dy = (float)(y - v->mouse_y);
        vrotate(v->fwd, v->up, -dx * rad_per_px);
        float right[3];
        vcross(v->fwd, v->up, right);
        vnorm(right);
        float before[3];
        memcpy(before, v->fwd, sizeof before);
        vrotate(v->fwd, right, -dy * rad_per_px);
        float along_up = v->fwd[0] * v->up[0] + v->fwd[1] * v->up[1] + v->fwd[2] * v->up[2];
        if (fabsf(along_up) > 0.99f) memcpy(v->fwd, before, sizeof before);
        vnorm(v->fwd);
    }
    v->mouse_x = x;
    v->mouse_y = y;
    v->mouse_known = true;
}

static void handle_scroll(viewer *v, double dy)
{
    if (v->camera_locked) return;
    v->fov = v->fov * powf(0.9f, (float)dy);
    v->fov = v->fov < 5.0f ? 5.0f : v->fov > 120.0f ? 120.0f : v->fov;
}

/* GLFW callbacks: ImGui sees each event first (its backend chains to these) and keeps the ones
 * aimed at the panel. */
static void on_key(GLFWwindow *w, int key, int scancode, int action, int mods)
{
    (void)scancode;
    viewer *v = glfwGetWindowUserPointer(w);
    if (gui_wants_keyboard() && action == GLFW_PRESS) return;
    handle_key(v, key, action, mods);
}

static void on_mouse_button(GLFWwindow *w, int button, int action, int mods)
{
    (void)mods;
    viewer *v = glfwGetWindowUserPointer(w);
    if (gui_wants_mouse() && action == GLFW_PRESS) return;
    handle_mouse_button(v, button, action);
}

static void on_cursor(GLFWwindow *w, double x, double y) { handle_cursor(glfwGetWindowUserPointer(w), x, y); }

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    (void)dx;
    if (gui_wants_mouse()) return;
    handle_scroll(glfwGetWindowUserPointer(w), dy);
}

static void on_close(GLFWwindow *w)
{
    viewer *v = glfwGetWindowUserPointer(w);
    v->quit = true;
}

static void move_camera(viewer *v, double dt)
{
    if (v->camera_locked) return;
    float step = v->speed * (float)dt * (v->keys[GLFW_KEY_LEFT_SHIFT] || v->keys[GLFW_KEY_RIGHT_SHIFT] ? 4.0f : 1.0f);
    float right[3];
    vcross(v->fwd, v->up, right);
    vnorm(right);
    float f = (float)(v->keys[GLFW_KEY_W] - v->keys[GLFW_KEY_S]);
    float s = (float)(v->keys[GLFW_KEY_D] - v->keys[GLFW_KEY_A]);
    float u = (float)(v->keys[GLFW_KEY_E] - v->keys[GLFW_KEY_Q]);
    for (int i = 0; i < 3; ++i) v->eye[i] += step * (f * v->fwd[i] + s * right[i] + u * v->up[i]);
}

/* ---- screenshots --------------------------------------------------------------------------- */
/* The window as it shows now (image and panel): the back buffer, before the swap. */
static void save_screenshot(viewer *v, const char *path)
{
    int w = v->fb_width, h = v->fb_height;
    size_t row = (size_t)w * 4;
    unsigned char *px = malloc(row * (size_t)h), *flipped = malloc(row * (size_t)h);
    if (!px || !flipped) {
        free(px);
        free(flipped);
        say(v, true, "out of memory for a %dx%d screenshot", w, h);
        return;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px);
    for (int y = 0; y < h; ++y) memcpy(flipped + (size_t)y * row, px + (size_t)(h - 1 - y) * row, row);
    for (size_t i = 3; i < row * (size_t)h; i += 4) flipped[i] = 255; /* the window's alpha is not the image's */
    mkdir(v->shot_dir, 0777); /* the default directory; a --shots or script path's must exist */
    if (ob_write_png(path, w, h, 4, flipped) != OB_OK) {
        const char *msg = "";
        ob_get_error(&msg);
        say(v, true, "screenshot failed: %s", msg);
    } else {
        say(v, false, "screenshot %s", path);
    }
    free(px);
    free(flipped);
}

/* ---- shader reload (development builds) ---------------------------------------------------- */
static void reload_shaders(viewer *v)
{
#ifdef OB_VIEW_SHADER_RELOAD
    char dir[4200];
    snprintf(dir, sizeof dir, "%s/shaders", ob_data_dir());
    if (ob_set_shader_directory(dir) != OB_OK) {
        const char *msg = "";
        ob_get_error(&msg);
        say(v, true, "reload: %s", msg);
        return;
    }
    /* A new renderer compiles every program from disk; the old one keeps running if anything
     * fails, so a typo in a shader shows its file:line here instead of ending the session. */
    ob_renderer *fresh = ob_make_renderer(v->ctx, &(ob_renderer_desc){.width = v->fb_width, .height = v->fb_height});
    ob_camera cam = current_camera(v);
    bool ok = fresh && ob_renderer_set_scene(fresh, v->scene) == OB_OK &&
              (!v->o.env || ob_renderer_set_environment(fresh, v->o.env) == OB_OK) &&
              ob_render_frame(fresh, &cam, &v->s) == OB_OK;
    if (!ok) {
        const char *msg = "";
        ob_get_error(&msg);
        say(v, true, "reload failed, keeping the old shaders: %s", msg);
        ob_destroy_renderer(fresh);
        return;
    }
    ob_destroy_renderer(v->r);
    v->r = fresh;
    profiler_reset(&v->prof);
    say(v, false, "shaders reloaded from %s", dir);
#else
    say(v, false, "shader reload is for development builds (CMAKE_BUILD_TYPE other than Release)");
#endif
}

/* ---- the panel ----------------------------------------------------------------------------- */
/* A slider, checkbox or list for one parameter of a registry table. Returns true when the value
 * changed (the caller marks it as set explicitly). */
static bool param_widget(const ob_param_info *p, float *value, float shown_default)
{
    char label[160];
    if (p->unit && *p->unit) snprintf(label, sizeof label, "%s (%s)", p->name, p->unit);
    else snprintf(label, sizeof label, "%s", p->name);
    bool changed = false;
    switch (p->type) {
    case OB_PARAM_BOOL: {
        bool b = *value != 0.0f;
        if ((changed = gui_checkbox(label, &b))) *value = b ? 1.0f : 0.0f;
        break;
    }
    case OB_PARAM_ENUM: {
        int i = (int)*value;
        if ((changed = gui_combo(label, &i, p->options, (int)p->max + 1))) *value = (float)i;
        break;
    }
    case OB_PARAM_INT: {
        int i = (int)*value;
        bool log = p->min > 0.0f && p->max / p->min >= 100.0f;
        if ((changed = gui_slider_int(label, &i, (int)p->min, (int)p->max, log))) *value = (float)i;
        break;
    }
    case OB_PARAM_FLOAT: {
        float f = shown_default;
        /* Ranges over several decades (radii in any unit) slide logarithmically. */
        bool log = p->min > 0.0f && p->max / p->min >= 100.0f;
        if ((changed = gui_slider_float(label, &f, p->min, p->max, "%.4g", log))) {
            f = f < p->min ? p->min : f > p->max ? p->max : f;
            *value = f;
        }
        break;
    }
    }
    gui_tooltip(p->help);
    return changed;
}

static void panel_method(viewer *v)
{
    const char *names[MAX_METHODS];
    int n = ob_method_count() < MAX_METHODS ? ob_method_count() : MAX_METHODS;
    for (int i = 0; i < n; ++i) names[i] = ob_method_at(i)->name;
    int m = v->s.method;
    if (gui_combo("method", &m, names, n)) select_method(v, m);
    const ob_method_info *info = ob_method_at(v->s.method);
    gui_tooltip(info->description);
    static const char *const qualities[] = {"method default", "low (12)", "medium (24)", "high (36)", "ultra (64)"};
    if (gui_combo("quality", &v->quality, qualities, 5)) select_method(v, v->s.method);
    for (int i = 0; i < info->param_count; ++i) {
        const ob_param_info *p = &info->params[i];
        bool follows = p->follows_scene_radius && !(v->s.params_set & (1u << i));
        float shown = follows ? ob_query_scene_ao_radius(v->scene) : v->s.params[i];
        gui_push_id(i);
        if (param_widget(p, &v->s.params[i], shown)) v->s.params_set |= 1u << i;
        gui_pop_id();
    }
    if (info->param_count > 0 && gui_button("defaults")) {
        ob_settings fresh;
        if (ob_settings_init(&fresh, info->name) == OB_OK) {
            memcpy(v->s.params, fresh.params, sizeof v->s.params);
            v->s.params_set = 0;
        }
    }
    gui_separator();
    const char *filters[MAX_METHODS];
    int fn = ob_filter_count() < MAX_METHODS ? ob_filter_count() : MAX_METHODS;
    for (int i = 0; i < fn; ++i) filters[i] = ob_filter_at(i)->name;
    int f = v->s.filter;
    if (gui_combo("filter", &f, filters, fn)) {
        ob_settings_set_filter(&v->s, filters[f]);
        profiler_reset(&v->prof);
    }
    const ob_filter_info *finfo = ob_filter_at(v->s.filter);
    gui_tooltip(finfo->description);
    for (int i = 0; i < finfo->param_count; ++i) {
        gui_push_id(100 + i);
        if (param_widget(&finfo->params[i], &v->s.filter_params[i], v->s.filter_params[i]))
            v->s.filter_params_set |= 1u << i;
        gui_pop_id();
    }
    static const char *const scales[] = {"1 (full)", "0.5", "0.25"};
    int si = v->s.ao_divisor == 2 ? 1 : v->s.ao_divisor == 4 ? 2 : 0;
    if (gui_combo("ao scale", &si, scales, 3)) {
        ob_settings_set_ao_scale(&v->s, si == 1 ? 0.5f : si == 2 ? 0.25f : 1.0f);
        profiler_reset(&v->prof);
    }
    gui_tooltip("run the method and the filter at this fraction of the size, then joint bilateral upsampling");
    gui_checkbox("adaptive samples", &v->s.adaptive);
    gui_tooltip("an edge pre-pass gives edge pixels 2x or 3x the base count (ssao, crytek)");
}

static void panel_lights(viewer *v)
{
    static const char *const kinds[] = {"directional", "point", "spot"};
    float reach = v->scene_size * 0.005f;
    for (int i = 0; i < v->s.light_count; ++i) {
        ob_light *l = &v->s.lights[i];
        char label[64];
        snprintf(label, sizeof label, "light %d: %s", i, kinds[l->type]);
        gui_push_id(200 + i);
        if (gui_header(label, i == 0)) {
            if (l->type == OB_LIGHT_DIRECTIONAL) {
                if (gui_drag3("toward light", l->direction, 0.01f)) vnorm(l->direction);
            } else {
                gui_drag3("position", l->position, reach);
                if (l->type == OB_LIGHT_SPOT) {
                    if (gui_drag3("axis", l->direction, 0.01f)) vnorm(l->direction);
                    gui_slider_float("inner cone (deg)", &l->spot_inner_deg, 0.0f, 89.0f, "%.1f", false);
                    gui_slider_float("outer cone (deg)", &l->spot_outer_deg, l->spot_inner_deg, 90.0f, "%.1f", false);
                }
            }
            gui_color3("colour", l->color);
            gui_slider_float("intensity", &l->intensity, 0.001f, 10000.0f, "%.4g", true);
        }
        gui_pop_id();
    }
    static const char *const shadows[] = {"none", "hard", "pcf", "vsm"};
    int sm = (int)v->s.shadow.method;
    if (gui_combo("shadows", &sm, shadows, 4)) v->s.shadow.method = (ob_shadow_method)sm;
    static const char *const sizes[] = {"256", "512", "1024", "2048", "4096"};
    int zi = 0;
    for (int k = 0; k < 5; ++k)
        if (v->s.shadow.size == 256 << k) zi = k;
    if (gui_combo("map size", &zi, sizes, 5)) v->s.shadow.size = 256 << zi;
    gui_checkbox("keep maps while lights are unchanged", &v->s.shadow.reuse);
    gui_tooltip("off: render the shadow maps every frame, as obscura render and bench time them");
    gui_slider_float("bias (texels)", &v->s.shadow.bias, 0.0f, 10.0f, "%.2f", false);
    gui_slider_float("slope bias", &v->s.shadow.slope_bias, 0.0f, 10.0f, "%.2f", false);
    if (v->s.shadow.method == OB_SHADOW_PCF) gui_slider_int("pcf radius", &v->s.shadow.pcf_radius, 1, 8, false);
    if (v->s.shadow.method == OB_SHADOW_VSM) {
        gui_slider_float("vsm blur (texels)", &v->s.shadow.vsm_blur, 0.0f, 16.0f, "%.2f", false);
        gui_slider_float("vsm bleed", &v->s.shadow.vsm_bleed, 0.0f, 0.99f, "%.2f", false);
    }
    static const char *const ambients[] = {"constant", "hemisphere", "environment"};
    int am = (int)v->s.ambient_mode;
    if (gui_combo("ambient", &am, ambients, v->o.env ? 3 : 2)) v->s.ambient_mode = (ob_ambient_mode)am;
    if (v->s.ambient_mode == OB_AMBIENT_CONSTANT) gui_color3("ambient colour", v->s.ambient);
    if (v->s.ambient_mode == OB_AMBIENT_HEMISPHERE) {
        gui_color3("sky", v->s.sky);
        gui_color3("ground", v->s.ground);
    }
    gui_checkbox("AO darkens all light", &v->s.ao_all_light);
}

static void panel_hdr(viewer *v)
{
    ob_hdr_settings *h = &v->s.hdr;
    gui_checkbox("tone mapping", &h->enabled);
    gui_tooltip("off: the radiance is clamped to [0,1] before sRGB");
    gui_slider_float("exposure", &h->exposure, 0.01f, 100.0f, "%.3g", true);
    if (h->enabled) {
        bool automatic = h->key == 0.0f;
        if (gui_checkbox("automatic key", &automatic)) h->key = automatic ? 0.0f : 0.18f;
        if (!automatic) gui_slider_float("key", &h->key, 0.045f, 0.9f, "%.3f", false);
        gui_slider_float("L_white", &h->l_white, 0.0f, 20.0f, "%.2f", false);
        gui_slider_float("bloom", &h->bloom_strength, 0.0f, 2.0f, "%.2f", false);
        gui_slider_float("bloom threshold", &h->bloom_threshold, 0.0f, 10.0f, "%.2f", false);
    }
}

static void panel_display(viewer *v)
{
    const char *views[OB_VIEW_COUNT];
    for (int i = 0; i < OB_VIEW_COUNT; ++i) views[i] = ob_view_name((ob_view)i);
    int vi = (int)v->view;
    if (gui_combo("view", &vi, views, OB_VIEW_COUNT)) set_view(v, vi);
    gui_color3("background", v->s.background);
    if (gui_checkbox("vsync", &v->vsync)) glfwSwapInterval(v->vsync ? 1 : 0);
    int count = ob_query_camera_count(v->scene);
    const char *cams[MAX_CAMERAS];
    ob_camera presets[MAX_CAMERAS];
    int cn = count < MAX_CAMERAS ? count : MAX_CAMERAS;
    for (int i = 0; i < cn; ++i) {
        presets[i] = ob_query_camera(v->scene, i);
        cams[i] = presets[i].name;
    }
    int ci = v->camera_index;
    if (gui_combo("camera", &ci, cams, cn)) use_camera(v, ci);
    gui_slider_float("fov (deg)", &v->fov, 5.0f, 120.0f, "%.1f", false);
    gui_slider_float("speed", &v->speed, v->scene_size * 0.001f, v->scene_size * 2.0f, "%.3g", true);
    gui_tooltip("world units per second (Shift: 4x)");
    gui_checkbox("lock camera (L)", &v->camera_locked);
    if (gui_button("screenshot (P)")) {
        char path[4200];
        default_shot_path(v, path, sizeof path);
        save_screenshot(v, path);
    }
#ifdef OB_VIEW_SHADER_RELOAD
    gui_same_line();
    if (gui_button("reload shaders (R)")) reload_shaders(v);
#endif
}

static void panel_profiler(viewer *v)
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

static void build_gui(viewer *v)
{
    gui_new_frame();
    if (v->gui_visible) {
        /* The overlay: what a screenshot should say about itself (seed 004 §2.7). */
        if (gui_begin_overlay("##overlay", 10.0f, 10.0f)) {
            gui_text("%.1f FPS  %.1f ms   %dx%d   %s", v->fps, v->last_frame_ms, v->fb_width, v->fb_height,
                     ob_query_renderer(v->ctx));
            gui_text("%s  %s  %s%s", ob_query_scene_name(v->scene), ob_method_at(v->s.method)->name,
                     ob_view_name(v->view), v->camera_locked ? "  [camera locked]" : "");
            gui_text("camera %.2f %.2f %.2f  fov %.1f", (double)v->eye[0], (double)v->eye[1], (double)v->eye[2],
                     (double)v->fov);
            if (v->test) {
                const test_run *t = v->test;
                gui_text_colored(1.0f, 0.85f, 0.3f, "test mode: cycle %d/%d, camera %d/%d, method %d/%d",
                                 t->cycle + 1, v->o.cycles, t->camera + 1, t->camera_count, t->method + 1,
                                 t->method_count);
            }
            if (v->message[0] && v->clock < v->message_until) {
                if (v->message_error) gui_text_colored(1.0f, 0.4f, 0.4f, "%s", v->message);
                else gui_text_colored(0.6f, 1.0f, 0.6f, "%s", v->message);
            }
        }
        gui_end();
        float panel_w = 380.0f, x = (float)v->fb_width - panel_w - 10.0f;
        if (gui_begin("Obscura", x > 0.0f ? x : 0.0f, 10.0f, panel_w, (float)v->fb_height - 20.0f)) {
            if (gui_header("Method and filter", true)) panel_method(v);
            if (gui_header("Profiler", true)) panel_profiler(v);
            if (gui_header("Camera and display", false)) panel_display(v);
            if (gui_header("Lights and shadows", false)) panel_lights(v);
            if (gui_header("HDR", false)) panel_hdr(v);
            if (gui_header("Keys", false))
                gui_text("WASD move, Q/E down/up, Shift faster\nright mouse: look, scroll: zoom\n1-9, Tab: "
                         "camera presets, L: lock camera\nM: method, V: view, F1/H: panel\nF3: vsync, P/F12: "
                         "screenshot\nR: reload shaders, Esc: quit");
        }
        gui_end();
    }
    gui_render();
}

/* ---- scripted events ----------------------------------------------------------------------- */
static void run_script_events(viewer *v)
{
    while (v->next_event < v->event_count && v->events[v->next_event].t <= v->clock + 1e-9) {
        const script_event *e = &v->events[v->next_event++];
        switch (e->kind) {
        case EV_KEY:
            if (e->action == 2) {
                handle_key(v, e->code, GLFW_PRESS, 0);
                handle_key(v, e->code, GLFW_RELEASE, 0);
            } else {
                int mods = v->keys[GLFW_KEY_LEFT_SHIFT] || v->keys[GLFW_KEY_RIGHT_SHIFT] ? GLFW_MOD_SHIFT : 0;
                handle_key(v, e->code, e->action, mods);
            }
            break;
        case EV_MOUSE: handle_mouse_button(v, e->code, e->action); break;
        case EV_MOVE: handle_cursor(v, e->x, e->y); break;
        case EV_SCROLL: handle_scroll(v, e->y); break;
        case EV_METHOD: select_method_by_name(v, e->arg); break;
        case EV_FILTER:
            if (ob_settings_set_filter(&v->s, e->arg) != OB_OK) say(v, true, "unknown filter '%s'", e->arg);
            break;
        case EV_SET:
            if (ob_settings_set(&v->s, e->arg) != OB_OK) {
                const char *msg = "";
                ob_get_error(&msg);
                say(v, true, "%s", msg);
            }
            break;
        case EV_CAMERA: {
            bool found = false;
            for (int i = 0; i < ob_query_camera_count(v->scene) && !found; ++i) {
                char index[16];
                snprintf(index, sizeof index, "%d", i);
                if (!strcmp(ob_query_camera(v->scene, i).name, e->arg) || !strcmp(index, e->arg)) {
                    use_camera(v, i);
                    found = true;
                }
            }
            if (!found) say(v, true, "unknown camera '%s'", e->arg);
            break;
        }
        case EV_VIEW: {
            bool found = false;
            for (int i = 0; i < OB_VIEW_COUNT && !found; ++i)
                if (!strcmp(ob_view_name((ob_view)i), e->arg)) {
                    set_view(v, i);
                    found = true;
                }
            if (!found) say(v, true, "unknown view '%s'", e->arg);
            break;
        }
        case EV_SCREENSHOT: break; /* taken after the frame is drawn: see frame() */
        case EV_QUIT: v->quit = true; break;
        case EV_CLOSE: glfwSetWindowShouldClose(v->window, GLFW_TRUE); break; /* as the close button */
        case EV_RESIZE: glfwSetWindowSize(v->window, (int)e->x, (int)e->y); break; /* as dragging its edge */
        }
        if (e->kind == EV_SCREENSHOT) {
            --v->next_event; /* frame() takes it once this frame is on the back buffer */
            return;
        }
    }
}

/* ---- test mode ------------------------------------------------------------------------------ */
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
static int test_finish(viewer *v)
{
    test_run *t = v->test;
    size_t cap = 4096 + (size_t)t->camera_count * (size_t)t->method_count * 512;
    char *csv = malloc(cap);
    if (!csv) return cli_fail(EXIT_RUNTIME, "out of memory writing the log");
    size_t n = 0;
    n += (size_t)snprintf(csv + n, cap - n, "scene,camera,method,width,height,cycles,frames,seconds,fps,fps_min,fps_max,frame_ms");
    for (int p = 0; p < PASS_ORDER_COUNT; ++p) n += (size_t)snprintf(csv + n, cap - n, ",%s_ms", pass_order[p]);
    n += (size_t)snprintf(csv + n, cap - n, "\n");
    printf("obscura view --test-mode: %s, %dx%d, %d cycle(s) of %.2f s per camera x method, %s\n",
           ob_query_scene_name(v->scene), v->fb_width, v->fb_height, v->o.cycles, (double)v->o.seconds,
           ob_query_renderer(v->ctx));
    printf("%-16s", "FPS");
    for (int m = 0; m < t->method_count; ++m) printf(" %12s", ob_method_at(t->methods[m])->name);
    printf("\n");
    for (int c = 0; c < t->camera_count; ++c) {
        ob_camera cam = ob_query_camera(v->scene, c);
        printf("%-16.16s", cam.name);
        for (int m = 0; m < t->method_count; ++m) {
            const test_cell *cell = &t->cells[(size_t)c * (size_t)t->method_count + (size_t)m];
            double lo = INFINITY, hi = 0.0;
            for (int k = 0; k < v->o.cycles; ++k) {
                lo = cell->fps[k] < lo ? cell->fps[k] : lo;
                hi = cell->fps[k] > hi ? cell->fps[k] : hi;
            }
            double fps = cell->seconds > 0.0 ? (double)cell->frames / cell->seconds : 0.0;
            printf(" %12.2f", fps);
            n += (size_t)snprintf(csv + n, cap - n, "%s,%s,%s,%d,%d,%d,%ld,%.4f,%.3f,%.3f,%.3f,%.3f",
                                  ob_query_scene_name(v->scene), cam.name, ob_method_at(t->methods[m])->name,
                                  v->fb_width, v->fb_height, v->o.cycles, cell->frames, cell->seconds, fps, lo, hi,
                                  cell->frames > 0 ? 1000.0 * cell->seconds / (double)cell->frames : 0.0);
            for (int p = 0; p < PASS_ORDER_COUNT; ++p) {
                if (cell->pass_calls[p] > 0)
                    n += (size_t)snprintf(csv + n, cap - n, ",%.4f", cell->pass_ms[p] / (double)cell->pass_calls[p]);
                else
                    n += (size_t)snprintf(csv + n, cap - n, ",");
            }
            n += (size_t)snprintf(csv + n, cap - n, "\n");
        }
        printf("\n");
    }
    int code = EXIT_OK;
    if (ob_write_text(v->o.log, csv) != OB_OK) code = cli_fail_library_as(EXIT_OUTPUT);
    else printf("log: %s; screenshots: %s/\n", v->o.log, t->dir);
    free(csv);
    return code;
}

/* After each frame: count it into the slot, and move on when the slot's time is up. */
static void test_step(viewer *v, const ob_pass_timing *timings, int n)
{
    test_run *t = v->test;
    double now = glfwGetTime();
    if (!t->warmed) {
        /* The slot's first frame pays for shader compiles and first-use allocations. */
        t->warmed = true;
        t->slot_start = now;
        return;
    }
    test_cell *cell = &t->cells[(size_t)t->camera * (size_t)t->method_count + (size_t)t->method];
    ++t->slot_frames;
    for (int i = 0; i < n; ++i) {
        int col = pass_column(timings[i].name);
        if (col < 0) continue;
        cell->pass_ms[col] += timings[i].ms;
        ++cell->pass_calls[col];
    }
    double elapsed = now - t->slot_start;
    if (elapsed < (double)v->o.seconds) return;
    cell->fps[t->cycle] = (double)t->slot_frames / elapsed;
    cell->frames += t->slot_frames;
    cell->seconds += elapsed;
    if (t->cycle == v->o.cycles - 1) {
        /* One screenshot per camera x method, of the image alone (the panel would hide it). */
        size_t bytes = ob_image_size(v->r, OB_IMAGE_FINAL_RGBA8);
        unsigned char *px = malloc(bytes);
        char cam[80], path[4400];
        safe_name(ob_query_camera(v->scene, t->camera).name, cam, sizeof cam);
        snprintf(path, sizeof path, "%s/%s_%s_%s.png", t->dir, ob_query_scene_name(v->scene), cam,
                 ob_method_at(t->methods[t->method])->name);
        if (!px || ob_read_image(v->r, OB_IMAGE_FINAL_RGBA8, px, bytes) != OB_OK ||
            ob_write_png(path, v->fb_width, v->fb_height, 4, px) != OB_OK) {
            const char *msg = "";
            ob_get_error(&msg);
            fprintf(stderr, "obscura view: screenshot %s failed: %s\n", path, msg);
            v->exit_code = EXIT_OUTPUT;
            v->quit = true;
        }
        free(px);
    }
    if (++t->method == t->method_count) {
        t->method = 0;
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

static int test_init(viewer *v)
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
    test_apply_slot(v);
    return 0;
}

/* ---- the frame ----------------------------------------------------------------------------- */
static bool frame(viewer *v, double dt)
{
    int w = 0, h = 0;
    glfwGetFramebufferSize(v->window, &w, &h);
    if (w <= 0 || h <= 0) return true; /* minimised: nothing to draw */
    if (w != v->fb_width || h != v->fb_height) {
        if (ob_renderer_resize(v->r, w, h) != OB_OK) {
            const char *msg = "";
            ob_get_error(&msg);
            say(v, true, "resize to %dx%d failed: %s", w, h, msg);
            return false;
        }
        v->fb_width = w;
        v->fb_height = h;
        profiler_reset(&v->prof);
    }
    if (v->events) run_script_events(v);
    move_camera(v, dt);
    ob_camera cam = current_camera(v);
    bool ok = ob_render_frame(v->r, &cam, &v->s) == OB_OK;
    ob_pass_timing timings[MAX_PASSES];
    int n = 0;
    if (ok) {
        n = ob_query_timings(v->r, timings, MAX_PASSES);
        ok = ob_present(v->r, v->view, 0, 0, 0, w, h) == OB_OK;
    }
    if (!ok) {
        /* A setting the renderer refuses (e.g. the environment ambient with no map): say so and
         * show the background rather than a stale frame. */
        const char *msg = "";
        ob_get_error(&msg);
        if (strcmp(msg, v->message) != 0 || v->clock >= v->message_until) say(v, true, "%s", msg);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, w, h);
        glClearColor(0.1f, 0.0f, 0.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, w, h);
    build_gui(v);
    if (v->events && v->next_event < v->event_count && v->events[v->next_event].kind == EV_SCREENSHOT &&
        v->events[v->next_event].t <= v->clock + 1e-9) {
        save_screenshot(v, v->events[v->next_event].arg);
        ++v->next_event;
    }
    glfwSwapBuffers(v->window);
    if (ok) {
        profiler_add(&v->prof, timings, n, v->last_frame_ms);
        if (v->test) test_step(v, timings, n);
    }
    return ok;
}

static int run(viewer *v)
{
    double last = glfwGetTime();
    v->fps_window_start = last;
    bool first = true;
    while (!v->quit) {
        glfwPollEvents();
        if (glfwWindowShouldClose(v->window)) v->quit = true;
        if (v->quit) break;
        double now = glfwGetTime();
        double wall_dt = now - last;
        last = now;
        /* A script replays on a simulated clock: 1/30 s per frame, whatever the frame took. */
        double dt = v->events ? 1.0 / 30.0 : (first ? 0.0 : wall_dt);
        if (!first) v->last_frame_ms = 1000.0 * wall_dt;
        bool ok = frame(v, dt);
        if (first && !ok) {
            /* The first frame failing (a shader, no memory) is not something a person can fix
             * from the panel. */
            return cli_fail(EXIT_RUNTIME, "%s", v->message);
        }
        first = false;
        v->clock += dt;
        ++v->fps_window_frames;
        double window = glfwGetTime() - v->fps_window_start;
        if (window >= 0.5) {
            v->fps = (double)v->fps_window_frames / window;
            v->fps_window_frames = 0;
            v->fps_window_start = glfwGetTime();
        }
    }
    if (v->exit_code != EXIT_OK) return v->exit_code;
    if (v->test) {
        if (!v->test->done) return cli_fail(EXIT_RUNTIME, "test mode stopped before the end: no log written");
        return test_finish(v);
    }
    return EXIT_OK;
}

static int setup_settings(viewer *v)
{
    const view_opts *o = &v->o;
    if (ob_settings_init(&v->s, o->method) != OB_OK) return cli_fail_from_library();
    for (int m = 0; m < ob_method_count() && m < MAX_METHODS; ++m) {
        ob_settings tmp;
        ob_settings_init(&tmp, ob_method_at(m)->name);
        memcpy(v->method_params[m], tmp.params, sizeof tmp.params);
    }
    if (ob_settings_set_filter(&v->s, o->filter) != OB_OK || ob_settings_set_ao_scale(&v->s, o->ao_scale) != OB_OK)
        return cli_fail_from_library();
    v->s.adaptive = o->adaptive;
    if (o->shadow_method >= 0) v->s.shadow.method = (ob_shadow_method)o->shadow_method;
    if (o->shadow_size > 0) v->s.shadow.size = o->shadow_size;
    /* Scenes are static: the maps only change with the lights or the shadow settings, not with
     * the camera (on llvmpipe FZK-Haus's sun + 2 cube maps cost 500+ ms a frame otherwise). */
    v->s.shadow.reuse = true;
    v->s.hdr.enabled = !o->hdr_off;
    if (o->quality_samples > 0) {
        static const int counts[] = {12, 24, 36, 64};
        for (int q = 0; q < 4; ++q)
            if (counts[q] == o->quality_samples) v->quality = q + 1;
        ob_error err = ob_settings_set_samples(&v->s, o->quality_samples);
        if (err != OB_OK && err != OB_ERR_INVALID_ARGUMENT) return cli_fail_from_library();
    }
    /* --set may name any method (ssao.radius=...): it goes to that method's stored values. */
    for (int i = 0; i < o->set_count; ++i) {
        const char *dot = strchr(o->sets[i], '.'), *eq = strchr(o->sets[i], '=');
        int m = v->s.method;
        if (dot && eq && dot < eq) {
            char name[64];
            snprintf(name, sizeof name, "%.*s", (int)(dot - o->sets[i]), o->sets[i]);
            if (ob_find_method(name) >= 0) m = ob_find_method(name);
        }
        int current = v->s.method;
        if (m != current) select_method(v, m);
        ob_error err = ob_settings_set(&v->s, o->sets[i]);
        if (m != current) select_method(v, current);
        if (err != OB_OK) return cli_fail_from_library();
    }
    /* The scene's lights as explicit ones, so the panel can edit them. */
    v->s.light_count = ob_query_scene_light_count(v->scene);
    if (v->s.light_count > OB_MAX_LIGHTS) v->s.light_count = OB_MAX_LIGHTS;
    for (int i = 0; i < v->s.light_count; ++i) v->s.lights[i] = ob_query_scene_light(v->scene, i);
    if (o->env) v->s.ambient_mode = OB_AMBIENT_ENVIRONMENT;
    return 0;
}

int cmd_view(int argc, char **argv)
{
    viewer *v = calloc(1, sizeof *v);
    if (!v) return cli_fail(EXIT_RUNTIME, "out of memory");
    int code = parse_view_opts(argc, argv, &v->o);
    if (code != 0) {
        free(v);
        return code < 0 ? EXIT_OK : code;
    }
    /* Everything that can be checked without a window is, first: the script, the scene, the
     * settings. */
    if (v->o.script && (code = load_script(v->o.script, &v->events, &v->event_count)) != 0) {
        free(v);
        return code;
    }
    v->scene = ob_load_scene(&(ob_scene_desc){.name = v->o.scene, .sidecar = v->o.sidecar, .up = v->o.up});
    if (!v->scene) {
        code = cli_fail_from_library();
        goto done;
    }
    if ((code = setup_settings(v)) != 0) goto done;
    v->camera_index = 0;
    if (v->o.camera) {
        ob_camera found;
        if (ob_find_camera(v->scene, v->o.camera, &found) != OB_OK) {
            code = cli_fail_from_library();
            goto done;
        }
        for (int i = 0; i < ob_query_camera_count(v->scene); ++i)
            if (!strcmp(ob_query_camera(v->scene, i).name, found.name)) v->camera_index = i;
    }
    use_camera(v, v->camera_index);
    ob_scene_stats st = ob_query_scene_stats(v->scene);
    float diag[3] = {st.bounds_max[0] - st.bounds_min[0], st.bounds_max[1] - st.bounds_min[1],
                     st.bounds_max[2] - st.bounds_min[2]};
    v->scene_size = vlen(diag) > 0.0f ? vlen(diag) : 1.0f;
    v->speed = 0.1f * v->scene_size; /* ten seconds across the scene */
    v->gui_visible = v->o.gui;
    v->vsync = v->o.vsync;
    v->shot_dir = v->o.shots ? v->o.shots : "screenshots";

    if (!getenv("DISPLAY") && !getenv("WAYLAND_DISPLAY")) {
        code = cli_fail(EXIT_NO_GPU, "view needs a display: DISPLAY is not set (on a server: xvfb-run -a obscura view ...)");
        goto done;
    }
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) {
        code = cli_fail(EXIT_NO_GPU, "view: no window system: %s", glfw_message);
        goto done;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
    glfwWindowHint(GLFW_SRGB_CAPABLE, GLFW_FALSE); /* the library writes sRGB bytes itself */
    v->window = glfwCreateWindow(v->o.width, v->o.height, "Obscura", NULL, NULL);
    if (!v->window) {
        code = cli_fail(EXIT_NO_GPU, "view: no OpenGL 4.5 core window: %s", glfw_message);
        glfwTerminate();
        goto done;
    }
    glfwMakeContextCurrent(v->window);
    glfwSwapInterval(v->vsync && !v->o.test_mode ? 1 : 0);
    glfwSetWindowUserPointer(v->window, v);
    glfwSetKeyCallback(v->window, on_key);
    glfwSetMouseButtonCallback(v->window, on_mouse_button);
    glfwSetCursorPosCallback(v->window, on_cursor);
    glfwSetScrollCallback(v->window, on_scroll);
    glfwSetWindowCloseCallback(v->window, on_close);
    v->ctx = ob_make_context(&(ob_context_desc){.use_current = true});
    if (!v->ctx) {
        code = cli_fail_from_library();
        goto close;
    }
    glfwGetFramebufferSize(v->window, &v->fb_width, &v->fb_height);
    v->r = ob_make_renderer(v->ctx, &(ob_renderer_desc){.width = v->fb_width, .height = v->fb_height});
    if (!v->r || ob_renderer_set_scene(v->r, v->scene) != OB_OK ||
        (v->o.env && ob_renderer_set_environment(v->r, v->o.env) != OB_OK)) {
        code = cli_fail_from_library();
        goto close;
    }
    if (!gui_init(v->window)) {
        code = cli_fail(EXIT_NO_GPU, "view: Dear ImGui could not start on this context");
        goto close;
    }
    update_title(v);
    if (v->o.test_mode && (code = test_init(v)) != 0) goto close_gui;
    code = run(v);
close_gui:
    gui_shutdown();
close:
    ob_destroy_renderer(v->r);
    ob_destroy_context(v->ctx);
    glfwDestroyWindow(v->window);
    glfwTerminate();
done:
    if (v->test) free(v->test->cells);
    free(v->test);
    free(v->events);
    ob_destroy_scene(v->scene);
    free(v);
    return code;
}
