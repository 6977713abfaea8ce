/* The error-against-time chart's geometry, worked out in C before gnuplot draws it (compare_chart.c):
 * the axes' ranges and where each row's label goes. Pure functions of numbers, no gnuplot and no
 * GL, so that tests/test_chart_layout.c can hold them to what the chart promises: both axes start
 * at zero, or the time axis is logarithmic from a decade at or below the fastest row when the times
 * spread over more than 10x; and no label covers another label or any point, and every label lies
 * inside the plot, or it is left out (the report's tables still have its row).
 *
 * Coordinates: data space is (time in ms, RMSE); pixel space is the SVG's, y down, in which the
 * script's explicit margins put the plot area at chart_axes.plot. */
#ifndef OB_APP_CHART_LAYOUT_H
#define OB_APP_CHART_LAYOUT_H

#include <stdbool.h>
#include <stddef.h>

typedef struct chart_box {
    double x0, y0, x1, y1; /* pixels: left, top, right, bottom (x0 <= x1, y0 <= y1) */
} chart_box;

typedef struct chart_axes {
    chart_box plot;        /* the plot area in pixels (the border gnuplot draws) */
    double x_min, x_max;   /* time, ms: 0 .. x_max, or a decade .. x_max when log_x */
    double y_min, y_max;   /* RMSE: always 0 .. y_max */
    bool log_x;
} chart_axes;

/* How big text and points are in pixels. */
typedef struct chart_text {
    double char_width;     /* estimated advance of one character: a label is chars x this wide */
    double line_height;    /* a label's box height */
    double point_radius;   /* a point's marker; no label box comes within it */
    double gap;            /* from a point's centre to its label's nearest edge */
    double padding;        /* kept free between two label boxes and between a box and the border */
} chart_text;

/* The report's chart (compare_chart.c): an SVG of CHART_W x CHART_H pixels whose script sets the
 * margins at exactly the plot area chart_report_plot gives (y down), so that these pixels are
 * gnuplot's; room on the left for the RMSE tics and title, below for the time tics and title. */
enum { CHART_W = 720, CHART_H = 420, CHART_PLOT_LEFT = 78, CHART_PLOT_RIGHT = 704, CHART_PLOT_TOP = 14,
       CHART_PLOT_BOTTOM = 362 };
chart_box chart_report_plot(void);
/* Its labels, in 'sans,10', and points ('pt 7 ps 1.2'). */
extern const chart_text CHART_REPORT_TEXT;

/* Which edge of its box a label's text is anchored at (gnuplot's left, right, center). */
typedef enum chart_anchor { CHART_ANCHOR_LEFT, CHART_ANCHOR_RIGHT, CHART_ANCHOR_CENTRE } chart_anchor;

typedef struct chart_label {
    double x, y;           /* the point it names, data space */
    int chars;             /* its text's length in characters (chart_utf8_chars) */
    /* out */
    bool placed;           /* false: left out (no free place near its point) */
    chart_box box;         /* the text's estimated box, pixels */
    chart_anchor anchor;
    double text_x, text_y; /* data space: where to hand gnuplot the text (the anchor edge's x, the
                              box's vertical middle) */
} chart_label;

/* Axes for n points (x >= 0, y >= 0) in the plot area `plot`: y from 0 to a round value above the
 * largest y; x the same, unless the positive x spread over more than 10x (largest / smallest):
 * then logarithmic, from the decade at or below the smallest positive x. Points at x = 0 are then
 * not drawn (chart_drawn). */
void chart_fit_axes(const double *x, const double *y, int n, chart_box plot, chart_axes *a);
/* Whether a point with this x can be drawn on a (a log axis has no 0). */
bool chart_drawn(const chart_axes *a, double x);
void chart_to_pixel(const chart_axes *a, double x, double y, double *px, double *py);
void chart_to_data(const chart_axes *a, double px, double py, double *x, double *y);

/* A polyline the labels keep off when they can (the Pareto front), data space. */
typedef struct chart_line {
    const double *x, *y;
    int count;
} chart_line;

/* Places labels[order[0]], labels[order[1]], ... (the first have the first choice) one at a time:
 * each takes the first of its candidate places around its point (right, left, the four corners,
 * above, below; then the same twice as far out) whose box lies inside the plot, meets no box placed
 * before it and covers no point of the n (drawn ones; a label whose own point is not drawn is left
 * out); of those, one that also keeps off the line when there is one. Returns how many were
 * placed. order may be NULL (labels' own order), line NULL (no line). */
int chart_place_labels(const chart_axes *a, const chart_text *t, chart_label *labels, int n, const int *order,
                       const chart_line *line);
/* Whether the segment (ax, ay)-(bx, by) passes through the box (pixels). */
bool chart_segment_crosses_box(double ax, double ay, double bx, double by, const chart_box *b);

/* Whether two boxes share any area (touching edges do not). */
bool chart_boxes_overlap(const chart_box *a, const chart_box *b);
/* Whether a box comes within radius r of the point (px, py). */
bool chart_box_near_point(const chart_box *b, double px, double py, double r);
/* Characters of a UTF-8 string (bytes that do not continue a sequence). */
int chart_utf8_chars(const char *s);

#endif
