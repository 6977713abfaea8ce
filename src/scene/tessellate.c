/* Midpoint subdivision of a whole scene, for the benchmark's triangle-count scaling study: the
 * surfaces stay exactly where they were (every new vertex lies on its triangle), so the image and
 * the screen-space passes see the same pixels while the G-buffer rasterises 4^levels as many
 * triangles. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "scene/scene.h"

enum { MAX_LEVELS = 4 };

/* One level: every triangle (a, b, c) gets its own three edge midpoints (ab, bc, ca) appended,
 * and becomes (a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca). Midpoints are not shared
 * between neighbours: sharing needs an edge map and buys nothing here, because coincident
 * vertices rasterise the same surface. Normals are averaged and renormalised, uvs averaged. */
static bool subdivide(const ob_mesh *in, ob_mesh *out)
{
    uint32_t tris = in->index_count / 3u;
    uint64_t vcount = (uint64_t)in->vertex_count + 3u * (uint64_t)tris;
    uint64_t icount = 12u * (uint64_t)tris;
    if (vcount > UINT32_MAX || icount > UINT32_MAX) return false;
    size_t vc = vcount ? (size_t)vcount : 1u;
    size_t ic = icount ? (size_t)icount : 1u;
    *out = (ob_mesh){.material = in->material};
    out->positions = malloc(vc * 3u * sizeof(float));
    out->normals = malloc(vc * 3u * sizeof(float));
    out->uvs = in->uvs ? malloc(vc * 2u * sizeof(float)) : NULL;
    out->indices = malloc(ic * sizeof(uint32_t));
    if (!out->positions || !out->normals || (in->uvs && !out->uvs) || !out->indices) return false;
    memcpy(out->positions, in->positions, (size_t)in->vertex_count * 3u * sizeof(float));
    memcpy(out->normals, in->normals, (size_t)in->vertex_count * 3u * sizeof(float));
    if (in->uvs) memcpy(out->uvs, in->uvs, (size_t)in->vertex_count * 2u * sizeof(float));
    uint32_t next = in->vertex_count;
    uint32_t *idx = out->indices;
    for (uint32_t t = 0; t < tris; ++t) {
        const uint32_t *v = in->indices + 3u * t;
        uint32_t mid[3] = {0, 0, 0}; /* ab, bc, ca */
        for (int e = 0; e < 3; ++e) {
            uint32_t p = v[e], q = v[(e + 1) % 3], m = next++;
            mid[e] = m;
            float n[3] = {0.0f, 0.0f, 0.0f};
            float len2 = 0.0f;
            for (int k = 0; k < 3; ++k) {
                out->positions[3u * m + (uint32_t)k] =
                    0.5f * (in->positions[3u * p + (uint32_t)k] + in->positions[3u * q + (uint32_t)k]);
                n[k] = in->normals[3u * p + (uint32_t)k] + in->normals[3u * q + (uint32_t)k];
                len2 += n[k] * n[k];
            }
            /* Opposite normals on one edge average to zero: keep the first one then. */
            float inv = len2 > 1e-20f ? 1.0f / sqrtf(len2) : 0.0f;
            for (int k = 0; k < 3; ++k)
                out->normals[3u * m + (uint32_t)k] = inv > 0.0f ? n[k] * inv : in->normals[3u * p + (uint32_t)k];
            if (in->uvs)
                for (int k = 0; k < 2; ++k)
                    out->uvs[2u * m + (uint32_t)k] = 0.5f * (in->uvs[2u * p + (uint32_t)k] + in->uvs[2u * q + (uint32_t)k]);
        }
        const uint32_t a = v[0], b = v[1], c = v[2], ab = mid[0], bc = mid[1], ca = mid[2];
        const uint32_t quad[12] = {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca};
        memcpy(idx, quad, sizeof quad);
        idx += 12;
    }
    out->vertex_count = (uint32_t)vcount;
    out->index_count = (uint32_t)icount;
    return true;
}

