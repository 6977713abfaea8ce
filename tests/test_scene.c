/* Scene module tests (CPU only): built-in scenes, Assimp import of the test models, sidecars,
 * name resolution and error codes. Runs on tests/check.h: the exit status is the failure count
 * and the last line "scene: N passed, N failed".
 *
 * The system models (glmark2-data, assimp test models, python3-tinyobjloader) are skipped with a
 * note when absent, so the test still runs on a machine without them. */
#if !defined(_POSIX_C_SOURCE) && !defined(_GNU_SOURCE)
#define _POSIX_C_SOURCE 200809L /* mkdtemp, setenv */
#endif

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "check.h"
#include "obscura/eval.h"
#include "scene/scene.h" /* mesh data: normals and winding are not in the public API */

#define BUNNY_OBJ "/usr/share/glmark2/models/bunny.obj"
#define CORNELL_OBJ "/usr/share/doc/python3-tinyobjloader/examples/cornell_box.obj"
#define FZK_IFC "/usr/share/assimp/models/IFC/AC14-FZK-Haus.ifc"
#define CAMERAS_GLTF "/usr/share/assimp/models/glTF2/cameras/Cameras.gltf"
#define BOX_GLTF "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf"
#define BOX_GLB "/usr/share/assimp/models/glTF2/BoxTextured-glTF-Binary/BoxTextured.glb"
/* glTF 1.0 as collada2gltf wrote it: asset.version the number 1, buffers keyed by id. */
#define TRUCK_GLTF1 "/usr/share/assimp/models/glTF/CesiumMilkTruck/CesiumMilkTruck.gltf"

/* Counts observed with Assimp 5.2.5 on Debian 12 (see the printed lines). */
#define BUNNY_TRIANGLES 69666u

static bool near(float a, float b, float tol)
{
    return fabsf(a - b) <= tol;
}

static bool file_exists(const char *path)
{
    return access(path, R_OK) == 0;
}

static char tmpdir[256] = "";

static void tmp_path(char *out, size_t n, const char *name)
{
    snprintf(out, n, "%s/%s", tmpdir, name);
}

static void write_file(const char *path, const char *data, size_t len)
{
    FILE *f = fopen(path, "wb");
    if (!f) {
        CHECK(false, "cannot write %s", path);
        return;
    }
    fwrite(data, 1, len, f);
    fclose(f);
}

static void write_text(const char *path, const char *text)
{
    write_file(path, text, strlen(text));
}

static ob_scene *load(const char *name, const char *sidecar, ob_up_axis up)
{
    ob_scene_desc desc = {.name = name, .sidecar = sidecar, .up = up};
    return ob_load_scene(&desc);
}

static const char *last_message(void)
{
    const char *msg = "";
    ob_get_error(&msg);
    return msg;
}

/* Every normal unit length, every triangle counter-clockwise about its vertex normals. */
static void check_mesh_sanity(const ob_scene *s)
{
    uint32_t bad_normals = 0, bad_winding = 0, bad_index = 0;
    for (int m = 0; m < s->mesh_count; ++m) {
        const ob_mesh *mesh = &s->meshes[m];
        for (uint32_t v = 0; v < mesh->vertex_count; ++v) {
            const float *n = &mesh->normals[3u * v];
            float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (!near(len, 1.0f, 1e-4f)) ++bad_normals;
        }
        for (uint32_t t = 0; t + 2u < mesh->index_count; t += 3u) {
            const uint32_t *ix = &mesh->indices[t];
            if (ix[0] >= mesh->vertex_count || ix[1] >= mesh->vertex_count ||
                ix[2] >= mesh->vertex_count) {
                ++bad_index;
                continue;
            }
            const float *a = &mesh->positions[3u * ix[0]];
            const float *b = &mesh->positions[3u * ix[1]];
            const float *c = &mesh->positions[3u * ix[2]];
            float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            float f[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                          e1[0] * e2[1] - e1[1] * e2[0]};
            float d = 0.0f;
            for (int i = 0; i < 3; ++i) {
                d += f[i] * (mesh->normals[3u * ix[0] + (uint32_t)i] +
                             mesh->normals[3u * ix[1] + (uint32_t)i] +
                             mesh->normals[3u * ix[2] + (uint32_t)i]);
            }
            /* Zero-area slivers (FZK-Haus has a few) have no orientation and cover no pixels. */
            float area2 = f[0] * f[0] + f[1] * f[1] + f[2] * f[2];
            if (area2 > 1e-20f && !(d > 0.0f)) ++bad_winding;
        }
        CHECK(mesh->material >= 0 && mesh->material < s->material_count,
              "%s mesh %d: material %d out of range", s->name, m, mesh->material);
    }
    CHECK(bad_normals == 0, "%s: %u normals are not unit length", s->name, bad_normals);
    CHECK(bad_winding == 0, "%s: %u triangles are not counter-clockwise about their normals",
          s->name, bad_winding);
    CHECK(bad_index == 0, "%s: %u indices out of range", s->name, bad_index);
}

static void check_bounds(const char *what, const ob_scene_stats *st, const float lo[3],
                         const float hi[3], float tol)
{
    for (int i = 0; i < 3; ++i) {
        CHECK(near(st->bounds_min[i], lo[i], tol) && near(st->bounds_max[i], hi[i], tol),
              "%s: bounds axis %d = [%g, %g], expected [%g, %g]", what, i,
              (double)st->bounds_min[i], (double)st->bounds_max[i], (double)lo[i],
              (double)hi[i]);
    }
}

static void print_stats(const char *what, const ob_scene *s)
{
    ob_scene_stats st = ob_query_scene_stats(s);
    printf("%s: %u triangles, %u vertices, %u meshes, %u materials, bounds [%.4f %.4f %.4f] - "
           "[%.4f %.4f %.4f], ao_radius %.4g, %d cameras\n",
           what, st.triangles, st.vertices, st.meshes, st.materials, (double)st.bounds_min[0],
           (double)st.bounds_min[1], (double)st.bounds_min[2], (double)st.bounds_max[0],
           (double)st.bounds_max[1], (double)st.bounds_max[2],
           (double)ob_query_scene_ao_radius(s), ob_query_camera_count(s));
}

static bool bounds_sane(const ob_scene_stats *st)
{
    for (int i = 0; i < 3; ++i) {
        if (!isfinite(st->bounds_min[i]) || !isfinite(st->bounds_max[i])) return false;
        if (!(st->bounds_max[i] > st->bounds_min[i])) return false;
    }
    return true;
}

/* ---- built-ins ------------------------------------------------------------------------------- */

static void test_builtins(void)
{
    CHECK(ob_builtin_scene_count() == 7, "7 built-in scenes, got %d", ob_builtin_scene_count());
    for (int i = 0; i < ob_builtin_scene_count(); ++i) {
        CHECK(ob_builtin_scene_name(i) && ob_builtin_scene_description(i) &&
                  ob_builtin_scene_description(i)[0],
              "built-in %d has a name and a description", i);
    }
    CHECK(ob_builtin_scene_name(7) == NULL, "built-in name out of range is NULL");

    const struct {
        const char *name;
        uint32_t triangles;
        float lo[3], hi[3];
        float radius;
        const char *preset;
    } expect[] = {
        /* 16 quads; x reaches 556 mm at the ceiling's edge in the published data */
        {"cornell", 32u, {0.0f, 0.0f, 0.0f}, {0.556f, 0.5488f, 0.5592f}, 0.1f, "front"},
        /* 3 planes x 8 x 8 quads */
        {"corner", 384u, {0.0f, 0.0f, 0.0f}, {4.0f, 4.0f, 4.0f}, 0.5f, "diagonal"},
        /* sphere 48 x 24 without the degenerate pole halves: 48 * 46; plane 20 x 20 quads */
        {"sphere-on-plane", 2208u + 800u, {-5.0f, 0.0f, -5.0f}, {5.0f, 2.0f, 5.0f}, 0.5f,
         "contact"},
        /* floor 16 x 16 quads; two closed boxes of 6 quads, the thick one's top at 1.15 m */
        {"slab", 512u + 2u * 12u, {-4.0f, 0.0f, -4.0f}, {4.0f, 1.15f, 4.0f}, 0.5f, "front"},
        /* floor 8 x 8 quads, wall 4 x 8 */
        {"bleed", 128u + 64u, {0.0f, 0.0f, -2.0f}, {4.0f, 2.0f, 2.0f}, 0.5f, "side"},
        /* floor 16 x 16 quads; 11 x 11 cells less 25 holes per face: the sheet's one face, the
         * closed plate's top and bottom, 4 walls per hole and its 4-quad rim */
        {"grille", 512u + 3u * 192u + 25u * 8u + 8u, {-4.0f, 0.0f, -4.0f}, {4.0f, 0.49f, 4.0f}, 0.5f, "front"},
        /* floor 16 x 16 quads; the wall's 8 front quads, the recess's 5 and the box's 5; the
         * vent's 11 x 7 cells less 15 holes */
        {"vent", 512u + 2u * 18u + 2u * 62u, {-4.0f, 0.0f, -4.0f}, {4.0f, 2.0f, 4.0f}, 0.5f, "front"},
    };
    for (size_t k = 0; k < sizeof expect / sizeof expect[0]; ++k) {
        ob_scene *s = load(expect[k].name, NULL, OB_UP_DEFAULT);
        CHECK(s != NULL, "built-in %s loads: %s", expect[k].name, last_message());
        if (!s) continue;
        print_stats(expect[k].name, s);
        ob_scene_stats st = ob_query_scene_stats(s);
        CHECK(st.triangles == expect[k].triangles, "%s: %u triangles, expected %u",
              expect[k].name, st.triangles, expect[k].triangles);
        check_bounds(expect[k].name, &st, expect[k].lo, expect[k].hi, 1e-5f);
        CHECK(near(ob_query_scene_ao_radius(s), expect[k].radius, 1e-6f), "%s: ao_radius %g",
              expect[k].name, (double)ob_query_scene_ao_radius(s));
        CHECK(strcmp(ob_query_scene_name(s), expect[k].name) == 0, "%s: scene name '%s'",
              expect[k].name, ob_query_scene_name(s));
        CHECK(ob_query_camera_count(s) >= 2 &&
                  strcmp(ob_query_camera(s, 0).name, "default") == 0,
              "%s: camera 0 is \"default\" followed by presets", expect[k].name);
        ob_camera cam = {0};
        CHECK(ob_find_camera(s, expect[k].preset, &cam) == OB_OK, "%s: preset %s",
              expect[k].name, expect[k].preset);
        ob_light light = ob_query_scene_light(s, 0);
        float ll = sqrtf(light.direction[0] * light.direction[0] +
                         light.direction[1] * light.direction[1] +
                         light.direction[2] * light.direction[2]);
        if (light.type == OB_LIGHT_DIRECTIONAL) {
            CHECK(light.intensity > 0.0f && near(ll, 1.0f, 1e-5f) && light.direction[1] > 0.0f,
                  "%s: a unit light from above", expect[k].name);
        } else {
            /* Cornell's stand-in for its ceiling patch: a spot inside the box, near the top, aimed
             * down with a cone under 90 degrees, so that like the patch it lights neither the
             * ceiling nor its own housing (docs/lighting.md, "Cornell"). */
            ob_scene_stats bounds = ob_query_scene_stats(s);
            bool inside = true;
            for (int i = 0; i < 3; ++i)
                inside = inside && light.position[i] > bounds.bounds_min[i] && light.position[i] < bounds.bounds_max[i];
            CHECK(light.type == OB_LIGHT_SPOT && light.intensity > 0.0f && inside &&
                      light.position[1] > 0.9f * bounds.bounds_max[1] && light.direction[1] < -0.999f &&
                      light.spot_outer_deg < 90.0f,
                  "%s: a spot inside, near the top, aimed down", expect[k].name);
        }
        check_mesh_sanity(s);
        ob_destroy_scene(s);
    }

    /* Corner: the analytic scene needs exact, axis-aligned normals. */
    ob_scene *s = load("corner", NULL, OB_UP_DEFAULT);
    if (s) {
        uint32_t bad = 0;
        for (int m = 0; m < s->mesh_count; ++m) {
            const ob_mesh *mesh = &s->meshes[m];
            for (uint32_t v = 0; v < mesh->vertex_count; ++v) {
                const float *n = &mesh->normals[3u * v];
                const float *p = &mesh->positions[3u * v];
                int ones = 0, zeros = 0;
                for (int i = 0; i < 3; ++i) {
                    if (n[i] == 1.0f) ++ones;
                    if (n[i] == 0.0f) ++zeros;
                }
                /* The normal's axis is the axis on which the vertex lies at 0. */
                int axis = n[0] == 1.0f ? 0 : (n[1] == 1.0f ? 1 : 2);
                if (ones != 1 || zeros != 2 || p[axis] != 0.0f) ++bad;
            }
        }
        CHECK(bad == 0, "corner: %u normals not exact +x/+y/+z of their plane", bad);
        /* The diagonal preset sees all three planes: their far corners project inside a square
         * frame (any landscape image is at least as wide). */
        ob_camera cam = {0};
        ob_find_camera(s, "diagonal", &cam);
        const float corners[6][3] = {{4.0f, 0.0f, 0.0f}, {0.0f, 4.0f, 0.0f}, {0.0f, 0.0f, 4.0f},
                                     {4.0f, 0.0f, 4.0f}, {0.0f, 4.0f, 4.0f}, {4.0f, 4.0f, 0.0f}};
        float f[3] = {cam.target[0] - cam.eye[0], cam.target[1] - cam.eye[1],
                      cam.target[2] - cam.eye[2]};
        float fl = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
        for (int i = 0; i < 3; ++i) f[i] /= fl;
        /* right = f x (0,1,0), up = right x f */
        float r[3] = {-f[2], 0.0f, f[0]};
        float rl = sqrtf(r[0] * r[0] + r[2] * r[2]);
        r[0] /= rl;
        r[2] /= rl;
        float u[3] = {r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2],
                      r[0] * f[1] - r[1] * f[0]};
        float half = tanf(0.5f * cam.fov_y_deg * 3.14159265f / 180.0f);
        int outside = 0;
        for (int k = 0; k < 6; ++k) {
            float d[3] = {corners[k][0] - cam.eye[0], corners[k][1] - cam.eye[1],
                          corners[k][2] - cam.eye[2]};
            float z = d[0] * f[0] + d[1] * f[1] + d[2] * f[2];
            float x = (d[0] * r[0] + d[1] * r[1] + d[2] * r[2]) / (z * half);
            float y = (d[0] * u[0] + d[1] * u[1] + d[2] * u[2]) / (z * half);
            if (!(z > 0.0f && fabsf(x) < 1.0f && fabsf(y) < 1.0f)) ++outside;
        }
        CHECK(outside == 0, "corner: diagonal camera sees all plane corners (%d outside)",
              outside);
        ob_destroy_scene(s);
    }

    /* Cornell: red on the viewer's left (x ~ 0.55), green on the right (x = 0). */
    s = load("cornell", NULL, OB_UP_DEFAULT);
    if (s) {
        for (int m = 0; m < s->mesh_count; ++m) {
            const ob_material *mat = &s->materials[s->meshes[m].material];
            if (strcmp(mat->name, "red") == 0) {
                CHECK(s->meshes[m].positions[0] > 0.5f, "cornell: red wall at x ~ 0.55");
            }
            if (strcmp(mat->name, "green") == 0) {
                CHECK(s->meshes[m].positions[0] == 0.0f, "cornell: green wall at x = 0");
            }
        }
        ob_camera cam = {0};
        CHECK(ob_find_camera(s, "front", &cam) == OB_OK && near(cam.eye[2], -0.8f, 1e-6f) &&
                  near(cam.fov_y_deg, 39.3f, 1e-4f),
              "cornell: published camera in metres");
        ob_destroy_scene(s);
    }
}

