/* obscura view's panel and overlay, drawn with Dear ImGui through view_gui.h. The method and
 * filter sections are generated from the registries' parameter tables (as `obscura list` and
 * `--set` are), so a new method or parameter appears here without code; lights, shadows, HDR and
 * the display are the ob_settings fields edited in place. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "view.h"
#include "view_gui.h"

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

/* The method's sample kernel from above (SSDO thesis Fig. 4.1/4.2): each entry's xy in the tangent
 * plane, coloured by which period of the Halton bases 2 x 5 (10 entries) it falls in, so a count
 * that is not a multiple of 10 shows its unevenly covered last period. */
static void panel_kernel(viewer *v)
{
    enum { MAX_KERNEL = 256 };
    static float xyzw[4 * MAX_KERNEL], xy[2 * MAX_KERNEL];
    int n = ob_method_kernel(&v->s, xyzw, MAX_KERNEL);
    if (n <= 0) {
        gui_text("%s has no sample kernel:", ob_method_at(v->s.method)->name);
        gui_text("it marches the depth buffer.");
        return;
    }
    float longest = 0.0f;
    for (int i = 0; i < n; ++i) {
        float len = sqrtf(xyzw[4 * i] * xyzw[4 * i] + xyzw[4 * i + 1] * xyzw[4 * i + 1] + xyzw[4 * i + 2] * xyzw[4 * i + 2]);
        longest = len > longest ? len : longest;
    }
    for (int i = 0; i < n; ++i) {
        xy[2 * i] = longest > 0.0f ? xyzw[4 * i] / longest : 0.0f;
        xy[2 * i + 1] = longest > 0.0f ? xyzw[4 * i + 1] / longest : 0.0f;
    }
    float sampling = ob_settings_get(&v->s, "sampling");
    bool halton = isnan(sampling) || sampling == 1.0f; /* the SSDOs' kernels are always Halton */
    gui_plot_points(xy, n, halton ? 10 : 0, 220.0f);
    if (halton)
        gui_text("%d Halton: %d x period 10 (2 x 5) + %d", n, n / 10, n % 10);
    else
        gui_text("%d random entries (seeded)", n);
    gui_tooltip("SSDO thesis Fig. 4.1/4.2: from above, each colour one period of the Halton bases 2 x 5");
}

/* The guard band (Belonogov 2018 §3.2.2, --guard): the checkbox switches it off and back to the last
 * width, so the border's darkening can be compared in place; 10 % of the larger side at first. */
