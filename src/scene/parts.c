/* The connected parts of a mesh, for the second depth layer (shaders/peel.frag.glsl): the
 * surface behind a pixel's first layer is the back of the same solid only when it belongs to the
 * same part. A part is a set of triangles joined through shared corners, where two corners at the
 * same position count as shared even as different vertices (an importer splits a vertex at every
 * hard edge to give each face its own normal, which would cut a box into six parts).
 *
 * Why parts and not the winding alone: the motorbike of the check views (one mesh of 67 parts
 * wound either way, on a ground quad) put the ground 0.8 m behind a part, wound the other way,
 * as that part's back, and its holes read black; the parts tell them apart. */
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>

#include "scene/scene.h"

/* A vertex's position on a grid of 1e-6 of the mesh's extent: corners that a builder or an
 * exporter computed along different sums (x0 + i c + c against x0 + (i + 1) c) differ in the last
 * bits and are still one corner. */
typedef struct corner {
    int64_t key[3];
    uint32_t vertex;
} corner;

static int compare_corners(const void *pa, const void *pb)
{
    const corner *a = pa, *b = pb;
    for (int k = 0; k < 3; ++k)
        if (a->key[k] != b->key[k]) return a->key[k] < b->key[k] ? -1 : 1;
    return 0;
}

static uint32_t find_root(uint32_t *parent, uint32_t v)
{
    while (parent[v] != v) {
        parent[v] = parent[parent[v]]; /* path halving */
        v = parent[v];
    }
    return v;
}

static void join(uint32_t *parent, uint32_t a, uint32_t b)
{
    a = find_root(parent, a);
    b = find_root(parent, b);
    if (a != b) parent[a < b ? b : a] = a < b ? a : b;
}

static int compare_edges(const void *pa, const void *pb)
{
    uint64_t a = *(const uint64_t *)pa, b = *(const uint64_t *)pb;
    return a < b ? -1 : a > b;
}

bool ob_triangle_plane(const ob_mesh *m, uint32_t t, double plane[4])
{
    const uint32_t n = m->vertex_count, a = m->indices[t], b = m->indices[t + 1u], c = m->indices[t + 2u];
    if (a >= n || b >= n || c >= n) return false;
    const float *p = m->positions;
    double u[3], w[3];
    for (uint32_t k = 0; k < 3u; ++k) {
        u[k] = (double)p[3u * b + k] - (double)p[3u * a + k];
        w[k] = (double)p[3u * c + k] - (double)p[3u * a + k];
    }
    double nx = u[1] * w[2] - u[2] * w[1], ny = u[2] * w[0] - u[0] * w[2], nz = u[0] * w[1] - u[1] * w[0];
    double len = sqrt(nx * nx + ny * ny + nz * nz);
    if (!(len > 0.0)) return false;
    plane[0] = nx / len, plane[1] = ny / len, plane[2] = nz / len;
    plane[3] = plane[0] * p[3u * a] + plane[1] * p[3u * a + 1u] + plane[2] * p[3u * a + 2u];
    return true;
}

/* Which of the parts with two loops or more (loops[root] >= 2) are flat: every vertex within
 * `tolerance` of the plane of the part's first triangle with an area. sheet[root] is set for those.
 * slot: n words of scratch. -1 when out of memory. */
