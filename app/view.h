/* obscura view's internal interface: the viewer struct every app/view_*.c file works on, and the
 * functions one of them calls in another. The files split the viewer by concern (see view.c's
 * header for the whole); what only one file uses stays static there. */
#ifndef OB_VIEW_H
#define OB_VIEW_H

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <stdbool.h>
#include <stdint.h>

#include "cli.h"
#include "cli_options.h"
#include "view_gui.h"

/* Fixed capacities: registry sizes, timed passes, scene presets and --cycles' upper bound. */
enum { MAX_METHODS = 32, MAX_PASSES = 16, MAX_CAMERAS = 64, MAX_CYCLES = 100 };

/* Stereo display (Belonogov 2018 §5.2): mono, both eyes side by side ("Mirror"), or the left eye alone
 * in the whole window ("SinglePass"); both eyes are rendered in either stereo mode. */
typedef enum view_stereo { VIEW_MONO = 0, VIEW_MIRROR, VIEW_SINGLE, VIEW_STEREO_COUNT } view_stereo;
extern const char *const view_stereo_names[VIEW_STEREO_COUNT]; /* "mono", "mirror", "single" */

/* The headset's frame budget: 90 Hz (Belonogov 2018 §5.2, the HTC Vive). */
#define VIEW_VR_BUDGET_MS (1000.0 / 90.0)

/* ---- options (view_options.c) ---------------------------------------------------------------- */
typedef struct view_opts {
    /* Scene, camera, window size, method, filter, --set, quality, lights, shadows, ambient and
     * HDR: the options every rendering command shares (app/cli_options.h). */
    cli_common common;
    const char *shots, *script, *log, *methods;
    bool vsync, gui, test_mode;
    view_stereo stereo;
    float ipd; /* eye separation, world units */
    int cycles;
    float seconds;
} view_opts;

/* 0 to go on, -1 after --help (printed), else the exit code (the message printed). */
int parse_view_opts(int argc, char **argv, view_opts *o);

/* ---- profiler (view_profiler.c) -------------------------------------------------------------- */
/* One pass's GPU time (timestamp queries) and CPU time (the calling thread issuing it), ms. */
typedef struct time_stats {
    double current, sum, min, max; /* current: in the newest timed frame, NAN if it did not run there */
} time_stats;

typedef struct pass_stats {
    const char *name;
    time_stats gpu, cpu;
    long calls;                    /* timed frames it ran in: a pass that ran once is averaged once */
} pass_stats;

typedef struct profiler {
    pass_stats pass[MAX_PASSES];
    int count;
    double frame_sum, frame_min, frame_max; /* wall-clock frame time, ms */
    long frames;
    /* Each timed frame's sum of its own passes (what the GPU spent on that frame, and the CPU
     * issuing it), ms: a pass that ran in one frame only (the shadow maps, then cached) is in that
     * frame's sum alone. */
    time_stats gpu, cpu;
    long gpu_frames;
    long long gpu_frame;   /* the renderer's frame the last timings described (ob_query_timings_frame) */
    long long first_frame; /* the first frame counted since the reset, -1 until the next add sets it */
    /* Stereo: each eye's GPU sum of passes (the pass rows above hold both eyes summed). */
    double eye_current[2], eye_sum[2], stereo_max;
    long stereo_frames, over_budget;
} profiler;

/* ---- the viewer ------------------------------------------------------------------------------ */
typedef struct script_event script_event; /* view_script.c */
typedef struct test_run test_run;         /* view_testmode.c */
typedef struct view_reference view_reference; /* view_reference.c */

