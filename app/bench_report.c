/* obscura bench's outputs: the tables on stdout, --csv and --json, from the rows bench.c and
 * bench_host.c measured (bench.h). Every time in them is GPU time from GL timestamps around each
 * pass (ob_query_timings); a frame's ms is the sum of its timed passes, not the wall-clock time of
 * the frame (the CPU's own work, any gap between passes and the present are not in it). Only
 * --host's call cpu ms is wall-clock time, measured on the CPU around the call. Every number of
 * the JSON goes through cli_json_add_number: 6 significant digits, whole numbers as they are. */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "bench.h"
#include "run_program.h"

/* ---- run info -------------------------------------------------------------------------------- */

static void cpu_model(char *out, size_t n)
{
    snprintf(out, n, "unknown");
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f) return;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        if (strncmp(line, "model name", 10)) continue;
        const char *c = strchr(line, ':');
        if (!c) break;
        for (++c; *c == ' ' || *c == '\t'; ++c) {}
        snprintf(out, n, "%s", c);
        out[strcspn(out, "\n")] = '\0';
        break;
    }
    fclose(f);
}

/* ---- the tables ------------------------------------------------------------------------------ */

static const char *method_name(int m) { return ob_method_at(m)->name; }

/* A table's parts, shared by the AO-pass table and the floor table: the header of the radius
 * columns, a row's "N = ..." label, and the row measured at one cell. */
static void print_radius_header(const float *rs, int rn)
{
    printf("%-8s", "");
    for (int q = 0; q < rn; ++q) {
        char h[32];
        if (rs[q] > 0.0f) snprintf(h, sizeof h, "r = %g", (double)rs[q]);
        else snprintf(h, sizeof h, "r = -");
        printf(" %20s", h);
    }
    printf("\n");
}

static void print_samples_label(int n)
{
    char h[32];
    if (n > 0) snprintf(h, sizeof h, "N = %d", n);
    else snprintf(h, sizeof h, "N = -");
    printf("%-8s", h);
}

static const bench_row *table_cell(const bench_state *st, int camera, const cli_config *cfg, int samples, float r)
{
    const bench_row *hit = NULL;
    for (int i = 0; i < st->count; ++i) {
        const bench_row *row = &st->rows[i];
        if (row->camera == camera && row->cfg == cfg && row->samples == samples && row->r == r) hit = row;
    }
    return hit;
}

/* --floor: the method's table again, each cell AO pass / floor (the median over the frames of each
 * one's ratio; the floor's median ms, its taps), rows N as asked (the floor's N is the method's
 * actual sample count). */
static void print_floor_table(const bench_state *st, int camera, const cli_config *cfg, const int *ns, int nn,
                              const float *rs, int rn)
{
    printf("%s: AO pass / floor (floor ms, taps)\n", cfg->label);
    print_radius_header(rs, rn);
    for (int j = 0; j < nn; ++j) {
        print_samples_label(ns[j]);
        for (int q = 0; q < rn; ++q) {
            const bench_row *hit = table_cell(st, camera, cfg, ns[j], rs[q]);
            char cell[48] = "-";
            if (hit && hit->floor_taps > 0 && hit->floor_ratio > 0.0)
                snprintf(cell, sizeof cell, "%.2fx (%.3f, %d)", hit->floor_ratio, hit->floor_med,
                         hit->floor_taps);
            printf(" %20s", cell);
        }
        printf("\n");
    }
}

/* The none frames of one camera: one per filter and AO scale, each the baseline of its
 * combinations. */
static void print_baselines(const bench_opts *o, const bench_state *st, int camera)
{
    for (int i = 0; i < st->count; ++i) {
        const bench_row *none = &st->rows[i];
        if (none->camera != camera || none->baseline != i) continue;
        printf("%s: frame %.3f ms (%.1f FPS)%s\n", none->cfg->label, none->frame_med, 1000.0 / none->frame_med,
               o->stereo ? (none->frame_med <= VR_BUDGET_MS ? ", within 11.1 ms" : ", over 11.1 ms") : "");
    }
}

/* One sample count and one radius for every method (the default run): one table with a row per
 * method, not a one-cell table each. */
static bool one_table(const bench_opts *o, const bench_state *st, int camera, const cli_config *configs, int count)
{
    bool one_cell = !o->floor && !o->stereo;
    for (int k = 0; k < count && one_cell; ++k) {
        int rows = 0;
        for (int i = 0; i < st->count; ++i) rows += st->rows[i].camera == camera && st->rows[i].cfg == &configs[k];
        one_cell = rows == 1;
    }
    return one_cell;
}

static void print_one_table(const bench_state *st, int camera, const cli_config *configs, int count)
{
    int width = 6;
    for (int k = 0; k < count; ++k) width = (int)strlen(configs[k].label) > width ? (int)strlen(configs[k].label) : width;
    printf("\n%-*s %6s %8s %27s %14s\n", width, "method", "N", "r", "AO-pass ms / frame ms (GPU)", "frame / none");
    for (int k = 0; k < count; ++k)
        for (int i = 0; i < st->count; ++i) {
            const bench_row *r = &st->rows[i];
            if (r->camera != camera || r->cfg != &configs[k]) continue;
            const bench_row *none = r->baseline >= 0 ? &st->rows[r->baseline] : NULL;
            char cell[48], ratio[16] = "-";
            snprintf(cell, sizeof cell, "%.3f / %.3f", r->ao_ms, r->frame_med);
            if (none && none->frame_med > 0.0) snprintf(ratio, sizeof ratio, "%.2fx", r->frame_med / none->frame_med);
            printf("%-*s %6d %8g %27s %14s\n", width, configs[k].label, r->samples, (double)r->r, cell, ratio);
            for (int p = 0; p < r->pass_count; ++p)
                if (!strcmp(r->pass[p], "temporal") && r->ao_ms > 0.0)
                    printf("%-*s temporal accumulation %.3f ms = %.1f %% of the AO pass\n", width, "", r->med[p],
                           100.0 * r->med[p] / r->ao_ms);
        }
}

