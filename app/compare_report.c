/* obscura compare's report: results.json (every number) and index.html (the tables, the images and
 * each view's chart, inlined), from the views compare.c ran. Both are written whole or not at
 * all: into the report's temporary directory (compare.h), index.html through a .tmp file. Every
 * number of results.json goes through cli_json_add_number: 6 significant digits, whole numbers as
 * they are (a float setting such as 0.1f comes out 0.1). */
#include <cjson/cJSON.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "compare.h"
#include "run_program.h"

/* ---- what the rows say together ------------------------------------------------------------ */

/* The rows on the error/time Pareto front: no other row is at most as slow (AO chain ms) and
 * strictly more accurate, or as accurate and strictly faster. */
void compare_mark_pareto(view_result *vr)
{
    for (int k = 0; k < vr->method_count; ++k) {
        method_result *a = &vr->methods[k];
        a->pareto = true;
        for (int j = 0; j < vr->method_count && a->pareto; ++j) {
            const method_result *b = &vr->methods[j];
            if (j == k) continue;
            bool dominates = b->chain_ms <= a->chain_ms && b->m.rmse <= a->m.rmse &&
                             (b->chain_ms < a->chain_ms || b->m.rmse < a->m.rmse);
            if (dominates) a->pareto = false;
        }
    }
}

/* The shoot-out's answer for one method: its most accurate row within the budget (-1 = none),
 * and its fastest row (for "over budget by"). */
static void best_within(const view_result *vr, const char *method, double budget, int *best, int *fastest)
{
    *best = *fastest = -1;
    for (int k = 0; k < vr->method_count; ++k) {
        const method_result *m = &vr->methods[k];
        if (strcmp(m->name, method)) continue;
        if (*fastest < 0 || m->chain_ms < vr->methods[*fastest].chain_ms) *fastest = k;
        if (m->chain_ms <= budget && (*best < 0 || m->m.rmse < vr->methods[*best].m.rmse)) *best = k;
    }
}

/* Each method once, in the order of its first row. */
static int method_names(const view_result *vr, const char **names, int max)
{
    int n = 0;
    for (int k = 0; k < vr->method_count; ++k) {
        bool seen = false;
        for (int j = 0; j < n; ++j) seen = seen || !strcmp(names[j], vr->methods[k].name);
        if (!seen && n < max) names[n++] = vr->methods[k].name;
    }
    return n;
}

/* The report's views of one set of scenes/views.json: how many, and each row's mean RMSE over them
 * into mean[0 .. rows) (every view has the same rows, in the same order). */
static const char *const view_set_names[2] = {"choose", "check"};
static int set_means(const view_result *views, int count, const char *set, double *mean, int rows)
{
    int n = 0;
    for (int k = 0; k < rows; ++k) mean[k] = 0.0;
    for (int v = 0; v < count; ++v) {
        if (!views[v].set || strcmp(views[v].set, set) || views[v].method_count != rows) continue;
        for (int k = 0; k < rows; ++k) mean[k] += views[v].methods[k].m.rmse;
        ++n;
    }
    for (int k = 0; k < rows && n; ++k) mean[k] /= n;
    return n;
}

/* The answer to "which method, at what cost?" across the report's views, one entry per row: mean
 * RMSE and bias, mean rank by RMSE (1 = the closest), wins (views where no row is closer), median
 * AO-pass ms, and whether the row is on the front (no other row is both as fast and closer, or
 * faster and as close). Every view has the same rows in the same order. */
typedef struct row_summary {
    double rmse, bias, rank, ao_ms;
    int wins;
    bool front;
} row_summary;

static int compare_doubles(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static row_summary *summarise(const view_result *views, int count, int rows)
{
    row_summary *r = rows > 0 ? calloc((size_t)rows, sizeof *r) : NULL;
    double *ms = count > 0 ? calloc((size_t)count, sizeof *ms) : NULL;
    if (!r || !ms) {
        free(r);
        free(ms);
        return NULL;
    }
    int used = 0;
    for (int v = 0; v < count; ++v) {
        if (views[v].method_count != rows) continue;
        ++used;
        const method_result *m = views[v].methods;
        for (int k = 0; k < rows; ++k) {
            int better = 0;
            for (int j = 0; j < rows; ++j) better += m[j].m.rmse < m[k].m.rmse;
            r[k].rmse += m[k].m.rmse;
            r[k].bias += m[k].m.bias;
            r[k].rank += 1.0 + better;
            r[k].wins += better == 0;
        }
    }
    for (int k = 0; k < rows; ++k) {
        int n = 0;
        for (int v = 0; v < count; ++v)
            if (views[v].method_count == rows) ms[n++] = views[v].methods[k].ao_ms;
        qsort(ms, (size_t)n, sizeof *ms, compare_doubles);
        r[k].ao_ms = n ? (n & 1 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2])) : 0.0;
        if (used) r[k].rmse /= used, r[k].bias /= used, r[k].rank /= used;
    }
    for (int k = 0; k < rows; ++k) {
        r[k].front = true;
        for (int j = 0; j < rows && r[k].front; ++j)
            r[k].front = !(j != k && r[j].rmse <= r[k].rmse && r[j].ao_ms <= r[k].ao_ms &&
                           (r[j].rmse < r[k].rmse || r[j].ao_ms < r[k].ao_ms));
    }
    free(ms);
    return r;
}

