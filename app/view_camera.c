/* obscura view's fly camera and the input that drives it: the scene's presets, WASD movement,
 * mouse look and zoom, and the discrete keys (methods, views, panel, screenshots). Script events
 * call the same handle_* functions as GLFW's callbacks, so a replay is a person's input. */
#include <math.h>
#include <string.h>

#include "view.h"
#include "view_gui.h"

/* ---- camera -------------------------------------------------------------------------------- */
static float vlen(const float a[3]) { return sqrtf(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

void vnorm(float a[3])
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

void use_camera(viewer *v, int index)
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

/* --path / --orbit while playing: the fly camera jumps to the path's next frame (paused, it stays
 * free to fly from there). */
void follow_path(viewer *v)
{
    const cli_common *c = &v->o.common;
    if (!cli_common_moves(c) || !v->path_playing) return;
    ob_camera base = ob_query_camera(v->scene, v->camera_index), cam;
    if (cli_common_path_camera(c, v->scene, &base, v->path_frame, &cam) != 0) {
        v->path_playing = false;
        return;
    }
    v->path_frame = (v->path_frame + 1) % c->path_frames;
    memcpy(v->eye, cam.eye, sizeof v->eye);
    for (int i = 0; i < 3; ++i) v->fwd[i] = cam.target[i] - cam.eye[i];
    vnorm(v->fwd);
    v->up[0] = v->up[2] = 0.0f;
    v->up[1] = 1.0f;
    v->fov = cam.fov_y_deg > 0.0f ? cam.fov_y_deg : v->fov;
}

ob_camera current_camera(const viewer *v)
{
    ob_camera c;
    memset(&c, 0, sizeof c);
    memcpy(c.eye, v->eye, sizeof c.eye);
    for (int i = 0; i < 3; ++i) c.target[i] = v->eye[i] + v->fwd[i];
    memcpy(c.up, v->up, sizeof c.up);
    c.fov_y_deg = v->fov;
    return c;
}

int camera_setup(viewer *v)
{
    v->camera_index = 0;
    const cli_common *c = &v->o.common;
    if (c->camera) {
        ob_camera found;
        if (ob_find_camera(v->scene, c->camera, &found) != OB_OK) return cli_fail_from_library();
        for (int i = 0; i < ob_query_camera_count(v->scene); ++i)
            if (!strcmp(ob_query_camera(v->scene, i).name, found.name)) v->camera_index = i;
    }
    use_camera(v, v->camera_index);
    if (c->has_eye || c->has_fov) {
        /* --eye/--target (and --fov) as every command takes them: the fly camera starts there. */
        ob_camera cam;
        int code = cli_common_camera(c, v->scene, NULL, &cam);
        if (code != 0) return code;
        memcpy(v->eye, cam.eye, sizeof v->eye);
        for (int i = 0; i < 3; ++i) v->fwd[i] = cam.target[i] - cam.eye[i];
        vnorm(v->fwd);
        if (vlen(cam.up) > 0.0f) memcpy(v->up, cam.up, sizeof v->up);
        vnorm(v->up);
        if (cam.fov_y_deg > 0.0f) v->fov = cam.fov_y_deg;
    }
    ob_scene_stats st = ob_query_scene_stats(v->scene);
    float diag[3] = {st.bounds_max[0] - st.bounds_min[0], st.bounds_max[1] - st.bounds_min[1],
                     st.bounds_max[2] - st.bounds_min[2]};
    v->scene_size = vlen(diag) > 0.0f ? vlen(diag) : 1.0f;
    v->speed = 0.1f * v->scene_size; /* ten seconds across the scene */
    return 0;
}

void move_camera(viewer *v, double dt)
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

/* ---- input --------------------------------------------------------------------------------- */
/* Discrete actions on key press; continuous ones (movement) read v->keys every frame. */
void handle_key(viewer *v, int key, int action, int mods)
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
        v->shot_requested = true; /* taken once the next frame is drawn (the back buffer holds it) */
    } else if (key == GLFW_KEY_G) {
        view_reference_toggle(v);
    } else if (key == GLFW_KEY_X) {
        v->s.textures_off = !v->s.textures_off;
        say(v, false, "albedo textures %s", v->s.textures_off ? "off (each material's diffuse colour)" : "on");
    } else if (key == GLFW_KEY_R) reload_shaders(v);
    else if (key == GLFW_KEY_SPACE && cli_common_moves(&v->o.common)) {
        v->path_playing = !v->path_playing;
        say(v, false, "path %s at frame %d", v->path_playing ? "playing" : "paused", v->path_frame);
    } else if (key == GLFW_KEY_T) {
        v->s.temporal = !v->s.temporal;
        say(v, false, "temporal accumulation %s", v->s.temporal ? "on" : "off");
    }
}

/* Looking starts on the picture only (a press on the bars or the panel's column is not the
 * camera's), and goes on wherever the held button drags the cursor. */
void handle_mouse_button(viewer *v, int button, int action)
{
    if (button != GLFW_MOUSE_BUTTON_RIGHT) return;
    if (action == GLFW_PRESS && !(v->mouse_known && view_in_picture(v, v->mouse_x, v->mouse_y))) return;
    v->look = action == GLFW_PRESS && !v->camera_locked;
}

void handle_cursor(viewer *v, double x, double y)
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

/* Zoom with the cursor on the picture only. */
void handle_scroll(viewer *v, double dy)
{
    if (v->camera_locked || !(v->mouse_known && view_in_picture(v, v->mouse_x, v->mouse_y))) return;
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

/* Where the cursor is now, for a button or the wheel (no move may have been reported since the
 * cursor entered the window). */
static void cursor_now(GLFWwindow *w, viewer *v)
{
    glfwGetCursorPos(w, &v->mouse_x, &v->mouse_y);
    v->mouse_known = true;
}

static void on_mouse_button(GLFWwindow *w, int button, int action, int mods)
{
    (void)mods;
    viewer *v = glfwGetWindowUserPointer(w);
    if (gui_wants_mouse() && action == GLFW_PRESS) return;
    cursor_now(w, v);
    handle_mouse_button(v, button, action);
}

static void on_cursor(GLFWwindow *w, double x, double y) { handle_cursor(glfwGetWindowUserPointer(w), x, y); }

static void on_scroll(GLFWwindow *w, double dx, double dy)
{
    (void)dx;
    if (gui_wants_mouse()) return;
    viewer *v = glfwGetWindowUserPointer(w);
    cursor_now(w, v);
    handle_scroll(v, dy);
}

static void on_close(GLFWwindow *w)
{
    viewer *v = glfwGetWindowUserPointer(w);
    v->quit = true;
}

void input_attach(viewer *v)
{
    glfwSetWindowUserPointer(v->window, v);
    glfwSetKeyCallback(v->window, on_key);
    glfwSetMouseButtonCallback(v->window, on_mouse_button);
    glfwSetCursorPosCallback(v->window, on_cursor);
    glfwSetScrollCallback(v->window, on_scroll);
    glfwSetWindowCloseCallback(v->window, on_close);
}