static int flat_parts(const ob_mesh *m, uint32_t *parent, const uint32_t *loops, double tolerance, uint32_t *slot,
                      bool *sheet)
{
    const uint32_t n = m->vertex_count;
    uint32_t count = 0;
    for (uint32_t v = 0; v < n; ++v) slot[v] = loops[v] >= 2u ? count++ : UINT32_MAX; /* loops counts at roots only */
    double *plane = malloc((size_t)count * 4u * sizeof *plane + 1);
    bool *has = calloc((size_t)count + 1, sizeof *has), *flat = malloc((size_t)count + 1);
    if (!plane || !has || !flat) {
        free(plane), free(has), free(flat);
        return -1;
    }
    for (uint32_t i = 0; i < count; ++i) flat[i] = true;
    for (uint32_t t = 0; count > 0 && t + 2u < m->index_count; t += 3u) {
        uint32_t a = m->indices[t];
        uint32_t c = a < n ? slot[find_root(parent, a)] : UINT32_MAX;
        if (c != UINT32_MAX && !has[c]) has[c] = ob_triangle_plane(m, t, &plane[4u * c]);
    }
    const float *p = m->positions;
    for (uint32_t v = 0; count > 0 && v < n; ++v) {
        uint32_t c = slot[find_root(parent, v)];
        if (c == UINT32_MAX || !has[c]) continue;
        const double *q = &plane[4u * c];
        if (fabs(q[0] * p[3u * v] + q[1] * p[3u * v + 1u] + q[2] * p[3u * v + 2u] - q[3]) > tolerance) flat[c] = false;
    }
    for (uint32_t v = 0; v < n; ++v) sheet[v] = slot[v] != UINT32_MAX && has[slot[v]] && flat[slot[v]];
    free(plane), free(has), free(flat);
    return 0;
}

/* Which parts are sheets: a flat part whose open edges (edges of one triangle only, corners taken
 * by position) form two loops or more is a surface with holes in it, a drilled or cut sheet, which
 * has no thickness of its own. A closed solid has no open edge; a single polygon, or a wall of a
 * Quake map (whose brushes are not closed in the mesh), has one loop and stays unknown: its solid
 * may lie behind it. Open edges alone are not enough: real meshes have cracks (the engine's
 * castings, the motorbike's parts read as sheets made the fins 4x worse: docs/methods.md, "Thin
 * holes"), and a part that is not flat is not a sheet of one plane. scene/sheets.c then settles
 * these candidates over the whole scene. sheet[part root] is set for each vertex's part (parent:
 * the parts' forest); welded[v] is the first vertex at v's position; loop_of[v] (n words) gets the
 * loop of open edges through v's position, UINT32_MAX where none. -1 when out of memory. */
static int find_sheets(const ob_mesh *m, const uint32_t *welded, uint32_t *parent, double tolerance, bool *sheet,
                       uint32_t *loop_of)
{
    uint32_t n = m->vertex_count;
    size_t edges = 0, cap = (size_t)(m->index_count / 3u) * 3u;
    uint64_t *edge = malloc(cap * sizeof *edge + 1);
    uint32_t *loop = malloc((size_t)n * sizeof *loop + 1), *loops = calloc((size_t)n + 1, sizeof *loops);
    bool *open = calloc((size_t)n + 1, sizeof *open);
    int code = edge && loop && loops && open ? 0 : -1;
    for (uint32_t t = 0; code == 0 && t + 2u < m->index_count; t += 3u)
        for (uint32_t k = 0; k < 3u; ++k) {
            uint32_t i = m->indices[t + k], j = m->indices[t + (k + 1u) % 3u];
            if (i >= n || j >= n || welded[i] == welded[j]) continue; /* out of range, or degenerate */
            uint32_t a = welded[i] < welded[j] ? welded[i] : welded[j], b = welded[i] < welded[j] ? welded[j] : welded[i];
            edge[edges++] = (uint64_t)a << 32 | b;
        }
    if (code == 0) {
        qsort(edge, edges, sizeof *edge, compare_edges);
        for (uint32_t v = 0; v < n; ++v) loop[v] = v;
        for (size_t e = 0, run; e < edges; e = run) {
            for (run = e + 1; run < edges && edge[run] == edge[e];) ++run;
            if (run > e + 1) continue; /* shared by two triangles or more */
            uint32_t a = (uint32_t)(edge[e] >> 32), b = (uint32_t)edge[e];
            open[a] = open[b] = true;
            join(loop, a, b);
        }
        /* Each loop once, at its root (an open corner: join keeps the lower index), on its part;
         * every vertex at an open corner's position keeps its loop for the holes' bounds. */
        for (uint32_t v = 0; v < n; ++v) {
            if (open[v] && find_root(loop, v) == v) ++loops[find_root(parent, v)];
            loop_of[v] = open[welded[v]] ? find_root(loop, welded[v]) : UINT32_MAX;
        }
        code = flat_parts(m, parent, loops, tolerance, loop, sheet); /* the loops' forest is done with */
    }
    free(edge);
    free(loop);
    free(loops);
    free(open);
    return code;
}