static void panel_guard(viewer *v)
{
    static int last = 0;
    if (v->s.guard > 0) last = v->s.guard;
    if (last == 0) last = ((v->eye_width > v->eye_height ? v->eye_width : v->eye_height) + 9) / 10;
    bool on = v->s.guard > 0;
    if (gui_checkbox("guard band", &on)) {
        v->s.guard = on ? last : 0;
        profiler_reset(&v->prof);
    }
    gui_tooltip("render the G-buffer and the AO chain beyond each side of the window and crop at compose, so "
                "occluders just outside the frame darken its border (Belonogov 2018 §3.2.2)");
    int g = v->s.guard;
    if (gui_slider_int("guard (px per side)", &g, 0, 256, false)) {
        v->s.guard = g;
        profiler_reset(&v->prof);
    }
    if (v->s.guard > 0) {
        /* As the renderer rounds it (a multiple of 4 x the AO divisor, renderer.c ob_guard_pixels). */
        int step = 4 * (v->s.ao_divisor > 1 ? v->s.ao_divisor : 1);
        int used = (v->s.guard + step - 1) / step * step;
        gui_text("AO chain at %dx%d (band %d px)", v->eye_width + 2 * used, v->eye_height + 2 * used, used);
    }
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
    /* Every method's radius_scale (occluder radius = scale x R, graded at R; --settings may tune it). */
    if (info->param_count > 0) {
        if (v->s.radius_scale <= 0.0f) v->s.radius_scale = 1.0f;
        gui_slider_float("radius scale (x R)", &v->s.radius_scale, OB_RADIUS_SCALE_MIN, OB_RADIUS_SCALE_MAX, "%.2f", false);
    }
    if (info->param_count > 0 && gui_button("defaults")) {
        ob_settings fresh;
        if (ob_settings_init(&fresh, info->name) == OB_OK) {
            memcpy(v->s.params, fresh.params, sizeof v->s.params);
            v->s.params_set = 0;
            v->s.radius_scale = 1.0f;
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
    if (si > 0) {
        const char *programs[OB_UPSAMPLE_PROGRAM_COUNT];
        for (int i = 0; i < OB_UPSAMPLE_PROGRAM_COUNT; ++i) programs[i] = ob_upsample_program_name((ob_upsample_program)i);
        if (gui_combo("upsample", &v->s.upsample, programs, OB_UPSAMPLE_PROGRAM_COUNT)) profiler_reset(&v->prof);
        gui_tooltip("the upsampler's program, the same image either way: block reads the AO grid once per k x k "
                    "pixels, plain once per pixel; auto takes block on a software rasteriser (docs/filters.md)");
    }
    gui_checkbox("adaptive samples", &v->s.adaptive);
    gui_tooltip("an edge pre-pass gives edge pixels 2x or 3x the base count (ssao, crytek)");
    if (gui_checkbox("temporal", &v->s.temporal) && !v->s.temporal) v->s.jitter = 0; /* no shaking image without it */
    gui_tooltip("accumulate the AO over frames: reprojected history, disocclusion by depth and normal, 4x4 clamp "
                "(docs/temporal.md); turns every method's noise with the frame index. The history_age view shows it");
    if (cli_common_moves(&v->o.common)) {
        gui_checkbox("play path", &v->path_playing);
        gui_tooltip("follow --path / --orbit, one path frame per rendered frame (Space)");
    }
    if (v->s.temporal) {
        static const char *const places[] = {"before the filter", "after the filter"};
        gui_combo("temporal at", &v->s.temporal_at, places, 2);
        int frames = v->s.temporal_frames > 0 ? v->s.temporal_frames : OB_TEMPORAL_FRAMES_DEFAULT;
        if (gui_slider_int("history frames", &frames, 1, OB_TEMPORAL_FRAMES_MAX, true)) v->s.temporal_frames = frames;
        gui_slider_float("keep detail", &v->s.temporal_detail, 0.0f, 0.95f, "%.2f", false);
        gui_tooltip("the least share of one-pixel detail the history keeps while the camera moves:\n"
                    "sharper, with more flicker (--temporal-detail; 0 = off)");
        gui_slider_int("jitter points", &v->s.jitter, 0, 16, false);
        gui_tooltip("sub-pixel jitter of the G-buffer over this many Halton points (0 = off; --jitter): the\n"
                    "history averages each pixel's footprint, and accumulates after the filter. The lit\n"
                    "image moves by the jitter too (docs/temporal.md, \"Jitter\")");
    }
    panel_guard(v);
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
        bool half = v->s.shadow.vsm_bits == 16;
        if (gui_checkbox("16-bit vsm moments (SSDO thesis Fig. 6.5)", &half)) v->s.shadow.vsm_bits = half ? 16 : 32;
    }
    static const char *const ambients[] = {"constant", "hemisphere", "environment"};
    int am = (int)v->s.ambient_mode;
    if (gui_combo("ambient", &am, ambients, v->o.common.env ? 3 : 2)) v->s.ambient_mode = (ob_ambient_mode)am;
    if (v->s.ambient_mode == OB_AMBIENT_CONSTANT) gui_color3("ambient colour", v->s.ambient);
    if (v->s.ambient_mode == OB_AMBIENT_HEMISPHERE) {
        gui_color3("sky", v->s.sky);
        gui_color3("ground", v->s.ground);
    }
    gui_checkbox("AO darkens all light", &v->s.ao_all_light);
    gui_checkbox("multi-bounce AO (Jimenez 2016)", &v->s.multibounce);
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
    int st = (int)v->stereo;
    if (gui_combo("stereo", &st, view_stereo_names, VIEW_STEREO_COUNT)) {
        v->stereo = (view_stereo)st;
        profiler_reset(&v->prof);
    }
    gui_tooltip("Belonogov 2018 §5.2: mono; mirror = both eyes side by side; single = the left eye alone (both are "
                "rendered, each with its own G-buffer and AO)");
    if (v->stereo != VIEW_MONO)
        gui_slider_float("ipd", &v->o.ipd, 0.001f * v->scene_size, 0.2f * v->scene_size, "%.4g", true);
    if (gui_button("screenshot (P)")) v->shot_requested = true;
#ifdef OB_VIEW_SHADER_RELOAD
    gui_same_line();
    if (gui_button("reload shaders (R)")) reload_shaders(v);
#endif
}

/* The GUI's scale for a framebuffer: 1 (ImGui's 13 px font) up to 1280x720, growing with the
 * smaller of the two ratios beyond (1.5 at 1920x1080), in quarter steps so that a window being
 * dragged does not rebuild the font every frame. Never below 1: smaller text is unreadable, so
 * on a small window the panel gets a larger share of the width instead (panel_limits). */
static float gui_scale_for(int w, int h)
{
    float s = fminf((float)w / 1280.0f, (float)h / 720.0f);
    s = floorf(s * 4.0f) / 4.0f;
    return s < 1.0f ? 1.0f : s > 3.0f ? 3.0f : s;
}

/* The panel takes a column of the window instead of covering the picture; test mode has none, so
 * that its timings are of the whole --size, as render's are. */
static bool panel_shown(const viewer *v) { return v->gui_visible && !v->o.test_mode; }

/* The panel's column: 30 % of the width, at least 340 px x scale (the labels' room, and the
 * profiler's pass column with its first four times), at most half the window; dragged by its left
 * edge, anywhere from 220 px x scale (or half the window, if less) to 60 % of it. */
static void panel_limits(int w, float scale, float *lo, float *def, float *hi)
{
    *hi = floorf(0.6f * (float)w);
    *lo = floorf(fminf(220.0f * scale, 0.5f * (float)w));
    *def = floorf(fminf(fmaxf(0.3f * (float)w, 340.0f * scale), 0.5f * (float)w));
}

void view_layout(viewer *v, int w, int h)
{
    float pw = 0.0f;
    if (panel_shown(v)) {
        float lo, def, hi;
        panel_limits(w, gui_scale_for(w, h), &lo, &def, &hi);
        pw = v->panel_dragged > 0.0f ? v->panel_dragged : def;
        pw = pw < lo ? lo : pw > hi ? hi : pw;
    }
    v->panel_width = pw;
    /* The picture keeps the window's shape (a panel shown or hidden does not change what the
     * camera frames, only how large it shows), as large as the rest of the width allows,
     * centred between bars above and below. */
    int area = w - (int)pw;
    area = area > 1 ? area : 1;
    int ph = (int)lround((double)area * (double)h / (double)w);
    ph = ph < 1 ? 1 : ph > h ? h : ph;
    v->pic_x = 0;
    v->pic_w = area;
    v->pic_h = ph;
    v->pic_y = (h - ph) / 2;
}

bool view_in_picture(const viewer *v, double x, double y)
{
    return x >= v->pic_x && x < v->pic_x + v->pic_w && y >= v->pic_y && y < v->pic_y + v->pic_h;
}

/* The switches a person reaches for most, above the sections: each has a key too. */
static void panel_switches(viewer *v, float width, float scale)
{
    bool on = view_reference_on(v);
    if (gui_checkbox("reference view (G)", &on)) view_reference_toggle(v);
    gui_tooltip("the Embree ground truth AO_R of this camera beside the method's AO and the signed error, with "
                "the RMSE (section Reference)");
    if (width >= 330.0f * scale) gui_same_line(); /* both on one line where they fit whole */
    bool textures = !v->s.textures_off;
    if (gui_checkbox("textures (X)", &textures)) v->s.textures_off = !textures;
    gui_tooltip("albedo textures; off: every material's diffuse colour alone (--textures off)");
}

void build_gui(viewer *v)
{
    float scale = gui_scale_for(v->fb_width, v->fb_height);
    gui_set_scale(scale);
    gui_new_frame(v->events ? &v->script_mouse : NULL);
    view_reference_labels(v);
    if (v->gui_visible) {
        /* The overlay: what a screenshot should say about itself (Puri 2024 §2.7), on the bar above
         * the picture, at its left; the lines that come and go (stereo, the reference, test mode,
         * messages) on the bar below, so that neither grows over the picture. */
        if (gui_begin_overlay("##overlay", (float)v->pic_x + 10.0f, 10.0f, false)) {
            gui_text("%.1f FPS  %.1f ms   %dx%d", v->fps, v->last_frame_ms, v->pic_w, v->pic_h);
            gui_text("%s", ob_query_renderer(v->ctx));
            gui_text("%s  %s  %s%s", ob_query_scene_name(v->scene), ob_method_at(v->s.method)->name,
                     ob_view_name(v->view), v->camera_locked ? "  [camera locked]" : "");
            gui_text("camera %.2f %.2f %.2f  fov %.1f", (double)v->eye[0], (double)v->eye[1], (double)v->eye[2],
                     (double)v->fov);
        }
        gui_end();
        const bool message = v->message[0] && v->clock < v->message_until;
        if (v->stereo != VIEW_MONO || view_reference_has_status(v) || v->test || message) {
            if (gui_begin_overlay("##status", (float)v->pic_x + 10.0f, (float)v->fb_height - 10.0f, true)) {
                if (v->stereo != VIEW_MONO)
                    gui_text("stereo %s, %dx%d per eye, ipd %.3g", view_stereo_names[v->stereo], v->eye_width,
                             v->eye_height, (double)v->o.ipd);
                view_reference_overlay(v);
                if (v->test) test_overlay(v);
                if (message) {
                    if (v->message_error) gui_text_colored(1.0f, 0.4f, 0.4f, "%s", v->message);
                    else gui_text_colored(0.6f, 1.0f, 0.6f, "%s", v->message);
                }
            }
            gui_end();
        }
    }
    if (panel_shown(v)) {
        /* The panel fills the column view_layout left it; a drag of its left edge sets the next
         * frame's layout (the picture follows one frame later). */
        float lo, def, hi, width = v->panel_width;
        panel_limits(v->fb_width, scale, &lo, &def, &hi);
        if (gui_begin_docked("Obscura", (float)v->fb_width, (float)v->fb_height, &width, lo, hi)) {
            /* Widgets take what the labels leave: 40 % of the panel for a label, at least 150 px x
             * scale (21 characters, e.g. "sigma_plane (x depth)"), at most 55 %. */
            gui_push_item_width(-fminf(fmaxf(150.0f * scale, 0.4f * width), 0.55f * width));
            panel_switches(v, width, scale);
            /* Stereo opens with the profiler and the stereo control in view, the method closed. */
            if (gui_header("Method and filter", v->stereo == VIEW_MONO)) panel_method(v);
            if (gui_header("Reference", view_reference_on(v))) panel_reference(v);
            if (gui_header("Kernel", false)) panel_kernel(v);
            if (gui_header("Profiler", true)) panel_profiler(v);
            if (gui_header("Camera and display", v->stereo != VIEW_MONO)) panel_display(v);
            if (gui_header("Lights and shadows", false)) panel_lights(v);
            if (gui_header("HDR", false)) panel_hdr(v);
            if (gui_header("Keys", false))
                gui_text("WASD move, Q/E down/up, Shift faster\nright mouse: look, scroll: zoom\n(on the "
                         "picture)\n1-9, Tab: camera presets, L: lock camera\nM: method, V: view, F1/H: panel\n"
                         "G: reference view, X: textures, T: temporal\nF3: vsync, P/F12: screenshot\nR: reload "
                         "shaders, Esc: quit\ndrag the panel's left edge to widen it");
            gui_pop_item_width();
        }
        gui_end();
        if (fabsf(width - v->panel_width) >= 1.0f) v->panel_dragged = width;
    }
    gui_render();
}