/* A deep copy (level 0), so the caller may destroy either scene first. */
static bool copy_mesh(const ob_mesh *in, ob_mesh *out)
{
    size_t vc = in->vertex_count ? in->vertex_count : 1u;
    size_t ic = in->index_count ? in->index_count : 1u;
    *out = *in;
    out->positions = malloc(vc * 3u * sizeof(float));
    out->normals = malloc(vc * 3u * sizeof(float));
    out->uvs = in->uvs ? malloc(vc * 2u * sizeof(float)) : NULL;
    out->indices = malloc(ic * sizeof(uint32_t));
    if (!out->positions || !out->normals || (in->uvs && !out->uvs) || !out->indices) return false;
    memcpy(out->positions, in->positions, (size_t)in->vertex_count * 3u * sizeof(float));
    memcpy(out->normals, in->normals, (size_t)in->vertex_count * 3u * sizeof(float));
    if (in->uvs) memcpy(out->uvs, in->uvs, (size_t)in->vertex_count * 2u * sizeof(float));
    memcpy(out->indices, in->indices, (size_t)in->index_count * sizeof(uint32_t));
    return true;
}

static void free_mesh(ob_mesh *m)
{
    free(m->positions);
    free(m->normals);
    free(m->uvs);
    free(m->indices);
    *m = (ob_mesh){0};
}

ob_scene *ob_tessellate_scene(const ob_scene *s, int levels)
{
    if (!s) {
        ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_tessellate_scene: NULL scene");
        return NULL;
    }
    if (levels < 0 || levels > MAX_LEVELS) {
        ob_set_error(OB_ERR_OUT_OF_RANGE, "ob_tessellate_scene: levels %d outside [0, %d]", levels, MAX_LEVELS);
        return NULL;
    }
    ob_scene *t = calloc(1, sizeof *t);
    if (!t) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory tessellating '%s'", s->name);
        return NULL;
    }
    /* Cameras, lights, radius and bounds carry over unchanged: subdivision moves no surface. */
    *t = *s;
    t->meshes = NULL;
    t->materials = NULL;
    t->mesh_count = 0;
    t->material_count = 0;
    bool ok = true;
    if (s->material_count > 0) {
        t->materials = calloc((size_t)s->material_count, sizeof *t->materials);
        ok = t->materials != NULL;
        for (int i = 0; ok && i < s->material_count; ++i) {
            t->materials[i] = s->materials[i];
            t->materials[i].texture = NULL;
            t->materials[i].texture_shared = false;
            t->material_count = i + 1;
            /* Pixels shared with an earlier material stay shared with that material's copy. */
            for (int j = 0; s->materials[i].texture_shared && j < i && !t->materials[i].texture; ++j) {
                if (!s->materials[j].texture_shared && s->materials[j].texture == s->materials[i].texture) {
                    t->materials[i].texture = t->materials[j].texture;
                    t->materials[i].texture_shared = true;
                }
            }
            if (s->materials[i].texture && !t->materials[i].texture) {
                size_t bytes = (size_t)s->materials[i].tex_width * (size_t)s->materials[i].tex_height * 4u;
                t->materials[i].texture = malloc(bytes);
                ok = t->materials[i].texture != NULL;
                if (ok) memcpy(t->materials[i].texture, s->materials[i].texture, bytes);
            }
        }
    }
    if (ok && s->mesh_count > 0) {
        t->meshes = calloc((size_t)s->mesh_count, sizeof *t->meshes);
        ok = t->meshes != NULL;
    }
    for (int m = 0; ok && m < s->mesh_count; ++m) {
        ob_mesh cur = {0};
        const ob_mesh *src = &s->meshes[m];
        for (int l = 0; ok && l < levels; ++l) {
            ob_mesh next = {0};
            ok = subdivide(l == 0 ? src : &cur, &next);
            if (l > 0) free_mesh(&cur);
            cur = next;
            if (!ok) free_mesh(&cur);
        }
        if (levels == 0) {
            ok = copy_mesh(src, &cur);
            if (!ok) free_mesh(&cur);
        }
        if (ok) {
            t->meshes[m] = cur;
            t->mesh_count = m + 1;
        }
    }
    if (!ok) {
        ob_destroy_scene(t);
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory (or over 2^32 indices) tessellating '%s' %d level(s)",
                     s->name, levels);
        return NULL;
    }
    return t;
}
