// The C interface of app/view_gui.h over Dear ImGui 1.86 (Debian's libimgui-dev) with its GLFW
// and OpenGL 3 backends. Kept to forwarding calls: the panel is built in C (app/view.c).
#include <cstdarg>
#include <cfloat>
#include <cmath>
#include <cstdio>

#include <imgui.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>

#include "view_gui.h"

static bool gui_ready = false;
static ImGuiStyle base_style; // the style at scale 1, scaled from afresh on every change
static float gui_current_scale = 1.0f;
static bool gui_framed = false; // a frame has started: the backend's GL objects exist

bool gui_init(GLFWwindow *window)
{
    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGuiIO &io = ImGui::GetIO();
    io.IniFilename = nullptr; // no imgui.ini in whatever directory the viewer was started from
    ImGui::StyleColorsDark();
    ImGui::GetStyle().WindowRounding = 2.0f;
    // The panel is opaque: it has a column of its own now. The overlays set their own alpha.
    base_style = ImGui::GetStyle();
    gui_current_scale = 1.0f;
    gui_framed = false;
    // true: ImGui's callbacks are installed in front of the viewer's and call them in turn.
    if (!ImGui_ImplGlfw_InitForOpenGL(window, true)) return false;
    if (!ImGui_ImplOpenGL3_Init("#version 450 core")) {
        ImGui_ImplGlfw_Shutdown();
        return false;
    }
    gui_ready = true;
    return true;
}

void gui_shutdown(void)
{
    if (!gui_ready) return;
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    gui_ready = false;
}

void gui_set_scale(float scale)
{
    if (!gui_ready || scale == gui_current_scale) return;
    ImGuiIO &io = ImGui::GetIO();
    // The font rasterised at the scaled size rather than io.FontGlobalScale: a 13 px bitmap
    // stretched by 1.5 blurs, the same font drawn at 19.5 px does not.
    io.Fonts->Clear();
    ImFontConfig cfg;
    cfg.SizePixels = 13.0f * scale;
    io.Fonts->AddFontDefault(&cfg);
    // Before the first frame the backend has no GL objects yet and makes the font texture itself.
    if (gui_framed) {
        ImGui_ImplOpenGL3_DestroyFontsTexture();
        ImGui_ImplOpenGL3_CreateFontsTexture();
    }
    ImGui::GetStyle() = base_style;
    ImGui::GetStyle().ScaleAllSizes(scale);
    gui_current_scale = scale;
}

void gui_new_frame(gui_mouse *scripted)
{
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    gui_framed = true;
    if (scripted) {
        // After the backend polled the system's cursor and buttons, before ImGui reads them.
        ImGuiIO &io = ImGui::GetIO();
        io.MousePos = scripted->known ? ImVec2((float)scripted->x, (float)scripted->y) : ImVec2(-FLT_MAX, -FLT_MAX);
        for (int b = 0; b < 2; ++b) {
            io.MouseDown[b] = scripted->down[b] || scripted->pressed[b];
            scripted->pressed[b] = false;
        }
        io.MouseWheel = scripted->wheel;
        io.MouseWheelH = 0.0f;
        scripted->wheel = 0.0f;
    }
    ImGui::NewFrame();
}

