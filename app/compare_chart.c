/* obscura compare's chart: each view's error (RMSE) against the AO's GPU time, with the rows'
 * Pareto front, drawn by gnuplot into REPORT/VIEW/chart.svg (index.html inlines it) from the script
 * REPORT/VIEW/chart.gp, which stays in the report (gnuplot < chart.gp > chart.svg draws it again).
 *
 * gnuplot places nothing by itself: the axes' ranges and every label's place are worked out here
 * (chart_layout.h) for the terminal's size and the plot area the script's margins fix, and handed
 * to gnuplot as numbers. gnuplot's own labels sit at one offset from every point, and on a view
 * where two methods land almost on the same spot (gtao and vbao, ssao and hbao) they covered each
 * other and the points. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "chart_layout.h"
#include "compare.h"
#include "run_program.h"

/* A row's label as one double-quoted field of gnuplot's inline data. gnuplot reads a quoted field
 * up to the next '"' with no escapes, and a line break would end the row (or spell the block's
 * closing "EOD"), so '"', '\\' and control bytes become '_'; invalid UTF-8 would make the whole
 * SVG unreadable to a browser, so it becomes U+FFFD first. Labels are registry names and numbers
 * today (cli_config_label): this keeps any later source of text from reaching gnuplot as syntax.
 * '`' and '@' stay: lines of a datablock are data, not commands, and gnuplot substitutes neither
 * backquotes nor macros in them. */
static void chart_label_text(char *out, size_t n, const char *label)
{
    char *valid = cli_utf8_valid(label);
    const char *src = valid ? valid : "";
    size_t k = 0;
    for (const unsigned char *p = (const unsigned char *)src; *p && k + 1 < n; ++p)
        out[k++] = *p == '"' || *p == '\\' || *p < 0x20 || *p == 0x7f ? '_' : (char)*p;
    out[k] = '\0';
    free(valid);
}

/* The chart's points (on a log axis those at 0 ms are not drawn), axes and labels, placed with the
 * Pareto front's rows first (fastest first), then the rest from the most accurate. labels and
 * order hold method_count each. */
static void chart_layout(const view_result *vr, chart_axes *a, chart_label *labels, int *order, char (*text)[CLI_MAX_LABEL])
{
    const int n = vr->method_count;
    double *x = malloc((size_t)n * sizeof *x), *y = malloc((size_t)n * sizeof *y);
    for (int k = 0; x && y && k < n; ++k) {
        x[k] = vr->methods[k].chain_ms;
        y[k] = vr->methods[k].m.rmse;
    }
    chart_fit_axes(x, y, x && y ? n : 0, chart_report_plot(), a);
    free(x);
    free(y);
    for (int k = 0; k < n; ++k) {
        chart_label_text(text[k], sizeof text[k], vr->methods[k].label);
        labels[k] = (chart_label){.x = vr->methods[k].chain_ms, .y = vr->methods[k].m.rmse,
                                  .chars = chart_utf8_chars(text[k])};
        order[k] = k;
    }
    /* Insertion sort: the front before the rest, the front by time, the rest by RMSE. */
    for (int i = 1; i < n; ++i)
        for (int j = i; j > 0; --j) {
            const method_result *p = &vr->methods[order[j - 1]], *q = &vr->methods[order[j]];
            const bool before = q->pareto != p->pareto ? q->pareto
                                : q->pareto        ? q->chain_ms < p->chain_ms
                                                   : q->m.rmse < p->m.rmse;
            if (!before) break;
            const int t = order[j - 1];
            order[j - 1] = order[j];
            order[j] = t;
        }
    /* The front's line, in order of time: the labels keep off it where they can. */
    double *fx = malloc((size_t)n * sizeof *fx), *fy = malloc((size_t)n * sizeof *fy);
    chart_line front = {fx, fy, 0};
    for (int k = 0; fx && fy && k < n; ++k) {
        const method_result *m = &vr->methods[order[k]];
        if (!m->pareto) break; /* the front comes first in order, fastest first */
        fx[front.count] = m->chain_ms;
        fy[front.count++] = m->m.rmse;
    }
    chart_place_labels(a, &CHART_REPORT_TEXT, labels, n, order, fx && fy ? &front : NULL);
    free(fx);
    free(fy);
}

/* The script's settings: the terminal, the margins at the plot area chart_layout worked in, the
 * axes' ranges and titles. */