/* ---- results.json -------------------------------------------------------------------------- */

/* What made the numbers: the tool, its commit, the command line as given, the GPU and the run's
 * settings. */
static void json_run(cJSON *root, const compare_opts *o)
{
    cJSON_AddStringToObject(root, "version", OB_VERSION_STRING);
    cli_json_commit_and_command(root, o->argc, o->argv);
    cJSON_AddStringToObject(root, "renderer", o->renderer);
    cJSON_AddStringToObject(root, "gl_version", o->gl_version);
    if (o->shard.count > 1) {
        /* One of N shards (--shard K/N): which views went where, for obscura merge. */
        cli_shard_json(root, &o->shard, o->views, o->owner, o->view_count);
    }
    /* What the rows' ms are: frame_ms is easily read as the frame's wall-clock time, which it is not. */
    cJSON_AddStringToObject(root, "timing", "GPU ms from GL_TIMESTAMP queries around each pass, medians of 5 frames: "
                                            "ao_ms the AO pass, chain_ms the AO chain (AO pass, depth MIPs, edges, "
                                            "filter, upsampling), frame_ms the sum of every timed pass of the frame, not "
                                            "wall-clock time");
    cli_json_add_number(root, "width", o->common.width);
    cli_json_add_number(root, "height", o->common.height);
    cli_json_add_number(root, "reference_spp", o->spp);
    /* --guard as given, in pixels per side (the renderer rounds it up to 4 x the AO divisor). */
    cli_json_add_number(root, "guard", o->common.guard_px);
    cJSON_AddBoolToObject(root, "temporal", o->common.temporal);
    cli_common_temporal_json(&o->common, root); /* the flicker rows' "on" too */
    time_t now = time(NULL);
    char date[32];
    strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", gmtime(&now));
    cJSON_AddStringToObject(root, "date", date);
}

/* Per set of scenes/views.json that this report has views of: their count and each row's mean
 * RMSE over them (null when the report has none of the set's views). */
static void json_sets(cJSON *root, const view_result *views, int count)
{
    cJSON *jsets = cJSON_AddObjectToObject(root, "sets");
    const int nrows = count > 0 ? views[0].method_count : 0;
    double *mean = nrows ? calloc((size_t)nrows, sizeof *mean) : NULL;
    for (int s = 0; s < 2; ++s) {
        int n = mean ? set_means(views, count, view_set_names[s], mean, nrows) : 0;
        if (!n) {
            cJSON_AddNullToObject(jsets, view_set_names[s]);
            continue;
        }
        cJSON *set = cJSON_AddObjectToObject(jsets, view_set_names[s]);
        cli_json_add_number(set, "views", n);
        cJSON *means = cJSON_AddObjectToObject(set, "mean_rmse");
        for (int k = 0; k < nrows; ++k) cli_json_add_number(means, views[0].methods[k].label, mean[k]);
    }
    free(mean);
}

/* "Which method, at what cost?" across the views (summarise), one entry per row. */
static void json_summary(cJSON *root, const view_result *views, int count)
{
    const int nrows = count > 0 ? views[0].method_count : 0;
    row_summary *sum = summarise(views, count, nrows);
    cJSON *jsum = cJSON_AddArrayToObject(root, "summary");
    for (int k = 0; sum && k < nrows; ++k) {
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "label", views[0].methods[k].label);
        cJSON_AddStringToObject(e, "method", views[0].methods[k].name);
        cli_json_add_number(e, "mean_rmse", sum[k].rmse);
        cli_json_add_number(e, "mean_bias", sum[k].bias);
        cli_json_add_number(e, "mean_rank", sum[k].rank);
        cli_json_add_number(e, "wins", sum[k].wins);
        cli_json_add_number(e, "median_ao_ms", sum[k].ao_ms);
        cJSON_AddBoolToObject(e, "front", sum[k].front);
        cJSON_AddItemToArray(jsum, e);
    }
    free(sum);
}

/* The view's metric masks: their settings as used, and each one's pixel count and image. */
static void json_masks(cJSON *j, const view_result *vr)
{
    const ob_metric_mask_desc *md = &vr->mask_desc;
    cJSON *js = cJSON_AddObjectToObject(j, "mask_settings");
    cli_json_add_number(js, "occluded_below", md->occluded_below);
    cli_json_add_number(js, "edge_relative", md->edge_relative);
    cli_json_add_number(js, "edge_band_px", md->edge_band);
    cli_json_add_number(js, "thin_reach_px", md->thin_reach);
    cli_json_add_number(js, "thin_depth", vr->radius);
    cli_json_add_number(js, "border_fraction", md->border_fraction);
    cJSON *jmask = cJSON_AddObjectToObject(j, "masks");
    for (int q = 0; q < OB_MASK_COUNT; ++q) {
        const char *name = ob_metric_mask_name((ob_metric_mask)q);
        cJSON *e = cJSON_AddObjectToObject(jmask, name);
        cli_json_add_number(e, "pixels", (double)vr->mask_pixels[q]);
        char image[300];
        snprintf(image, sizeof image, "%s/mask_%s.png", vr->dir, name);
        cJSON_AddStringToObject(e, "image", image);
    }
}