/* The radii (columns) and sample counts (rows) measured for one combination on one camera. */
static void table_axes(const bench_state *st, int camera, const cli_config *cfg, float *rs, int *rn, int *ns, int *nn)
{
    *rn = *nn = 0;
    for (int i = 0; i < st->count; ++i) {
        const bench_row *r = &st->rows[i];
        if (r->camera != camera || r->cfg != cfg) continue;
        bool seen = false;
        for (int q = 0; q < *rn; ++q) seen = seen || rs[q] == r->r;
        if (!seen && *rn < MAX_LIST) rs[(*rn)++] = r->r;
        seen = false;
        for (int q = 0; q < *nn; ++q) seen = seen || ns[q] == r->samples;
        if (!seen && *nn < MAX_LIST) ns[(*nn)++] = r->samples;
    }
}

/* One combination's table shaped like Belonogov 2018's: rows N, columns r, and the mean frame /
 * none frame; then its floor table and its accumulation's share. */
static void print_method_table(const bench_opts *o, const bench_state *st, int camera, const cli_config *cfg)
{
    printf("\n%s: AO-pass ms / frame ms (GPU; frame = the sum of its passes)", cfg->label);
    if (o->stereo) printf(" (frame budget 11.1 ms at 90 Hz; * = over)");
    printf("\n");
    float rs[MAX_LIST];
    int ns[MAX_LIST], rn = 0, nn = 0;
    table_axes(st, camera, cfg, rs, &rn, ns, &nn);
    print_radius_header(rs, rn);
    double sum_ratio = 0.0;
    int cells = 0;
    for (int j = 0; j < nn; ++j) {
        print_samples_label(ns[j]);
        for (int q = 0; q < rn; ++q) {
            const bench_row *hit = table_cell(st, camera, cfg, ns[j], rs[q]);
            char cell[48];
            const bench_row *none = hit && hit->baseline >= 0 ? &st->rows[hit->baseline] : NULL;
            if (hit) {
                snprintf(cell, sizeof cell, "%.3f / %.3f%s", hit->ao_ms, hit->frame_med,
                         o->stereo && hit->frame_med > VR_BUDGET_MS ? "*" : "");
                if (none && none->frame_med > 0.0) {
                    sum_ratio += hit->frame_med / none->frame_med;
                    ++cells;
                }
            } else {
                snprintf(cell, sizeof cell, "-");
            }
            printf(" %20s", cell);
        }
        printf("\n");
    }
    if (cells) printf("mean frame / none frame: %.2fx\n", sum_ratio / cells);
    if (o->floor) print_floor_table(st, camera, cfg, ns, nn, rs, rn);
    /* --temporal on: the accumulation pass against the method's AO pass, the same frames
     * (issue 17's budget: at most 15 % of gtao-high's). */
    for (int i = 0; i < st->count; ++i) {
        const bench_row *r = &st->rows[i];
        if (r->camera != camera || r->cfg != cfg) continue;
        for (int p = 0; p < r->pass_count; ++p)
            if (!strcmp(r->pass[p], "temporal") && r->ao_ms > 0.0)
                printf("temporal accumulation N=%d r=%g: %.3f ms = %.1f %% of the AO pass (%.3f ms)\n", r->samples,
                       (double)r->r, r->med[p], 100.0 * r->med[p] / r->ao_ms, r->ao_ms);
    }
}

void bench_print_tables(const bench_opts *o, const ob_scene *scene, const bench_state *st, const int *cams, int cam_count,
                        const cli_config *configs, int config_count)
{
    const char *unit = o->stereo ? "both eyes" : "one view";
    for (int c = 0; c < cam_count; ++c) {
        const char *cname = ob_query_camera(scene, cams[c]).name;
        printf("\n== %s, camera %s, %dx%d%s, GPU ms, median of %d frames (%s) ==\n", ob_query_scene_name(scene),
               cname, o->common.width, o->common.height, o->stereo ? " per eye" : "", o->frames, unit);
        printf("GPU ms from timestamps around each pass; frame ms = the sum of the frame's passes, not wall-clock "
               "time\n");
        print_baselines(o, st, cams[c]);
        if (one_table(o, st, cams[c], configs, config_count)) {
            print_one_table(st, cams[c], configs, config_count);
            continue;
        }
        for (int k = 0; k < config_count; ++k) print_method_table(o, st, cams[c], &configs[k]);
    }
}

/* ---- scaling --------------------------------------------------------------------------------- */

typedef struct scaling_verdict {
    bool flat_in_triangles, linear_in_pixels;
    double tri_ratio, mpx_spread; /* max/min AO ms over tessellation; max |ms/MP / median - 1| */
} scaling_verdict;

