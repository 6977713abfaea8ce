/* The viewer's GUI: a thin C interface over the few Dear ImGui calls the viewer uses
 * (app/view_gui.cpp is the only C++ in the project). The panel itself is built in C, in
 * app/view_panel.c, from the method and filter registries. */
#ifndef OB_VIEW_GUI_H
#define OB_VIEW_GUI_H

#include <stdbool.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct GLFWwindow GLFWwindow;

/* Call after the viewer has installed its own GLFW callbacks: ImGui's callbacks go in front of
 * them and pass every event on. */
bool gui_init(GLFWwindow *window);
void gui_shutdown(void);
/* The mouse as a script plays it (view_script.c): in a script run it replaces the system cursor,
 * which ImGui's GLFW backend would otherwise read every frame, so that scripted clicks reach the
 * panel and a run does not depend on where the X cursor happens to be. */
typedef struct gui_mouse {
    double x, y;
    bool known;      /* a move has placed it (before: off the window) */
    bool down[2];    /* left, right */
    bool pressed[2]; /* pressed since the last frame: held for that frame even if released, so a
                        click shorter than a frame still counts (as the GLFW backend does) */
    float wheel;     /* scroll since the last frame */
} gui_mouse;
/* Scale the font and the style's sizes by `scale` (1 = ImGui's 13 px font); a no-op when it is
 * the scale already in use. Call outside gui_new_frame .. gui_render. */
void gui_set_scale(float scale);
/* scripted: NULL for the system's mouse; else the script's (its pressed flags and wheel are
 * consumed). */
void gui_new_frame(gui_mouse *scripted);
/* Draw what was built since gui_new_frame into the current framebuffer. */
void gui_render(void);
/* ImGui wants the mouse (the cursor is over a window or a widget is active) or the keyboard
 * (a text field has focus): the camera leaves those events alone. */
bool gui_wants_mouse(void);
bool gui_wants_keyboard(void);

/* A window at (x, y) of size (w, h) on first use, and again whenever `place` is true (the
 * framebuffer changed size); returns whether it is expanded (its title bar collapses it). Always
 * pair with gui_end. */
bool gui_begin(const char *title, float x, float y, float w, float h, bool place);
/* Widgets this wide until the pop (negative: the content width minus that much, which is left to
 * the labels). */
void gui_push_item_width(float w);
void gui_pop_item_width(void);
/* A bar filled to fraction (0..1) with text on it. */
void gui_progress(float fraction, const char *text);
/* A small undecorated overlay at (x, y) that takes no input (FPS, camera, messages). */
bool gui_begin_overlay(const char *id, float x, float y);
void gui_end(void);
/* Text (lines split by \n) on a dark box whose bottom-left corner is at (x, y), behind every
 * window (the panel and the overlay cover it), in colour r, g, b. */
void gui_label(float x, float y, float r, float g, float b, const char *fmt, ...) __attribute__((format(printf, 6, 7)));
bool gui_header(const char *label, bool default_open);
/* A square plot of n points (x, y in [-1, 1], +y up) inside the unit circle, size px wide; point i
 * takes colour group i / period (period 0: one colour), so a kernel's repeats show. */
void gui_plot_points(const float *xy, int n, int period, float size);
void gui_text(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void gui_text_colored(float r, float g, float b, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
void gui_tooltip(const char *text); /* for the last item, when hovered */
bool gui_combo(const char *label, int *index, const char *const *items, int count);
/* log: a logarithmic slider (for ranges over several decades, e.g. a radius in metres). */
bool gui_slider_float(const char *label, float *v, float min, float max, const char *format, bool log);
bool gui_slider_int(const char *label, int *v, int min, int max, bool log);
bool gui_checkbox(const char *label, bool *v);
bool gui_color3(const char *label, float rgb[3]);
bool gui_drag3(const char *label, float v[3], float speed);
bool gui_button(const char *label);
void gui_same_line(void);
void gui_separator(void);
void gui_push_id(int id);
void gui_pop_id(void);

/* Tables: gui_begin_table, then per row gui_table_row and one gui_table_cell per column. */
bool gui_begin_table(const char *id, int columns, const char *const *headers);
void gui_table_row(void);
void gui_table_cell(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void gui_end_table(void);

#ifdef __cplusplus
}
#endif
#endif