/* One row: its settings, its metrics over the view and inside each mask, and its times. */
static cJSON *json_row(const method_result *m)
{
    cJSON *e = cJSON_CreateObject();
    cJSON_AddStringToObject(e, "method", m->name);
    /* The row's settings: the label names those that vary between rows. */
    cJSON_AddStringToObject(e, "label", m->label);
    cJSON_AddStringToObject(e, "filter", ob_filter_at(m->config->filter)->name);
    cli_json_add_number(e, "ao_scale", 1.0 / m->config->ao_divisor);
    if (m->config->samples.quality) cJSON_AddStringToObject(e, "quality", m->config->samples.quality);
    if (m->config->samples.count > 0) cli_json_add_number(e, "samples", m->config->samples.count);
    cli_json_add_number(e, "rmse", m->m.rmse);
    cli_json_add_number(e, "mae", m->m.mae);
    cli_json_add_number(e, "bias", m->m.bias);
    /* JSON has no infinity: identical images report psnr null. */
    if (isfinite(m->m.psnr)) cli_json_add_number(e, "psnr", m->m.psnr);
    else cJSON_AddNullToObject(e, "psnr");
    /* XeGTAO's measure: PSNR of the sRGB-encoded AO. */
    if (isfinite(m->m.psnr_srgb)) cli_json_add_number(e, "psnr_srgb", m->m.psnr_srgb);
    else cJSON_AddNullToObject(e, "psnr_srgb");
    cli_json_add_number(e, "ssim", m->m.ssim);
    cli_json_add_number(e, "pixels", (double)m->m.count);
    /* The error inside each metric mask; an empty mask has no error to report (null). */
    cJSON *jin = cJSON_AddObjectToObject(e, "masks");
    for (int q = 0; q < OB_MASK_COUNT; ++q) {
        cJSON *x = cJSON_AddObjectToObject(jin, ob_metric_mask_name((ob_metric_mask)q));
        const ob_metrics *mm = &m->in_mask[q];
        if (mm->count > 0) {
            cli_json_add_number(x, "rmse", mm->rmse);
            cli_json_add_number(x, "bias", mm->bias);
        } else {
            cJSON_AddNullToObject(x, "rmse");
            cJSON_AddNullToObject(x, "bias");
        }
        cli_json_add_number(x, "pixels", (double)mm->count);
    }
    if (m->directional) {
        cJSON *rgb = cJSON_AddObjectToObject(e, "radiance");
        cli_json_add_number(rgb, "rmse", m->rgb.rmse);
        cli_json_add_number(rgb, "bias", m->rgb.bias);
        cli_json_add_number(rgb, "ssim", m->rgb.ssim);
    }
    cli_json_add_number(e, "ao_ms", m->ao_ms);
    cli_json_add_number(e, "chain_ms", m->chain_ms);
    cJSON_AddBoolToObject(e, "pareto", m->pareto);
    cli_json_add_number(e, "frame_ms", m->frame_ms);
    return e;
}

/* The flicker metrics (flicker.h): per configuration, temporal accumulation off (the same moving
 * noise, a one-frame history) and on. */
static void json_flicker(cJSON *j, const compare_opts *o, const view_result *vr)
{
    cJSON *fl = cJSON_AddObjectToObject(j, "flicker");
    cJSON_AddStringToObject(fl, "path", o->common.path ? o->common.path : "orbit");
    if (o->common.has_orbit) cli_json_add_number(fl, "orbit_degrees", o->common.orbit_deg);
    cli_json_add_number(fl, "path_frames", vr->flicker_ref.frames);
    /* Frames that see nothing (--allow-empty): in no mean; their rmse_frames are null. */
    cli_json_add_number(fl, "path_frames_empty", vr->flicker_ref.frames_empty);
    cli_json_add_number(fl, "still_frames", FLICKER_STILL_FRAMES);
    /* Both variants' G-buffer jitter and the reference's footprint (0: pixel centres). */
    cli_json_add_number(fl, "jitter_positions", vr->flicker_ref.jitter);
    cli_json_add_number(fl, "reference_warped_error", vr->flicker_ref.warped);
    cJSON *rows = cJSON_AddArrayToObject(fl, "rows");
    for (int k = 0; k < vr->method_count; ++k) {
        const cli_flicker_row *row = &vr->flicker[k];
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "label", vr->methods[k].label);
        cJSON_AddStringToObject(e, "method", vr->methods[k].name);
        const cli_flicker_variant *vs[2] = {&row->off, &row->on};
        for (int q = 0; q < 2; ++q) {
            cJSON *x = cJSON_AddObjectToObject(e, q ? "temporal_on" : "temporal_off");
            cli_json_add_number(x, "static_noise", vs[q]->static_noise);
            cli_json_add_number(x, "warped_error", vs[q]->warped_excess);
            cli_json_add_number(x, "warped_error_raw", vs[q]->warped);
            cli_json_add_number(x, "rmse_last", vs[q]->rmse_last);
            cli_json_add_number(x, "rmse_worst", vs[q]->rmse_worst);
            cli_json_add_number(x, "worst_frame", vs[q]->worst_frame);
            cli_json_add_number(x, "rmse_mean", vs[q]->rmse_mean);
            cJSON *curve = cJSON_AddArrayToObject(x, "rmse_frames");
            for (int t = 0; vs[q]->rmse_frames && t < vr->flicker_ref.frames; ++t)
                cJSON_AddItemToArray(curve, cJSON_CreateNumber(cli_json_round(vs[q]->rmse_frames[t])));
            cli_json_add_number(x, "temporal_ms", vs[q]->temporal_ms);
        }
        cJSON_AddItemToArray(rows, e);
    }
}