/* ---- cameras --------------------------------------------------------------------------------- */

static void test_cameras(void)
{
    ob_scene *s = load("cornell", NULL, OB_UP_DEFAULT);
    if (!s) return;
    ob_camera cam = {0};
    CHECK(ob_find_camera(s, "front", &cam) == OB_OK && strcmp(cam.name, "front") == 0,
          "find camera by name");
    CHECK(ob_find_camera(s, "1", &cam) == OB_OK && strcmp(cam.name, "front") == 0,
          "find camera by index 1");
    CHECK(ob_find_camera(s, "0", &cam) == OB_OK && strcmp(cam.name, "default") == 0,
          "find camera by index 0");
    ob_error err = ob_find_camera(s, "nope", &cam);
    CHECK(err == OB_ERR_UNKNOWN_CAMERA && strstr(last_message(), "default") &&
              strstr(last_message(), "front"),
          "unknown camera lists the presets: %s", last_message());
    CHECK(ob_find_camera(s, "2", &cam) == OB_ERR_UNKNOWN_CAMERA, "index out of range");
    CHECK(ob_find_camera(s, "-1", &cam) == OB_ERR_UNKNOWN_CAMERA, "negative index");
    CHECK(ob_find_camera(s, "", &cam) == OB_ERR_UNKNOWN_CAMERA, "empty camera name");
    CHECK(ob_find_camera(NULL, "0", &cam) == OB_ERR_INVALID_ARGUMENT, "NULL scene");

    /* Default camera frames the bounds; planes are positive and ordered, also from inside. */
    ob_camera def = ob_query_camera(s, 0);
    ob_camera_fit_planes(&def, s->bounds_min, s->bounds_max);
    CHECK(def.near_z > 0.0f && def.far_z > def.near_z, "default camera planes %g %g",
          (double)def.near_z, (double)def.far_z);
    ob_camera inside = {.eye = {0.278f, 0.27f, 0.3f}, .target = {0.278f, 0.27f, 0.5f}};
    ob_camera_fit_planes(&inside, s->bounds_min, s->bounds_max);
    CHECK(inside.near_z > 0.0f && inside.near_z < 0.01f && inside.far_z > 0.5f,
          "interior camera planes %g %g", (double)inside.near_z, (double)inside.far_z);
    ob_destroy_scene(s);

    float lo[3] = {-1.0f, -2.0f, -3.0f}, hi[3] = {1.0f, 2.0f, 3.0f};
    ob_camera f = ob_camera_frame_bounds(lo, hi, 0.0f);
    float d[3] = {f.eye[0] - f.target[0], f.eye[1] - f.target[1], f.eye[2] - f.target[2]};
    float dist = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    float r = sqrtf(1.0f + 4.0f + 9.0f);
    CHECK(near(f.fov_y_deg, 60.0f, 1e-6f) && near(dist, 1.1f * r / 0.5f, 1e-3f) &&
              f.target[0] == 0.0f && f.eye[2] > 0.0f,
          "frame_bounds: sphere fits 60 degrees with 10%% margin (dist %g)", (double)dist);
}

/* ---- imported models ------------------------------------------------------------------------- */

static void test_bunny(void)
{
    if (!file_exists(BUNNY_OBJ)) {
        printf("skip: %s not installed\n", BUNNY_OBJ);
        return;
    }
    ob_scene *s = load(BUNNY_OBJ, NULL, OB_UP_DEFAULT);
    CHECK(s != NULL, "bunny loads: %s", last_message());
    if (!s) return;
    print_stats("bunny.obj", s);
    ob_scene_stats st = ob_query_scene_stats(s);
    /* The file's own scene sidecar (scenes/bunny.obscura.json) stands it on a ground: 2 more. */
    CHECK(st.triangles == BUNNY_TRIANGLES + 2u, "bunny: %u triangles, expected %u and the ground's 2",
          st.triangles, BUNNY_TRIANGLES);
    CHECK(bounds_sane(&st), "bunny: finite, non-degenerate bounds");
    check_mesh_sanity(s);
    ob_destroy_scene(s);

    /* The named scene: scenes/bunny.obscura.json in the data directory. */
    s = load("bunny", NULL, OB_UP_DEFAULT);
    CHECK(s != NULL, "named scene bunny loads: %s", last_message());
    if (s) {
        ob_camera cam = {0};
        CHECK(strcmp(ob_query_scene_name(s), "bunny") == 0, "named scene keeps its name");
        CHECK(ob_find_camera(s, "front", &cam) == OB_OK &&
                  ob_find_camera(s, "side", &cam) == OB_OK &&
                  ob_find_camera(s, "closeup", &cam) == OB_OK,
              "bunny presets front, side, closeup");
        ob_destroy_scene(s);
    }
}

static const ob_material_info *find_material(const ob_material_info *m, int n, const char *name)
{
    for (int i = 0; i < n; ++i) {
        if (strcmp(m[i].name, name) == 0) return &m[i];
    }
    return NULL;
}

static void test_cornell_obj(void)
{
    if (!file_exists(CORNELL_OBJ)) {
        printf("skip: %s not installed\n", CORNELL_OBJ);
        return;
    }
    ob_scene *s = load(CORNELL_OBJ, NULL, OB_UP_DEFAULT);
    CHECK(s != NULL, "cornell_box.obj loads: %s", last_message());
    if (!s) return;
    print_stats("cornell_box.obj", s);
    ob_scene_stats st = ob_query_scene_stats(s);
    /* 18 quads (the floor carries the blocks' footprints too; the front wall is commented
     * out). */
    CHECK(st.triangles == 36u, "cornell_box.obj: %u triangles, expected 36", st.triangles);
    const float lo[3] = {0.0f, 0.0f, 0.0f}, hi[3] = {556.0f, 548.8f, 559.2f};
    check_bounds("cornell_box.obj", &st, lo, hi, 1e-3f);
    ob_material_info mats[16] = {0};
    int n = ob_query_scene_material_count(s);
    for (int i = 0; i < n && i < 16; ++i) mats[i] = ob_query_scene_material(s, i);
    const ob_material_info *red = find_material(mats, n, "red");
    const ob_material_info *green = find_material(mats, n, "green");
    const ob_material_info *white = find_material(mats, n, "white");
    CHECK(red && near(red->diffuse[0], 1.0f, 1e-6f) && near(red->diffuse[1], 0.0f, 1e-6f) &&
              near(red->diffuse[2], 0.0f, 1e-6f),
          "cornell_box.obj: red is (1, 0, 0)");
    CHECK(green && near(green->diffuse[0], 0.0f, 1e-6f) &&
              near(green->diffuse[1], 1.0f, 1e-6f) && near(green->diffuse[2], 0.0f, 1e-6f),
          "cornell_box.obj: green is (0, 1, 0)");
    CHECK(white && near(white->diffuse[0], 1.0f, 1e-6f) &&
              near(white->diffuse[1], 1.0f, 1e-6f) && near(white->diffuse[2], 1.0f, 1e-6f),
          "cornell_box.obj: white is (1, 1, 1)");
    CHECK(find_material(mats, n, "blue") == NULL, "cornell_box.obj: unused blue is left out");
    CHECK(!mats[0].has_texture, "cornell_box.obj: no textures");
    check_mesh_sanity(s);
    ob_destroy_scene(s);

    s = load("cornell-obj", NULL, OB_UP_DEFAULT);
    CHECK(s != NULL, "named scene cornell-obj loads: %s", last_message());
    if (s) {
        ob_camera cam = {0};
        CHECK(ob_find_camera(s, "front", &cam) == OB_OK && near(cam.eye[2], -800.0f, 1e-3f) &&
                  near(cam.fov_y_deg, 39.3f, 1e-4f),
              "cornell-obj: front camera from the sidecar");
        CHECK(near(ob_query_scene_ao_radius(s), 100.0f, 1e-4f), "cornell-obj: ao_radius 100");
        ob_camera def = ob_query_camera(s, 0);
        CHECK(strcmp(def.name, "default") == 0 && near(def.eye[2], -800.0f, 1e-3f) &&
                  ob_query_camera_count(s) == 2,
              "cornell-obj: the sidecar's \"default\" replaces the framing camera");
        ob_destroy_scene(s);
    }
}

