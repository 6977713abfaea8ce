/* The chart's axes and label places (chart_layout.h). */
#include "chart_layout.h"

#include <math.h>
#include <stdlib.h>

chart_box chart_report_plot(void)
{
    return (chart_box){CHART_PLOT_LEFT, CHART_PLOT_TOP, CHART_PLOT_RIGHT, CHART_PLOT_BOTTOM};
}

/* About 0.6 em a character in DejaVu Sans, the browsers' sans on Debian (the widest lowercase
 * letters, m and w, are 0.97 and 0.82 em; a label of names and numbers averages under 0.6), boxes
 * 1.2 em high (gnuplot centres a label's text on its y); gnuplot's SVG draws a 'pt 7 ps 1.2' point
 * 4.95 px in radius: kept 6.5 px clear. */
const chart_text CHART_REPORT_TEXT = {.char_width = 6.2, .line_height = 12.0, .point_radius = 6.5, .gap = 9.0,
                                      .padding = 2.0};

/* The smallest round number (1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6, 8 times a power of ten) at or above
 * v > 0: an axis end gnuplot's tics divide evenly. */
static double round_up(double v)
{
    static const double steps[] = {1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0};
    const double decade = pow(10.0, floor(log10(v)));
    for (size_t i = 0; i < sizeof steps / sizeof steps[0]; ++i)
        if (steps[i] * decade >= v * (1.0 - 1e-12)) return steps[i] * decade;
    return 10.0 * decade;
}

void chart_fit_axes(const double *x, const double *y, int n, chart_box plot, chart_axes *a)
{
    double x_lo = INFINITY, x_hi = 0.0, y_hi = 0.0;
    for (int i = 0; i < n; ++i) {
        if (x[i] > 0.0 && x[i] < x_lo) x_lo = x[i];
        if (x[i] > x_hi) x_hi = x[i];
        if (y[i] > y_hi) y_hi = y[i];
    }
    *a = (chart_axes){.plot = plot, .x_min = 0.0, .y_min = 0.0};
    /* Headroom past the largest value, so that no point sits on the top or right border. */
    a->y_max = y_hi > 0.0 ? round_up(1.08 * y_hi) : 1.0;
    a->log_x = x_hi > 0.0 && x_hi > 10.0 * x_lo;
    if (a->log_x) {
        a->x_min = pow(10.0, floor(log10(x_lo)));
        a->x_max = round_up(1.15 * x_hi);
    } else {
        a->x_max = x_hi > 0.0 ? round_up(1.08 * x_hi) : 1.0;
    }
}

bool chart_drawn(const chart_axes *a, double x) { return !a->log_x || x > 0.0; }

/* x as the fraction of the axis's width from its left end. */
static double x_fraction(const chart_axes *a, double x)
{
    if (a->log_x) return (log10(x) - log10(a->x_min)) / (log10(a->x_max) - log10(a->x_min));
    return (x - a->x_min) / (a->x_max - a->x_min);
}

void chart_to_pixel(const chart_axes *a, double x, double y, double *px, double *py)
{
    *px = a->plot.x0 + x_fraction(a, x) * (a->plot.x1 - a->plot.x0);
    *py = a->plot.y1 - (y - a->y_min) / (a->y_max - a->y_min) * (a->plot.y1 - a->plot.y0);
}

void chart_to_data(const chart_axes *a, double px, double py, double *x, double *y)
{
    const double f = (px - a->plot.x0) / (a->plot.x1 - a->plot.x0);
    if (a->log_x) *x = pow(10.0, log10(a->x_min) + f * (log10(a->x_max) - log10(a->x_min)));
    else *x = a->x_min + f * (a->x_max - a->x_min);
    *y = a->y_min + (a->plot.y1 - py) / (a->plot.y1 - a->plot.y0) * (a->y_max - a->y_min);
}

bool chart_boxes_overlap(const chart_box *a, const chart_box *b)
{
    return a->x0 < b->x1 && b->x0 < a->x1 && a->y0 < b->y1 && b->y0 < a->y1;
}

bool chart_box_near_point(const chart_box *b, double px, double py, double r)
{
    const double dx = px < b->x0 ? b->x0 - px : px > b->x1 ? px - b->x1 : 0.0;
    const double dy = py < b->y0 ? b->y0 - py : py > b->y1 ? py - b->y1 : 0.0;
    return dx * dx + dy * dy < r * r;
}

int chart_utf8_chars(const char *s)
{
    int n = 0;
    for (const unsigned char *p = (const unsigned char *)s; *p; ++p) n += (*p & 0xC0) != 0x80;
    return n;
}

bool chart_segment_crosses_box(double ax, double ay, double bx, double by, const chart_box *b)
{
    /* Liang-Barsky: clip the segment's parameter t in [0, 1] against each side of the box. */
    const double dx = bx - ax, dy = by - ay;
    const double p[4] = {-dx, dx, -dy, dy}, q[4] = {ax - b->x0, b->x1 - ax, ay - b->y0, b->y1 - ay};
    double t0 = 0.0, t1 = 1.0;
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0.0) {
            if (q[i] < 0.0) return false; /* parallel to this side and outside it */
            continue;
        }
        const double t = q[i] / p[i];
        if (p[i] < 0.0) t0 = t > t0 ? t : t0;
        else t1 = t < t1 ? t : t1;
        if (t0 > t1) return false;
    }
    return true;
}

/* Whether the box crosses the line (its drawn points' segments). */
static bool box_on_line(const chart_axes *a, const chart_line *line, const chart_box *b)
{
    if (!line) return false;
    double px = 0.0, py = 0.0;
    bool have = false;
    for (int i = 0; i < line->count; ++i) {
        if (!chart_drawn(a, line->x[i])) continue;
        double qx, qy;
        chart_to_pixel(a, line->x[i], line->y[i], &qx, &qy);
        if (have && chart_segment_crosses_box(px, py, qx, qy, b)) return true;
        px = qx, py = qy, have = true;
    }
    return false;
}