/* The equal-time shoot-out: each method's most accurate row within the budget. */
static void json_shootout(cJSON *j, const view_result *vr, double budget)
{
    cJSON *so = cJSON_AddObjectToObject(j, "shootout");
    cli_json_add_number(so, "budget_ms", budget);
    cJSON *arr = cJSON_AddArrayToObject(so, "methods");
    const char *names[CLI_MAX_CONFIGS];
    int n = method_names(vr, names, CLI_MAX_CONFIGS);
    for (int q = 0; q < n; ++q) {
        int best = -1, fastest = -1;
        best_within(vr, names[q], budget, &best, &fastest);
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "method", names[q]);
        cJSON_AddBoolToObject(e, "within_budget", best >= 0);
        if (best >= 0) {
            cJSON_AddStringToObject(e, "label", vr->methods[best].label);
            cli_json_add_number(e, "rmse", vr->methods[best].m.rmse);
            cli_json_add_number(e, "chain_ms", vr->methods[best].chain_ms);
        }
        cli_json_add_number(e, "fastest_ms", vr->methods[fastest].chain_ms);
        cJSON_AddItemToArray(arr, e);
    }
}

static cJSON *json_view(const compare_opts *o, const view_result *vr)
{
    cJSON *j = cJSON_CreateObject();
    cJSON_AddStringToObject(j, "scene", vr->scene);
    cJSON_AddStringToObject(j, "camera", vr->camera);
    cJSON_AddStringToObject(j, "dir", vr->dir);
    if (vr->set) cJSON_AddStringToObject(j, "set", vr->set);
    else cJSON_AddNullToObject(j, "set");
    cli_json_add_number(j, "radius", vr->radius);
    cJSON *jr = cJSON_AddObjectToObject(j, "reference");
    cli_json_add_number(jr, "seconds", vr->ref_seconds);
    cJSON_AddBoolToObject(jr, "cached", vr->ref_cached);
    cli_json_add_number(jr, "mean_standard_error", vr->ref_stderr_mean);
    if (vr->has_bounce) cli_json_add_number(jr, "bounce_seconds", vr->bounce_seconds);
    json_masks(j, vr);
    cJSON *jm = cJSON_AddArrayToObject(j, "methods");
    for (int k = 0; k < vr->method_count; ++k) cJSON_AddItemToArray(jm, json_row(&vr->methods[k]));
    if (vr->flicker) json_flicker(j, o, vr);
    if (o->budget_ms > 0.0) json_shootout(j, vr, o->budget_ms);
    return j;
}

int compare_write_json(const compare_opts *o, const view_result *views, int count, report_files *out)
{
    cJSON *root = cJSON_CreateObject();
    json_run(root, o);
    json_sets(root, views, count);
    json_summary(root, views, count);
    cJSON *jv = cJSON_AddArrayToObject(root, "views");
    for (int v = 0; v < count; ++v) cJSON_AddItemToArray(jv, json_view(o, &views[v]));
    char *text = cJSON_Print(root);
    cJSON_Delete(root);
    if (!text) return cli_fail(EXIT_RUNTIME, "out of memory writing results.json");
    char path[700];
    snprintf(path, sizeof path, "%s/results.json", o->report);
    if (!compare_track_file(out, path)) {
        free(text);
        return cli_fail(EXIT_RUNTIME, "out of memory");
    }
    /* Scene and camera names are bytes from files: valid UTF-8 before any parser sees them. */
    char *valid = cli_utf8_valid(text);
    free(text);
    if (!valid) return cli_fail(EXIT_RUNTIME, "out of memory writing results.json");
    ob_error e = ob_write_text(path, valid);
    free(valid);
    return e == OB_OK ? EXIT_OK : cli_fail_library_as(EXIT_OUTPUT);
}

/* ---- index.html ----------------------------------------------------------------------------- */

static void html_escape(FILE *f, const char *text)
{
    /* Names from models and sidecars are bytes: valid UTF-8 first (the page says utf-8). */
    char *valid = cli_utf8_valid(text);
    if (!valid) return;
    for (const char *s = valid; *s; ++s) {
        switch (*s) {
        case '&': fputs("&amp;", f); break;
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '"': fputs("&quot;", f); break;
        case '\'': fputs("&#39;", f); break;
        default: fputc(*s, f);
        }
    }
    free(valid);
}