static void test_fzk_haus(void)
{
    if (!file_exists(FZK_IFC)) {
        printf("skip: %s not installed\n", FZK_IFC);
        return;
    }
    /* As the file comes, then as the named scene (with its sidecar's cameras). */
    ob_scene *s = load(FZK_IFC, NULL, OB_UP_DEFAULT);
    CHECK(s != NULL, "FZK-Haus loads: %s", last_message());
    if (!s) return;
    print_stats("AC14-FZK-Haus.ifc", s);
    ob_scene_stats st = ob_query_scene_stats(s);
    CHECK(st.triangles > 1000u, "FZK-Haus: %u triangles > 1000", st.triangles);
    CHECK(bounds_sane(&st), "FZK-Haus: finite, non-degenerate bounds");
    /* A house is wider than tall: after import the short axis must be Y (the importer already
     * turns IFC's Z-up into Y-up). */
    float ex = st.bounds_max[0] - st.bounds_min[0], ey = st.bounds_max[1] - st.bounds_min[1];
    float ez = st.bounds_max[2] - st.bounds_min[2];
    CHECK(ey < ex && ey < ez, "FZK-Haus: Y is up after import (extent %g %g %g)", (double)ex,
          (double)ey, (double)ez);
    check_mesh_sanity(s);
    /* Flat walls keep flat normals: the painted walls ("Anstrich") are planar quads, so every
     * vertex normal must equal its triangle's face normal. A crease angle of 45 degrees or
     * more blends the walls' 45-degree mitres into them. */
    uint32_t bent = 0, wall_vertices = 0;
    for (int m = 0; m < s->mesh_count; ++m) {
        const ob_mesh *mesh = &s->meshes[m];
        if (strcmp(s->materials[mesh->material].name, "Anstrich") != 0) continue;
        for (uint32_t t = 0; t + 2u < mesh->index_count; t += 3u) {
            const uint32_t *ix = &mesh->indices[t];
            const float *a = &mesh->positions[3u * ix[0]];
            const float *b = &mesh->positions[3u * ix[1]];
            const float *c = &mesh->positions[3u * ix[2]];
            float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            float f[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                          e1[0] * e2[1] - e1[1] * e2[0]};
            float fl = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
            if (!(fl > 1e-6f)) continue;
            for (int k = 0; k < 3; ++k) {
                const float *n = &mesh->normals[3u * ix[k]];
                float cosang = (n[0] * f[0] + n[1] * f[1] + n[2] * f[2]) / fl;
                ++wall_vertices;
                if (cosang < cosf(1.0f * 3.14159265f / 180.0f)) ++bent;
            }
        }
    }
    CHECK(wall_vertices > 0 && bent == 0,
          "FZK-Haus: %u of %u wall triangle corners have normals bent > 1 degree", bent,
          wall_vertices);
    ob_destroy_scene(s);

    s = load("fzk-haus", NULL, OB_UP_DEFAULT);
    CHECK(s != NULL, "named scene fzk-haus loads: %s", last_message());
    if (s) {
        print_stats("fzk-haus (named)", s);
        for (int i = 0; i < ob_query_camera_count(s); ++i) {
            ob_camera c = ob_query_camera(s, i);
            printf("  camera %d %s eye (%.2f %.2f %.2f) target (%.2f %.2f %.2f) fov %.1f\n", i,
                   c.name, (double)c.eye[0], (double)c.eye[1], (double)c.eye[2],
                   (double)c.target[0], (double)c.target[1], (double)c.target[2],
                   (double)c.fov_y_deg);
        }
        CHECK(ob_query_camera_count(s) >= 4, "fzk-haus: exterior and two interior presets");
        ob_destroy_scene(s);
    }
}

/* A glTF 1.0 file Assimp reads is read: the pre-check takes a version of 1 (a number, as
 * collada2gltf wrote it) or buffers keyed by id as glTF 1 and checks it as such, where it took the
 * number for glTF 2 and refused "bufferView 0 lies outside its buffer". */
static void test_gltf1(void)
{
    if (!file_exists(TRUCK_GLTF1)) {
        printf("skip: %s not installed\n", TRUCK_GLTF1);
        return;
    }
    ob_scene *s = load(TRUCK_GLTF1, NULL, OB_UP_DEFAULT);
    CHECK(s != NULL, "CesiumMilkTruck.gltf (glTF 1.0, version 1) loads: %s", last_message());
    if (!s) return;
    ob_scene_stats st = ob_query_scene_stats(s);
    printf("CesiumMilkTruck.gltf: %u triangles, %u meshes, %u materials\n", (unsigned)st.triangles, (unsigned)st.meshes,
           (unsigned)st.materials);
    CHECK(st.triangles > 1000 && st.meshes >= 1, "the truck has its triangles (%u)", (unsigned)st.triangles);
    ob_destroy_scene(s);
}

/* A model with no sidecar (glmark2's horse) gets a ground under it only when asked
 * (ob_scene_desc.automatic_ground): two triangles at its lowest point in a material named
 * OB_AUTOMATIC_GROUND_MATERIAL, 4 x its width, the AO radius and the default camera its own. A
 * model with a sidecar (the bunny, scenes/bunny.obscura.json) gets none. */
#define HORSE_3DS "/usr/share/glmark2/models/horse.3ds"
static void test_automatic_ground(void)
{
    if (!file_exists(HORSE_3DS)) {
        printf("skip: %s not installed\n", HORSE_3DS);
        return;
    }
    ob_scene *plain = ob_load_scene(&(ob_scene_desc){.name = HORSE_3DS});
    ob_scene *ground = ob_load_scene(&(ob_scene_desc){.name = HORSE_3DS, .automatic_ground = true});
    ob_scene *bunny = ob_load_scene(&(ob_scene_desc){.name = BUNNY_OBJ, .automatic_ground = true});
    CHECK(plain && ground, "the horse loads: %s", last_message());
    if (plain && ground) {
        ob_scene_stats a = ob_query_scene_stats(plain), b = ob_query_scene_stats(ground);
        const int n = ob_query_scene_material_count(ground);
        ob_material_info last = ob_query_scene_material(ground, n - 1);
        float wa = fmaxf(a.bounds_max[0] - a.bounds_min[0], a.bounds_max[2] - a.bounds_min[2]);
        float wb = fminf(b.bounds_max[0] - b.bounds_min[0], b.bounds_max[2] - b.bounds_min[2]);
        printf("horse: %u triangles, ground %u more; width %g, ground's %g; AO radius %g and %g\n", a.triangles,
               b.triangles - a.triangles, (double)wa, (double)wb, (double)ob_query_scene_ao_radius(plain),
               (double)ob_query_scene_ao_radius(ground));
        CHECK(b.triangles == a.triangles + 2 && n == ob_query_scene_material_count(plain) + 1 &&
                  !strcmp(last.name, OB_AUTOMATIC_GROUND_MATERIAL),
              "the automatic ground: two triangles in the material '%s' (got %u more, '%s')", OB_AUTOMATIC_GROUND_MATERIAL,
              b.triangles - a.triangles, last.name);
        CHECK(b.bounds_min[1] == a.bounds_min[1] && fabsf(wb - 4.0f * wa) <= 1e-3f * wa,
              "it lies at the model's lowest point, 4 x its width (%g against %g)", (double)wb, (double)wa);
        CHECK(ob_query_scene_ao_radius(ground) == ob_query_scene_ao_radius(plain),
              "the AO radius follows the model alone");
        bool none = true;
        for (int i = 0; i < ob_query_scene_material_count(plain); ++i)
            none = none && strcmp(ob_query_scene_material(plain, i).name, OB_AUTOMATIC_GROUND_MATERIAL) != 0;
        CHECK(none, "no ground unless asked");
    }
    if (bunny) {
        bool none = true;
        for (int i = 0; i < ob_query_scene_material_count(bunny); ++i)
            none = none && strcmp(ob_query_scene_material(bunny, i).name, OB_AUTOMATIC_GROUND_MATERIAL) != 0;
        CHECK(none, "a model with a sidecar gets no automatic ground");
    }
    ob_destroy_scene(plain);
    ob_destroy_scene(ground);
    ob_destroy_scene(bunny);
}

static void test_gltf_cameras(void)
{
    if (!file_exists(CAMERAS_GLTF)) {
        printf("skip: %s not installed\n", CAMERAS_GLTF);
        return;
    }
    ob_scene *s = load(CAMERAS_GLTF, NULL, OB_UP_DEFAULT);
    CHECK(s != NULL, "Cameras.gltf loads: %s", last_message());
    if (!s) return;
    /* One perspective camera (yfov 0.7 rad, aspect 1) at node translation (0.5, 0.5, 3)
     * looking down -Z; the orthographic one is skipped. */
    CHECK(ob_query_camera_count(s) == 2, "Cameras.gltf: default + 1 perspective preset, got %d",
          ob_query_camera_count(s));
    if (ob_query_camera_count(s) >= 2) {
        ob_camera c = ob_query_camera(s, 1);
        printf("Cameras.gltf: preset '%s' eye (%g %g %g) target (%g %g %g) fov %g\n", c.name,
               (double)c.eye[0], (double)c.eye[1], (double)c.eye[2], (double)c.target[0],
               (double)c.target[1], (double)c.target[2], (double)c.fov_y_deg);
        CHECK(near(c.eye[0], 0.5f, 1e-5f) && near(c.eye[1], 0.5f, 1e-5f) &&
                  near(c.eye[2], 3.0f, 1e-5f),
              "Cameras.gltf: eye from the node transform");
        CHECK(c.target[2] < c.eye[2] && near(c.target[0], c.eye[0], 1e-5f),
              "Cameras.gltf: looks down -Z");
        CHECK(near(c.fov_y_deg, 0.7f * 180.0f / 3.14159265f, 1e-3f),
              "Cameras.gltf: vertical fov %g from the horizontal one", (double)c.fov_y_deg);
    }
    ob_destroy_scene(s);
}