static void script_frame(FILE *f, const view_result *vr, const chart_axes *a)
{
    fprintf(f, "# obscura compare: %s's error against time (gnuplot < chart.gp > chart.svg draws it again)\n"
               "set encoding utf8\n"
               "set terminal svg size %d,%d font 'sans,11' background rgb 'white' noenhanced\n"
               "set lmargin at screen %.6f\nset rmargin at screen %.6f\n"
               "set tmargin at screen %.6f\nset bmargin at screen %.6f\n",
            vr->dir, CHART_W, CHART_H, (double)CHART_PLOT_LEFT / CHART_W, (double)CHART_PLOT_RIGHT / CHART_W,
            1.0 - (double)CHART_PLOT_TOP / CHART_H, 1.0 - (double)CHART_PLOT_BOTTOM / CHART_H);
    int hidden = 0;
    for (int k = 0; k < vr->method_count; ++k) hidden += !chart_drawn(a, vr->methods[k].chain_ms);
    char note[96] = "";
    if (a->log_x && hidden) snprintf(note, sizeof note, "; %d row%s at 0 ms not drawn", hidden, hidden == 1 ? "" : "s");
    fprintf(f, "set xlabel 'AO ms: pass + depth MIPs + filter + upsampling (GPU timestamps)%s%s'\n",
            a->log_x ? ", log scale" : "", note);
    if (a->log_x) fputs("set logscale x 10\nset mxtics 10\n", f);
    fprintf(f, "set xrange [%.9g:%.9g]\nset yrange [%.9g:%.9g]\n", a->x_min, a->x_max, a->y_min, a->y_max);
    fputs("set ylabel 'RMSE against the reference'\n"
          "set grid\n"
          "unset key\n",
          f);
}

/* The data, inline: the points, the Pareto front in order of time, and the placed labels in one
 * block per anchor (gnuplot justifies a whole plot element one way). Labels in double quotes:
 * gnuplot reads "hbao · filter none" as one column. Returns which label blocks have rows. */
static unsigned script_data(FILE *f, const view_result *vr, const chart_axes *a, const chart_label *labels,
                            char (*text)[CLI_MAX_LABEL])
{
    fputs("$points << EOD\n", f);
    for (int k = 0; k < vr->method_count; ++k)
        if (chart_drawn(a, vr->methods[k].chain_ms))
            fprintf(f, "%.9g %.9g\n", vr->methods[k].chain_ms, vr->methods[k].m.rmse);
    fputs("EOD\n$front << EOD\n", f);
    double last = -1.0;
    for (;;) {
        int next = -1;
        for (int k = 0; k < vr->method_count; ++k) {
            const method_result *m = &vr->methods[k];
            if (m->pareto && m->chain_ms > last && (next < 0 || m->chain_ms < vr->methods[next].chain_ms)) next = k;
        }
        if (next < 0) break;
        last = vr->methods[next].chain_ms;
        if (chart_drawn(a, last)) fprintf(f, "%.9g %.9g\n", last, vr->methods[next].m.rmse);
    }
    fputs("EOD\n", f);
    static const char *const blocks[3] = {"left", "right", "centre"};
    unsigned used = 0;
    for (int b = 0; b < 3; ++b) {
        fprintf(f, "$%s << EOD\n", blocks[b]);
        for (int k = 0; k < vr->method_count; ++k)
            if (labels[k].placed && (int)labels[k].anchor == b) {
                fprintf(f, "%.9g %.9g \"%s\"\n", labels[k].text_x, labels[k].text_y, text[k]);
                used |= 1u << b;
            }
        fputs("EOD\n", f);
    }
    return used;
}

/* The whole script into f: frame, data and the plot command. */
static void write_script(FILE *f, const view_result *vr)
{
    const int n = vr->method_count > 0 ? vr->method_count : 1;
    chart_label *labels = calloc((size_t)n, sizeof *labels);
    int *order = calloc((size_t)n, sizeof *order);
    char(*text)[CLI_MAX_LABEL] = calloc((size_t)n, sizeof *text);
    chart_axes a;
    if (labels && order && text) chart_layout(vr, &a, labels, order, text);
    else chart_fit_axes(NULL, NULL, 0, chart_report_plot(), &a);
    script_frame(f, vr, &a);
    const unsigned used = labels && order && text ? script_data(f, vr, &a, labels, text) : 0u;
    /* The labels are drawn in the box chart_layout gave them: no offset. */
    fputs("plot $points using 1:2 with points pt 7 ps 1.2 lc rgb '#3060a0', "
          "$front using 1:2 with lines lw 1.5 lc rgb '#c05020'",
          f);
    static const char *const clause[3] = {", $left using 1:2:3 with labels left font 'sans,10'",
                                          ", $right using 1:2:3 with labels right font 'sans,10'",
                                          ", $centre using 1:2:3 with labels center font 'sans,10'"};
    for (int b = 0; b < 3; ++b)
        if (used & (1u << b)) fputs(clause[b], f);
    fputs("\n", f);
    free(labels);
    free(order);
    free(text);
}