/* The holes of each sheet candidate: every loop of its open edges but the widest, its outline, as
 * a box in the mesh's coordinates with the part's label (sheets.c asks whether anything stands
 * in one). loop_of from find_sheets. -1 when out of memory. */
static int sheet_holes(const ob_mesh *m, uint32_t *parent, const bool *sheet, const uint32_t *loop_of,
                       const float *labels, ob_holes *holes)
{
    const uint32_t n = m->vertex_count;
    uint32_t *slot = malloc((size_t)n * sizeof *slot + 1), count = 0;
    if (!slot) return -1;
    for (uint32_t v = 0; v < n; ++v) slot[v] = UINT32_MAX;
    for (uint32_t v = 0; v < n; ++v) /* one box per loop of a candidate, at the loop's root */
        if (loop_of[v] != UINT32_MAX && sheet[find_root(parent, v)] && slot[loop_of[v]] == UINT32_MAX)
            slot[loop_of[v]] = count++;
    typedef struct {
        float lo[3], hi[3];
        uint32_t part;
        bool used;
    } box;
    box *b = calloc((size_t)count + 1, sizeof *b);
    uint32_t *widest = malloc((size_t)n * sizeof *widest + 1); /* per part root: its widest loop's box */
    if (!b || !widest) return free(slot), free(b), free(widest), -1;
    for (uint32_t v = 0; v < n; ++v) {
        widest[v] = UINT32_MAX;
        if (loop_of[v] == UINT32_MAX || slot[loop_of[v]] == UINT32_MAX) continue;
        box *x = &b[slot[loop_of[v]]];
        const float *p = &m->positions[3u * v];
        for (int k = 0; k < 3; ++k) {
            x->lo[k] = x->used && x->lo[k] < p[k] ? x->lo[k] : p[k];
            x->hi[k] = x->used && x->hi[k] > p[k] ? x->hi[k] : p[k];
        }
        x->part = find_root(parent, v);
        x->used = true;
    }
    /* The outline is the loop whose box has the longest diagonal: a hole lies inside it. */
    for (uint32_t i = 0; i < count; ++i) {
        float d = 0.0f, e = 0.0f;
        uint32_t *w = &widest[b[i].part];
        for (int k = 0; k < 3; ++k) {
            d += (b[i].hi[k] - b[i].lo[k]) * (b[i].hi[k] - b[i].lo[k]);
            if (*w != UINT32_MAX) e += (b[*w].hi[k] - b[*w].lo[k]) * (b[*w].hi[k] - b[*w].lo[k]);
        }
        if (*w == UINT32_MAX || d > e) *w = i;
    }
    int code = 0;
    for (uint32_t i = 0; code == 0 && i < count; ++i) {
        if (widest[b[i].part] == i) continue;
        if (holes->count == holes->cap) {
            size_t cap = holes->cap ? 2 * holes->cap : 16;
            ob_hole *grown = realloc(holes->items, cap * sizeof *grown);
            if (!grown) {
                code = -1;
                break;
            }
            holes->items = grown, holes->cap = cap;
        }
        ob_hole *h = &holes->items[holes->count++];
        h->label = labels[b[i].part];
        for (int k = 0; k < 3; ++k) h->lo[k] = b[i].lo[k], h->hi[k] = b[i].hi[k];
    }
    free(slot), free(b), free(widest);
    return code;
}