static void test_textures(void)
{
    /* External PNG beside the glTF, then the same image embedded in a .glb ("*0"). */
    const char *files[2] = {BOX_GLTF, BOX_GLB};
    for (int k = 0; k < 2; ++k) {
        if (!file_exists(files[k])) {
            printf("skip: %s not installed\n", files[k]);
            continue;
        }
        ob_scene *s = load(files[k], NULL, OB_UP_DEFAULT);
        CHECK(s != NULL, "%s loads: %s", files[k], last_message());
        if (!s) continue;
        bool textured = false;
        for (int m = 0; m < s->mesh_count; ++m) {
            const ob_material *mat = &s->materials[s->meshes[m].material];
            if (mat->texture && mat->tex_width == 211 && mat->tex_height == 211 &&
                s->meshes[m].uvs) {
                textured = true;
            }
        }
        CHECK(textured, "%s: 211 x 211 diffuse texture and uvs", files[k]);
        CHECK(ob_query_scene_material(s, 0).has_texture, "%s: has_texture", files[k]);
        ob_destroy_scene(s);
    }

    /* A texture that cannot be found is not fatal. */
    char obj[512], mtl[512];
    tmp_path(obj, sizeof obj, "tex.obj");
    tmp_path(mtl, sizeof mtl, "tex.mtl");
    write_text(mtl, "newmtl m\nKd 0.5 0.25 0.125\nmap_Kd missing_texture.png\n");
    write_text(obj, "mtllib tex.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
                    "usemtl m\nf 1/1 2/2 3/3\n");
    ob_scene *s = load(obj, NULL, OB_UP_DEFAULT);
    CHECK(s != NULL, "model with a missing texture still loads: %s", last_message());
    if (s) {
        ob_material_info info = ob_query_scene_material(s, 0);
        CHECK(!info.has_texture && near(info.diffuse[1], 0.25f, 1e-6f),
              "missing texture: colour kept, no texture");
        ob_destroy_scene(s);
    }
    unlink(obj);
    unlink(mtl);
}

/* ---- sidecars, name resolution, errors ------------------------------------------------------- */

static const char quad_obj[] = "v 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nf 1 2 3 4\n";

static void test_resolution_and_sidecars(void)
{
    char obj[512], json[512], path[512];

    /* A model with MODEL.obscura.json beside it: "up": "z" turns the XY quad into XZ. */
    tmp_path(obj, sizeof obj, "quad.obj");
    write_text(obj, quad_obj);
    tmp_path(json, sizeof json, "quad.obscura.json");
    write_text(json, "{ \"_comment\": \"test\", \"up\": \"z\", \"ao_radius\": 0.25,\n"
                     "  \"cameras\": [ {\"name\": \"top\", \"eye\": [1, 5, 0.5],"
                     " \"target\": [1, 0, 0.5], \"up\": [0, 0, -1], \"fov\": 30} ],\n"
                     "  \"lights\": [ {\"type\": \"directional\", \"direction\": [0, 2, 0],"
                     " \"color\": [1, 0.5, 0.25], \"intensity\": 2} ] }\n");
    ob_scene *s = load(obj, NULL, OB_UP_DEFAULT);
    CHECK(s != NULL, "quad.obj with sidecar loads: %s", last_message());
    if (s) {
        ob_scene_stats st = ob_query_scene_stats(s);
        const float lo[3] = {0.0f, 0.0f, -1.0f}, hi[3] = {2.0f, 0.0f, 0.0f};
        check_bounds("quad z-up", &st, lo, hi, 1e-6f);
        CHECK(near(ob_query_scene_ao_radius(s), 0.25f, 1e-6f), "sidecar ao_radius");
        ob_light l = ob_query_scene_light(s, 0);
        CHECK(near(l.direction[1], 1.0f, 1e-6f) && near(l.color[1], 0.5f, 1e-6f) &&
                  near(l.intensity, 2.0f, 1e-6f),
              "sidecar light (direction normalised)");
        ob_camera c = {0};
        CHECK(ob_find_camera(s, "top", &c) == OB_OK && near(c.fov_y_deg, 30.0f, 1e-6f) &&
                  near(c.up[2], -1.0f, 1e-6f),
              "sidecar camera");
        CHECK(strcmp(ob_query_scene_name(s), "quad") == 0, "model scene named by its stem");
        check_mesh_sanity(s);
        ob_destroy_scene(s);
    }
    /* desc->up overrides the sidecar's. */
    s = load(obj, NULL, OB_UP_Y);
    if (s) {
        ob_scene_stats st = ob_query_scene_stats(s);
        const float lo[3] = {0.0f, 0.0f, 0.0f}, hi[3] = {2.0f, 1.0f, 0.0f};
        check_bounds("quad desc.up = y", &st, lo, hi, 1e-6f);
        ob_destroy_scene(s);
    }

    /* A named scene from the data directory with a model path relative to the JSON. */
    const char *old_env = getenv("OBSCURA_DATA_DIR");
    char saved[512] = "";
    if (old_env) snprintf(saved, sizeof saved, "%s", old_env);
    tmp_path(path, sizeof path, "scenes");
    mkdir(path, 0700);
    tmp_path(json, sizeof json, "scenes/flat.obscura.json");
    write_text(json, "{\"model\": \"../quad.obj\", \"cameras\": [{\"name\": \"a\","
                     " \"eye\": [1, 1, 3], \"target\": [1, 0.5, 0]}]}");
    setenv("OBSCURA_DATA_DIR", tmpdir, 1);
    s = load("flat", NULL, OB_UP_DEFAULT);
    CHECK(s != NULL, "named scene with a relative model: %s", last_message());
    if (s) {
        ob_scene_stats st = ob_query_scene_stats(s);
        /* quad.obscura.json beside the model is not used for a named scene: Y stays up. */
        const float lo[3] = {0.0f, 0.0f, 0.0f}, hi[3] = {2.0f, 1.0f, 0.0f};
        check_bounds("named flat", &st, lo, hi, 1e-6f);
        CHECK(strcmp(ob_query_scene_name(s), "flat") == 0 && ob_query_camera_count(s) == 2,
              "named scene: name and preset");
        ob_destroy_scene(s);
    }
    write_text(json, "{\"cameras\": []}");
    s = load("flat", NULL, OB_UP_DEFAULT);
    CHECK(!s && ob_get_error(NULL) == OB_ERR_SIDECAR, "named scene without model: %s",
          last_message());
    write_text(json, "{\"model\": \"missing.obj\"}");
    s = load("flat", NULL, OB_UP_DEFAULT);
    CHECK(!s && ob_get_error(NULL) == OB_ERR_IO, "named scene with a missing model: %s",
          last_message());
    if (old_env) {
        setenv("OBSCURA_DATA_DIR", saved, 1);
    } else {
        unsetenv("OBSCURA_DATA_DIR");
    }

    /* Malformed sidecars, given explicitly to a built-in. */
#define CAM_A "{\"cameras\": [{\"name\": \"a\", "
    const struct {
        const char *text;
        const char *why;
    } bad[] = {
        {"{\"cameras\": [", "bad JSON"},
        {"", "empty file"},
        {"[1, 2]", "not an object"},
        {CAM_A "\"eye\": [1, 2], \"target\": [0, 0, 0]}]}", "eye of length 2"},
        {"{\"camera\": []}", "unknown key"},
        {"{\"ao_radius\": 0}", "ao_radius 0"},
        {"{\"ao_radius\": -1}", "ao_radius < 0"},
        {"{\"ao_radius\": \"big\"}", "ao_radius string"},
        {"{\"ao_radius\": 1e999}", "ao_radius infinite"},
        {"{\"up\": \"x\"}", "unknown up"},
        {CAM_A "\"eye\": [1, 2, 3], \"target\": [1, 2, 3]}]}", "eye == target"},
        {CAM_A "\"eye\": [0, 0, 1], \"target\": [0, 0, 0], \"fov\": 179}]}", "fov 179"},
        {CAM_A "\"eye\": [0, 0, 1], \"target\": [0, 0, 0], \"fov\": 1}]}", "fov 1"},
        {"{\"cameras\": [{\"eye\": [0, 0, 1], \"target\": [0, 0, 0]}]}", "camera without name"},
        {CAM_A "\"eye\": [0, 5, 0], \"target\": [0, 0, 0]}]}", "view parallel to up"},
        {CAM_A "\"eye\": [0, 0, 1], \"target\": [0, 0, 0], \"zoom\": 2}]}", "unknown camera key"},
        {CAM_A "\"eye\": [0, 0, 1], \"target\": [0, 0, 0]},"
               " {\"name\": \"a\", \"eye\": [0, 0, 2], \"target\": [0, 0, 0]}]}",
         "duplicate camera name"},
        {"{\"cameras\": [{\"name\": \"\", \"eye\": [0, 0, 1], \"target\": [0, 0, 0]}]}",
         "empty camera name"},
        {"{\"cameras\": {\"name\": \"a\"}}", "cameras not an array"},
        {CAM_A "\"eye\": [0, 0, \"1\"], \"target\": [0, 0, 0]}]}", "string coordinate"},
        {"{\"lights\": [{\"type\": \"point\", \"direction\": [0, 1, 0]}]}", "point light"},
        {"{\"lights\": [{\"direction\": [0, 0, 0]}]}", "zero light direction"},
        {"{\"ao_radius\": 1, \"ao_radius\": 2}", "duplicate key"},
        {"{\"up\": \"y\"} trailing", "trailing garbage"},
    };
    tmp_path(json, sizeof json, "bad.obscura.json");
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
        write_text(json, bad[k].text);
        s = load("corner", json, OB_UP_DEFAULT);
        ob_error err = ob_get_error(NULL);
        CHECK(!s && err == OB_ERR_SIDECAR && strstr(last_message(), json),
              "sidecar with %s: %s %s", bad[k].why, ob_error_name(err), last_message());
        if (k < 5 || k == 10) printf("  %s -> %s\n", bad[k].why, last_message());
        ob_destroy_scene(s);
    }
#undef CAM_A
    /* A good explicit sidecar on a built-in adds its presets. */
    write_text(json, "{\"_note\": 1, \"cameras\": [{\"name\": \"low\", \"eye\": [3, 0.3, 3],"
                     " \"target\": [0, 0.5, 0]}]}");
    s = load("corner", json, OB_UP_DEFAULT);
    CHECK(s && ob_find_camera(s, "low", NULL) == OB_OK && ob_query_camera_count(s) == 3,
          "explicit sidecar on a built-in: %s", last_message());
    ob_destroy_scene(s);
    unlink(json);
    tmp_path(path, sizeof path, "no-such.obscura.json");
    s = load("corner", path, OB_UP_DEFAULT);
    CHECK(!s && ob_get_error(NULL) == OB_ERR_IO, "missing explicit sidecar: %s",
          last_message());

    /* Unknown names and broken models. */
    s = load("/nonexistent/model.obj", NULL, OB_UP_DEFAULT);
    CHECK(!s && ob_get_error(NULL) == OB_ERR_IO, "missing model: %s",
          last_message());
    s = load("no-such-scene", NULL, OB_UP_DEFAULT);
    CHECK(!s && ob_get_error(NULL) == OB_ERR_UNKNOWN_SCENE, "unknown name: %s", last_message());
    CHECK(ob_load_scene(NULL) == NULL && ob_get_error(NULL) == OB_ERR_INVALID_ARGUMENT,
          "NULL desc");
    ob_scene_desc empty = {0};
    CHECK(ob_load_scene(&empty) == NULL && ob_get_error(NULL) == OB_ERR_INVALID_ARGUMENT,
          "NULL name");

    char garbage[4096] = {0};
    uint32_t x = 12345u;
    for (size_t i = 0; i < sizeof garbage; ++i) {
        x = x * 1664525u + 1013904223u; /* deterministic noise */
        garbage[i] = (char)(x >> 24);
    }
    const char *bad_models[] = {"garbage.obj", "garbage.ply", "empty.obj"};
    for (int k = 0; k < 3; ++k) {
        tmp_path(path, sizeof path, bad_models[k]);
        write_file(path, garbage, k == 2 ? 0u : sizeof garbage);
        s = load(path, NULL, OB_UP_DEFAULT);
        CHECK(!s && ob_get_error(NULL) == OB_ERR_MODEL, "corrupt %s: %s %s", bad_models[k],
              ob_error_name(ob_get_error(NULL)), last_message());
        printf("  %s -> %s\n", bad_models[k], last_message());
        unlink(path);
    }
    /* An OBJ with only a line: no triangles. */
    tmp_path(path, sizeof path, "line.obj");
    write_text(path, "v 0 0 0\nv 1 0 0\nl 1 2\n");
    s = load(path, NULL, OB_UP_DEFAULT);
    CHECK(!s && ob_get_error(NULL) == OB_ERR_MODEL, "lines only: %s", last_message());
    unlink(path);

    tmp_path(path, sizeof path, "quad.obj");
    unlink(path);
    tmp_path(path, sizeof path, "quad.obscura.json");
    unlink(path);
    tmp_path(path, sizeof path, "scenes/flat.obscura.json");
    unlink(path);
    tmp_path(path, sizeof path, "scenes");
    rmdir(path);
}

