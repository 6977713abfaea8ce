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

int64_t ob_mesh_part_labels(const ob_mesh *m, uint32_t first, float *labels)
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
    for (uint32_t i = 1; i < n; ++i)
        if (compare_corners(&sorted[i - 1], &sorted[i]) == 0) join(parent, sorted[i - 1].vertex, sorted[i].vertex);
    free(sorted);
    for (uint32_t t = 0; t + 2u < m->index_count; t += 3u) {
        uint32_t a = m->indices[t], b = m->indices[t + 1u], c = m->indices[t + 2u];
        if (a >= n || b >= n || c >= n) continue; /* ob_scene checks indices; never trust them here */
        join(parent, a, b);
        join(parent, a, c);
    }
    /* Each root takes the next number in vertex order; the label is that number from `first` on,
     * folded into 1..OB_PART_LABELS (an RGBA16F channel holds the integers to 2048 exactly). Two
     * parts that fold onto one label are told apart by the winding alone. */
    uint32_t *number = malloc((size_t)n * sizeof *number + 1);
    if (!number) {
        free(parent);
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory finding the parts of a %u-vertex mesh", n);
        return -1;
    }
    for (uint32_t v = 0; v < n; ++v) number[v] = UINT32_MAX;
    uint32_t count = 0;
    for (uint32_t v = 0; v < n; ++v) {
        uint32_t r = find_root(parent, v);
        if (number[r] == UINT32_MAX) number[r] = count++;
        labels[v] = (float)(1u + (first + number[r]) % OB_PART_LABELS);
    }
    free(number);
    free(parent);
    return count;
}
