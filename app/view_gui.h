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

/* A window docked at the right edge of a display_w x display_h display: the full height, *width
 * wide; its left edge drags it wider or narrower within [min_width, max_width], and *width gets
 * the width it has after this frame's input. It neither moves nor collapses. Returns whether its
 * contents show; always pair with gui_end. */
bool gui_begin_docked(const char *title, float display_w, float display_h, float *width, float min_width,
                      float max_width);
/* Widgets this wide until the pop (negative: the content width minus that much, which is left to
 * the labels). */
void gui_push_item_width(float w);
void gui_pop_item_width(void);
/* A bar filled to fraction (0..1) with text on it. */
void gui_progress(float fraction, const char *text);
/* A small undecorated overlay that takes no input (FPS, camera, messages), its top-left corner at
 * (x, y), or its bottom-left corner with `bottom`. */
bool gui_begin_overlay(const char *id, float x, float y, bool bottom);
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
/* A column of gui_begin_wide_table: its header, what it shows when hovered (NULL: nothing) and the
 * header's colour (all 0: the style's). */
typedef struct gui_column {
    const char *label;
    const char *tip;
    float rgb[3];
} gui_column;
/* A table for more columns than the window may be wide: the first column stays in place while the
 * others scroll sideways (a scroll bar below, when they do not fit), as a profiler's name column
 * does; `rows` body rows, which set its height (no vertical scrolling inside). */
bool gui_begin_wide_table(const char *id, int columns, const gui_column *cols, int rows);
void gui_table_row(void);
void gui_table_cell(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void gui_end_table(void);

#ifdef __cplusplus
}
#endif
#endif