/* Sidecar lights of every type, and the ones that must be refused. */
static void test_sidecar_lights(void)
{
    char path[512];
    tmp_path(path, sizeof path, "lights.obscura.json");
    write_text(path, "{\"lights\": ["
                     "{\"direction\": [0, 2, 0], \"intensity\": 2},"
                     "{\"type\": \"point\", \"position\": [1, 2, 3], \"range\": 5, \"color\": [1, 0.5, 0]},"
                     "{\"type\": \"spot\", \"position\": [0, 3, 0], \"direction\": [0, -1, 0], \"cone\": [10, 20]}]}");
    ob_scene *s = load("corner", path, OB_UP_DEFAULT);
    CHECK(s != NULL, "three lights: %s", last_message());
    if (s) {
        CHECK(ob_query_scene_light_count(s) == 3, "3 lights, got %d", ob_query_scene_light_count(s));
        ob_light a = ob_query_scene_light(s, 0), b = ob_query_scene_light(s, 1), c = ob_query_scene_light(s, 2);
        CHECK(a.type == OB_LIGHT_DIRECTIONAL && near(a.direction[1], 1.0f, 1e-6f) && near(a.intensity, 2.0f, 1e-6f),
              "directional");
        CHECK(b.type == OB_LIGHT_POINT && near(b.position[2], 3.0f, 1e-6f) && near(b.range, 5.0f, 1e-6f) &&
                  near(b.color[1], 0.5f, 1e-6f),
              "point");
        CHECK(c.type == OB_LIGHT_SPOT && near(c.spot_inner_deg, 10.0f, 1e-6f) && near(c.spot_outer_deg, 20.0f, 1e-6f),
              "spot");
        ob_destroy_scene(s);
    }
    const char *bad[] = {
        "{\"lights\": [{\"type\": \"point\"}]}",
        "{\"lights\": [{\"type\": \"spot\", \"position\": [0, 1, 0]}]}",
        "{\"lights\": [{\"type\": \"spot\", \"position\": [0, 1, 0], \"direction\": [0, -1, 0], \"cone\": [30, 20]}]}",
        "{\"lights\": [{\"type\": \"point\", \"position\": [0, 1, 0], \"range\": 0}]}",
        "{\"lights\": [{\"type\": \"area\", \"position\": [0, 1, 0]}]}",
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        write_text(path, bad[i]);
        s = load("corner", path, OB_UP_DEFAULT);
        CHECK(!s && ob_get_error(NULL) == OB_ERR_SIDECAR, "bad light %zu refused: %s", i, last_message());
        ob_destroy_scene(s);
    }
    unlink(path);
}

/* glTF KHR_lights_punctual through Assimp: a point light with colour and a spot light turned to
 * point down, both placed by their nodes. */
static void test_gltf_lights(void)
{
    char path[512];
    tmp_path(path, sizeof path, "lights.gltf");
    write_text(path, "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_lights_punctual\"],\"extensions\":{\"KHR_lights_punctual\":{\"lights\":[{\"type\":\"point\",\"color\":[1,0.5,0.25],\"intensity\":5,\"name\":\"lamp\"},{\"type\":\"spot\",\"intensity\":3,\"spot\":{\"innerConeAngle\":0.2,\"outerConeAngle\":0.4},\"name\":\"spotty\"}]}},\"scene\":0,\"scenes\":[{\"nodes\":[0,1,2]}],\"nodes\":[{\"mesh\":0},{\"name\":\"lamp\",\"translation\":[1,2,3],\"extensions\":{\"KHR_lights_punctual\":{\"light\":0}}},{\"name\":\"spotty\",\"translation\":[0,4,0],\"rotation\":[-0.7071068,0,0,0.7071068],\"extensions\":{\"KHR_lights_punctual\":{\"light\":1}}}],\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0},\"indices\":1}]}],\"buffers\":[{\"uri\":\"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAAAAAAIA/AAABAAIA\",\"byteLength\":42}],\"bufferViews\":[{\"buffer\":0,\"byteOffset\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":6}],\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\",\"min\":[0,0,0],\"max\":[1,0,1]},{\"bufferView\":1,\"componentType\":5123,\"count\":3,\"type\":\"SCALAR\"}]}");
    ob_scene *s = load(path, NULL, OB_UP_DEFAULT);
    CHECK(s != NULL, "lights.gltf loads: %s", last_message());
    if (s) {
        CHECK(ob_query_scene_light_count(s) == 2, "2 glTF lights, got %d", ob_query_scene_light_count(s));
        ob_light a = ob_query_scene_light(s, 0), b = ob_query_scene_light(s, 1);
        CHECK(a.type == OB_LIGHT_POINT && near(a.position[0], 1.0f, 1e-5f) && near(a.position[1], 2.0f, 1e-5f) &&
                  near(a.position[2], 3.0f, 1e-5f),
              "point light at its node (%g %g %g)", (double)a.position[0], (double)a.position[1], (double)a.position[2]);
        CHECK(near(a.intensity, 5.0f, 1e-5f) && near(a.color[1], 0.5f, 1e-5f) && near(a.color[2], 0.25f, 1e-5f),
              "point colour %g %g %g x %g", (double)a.color[0], (double)a.color[1], (double)a.color[2], (double)a.intensity);
        CHECK(b.type == OB_LIGHT_SPOT && near(b.position[1], 4.0f, 1e-5f) && near(b.direction[1], -1.0f, 1e-4f),
              "spot at (0,4,0) pointing down (dir %g %g %g)", (double)b.direction[0], (double)b.direction[1],
              (double)b.direction[2]);
        /* glTF's cone angles are half-angles: 0.2 and 0.4 rad. */
        CHECK(near(b.spot_inner_deg, 11.459f, 1e-2f) && near(b.spot_outer_deg, 22.918f, 1e-2f), "spot cone %g %g",
              (double)b.spot_inner_deg, (double)b.spot_outer_deg);
        ob_destroy_scene(s);
    }
    unlink(path);
}

/* The sidecar's "ground": a square under the model, at its lowest point by default, 4 x its
 * larger horizontal extent, +Y normals and counter-clockwise from above; the bounds grow to hold
 * it, the default camera and the radius stay the model's. */