int64_t ob_mesh_part_labels(const ob_mesh *m, uint32_t first, float *labels, ob_holes *holes)
{
    uint32_t n = m->vertex_count;
    uint32_t *parent = malloc((size_t)n * sizeof *parent + 1);
    corner *sorted = malloc((size_t)n * sizeof *sorted + 1);
    if (!parent || !sorted) {
        free(parent);
        free(sorted);
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory finding the parts of a %u-vertex mesh", n);
        return -1;
    }
    float lo[3] = {0.0f, 0.0f, 0.0f}, hi[3] = {0.0f, 0.0f, 0.0f};
    for (uint32_t v = 0; v < n; ++v)
        for (int k = 0; k < 3; ++k) {
            float x = m->positions[3u * v + (uint32_t)k];
            lo[k] = v == 0 || x < lo[k] ? x : lo[k];
            hi[k] = v == 0 || x > hi[k] ? x : hi[k];
        }
    double extent = 0.0;
    for (int k = 0; k < 3; ++k) extent = (double)hi[k] - (double)lo[k] > extent ? (double)hi[k] - (double)lo[k] : extent;
    double quantum = extent > 0.0 && isfinite(extent) ? 1e-6 * extent : 1.0;
    for (uint32_t v = 0; v < n; ++v) {
        parent[v] = v;
        sorted[v].vertex = v;
        for (int k = 0; k < 3; ++k)
            sorted[v].key[k] = (int64_t)llround(((double)m->positions[3u * v + (uint32_t)k] - (double)lo[k]) / quantum);
    }
    qsort(sorted, n, sizeof *sorted, compare_corners);
    uint32_t *welded = malloc((size_t)n * sizeof *welded + 1); /* the first vertex at each position */
    bool *sheet = malloc((size_t)n * sizeof *sheet + 1);
    for (uint32_t i = 0, run = 0; welded && i < n; ++i) {
        if (i > 0 && compare_corners(&sorted[i - 1], &sorted[i]) == 0)
            join(parent, sorted[i - 1].vertex, sorted[i].vertex);
        else
            run = sorted[i].vertex;
        welded[sorted[i].vertex] = run;
    }
    free(sorted);
    for (uint32_t t = 0; t + 2u < m->index_count; t += 3u) {
        uint32_t a = m->indices[t], b = m->indices[t + 1u], c = m->indices[t + 2u];
        if (a >= n || b >= n || c >= n) continue; /* ob_scene checks indices; never trust them here */
        join(parent, a, b);
        join(parent, a, c);
    }
    /* Each root takes the next number in vertex order; the label is that number from `first` on,
     * folded into 1..OB_PART_LABELS (an RGBA16F channel holds the integers to 2048 exactly). Two
     * parts that fold onto one label are told apart by the winding alone. A sheet's vertices carry
     * OB_PART_SHEET on top, which the raster passes take off (shaders/gbuffer.vert.glsl). */
    uint32_t *number = malloc((size_t)n * sizeof *number + 1), *loop_of = malloc((size_t)n * sizeof *loop_of + 1);
    if (!number || !welded || !sheet || !loop_of ||
        find_sheets(m, welded, parent, 100.0 * quantum, sheet, loop_of) != 0) {
        free(number);
        free(loop_of);
        free(welded);
        free(sheet);
        free(parent);
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory finding the parts of a %u-vertex mesh", n);
        return -1;
    }
    for (uint32_t v = 0; v < n; ++v) number[v] = UINT32_MAX;
    uint32_t count = 0;
    for (uint32_t v = 0; v < n; ++v) {
        uint32_t r = find_root(parent, v);
        if (number[r] == UINT32_MAX) number[r] = count++;
        labels[v] = (float)(1u + (first + number[r]) % OB_PART_LABELS + (sheet[r] ? OB_PART_SHEET : 0u));
    }
    bool holes_ok = !holes || sheet_holes(m, parent, sheet, loop_of, labels, holes) == 0;
    free(number);
    free(loop_of);
    free(welded);
    free(sheet);
    free(parent);
    if (!holes_ok) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory finding the holes of a %u-vertex mesh", n);
        return -1;
    }
    return count;
}
