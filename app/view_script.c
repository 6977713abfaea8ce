/* obscura view --script: timed input events, replayed on a simulated clock (1/30 s per frame) so
 * a run moves, switches and takes its screenshots at the same frames on any machine. The whole
 * file is read and checked before a window opens; the events go through the same handlers as a
 * person's keys and mouse. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "view.h"
#include "view_gui.h"

enum { MAX_EVENTS = 4096 }; /* one allocation holds a whole script */

typedef enum event_kind {
    EV_KEY, EV_MOUSE, EV_MOVE, EV_SCROLL, EV_METHOD, EV_FILTER, EV_SET, EV_CAMERA, EV_VIEW, EV_SCREENSHOT, EV_QUIT, EV_CLOSE, EV_RESIZE,
    EV_STEREO, EV_SCREENSHOT_UI
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
int load_script(const char *path, script_event **out, int *count)
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
                {"view", EV_VIEW}, {"screenshot", EV_SCREENSHOT}, {"screenshot_ui", EV_SCREENSHOT_UI},
                {"stereo", EV_STEREO}};
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

void run_script_events(viewer *v)
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
        /* The mouse goes to the panel as a person's does (ImGui sees it first, view_gui.h) and on
         * to the camera unless the panel keeps it, as the GLFW callbacks decide (view_camera.c). */
        case EV_MOUSE: {
            int b = e->code == GLFW_MOUSE_BUTTON_LEFT ? 0 : 1;
            v->script_mouse.down[b] = e->action == GLFW_PRESS;
            if (e->action == GLFW_PRESS) v->script_mouse.pressed[b] = true;
            if (!(gui_wants_mouse() && e->action == GLFW_PRESS)) handle_mouse_button(v, e->code, e->action);
            break;
        }
        case EV_MOVE:
            v->script_mouse.x = e->x;
            v->script_mouse.y = e->y;
            v->script_mouse.known = true;
            handle_cursor(v, e->x, e->y);
            break;
        case EV_SCROLL:
            v->script_mouse.wheel += (float)e->y;
            if (!gui_wants_mouse()) handle_scroll(v, e->y);
            break;
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
        case EV_STEREO: {
            int found = -1;
            for (int i = 0; i < VIEW_STEREO_COUNT; ++i)
                if (!strcmp(view_stereo_names[i], e->arg)) found = i;
            if (found < 0) {
                say(v, true, "unknown stereo mode '%s' (mono, mirror, single)", e->arg);
            } else {
                v->stereo = (view_stereo)found;
                profiler_reset(&v->prof);
            }
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
        case EV_SCREENSHOT:
        case EV_SCREENSHOT_UI: break; /* taken once the frame is drawn: see script_screenshot */
        case EV_QUIT: v->quit = true; break;
        case EV_CLOSE: glfwSetWindowShouldClose(v->window, GLFW_TRUE); break; /* as the close button */
        case EV_RESIZE: glfwSetWindowSize(v->window, (int)e->x, (int)e->y); break; /* as dragging its edge */
        }
        if (e->kind == EV_SCREENSHOT || e->kind == EV_SCREENSHOT_UI) {
            --v->next_event; /* script_screenshot takes it once this frame is on the back buffer */
            return;
        }
    }
}

void script_screenshot(viewer *v, bool with_ui)
{
    /* Several due at once are taken in the script's order: an image-alone one after a window one
     * waits for the next frame (the panel is on this one's back buffer already). */
    event_kind want = with_ui ? EV_SCREENSHOT_UI : EV_SCREENSHOT;
    while (v->next_event < v->event_count && v->events[v->next_event].kind == want &&
           v->events[v->next_event].t <= v->clock + 1e-9) {
        save_screenshot(v, v->events[v->next_event].arg, !with_ui);
        ++v->next_event;
    }
}
