/* The scene container: allocation helpers shared by the builders (builtin.c, import.c,
 * sidecar.c), the bounds and the public queries and camera lookup. The loader that picks a builder
 * for a name is load.c, above them all: the container calls none of its builders. */
#include "scene/scene.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "base/suggest.h"

/* ---- allocation helpers ---------------------------------------------------------------------- */

/* Arrays grow to powers of two (at least 4) without storing a capacity: the count alone says
 * when the current block is full. Large IFC files add thousands of meshes, so growing one at a
 * time would copy quadratically. */
static bool grow_array(void **array, int count, size_t elem_size)
{
    bool full = count == 0 || (count >= 4 && (count & (count - 1)) == 0);
    if (!full) return true;
    size_t cap = count == 0 ? 4u : (size_t)count * 2u;
    void *p = realloc(*array, cap * elem_size);
    if (!p) return false;
    *array = p;
    return true;
}

ob_scene *ob_scene_alloc(const char *name)
{
    ob_scene *s = calloc(1, sizeof *s);
    if (!s) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory allocating scene '%s'", name ? name : "");
        return NULL;
    }
    snprintf(s->name, sizeof s->name, "%s", name ? name : "");
    return s;
}

ob_mesh *ob_scene_add_mesh(ob_scene *s, uint32_t vertex_count, uint32_t index_count, bool uvs)
{
    if (!s) return NULL;
    if (!grow_array((void **)&s->meshes, s->mesh_count, sizeof *s->meshes)) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: out of memory adding mesh %d", s->name,
                     s->mesh_count);
        return NULL;
    }
    /* calloc(0) may return NULL, which would read as a failure: ask for at least one. */
    size_t vc = vertex_count ? vertex_count : 1u;
    size_t ic = index_count ? index_count : 1u;
    ob_mesh m = {0};
    m.positions = calloc(vc * 3u, sizeof(float));
    m.normals = calloc(vc * 3u, sizeof(float));
    m.uvs = uvs ? calloc(vc * 2u, sizeof(float)) : NULL;
    m.indices = calloc(ic, sizeof(uint32_t));
    if (!m.positions || !m.normals || (uvs && !m.uvs) || !m.indices) {
        free(m.positions);
        free(m.normals);
        free(m.uvs);
        free(m.indices);
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: out of memory for a mesh of %u vertices", s->name,
                     (unsigned)vertex_count);
        return NULL;
    }
    m.vertex_count = vertex_count;
    m.index_count = index_count;
    m.material = 0;
    s->meshes[s->mesh_count] = m;
    return &s->meshes[s->mesh_count++];
}

int ob_scene_add_material(ob_scene *s, const char *name, float r, float g, float b)
{
    if (!s) return -1;
    if (!grow_array((void **)&s->materials, s->material_count, sizeof *s->materials)) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: out of memory adding material '%s'", s->name,
                     name ? name : "");
        return -1;
    }
    ob_material m = {0};
    snprintf(m.name, sizeof m.name, "%s", name ? name : "");
    m.diffuse[0] = r;
    m.diffuse[1] = g;
    m.diffuse[2] = b;
    m.texture = NULL;
    s->materials[s->material_count] = m;
    return s->material_count++;
}

bool ob_scene_add_camera(ob_scene *s, const ob_camera *cam)
{
    if (!s || !cam) return false;
    /* A later source (sidecar after glTF) wins by name; a camera named "default" replaces the
     * framing one at index 0. */
    for (int i = 0; i < s->camera_count; ++i) {
        if (strcmp(s->cameras[i].name, cam->name) == 0) {
            s->cameras[i] = *cam;
            return true;
        }
    }
    if (s->camera_count >= OB_MAX_CAMERAS) return false;
    s->cameras[s->camera_count++] = *cam;
    return true;
}