void gui_render(void)
{
    ImGui::Render();
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

bool gui_wants_mouse(void) { return gui_ready && ImGui::GetIO().WantCaptureMouse; }
bool gui_wants_keyboard(void) { return gui_ready && ImGui::GetIO().WantCaptureKeyboard; }

bool gui_begin_docked(const char *title, float display_w, float display_h, float *width, float min_width,
                      float max_width)
{
    const float w = fminf(fmaxf(*width, min_width), max_width);
    // Placed every frame: a drag of the left edge changes the size (and, for this frame, the
    // position) after these, inside Begin, within the constraints.
    ImGui::SetNextWindowPos(ImVec2(display_w - w, 0.0f), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(w, display_h), ImGuiCond_Always);
    ImGui::SetNextWindowSizeConstraints(ImVec2(min_width, display_h), ImVec2(max_width, display_h));
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoCollapse |
                                   ImGuiWindowFlags_NoSavedSettings;
    const bool shown = ImGui::Begin(title, nullptr, flags);
    *width = ImGui::GetWindowWidth();
    return shown;
}

void gui_push_item_width(float w) { ImGui::PushItemWidth(w); }
void gui_pop_item_width(void) { ImGui::PopItemWidth(); }

void gui_progress(float fraction, const char *text) { ImGui::ProgressBar(fraction, ImVec2(-FLT_MIN, 0.0f), text); }

bool gui_begin_overlay(const char *id, float x, float y, bool bottom)
{
    ImGui::SetNextWindowPos(ImVec2(x, y), ImGuiCond_Always, ImVec2(0.0f, bottom ? 1.0f : 0.0f));
    ImGui::SetNextWindowBgAlpha(0.6f);
    const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                   ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoInputs;
    return ImGui::Begin(id, nullptr, flags);
}

void gui_end(void) { ImGui::End(); }

void gui_label(float x, float y, float r, float g, float b, const char *fmt, ...)
{
    char text[1024];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    // The background list: drawn before every window, so a label never hides the panel.
    ImDrawList *draw = ImGui::GetBackgroundDrawList();
    const ImVec2 pad = ImGui::GetStyle().WindowPadding;
    const ImVec2 size = ImGui::CalcTextSize(text);
    const ImVec2 lo(x, y - size.y - 2.0f * pad.y), hi(x + size.x + 2.0f * pad.x, y);
    draw->AddRectFilled(lo, hi, IM_COL32(0, 0, 0, 150), ImGui::GetStyle().WindowRounding);
    draw->AddText(ImVec2(lo.x + pad.x, lo.y + pad.y), ImGui::GetColorU32(ImVec4(r, g, b, 1.0f)), text);
}

bool gui_header(const char *label, bool default_open)
{
    return ImGui::CollapsingHeader(label, default_open ? ImGuiTreeNodeFlags_DefaultOpen : 0);
}

void gui_plot_points(const float *xy, int n, int period, float size)
{
    ImDrawList *draw = ImGui::GetWindowDrawList();
    ImVec2 o = ImGui::GetCursorScreenPos();
    float r = 0.5f * size - 4.0f;
    ImVec2 c(o.x + 0.5f * size, o.y + 0.5f * size);
    draw->AddRectFilled(o, ImVec2(o.x + size, o.y + size), IM_COL32(20, 20, 24, 255));
    draw->AddCircle(c, r, IM_COL32(120, 120, 120, 255), 64);
    draw->AddLine(ImVec2(c.x - r, c.y), ImVec2(c.x + r, c.y), IM_COL32(60, 60, 60, 255));
    draw->AddLine(ImVec2(c.x, c.y - r), ImVec2(c.x, c.y + r), IM_COL32(60, 60, 60, 255));
    /* Groups: the first period bright, later ones darker and shifted in hue. */
    static const ImU32 colours[4] = {IM_COL32(255, 210, 60, 255), IM_COL32(80, 200, 255, 255),
                                     IM_COL32(255, 110, 160, 255), IM_COL32(140, 255, 120, 255)};
    for (int i = 0; i < n; ++i) {
        int group = period > 0 ? (i / period) % 4 : 0;
        ImVec2 p(c.x + xy[2 * i] * r, c.y - xy[2 * i + 1] * r);
        draw->AddCircleFilled(p, 2.5f, colours[group]);
    }
    ImGui::Dummy(ImVec2(size, size));
}

void gui_text(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    ImGui::TextV(fmt, ap);
    va_end(ap);
}

void gui_text_colored(float r, float g, float b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    ImGui::TextColoredV(ImVec4(r, g, b, 1.0f), fmt, ap);
    va_end(ap);
}

// A tooltip now, whatever is hovered.
static void tooltip_now(const char *text)
{
    // Wrapped at 35 em, and never wider than the window, so a small window shows it whole.
    const float em = ImGui::GetFontSize();
    const float wrap = fminf(35.0f * em, ImGui::GetIO().DisplaySize.x - 2.0f * em);
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(wrap > 4.0f * em ? wrap : 4.0f * em);
    ImGui::TextUnformatted(text);
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
}

void gui_tooltip(const char *text)
{
    if (!text || !*text || !ImGui::IsItemHovered()) return;
    tooltip_now(text);
}

bool gui_combo(const char *label, int *index, const char *const *items, int count)
{
    return ImGui::Combo(label, index, items, count);
}

bool gui_slider_float(const char *label, float *v, float min, float max, const char *format, bool log)
{
    return ImGui::SliderFloat(label, v, min, max, format, log ? ImGuiSliderFlags_Logarithmic : 0);
}

bool gui_slider_int(const char *label, int *v, int min, int max, bool log)
{
    return ImGui::SliderInt(label, v, min, max, "%d", log ? ImGuiSliderFlags_Logarithmic : 0);
}
bool gui_checkbox(const char *label, bool *v) { return ImGui::Checkbox(label, v); }
bool gui_color3(const char *label, float rgb[3]) { return ImGui::ColorEdit3(label, rgb, ImGuiColorEditFlags_Float); }
bool gui_drag3(const char *label, float v[3], float speed) { return ImGui::DragFloat3(label, v, speed); }
bool gui_button(const char *label) { return ImGui::Button(label); }
void gui_same_line(void) { ImGui::SameLine(); }
void gui_separator(void) { ImGui::Separator(); }
void gui_push_id(int id) { ImGui::PushID(id); }
void gui_pop_id(void) { ImGui::PopID(); }

bool gui_begin_table(const char *id, int columns, const char *const *headers)
{
    const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit;
    if (!ImGui::BeginTable(id, columns, flags)) return false;
    for (int i = 0; i < columns; ++i) ImGui::TableSetupColumn(headers[i]);
    ImGui::TableHeadersRow();
    return true;
}

bool gui_begin_wide_table(const char *id, int columns, const gui_column *cols, int rows)
{
    const ImGuiStyle &style = ImGui::GetStyle();
    // Its own height: the header and the rows, the horizontal scroll bar and the borders; a child
    // window of height 0 would take the panel's whole remaining height instead.
    const float row = ImGui::GetTextLineHeight() + 2.0f * style.CellPadding.y;
    const float height = (float)(rows + 1) * row + style.ScrollbarSize + 2.0f;
    const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit |
                                  ImGuiTableFlags_ScrollX;
    if (!ImGui::BeginTable(id, columns, flags, ImVec2(0.0f, height))) return false;
    ImGui::TableSetupScrollFreeze(1, 1); // the name column and the header stay
    for (int i = 0; i < columns; ++i) ImGui::TableSetupColumn(cols[i].label, ImGuiTableColumnFlags_NoHide);
    // The header row by hand, for each header's colour and tooltip (TableHeadersRow has neither).
    ImGui::TableNextRow(ImGuiTableRowFlags_Headers);
    for (int i = 0; i < columns; ++i) {
        if (!ImGui::TableSetColumnIndex(i)) continue;
        const bool tinted = cols[i].rgb[0] > 0.0f || cols[i].rgb[1] > 0.0f || cols[i].rgb[2] > 0.0f;
        if (tinted) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(cols[i].rgb[0], cols[i].rgb[1], cols[i].rgb[2], 1.0f));
        ImGui::PushID(i);
        ImGui::TableHeader(cols[i].label);
        ImGui::PopID();
        if (tinted) ImGui::PopStyleColor();
        if (cols[i].tip && ImGui::IsItemHovered()) tooltip_now(cols[i].tip);
    }
    return true;
}

void gui_table_row(void) { ImGui::TableNextRow(); }

void gui_table_cell(const char *fmt, ...)
{
    ImGui::TableNextColumn();
    va_list ap;
    va_start(ap, fmt);
    ImGui::TextV(fmt, ap);
    va_end(ap);
}

void gui_end_table(void) { ImGui::EndTable(); }
