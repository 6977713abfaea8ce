/* The report chart's geometry (app/chart_layout.c), with the report's own plot area and text sizes:
 * both axes start at 0, or the time axis is logarithmic from a decade at or below the fastest row
 * when the times spread over more than 10x; points map to the plot's pixels and back; and the
 * labels, placed on crowded points (ssao and hbao, gtao and vbao almost on top of each other, as
 * they land on cornell:front), never overlap one another, never cover a point, and all lie inside
 * the plot, or are left out. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "chart_layout.h"
#include "check.h"

/* Every placed label against every other and every drawn point, and the plot's border; returns
 * the number of broken rules (each reported). */
static int check_layout(const char *what, const chart_axes *a, const chart_label *l, int n)
{
    const chart_text *t = &CHART_REPORT_TEXT;
    int broken = 0;
    for (int i = 0; i < n; ++i) {
        if (!l[i].placed) continue;
        const chart_box *b = &l[i].box;
        if (b->x0 < a->plot.x0 || b->x1 > a->plot.x1 || b->y0 < a->plot.y0 || b->y1 > a->plot.y1) {
            ++broken;
            fprintf(stderr, "%s: label %d (%g..%g, %g..%g) outside the plot\n", what, i, b->x0, b->x1, b->y0, b->y1);
        }
        CHECK_NEAR(b->x1 - b->x0, l[i].chars * t->char_width, 1e-9, "box width: characters x their width");
        for (int j = 0; j < n; ++j) {
            if (j != i && l[j].placed && chart_boxes_overlap(b, &l[j].box)) {
                ++broken;
                fprintf(stderr, "%s: labels %d and %d overlap\n", what, i, j);
            }
            if (!chart_drawn(a, l[j].x)) continue;
            double px, py;
            chart_to_pixel(a, l[j].x, l[j].y, &px, &py);
            /* gnuplot draws the point 4.95 px in radius: no label box may come within it. */
            if (chart_box_near_point(b, px, py, 4.95)) {
                ++broken;
                fprintf(stderr, "%s: label %d covers point %d\n", what, i, j);
            }
        }
        /* Near its own point: within the far ring (twice the gap, and half again for a corner),
         * or beside it at most three lines up or down (the last resort of a crowded point: its
         * near edge one gap off the point's x). */
        double px, py;
        chart_to_pixel(a, l[i].x, l[i].y, &px, &py);
        const double dx = px < b->x0 ? b->x0 - px : px > b->x1 ? px - b->x1 : 0.0;
        const double dy = py < b->y0 ? b->y0 - py : py > b->y1 ? py - b->y1 : 0.0;
        const double h = t->line_height;
        const bool ring = hypot(dx, dy) <= 2.0 * t->gap * 1.5 + 1e-9,
                   beside = dx <= t->gap + 1e-9 && dy <= 3.0 * (h + t->gap) - 0.5 * h + 1e-9;
        CHECK(ring || beside, "%s: label %d is %g px across and %g px up or down from its point", what, i, dx, dy);
    }
    CHECK(broken == 0, "%s: %d rules broken", what, broken);
    return broken;
}

static chart_label label(double x, double y, const char *text)
{
    return (chart_label){.x = x, .y = y, .chars = chart_utf8_chars(text)};
}

