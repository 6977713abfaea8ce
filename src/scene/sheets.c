/* Which flat parts with holes are sheets, over the whole scene (scene/parts.c marks the
 * candidates mesh by mesh and finds their holes). A drilled plate or a grille is a flat part whose
 * open edges form two loops or more, and nothing stands in its holes: the floor seen through them
 * lies far off its plane. A Quake map's floor is flat with holes too, but the holes are where
 * pillars and walls stand on it, and the floor is the top of a solid the mesh does not close: its
 * thickness is unknown, not nothing. Treating those as sheets made the floors and ledges of the
 * OpenArena views read too open (docs/methods.md, "Thin holes"). So a candidate stays a sheet only
 * when no vertex of any other part lies on its plane within one of its holes (a pillar in a hole,
 * a pit's wall at a hole's rim). What touches it along its outline alone, the wall a vent or a
 * grille is set flush into or a frame round it, leaves it a sheet: the first rule asked nothing
 * of any other part within the candidate's whole bounds, and read such a vent as unknown, a slab
 * of the constant thickness behind its slots. */
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
    size_t first_hole, holes; /* its holes in the gathered list */
} candidate;

static int find_candidate(const candidate *c, int count, int mesh, float label, int hint)
{
    if (hint >= 0 && hint < count && c[hint].mesh == mesh && c[hint].label == label) return hint;
    for (int i = 0; i < count; ++i)
        if (c[i].mesh == mesh && c[i].label == label) return i;
    return -1;
}

/* The candidates, their planes, and their holes' boxes (hole[c.first_hole ..], c.holes of them). -1
 * when out of memory. */
static int gather(const ob_scene *s, float *const *labels, const ob_holes *holes, candidate **out, int *count,
                  ob_hole **hole_out)
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
            }
            hint = i;
        }
    }
    size_t total = 0;
    for (int m = 0; m < s->mesh_count; ++m) total += holes[m].count;
    ob_hole *hole = malloc(total * sizeof *hole + 1);
    if (!hole) return free(c), -1;
    size_t k = 0;
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
        c[i].first_hole = k;
        const ob_holes *h = &holes[c[i].mesh];
        for (size_t j = 0; j < h->count; ++j)
            if (h->items[j].label == c[i].label) hole[k++] = h->items[j];
        c[i].holes = k - c[i].first_hole;
    }
    *out = c;
    *count = n;
    *hole_out = hole;
    return 0;
}

static bool inside(const float x[3], const float lo[3], const float hi[3])
{
    return x[0] >= lo[0] && x[0] <= hi[0] && x[1] >= lo[1] && x[1] <= hi[1] && x[2] >= lo[2] && x[2] <= hi[2];
}

int ob_scene_settle_sheets(const ob_scene *s, float *const *labels, const ob_holes *holes)
{
    candidate *c = NULL;
    ob_hole *hole = NULL;
    int n = 0;
    if (gather(s, labels, holes, &c, &n, &hole) != 0)
        return ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory finding the sheets of scene '%s'", s->name), -1;
    double extent = 0.0;
    for (int k = 0; k < 3; ++k)
        extent = fmax(extent, (double)s->bounds_max[k] - (double)s->bounds_min[k]);
    /* The parts' own tolerance (scene/parts.c: 1e-6 of a mesh's extent per grid step, 100 steps). */
    float tol = (float)(1e-4 * (extent > 0.0 && isfinite(extent) ? extent : 1.0));
    float all_lo[3] = {INFINITY, INFINITY, INFINITY}, all_hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    size_t hole_count = n > 0 ? c[n - 1].first_hole + c[n - 1].holes : 0;
    for (size_t j = 0; j < hole_count; ++j)
        for (int k = 0; k < 3; ++k) {
            hole[j].lo[k] -= tol, hole[j].hi[k] += tol;
            all_lo[k] = fminf(all_lo[k], hole[j].lo[k]), all_hi[k] = fmaxf(all_hi[k], hole[j].hi[k]);
        }
    for (int m = 0; m < s->mesh_count && hole_count > 0; ++m) {
        const ob_mesh *mesh = &s->meshes[m];
        for (uint32_t v = 0; v < mesh->vertex_count; ++v) {
            const float *x = &mesh->positions[3u * v];
            /* Most vertices lie outside every hole: one test against their union first. */
            if (!inside(x, all_lo, all_hi)) continue;
            for (int i = 0; i < n; ++i) {
                candidate *ci = &c[i];
                if (ci->standing || (ci->mesh == m && ci->label == labels[m][v])) continue;
                bool in_hole = false;
                for (size_t j = ci->first_hole; !in_hole && j < ci->first_hole + ci->holes; ++j)
                    in_hole = inside(x, hole[j].lo, hole[j].hi);
                if (!in_hole) continue;
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
    free(hole);
    return sheets;
}