static scaling_verdict verdict(const bench_state *st, const cli_config *cfg)
{
    scaling_verdict v = {false, false, 0.0, 0.0};
    double lo = INFINITY, hi = 0.0, per_mp[MAX_SIZES] = {0};
    int n = 0;
    for (int i = 0; i < st->count; ++i) {
        const bench_row *r = &st->rows[i];
        if (r->cfg != cfg) continue;
        if (r->study == 2) {
            lo = fmin(lo, r->ao_ms);
            hi = fmax(hi, r->ao_ms);
        } else if (r->study == 1 && n < MAX_SIZES) {
            per_mp[n++] = r->ao_ms / ((double)r->width * r->height * 1e-6);
        }
    }
    if (hi > 0.0 && lo > 0.0) {
        v.tri_ratio = hi / lo;
        v.flat_in_triangles = v.tri_ratio < 1.2;
    }
    if (n > 0) {
        double sorted[MAX_SIZES];
        memcpy(sorted, per_mp, sizeof sorted);
        const double med = cli_median(sorted, n);
        for (int k = 0; k < n && med > 0.0; ++k) v.mpx_spread = fmax(v.mpx_spread, fabs(per_mp[k] / med - 1.0));
        v.linear_in_pixels = med > 0.0 && v.mpx_spread <= 0.3;
    }
    return v;
}

/* --floor in the scaling lines: ", 2.91x floor" (one static buffer: one call per printf). */
static const char *floor_note(const bench_row *r)
{
    static char note[48];
    note[0] = '\0';
    if (r->floor_taps > 0 && r->floor_ratio > 0.0) snprintf(note, sizeof note, ", %.2fx floor", r->floor_ratio);
    return note;
}

void bench_print_scaling(const bench_opts *o, const ob_scene *scene, const ob_camera *cam, const bench_state *st,
                         const cli_config *configs, int count)
{
    printf("\n== scaling: AO-pass median GPU ms, %s camera %s, %d frames ==\n", ob_query_scene_name(scene), cam->name,
           o->frames);
    for (int k = 0; k < count; ++k) {
        printf("\n%s\n  resolution:", configs[k].label);
        for (int i = 0; i < st->count; ++i)
            if (st->rows[i].cfg == &configs[k] && st->rows[i].study == 1)
                printf("  %dx%d %.3f ms (%.3f ms/MP%s)", st->rows[i].width, st->rows[i].height, st->rows[i].ao_ms,
                       st->rows[i].ao_ms / (st->rows[i].width * (double)st->rows[i].height * 1e-6),
                       floor_note(&st->rows[i]));
        printf("\n  triangles: ");
        for (int i = 0; i < st->count; ++i)
            if (st->rows[i].cfg == &configs[k] && st->rows[i].study == 2)
                printf("  %u tris %.3f ms%s", st->rows[i].triangles, st->rows[i].ao_ms, floor_note(&st->rows[i]));
        scaling_verdict v = verdict(st, &configs[k]);
        printf("\n  flat in triangles: %s (max/min %.2f, < 1.2); linear in pixels: %s (ms/MP within %.0f%% of "
               "the median, limit 30%%)\n",
               v.flat_in_triangles ? "yes" : "no", v.tri_ratio, v.linear_in_pixels ? "yes" : "no", 100.0 * v.mpx_spread);
    }
}

void bench_print_full_hint(const bench_opts *o, int measured, int full_configs, double seconds)
{
    const double per_frame = measured > 0 ? seconds / ((double)measured * (o->frames + o->warmup)) : 0.0;
    const double minutes = per_frame * full_configs * (FULL_FRAMES + FULL_WARMUP) / 60.0;
    printf("\nThis was a quick run (%d configurations, %d frames each, shadow maps rendered once).\n"
           "Belonogov 2018's whole table: add --full (every camera preset, N = 12,24,36,64, r = 2,4,8, %d frames\n"
           "after %d, shadow maps every frame): %d configurations, over %.0f min at this run's pace.\n",
           measured, o->frames, FULL_FRAMES, FULL_WARMUP, full_configs, minutes);
}

/* ---- rows as JSON and CSV ----------------------------------------------------------------------- */

/* A row's label: its combination's, then the sweep's N and r where the method takes them. */
static void row_label(const bench_row *r, char *out, size_t n)
{
    int len = snprintf(out, n, "%s", r->cfg->label);
    if (r->samples > 0 && len >= 0 && (size_t)len < n) len += snprintf(out + len, n - (size_t)len, " \xc2\xb7 N %d", r->samples);
    if (r->r > 0.0f && len >= 0 && (size_t)len < n) snprintf(out + len, n - (size_t)len, " \xc2\xb7 r %g", (double)r->r);
}

/* The fields every row's JSON starts with: what was run, on which camera, at what size. */
static void config_json(cJSON *j, const char *label, int method, const cli_config *cfg, const ob_scene *scene,
                        int camera, int samples, float r, float radius_world, int width, int height)
{
    cJSON_AddStringToObject(j, "method", method_name(method));
    cJSON_AddStringToObject(j, "label", label);
    cJSON_AddStringToObject(j, "filter", ob_filter_at(cfg->filter)->name);
    cli_json_add_number(j, "ao_scale", 1.0 / cfg->ao_divisor);
    cJSON_AddStringToObject(j, "camera", ob_query_camera(scene, camera).name);
    if (samples > 0) cli_json_add_number(j, "samples", samples);
    else cJSON_AddNullToObject(j, "samples");
    if (r > 0.0f) {
        cli_json_add_number(j, "radius", r);
        cli_json_add_number(j, "radius_world", radius_world);
    } else {
        cJSON_AddNullToObject(j, "radius");
        cJSON_AddNullToObject(j, "radius_world");
    }
    cli_json_add_number(j, "width", width);
    cli_json_add_number(j, "height", height);
}