static void test_axes(void)
{
    chart_axes a;
    /* Times within 10x: both axes linear from 0, past the largest value. */
    const double x[] = {2.0, 2.05, 6.1, 6.15, 0.0}, y[] = {0.1664, 0.1632, 0.0838, 0.0775, 0.21};
    chart_fit_axes(x, y, 5, chart_report_plot(), &a);
    CHECK(!a.log_x, "linear within 10x");
    CHECK(a.x_min == 0.0 && a.y_min == 0.0, "both axes from 0: %g, %g", a.x_min, a.y_min);
    CHECK(a.x_max >= 6.15 && a.x_max <= 10.0, "x to a round value past 6.15: %g", a.x_max);
    CHECK(a.y_max >= 0.21 && a.y_max <= 0.3, "y to a round value past 0.21: %g", a.y_max);
    CHECK(chart_drawn(&a, 0.0), "a 0 ms row is drawn on a linear axis");
    /* Exactly 10x is not more than 10x. */
    const double x10[] = {1.5, 15.0};
    chart_fit_axes(x10, y, 2, chart_report_plot(), &a);
    CHECK(!a.log_x && a.x_min == 0.0, "10x: linear");
    /* More than 10x (the shoot-out: quarter-scale low against full-scale ultra): log, from the
     * decade at or below the fastest; a 0 ms row (none) is not drawn there; y still from 0. */
    const double xs[] = {0.93, 2.5, 46.0, 0.0}, ys[] = {0.19, 0.12, 0.038, 0.21};
    chart_fit_axes(xs, ys, 4, chart_report_plot(), &a);
    CHECK(a.log_x, "log past 10x");
    CHECK_NEAR(a.x_min, 0.1, 1e-12, "log axis from the decade below 0.93");
    CHECK(a.x_max >= 46.0 && a.x_max <= 100.0, "log axis to a round value past 46: %g", a.x_max);
    CHECK(a.y_min == 0.0 && a.y_max >= 0.21, "y from 0 on a log chart: %g..%g", a.y_min, a.y_max);
    CHECK(!chart_drawn(&a, 0.0) && chart_drawn(&a, 0.93), "0 ms not drawn on a log axis");
    const double xd[] = {1.0, 20.0};
    chart_fit_axes(xd, ys, 2, chart_report_plot(), &a);
    CHECK(a.log_x && a.x_min == 1.0, "a decade minimum is the axis's start: %g", a.x_min);
    /* Nothing to fit: a usable range all the same. */
    chart_fit_axes(NULL, NULL, 0, chart_report_plot(), &a);
    CHECK(a.x_max > a.x_min && a.y_max > a.y_min, "empty: %g..%g, %g..%g", a.x_min, a.x_max, a.y_min, a.y_max);
}

static void test_mapping(void)
{
    chart_axes a;
    const double x[] = {1.0, 5.0}, y[] = {0.1, 0.2};
    chart_fit_axes(x, y, 2, chart_report_plot(), &a);
    double px, py, bx, by;
    chart_to_pixel(&a, 0.0, 0.0, &px, &py);
    CHECK_NEAR(px, CHART_PLOT_LEFT, 1e-9, "x 0 on the left border");
    CHECK_NEAR(py, CHART_PLOT_BOTTOM, 1e-9, "y 0 on the bottom border (SVG y down)");
    chart_to_pixel(&a, a.x_max, a.y_max, &px, &py);
    CHECK_NEAR(px, CHART_PLOT_RIGHT, 1e-9, "x_max on the right border");
    CHECK_NEAR(py, CHART_PLOT_TOP, 1e-9, "y_max on the top border");
    chart_to_pixel(&a, 3.3, 0.123, &px, &py);
    chart_to_data(&a, px, py, &bx, &by);
    CHECK_NEAR(bx, 3.3, 1e-9, "round trip x");
    CHECK_NEAR(by, 0.123, 1e-12, "round trip y");
    const double xl[] = {0.5, 40.0};
    chart_fit_axes(xl, y, 2, chart_report_plot(), &a);
    chart_to_pixel(&a, 1.0, 0.0, &px, &py);
    double p10, p100;
    chart_to_pixel(&a, 10.0, 0.0, &p10, &py);
    chart_to_pixel(&a, 100.0, 0.0, &p100, &py);
    CHECK_NEAR(p10 - px, p100 - p10, 1e-9, "log axis: equal decades");
    chart_to_data(&a, p10, py, &bx, &by);
    CHECK_NEAR(bx, 10.0, 1e-9, "log round trip");
}