void ob_scene_finish(ob_scene *s)
{
    if (!s) return;
    float bmin[3] = {FLT_MAX, FLT_MAX, FLT_MAX};
    float bmax[3] = {-FLT_MAX, -FLT_MAX, -FLT_MAX};
    bool any = false;
    for (int m = 0; m < s->mesh_count; ++m) {
        const ob_mesh *mesh = &s->meshes[m];
        for (uint32_t v = 0; v < mesh->vertex_count; ++v) {
            for (int i = 0; i < 3; ++i) {
                float p = mesh->positions[3u * v + (uint32_t)i];
                if (p < bmin[i]) bmin[i] = p;
                if (p > bmax[i]) bmax[i] = p;
            }
            any = true;
        }
    }
    for (int i = 0; i < 3; ++i) {
        s->bounds_min[i] = any ? bmin[i] : 0.0f;
        s->bounds_max[i] = any ? bmax[i] : 0.0f;
    }

    /* Every mesh must name a real material, so the renderer never indexes out of range. */
    bool need_default_material = s->material_count == 0;
    for (int m = 0; m < s->mesh_count; ++m) {
        if (s->meshes[m].material < 0 || s->meshes[m].material >= s->material_count) {
            need_default_material = true;
        }
    }
    if (need_default_material) {
        int old_count = s->material_count;
        int def = ob_scene_add_material(s, "default", 0.8f, 0.8f, 0.8f);
        for (int m = 0; m < s->mesh_count && def >= 0; ++m) {
            if (s->meshes[m].material < 0 || s->meshes[m].material >= old_count) {
                s->meshes[m].material = def;
            }
        }
    }

    ob_camera def_cam = ob_camera_frame_bounds(s->bounds_min, s->bounds_max, 60.0f);
    if (s->camera_count > 0 && strcmp(s->cameras[0].name, "default") == 0) {
        s->cameras[0] = def_cam; /* finish() called again: refresh the framing */
    } else {
        /* Presets added before finish() keep their order behind "default". */
        int keep = s->camera_count < OB_MAX_CAMERAS ? s->camera_count : OB_MAX_CAMERAS - 1;
        memmove(&s->cameras[1], &s->cameras[0], (size_t)keep * sizeof s->cameras[0]);
        s->cameras[0] = def_cam;
        s->camera_count = keep + 1;
    }

    if (s->light_count == 0) {
        s->light_count = 1;
        s->lights[0].type = OB_LIGHT_DIRECTIONAL;
        /* Above, in front and to the left: the default camera sits front-right, so shadows fall
         * away from it and show the shape instead of hiding behind it. */
        const float d[3] = {-0.4f, 1.0f, 0.5f};
        float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        for (int i = 0; i < 3; ++i) {
            s->lights[0].direction[i] = d[i] / len;
            s->lights[0].color[i] = 1.0f;
        }
        /* Direct + ambient stays near 1 on white: a sensible exposure even with --hdr off. */
        s->lights[0].intensity = 0.8f;
    }

    if (!(s->ao_radius > 0.0f) || !isfinite(s->ao_radius)) {
        float d2 = 0.0f;
        for (int i = 0; i < 3; ++i) {
            float e = s->bounds_max[i] - s->bounds_min[i];
            d2 += e * e;
        }
        float diag = sqrtf(d2);
        s->ao_radius = diag > 0.0f ? 0.05f * diag : 1.0f;
    }
}

/* ---- bounds ---------------------------------------------------------------------------------- */

/* The range a scene must lie in, from float (24-bit significand, normal range 1.2e-38..3.4e38):
 * - Size: the passes square distances and divide by squared radii (falloffs 1/d^2, r^2 in the AO
 *   kernels, projection terms near*far), and products of two such terms occur: d^4 must stay a
 *   normal float with room to spare. A diagonal in [1e-6, 1e8] keeps d^4 in [1e-24, 1e32].
 *   Outside it a model is almost surely in the wrong unit (or hostile: 3e37 and 1e-30 rendered
 *   empty frames).
 * - Offset: positions are float, so a vertex at distance C from the origin is only known to
 *   C * 2^-23 (1.2e-7 C). Screen-space AO compares depths at a twentieth of the scene's size;
 *   an error of a tenth of that (5e-3 of the diagonal) is where it starts to show as noise, so
 *   C may be at most 5e-3 / 1.2e-7, about 4e4 diagonals: 1e4 leaves a margin for the view
 *   transform's own rounding.
 * A scene outside these is an error, not a rescale: sidecar cameras and lights are written in
 * the model's units and would no longer match. */