static void test_sidecar_ground(void)
{
    char obj[512], json[512];
    tmp_path(obj, sizeof obj, "tri.obj");
    /* Bounds x 0..2, y 1..2, z 0..1: floating a unit over y = 0. */
    write_text(obj, "v 0 1 0\nv 2 1 0\nv 0 2 1\nf 1 2 3\n");
    tmp_path(json, sizeof json, "ground.obscura.json");

    ob_scene *bare = load(obj, NULL, OB_UP_DEFAULT);
    CHECK(bare != NULL, "tri.obj loads: %s", last_message());
    if (!bare) return;
    ob_camera bare_cam = ob_query_camera(bare, 0);

    write_text(json, "{\"ground\": {\"_comment\": \"defaults\"}}");
    ob_scene *s = load(obj, json, OB_UP_DEFAULT);
    CHECK(s != NULL, "ground {}: %s", last_message());
    if (s) {
        CHECK(s->mesh_count == bare->mesh_count + 1, "ground: one mesh more (%d, %d)", s->mesh_count,
              bare->mesh_count);
        const ob_mesh *g = &s->meshes[s->mesh_count - 1];
        CHECK(g->vertex_count == 4u && g->index_count == 6u, "ground: a quad, %u vertices %u indices",
              g->vertex_count, g->index_count);
        float lo[3] = {1e9f, 1e9f, 1e9f}, hi[3] = {-1e9f, -1e9f, -1e9f};
        for (uint32_t v = 0; v < g->vertex_count; ++v) {
            for (int i = 0; i < 3; ++i) {
                lo[i] = fminf(lo[i], g->positions[3u * v + (uint32_t)i]);
                hi[i] = fmaxf(hi[i], g->positions[3u * v + (uint32_t)i]);
            }
            CHECK(near(g->normals[3u * v + 1u], 1.0f, 0.0f), "ground normal +Y");
        }
        /* 8 = 4 x 2 (x extent), centred on (1, 0.5), at y = 1. */
        CHECK(near(lo[0], -3.0f, 1e-6f) && near(hi[0], 5.0f, 1e-6f) && near(lo[2], -3.5f, 1e-6f) &&
                  near(hi[2], 4.5f, 1e-6f) && near(lo[1], 1.0f, 0.0f) && near(hi[1], 1.0f, 0.0f),
              "ground square x [%g, %g] y [%g, %g] z [%g, %g]", (double)lo[0], (double)hi[0],
              (double)lo[1], (double)hi[1], (double)lo[2], (double)hi[2]);
        ob_scene_stats st = ob_query_scene_stats(s);
        const float blo[3] = {-3.0f, 1.0f, -3.5f}, bhi[3] = {5.0f, 2.0f, 4.5f};
        check_bounds("ground bounds", &st, blo, bhi, 1e-6f);
        ob_material_info m = ob_query_scene_material(s, g->material);
        CHECK(strcmp(m.name, "ground") == 0 && near(m.diffuse[0], 0.8f, 1e-6f), "ground material %s %g",
              m.name, (double)m.diffuse[0]);
        ob_camera cam = ob_query_camera(s, 0);
        CHECK(near(cam.eye[0], bare_cam.eye[0], 0.0f) && near(cam.eye[2], bare_cam.eye[2], 0.0f),
              "the default camera still frames the model alone");
        CHECK(ob_query_scene_ao_radius(s) == ob_query_scene_ao_radius(bare), "radius from the model");
        check_mesh_sanity(s);
        ob_destroy_scene(s);
    }

    write_text(json, "{\"ground\": {\"y\": -0.5, \"size\": 3, \"color\": [0.2, 0.3, 0.4]},"
                     " \"cameras\": [{\"name\": \"default\", \"eye\": [0, 1, 9], \"target\": [0, 1, 0]}]}");
    s = load(obj, json, OB_UP_DEFAULT);
    CHECK(s != NULL, "ground with y, size, color: %s", last_message());
    if (s) {
        ob_scene_stats st = ob_query_scene_stats(s);
        const float blo[3] = {-0.5f, -0.5f, -1.0f}, bhi[3] = {2.5f, 2.0f, 2.0f};
        check_bounds("ground y -0.5 size 3", &st, blo, bhi, 1e-6f);
        ob_material_info m = ob_query_scene_material(s, s->meshes[s->mesh_count - 1].material);
        CHECK(near(m.diffuse[0], 0.2f, 1e-6f) && near(m.diffuse[1], 0.3f, 1e-6f) && near(m.diffuse[2], 0.4f, 1e-6f),
              "ground colour");
        CHECK(near(ob_query_camera(s, 0).eye[2], 9.0f, 0.0f), "the sidecar's \"default\" camera kept");
        check_mesh_sanity(s);
        ob_destroy_scene(s);
    }

    /* On a built-in too, and refused when malformed, with nothing applied. */
    write_text(json, "{\"ground\": {\"y\": -1}}");
    s = load("corner", json, OB_UP_DEFAULT);
    CHECK(s && ob_query_scene_stats(s).bounds_min[1] == -1.0f, "ground under a built-in: %s", last_message());
    ob_destroy_scene(s);
    const char *bad[] = {
        "{\"ground\": true}",
        "{\"ground\": {\"size\": 0}}",
        "{\"ground\": {\"size\": -2}}",
        "{\"ground\": {\"height\": 1}}",
        "{\"ground\": {\"color\": [2, 0, 0]}}",
        "{\"ground\": {\"color\": [0.5, 0.5]}}",
        "{\"ground\": {\"y\": 1, \"y\": 2}}",
        "{\"ground\": {\"y\": \"low\"}}",
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
        write_text(json, bad[k]);
        s = load(obj, json, OB_UP_DEFAULT);
        CHECK(!s && ob_get_error(NULL) == OB_ERR_SIDECAR, "bad ground %s: %s", bad[k], last_message());
        if (k == 3) printf("  %s -> %s\n", bad[k], last_message());
        ob_destroy_scene(s);
    }

    /* "walls": a wall at x = 3 (right of the model's centre x = 1: it faces -x) and one at z = -1
     * (behind z = 0.5: it faces +z), as wide as the 8-unit ground, 1.5 x the model's height (1)
     * by default or as given; each faces the model and its triangles turn counter-clockwise seen
     * from that side (the rasteriser's front faces). */
    write_text(json, "{\"ground\": {\"walls\": [{\"x\": 3}, {\"z\": -1, \"height\": 4, \"_c\": \"\"}]}}");
    s = load(obj, json, OB_UP_DEFAULT);
    CHECK(s != NULL, "ground with walls: %s", last_message());
    if (s) {
        CHECK(s->mesh_count == bare->mesh_count + 3, "a ground and two walls: %d meshes, %d without", s->mesh_count,
              bare->mesh_count);
        const float facing[2][3] = {{-1.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 1.0f}}, top[2] = {2.5f, 5.0f};
        for (int w = 0; w < 2 && s->mesh_count == bare->mesh_count + 3; ++w) {
            const ob_mesh *m = &s->meshes[s->mesh_count - 2 + w];
            const float *p = m->positions;
            float e1[3], e2[3];
            for (int i = 0; i < 3; ++i) {
                e1[i] = p[3u * m->indices[1] + (uint32_t)i] - p[3u * m->indices[0] + (uint32_t)i];
                e2[i] = p[3u * m->indices[2] + (uint32_t)i] - p[3u * m->indices[0] + (uint32_t)i];
            }
            const float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
            float hi = -1e9f, along_lo = 1e9f, along_hi = -1e9f;
            for (uint32_t v = 0; v < 4u; ++v) {
                CHECK(near(m->normals[3u * v], facing[w][0], 0.0f) && near(m->normals[3u * v + 2u], facing[w][2], 0.0f),
                      "wall %d: normal toward the model", w);
                hi = fmaxf(hi, p[3u * v + 1u]);
                along_lo = fminf(along_lo, p[3u * v + (w == 0 ? 2u : 0u)]);
                along_hi = fmaxf(along_hi, p[3u * v + (w == 0 ? 2u : 0u)]);
            }
            CHECK(n[0] * facing[w][0] + n[2] * facing[w][2] > 0.0f, "wall %d: counter-clockwise from the model's side", w);
            CHECK(near(hi, top[w], 1e-6f), "wall %d: top at %g, expected %g", w, (double)hi, (double)top[w]);
            CHECK(near(along_hi - along_lo, 8.0f, 1e-6f), "wall %d: %g wide, the ground's 8", w,
                  (double)(along_hi - along_lo));
        }
        CHECK(ob_query_scene_stats(s).bounds_max[1] == 5.0f, "the bounds hold the walls");
        /* The default camera frames the model from +x, +z: the wall at x = 3 stood between it and
         * the model, so it looks from -x now; the wall at z = -1 is behind the model from +z. */
        const ob_camera *c = &s->cameras[0];
        CHECK(!strcmp(c->name, "default") && c->eye[0] < c->target[0] && c->eye[2] > c->target[2],
              "the default camera looks from the walls' open side: eye - target (%g, %g)",
              (double)(c->eye[0] - c->target[0]), (double)(c->eye[2] - c->target[2]));
        check_mesh_sanity(s);
        ob_destroy_scene(s);
    }
    /* Walls on both sides of x: no open side there, the camera stays on +x. */
    write_text(json, "{\"ground\": {\"walls\": [{\"x\": 3}, {\"x\": -1}]}}");
    s = load(obj, json, OB_UP_DEFAULT);
    CHECK(s != NULL, "ground with two x walls: %s", last_message());
    if (s) {
        const ob_camera *c = &s->cameras[0];
        CHECK(c->eye[0] > c->target[0] && c->eye[2] > c->target[2], "walls on both sides of x: the default camera "
              "stays (eye - target %g, %g)", (double)(c->eye[0] - c->target[0]), (double)(c->eye[2] - c->target[2]));
        ob_destroy_scene(s);
    }
    const char *bad_walls[] = {
        "{\"ground\": {\"walls\": {\"x\": 1}}}",
        "{\"ground\": {\"walls\": [{\"x\": 1, \"z\": 1}]}}",
        "{\"ground\": {\"walls\": [{\"height\": 1}]}}",
        "{\"ground\": {\"walls\": [{\"x\": 1, \"height\": 0}]}}",
        "{\"ground\": {\"walls\": [{\"y\": 1}]}}",
        "{\"ground\": {\"walls\": [{\"x\": 1}, {\"x\": 2}, {\"x\": 3}, {\"z\": 1}, {\"z\": 2}]}}",
    };
    const char *why[] = {"expected an array", "not both", "missing \"x\" or \"z\"", "must be > 0", "unknown key",
                         "at most 4"};
    for (size_t k = 0; k < sizeof bad_walls / sizeof bad_walls[0]; ++k) {
        write_text(json, bad_walls[k]);
        s = load(obj, json, OB_UP_DEFAULT);
        CHECK(!s && ob_get_error(NULL) == OB_ERR_SIDECAR && strstr(last_message(), why[k]) &&
                  strstr(last_message(), "ground.walls"),
              "bad walls %s: %s (want '%s')", bad_walls[k], last_message(), why[k]);
        ob_destroy_scene(s);
    }
    ob_destroy_scene(bare);
    unlink(json);
    unlink(obj);
}

/* The named scenes that scripts/install-deps.sh makes or finds (skipped when absent): each loads
 * with its sidecar's radius and cameras, and the scanned object and the engine stand on a ground. */
static void test_new_named_scenes(void)
{
    static const struct {
        const char *name, *model;
        float radius;
        const char *cameras[3];
        bool ground;
    } scenes[] = {
        {"oa_shine", "data/oa_shine.pk3", 16.0f, {"spawn1", "spawn7", "intermission"}, false},
        {"armadillo", "data/armadillo.off", 10.0f, {"front", "feet", "back"}, true},
        {"engine", "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", 20.0f,
         {"overview", "fins", "contact"}, true},
        {"czest1dm", "data/czest1dm.pk3", 16.0f, {"detail", "across", "upper"}, false},
        /* The demo's bunny: the last mesh is its second wall, in the ground's material, from the floor up. */
        {"bunny-corner", "/usr/share/glmark2/models/bunny.obj", 0.3f, {"front", "side", "default"}, true},
    };
    for (size_t k = 0; k < sizeof scenes / sizeof scenes[0]; ++k) {
        char model[4096] = "";
        if (scenes[k].model[0] == '/') snprintf(model, sizeof model, "%s", scenes[k].model);
        else snprintf(model, sizeof model, "%s/%s", ob_data_dir(), scenes[k].model);
        if (!file_exists(model)) {
            printf("skip: %s absent (scripts/install-deps.sh)\n", model);
            continue;
        }
        ob_scene *s = load(scenes[k].name, NULL, OB_UP_DEFAULT);
        CHECK(s != NULL, "%s loads: %s", scenes[k].name, last_message());
        if (!s) continue;
        print_stats(scenes[k].name, s);
        ob_scene_stats st = ob_query_scene_stats(s);
        CHECK(st.triangles > 1000u && bounds_sane(&st), "%s: %u triangles, sane bounds", scenes[k].name,
              st.triangles);
        CHECK(ob_query_scene_ao_radius(s) == scenes[k].radius, "%s: radius %g", scenes[k].name,
              (double)ob_query_scene_ao_radius(s));
        for (int c = 0; c < 3; ++c) {
            CHECK(ob_find_camera(s, scenes[k].cameras[c], NULL) == OB_OK, "%s: camera %s", scenes[k].name,
                  scenes[k].cameras[c]);
        }
        const ob_mesh *last = &s->meshes[s->mesh_count - 1];
        bool ground = strcmp(s->materials[last->material].name, "ground") == 0;
        CHECK(ground == scenes[k].ground, "%s: ground %s", scenes[k].name, ground ? "present" : "absent");
        if (ground) {
            /* It touches the model: its height is the lowest of the model's other vertices. */
            float y = last->positions[1], lowest = 1e30f;
            for (int m = 0; m + 1 < s->mesh_count; ++m) {
                for (uint32_t v = 0; v < s->meshes[m].vertex_count; ++v) {
                    lowest = fminf(lowest, s->meshes[m].positions[3u * v + 1u]);
                }
            }
            CHECK(y == lowest, "%s: ground at %g, model's lowest point %g", scenes[k].name, (double)y,
                  (double)lowest);
        }
        ob_destroy_scene(s);
    }
}

/* OpenArena's oa_dm1 through the named scene: a Quake 3 map in a .pk3, which Assimp 5.2.5's
 * Q3BSP importer hands over with unwritten indices and clockwise triangles (import.c repairs
 * both). The .pk3 is made by scripts/install-deps.sh, so it may be absent. */