/* Candidate k's box for a w x h label of the point (px, py), and the edge its text is anchored at:
 * eight places around the point, then the same eight twice as far out. The sides come first (the
 * text reads on from its point), the corners next, straight above and below last. Then, for a
 * point with others close on both sides (three rows within a label's width and height of each
 * other: the lists' test caught one, at random GPU times, with no place left of 16), its sides
 * again one, two and three lines up and down, the text still starting at the point's x. false past
 * the last candidate. */
enum { CANDIDATES = 28 };
static bool candidate(int k, double px, double py, double w, double h, double gap, chart_box *b, chart_anchor *anchor)
{
    if (k < 0 || k >= CANDIDATES) return false;
    if (k >= 16) {
        const int j = k - 16, lines = 1 + j / 4;
        const bool right = (j & 2) == 0, up = (j & 1) == 0;
        const double x0 = right ? px + gap : px - gap - w, y0 = py - 0.5 * h + (up ? -1.0 : 1.0) * lines * (h + gap);
        *anchor = right ? CHART_ANCHOR_LEFT : CHART_ANCHOR_RIGHT;
        *b = (chart_box){x0, y0, x0 + w, y0 + h};
        return true;
    }
    /* A corner's box starts 3/4 of the gap off each axis: ~1.06 gaps from the point, clear of it. */
    const double g = k < 8 ? gap : 2.0 * gap, half = 0.75 * g;
    double x0 = 0.0, y0 = 0.0;
    switch (k % 8) {
    case 0: x0 = px + g, y0 = py - 0.5 * h, *anchor = CHART_ANCHOR_LEFT; break;            /* right */
    case 1: x0 = px - g - w, y0 = py - 0.5 * h, *anchor = CHART_ANCHOR_RIGHT; break;       /* left */
    case 2: x0 = px + half, y0 = py - half - h, *anchor = CHART_ANCHOR_LEFT; break;        /* above right */
    case 3: x0 = px + half, y0 = py + half, *anchor = CHART_ANCHOR_LEFT; break;            /* below right */
    case 4: x0 = px - half - w, y0 = py - half - h, *anchor = CHART_ANCHOR_RIGHT; break;   /* above left */
    case 5: x0 = px - half - w, y0 = py + half, *anchor = CHART_ANCHOR_RIGHT; break;       /* below left */
    case 6: x0 = px - 0.5 * w, y0 = py - g - h, *anchor = CHART_ANCHOR_CENTRE; break;      /* above */
    default: x0 = px - 0.5 * w, y0 = py + g, *anchor = CHART_ANCHOR_CENTRE; break;        /* below */
    }
    *b = (chart_box){x0, y0, x0 + w, y0 + h};
    return true;
}

/* Whether box b (label `self`'s) is free: inside the plot, clear of every placed box by the
 * padding, and of every drawn point by its radius. */
static bool box_free(const chart_axes *a, const chart_text *t, const chart_label *labels, int n, int self,
                     const chart_box *b)
{
    const double pad = t->padding;
    if (b->x0 < a->plot.x0 + pad || b->x1 > a->plot.x1 - pad || b->y0 < a->plot.y0 + pad || b->y1 > a->plot.y1 - pad)
        return false;
    const chart_box grown = {b->x0 - pad, b->y0 - pad, b->x1 + pad, b->y1 + pad};
    for (int i = 0; i < n; ++i) {
        if (i != self && labels[i].placed && chart_boxes_overlap(&grown, &labels[i].box)) return false;
        if (!chart_drawn(a, labels[i].x)) continue;
        double px, py;
        chart_to_pixel(a, labels[i].x, labels[i].y, &px, &py);
        if (chart_box_near_point(b, px, py, t->point_radius)) return false;
    }
    return true;
}

/* Label i at its first free candidate place off the line, else its first free one, if any. */
static bool place_one(const chart_axes *a, const chart_text *t, chart_label *labels, int n, int i,
                      const chart_line *line)
{
    chart_label *l = &labels[i];
    if (!chart_drawn(a, l->x) || l->chars <= 0) return false;
    double px, py;
    chart_to_pixel(a, l->x, l->y, &px, &py);
    const double w = l->chars * t->char_width, h = t->line_height;
    chart_box b;
    chart_anchor anchor;
    /* Every candidate off the line first, then every candidate again, the line allowed. */
    for (int k = 0; k < 2 * CANDIDATES; ++k) {
        candidate(k % CANDIDATES, px, py, w, h, t->gap, &b, &anchor);
        if ((k < CANDIDATES && box_on_line(a, line, &b)) || !box_free(a, t, labels, n, i, &b)) continue;
        l->placed = true;
        l->box = b;
        l->anchor = anchor;
        const double tx = anchor == CHART_ANCHOR_LEFT ? b.x0 : anchor == CHART_ANCHOR_RIGHT ? b.x1 : 0.5 * (b.x0 + b.x1);
        chart_to_data(a, tx, 0.5 * (b.y0 + b.y1), &l->text_x, &l->text_y);
        return true;
    }
    return false;
}

int chart_place_labels(const chart_axes *a, const chart_text *t, chart_label *labels, int n, const int *order,
                       const chart_line *line)
{
    for (int i = 0; i < n; ++i) labels[i].placed = false;
    int placed = 0;
    for (int k = 0; k < n; ++k) {
        const int i = order ? order[k] : k;
        if (i >= 0 && i < n && !labels[i].placed) placed += place_one(a, t, labels, n, i, line);
    }
    return placed;
}