#define OB_SCENE_MIN_SIZE 1e-6
#define OB_SCENE_MAX_SIZE 1e8
#define OB_SCENE_MAX_OFFSET 1e4

bool ob_scene_check_bounds(const ob_scene *s, const char *source)
{
    for (int m = 0; m < s->mesh_count; ++m) {
        const ob_mesh *mesh = &s->meshes[m];
        for (uint32_t k = 0; k < 3u * mesh->vertex_count; ++k) {
            if (!isfinite(mesh->positions[k])) {
                ob_set_error(OB_ERR_MODEL, "%s: vertex %u has a non-finite coordinate (%g) after its node transforms",
                             source, k / 3u, (double)mesh->positions[k]);
                return false;
            }
        }
    }
    double d2 = 0.0, far = 0.0;
    for (int i = 0; i < 3; ++i) {
        double e = (double)s->bounds_max[i] - (double)s->bounds_min[i];
        d2 += e * e;
        far = fmax(far, fmax(fabs((double)s->bounds_min[i]), fabs((double)s->bounds_max[i])));
    }
    double size = sqrt(d2);
    if (!(size >= OB_SCENE_MIN_SIZE) || !(size <= OB_SCENE_MAX_SIZE)) {
        ob_set_error(OB_ERR_MODEL, "%s: the model is %g units across; Obscura renders %g to %g (float depth and lighting): wrong unit?",
                     source, size, OB_SCENE_MIN_SIZE, OB_SCENE_MAX_SIZE);
        return false;
    }
    if (far > OB_SCENE_MAX_OFFSET * size) {
        ob_set_error(OB_ERR_MODEL, "%s: the model lies %g units from the origin but is only %g across; float positions lose its detail beyond %g times its size: move it nearer the origin",
                     source, far, size, OB_SCENE_MAX_OFFSET);
        return false;
    }
    return true;
}

void ob_destroy_scene(ob_scene *scene)
{
    if (!scene) return;
    for (int m = 0; m < scene->mesh_count; ++m) {
        free(scene->meshes[m].positions);
        free(scene->meshes[m].normals);
        free(scene->meshes[m].uvs);
        free(scene->meshes[m].indices);
    }
    for (int m = 0; m < scene->material_count; ++m)
        if (!scene->materials[m].texture_shared) free(scene->materials[m].texture);
    free(scene->meshes);
    free(scene->materials);
    free(scene);
}

/* ---- queries --------------------------------------------------------------------------------- */

ob_scene_stats ob_query_scene_stats(const ob_scene *scene)
{
    ob_scene_stats st = {0};
    if (!scene) {
        ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_query_scene_stats: scene is NULL");
        return st;
    }
    uint64_t tris = 0;
    uint64_t verts = 0;
    for (int m = 0; m < scene->mesh_count; ++m) {
        tris += scene->meshes[m].index_count / 3u;
        verts += scene->meshes[m].vertex_count;
    }
    st.triangles = tris > UINT32_MAX ? UINT32_MAX : (uint32_t)tris;
    st.vertices = verts > UINT32_MAX ? UINT32_MAX : (uint32_t)verts;
    st.meshes = (uint32_t)scene->mesh_count;
    st.materials = (uint32_t)scene->material_count;
    for (int i = 0; i < 3; ++i) {
        st.bounds_min[i] = scene->bounds_min[i];
        st.bounds_max[i] = scene->bounds_max[i];
    }
    return st;
}

