/* obscura view: the interactive viewer (Puri 2024 §2.7, §3.5; Belonogov 2018 §5.1's profiler).
 *
 * A GLFW window whose GL 4.5 context the library adopts (ob_context_desc.use_current), so every
 * frame goes through the very ob_render_frame the CLI and the tests use; ob_present blits the
 * result (or a debug view) into the picture's part of the window and Dear ImGui draws the panel in
 * a column beside it (view_layout). The panel is generated from the method and filter registries'
 * parameter tables, like `obscura list` and `--set`.
 *
 * Three ways to drive it: a person (keys, mouse, panel), a script of timed input events
 * (--script, replayed on a simulated clock so it runs the same on any machine) and the automatic
 * test mode (--test-mode: every camera preset x every method, timed, logged to CSV with a
 * screenshot each).
 *
 * This file holds the window, the viewer's lifecycle and the frame loop; the rest is split by
 * concern behind view.h: view_options.c (options, help), view_settings.c (the ob_settings being
 * rendered), view_camera.c (camera and input), view_script.c (--script), view_profiler.c,
 * view_panel.c (the ImGui panel) and view_testmode.c (--test-mode). */
#include <epoxy/gl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include "view.h"
#include "view_gui.h"

static char glfw_message[512];

static void on_glfw_error(int code, const char *description)
{
    snprintf(glfw_message, sizeof glfw_message, "%s (GLFW error 0x%x)", description ? description : "?", code);
}

void say(viewer *v, bool error, const char *fmt, ...)
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

void update_title(viewer *v)
{
    /* --set switches methods while the settings are built, before the window exists (GLFW
     * asserts on a NULL window); cmd_view sets the title once the window is open. */
    if (!v->window) return;
    char title[256] = "";
    snprintf(title, sizeof title, "Obscura - %s - %s%s", ob_query_scene_name(v->scene), ob_method_at(v->s.method)->name,
             v->view == OB_VIEW_FINAL ? "" : " (debug view)");
    if (strcmp(title, v->title) != 0) {
        snprintf(v->title, sizeof v->title, "%s", title);
        glfwSetWindowTitle(v->window, title);
    }
}

/* ---- screenshots --------------------------------------------------------------------------- */
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

/* The window as it shows now (image and panel), or the picture's part of it: the back buffer,
 * before the swap. */
void save_screenshot(viewer *v, const char *path, bool picture_only)
{
    char default_path[4200] = "";
    if (!path) {
        default_shot_path(v, default_path, sizeof default_path);
        path = default_path;
    }
    int x = 0, y = 0, w = v->fb_width, h = v->fb_height;
    if (picture_only) {
        x = v->pic_x;
        y = v->fb_height - v->pic_y - v->pic_h; /* GL's rows run bottom to top */
        w = v->pic_w;
        h = v->pic_h;
    }
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
    glReadPixels(x, y, w, h, GL_RGBA, GL_UNSIGNED_BYTE, px);
    for (int r = 0; r < h; ++r) memcpy(flipped + (size_t)r * row, px + (size_t)(h - 1 - r) * row, row);
    for (size_t i = 3; i < row * (size_t)h; i += 4) flipped[i] = 255; /* the window's alpha is not the image's */
    /* Only the default name's directory is made, and only now: a viewer that takes no screenshot
     * leaves nothing behind, and a script's or --shots path's directory must exist. */
    if (path == default_path) mkdir(v->shot_dir, 0777);
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
void reload_shaders(viewer *v)
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
    ob_renderer *fresh = ob_make_renderer(v->ctx, &(ob_renderer_desc){.width = v->eye_width, .height = v->eye_height});
    ob_camera cam = current_camera(v);
    bool ok = fresh && ob_renderer_set_scene(fresh, v->scene) == OB_OK &&
              (!v->o.common.env || ob_renderer_set_environment(fresh, v->o.common.env) == OB_OK) &&
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
    /* The right eye is made again, from the same shaders, by the next stereo frame. */
    ob_destroy_renderer(v->right);
    v->right = NULL;
    profiler_reset(&v->prof);
    say(v, false, "shaders reloaded from %s", dir);
#else
    say(v, false, "shader reload is for development builds (CMAKE_BUILD_TYPE other than Release)");
#endif
}

/* ---- the frame ----------------------------------------------------------------------------- */
const char *const view_stereo_names[VIEW_STEREO_COUNT] = {"mono", "mirror", "single"};

/* Each renderer at the eye's size (the picture's, or half its width in mirror), the right eye's
 * renderer made when stereo first needs it. */