static void test_oa_dm1(void)
{
    char pk3[4096] = "";
    snprintf(pk3, sizeof pk3, "%s/data/oa_dm1.pk3", ob_data_dir());
    if (!file_exists(pk3)) {
        printf("skip: %s not made (scripts/install-deps.sh repacks it)\n", pk3);
        return;
    }
    ob_scene *s = load("oa_dm1", NULL, OB_UP_DEFAULT);
    CHECK(s != NULL, "oa_dm1 loads: %s", last_message());
    if (!s) return;
    print_stats("oa_dm1", s);
    ob_scene_stats st = ob_query_scene_stats(s);
    CHECK(st.triangles > 1000u, "oa_dm1: %u triangles > 1000", st.triangles);
    CHECK(bounds_sane(&st), "oa_dm1: finite, non-degenerate bounds");
    /* Indices in range, and the winding: counter-clockwise about the vertex normals for a
     * majority of triangles. Not all: the normals are smoothed within the crease angle, and a
     * sliver whose corners lie on a curve may tilt past its own face. Still-clockwise triangles
     * would put nearly all of them on the wrong side. */
    uint32_t bad_index = 0, agree = 0, disagree = 0;
    for (int m = 0; m < s->mesh_count; ++m) {
        const ob_mesh *mesh = &s->meshes[m];
        for (uint32_t t = 0; t + 2u < mesh->index_count; t += 3u) {
            const uint32_t *ix = &mesh->indices[t];
            if (ix[0] >= mesh->vertex_count || ix[1] >= mesh->vertex_count ||
                ix[2] >= mesh->vertex_count) {
                ++bad_index;
                continue;
            }
            const float *a = &mesh->positions[3u * ix[0]];
            const float *b = &mesh->positions[3u * ix[1]];
            const float *c = &mesh->positions[3u * ix[2]];
            float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
            float e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            float f[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                          e1[0] * e2[1] - e1[1] * e2[0]};
            float area2 = f[0] * f[0] + f[1] * f[1] + f[2] * f[2];
            if (!(area2 > 1e-12f)) continue; /* zero-area slivers have no orientation */
            float d = 0.0f;
            for (int i = 0; i < 3; ++i) {
                d += f[i] * (mesh->normals[3u * ix[0] + (uint32_t)i] +
                             mesh->normals[3u * ix[1] + (uint32_t)i] +
                             mesh->normals[3u * ix[2] + (uint32_t)i]);
            }
            if (d > 0.0f) ++agree;
            else ++disagree;
        }
    }
    CHECK(bad_index == 0, "oa_dm1: %u indices out of range", bad_index);
    CHECK(agree > 0u && agree > 9u * disagree,
          "oa_dm1: %u triangles agree with their vertex normals, %u do not", agree, disagree);
    /* Quake is Z-up: after the sidecar's "up": "z" the map must be wider than tall. */
    float ex = st.bounds_max[0] - st.bounds_min[0], ey = st.bounds_max[1] - st.bounds_min[1];
    float ez = st.bounds_max[2] - st.bounds_min[2];
    CHECK(ey < ex && ey < ez, "oa_dm1: Y is up after import (extent %g %g %g)", (double)ex,
          (double)ey, (double)ez);
    CHECK(ob_query_scene_ao_radius(s) == 16.0f, "oa_dm1: the sidecar's ao_radius 16, got %g",
          (double)ob_query_scene_ao_radius(s));
    CHECK(ob_query_camera_count(s) >= 4, "oa_dm1: the sidecar's cameras, got %d",
          ob_query_camera_count(s));
    ob_destroy_scene(s);
}

/* ob_tessellate_scene: 4^levels triangles, every new vertex on its original triangle's plane
 * (so the surfaces are the same), unit normals, the scene's cameras, bounds and radius kept. */
static void test_tessellate(void)
{
    ob_scene *s = ob_load_scene(&(ob_scene_desc){.name = "cornell"});
    CHECK(s != NULL, "cornell loads");
    if (!s) return;
    ob_scene_stats base = ob_query_scene_stats(s);
    for (int levels = 0; levels <= 2; ++levels) {
        ob_scene *t = ob_tessellate_scene(s, levels);
        CHECK(t != NULL, "tessellate %d", levels);
        if (!t) continue;
        ob_scene_stats st = ob_query_scene_stats(t);
        CHECK(st.triangles == base.triangles << (2 * levels), "level %d: %u triangles from %u", levels, st.triangles,
              base.triangles);
        for (int k = 0; k < 3; ++k) {
            CHECK_NEAR(st.bounds_min[k], base.bounds_min[k], 0.0, "bounds min");
            CHECK_NEAR(st.bounds_max[k], base.bounds_max[k], 0.0, "bounds max");
        }
        CHECK(ob_query_camera_count(t) == ob_query_camera_count(s), "cameras kept");
        CHECK(ob_query_scene_ao_radius(t) == ob_query_scene_ao_radius(s), "radius kept");
        /* Every vertex of every sub-triangle lies on some original triangle's plane within 1e-5,
         * checked per mesh (a mesh keeps its material and its own triangles). */
        double worst_plane = 0.0, worst_normal = 0.0;
        for (int m = 0; m < t->mesh_count; ++m) {
            const ob_mesh *a = &s->meshes[m], *b = &t->meshes[m];
            for (uint32_t v = 0; v < b->vertex_count; ++v) {
                const float *p = b->positions + 3u * v, *n = b->normals + 3u * v;
                worst_normal = fmax(worst_normal, fabs(sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]) - 1.0));
                double best = INFINITY;
                for (uint32_t i = 0; i + 2 < a->index_count; i += 3) {
                    const float *p0 = a->positions + 3u * a->indices[i], *p1 = a->positions + 3u * a->indices[i + 1],
                                *p2 = a->positions + 3u * a->indices[i + 2];
                    double e1[3], e2[3], c[3], d[3];
                    for (int k = 0; k < 3; ++k) {
                        e1[k] = (double)p1[k] - p0[k];
                        e2[k] = (double)p2[k] - p0[k];
                        d[k] = (double)p[k] - p0[k];
                    }
                    c[0] = e1[1] * e2[2] - e1[2] * e2[1];
                    c[1] = e1[2] * e2[0] - e1[0] * e2[2];
                    c[2] = e1[0] * e2[1] - e1[1] * e2[0];
                    double len = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
                    if (len > 0.0) best = fmin(best, fabs(c[0] * d[0] + c[1] * d[1] + c[2] * d[2]) / len);
                }
                worst_plane = fmax(worst_plane, best);
            }
        }
        CHECK(worst_plane < 1e-5, "level %d: a vertex %.3g off the original surface", levels, worst_plane);
        CHECK(worst_normal < 1e-4, "level %d: normal length off by %.3g", levels, worst_normal);
        ob_destroy_scene(t);
    }
    CHECK(ob_tessellate_scene(s, 5) == NULL && ob_get_error(NULL) == OB_ERR_OUT_OF_RANGE, "levels 5 refused");
    CHECK(ob_tessellate_scene(NULL, 1) == NULL && ob_get_error(NULL) == OB_ERR_INVALID_ARGUMENT, "NULL refused");
    ob_destroy_scene(s);
}

/* Camera paths (issue 17): a sidecar path through its keys, C1 between them, the fov linear,
 * unknown names, orbits, and the validation of "paths". */
static void test_paths(void)
{
    char json[512];
    tmp_path(json, sizeof json, "path.obscura.json");
    write_text(json, "{\"paths\": [{\"name\": \"walk\", \"keys\": ["
                     "{\"time\": 0, \"eye\": [0, 1, 4], \"target\": [0, 0.5, 0], \"fov\": 40},"
                     "{\"time\": 1, \"eye\": [2, 1, 3], \"target\": [0.5, 0.5, 0]},"
                     "{\"time\": 3, \"eye\": [4, 2, 0], \"target\": [1, 0.5, 0], \"fov\": 80}]}]}");
    ob_scene *s = load("corner", json, OB_UP_DEFAULT);
    CHECK(s && ob_query_path_count(s) == 1 && !strcmp(ob_query_path_name(s, 0), "walk") &&
              !strcmp(ob_query_path_name(s, 1), ""),
          "a sidecar path: %s", last_message());
    if (s) {
        ob_camera c0, c1, c3, a, b;
        /* u = 1/3 is time 1 of the span 0..3: the middle key, exactly. */
        CHECK(ob_camera_on_path(s, "walk", 0.0f, &c0) == OB_OK && ob_camera_on_path(s, "walk", 1.0f / 3.0f, &c1) == OB_OK &&
                  ob_camera_on_path(s, "walk", 1.0f, &c3) == OB_OK,
              "path cameras");
        CHECK(near(c0.eye[2], 4.0f, 1e-5f) && near(c1.eye[0], 2.0f, 1e-5f) && near(c1.eye[2], 3.0f, 1e-5f) &&
                  near(c3.eye[0], 4.0f, 1e-5f) && near(c3.target[0], 1.0f, 1e-5f),
              "the path passes through its keys (%g %g %g)", (double)c1.eye[0], (double)c1.eye[1], (double)c1.eye[2]);
        CHECK(near(c0.fov_y_deg, 40.0f, 1e-4f) && near(c1.fov_y_deg, 60.0f, 1e-4f) && near(c3.fov_y_deg, 80.0f, 1e-4f),
              "fov: the keys' (60 when not given), linear between");
        /* C1 at the middle key: the same velocity on both sides (per unit time: the gaps differ). */
        const float e = 1e-3f;
        ob_camera_on_path(s, "walk", 1.0f / 3.0f - e, &a);
        ob_camera_on_path(s, "walk", 1.0f / 3.0f + e, &b);
        float left = (c1.eye[0] - a.eye[0]) / e, right = (b.eye[0] - c1.eye[0]) / e;
        CHECK(fabsf(left - right) < 0.02f * fabsf(left), "no kink at a key (%g vs %g)", (double)left, (double)right);
        CHECK(ob_camera_on_path(s, "run", 0.5f, &a) == OB_ERR_INVALID_ARGUMENT && strstr(last_message(), "walk"),
              "an unknown path names the scene's: %s", last_message());
    }
    ob_destroy_scene(s);
    const ob_camera cam = {.eye = {3.0f, 2.0f, 0.0f}, .target = {1.0f, 0.5f, 0.0f}, .fov_y_deg = 50.0f};
    ob_camera q = ob_camera_orbit(&cam, 90.0f), full = ob_camera_orbit(&cam, 360.0f);
    CHECK(near(q.eye[0], 1.0f, 1e-5f) && near(q.eye[1], 2.0f, 1e-6f) && near(fabsf(q.eye[2]), 2.0f, 1e-5f) &&
              near(q.target[0], 1.0f, 0.0f) && near(full.eye[0], 3.0f, 1e-5f) && near(full.eye[2], 0.0f, 1e-5f),
          "an orbit turns the eye about the vertical through the target (%g %g %g)", (double)q.eye[0], (double)q.eye[1],
          (double)q.eye[2]);
#define KEY(t) "{\"time\": " #t ", \"eye\": [0, 1, 4], \"target\": [0, 0, 0]}"
    static const struct { const char *text, *why; } bad[] = {
        {"{\"paths\": [{\"name\": \"p\", \"keys\": [" KEY(0) "]}]}", "one key"},
        {"{\"paths\": [{\"name\": \"p\", \"keys\": [" KEY(1) "," KEY(1) "]}]}", "times not increasing"},
        {"{\"paths\": [{\"keys\": [" KEY(0) "," KEY(1) "]}]}", "path without name"},
        {"{\"paths\": [{\"name\": \"p\"}]}", "path without keys"},
        {"{\"paths\": [{\"name\": \"p\", \"keys\": [" KEY(0) ", {\"time\": 1, \"eye\": [0, 1, 4]}]}]}",
         "key without target"},
        {"{\"paths\": [{\"name\": \"p\", \"keys\": [" KEY(0) ", {\"time\": 1, \"eye\": [0, 3, 0], "
         "\"target\": [0, 0, 0]}]}]}",
         "key looking straight down"},
        {"{\"paths\": [{\"name\": \"p\", \"keys\": [" KEY(0) "," KEY(1) "], \"loop\": true}]}", "unknown path key"},
        {"{\"paths\": [{\"name\": \"p\", \"keys\": [" KEY(0) "," KEY(1) "]}, {\"name\": \"p\", \"keys\": [" KEY(0)
         "," KEY(1) "]}]}",
         "duplicate path name"},
    };
#undef KEY
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
        write_text(json, bad[k].text);
        s = load("corner", json, OB_UP_DEFAULT);
        ob_error err = ob_get_error(NULL);
        CHECK(!s && err == OB_ERR_SIDECAR && strstr(last_message(), json) && !strchr(last_message(), '\n'),
              "sidecar path with %s: %s %s", bad[k].why, ob_error_name(err), last_message());
        if (k < 2) printf("  %s -> %s\n", bad[k].why, last_message());
        ob_destroy_scene(s);
    }
    unlink(json);
}

/* The connected parts the second depth layer tells solids apart by (scene/parts.c): the built-in
 * slab's floor and two boxes, each box face its own four vertices (the corners shared only by
 * position), are three parts; the grille's floor, sheet and closed plate three more; corners that
 * differ in the last bits (x0 + i c + c against x0 + (i + 1) c) are one; labels count from `first`
 * and fold into 1..OB_PART_LABELS. */