static void test_crowded(void)
{
    /* cornell:front at 160x120 (results.json): ssao and hbao 0.05 ms and 0.003 apart, gtao and
     * vbao the same, none at 0 ms; the Pareto front through all five. */
    chart_label l[] = {label(2.00, 0.1664, "ssao"), label(2.05, 0.1632, "hbao"), label(6.10, 0.0838, "gtao"),
                       label(6.15, 0.0775, "vbao"), label(0.0, 0.2101, "none")};
    const int n = 5;
    double x[5], y[5];
    for (int i = 0; i < n; ++i) x[i] = l[i].x, y[i] = l[i].y;
    chart_axes a;
    chart_fit_axes(x, y, n, chart_report_plot(), &a);
    const double fx[] = {0.0, 2.0, 2.05, 6.10, 6.15}, fy[] = {0.2101, 0.1664, 0.1632, 0.0838, 0.0775};
    const chart_line front = {fx, fy, 5};
    const int placed = chart_place_labels(&a, &CHART_REPORT_TEXT, l, n, NULL, &front);
    CHECK(placed == n, "every label of five has room: %d placed", placed);
    check_layout("crowded", &a, l, n);
    /* The first label has the first choice: right of its point, its text anchored there. */
    double px, py;
    chart_to_pixel(&a, l[0].x, l[0].y, &px, &py);
    CHECK(l[0].anchor == CHART_ANCHOR_LEFT && l[0].box.x0 > px, "ssao right of its point");
    /* gnuplot gets the anchor edge's x and the box's middle, in data space. */
    chart_to_pixel(&a, l[0].text_x, l[0].text_y, &px, &py);
    CHECK_NEAR(px, l[0].box.x0, 1e-6, "text x at the anchored edge");
    CHECK_NEAR(py, 0.5 * (l[0].box.y0 + l[0].box.y1), 1e-6, "text y at the box's middle");
    /* Long labels (a lists run) on the same points. */
    chart_label m[] = {label(2.00, 0.1664, "ssao · filter crease · ao 0.5 · quality ultra"),
                       label(2.05, 0.1632, "hbao · filter crease · ao 0.5 · quality ultra"),
                       label(6.10, 0.0838, "gtao · filter crease · ao 0.5 · quality ultra"),
                       label(6.15, 0.0775, "vbao · filter crease · ao 0.5 · quality ultra"),
                       label(0.0, 0.2101, "none · filter crease · ao 0.5")};
    chart_place_labels(&a, &CHART_REPORT_TEXT, m, n, NULL, &front);
    check_layout("crowded, long labels", &a, m, n);
}

static void test_pile(void)
{
    /* Twenty rows on one spot: some labels cannot be placed; those placed still keep every rule,
     * and the points of the labels left out are still kept clear. */
    enum { N = 20 };
    chart_label l[N];
    double x[N], y[N];
    for (int i = 0; i < N; ++i) {
        x[i] = 3.0 + 0.01 * i;
        y[i] = 0.10 + 0.0005 * i;
        l[i] = label(x[i], y[i], "gtao · ao 0.5");
    }
    chart_axes a;
    chart_fit_axes(x, y, N, chart_report_plot(), &a);
    const int placed = chart_place_labels(&a, &CHART_REPORT_TEXT, l, N, NULL, NULL);
    CHECK(placed >= 4 && placed < N, "a pile of %d: %d placed", N, placed);
    check_layout("pile", &a, l, N);
    /* In the given order: the first of order is placed first. */
    int order[N];
    for (int i = 0; i < N; ++i) order[i] = N - 1 - i;
    chart_place_labels(&a, &CHART_REPORT_TEXT, l, N, order, NULL);
    CHECK(l[N - 1].placed, "order: the first asked is placed");
    check_layout("pile, reversed", &a, l, N);
}