static bool fit_renderers(viewer *v, int w, int h)
{
    int ew = v->stereo == VIEW_MIRROR ? (w / 2 > 0 ? w / 2 : 1) : w;
    const char *msg = "";
    if (ew != v->eye_width || h != v->eye_height) {
        if (ob_renderer_resize(v->r, ew, h) != OB_OK || (v->right && ob_renderer_resize(v->right, ew, h) != OB_OK)) {
            ob_get_error(&msg);
            say(v, true, "resize to %dx%d failed: %s", ew, h, msg);
            return false;
        }
        v->eye_width = ew;
        v->eye_height = h;
        profiler_reset(&v->prof);
    }
    if (v->stereo != VIEW_MONO && !v->right) {
        v->right = ob_make_renderer(v->ctx, &(ob_renderer_desc){.width = ew, .height = h});
        if (!v->right || ob_renderer_set_scene(v->right, v->scene) != OB_OK ||
            (v->o.common.env && ob_renderer_set_environment(v->right, v->o.common.env) != OB_OK)) {
            ob_get_error(&msg);
            say(v, true, "no renderer for the right eye, back to mono: %s", msg);
            ob_destroy_renderer(v->right);
            v->right = NULL;
            v->stereo = VIEW_MONO;
            return fit_renderers(v, w, h);
        }
    }
    return true;
}

/* Both eyes' passes as one list (the stereo frame's cost per pass), and each eye's sum. */
static int merge_timings(ob_pass_timing *t, int n, const ob_pass_timing *right, int rn, double eye_ms[2])
{
    eye_ms[0] = eye_ms[1] = 0.0;
    for (int i = 0; i < n; ++i) eye_ms[0] += t[i].ms;
    for (int i = 0; i < rn; ++i) {
        eye_ms[1] += right[i].ms;
        int k = 0;
        while (k < n && strcmp(t[k].name, right[i].name) != 0) ++k;
        if (k < n) {
            t[k].ms += right[i].ms;
            t[k].cpu_ms += right[i].cpu_ms;
        } else if (n < MAX_PASSES) {
            t[n++] = right[i];
        }
    }
    return n;
}

int view_timings(viewer *v, bool wait, ob_pass_timing *t, double eye_ms[2], long long *timed, long long *rendered)
{
    if (wait && (ob_wait_timings(v->r) != OB_OK || (v->right && ob_wait_timings(v->right) != OB_OK))) return 0;
    int n = ob_query_timings(v->r, t, MAX_PASSES);
    ob_query_timings_frame(v->r, timed, rendered);
    eye_ms[0] = eye_ms[1] = 0.0;
    for (int i = 0; i < n; ++i) eye_ms[0] += t[i].ms;
    if (v->stereo != VIEW_MONO && v->right) {
        /* The eyes render in lockstep, so the right eye's newest timed frame is the left's or the
         * one before: close enough for per-pass averages, and a wait makes them the same. */
        ob_pass_timing right[MAX_PASSES];
        n = merge_timings(t, n, right, ob_query_timings(v->right, right, MAX_PASSES), eye_ms);
    }
    return n;
}

/* The scene in the picture's place: mono, both eyes, or the reference view's panes. */
static bool draw_image(viewer *v)
{
    if (view_reference_on(v)) return view_reference_frame(v);
    const int x = v->pic_x, y = v->fb_height - v->pic_y - v->pic_h, w = v->pic_w, h = v->pic_h;
    ob_camera cam = current_camera(v);
    /* Stereo: the eyes of the fly camera (parallel axes, frusta converging at its target). */
    ob_camera eyes[2] = {cam, cam};
    bool ok = v->stereo == VIEW_MONO ||
              ob_stereo_cameras(&cam, &(ob_stereo_desc){.ipd = v->o.ipd, .aspect = (float)v->eye_width / (float)h},
                                eyes) == OB_OK;
    ok = ok && ob_render_frame(v->r, &eyes[0], &v->s) == OB_OK;
    if (ok && v->stereo != VIEW_MONO) ok = ob_render_frame(v->right, &eyes[1], &v->s) == OB_OK;
    if (ok) {
        if (v->stereo == VIEW_MIRROR)
            ok = ob_present(v->r, v->view, 0, x, y, v->eye_width, h) == OB_OK &&
                 ob_present(v->right, v->view, 0, x + v->eye_width, y, v->eye_width, h) == OB_OK;
        else
            ok = ob_present(v->r, v->view, 0, x, y, w, h) == OB_OK;
    }
    return ok;
}

