/* obscura compare's chart: each view's error (RMSE) against the AO's GPU time, with the rows'
 * Pareto front, drawn by gnuplot into REPORT/VIEW/chart.svg (index.html inlines it). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "compare.h"
#include "run_program.h"

/* A row's label as one double-quoted field of gnuplot's inline data. gnuplot reads a quoted field
 * up to the next '"' with no escapes, and a line break would end the row (or spell the block's
 * closing "EOD"), so '"', '\\' and control bytes become '_'; invalid UTF-8 would make the whole
 * SVG unreadable to a browser, so it becomes U+FFFD first. Labels are registry names and numbers
 * today (cli_config_label): this keeps any later source of text from reaching gnuplot as syntax.
 * '`' and '@' stay: lines of a datablock are data, not commands, and gnuplot substitutes neither
 * backquotes nor macros in them. */
static void chart_label(char *out, size_t n, const char *label)
{
    char *valid = cli_utf8_valid(label);
    const char *src = valid ? valid : "";
    size_t k = 0;
    for (const unsigned char *p = (const unsigned char *)src; *p && k + 1 < n; ++p)
        out[k++] = *p == '"' || *p == '\\' || *p < 0x20 || *p == 0x7f ? '_' : (char)*p;
    out[k] = '\0';
    free(valid);
}

/* Quality against time for one view, as SVG through gnuplot (Debian's gnuplot-nox). No path and
 * no name the user gave reaches gnuplot or a shell (issue 44): gnuplot runs without one
 * (cli_spawn), reads the script on stdin from a file we opened, finds its data inline in the
 * script, and writes the SVG to its stdout, which we write into the report ourselves. The
 * script holds nothing but our own text and the sanitised labels (chart_label). */
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
    fprintf(f, "set encoding utf8\n"
               "set terminal svg size 560,360 font 'sans,11' background rgb 'white' noenhanced\n"
               "set xlabel 'AO ms: pass + depth MIPs + filter + upsampling (GPU timestamps)'\n"
               "set ylabel 'RMSE against the reference'\n"
               "set grid\n"
               "unset key\n"
               "set offsets graph 0.05, graph 0.15, graph 0.1, graph 0.1\n");
    /* Labels in double quotes: gnuplot reads "hbao · filter none" as one column. Past 16 rows the
     * labels would cover each other: only the front's are written. */
    fputs("$points << EOD\n", f);
    for (int k = 0; k < vr->method_count; ++k) {
        char label[CLI_MAX_LABEL] = "";
        if (vr->method_count <= 16 || vr->methods[k].pareto) chart_label(label, sizeof label, vr->methods[k].label);
        fprintf(f, "%.6f %.6f \"%s\"\n", vr->methods[k].chain_ms, vr->methods[k].m.rmse, label);
    }
    /* The Pareto front in order of time, drawn as a line. */
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
        fprintf(f, "%.6f %.6f\n", vr->methods[next].chain_ms, vr->methods[next].m.rmse);
    }
    fputs("EOD\n"
          "plot $points using 1:2 with points pt 7 ps 1.2 lc rgb '#3060a0', "
          "$points using 1:2:3 with labels offset 0.8,0.6 left font 'sans,10', "
          "$front using 1:2 with lines lw 1.5 lc rgb '#c05020' title 'Pareto front'\n",
          f);
    if (fflush(f) != 0 || ferror(f) || fseek(f, 0, SEEK_SET) != 0) {
        int e = errno;
        fclose(f);
        return cli_fail(EXIT_OUTPUT, "--report %s: cannot write %s/chart.gp: %s", shown, vr->dir, strerror(e));
    }
    /* A chart of 256 rows is about 100 KB of SVG; 16 MiB is far beyond any. */
    cli_spawn_output svg = {.limit = 16u << 20}, err = {.limit = 4096};
    const char *argv[] = {"gnuplot", NULL};
    int status = -1;
    int e = cli_spawn(argv, fileno(f), &svg, &err, &status);
    fclose(f);
    remove(script);
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