static cJSON *row_json(const bench_row *r, const bench_row *none, const ob_scene *scene)
{
    cJSON *j = cJSON_CreateObject();
    char label[CLI_MAX_LABEL + 32] = "";
    row_label(r, label, sizeof label);
    config_json(j, label, r->method, r->cfg, scene, r->camera, r->samples, r->r, r->radius_world, r->width, r->height);
    cli_json_add_number(j, "triangles", r->triangles);
    cli_json_add_number(j, "tessellation_levels", r->tess);
    cJSON *passes = cJSON_AddArrayToObject(j, "passes");
    for (int p = 0; p < r->pass_count; ++p) {
        cJSON *q = cJSON_CreateObject();
        cJSON_AddStringToObject(q, "name", r->pass[p]);
        cli_json_add_number(q, "median", r->med[p]);
        cli_json_add_number(q, "min", r->min[p]);
        cli_json_add_number(q, "max", r->max[p]);
        cJSON_AddItemToArray(passes, q);
    }
    cJSON *fr = cJSON_AddObjectToObject(j, "frame_ms");
    cli_json_add_number(fr, "median", r->frame_med);
    cli_json_add_number(fr, "min", r->frame_min);
    cli_json_add_number(fr, "max", r->frame_max);
    cli_json_add_number(j, "fps", 1000.0 / r->frame_med);
    cli_json_add_number(j, "ao_ms", r->ao_ms);
    if (r->floor_taps > 0) {
        cJSON *fl = cJSON_AddObjectToObject(j, "floor_ms");
        cli_json_add_number(fl, "median", r->floor_med);
        cli_json_add_number(fl, "min", r->floor_min);
        cli_json_add_number(fl, "max", r->floor_max);
        if (r->floor_ratio > 0.0) cli_json_add_number(j, "floor_ratio", r->floor_ratio);
        else cJSON_AddNullToObject(j, "floor_ratio");
        cli_json_add_number(j, "floor_taps", r->floor_taps);
        cJSON_AddStringToObject(j, "floor_pattern", r->floor_rays > 0 ? "rays" : "disk");
        if (r->floor_rays > 0) cli_json_add_number(j, "floor_rays", r->floor_rays);
    } else {
        cJSON_AddNullToObject(j, "floor_ms");
        cJSON_AddNullToObject(j, "floor_ratio");
    }
    if (none) {
        cJSON *v = cJSON_AddObjectToObject(j, "vs_none");
        cli_json_add_number(v, "ao_minus_ms", r->ao_ms - none->ao_ms);
        if (none->ao_ms > 0.0) cli_json_add_number(v, "ao_ratio", r->ao_ms / none->ao_ms);
        else cJSON_AddNullToObject(v, "ao_ratio");
        cli_json_add_number(v, "frame_minus_ms", r->frame_med - none->frame_med);
        cli_json_add_number(v, "frame_ratio", r->frame_med / none->frame_med);
    } else {
        cJSON_AddNullToObject(j, "vs_none");
    }
    return j;
}

static const bench_row *baseline_of(const bench_state *st, const bench_row *r)
{
    return r->baseline >= 0 ? &st->rows[r->baseline] : NULL;
}

int bench_write_csv(cli_outputs *outs, int index, const bench_state *st, const ob_scene *scene, int eyes)
{
    size_t cap = 4096 + (size_t)st->count * (MAX_PASSES + 1) * (300 + CLI_MAX_LABEL), len = 0;
    char *buf = malloc(cap);
    if (!buf) return cli_fail(EXIT_RUNTIME, "out of memory");
    len += (size_t)snprintf(buf + len, cap - len,
                            "scene,camera,method,samples,r,radius_world,filter,ao_scale,width,height,eyes,triangles,pass,"
                            "median_ms,min_ms,max_ms,fps,minus_none_ms,ratio_none,label,floor_ms,floor_ratio\n");
    for (int i = 0; i < st->count; ++i) {
        const bench_row *r = &st->rows[i];
        const bench_row *none = baseline_of(st, r);
        for (int p = 0; p <= r->pass_count; ++p) {
            bool frame = p == r->pass_count; /* the last row of a configuration: the whole frame */
            double med = frame ? r->frame_med : r->med[p], lo = frame ? r->frame_min : r->min[p],
                   hi = frame ? r->frame_max : r->max[p];
            double base = 0.0;
            bool has_base = false;
            if (none && frame) {
                base = none->frame_med;
                has_base = true;
            } else if (none && !strcmp(r->pass[p], "ao")) {
                base = none->ao_ms;
                has_base = true;
            }
            char samples[16] = "", rr[32] = "", rw[32] = "", fps[32] = "", minus[32] = "", ratio[32] = "";
            if (r->samples > 0) snprintf(samples, sizeof samples, "%d", r->samples);
            if (r->r > 0.0f) {
                snprintf(rr, sizeof rr, "%g", (double)r->r);
                snprintf(rw, sizeof rw, "%g", (double)r->radius_world);
            }
            if (frame) snprintf(fps, sizeof fps, "%.3f", 1000.0 / r->frame_med);
            if (has_base) {
                snprintf(minus, sizeof minus, "%.4f", med - base);
                if (base > 0.0) snprintf(ratio, sizeof ratio, "%.4f", med / base);
            }
            char label[CLI_MAX_LABEL + 32] = "";
            row_label(r, label, sizeof label);
            /* The floor on the ao row: its median and AO pass / floor. */
            char fms[32] = "", fratio[32] = "";
            if (!frame && r->floor_taps > 0 && !strcmp(r->pass[p], "ao")) {
                snprintf(fms, sizeof fms, "%.4f", r->floor_med);
                if (r->floor_ratio > 0.0) snprintf(fratio, sizeof fratio, "%.4f", r->floor_ratio);
            }
            len += (size_t)snprintf(buf + len, cap - len,
                                    "%s,%s,%s,%s,%s,%s,%s,%g,%d,%d,%d,%u,%s,%.4f,%.4f,%.4f,%s,%s,%s,%s,%s,%s\n",
                                    ob_query_scene_name(scene), ob_query_camera(scene, r->camera).name,
                                    method_name(r->method), samples, rr, rw, ob_filter_at(r->cfg->filter)->name,
                                    1.0 / r->cfg->ao_divisor, r->width, r->height, eyes, r->triangles,
                                    frame ? "frame" : r->pass[p], med, lo, hi, fps, minus, ratio, label, fms, fratio);
        }
    }
    int code = cli_outputs_write_text(outs, index, buf);
    free(buf);
    return code;
}