static bool frame(viewer *v, double dt)
{
    int w = 0, h = 0;
    glfwGetFramebufferSize(v->window, &w, &h);
    if (w <= 0 || h <= 0) return true; /* minimised: nothing to draw */
    v->fb_width = w;
    v->fb_height = h;
    if (v->events) run_script_events(v);
    /* After the script's events, which may hide the panel or resize the window. */
    view_layout(v, w, h);
    if (!fit_renderers(v, v->pic_w, v->pic_h)) return false;
    move_camera(v, dt);
    follow_path(v);
    /* The window's background: the bars beside the picture and the panel's column. */
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, w, h);
    glClearColor(0.06f, 0.06f, 0.07f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    bool ok = draw_image(v);
    if (!ok) {
        /* A setting the renderer refuses (e.g. the environment ambient with no map): say so and
         * show the picture's background rather than a stale frame. */
        const char *msg = "";
        ob_get_error(&msg);
        if (strcmp(msg, v->message) != 0 || v->clock >= v->message_until) say(v, true, "%s", msg);
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glEnable(GL_SCISSOR_TEST);
        glScissor(v->pic_x, h - v->pic_y - v->pic_h, v->pic_w, v->pic_h);
        glClearColor(0.1f, 0.0f, 0.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT);
        glDisable(GL_SCISSOR_TEST);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, w, h);
    /* `screenshot`: the image alone, before the panel and the messages are drawn over it. */
    if (v->events) script_screenshot(v, false);
    build_gui(v);
    /* `screenshot_ui`, P, F12 and the panel's button: the window as it shows. */
    if (v->events) script_screenshot(v, true);
    if (v->shot_requested) {
        v->shot_requested = false;
        save_screenshot(v, NULL, false);
    }
    glfwSwapBuffers(v->window);
    /* The reference view renders the panes' renderer, not these: no timings of theirs to add. */
    if (ok && !view_reference_on(v)) {
        ob_pass_timing timings[MAX_PASSES];
        double eye_ms[2] = {0.0, 0.0};
        long long timed = -1, rendered = -1;
        int n = view_timings(v, false, timings, eye_ms, &timed, &rendered);
        if (profiler_add_frame(&v->prof, timings, n, timed, rendered, v->last_frame_ms) && v->stereo != VIEW_MONO)
            profiler_add_eyes(&v->prof, eye_ms);
        if (v->test) test_step(v);
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
        /* A script replays on a simulated clock: 1/30 s per frame, whatever the frame took; it
         * stands still while the reference is traced, so what follows sees it finished. */
        double dt = v->events ? (view_reference_busy(v) ? 0.0 : 1.0 / 30.0) : (first ? 0.0 : wall_dt);
        if (!first) v->last_frame_ms = 1000.0 * wall_dt;
        bool ok = frame(v, dt);
        if (first && !ok) {
            /* The first frame failing (a shader, no memory) is not something a person can fix
             * from the panel. */
            return cli_fail(EXIT_RUNTIME, "%s", v->message);
        }
        first = false;
        v->clock += dt;
        /* While the reference is traced, five frames a second keep the panel and the progress
         * line alive and leave the cores to the tracer: on llvmpipe every frame is drawn on those
         * same cores. */
        if (view_reference_busy(v)) glfwWaitEventsTimeout(0.2);
        ++v->fps_window_frames;
        double window = glfwGetTime() - v->fps_window_start;
        if (window >= 0.5) {
            v->fps = (double)v->fps_window_frames / window;
            v->fps_window_frames = 0;
            v->fps_window_start = glfwGetTime();
        }
    }
    if (v->exit_code != EXIT_OK) return v->exit_code;
    if (v->test) return test_finish(v);
    return EXIT_OK;
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
    if ((code = cli_common_load_scene(&v->o.common, NULL, &v->scene)) != EXIT_OK) goto done;
    if ((code = setup_settings(v)) != 0) goto done;
    if ((code = camera_setup(v)) != 0) goto done;
    v->path_playing = cli_common_moves(&v->o.common); /* --path / --orbit starts playing */
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
    v->window = glfwCreateWindow(v->o.common.width, v->o.common.height, "Obscura", NULL, NULL);
    if (!v->window) {
        code = cli_fail(EXIT_NO_GPU, "view: no OpenGL 4.5 core window: %s", glfw_message);
        glfwTerminate();
        goto done;
    }
    glfwMakeContextCurrent(v->window);
    glfwSwapInterval(v->vsync && !v->o.test_mode ? 1 : 0);
    input_attach(v); /* before gui_init, whose callbacks chain to these */
    v->ctx = ob_make_context(&(ob_context_desc){.use_current = true});
    if (!v->ctx) {
        code = cli_fail_from_library();
        goto close;
    }
    glfwGetFramebufferSize(v->window, &v->fb_width, &v->fb_height);
    v->stereo = v->o.stereo;
    view_layout(v, v->fb_width, v->fb_height);
    /* Mono's size; the first frame fits the eyes of a stereo start. */
    v->eye_width = v->pic_w;
    v->eye_height = v->pic_h;
    v->r = ob_make_renderer(v->ctx, &(ob_renderer_desc){.width = v->eye_width, .height = v->eye_height});
    if (!v->r || ob_renderer_set_scene(v->r, v->scene) != OB_OK) {
        code = cli_fail_from_library();
        goto close;
    }
    if ((code = cli_common_prepare(&v->o.common, v->r)) != 0) goto close;
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
    view_reference_free(v);
    ob_destroy_renderer(v->right);
    ob_destroy_renderer(v->r);
    ob_destroy_context(v->ctx);
    glfwDestroyWindow(v->window);
    glfwTerminate();
done:
    test_free(v->test);
    free(v->events);
    ob_destroy_scene(v->scene);
    free(v);
    return code;
}