const char *ob_query_scene_name(const ob_scene *scene)
{
    return scene ? scene->name : "";
}

int ob_query_scene_material_count(const ob_scene *scene)
{
    return scene ? scene->material_count : 0;
}

ob_material_info ob_query_scene_material(const ob_scene *scene, int index)
{
    ob_material_info info = {0};
    if (!scene || index < 0 || index >= scene->material_count) {
        ob_set_error(OB_ERR_OUT_OF_RANGE, "material index %d out of range (scene has %d)", index,
                     scene ? scene->material_count : 0);
        return info;
    }
    const ob_material *m = &scene->materials[index];
    memcpy(info.name, m->name, sizeof info.name);
    info.name[sizeof info.name - 1] = '\0';
    for (int i = 0; i < 3; ++i) info.diffuse[i] = m->diffuse[i];
    info.has_texture = m->texture != NULL;
    return info;
}

float ob_query_scene_ao_radius(const ob_scene *scene)
{
    return scene ? scene->ao_radius : 0.0f;
}

int ob_query_scene_light_count(const ob_scene *scene) { return scene ? scene->light_count : 0; }

ob_light ob_query_scene_light(const ob_scene *scene, int index)
{
    ob_light l = {0};
    return scene && index >= 0 && index < scene->light_count ? scene->lights[index] : l;
}

int ob_query_camera_count(const ob_scene *scene)
{
    return scene ? scene->camera_count : 0;
}

ob_camera ob_query_camera(const ob_scene *scene, int index)
{
    ob_camera cam = {0};
    if (!scene || index < 0 || index >= scene->camera_count) {
        ob_set_error(OB_ERR_OUT_OF_RANGE, "camera index %d out of range (scene has %d)", index,
                     scene ? scene->camera_count : 0);
        return cam;
    }
    return scene->cameras[index];
}

ob_error ob_find_camera(const ob_scene *scene, const char *name_or_index, ob_camera *out)
{
    if (!scene || !name_or_index) {
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_find_camera: %s is NULL",
                            !scene ? "scene" : "camera name");
    }
    for (int i = 0; i < scene->camera_count; ++i) {
        if (strcmp(scene->cameras[i].name, name_or_index) == 0) {
            if (out) *out = scene->cameras[i];
            return OB_OK;
        }
    }
    /* A decimal index: digits only, so "1e0", "-0" or " 1" are names, not numbers. */
    const char *c = name_or_index;
    long index = 0;
    bool digits = *c != '\0';
    for (; *c; ++c) {
        if (*c < '0' || *c > '9') {
            digits = false;
            break;
        }
        if (index <= OB_MAX_CAMERAS) index = index * 10 + (*c - '0');
    }
    if (digits && index < scene->camera_count) {
        if (out) *out = scene->cameras[index];
        return OB_OK;
    }
    char names[OB_MAX_CAMERAS * 66] = "";
    size_t used = 0;
    for (int i = 0; i < scene->camera_count; ++i) {
        int len = snprintf(names + used, sizeof names - used, "%s%s", i ? ", " : "",
                           scene->cameras[i].name);
        if (len < 0 || (size_t)len >= sizeof names - used) break;
        used += (size_t)len;
    }
    const char *known[OB_MAX_CAMERAS] = {0};
    for (int i = 0; i < scene->camera_count && i < OB_MAX_CAMERAS; ++i) known[i] = scene->cameras[i].name;
    char hint[96];
    return ob_set_error(OB_ERR_UNKNOWN_CAMERA,
                        "unknown camera '%s' in scene '%s'%s (available: %s; or an index 0-%d)", name_or_index,
                        scene->name,
                        ob_suggest_text(name_or_index, strlen(name_or_index), known,
                                        scene->camera_count < OB_MAX_CAMERAS ? scene->camera_count : OB_MAX_CAMERAS,
                                        hint, sizeof hint),
                        names, scene->camera_count - 1);
}