typedef struct viewer {
    view_opts o;
    GLFWwindow *window;
    ob_context *ctx;
    ob_renderer *r;         /* mono, or the left eye */
    ob_renderer *right;     /* the right eye in stereo (made on the first stereo frame) */
    view_stereo stereo;
    int eye_width, eye_height; /* each renderer's size: the window, or half its width in mirror */
    ob_scene *scene;
    ob_settings s;
    float method_params[MAX_METHODS][OB_MAX_PARAMS]; /* each method keeps its own values */
    uint32_t method_set[MAX_METHODS];
    float method_radius_scale[MAX_METHODS]; /* and its own radius_scale (--settings may tune it) */
    int quality;            /* 0 = the methods' defaults, 1..4 = low..ultra */
    ob_view view;
    /* camera: eye, unit forward and world up; presets from the scene */
    int camera_index;
    float eye[3], fwd[3], up[3];
    float fov, speed, scene_size;
    bool camera_locked, gui_visible, vsync;
    /* --path / --orbit: the camera follows it while playing (Space: play/pause), one path frame per
     * rendered frame, from path_frame */
    bool path_playing;
    int path_frame;
    bool keys[GLFW_KEY_LAST + 1];
    bool look;              /* right button held */
    double mouse_x, mouse_y;
    bool mouse_known;
    int fb_width, fb_height;
    /* The window's layout (view_layout): the panel docked in a column at the right edge, and the
     * picture (the scene, both eyes or the reference view's panes) in the rest, with the window's
     * shape scaled to fit and centred, bars above and below; framebuffer pixels from the top left.
     * The panel never covers the picture; the overlay's lines sit on the bars (over the picture
     * only in test mode, whose window is all picture, or where a narrow panel leaves thin bars). */
    int pic_x, pic_y, pic_w, pic_h;
    float panel_width;   /* the panel's column, px; 0 while it is hidden (F1, test mode) */
    float panel_dragged; /* the width its left edge was dragged to, 0 if never */
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
    bool shot_requested;    /* P, F12 or the panel's button: the window, once this frame is drawn */
    gui_mouse script_mouse; /* a script's mouse, which ImGui sees instead of the system's */
    view_reference *ref;    /* the reference view (G): NULL until first used */
    script_event *events;
    int event_count, next_event;
    test_run *test;
    char title[256];
} viewer;