/* ---- --host ---------------------------------------------------------------------------------- */

/* "12.345 (12.1-13.0)", or "-" for a pass the path did not run. */
static void host_cell(char *out, size_t n, const double *v, bool ran)
{
    if (!ran) snprintf(out, n, "-");
    else snprintf(out, n, "%.3f (%.3f-%.3f)", v[0], v[1], v[2]);
}

void bench_print_host_tables(const bench_opts *o, const ob_scene *scene, const host_state *hst, const int *cams,
                             int cam_count)
{
    static const char *const letter[HOST_PATHS] = {"(a)", "(b)", "(c)", "(d)"};
    for (int ci = 0; ci < cam_count; ++ci) {
        printf("\n== %s, camera %s, %dx%d%s: the host path (ob_host_ao) beside the frame's AO chain, GPU ms median (min-max) "
               "of %d frames, the four alternated frame by frame ==\n",
               ob_query_scene_name(scene), ob_query_camera(scene, cams[ci]).name, o->common.width, o->common.height,
               o->common.temporal ? ", temporal on" : "", o->frames);
        printf("(a) frame            ob_render_frame, the sum of its chain passes (downsample, edges, depth_mips, "
               "second_back, ao, temporal, filter, upsample)\n"
               "(b) host_linear      ob_host_ao, R32F linear depth + RGBA16F view normals -> R32F\n"
               "(c) host_packed      ob_host_ao, D32F reversed-Z depth + octahedral RG16F world normals -> R8\n"
               "(d) host_no_normals  ob_host_ao, D32F reversed-Z depth, no normals (rebuilt by the input pass) -> R8\n"
               "x (a): the median over the frames of each frame's total / (a) in the same frame\n"
               "call cpu ms: the call's wall time on the CPU (checks, GL-state save and restore, submission; the "
               "GPU runs on asynchronously), with (a)'s G-buffer and lighting\n");
        for (int i = 0; i < hst->count; ++i) {
            const host_row *r = &hst->rows[i];
            if (r->camera != cams[ci]) continue;
            char label[CLI_MAX_LABEL + 32];
            snprintf(label, sizeof label, "%s", r->cfg->label);
            if (r->samples > 0) snprintf(label + strlen(label), sizeof label - strlen(label), " \xc2\xb7 N %d", r->samples);
            if (r->r > 0.0f) snprintf(label + strlen(label), sizeof label - strlen(label), " \xc2\xb7 r %g", (double)r->r);
            printf("\n%s\n  %-20s %-26s %-26s %-26s %-26s %-8s %s\n", label, "path", "chain ms", "input ms", "output ms",
                   "total ms", "x (a)", "call cpu ms");
            for (int p = 0; p < HOST_PATHS; ++p) {
                const host_path_row *pr = &r->path[p];
                char ch[64], inp[64], out[64], tot[64], cpu[64];
                host_cell(ch, sizeof ch, pr->chain, true);
                host_cell(inp, sizeof inp, pr->input, pr->has_input);
                host_cell(out, sizeof out, pr->output, pr->has_output);
                host_cell(tot, sizeof tot, pr->total, true);
                host_cell(cpu, sizeof cpu, pr->call, true);
                printf("  %s %-16s %-26s %-26s %-26s %-26s %.3fx   %s\n", letter[p], host_path_names[p], ch, inp, out, tot,
                       pr->ratio[0], cpu);
            }
            const double *q = r->path[HOST_LINEAR].ratio;
            printf("  (b)/(a) = %.3fx (frames' ratios: median, min %.3f, max %.3f): %s %.2fx\n", q[0], q[1], q[2],
                   q[0] <= HOST_TARGET ? "within" : "over", HOST_TARGET);
        }
    }
    if (hst->acc_count > 0) {
        printf("\n== host path accuracy: RMSE (bias) against the ray-traced AO_R (%d rays/px), %dx%d, each view's "
               "suggested radius, after %d calls ==\n",
               HOST_RMSE_SPP, HOST_RMSE_W, HOST_RMSE_H, HOST_RMSE_FRAMES);
        printf("  %-28s %-24s %-20s %-20s %-20s %-20s %s\n", "view", "configuration", "(a) frame", "(b) host_linear",
               "(c) host_packed", "(d) host_no_normals", "(d) - (b)");
        for (int i = 0; i < hst->acc_count; ++i) {
            const host_acc_row *a = &hst->acc[i];
            char view[330], cells[HOST_PATHS][48];
            snprintf(view, sizeof view, "%s:%s", a->scene, a->camera);
            for (int p = 0; p < HOST_PATHS; ++p)
                snprintf(cells[p], sizeof cells[p], "%.4f (%+.4f)", a->m[p].rmse, a->m[p].bias);
            printf("  %-28s %-24s %-20s %-20s %-20s %-20s %+.4f\n", view, a->cfg->label, cells[0], cells[1], cells[2],
                   cells[3], a->m[HOST_NO_NORMALS].rmse - a->m[HOST_LINEAR].rmse);
        }
    }
}