/* gnuplot, run on the script (f, rewound), its SVG written to svg_path. */
static int run_gnuplot(FILE *f, const char *shown, const view_result *vr, const char *svg_path)
{
    /* A chart of 256 rows is about 100 KB of SVG; 16 MiB is far beyond any. */
    cli_spawn_output svg = {.limit = 16u << 20}, err = {.limit = 4096};
    const char *argv[] = {"gnuplot", NULL};
    int status = -1;
    int e = cli_spawn(argv, fileno(f), &svg, &err, &status);
    int code = EXIT_OK;
    char why[256] = "";
    cli_spawn_last_line(&err, why, sizeof why);
    if (e == ENOENT) {
        code = cli_fail(EXIT_RUNTIME, "--report %s: cannot draw %s/chart.svg: gnuplot is not installed (Debian: "
                                      "gnuplot-nox; scripts/install-deps.sh)",
                        shown, vr->dir);
    } else if (e != 0) {
        code = cli_fail(EXIT_RUNTIME, "--report %s: cannot run gnuplot for %s/chart.svg: %s", shown, vr->dir, strerror(e));
    } else if (status != 0 || svg.len == 0 || svg.truncated) {
        code = cli_fail(EXIT_RUNTIME, "--report %s: gnuplot failed to draw %s/chart.svg (%s%d): %s", shown, vr->dir,
                        status != 0 ? "exit status " : "no SVG, exit status ", status,
                        why[0] ? why : svg.truncated ? "more than 16 MiB of SVG" : "it said nothing");
    } else {
        FILE *s = fopen(svg_path, "wb");
        bool ok = s && fwrite(svg.data, 1, svg.len, s) == svg.len;
        int we = errno;
        if (s && fclose(s) != 0 && ok) {
            ok = false;
            we = errno;
        }
        if (!ok) code = cli_fail(EXIT_OUTPUT, "--report %s: cannot write %s/chart.svg: %s", shown, vr->dir, strerror(we));
    }
    cli_spawn_output_free(&svg);
    cli_spawn_output_free(&err);
    return code;
}

/* Quality against time for one view, as SVG through gnuplot (Debian's gnuplot-nox). No path and
 * no name the user gave reaches gnuplot or a shell (issue 44): gnuplot runs without one
 * (cli_spawn), reads the script on stdin from a file we opened, finds its data inline in the
 * script, and writes the SVG to its stdout, which we write into the report ourselves. The
 * script holds nothing but our own text, numbers and the sanitised labels (chart_label_text), the
 * labels as data, never in a command. */
int compare_write_chart(const compare_opts *o, const view_result *vr, report_files *out)
{
    const char *shown = o->final_report ? o->final_report : o->report; /* messages name --report */
    char svg_path[700], script[700];
    snprintf(svg_path, sizeof svg_path, "%s/%s/chart.svg", o->report, vr->dir);
    snprintf(script, sizeof script, "%s/%s/chart.gp", o->report, vr->dir);
    if (!compare_track_file(out, script) || !compare_track_file(out, svg_path)) return cli_fail(EXIT_RUNTIME, "out of memory");
    /* w+: the same descriptor becomes gnuplot's stdin once rewound. */
    FILE *f = fopen(script, "w+");
    if (!f) return cli_fail(EXIT_OUTPUT, "--report %s: cannot write %s/chart.gp: %s", shown, vr->dir, strerror(errno));
    write_script(f, vr);
    if (fflush(f) != 0 || ferror(f) || fseek(f, 0, SEEK_SET) != 0) {
        int e = errno;
        fclose(f);
        return cli_fail(EXIT_OUTPUT, "--report %s: cannot write %s/chart.gp: %s", shown, vr->dir, strerror(e));
    }
    int code = run_gnuplot(f, shown, vr, svg_path);
    if (fclose(f) != 0 && code == EXIT_OK)
        code = cli_fail(EXIT_OUTPUT, "--report %s: cannot write %s/chart.gp: %s", shown, vr->dir, strerror(errno));
    return code;
}