static void test_parts(void)
{
    const char *names[] = {"slab", "grille"};
    for (int k = 0; k < 2; ++k) {
        ob_scene *s = load(names[k], NULL, OB_UP_DEFAULT);
        CHECK(s != NULL && s->mesh_count == 1, "%s loads as one mesh", names[k]);
        if (!s || s->mesh_count != 1) continue;
        const ob_mesh *m = &s->meshes[0];
        float *labels = malloc((size_t)m->vertex_count * sizeof(float));
        int64_t parts = labels ? ob_mesh_part_labels(m, 0u, labels, NULL) : -1;
        CHECK(parts == 3, "%s: %lld parts (floor and two solids or sheets), expected 3", names[k], (long long)parts);
        /* Every triangle's corners share a label, and the floor (y = 0) has its own. */
        int split = 0, floor_label = -1, floor_mixed = 0;
        for (uint32_t t = 0; labels && t + 2u < m->index_count; t += 3u) {
            float a = labels[m->indices[t]], b = labels[m->indices[t + 1u]], c = labels[m->indices[t + 2u]];
            split += a != b || a != c;
            bool on_floor = m->positions[3u * m->indices[t] + 1u] == 0.0f && m->positions[3u * m->indices[t + 1u] + 1u] == 0.0f;
            if (on_floor && floor_label < 0) floor_label = (int)a;
            floor_mixed += on_floor && (int)a != floor_label;
        }
        CHECK(split == 0 && floor_mixed == 0, "%s: %d triangles across parts, %d floor triangles off the floor's part",
              names[k], split, floor_mixed);
        int64_t again = labels ? ob_mesh_part_labels(m, OB_PART_LABELS - 1u, labels, NULL) : -1;
        float lo = 1e9f, hi = 0.0f;
        for (uint32_t v = 0; labels && v < m->vertex_count; ++v) {
            float l = labels[v] >= (float)OB_PART_SHEET ? labels[v] - (float)OB_PART_SHEET : labels[v]; /* a sheet's flag off */
            lo = l < lo ? l : lo;
            hi = l > hi ? l : hi;
        }
        /* From first = 2046 the three parts are 2047, then 1 and 2 (folded). */
        CHECK(again == 3 && lo == 1.0f && hi == (float)OB_PART_LABELS, "%s: labels from 2046 fold into %g..%g", names[k],
              (double)lo, (double)hi);
        free(labels);
        ob_destroy_scene(s);
    }
}

/* A 2 x 2 square frame with a 1 x 1 hole at height y, one part in a mesh of its own (8 corners,
 * 8 triangles): a flat part whose open edges form two loops, a sheet candidate. `bend` lifts one
 * outer corner off the plane. */
static void add_frame_scaled(ob_scene *s, float y, float bend, float scale)
{
    ob_mesh *m = ob_scene_add_mesh(s, 8, 24, false);
    if (!m) return;
    static const float xz[8][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {-0.5f, -0.5f}, {0.5f, -0.5f}, {0.5f, 0.5f}, {-0.5f, 0.5f}};
    for (int v = 0; v < 8; ++v) {
        m->positions[3 * v] = scale * xz[v][0], m->positions[3 * v + 1] = y + (v == 0 ? bend : 0.0f),
        m->positions[3 * v + 2] = scale * xz[v][1];
        m->normals[3 * v] = 0.0f, m->normals[3 * v + 1] = 1.0f, m->normals[3 * v + 2] = 0.0f;
    }
    for (uint32_t k = 0; k < 4; ++k) { /* each side of the frame: outer k, k+1 and inner k, k+1 */
        uint32_t a = k, b = (k + 1u) % 4u, c = 4u + (k + 1u) % 4u, d = 4u + k, *ix = &m->indices[6u * k];
        ix[0] = a, ix[1] = b, ix[2] = c, ix[3] = a, ix[4] = c, ix[5] = d;
    }
}

static void add_frame(ob_scene *s, float y, float bend)
{
    add_frame_scaled(s, y, bend, 1.0f);
}

/* A 0.5 m box standing on y = 0 at the origin, in a mesh of its own: its bottom corners lie on
 * the frame's plane, in its hole. */
static void add_box(ob_scene *s)
{
    ob_mesh *m = ob_scene_add_mesh(s, 8, 36, false);
    if (!m) return;
    for (int v = 0; v < 8; ++v) {
        m->positions[3 * v] = (v & 1) ? 0.25f : -0.25f;
        m->positions[3 * v + 1] = (v & 2) ? 0.5f : 0.0f;
        m->positions[3 * v + 2] = (v & 4) ? 0.25f : -0.25f;
        m->normals[3 * v + 1] = 1.0f;
    }
    static const uint32_t quads[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    for (uint32_t q = 0; q < 6u; ++q) {
        uint32_t *ix = &m->indices[6u * q];
        ix[0] = quads[q][0], ix[1] = quads[q][1], ix[2] = quads[q][2], ix[3] = quads[q][0], ix[4] = quads[q][2],
        ix[5] = quads[q][3];
    }
}

/* Sheets found and settled over a scene: the number of sheets, or -1. */
static int count_sheets(ob_scene *s)
{
    float *labels[8] = {0};
    ob_holes holes[8] = {{0}};
    int sheets = -1;
    bool ok = s->mesh_count <= 8;
    for (int m = 0; ok && m < s->mesh_count; ++m) {
        labels[m] = malloc((size_t)s->meshes[m].vertex_count * sizeof(float));
        ok = labels[m] && ob_mesh_part_labels(&s->meshes[m], 0u, labels[m], &holes[m]) >= 0;
    }
    if (ok) sheets = ob_scene_settle_sheets(s, labels, holes);
    /* What is left marked is the sheets, each vertex of them. */
    int marked = 0;
    for (int m = 0; ok && m < s->mesh_count; ++m)
        for (uint32_t v = 0; v < s->meshes[m].vertex_count; ++v) marked += labels[m][v] >= (float)OB_PART_SHEET;
    CHECK(!ok || (sheets == 0) == (marked == 0), "%s: %d sheets, %d vertices marked", s->name, sheets, marked);
    for (int m = 0; m < 8; ++m) free(labels[m]), free(holes[m].items);
    return sheets;
}

/* Which parts are sheets (scene/parts.c, scene/sheets.c): a flat part with holes that nothing
 * stands in. The grille's drilled sheet is one; its closed plate and its floor are not; the vent's
 * grille is one, though the wall touches its outline. A frame is one alone, over a floor far below
 * it and flush in a wall; bent off its plane, or with a box standing in its hole (a Quake map's
 * floor around a pillar), it is not; nor is a plain quad (one loop). */
static void test_sheets(void)
{
    ob_scene *g = load("grille", NULL, OB_UP_DEFAULT);
    CHECK(g != NULL, "grille loads");
    if (g) {
        const ob_mesh *m = &g->meshes[0];
        float *labels = malloc((size_t)m->vertex_count * sizeof(float));
        ob_holes holes = {0};
        int sheets = labels && ob_mesh_part_labels(m, 0u, labels, &holes) >= 0 ? ob_scene_settle_sheets(g, &labels, &holes) : -1;
        free(holes.items);
        int wrong = 0, on_sheet = 0;
        for (uint32_t v = 0; labels && v < m->vertex_count; ++v) {
            const float *p = &m->positions[3u * v];
            bool sheet_vertex = fabsf(p[1] - 0.45f) < 1e-4f && p[0] < -0.5f; /* build_grille's sheet, x in [-1.8, -0.6] */
            on_sheet += sheet_vertex;
            wrong += sheet_vertex != (labels[v] >= (float)OB_PART_SHEET);
        }
        CHECK(sheets == 1 && on_sheet > 0 && wrong == 0, "grille: %d sheets (1), %d of %d vertices wrongly marked",
              sheets, wrong, (int)m->vertex_count);
        free(labels);
        ob_destroy_scene(g);
    }
    /* A wall round the frame, flush in its plane: a frame of twice the size in a mesh of its own,
     * whose hole is the frame's outline. It touches the frame along the outline alone and leaves
     * it a sheet (a vent set into a wall); the frame lies in the wall's hole, so the wall is not. */
    struct {
        const char *name;
        float bend;
        bool box, wall;
        int sheets;
    } cases[] = {{"frame", 0.0f, false, false, 1},
                 {"bent frame", 0.2f, false, false, 0},
                 {"frame round a box", 0.0f, true, false, 0},
                 {"frame flush in a wall", 0.0f, false, true, 1}};
    for (int k = 0; k < 4; ++k) {
        ob_scene *s = ob_scene_alloc(cases[k].name);
        add_frame(s, 0.0f, cases[k].bend);
        if (cases[k].box) add_box(s);
        if (cases[k].wall) add_frame_scaled(s, 0.0f, 0.0f, 2.0f);
        ob_scene_finish(s);
        int got = count_sheets(s);
        CHECK(got == cases[k].sheets, "%s: %d sheets, expected %d", cases[k].name, got, cases[k].sheets);
        ob_destroy_scene(s);
    }
    ob_scene *vent = load("vent", NULL, OB_UP_DEFAULT);
    CHECK(vent && vent->mesh_count == 3 && count_sheets(vent) == 1, "vent: one sheet (the grille; not the wall or floor)");
    if (vent && vent->mesh_count == 3) { /* build_vent: floor, wall, then the grille: only the grille's vertices marked */
        float *labels[3] = {0};
        ob_holes holes[3] = {{0}};
        bool ok = true;
        for (int m = 0; m < 3; ++m) {
            labels[m] = malloc((size_t)vent->meshes[m].vertex_count * sizeof(float));
            ok = ok && labels[m] && ob_mesh_part_labels(&vent->meshes[m], 0u, labels[m], &holes[m]) >= 0;
        }
        ok = ok && ob_scene_settle_sheets(vent, labels, holes) == 1;
        int marked[3] = {0, 0, 0};
        for (int m = 0; ok && m < 3; ++m)
            for (uint32_t v = 0; v < vent->meshes[m].vertex_count; ++v) marked[m] += labels[m][v] >= (float)OB_PART_SHEET;
        CHECK(ok && marked[0] == 0 && marked[1] == 0 && marked[2] == (int)vent->meshes[2].vertex_count,
              "vent: the grille's %d of %u vertices marked, the floor's %d and the wall's %d", marked[2],
              vent->meshes[2].vertex_count, marked[0], marked[1]);
        for (int m = 0; m < 3; ++m) free(labels[m]), free(holes[m].items);
    }
    ob_destroy_scene(vent);
    /* One loop: slab's floor, a plain 8 m quad grid, is no candidate. */
    ob_scene *slab = load("slab", NULL, OB_UP_DEFAULT);
    CHECK(slab && count_sheets(slab) == 0, "slab: no sheet");
    ob_destroy_scene(slab);
}

int main(void)
{
    snprintf(tmpdir, sizeof tmpdir, "%s", "/tmp/obscura_test_scene_XXXXXX");
    if (!mkdtemp(tmpdir)) {
        CHECK(false, "cannot make a temporary directory");
        return check_finish("scene");
    }
    test_builtins();
    test_cameras();
    test_resolution_and_sidecars();
    test_sidecar_lights();
    test_gltf_lights();
    test_cornell_obj();
    test_gltf_cameras();
    test_gltf1();
    test_automatic_ground();
    test_textures();
    test_bunny();
    test_fzk_haus();
    test_oa_dm1();
    test_sidecar_ground();
    test_new_named_scenes();
    test_tessellate();
    test_paths();
    test_parts();
    test_sheets();
    rmdir(tmpdir);
    return check_finish("scene");
}