static void stat_json(cJSON *parent, const char *name, const double *v, bool ran)
{
    if (!ran) {
        cJSON_AddNullToObject(parent, name);
        return;
    }
    cJSON *j = cJSON_AddObjectToObject(parent, name);
    cli_json_add_number(j, "median", v[0]);
    cli_json_add_number(j, "min", v[1]);
    cli_json_add_number(j, "max", v[2]);
}

static cJSON *host_row_json(const host_row *r, const ob_scene *scene)
{
    cJSON *j = cJSON_CreateObject();
    char label[CLI_MAX_LABEL + 32] = "";
    row_label(&(bench_row){.cfg = r->cfg, .samples = r->samples, .r = r->r}, label, sizeof label);
    config_json(j, label, r->cfg->method, r->cfg, scene, r->camera, r->samples, r->r, r->radius_world, r->width,
                r->height);
    cJSON_AddBoolToObject(j, "temporal", r->cfg->settings.temporal);
    cJSON *paths = cJSON_AddObjectToObject(j, "paths");
    for (int p = 0; p < HOST_PATHS; ++p) {
        const host_path_row *pr = &r->path[p];
        cJSON *x = cJSON_AddObjectToObject(paths, host_path_names[p]);
        cJSON_AddStringToObject(x, "depth", host_path_depth[p]);
        cJSON_AddStringToObject(x, "normals", host_path_normals[p]);
        cJSON_AddStringToObject(x, "output", host_path_output[p]);
        cJSON *passes = cJSON_AddArrayToObject(x, "passes");
        for (int k = 0; k < pr->pass_count; ++k) {
            cJSON *q = cJSON_CreateObject();
            cJSON_AddStringToObject(q, "name", pr->pass[k]);
            cli_json_add_number(q, "median", pr->med[k]);
            cli_json_add_number(q, "min", pr->min[k]);
            cli_json_add_number(q, "max", pr->max[k]);
            cJSON_AddItemToArray(passes, q);
        }
        stat_json(x, "chain_ms", pr->chain, true);
        stat_json(x, "input_ms", pr->input, pr->has_input);
        stat_json(x, "output_ms", pr->output, pr->has_output);
        stat_json(x, "total_ms", pr->total, true);
        stat_json(x, "ratio_to_frame", pr->ratio, true);
        stat_json(x, "call_cpu_ms", pr->call, true);
    }
    const double *q = r->path[HOST_LINEAR].ratio;
    cli_json_add_number(j, "host_ratio", q[0]);
    cJSON_AddBoolToObject(j, "host_within_target", q[0] <= HOST_TARGET);
    return j;
}

static cJSON *host_acc_json(const host_state *hst)
{
    cJSON *j = cJSON_CreateObject();
    cli_json_add_number(j, "width", HOST_RMSE_W);
    cli_json_add_number(j, "height", HOST_RMSE_H);
    cli_json_add_number(j, "reference_spp", HOST_RMSE_SPP);
    cli_json_add_number(j, "calls", HOST_RMSE_FRAMES);
    cJSON *arr = cJSON_AddArrayToObject(j, "views");
    for (int i = 0; i < hst->acc_count; ++i) {
        const host_acc_row *a = &hst->acc[i];
        cJSON *x = cJSON_CreateObject();
        cJSON_AddStringToObject(x, "scene", a->scene);
        cJSON_AddStringToObject(x, "camera", a->camera);
        cJSON_AddStringToObject(x, "method", method_name(a->cfg->method));
        cJSON_AddStringToObject(x, "label", a->cfg->label);
        if (a->samples > 0) cli_json_add_number(x, "samples", a->samples);
        else cJSON_AddNullToObject(x, "samples");
        cli_json_add_number(x, "radius_world", a->radius);
        cJSON_AddBoolToObject(x, "reference_cached", a->ref_cached);
        cli_json_add_number(x, "reference_stderr", a->ref_stderr);
        cli_json_add_number(x, "pixels", (double)a->m[HOST_FRAME].count);
        for (int p = 0; p < HOST_PATHS; ++p) {
            cJSON *m = cJSON_AddObjectToObject(x, host_path_names[p]);
            cli_json_add_number(m, "rmse", a->m[p].rmse);
            cli_json_add_number(m, "bias", a->m[p].bias);
            cli_json_add_number(m, "mae", a->m[p].mae);
            cli_json_add_number(m, "ssim", a->m[p].ssim);
        }
        cli_json_add_number(x, "no_normals_minus_linear_rmse", a->m[HOST_NO_NORMALS].rmse - a->m[HOST_LINEAR].rmse);
        cJSON_AddItemToArray(arr, x);
    }
    return j;
}