/* The equal-time shoot-out: each method's most accurate row within the budget, best first. */
static void write_shootout_table(FILE *f, const view_result *vr, double budget)
{
    const char *names[CLI_MAX_CONFIGS];
    int n = method_names(vr, names, CLI_MAX_CONFIGS);
    int order[CLI_MAX_CONFIGS], best[CLI_MAX_CONFIGS], fastest[CLI_MAX_CONFIGS];
    for (int q = 0; q < n; ++q) {
        order[q] = q;
        best_within(vr, names[q], budget, &best[q], &fastest[q]);
    }
    /* Within the budget by RMSE, then the rest by how fast they can go. */
    for (int a = 1; a < n; ++a)
        for (int b = a; b > 0; --b) {
            int x = order[b - 1], y = order[b];
            double kx = best[x] >= 0 ? vr->methods[best[x]].m.rmse : 10.0 + vr->methods[fastest[x]].chain_ms;
            double ky = best[y] >= 0 ? vr->methods[best[y]].m.rmse : 10.0 + vr->methods[fastest[y]].chain_ms;
            if (ky < kx) {
                order[b - 1] = y;
                order[b] = x;
            }
        }
    fprintf(f, "<p class=\"note\">Equal-time shoot-out: the most accurate row of each method whose AO (pass + depth "
               "MIPs + filter + upsampling) took at most %.2f ms.</p>\n<table class=\"sortable\"><thead><tr><th>method</th><th>best row "
               "within budget</th><th>RMSE</th><th>AO ms</th></tr></thead><tbody>\n",
            budget);
    for (int i = 0; i < n; ++i) {
        int q = order[i];
        fputs("<tr><td>", f);
        html_escape(f, names[q]);
        fputs("</td><td>", f);
        if (best[q] >= 0) {
            html_escape(f, vr->methods[best[q]].label);
            fprintf(f, "</td><td>%.4f</td><td>%.2f</td></tr>\n", vr->methods[best[q]].m.rmse, vr->methods[best[q]].chain_ms);
        } else {
            fprintf(f, "over budget (fastest %.2f ms)</td><td>&ndash;</td><td>&ndash;</td></tr>\n",
                    vr->methods[fastest[q]].chain_ms);
        }
    }
    fputs("</tbody></table>\n", f);
}

static void embed_file(FILE *out, const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return;
    char buf[4096];
    /* Skip the XML prolog: inline SVG starts at <svg. */
    bool started = false;
    while (fgets(buf, sizeof buf, f)) {
        if (!started) {
            char *s = strstr(buf, "<svg");
            if (!s) continue;
            started = true;
            fputs(s, out);
            continue;
        }
        fputs(buf, out);
    }
    fclose(f);
}

/* The error where it matters: RMSE and bias inside each metric mask, and the masks themselves. */
static void write_mask_table(FILE *f, const view_result *vr, int w, int h)
{
    const ob_metric_mask_desc *md = &vr->mask_desc;
    const size_t *n = vr->mask_pixels;
    fprintf(f,
            "<p class=\"note\">Error where it matters, in pixels of geometry: <b>occluded</b> (reference &lt; %g) %zu; "
            "<b>silhouette</b> (within %d px of a depth step over %g%% or sky) %zu; <b>thin</b> (background over "
            "R = %g farther on both sides within %d px) %zu; <b>border</b> (outer %g%% of each side) %zu. "
            "n/a: the mask is empty. Mask images: white = in the mask, over the reference dimmed; sky dark blue.</p>\n",
            (double)md->occluded_below, n[OB_MASK_OCCLUDED], md->edge_band, 100.0 * (double)md->edge_relative,
            n[OB_MASK_SILHOUETTE], (double)vr->radius, md->thin_reach, n[OB_MASK_THIN],
            100.0 * (double)md->border_fraction, n[OB_MASK_BORDER]);
    fputs("<table class=\"sortable masks\"><thead><tr><th>method</th>", f);
    for (int q = 0; q < OB_MASK_COUNT; ++q) {
        const char *name = ob_metric_mask_name((ob_metric_mask)q);
        fprintf(f, "<th>%s RMSE</th><th>%s bias</th>", name, name);
    }
    fputs("</tr></thead><tbody>\n", f);
    for (int k = 0; k < vr->method_count; ++k) {
        const method_result *m = &vr->methods[k];
        fputs("<tr><td>", f);
        html_escape(f, m->label);
        fputs("</td>", f);
        for (int q = 0; q < OB_MASK_COUNT; ++q) {
            if (m->in_mask[q].count > 0) fprintf(f, "<td>%.4f</td><td>%+.4f</td>", m->in_mask[q].rmse, m->in_mask[q].bias);
            else fputs("<td>n/a</td><td>n/a</td>", f);
        }
        fputs("</tr>\n", f);
    }
    fputs("</tbody></table>\n<div class=\"grid\">", f);
    for (int q = 0; q < OB_MASK_COUNT; ++q) {
        const char *name = ob_metric_mask_name((ob_metric_mask)q);
        fprintf(f, "<div class=\"cell\"><img src=\"%s/mask_%s.png\" width=\"%d\" height=\"%d\" alt=\"%s mask\">"
                   "%s mask, %zu px</div>",
                vr->dir, name, w, h, name, name, n[q]);
    }
    fputs("</div>\n", f);
}

