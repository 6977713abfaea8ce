/* Which flat parts with holes are sheets, over the whole scene (scene/parts.c marks the
 * candidates mesh by mesh). A drilled plate or a grille is a flat part whose open edges form two
 * loops or more, and nothing stands in its holes: the floor seen through them lies far off its
 * plane. A Quake map's floor is flat with holes too, but the holes are where pillars and walls
 * stand on it, and the floor is the top of a solid the mesh does not close: its thickness is
 * unknown, not nothing. Treating those as sheets made the floors and ledges of the OpenArena
 * views read too open (docs/methods.md, "Thin holes"). So a candidate stays a sheet only when no
 * vertex of any other part lies on its plane within its bounds; anything touching it in its own
 * plane (a wall at its edge, a pillar in a hole, a flush frame) makes it unknown again. */
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>

#include "scene/scene.h"

typedef struct candidate {
    int mesh;
    float label;       /* the part's label with OB_PART_SHEET */
    double normal[3];  /* the plane of its first triangle with an area */
    double offset;
    bool has_plane, standing;
    float lo[3], hi[3]; /* its bounds, grown by the tolerance */
} candidate;

static int find_candidate(const candidate *c, int count, int mesh, float label, int hint)
{
    if (hint >= 0 && hint < count && c[hint].mesh == mesh && c[hint].label == label) return hint;
    for (int i = 0; i < count; ++i)
        if (c[i].mesh == mesh && c[i].label == label) return i;
    return -1;
}

/* The candidates' bounds and planes. -1 when out of memory. */
static int gather(const ob_scene *s, float *const *labels, candidate **out, int *count)
{
    int n = 0, cap = 0, hint = -1;
    candidate *c = NULL;
    for (int m = 0; m < s->mesh_count; ++m) {
        const ob_mesh *mesh = &s->meshes[m];
        for (uint32_t v = 0; v < mesh->vertex_count; ++v) {
            if (labels[m][v] < (float)OB_PART_SHEET) continue;
            int i = find_candidate(c, n, m, labels[m][v], hint);
            if (i < 0) {
                if (n == cap) {
                    cap = cap ? 2 * cap : 16;
                    candidate *grown = realloc(c, (size_t)cap * sizeof *c);
                    if (!grown) return free(c), -1;
                    c = grown;
                }
                i = n++;
                c[i] = (candidate){.mesh = m, .label = labels[m][v]};
                for (int k = 0; k < 3; ++k) c[i].lo[k] = c[i].hi[k] = mesh->positions[3u * v + (uint32_t)k];
            }
            hint = i;
            for (int k = 0; k < 3; ++k) {
                float x = mesh->positions[3u * v + (uint32_t)k];
                c[i].lo[k] = x < c[i].lo[k] ? x : c[i].lo[k];
                c[i].hi[k] = x > c[i].hi[k] ? x : c[i].hi[k];
            }
        }
    }
    for (int i = 0; i < n; ++i) {
        const ob_mesh *mesh = &s->meshes[c[i].mesh];
        for (uint32_t t = 0; !c[i].has_plane && t + 2u < mesh->index_count; t += 3u) {
            uint32_t a = mesh->indices[t];
            if (a >= mesh->vertex_count || labels[c[i].mesh][a] != c[i].label) continue;
            double q[4];
            if (!ob_triangle_plane(mesh, t, q)) continue;
            c[i].normal[0] = q[0], c[i].normal[1] = q[1], c[i].normal[2] = q[2], c[i].offset = q[3];
            c[i].has_plane = true;
        }
    }
    *out = c;
    *count = n;
    return 0;
}

int ob_scene_settle_sheets(const ob_scene *s, float *const *labels)
{
    candidate *c = NULL;
    int n = 0;
    if (gather(s, labels, &c, &n) != 0)
        return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory finding the sheets of scene '%s'", s->name), -1;
    double extent = 0.0;
    for (int k = 0; k < 3; ++k)
        extent = fmax(extent, (double)s->bounds_max[k] - (double)s->bounds_min[k]);
    /* The parts' own tolerance (scene/parts.c: 1e-6 of a mesh's extent per grid step, 100 steps). */
    float tol = (float)(1e-4 * (extent > 0.0 && isfinite(extent) ? extent : 1.0));
    float all_lo[3] = {INFINITY, INFINITY, INFINITY}, all_hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < n; ++i)
        for (int k = 0; k < 3; ++k) {
            c[i].lo[k] -= tol, c[i].hi[k] += tol;
            all_lo[k] = fminf(all_lo[k], c[i].lo[k]), all_hi[k] = fmaxf(all_hi[k], c[i].hi[k]);
        }
    for (int m = 0; m < s->mesh_count && n > 0; ++m) {
        const ob_mesh *mesh = &s->meshes[m];
        for (uint32_t v = 0; v < mesh->vertex_count; ++v) {
            const float *x = &mesh->positions[3u * v];
            /* Most vertices lie outside every candidate: one test against their union first. */
            if (x[0] < all_lo[0] || x[0] > all_hi[0] || x[1] < all_lo[1] || x[1] > all_hi[1] || x[2] < all_lo[2] ||
                x[2] > all_hi[2])
                continue;
            for (int i = 0; i < n; ++i) {
                candidate *ci = &c[i];
                if (ci->standing || (ci->mesh == m && ci->label == labels[m][v])) continue;
                if (x[0] < ci->lo[0] || x[0] > ci->hi[0] || x[1] < ci->lo[1] || x[1] > ci->hi[1] || x[2] < ci->lo[2] ||
                    x[2] > ci->hi[2])
                    continue;
                double d = ci->normal[0] * x[0] + ci->normal[1] * x[1] + ci->normal[2] * x[2] - ci->offset;
                if (!ci->has_plane || fabs(d) <= (double)tol) ci->standing = true;
            }
        }
    }
    int sheets = 0;
    for (int i = 0; i < n; ++i) {
        sheets += !c[i].standing;
        if (!c[i].standing) continue;
        const ob_mesh *mesh = &s->meshes[c[i].mesh];
        for (uint32_t v = 0; v < mesh->vertex_count; ++v)
            if (labels[c[i].mesh][v] == c[i].label) labels[c[i].mesh][v] -= (float)OB_PART_SHEET;
    }
    free(c);
    return sheets;
}