int bench_write_host_csv(cli_outputs *outs, int index, const host_state *hst, const ob_scene *scene)
{
    size_t cap = 4096 + (size_t)hst->count * HOST_PATHS * (700 + CLI_MAX_LABEL), len = 0;
    char *buf = malloc(cap);
    if (!buf) return cli_fail(EXIT_RUNTIME, "out of memory");
    len += (size_t)snprintf(buf + len, cap - len,
                            "scene,camera,method,samples,r,radius_world,filter,ao_scale,temporal,width,height,path,depth,"
                            "normals,output,chain_ms,chain_min_ms,chain_max_ms,input_ms,input_min_ms,input_max_ms,output_ms,"
                            "output_min_ms,output_max_ms,total_ms,total_min_ms,total_max_ms,ratio_frame,ratio_frame_min,"
                            "ratio_frame_max,call_cpu_ms,call_cpu_min_ms,call_cpu_max_ms,label\n");
    for (int i = 0; i < hst->count; ++i) {
        const host_row *r = &hst->rows[i];
        char label[CLI_MAX_LABEL + 32] = "", samples[16] = "", rr[32] = "", rw[32] = "";
        row_label(&(bench_row){.cfg = r->cfg, .samples = r->samples, .r = r->r}, label, sizeof label);
        if (r->samples > 0) snprintf(samples, sizeof samples, "%d", r->samples);
        if (r->r > 0.0f) {
            snprintf(rr, sizeof rr, "%g", (double)r->r);
            snprintf(rw, sizeof rw, "%g", (double)r->radius_world);
        }
        for (int p = 0; p < HOST_PATHS; ++p) {
            const host_path_row *pr = &r->path[p];
            char in[96] = ",,", out[96] = ",,";
            if (pr->has_input) snprintf(in, sizeof in, "%.4f,%.4f,%.4f", pr->input[0], pr->input[1], pr->input[2]);
            if (pr->has_output) snprintf(out, sizeof out, "%.4f,%.4f,%.4f", pr->output[0], pr->output[1], pr->output[2]);
            len += (size_t)snprintf(buf + len, cap - len,
                                    "%s,%s,%s,%s,%s,%s,%s,%g,%s,%d,%d,%s,%s,%s,%s,%.4f,%.4f,%.4f,%s,%s,%.4f,%.4f,%.4f,"
                                    "%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%s\n",
                                    ob_query_scene_name(scene), ob_query_camera(scene, r->camera).name,
                                    method_name(r->cfg->method), samples, rr, rw, ob_filter_at(r->cfg->filter)->name,
                                    1.0 / r->cfg->ao_divisor, r->cfg->settings.temporal ? "on" : "off", r->width, r->height,
                                    host_path_names[p], host_path_depth[p], host_path_normals[p], host_path_output[p],
                                    pr->chain[0], pr->chain[1], pr->chain[2], in, out, pr->total[0], pr->total[1],
                                    pr->total[2], pr->ratio[0], pr->ratio[1], pr->ratio[2], pr->call[0], pr->call[1],
                                    pr->call[2], label);
        }
    }
    int code = cli_outputs_write_text(outs, index, buf);
    free(buf);
    return code;
}

/* ---- --json ---------------------------------------------------------------------------------- */

/* What made the numbers: the tool, its commit and command line, the machine, the scene and the
 * run's settings. */