/* ---- view.c: the window and the frame loop --------------------------------------------------- */
/* A message in the overlay for four seconds, and on stderr. */
void say(viewer *v, bool error, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
/* The window's title names the scene, the method and whether a debug view shows. */
void update_title(viewer *v);
/* The back buffer as PNG, as it is now: the picture alone (picture_only; take it before the GUI is
 * drawn: no overlay) or the whole window as shown (after); path NULL: a new name in the shot
 * directory, which is made then (never before a screenshot is taken). */
void save_screenshot(viewer *v, const char *path, bool picture_only);
/* Development builds: a new renderer from the shaders on disk, the old one kept if it fails. */
void reload_shaders(viewer *v);

/* ---- view_settings.c: the settings being rendered -------------------------------------------- */
/* ob_settings from the options (method, filter, --set, shadows, HDR) and the scene's lights. */
int setup_settings(viewer *v);
/* Switch method (index wraps), keeping each method's own parameter values. */
void select_method(viewer *v, int index);
/* select_method by name; an unknown one is said and changes nothing. */
bool select_method_by_name(viewer *v, const char *name);
/* Switch the debug view (index wraps). */
void set_view(viewer *v, int index);

/* ---- view_camera.c: the fly camera and the input that drives it ------------------------------ */
/* Normalise a 3-vector in place (zero stays zero). */
void vnorm(float a[3]);
/* The starting preset (--camera) and the movement speed from the scene's size. */
int camera_setup(viewer *v);
/* Make preset index (wrapping) the current camera. */
void use_camera(viewer *v, int index);
/* The camera to render now. */
/* --path / --orbit while playing: the camera of the next path frame. */
void follow_path(viewer *v);
ob_camera current_camera(const viewer *v);
/* Move by the held keys over dt seconds. */
void move_camera(viewer *v, double dt);
/* The GLFW callbacks that feed the handle_* functions below. */
void input_attach(viewer *v);
/* One input event, from GLFW or a script. */
void handle_key(viewer *v, int key, int action, int mods);
void handle_mouse_button(viewer *v, int button, int action);
void handle_cursor(viewer *v, double x, double y);
void handle_scroll(viewer *v, double dy);

/* ---- view_script.c: timed input events ------------------------------------------------------- */
/* Read and check a whole script before any window opens; 0 or the exit code. */
int load_script(const char *path, script_event **out, int *count);
/* Apply the events due on the clock, stopping at a screenshot (see script_screenshot). */
void run_script_events(viewer *v);
/* Take the screenshots due now, once the frame is on the back buffer: with_ui false before the
 * GUI is drawn (`screenshot`: the image alone), true after (`screenshot_ui`: the window). */
void script_screenshot(viewer *v, bool with_ui);

/* ---- view.c ---------------------------------------------------------------------------------- */
/* The newest timed frame's passes (both eyes summed in stereo, each eye's sum in eye_ms) and its
 * number (*timed; *rendered: the last rendered), waiting for the GPU first when `wait`. Returns
 * the count (at most MAX_PASSES). */
int view_timings(viewer *v, bool wait, ob_pass_timing *t, double eye_ms[2], long long *timed, long long *rendered);

/* ---- view_profiler.c ------------------------------------------------------------------------- */
/* Forget every statistic (after a change that makes the old ones meaningless). */
void profiler_reset(profiler *p);
/* Count one wall-clock frame (frame_ms <= 0: the first frame, which has no interval yet) and, when
 * `timed` names a frame not counted yet and rendered after the reset, its pass timings (`timed`
 * and `rendered` from ob_query_timings_frame). Returns whether the timings were counted. */
bool profiler_add_frame(profiler *p, const ob_pass_timing *t, int n, long long timed, long long rendered,
                        double frame_ms);
/* Count one stereo frame's per-eye GPU sums (after profiler_add with both eyes' passes summed). */
void profiler_add_eyes(profiler *p, const double eye_ms[2]);
/* The profiler's table in the panel. */
void panel_profiler(viewer *v);

/* ---- view_panel.c ---------------------------------------------------------------------------- */
/* The layout of a w x h framebuffer (pic_*, panel_width) for this frame: the panel's column when
 * it shows, the picture in the rest. */
void view_layout(viewer *v, int w, int h);
/* Whether (x, y), in window pixels from the top left, is on the picture (the mouse's camera
 * control starts only there). */
bool view_in_picture(const viewer *v, double x, double y);
/* The overlay and the panel for this frame, drawn into the current framebuffer. */
void build_gui(viewer *v);

/* ---- view_reference.c: the reference view (G) ------------------------------------------------ */
/* Whether the reference view is on (then view_reference_frame draws the window's image). */
bool view_reference_on(const viewer *v);
/* Turn the reference view on (tracing AO_R for the current camera unless it is the one shown) or
 * off (stopping a trace under way). */
void view_reference_toggle(viewer *v);
/* A trace is under way on its worker thread (a script's clock waits for it). */
bool view_reference_busy(const viewer *v);
/* The four panes in the picture's place: the method's AO, the reference, the signed error and the
 * current view, each half the picture each way. False with the library's error in v->message. */
bool view_reference_frame(viewer *v);
/* The panes' labels (ImGui; drawn even with the panel hidden) and the panel's section. */
void view_reference_labels(viewer *v);
void panel_reference(viewer *v);
/* One line for the overlay while a trace is under way or the view is on (then has_status). */
bool view_reference_has_status(const viewer *v);
void view_reference_overlay(const viewer *v);
/* The AO radius R the current method is graded at (its radius, else the scene's). */
float view_ao_radius(const viewer *v);
/* Stop any trace, free the renderer and the GL objects (the context still current). */
void view_reference_free(viewer *v);

/* ---- view_testmode.c: every camera x method, timed ------------------------------------------- */
/* Check --methods and the screenshot directory and start the first slot; 0 or the exit code. */
int test_init(viewer *v);
/* Count a drawn frame's timings into the current slot (those of frames the slot rendered, after its
 * first) and move on when its time is up. */
void test_step(viewer *v);
/* The summary table and the CSV log, or a failure when the run stopped early. */
int test_finish(viewer *v);
/* The test mode's progress line in the overlay. */
void test_overlay(const viewer *v);
/* Free a test run (NULL is fine). */
void test_free(test_run *t);

#endif