static void test_edges(void)
{
    /* A point in the top right corner and one at 0 ms on the left border: their labels inside. A
     * label wider than the plot is left out; the others are not held up by it. */
    chart_label l[] = {label(10.0, 0.25, "vbao · ao 1 · quality ultra"), label(0.0, 0.0, "none"),
                       label(5.0, 0.1, "a label far too long for any place in the chart: "
                                       "............................................................"
                                       "............................................................")};
    chart_axes a;
    const double x[] = {10.0, 0.0, 5.0}, y[] = {0.25, 0.0, 0.1};
    chart_fit_axes(x, y, 3, chart_report_plot(), &a);
    a.x_max = 10.0; /* the corner point exactly on the corner */
    a.y_max = 0.25;
    chart_place_labels(&a, &CHART_REPORT_TEXT, l, 3, NULL, NULL);
    CHECK(l[0].placed && l[1].placed, "corner and border labels placed: %d %d", l[0].placed, l[1].placed);
    CHECK(!l[2].placed, "a label wider than the plot is left out");
    check_layout("edges", &a, l, 3);
    /* On a log axis a 0 ms point is not drawn, so its label is not placed. */
    chart_label g[] = {label(0.5, 0.1, "alchemy · ao 0.25"), label(40.0, 0.05, "vbao"), label(0.0, 0.2, "none")};
    const double gx[] = {0.5, 40.0, 0.0}, gy[] = {0.1, 0.05, 0.2};
    chart_fit_axes(gx, gy, 3, chart_report_plot(), &a);
    CHECK(a.log_x, "log");
    CHECK(chart_place_labels(&a, &CHART_REPORT_TEXT, g, 3, NULL, NULL) == 2 && !g[2].placed, "none left out on log");
    check_layout("log", &a, g, 3);
}

static void test_helpers(void)
{
    CHECK(chart_utf8_chars("hbao \xc2\xb7 ao 0.5") == 13, "a middle dot is one character");
    CHECK(chart_utf8_chars("") == 0, "empty");
    const chart_box b = {10, 10, 20, 20}, c = {20, 10, 30, 20}, d = {19, 19, 25, 25};
    CHECK(!chart_boxes_overlap(&b, &c), "touching edges do not overlap");
    CHECK(chart_boxes_overlap(&b, &d) && chart_boxes_overlap(&d, &b), "a shared corner area overlaps");
    CHECK(chart_box_near_point(&b, 25, 15, 5.5) && !chart_box_near_point(&b, 25, 15, 4.5), "point distance");
    CHECK(chart_box_near_point(&b, 15, 15, 0.1), "a point inside");
    CHECK(chart_segment_crosses_box(0, 15, 40, 15, &b), "a segment through the box");
    CHECK(!chart_segment_crosses_box(0, 0, 40, 5, &b), "a segment above it");
    CHECK(chart_segment_crosses_box(15, 15, 16, 16, &b), "a segment inside it");
    CHECK(!chart_segment_crosses_box(0, 30, 30, 21, &b), "a segment past the corner");
}

/* test_report's lists (hbao x filter none, geometry x AO scale 1, 0.5 on cornell:front at 48x36),
 * at GPU times a loaded machine gave once: three long labels within a label's size of each other
 * at the left, and the fastest, first in order, had no free place among the 16 round it. Every
 * label of four must be placed. */
static void test_three_close(void)
{
    chart_label l[] = {label(3.10784, 0.185862, "hbao \u00b7 filter none \u00b7 ao 1"),
                       label(0.364742, 0.213144, "hbao \u00b7 filter none \u00b7 ao 0.5"),
                       label(0.792936, 0.199778, "hbao \u00b7 filter geometry \u00b7 ao 1"),
                       label(0.454284, 0.219978, "hbao \u00b7 filter geometry \u00b7 ao 0.5")};
    double x[4], y[4];
    for (int i = 0; i < 4; ++i) x[i] = l[i].x, y[i] = l[i].y;
    chart_axes a;
    chart_fit_axes(x, y, 4, chart_report_plot(), &a);
    const int order[4] = {1, 2, 0, 3}; /* the front by time, then the rest (compare_chart.c) */
    const double fx[] = {0.364742, 0.792936, 3.10784}, fy[] = {0.213144, 0.199778, 0.185862};
    const chart_line front = {fx, fy, 3};
    const int placed = chart_place_labels(&a, &CHART_REPORT_TEXT, l, 4, order, &front);
    CHECK(placed == 4, "three close points and one far: %d of 4 placed", placed);
    check_layout("three close", &a, l, 4);
}

int main(void)
{
    test_axes();
    test_mapping();
    test_crowded();
    test_three_close();
    test_pile();
    test_edges();
    test_helpers();
    return check_finish("chart_layout");
}