static void json_run(cJSON *root, const bench_opts *o, ob_context *ctx, const ob_scene *scene, double seconds)
{
    const cli_common *c = &o->common;
    char cpu[256], date[64];
    cpu_model(cpu, sizeof cpu);
    time_t t = time(NULL);
    struct tm tm_utc;
    gmtime_r(&t, &tm_utc);
    strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", &tm_utc);
    /* The filters as one string: "geometry", or "none,geometry" for a list. */
    char filters[256] = "";
    for (int f = 0; f < c->filter_count; ++f) {
        size_t len = strlen(filters);
        snprintf(filters + len, sizeof filters - len, "%s%s", f ? "," : "", ob_filter_at(c->filters[f])->name);
    }
    cJSON_AddStringToObject(root, "tool", "obscura bench " OB_VERSION_STRING);
    cJSON_AddStringToObject(root, "date", date);
    /* Every option that shaped the run (--set, --settings, --shadow, --hdr included), as given. */
    cli_json_commit_and_command(root, o->argc, o->argv);
    cJSON_AddStringToObject(root, "renderer", ob_query_renderer(ctx));
    cJSON_AddStringToObject(root, "gl_version", ob_query_gl_version(ctx));
    cJSON_AddStringToObject(root, "device", ob_query_device(ctx));
    cJSON_AddBoolToObject(root, "software", ob_query_is_software(ctx));
    cJSON_AddStringToObject(root, "cpu", cpu);
    cli_json_add_number(root, "cpu_cores", (double)sysconf(_SC_NPROCESSORS_ONLN));
    cJSON_AddStringToObject(root, "scene", ob_query_scene_name(scene));
    cli_json_add_number(root, "triangles", ob_query_scene_stats(scene).triangles);
    cli_json_add_number(root, "scene_radius", ob_query_scene_ao_radius(scene));
    cJSON_AddStringToObject(root, "radius_rule", "radius_world = r x scene_radius / 4 (r = 4: the suggested radius)");
    cJSON_AddStringToObject(root, "mode", o->host ? "host" : o->scaling ? "scaling" : o->stereo ? "stereo" : "sweep");
    cli_json_add_number(root, "width", c->width);
    cli_json_add_number(root, "height", c->height);
    cli_json_add_number(root, "eyes", o->stereo ? 2 : 1);
    if (o->stereo) {
        cli_json_add_number(root, "ipd", o->ipd);
        cli_json_add_number(root, "budget_ms", VR_BUDGET_MS);
    }
    cli_json_add_number(root, "frames", o->frames);
    /* Issue 17: the accumulation and the camera's motion change every pass's work. */
    cJSON_AddBoolToObject(root, "temporal", c->temporal);
    if (c->temporal) cli_common_temporal_json(c, root);
    if (c->path) cJSON_AddStringToObject(root, "path", c->path);
    if (c->has_orbit) cli_json_add_number(root, "orbit_degrees", c->orbit_deg);
    if (cli_common_moves(c)) cli_json_add_number(root, "path_frames", c->path_frames);
    cli_json_add_number(root, "warmup", o->warmup);
    cJSON_AddBoolToObject(root, "floor", o->floor);
    /* What every ms below is: frame_ms is easily read as the frame's wall-clock time, which it is not. */
    cJSON_AddStringToObject(root, "timing", "GPU ms from GL_TIMESTAMP queries around each pass, median/min/max over the "
                                            "measured frames; frame_ms is the sum of a frame's timed passes (stereo: both "
                                            "eyes') and fps 1000 / its median, not wall-clock time; only --host's "
                                            "call_cpu_ms is wall-clock time, on the CPU");
    cJSON_AddStringToObject(root, "filter", filters);
    cli_json_add_number(root, "seconds", seconds);
}

/* --host: the target, the four paths, each configuration's paths and the accuracy. */
static void json_host(cJSON *root, cJSON *arr, const host_state *hst, const ob_scene *scene)
{
    cli_json_add_number(root, "host_target", HOST_TARGET);
    cJSON *hp = cJSON_AddArrayToObject(root, "host_paths");
    for (int p = 0; p < HOST_PATHS; ++p) {
        cJSON *x = cJSON_CreateObject();
        cJSON_AddStringToObject(x, "name", host_path_names[p]);
        cJSON_AddStringToObject(x, "depth", host_path_depth[p]);
        cJSON_AddStringToObject(x, "normals", host_path_normals[p]);
        cJSON_AddStringToObject(x, "output", host_path_output[p]);
        cJSON_AddItemToArray(hp, x);
    }
    for (int i = 0; i < hst->count; ++i) cJSON_AddItemToArray(arr, host_row_json(&hst->rows[i], scene));
    if (hst->acc_count > 0) cJSON_AddItemToObject(root, "host_rmse", host_acc_json(hst));
    else cJSON_AddNullToObject(root, "host_rmse");
}

/* --scaling: each combination's verdicts. */
static void json_scaling(cJSON *root, const bench_state *st, const cli_config *configs, int count)
{
    cJSON *sc = cJSON_AddArrayToObject(root, "scaling");
    for (int k = 0; k < count; ++k) {
        scaling_verdict v = verdict(st, &configs[k]);
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "method", method_name(configs[k].method));
        cJSON_AddStringToObject(j, "label", configs[k].label);
        cli_json_add_number(j, "triangle_max_min_ratio", v.tri_ratio);
        cJSON_AddBoolToObject(j, "flat_in_triangles", v.flat_in_triangles);
        cli_json_add_number(j, "ms_per_megapixel_spread", v.mpx_spread);
        cJSON_AddBoolToObject(j, "linear_in_pixels", v.linear_in_pixels);
        cJSON_AddItemToArray(sc, j);
    }
}

int bench_write_json(cli_outputs *outs, int index, const bench_opts *o, ob_context *ctx, const ob_scene *scene,
                     const bench_state *st, const host_state *hst, const bench_plan *p, double seconds)
{
    cJSON *root = cJSON_CreateObject();
    json_run(root, o, ctx, scene, seconds);
    cJSON *arr = cJSON_AddArrayToObject(root, "configurations");
    if (o->host) json_host(root, arr, hst, scene);
    for (int i = 0; i < st->count; ++i) {
        cJSON *j = row_json(&st->rows[i], baseline_of(st, &st->rows[i]), scene);
        if (o->stereo) cJSON_AddBoolToObject(j, "within_budget", st->rows[i].frame_med <= VR_BUDGET_MS);
        cJSON_AddItemToArray(arr, j);
    }
    if (o->scaling) json_scaling(root, st, p->configs, p->count);
    char *text = cJSON_Print(root);
    cJSON_Delete(root);
    int code = text ? cli_outputs_write_text(outs, index, text) : cli_fail(EXIT_RUNTIME, "out of memory");
    free(text);
    return code;
}