/* The flicker table (flicker.h) and each configuration's worst frame with temporal on. */
static void write_flicker_table(FILE *f, const compare_opts *o, const view_result *vr)
{
    const cli_common *c = &o->common;
    fprintf(f, "<h3>Flicker along ");
    if (c->path) {
        fputs("path ", f);
        html_escape(f, c->path);
    } else {
        fprintf(f, "an orbit of %g&deg;", (double)c->orbit_deg);
    }
    char jitter_note[200] = "Both variants sample the pixel centres, as does the reference (--jitter off).";
    if (vr->flicker_ref.jitter > 0)
        snprintf(jitter_note, sizeof jitter_note,
                 "Both variants jitter the G-buffer over %d sub-pixel points, and each frame's reference is "
                 "AO<sub>R</sub> averaged over the same %d points (--jitter).",
                 vr->flicker_ref.jitter, vr->flicker_ref.jitter);
    fprintf(f, " (%d frames)</h3>\n<p class=\"note\">off: the spatial filter alone with the same noise moving every "
               "frame; on: temporal accumulation (%s the filter, history %d frames, detail %g). Static noise: camera "
               "still for %d frames, mean per-pixel std-dev; "
               "warped error: mean |AO<sub>t</sub> &minus; reprojected AO<sub>t&minus;1</sub>| over pixels seen in both "
               "(the ratio is of these), and the same minus the reference's own (%.4f: AO<sub>R</sub> belongs to the "
               "surface point, so on a static scene the reference's change is its Monte Carlo noise and "
               "resampling); RMSE against the reference on the last and the worst frame, and its mean over the "
               "path's frames (a screen-space estimate depends on the view, and the accumulation averages the "
               "last views: the last frame alone can land where the single frame's error dips). %s</p>\n",
            vr->flicker_ref.frames, cli_common_temporal_at(c), cli_common_temporal_frames(c), (double)c->temporal_detail,
            FLICKER_STILL_FRAMES, vr->flicker_ref.warped, jitter_note);
    fputs("<table class=\"sortable\"><thead><tr><th>method</th><th>static noise off</th><th>on</th><th>ratio</th>"
          "<th>warped error off</th><th>on</th><th>ratio</th><th>minus reference off</th><th>on</th><th>RMSE last off</th><th>on</th>"
          "<th>RMSE worst off (frame)</th><th>on (frame)</th><th>RMSE mean off</th><th>on</th><th>temporal ms</th>"
          "</tr></thead><tbody>\n",
          f);
    for (int k = 0; k < vr->method_count; ++k) {
        const cli_flicker_variant *a = &vr->flicker[k].off, *b = &vr->flicker[k].on;
        fputs("<tr><td>", f);
        html_escape(f, vr->methods[k].label);
        fprintf(f, "</td><td>%.4f</td><td>%.4f</td><td>%.1fx</td><td>%.4f</td><td>%.4f</td><td>%.1fx</td>"
                   "<td>%+.4f</td><td>%+.4f</td><td>%.4f</td><td>%.4f</td><td>%.4f (%d)</td><td>%.4f (%d)</td><td>%.4f</td><td>%.4f</td>"
                   "<td>%.2f</td></tr>\n",
                a->static_noise, b->static_noise, b->static_noise > 0.0 ? a->static_noise / b->static_noise : 0.0,
                a->warped, b->warped, b->warped > 0.0 ? a->warped / b->warped : 0.0, a->warped_excess, b->warped_excess,
                a->rmse_last, b->rmse_last, a->rmse_worst, a->worst_frame, b->rmse_worst, b->worst_frame, a->rmse_mean,
                b->rmse_mean, b->temporal_ms);
    }
    fputs("</tbody></table>\n<div class=\"grid\">", f);
    for (int k = 0; k < vr->method_count; ++k) {
        fprintf(f, "<div class=\"cell\"><img src=\"%s/%s_temporal_worst.png\" width=\"%d\" height=\"%d\" alt=\"\">",
                vr->dir, vr->methods[k].stem, c->width, c->height);
        html_escape(f, vr->methods[k].label);
        fprintf(f, " temporal on, worst frame %d</div>", vr->flicker[k].on.worst_frame);
    }
    fputs("</div>\n", f);
}

/* The page's head, its style and the run's line. */
static void html_head(FILE *f, const compare_opts *o)
{
    fputs("<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>Obscura: AO against ground truth</title>\n"
          "<style>body{font:14px sans-serif;margin:24px;color:#222}h2{margin-top:36px}"
          "table{border-collapse:collapse;margin:12px 0}th,td{padding:4px 10px;border-bottom:1px solid #ddd;text-align:right}"
          "th{cursor:pointer;background:#f2f2f2}td:first-child,th:first-child{text-align:left}"
          /* The sorted column's header shows its direction: the arrow follows aria-sort. */
          "th[aria-sort=ascending]::after{content:\" \xe2\x96\xb2\"}th[aria-sort=descending]::after{content:\" \xe2\x96\xbc\"}"
          ".grid{display:flex;flex-wrap:wrap;gap:10px}.cell{font-size:12px}.cell img{display:block;border:1px solid #ccc}"
          ".note{color:#666}</style></head><body>\n<h1>Screen-space AO against the ray-traced ground truth</h1>\n<p class=\"note\">",
          f);
    fprintf(f, "%dx%d, reference %d rays per pixel (cosine-weighted, AO<sub>R</sub> as in docs/compare.md), GPU: ",
            o->common.width, o->common.height, o->spp);
    html_escape(f, o->renderer);
    fputs(". Error maps: red = the method is brighter (misses occlusion), blue = darker; &plusmn;0.5 saturates. "
          "Click a column's header to sort by it (&#9650; ascending, &#9660; descending; again to reverse).</p>\n",
          f);
}

/* Which method, at what cost: the summary across every view of the report. */
static void html_summary(FILE *f, const view_result *views, int count, int rows)
{
    row_summary *sum = summarise(views, count, rows);
    if (!sum) return;
    fprintf(f, "<h2>Summary over %d view%s</h2>\n<p class=\"note\">Mean RMSE and signed bias against "
               "AO<sub>R</sub>, mean rank by RMSE (1 = the closest row of a view), wins (views no row is "
               "closer on), median GPU time of the AO pass, and the front: rows no other row beats on both "
               "error and time.</p>\n",
            count, count == 1 ? "" : "s");
    fputs("<table class=\"sortable\"><thead><tr><th>row</th><th>mean RMSE</th><th>mean bias</th>"
          "<th>mean rank</th><th>wins</th><th>AO ms (median)</th><th>front</th></tr></thead><tbody>\n",
          f);
    for (int k = 0; k < rows; ++k) {
        fputs("<tr><td>", f);
        html_escape(f, views[0].methods[k].label);
        fprintf(f, "</td><td>%.4f</td><td>%+.4f</td><td>%.2f</td><td>%d</td><td>%.3f</td><td>%s</td></tr>\n",
                sum[k].rmse, sum[k].bias, sum[k].rank, sum[k].wins, sum[k].ao_ms, sum[k].front ? "yes" : "");
    }
    fputs("</tbody></table>\n", f);
    free(sum);
}

/* The views' sets (scenes/views.json): the mean of each row over the choose views, the ones the
 * defaults were chosen on, and over the check views, never chosen on. */
static void html_sets(FILE *f, const view_result *views, int count, int rows)
{
    double *mean[2] = {NULL, NULL};
    int in_set[2] = {0, 0};
    for (int s = 0; s < 2 && rows; ++s) {
        mean[s] = calloc((size_t)rows, sizeof(double));
        if (mean[s]) in_set[s] = set_means(views, count, view_set_names[s], mean[s], rows);
    }
    if (in_set[0] || in_set[1]) {
        fputs("<h2>Choose and check views</h2>\n<p class=\"note\">The project's views in two sets "
              "(scenes/views.json, docs/methods.md): <em>choose</em> views, the ones the defaults were chosen on, "
              "and <em>check</em> views, never used for a choice. Mean RMSE of each row over this report's views of "
              "each set.</p>\n<table class=\"sortable\"><thead><tr><th>row</th>",
              f);
        for (int s = 0; s < 2; ++s)
            if (in_set[s]) fprintf(f, "<th>%s (%d view%s)</th>", view_set_names[s], in_set[s], in_set[s] == 1 ? "" : "s");
        fputs("</tr></thead><tbody>\n", f);
        for (int k = 0; k < rows; ++k) {
            fputs("<tr><td>", f);
            html_escape(f, views[0].methods[k].label);
            fputs("</td>", f);
            for (int s = 0; s < 2; ++s)
                if (in_set[s]) fprintf(f, "<td>%.4f</td>", mean[s][k]);
            fputs("</tr>\n", f);
        }
        fputs("</tbody></table>\n", f);
    }
    free(mean[0]);
    free(mean[1]);
}

/* A view's main table: every row's metrics over the view and its times. */
static void html_rows_table(FILE *f, const view_result *vr)
{
    fputs("<table class=\"sortable\"><thead><tr><th>method</th><th>RMSE</th><th>bias</th><th>MAE</th><th>SSIM</th>"
          "<th>PSNR dB</th><th>sRGB PSNR dB</th><th>AO GPU ms</th><th>frame GPU ms</th></tr></thead><tbody>\n",
          f);
    for (int k = 0; k < vr->method_count; ++k) {
        const method_result *m = &vr->methods[k];
        fputs("<tr><td>", f);
        html_escape(f, m->label);
        fprintf(f, "</td><td>%.4f</td><td>%+.4f</td><td>%.4f</td><td>%.3f</td>", m->m.rmse, m->m.bias, m->m.mae,
                m->m.ssim);
        const double psnrs[2] = {m->m.psnr, m->m.psnr_srgb};
        for (int q = 0; q < 2; ++q) {
            if (isfinite(psnrs[q])) fprintf(f, "<td>%.2f</td>", psnrs[q]);
            else fputs("<td>&infin;</td>", f);
        }
        fprintf(f, "<td>%.2f</td><td>%.1f</td></tr>\n", m->ao_ms, m->frame_ms);
    }
    fprintf(f, "</tbody></table>\n<p class=\"note\">AO GPU ms and frame GPU ms: GPU time from timestamps around each "
               "pass, medians of %d frames; the AO pass alone, and the sum of every pass of the frame (shadows, "
               "G-buffer, lighting, the AO chain, compose, tone map), which is not the frame's wall-clock time.</p>\n",
            FRAMES);
}

/* Directional methods: their composed radiance against the one-bounce reference. */
static void html_bounce_table(FILE *f, const view_result *vr)
{
    fprintf(f, "<p class=\"note\">Directional methods: composed HDR radiance against the one-bounce reference "
               "(shadow rays, one diffuse bounce within R, ambient &times; AO<sub>R</sub>; %.1f s).</p>\n"
               "<table class=\"sortable\"><thead><tr><th>method</th><th>radiance RMSE</th><th>bias</th>"
               "<th>SSIM</th></tr></thead><tbody>\n",
            vr->bounce_seconds);
    for (int k = 0; k < vr->method_count; ++k) {
        const method_result *m = &vr->methods[k];
        if (!m->directional) continue;
        fputs("<tr><td>", f);
        html_escape(f, m->label);
        fprintf(f, "</td><td>%.4f</td><td>%+.4f</td><td>%.3f</td></tr>\n", m->rgb.rmse, m->rgb.bias, m->rgb.ssim);
    }
    fputs("</tbody></table>\n", f);
}

/* The view's chart (its SVG inlined) and images: the reference, then each row's final, AO and error. */
static void html_images(FILE *f, const compare_opts *o, const view_result *vr)
{
    fputs("<div class=\"chart\">", f);
    char svg[700];
    snprintf(svg, sizeof svg, "%s/%s/chart.svg", o->report, vr->dir);
    embed_file(f, svg);
    fputs("</div>\n<div class=\"grid\">", f);
    fprintf(f, "<div class=\"cell\"><img src=\"%s/reference_ao.png\" width=\"%d\" height=\"%d\" alt=\"reference\">reference AO</div>",
            vr->dir, o->common.width, o->common.height);
    fputs("</div>\n", f);
    for (int k = 0; k < vr->method_count; ++k) {
        const method_result *m = &vr->methods[k];
        fputs("<div class=\"grid\">", f);
        const char *kinds[3] = {"final", "ao", "error"};
        for (int q = 0; q < 3; ++q) {
            fprintf(f, "<div class=\"cell\"><img src=\"%s/%s_%s.png\" width=\"%d\" height=\"%d\" alt=\"\">", vr->dir,
                    m->stem, kinds[q], o->common.width, o->common.height);
            html_escape(f, m->label);
            fprintf(f, " %s</div>", kinds[q]);
        }
        fputs("</div>\n", f);
    }
}

static void html_view(FILE *f, const compare_opts *o, const view_result *vr)
{
    fputs("<section class=\"view\"><h2>", f);
    html_escape(f, vr->scene);
    fputs(" &mdash; ", f);
    html_escape(f, vr->camera);
    if (vr->set) fprintf(f, " <span class=\"note\">(a %s view)</span>", vr->set);
    fprintf(f, "</h2>\n<p class=\"note\">R = %g; reference: %.1f s%s, mean standard error %.4f</p>\n",
            (double)vr->radius, vr->ref_seconds, vr->ref_cached ? " (cached)" : "", vr->ref_stderr_mean);
    html_rows_table(f, vr);
    if (vr->has_bounce) html_bounce_table(f, vr);
    if (o->budget_ms > 0.0) write_shootout_table(f, vr, o->budget_ms);
    if (vr->flicker) write_flicker_table(f, o, vr);
    write_mask_table(f, vr, o->common.width, o->common.height);
    html_images(f, o, vr);
    fputs("</section>\n", f);
}

/* Sort a table by a column: numbers numerically, text alphabetically; click again (or Enter or
 * Space on the focused header) to reverse. The sorted header carries aria-sort, ascending or
 * descending, which the style shows as ▲ or ▼ and a screen reader reads; the table's other
 * headers lose theirs. The column is the header cell's index in its own row (forEach's index
 * counts every table's). Inline: the report works offline, from any directory. */
static void html_script(FILE *f)
{
    fputs("<script>\n"
          "document.querySelectorAll('table.sortable th').forEach(function (th) {\n"
          "  th.tabIndex = 0;\n"
          "  th.title = 'Sort by this column';\n"
          "  function sort() {\n"
          "    var col = th.cellIndex;\n"
          "    var body = th.closest('table').tBodies[0];\n"
          "    var rows = Array.prototype.slice.call(body.rows);\n"
          "    var dir = th.getAttribute('aria-sort') === 'ascending' ? -1 : 1;\n"
          "    th.parentNode.querySelectorAll('th').forEach(function (h) { h.removeAttribute('aria-sort'); });\n"
          "    th.setAttribute('aria-sort', dir === 1 ? 'ascending' : 'descending');\n"
          "    rows.sort(function (a, b) {\n"
          "      var x = a.cells[col].textContent, y = b.cells[col].textContent;\n"
          "      var nx = parseFloat(x), ny = parseFloat(y);\n"
          "      var c = isNaN(nx) || isNaN(ny) ? x.localeCompare(y) : nx - ny;\n"
          "      return dir * c;\n"
          "    });\n"
          "    rows.forEach(function (r) { body.appendChild(r); });\n"
          "  }\n"
          "  th.addEventListener('click', sort);\n"
          "  th.addEventListener('keydown', function (e) {\n"
          "    if (e.key === 'Enter' || e.key === ' ') { e.preventDefault(); sort(); }\n"
          "  });\n"
          "});\n"
          "</script>\n</body></html>\n",
          f);
}

int compare_write_html(const compare_opts *o, const view_result *views, int count, report_files *out)
{
    char path[700], tmp[720];
    snprintf(path, sizeof path, "%s/index.html", o->report);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    if (!compare_track_file(out, path)) return cli_fail(EXIT_RUNTIME, "out of memory");
    FILE *f = fopen(tmp, "w");
    if (!f) return cli_fail(EXIT_OUTPUT, "cannot write %s: %s", path, strerror(errno));
    html_head(f, o);
    const int rows = count > 0 ? views[0].method_count : 0;
    html_summary(f, views, count, rows);
    html_sets(f, views, count, rows);
    for (int v = 0; v < count; ++v) html_view(f, o, &views[v]);
    html_script(f);
    bool ok = !ferror(f);
    if (fclose(f) != 0 || !ok || rename(tmp, path) != 0) {
        remove(tmp);
        return cli_fail(EXIT_OUTPUT, "cannot write %s", path);
    }
    return EXIT_OK;
}
