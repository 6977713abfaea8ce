/* Built-in scenes that need no file: the Cornell box (published data, in metres), two analytic
 * AO test scenes whose ground truth can be reasoned about by hand, and two scenes that tell
 * methods apart where screen space loses information: floating slabs (thickness), drilled plates
 * (through-holes) and a red wall on a white floor (colour bleeding). */
#include "scene/scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"

#define OB_PI_F 3.14159265358979f

static const struct {
    const char *name;
    const char *description;
} builtins[] = {
    {"cornell", "Cornell box (Cornell University published data) in metres, open front"},
    {"corner", "three perpendicular 4 m planes meeting at the origin (analytic AO corner)"},
    {"sphere-on-plane", "unit sphere resting on a 10 m plane (contact occlusion)"},
    {"slab", "a 2 cm and a 1 m thick slab floating 15 cm above an 8 m floor (occluder thickness)"},
    {"bleed", "a red wall standing on a white floor, both lit (one-bounce colour bleeding)"},
    {"grille", "two plates drilled with 25 square holes floating 45 cm above a floor: a single sheet and a "
               "closed 4 cm plate (through-holes, second depth layer)"},
    {"vent", "a grille of 15 square holes set flush into a wall, in front of a 40 cm deep recess (a thin "
             "part touching another in its own plane, second depth layer)"},
};

#define BUILTIN_COUNT ((int)(sizeof builtins / sizeof builtins[0]))

int ob_builtin_scene_count(void)
{
    return BUILTIN_COUNT;
}

const char *ob_builtin_scene_name(int index)
{
    return index >= 0 && index < BUILTIN_COUNT ? builtins[index].name : NULL;
}

const char *ob_builtin_scene_description(int index)
{
    return index >= 0 && index < BUILTIN_COUNT ? builtins[index].description : NULL;
}

/* ---- a growable triangle list, flushed into one ob_mesh per material ----------------------- */

typedef struct geo {
    float *pos;
    float *nrm;
    uint32_t *idx;
    uint32_t vcount, vcap;
    uint32_t icount, icap;
    bool failed; /* out of memory: later calls do nothing, geo_emit reports it */
} geo;

static void cross3(const float a[3], const float b[3], float out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static float dot3(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void normalize3(float v[3])
{
    float len = sqrtf(dot3(v, v));
    if (len > 0.0f) {
        v[0] /= len;
        v[1] /= len;
        v[2] /= len;
    }
}

static uint32_t geo_vertex(geo *g, const float p[3], const float n[3])
{
    if (g->failed) return 0;
    if (g->vcount == g->vcap) {
        uint32_t cap = g->vcap ? g->vcap * 2u : 256u;
        float *pos = realloc(g->pos, (size_t)cap * 3u * sizeof(float));
        if (pos) g->pos = pos;
        float *nrm = pos ? realloc(g->nrm, (size_t)cap * 3u * sizeof(float)) : NULL;
        if (nrm) g->nrm = nrm;
        if (!pos || !nrm) {
            g->failed = true;
            return 0;
        }
        g->vcap = cap;
    }
    for (int i = 0; i < 3; ++i) {
        g->pos[3u * g->vcount + (uint32_t)i] = p[i];
        g->nrm[3u * g->vcount + (uint32_t)i] = n[i];
    }
    return g->vcount++;
}

/* Triangle a b c, reordered if needed so that it is counter-clockwise seen from the side its
 * vertex normals point to (the G-buffer culls back faces). */
static void geo_tri(geo *g, uint32_t a, uint32_t b, uint32_t c)
{
    if (g->failed) return;
    if (g->icount + 3u > g->icap) {
        uint32_t cap = g->icap ? g->icap * 2u : 768u;
        uint32_t *idx = realloc(g->idx, (size_t)cap * sizeof(uint32_t));
        if (!idx) {
            g->failed = true;
            return;
        }
        g->idx = idx;
        g->icap = cap;
    }
    const float *pa = &g->pos[3u * a], *pb = &g->pos[3u * b], *pc = &g->pos[3u * c];
    float e1[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
    float e2[3] = {pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]};
    float face[3] = {0.0f, 0.0f, 0.0f};
    cross3(e1, e2, face);
    float nsum[3] = {0.0f, 0.0f, 0.0f};
    for (int i = 0; i < 3; ++i) {
        nsum[i] = g->nrm[3u * a + (uint32_t)i] + g->nrm[3u * b + (uint32_t)i] +
                  g->nrm[3u * c + (uint32_t)i];
    }
    bool flip = dot3(face, nsum) < 0.0f;
    g->idx[g->icount++] = a;
    g->idx[g->icount++] = flip ? c : b;
    g->idx[g->icount++] = flip ? b : c;
}

/* A flat grid o + s*u + t*v (s, t in [0,1]) of nu x nv quads with normal n. */
static void geo_grid(geo *g, const float o[3], const float u[3], const float v[3], int nu, int nv,
                     const float n[3])
{
    uint32_t base = g->vcount;
    for (int j = 0; j <= nv; ++j) {
        for (int i = 0; i <= nu; ++i) {
            float s = (float)i / (float)nu, t = (float)j / (float)nv;
            float p[3] = {o[0] + s * u[0] + t * v[0], o[1] + s * u[1] + t * v[1],
                          o[2] + s * u[2] + t * v[2]};
            geo_vertex(g, p, n);
        }
    }
    uint32_t row = (uint32_t)nu + 1u;
    for (uint32_t j = 0; j < (uint32_t)nv; ++j) {
        for (uint32_t i = 0; i < (uint32_t)nu; ++i) {
            uint32_t a = base + j * row + i;
            geo_tri(g, a, a + 1u, a + row + 1u);
            geo_tri(g, a, a + row + 1u, a + row);
        }
    }
}

/* A quad of four corners (millimetres in, metres out) with its own flat normal: the Newell
 * normal, which copes with the slightly non-planar published walls, turned to point toward
 * `toward` (or away from it when away is true). */
static void geo_quad_mm(geo *g, const float *corners, const float toward[3], bool away)
{
    /* corners: 4 x xyz, flat (a 2-D array parameter would need matching qualifiers). */
    const float(*q)[3] = (const float(*)[3])corners;
    float n[3] = {0.0f, 0.0f, 0.0f};
    float c[3] = {0.0f, 0.0f, 0.0f};
    for (int k = 0; k < 4; ++k) {
        const float *p = q[k], *r = q[(k + 1) % 4];
        n[0] += (p[1] - r[1]) * (p[2] + r[2]);
        n[1] += (p[2] - r[2]) * (p[0] + r[0]);
        n[2] += (p[0] - r[0]) * (p[1] + r[1]);
        for (int i = 0; i < 3; ++i) c[i] += 0.25f * p[i];
    }
    float d[3] = {toward[0] - c[0], toward[1] - c[1], toward[2] - c[2]};
    if ((dot3(n, d) < 0.0f) != away) {
        n[0] = -n[0];
        n[1] = -n[1];
        n[2] = -n[2];
    }
    normalize3(n);
    uint32_t v[4] = {0, 0, 0, 0};
    for (int k = 0; k < 4; ++k) {
        float p[3] = {q[k][0] * 0.001f, q[k][1] * 0.001f, q[k][2] * 0.001f};
        v[k] = geo_vertex(g, p, n);
    }
    geo_tri(g, v[0], v[1], v[2]);
    geo_tri(g, v[0], v[2], v[3]);
}

/* Move the triangles into a new mesh of the scene and reset g. */
static bool geo_emit(geo *g, ob_scene *s, int material)
{
    bool ok = !g->failed && material >= 0;
    if (ok) {
        ob_mesh *m = ob_scene_add_mesh(s, g->vcount, g->icount, false);
        if (m) {
            memcpy(m->positions, g->pos, (size_t)g->vcount * 3u * sizeof(float));
            memcpy(m->normals, g->nrm, (size_t)g->vcount * 3u * sizeof(float));
            memcpy(m->indices, g->idx, (size_t)g->icount * sizeof(uint32_t));
            m->material = material;
        }
        ok = m != NULL;
    } else if (g->failed) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: out of memory building geometry", s->name);
    }
    free(g->pos);
    free(g->nrm);
    free(g->idx);
    memset(g, 0, sizeof *g);
    return ok;
}

static ob_camera make_camera(const char *name, float ex, float ey, float ez, float tx, float ty,
                             float tz, float fov)
{
    ob_camera cam = {.eye = {ex, ey, ez}, .target = {tx, ty, tz}, .up = {0.0f, 1.0f, 0.0f},
                     .fov_y_deg = fov};
    snprintf(cam.name, sizeof cam.name, "%s", name);
    return cam;
}

static void set_light(ob_scene *s, float x, float y, float z)
{
    float d[3] = {x, y, z};
    normalize3(d);
    for (int i = 0; i < 3; ++i) {
        s->lights[0].direction[i] = d[i];
        s->lights[0].color[i] = 1.0f;
    }
    s->lights[0].type = OB_LIGHT_DIRECTIONAL;
    s->lights[0].intensity = 0.8f;
    s->light_count = 1;
}

/* ---- cornell --------------------------------------------------------------------------------- */

/* Corner coordinates in millimetres from the Cornell University Program of Computer Graphics
 * "Cornell Box Data" page (the same numbers as the OBJ shipped with tinyobjloader). The walls
 * are not exactly a box: that is the measured data. */
static const float cornell_floor[4][3] = {
    {552.8f, 0.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 559.2f}, {549.6f, 0.0f, 559.2f}};
static const float cornell_ceiling[4][3] = {
    {556.0f, 548.8f, 0.0f}, {556.0f, 548.8f, 559.2f}, {0.0f, 548.8f, 559.2f}, {0.0f, 548.8f, 0.0f}};
static const float cornell_back[4][3] = {
    {549.6f, 0.0f, 559.2f}, {0.0f, 0.0f, 559.2f}, {0.0f, 548.8f, 559.2f}, {556.0f, 548.8f, 559.2f}};
/* x = 0 is on the viewer's right: the camera looks down +z with +y up. */
static const float cornell_green[4][3] = {
    {0.0f, 0.0f, 559.2f}, {0.0f, 0.0f, 0.0f}, {0.0f, 548.8f, 0.0f}, {0.0f, 548.8f, 559.2f}};
static const float cornell_red[4][3] = {
    {552.8f, 0.0f, 0.0f}, {549.6f, 0.0f, 559.2f}, {556.0f, 548.8f, 559.2f}, {556.0f, 548.8f, 0.0f}};
/* The light patch hangs 0.8 mm below the ceiling in the data. */
static const float cornell_light[4][3] = {{343.0f, 548.0f, 227.0f},
                                          {343.0f, 548.0f, 332.0f},
                                          {213.0f, 548.0f, 332.0f},
                                          {213.0f, 548.0f, 227.0f}};
/* Blocks: footprint corners in order (x, z) and height. */
static const float short_block_xz[4][2] = {
    {130.0f, 65.0f}, {82.0f, 225.0f}, {240.0f, 272.0f}, {290.0f, 114.0f}};
static const float tall_block_xz[4][2] = {
    {423.0f, 247.0f}, {265.0f, 296.0f}, {314.0f, 456.0f}, {472.0f, 406.0f}};

/* Top and four sides (the bottom rests on the floor and is never seen). */
static void cornell_block(geo *g, const float xz[4][2], float height)
{
    float centre[3] = {0.0f, 0.5f * height, 0.0f};
    for (int k = 0; k < 4; ++k) {
        centre[0] += 0.25f * xz[k][0];
        centre[2] += 0.25f * xz[k][1];
    }
    float top[4][3] = {{0.0f}};
    for (int k = 0; k < 4; ++k) {
        top[k][0] = xz[k][0];
        top[k][1] = height;
        top[k][2] = xz[k][1];
    }
    geo_quad_mm(g, &top[0][0], centre, true);
    for (int k = 0; k < 4; ++k) {
        const float *a = xz[k], *b = xz[(k + 1) % 4];
        float side[4][3] = {{a[0], 0.0f, a[1]}, {b[0], 0.0f, b[1]}, {b[0], height, b[1]},
                            {a[0], height, a[1]}};
        geo_quad_mm(g, &side[0][0], centre, true);
    }
}

static bool build_cornell(ob_scene *s)
{
    /* Reflectances: the published white/red/green; the light's housing is white. */
    int white = ob_scene_add_material(s, "white", 0.73f, 0.73f, 0.73f);
    int red = ob_scene_add_material(s, "red", 0.63f, 0.065f, 0.05f);
    int green = ob_scene_add_material(s, "green", 0.14f, 0.45f, 0.091f);
    int light = ob_scene_add_material(s, "light", 0.78f, 0.78f, 0.78f);
    if (white < 0 || red < 0 || green < 0 || light < 0) return false;

    const float inside[3] = {278.0f, 274.4f, 279.6f};
    geo g = {0};
    geo_quad_mm(&g, &cornell_floor[0][0], inside, false);
    geo_quad_mm(&g, &cornell_ceiling[0][0], inside, false);
    geo_quad_mm(&g, &cornell_back[0][0], inside, false);
    cornell_block(&g, short_block_xz, 165.0f);
    cornell_block(&g, tall_block_xz, 330.0f);
    if (!geo_emit(&g, s, white)) return false;
    geo_quad_mm(&g, &cornell_red[0][0], inside, false);
    if (!geo_emit(&g, s, red)) return false;
    geo_quad_mm(&g, &cornell_green[0][0], inside, false);
    if (!geo_emit(&g, s, green)) return false;
    geo_quad_mm(&g, &cornell_light[0][0], inside, false);
    if (!geo_emit(&g, s, light)) return false;

    /* Radius: about a fifth of the box, so the blocks' contact creases read clearly. */
    s->ao_radius = 0.1f;
    /* The published box is lit by its ceiling patch (130 x 105 mm at y = 548 mm), an emitter that
     * faces down: it lights neither the ceiling nor its own housing. A spot 2 cm below the patch's
     * centre, aimed down, stands in for it. Its smoothstep cone (inner 0, outer 78 degrees: the
     * widest whose map, with its 2-degree margin, stays within the 160-degree limit) is within
     * 0.07 of a Lambertian emitter's cos(theta) out to 50 degrees, dimmer beyond. Not a point light:
     * one lit the ceiling with a hot spot no real box has, and the housing 2 cm above it, grazed
     * at 13-17 degrees, cast real shadow slivers up to 3.5 mm wide on the ceiling at its corners:
     * the dark specks beside the lamp, with hard and PCF maps alike (docs/lighting.md, "Cornell").
     * Intensity: the split-flux estimate of the interreflected light (docs/lighting.md,
     * "Ambient share") is E = Phi rho_1 / (A (1 - rho)) = 1.0 x I for this cone and box, so
     * I = 0.3 makes the default ambient of 0.3 the box's own indirect light. */
    s->lights[0] = (ob_light){.type = OB_LIGHT_SPOT, .position = {0.278f, 0.528f, 0.2795f},
                              .direction = {0.0f, -1.0f, 0.0f}, .color = {1.0f, 1.0f, 1.0f},
                              .intensity = 0.3f, .spot_inner_deg = 0.0f, .spot_outer_deg = 78.0f};
    s->light_count = 1;
    ob_scene_finish(s);
    /* The published camera: eye (278, 273, -800) mm looking down +z, 35 mm lens on a 25 mm
     * film: 2 atan(12.5 / 35) = 39.3 degrees. */
    ob_camera front = make_camera("front", 0.278f, 0.273f, -0.800f, 0.278f, 0.273f, 0.0f, 39.3f);
    /* The box opens toward -z, so the generic front-right framing would show the outside of the
     * back wall: "default" takes the published view, which frames the whole box too. */
    ob_camera def = front;
    snprintf(def.name, sizeof def.name, "%s", "default");
    s->cameras[0] = def;
    return ob_scene_add_camera(s, &front);
}

/* ---- corner ---------------------------------------------------------------------------------- */

static bool build_corner(ob_scene *s)
{
    int white = ob_scene_add_material(s, "white", 0.8f, 0.8f, 0.8f);
    if (white < 0) return false;
    const float L = 4.0f;
    const int cells = 8; /* 0.5 m cells: exact in binary, so the bounds are exactly [0, 4] */
    const float o[3] = {0.0f, 0.0f, 0.0f};
    const float ex[3] = {L, 0.0f, 0.0f}, ey[3] = {0.0f, L, 0.0f}, ez[3] = {0.0f, 0.0f, L};
    const float nx[3] = {1.0f, 0.0f, 0.0f}, ny[3] = {0.0f, 1.0f, 0.0f}, nz[3] = {0.0f, 0.0f, 1.0f};
    geo g = {0};
    geo_grid(&g, o, ex, ez, cells, cells, ny); /* floor y = 0 */
    geo_grid(&g, o, ey, ez, cells, cells, nx); /* wall x = 0 */
    geo_grid(&g, o, ex, ey, cells, cells, nz); /* wall z = 0 */
    if (!geo_emit(&g, s, white)) return false;

    s->ao_radius = 0.5f;
    /* From inside the octant, so all three planes are lit. */
    set_light(s, 0.5f, 1.0f, 0.7f);
    ob_scene_finish(s);
    /* From the open side of the octant, aimed past the corner so the three planes fill the
     * frame and the corner vertex sits a little below the centre. */
    ob_camera diag = make_camera("diagonal", 6.5f, 5.0f, 6.5f, 1.4f, 1.1f, 1.4f, 60.0f);
    return ob_scene_add_camera(s, &diag);
}

/* ---- sphere-on-plane ------------------------------------------------------------------------- */

static bool build_sphere_on_plane(ob_scene *s)
{
    int sphere_mat = ob_scene_add_material(s, "sphere", 0.8f, 0.8f, 0.8f);
    int plane_mat = ob_scene_add_material(s, "plane", 0.8f, 0.8f, 0.8f);
    if (sphere_mat < 0 || plane_mat < 0) return false;

    const int seg = 48, rings = 24;
    geo g = {0};
    for (int i = 0; i <= rings; ++i) {
        float theta = OB_PI_F * (float)i / (float)rings;
        /* Exact poles, so the sphere touches the plane at y = 0 and tops out at y = 2. */
        float ct = i == 0 ? 1.0f : (i == rings ? -1.0f : cosf(theta));
        float st = i == 0 || i == rings ? 0.0f : sinf(theta);
        for (int j = 0; j <= seg; ++j) {
            float phi = 2.0f * OB_PI_F * (float)j / (float)seg;
            float n[3] = {st * cosf(phi), ct, st * sinf(phi)};
            float p[3] = {n[0], 1.0f + n[1], n[2]};
            geo_vertex(&g, p, n);
        }
    }
    uint32_t row = (uint32_t)seg + 1u;
    for (uint32_t i = 0; i < (uint32_t)rings; ++i) {
        for (uint32_t j = 0; j < (uint32_t)seg; ++j) {
            uint32_t a = i * row + j;
            /* At the poles one triangle of each quad has zero area: leave it out. */
            if (i != 0) geo_tri(&g, a, a + 1u, a + row + 1u);
            if (i != (uint32_t)rings - 1u) geo_tri(&g, a, a + row + 1u, a + row);
        }
    }
    if (!geo_emit(&g, s, sphere_mat)) return false;

    const float o[3] = {-5.0f, 0.0f, -5.0f};
    const float ux[3] = {10.0f, 0.0f, 0.0f}, uz[3] = {0.0f, 0.0f, 10.0f};
    const float up[3] = {0.0f, 1.0f, 0.0f};
    geo_grid(&g, o, ux, uz, 20, 20, up);
    if (!geo_emit(&g, s, plane_mat)) return false;

    s->ao_radius = 0.5f;
    ob_scene_finish(s);
    ob_camera front = make_camera("front", 0.0f, 2.2f, 5.5f, 0.0f, 0.7f, 0.0f, 45.0f);
    ob_camera contact = make_camera("contact", 3.6f, 0.8f, 3.6f, 0.0f, 0.6f, 0.0f, 40.0f);
    return ob_scene_add_camera(s, &front) && ob_scene_add_camera(s, &contact);
}

/* ---- slab ------------------------------------------------------------------------------------ */

/* The four sides of the axis-aligned box lo..hi (x and z faces), every face outward. */
static void geo_box_sides(geo *g, const float lo[3], const float hi[3])
{
    const float dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
    const float ux[3] = {dx, 0.0f, 0.0f}, uy[3] = {0.0f, dy, 0.0f}, uz[3] = {0.0f, 0.0f, dz};
    const float hx[3] = {hi[0], lo[1], lo[2]}, hz[3] = {lo[0], lo[1], hi[2]};
    const float px[3] = {1.0f, 0.0f, 0.0f}, pz[3] = {0.0f, 0.0f, 1.0f};
    const float mx[3] = {-1.0f, 0.0f, 0.0f}, mz[3] = {0.0f, 0.0f, -1.0f};
    geo_grid(g, lo, uy, uz, 1, 1, mx);
    geo_grid(g, hx, uy, uz, 1, 1, px);
    geo_grid(g, lo, ux, uy, 1, 1, mz);
    geo_grid(g, hz, ux, uy, 1, 1, pz);
}

/* A closed axis-aligned box lo..hi, every face outward and the bottom included: the reference
 * rays from the floor below hit it. */
static void geo_box(geo *g, const float lo[3], const float hi[3])
{
    const float ux[3] = {hi[0] - lo[0], 0.0f, 0.0f}, uz[3] = {0.0f, 0.0f, hi[2] - lo[2]};
    const float hy[3] = {lo[0], hi[1], lo[2]};
    const float py[3] = {0.0f, 1.0f, 0.0f}, my[3] = {0.0f, -1.0f, 0.0f};
    geo_box_sides(g, lo, hi);
    geo_grid(g, lo, ux, uz, 1, 1, my);
    geo_grid(g, hy, ux, uz, 1, 1, py);
}

/* The 8 m floor of `slab` and `grille`, y = 0, 0.5 m cells: the bounds are exactly [-4, 4]. */
static void geo_floor(geo *g)
{
    const float o[3] = {-4.0f, 0.0f, -4.0f};
    const float ux[3] = {8.0f, 0.0f, 0.0f}, uz[3] = {0.0f, 0.0f, 8.0f}, up[3] = {0.0f, 1.0f, 0.0f};
    geo_grid(g, o, ux, uz, 16, 16, up);
}

/* The end of `slab`, `grille` and `vent`: their (last) mesh, R = 0.5 m and the key light from the
 * front, above and right. False when the mesh could not be made (geo_emit set the error). */
static bool finish_floor_scene(ob_scene *s, geo *g, int material)
{
    if (!geo_emit(g, s, material)) return false;
    s->ao_radius = 0.5f;
    set_light(s, 0.5f, 1.0f, 0.7f);
    ob_scene_finish(s);
    return true;
}

/* Two slabs of one 1.2 m square footprint whose bottoms float 0.15 m (0.3 R) above the floor:
 * 0.02 m thick on the left (x < 0), 1 m thick (twice R) on the right, 1.2 m (2.4 R) apart. A
 * depth buffer sees only their tops and the faces turned to the camera; the ray tracer also
 * sees the gap below and how deep each slab really is. A horizon method closes the gap under
 * both alike (tests/test_vbao.c measures it); a method that gives its samples a thickness has
 * to get both slabs right at once. */
static bool build_slab(ob_scene *s)
{
    int white = ob_scene_add_material(s, "white", 0.8f, 0.8f, 0.8f);
    if (white < 0) return false;
    geo g = {0};
    geo_floor(&g);
    const float thin_lo[3] = {-1.8f, 0.15f, -0.6f}, thin_hi[3] = {-0.6f, 0.17f, 0.6f};
    const float thick_lo[3] = {0.6f, 0.15f, -0.6f}, thick_hi[3] = {1.8f, 1.15f, 0.6f};
    geo_box(&g, thin_lo, thin_hi);
    geo_box(&g, thick_lo, thick_hi);
    if (!finish_floor_scene(s, &g, white)) return false;
    /* From the front (+z) and above, between the slabs: the floor in front of each and beside
     * its inner side lies in view. */
    ob_camera front = make_camera("front", 0.0f, 2.6f, 3.6f, 0.0f, 0.2f, 0.2f, 50.0f);
    /* Eye 0.1 m above the floor, below the slabs' bottoms: their undersides and the floor
     * beneath them show through the gap. */
    ob_camera low = make_camera("low", 0.0f, 0.1f, 1.8f, 0.0f, 0.05f, 0.0f, 75.0f);
    return ob_scene_add_camera(s, &front) && ob_scene_add_camera(s, &low);
}

/* ---- grille ---------------------------------------------------------------------------------- */

/* A drilled face: nu x nv cells o + i u + j v, those with both indices odd left out (the holes),
 * facing n; `grille`'s plates and `vent`'s grille. */
static void drilled_face(geo *g, const float o[3], const float u[3], const float v[3], int nu, int nv, const float n[3])
{
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            if (i % 2 == 1 && j % 2 == 1) continue;
            const float c[3] = {o[0] + (float)i * u[0] + (float)j * v[0], o[1] + (float)i * u[1] + (float)j * v[1],
                                o[2] + (float)i * u[2] + (float)j * v[2]};
            geo_grid(g, c, u, v, 1, 1, n);
        }
}

/* The cells of a plate's top (or bottom) face: an 11 x 11 grid over [x0, x0 + 1.2] x [-0.6, 0.6]
 * at height y, the cells with both indices odd left out (the 5 x 5 holes, 0.109 m square), facing
 * n. The holes' walls, when `walls`, run from y down to y - depth. */
#define GRILLE_CELLS 11
#define GRILLE_SIZE 1.2f

static void grille_face(geo *g, float x0, float y, const float n[3])
{
    const float c = GRILLE_SIZE / (float)GRILLE_CELLS;
    const float o[3] = {x0, y, -0.5f * GRILLE_SIZE}, u[3] = {c, 0.0f, 0.0f}, v[3] = {0.0f, 0.0f, c};
    drilled_face(g, o, u, v, GRILLE_CELLS, GRILLE_CELLS, n);
}

static void grille_walls(geo *g, float x0, float y_lo, float depth)
{
    const float c = GRILLE_SIZE / (float)GRILLE_CELLS;
    const float up[3] = {0.0f, depth, 0.0f}, ux[3] = {c, 0.0f, 0.0f}, uz[3] = {0.0f, 0.0f, c};
    const float px[3] = {1.0f, 0.0f, 0.0f}, mx[3] = {-1.0f, 0.0f, 0.0f};
    const float pz[3] = {0.0f, 0.0f, 1.0f}, mz[3] = {0.0f, 0.0f, -1.0f};
    for (int j = 1; j < GRILLE_CELLS; j += 2)
        for (int i = 1; i < GRILLE_CELLS; i += 2) {
            float hx = x0 + (float)i * c, hz = -0.5f * GRILLE_SIZE + (float)j * c;
            /* Each wall faces into the hole. */
            const float a[3] = {hx, y_lo, hz}, b[3] = {hx + c, y_lo, hz}, d[3] = {hx, y_lo, hz + c};
            geo_grid(g, a, up, uz, 1, 1, px);
            geo_grid(g, b, up, uz, 1, 1, mx);
            geo_grid(g, a, ux, up, 1, 1, pz);
            geo_grid(g, d, ux, up, 1, 1, mz);
        }
}

/* Two drilled plates of the slab scene's footprint, bottoms 0.45 m (0.9 R) above the floor, more
 * than vbao's default thickness (0.75 R), so that a sample on a plate whose back is taken right
 * is not solid down to the floor:
 * on the left a single sheet (one polygon thick, as CAD and CFD exports often give thin parts: a
 * brake disc, a grille), on the right a closed plate 4 cm thick with walls in its holes. A
 * depth buffer shows the floor through the holes; behind the sheet the next surface is the
 * floor, behind the closed plate's top its bottom, and the second depth layer has to tell the
 * two apart (peel.frag.glsl; tests/test_vbao.c). AO_R is open through the holes where the floor
 * lies beyond R of the plate, and each method's samples on the plate must not close them. */
static bool build_grille(ob_scene *s)
{
    int white = ob_scene_add_material(s, "white", 0.8f, 0.8f, 0.8f);
    if (white < 0) return false;
    const float up[3] = {0.0f, 1.0f, 0.0f}, down[3] = {0.0f, -1.0f, 0.0f};
    geo g = {0};
    geo_floor(&g);
    grille_face(&g, -1.8f, 0.45f, up); /* the sheet */
    const float lo = 0.45f, hi = 0.49f, x0 = 0.6f;
    grille_face(&g, x0, hi, up);
    grille_face(&g, x0, lo, down);
    grille_walls(&g, x0, lo, hi - lo);
    /* The closed plate's rim. */
    const float rim_lo[3] = {x0, lo, -0.5f * GRILLE_SIZE}, rim_hi[3] = {x0 + GRILLE_SIZE, hi, 0.5f * GRILLE_SIZE};
    geo_box_sides(&g, rim_lo, rim_hi);
    if (!finish_floor_scene(s, &g, white)) return false;
    /* From the front and above, both plates and the floor through their holes. */
    ob_camera front = make_camera("front", 0.0f, 2.6f, 3.2f, 0.0f, 0.1f, 0.0f, 50.0f);
    /* Steeply down on the sheet: the floor under every hole. */
    ob_camera top = make_camera("top", -1.2f, 2.6f, 0.9f, -1.2f, 0.1f, 0.0f, 45.0f);
    return ob_scene_add_camera(s, &front) && ob_scene_add_camera(s, &top);
}

/* ---- vent ------------------------------------------------------------------------------------ */

/* The vent's opening in the wall z = 0: 11 x 7 cells of 8 cm from (VENT_X0, VENT_Y0), 0.88 m by
 * 0.56 m; its holes are the cells with both indices odd (5 x 3). */
#define VENT_X0 (-0.44f)
#define VENT_Y0 0.5f
#define VENT_CELL 0.08f
#define VENT_DEPTH 0.4f

/* A wall 4 m long, 2 m high and 0.6 m thick standing on the floor, its front face z = 0 with the
 * vent's opening, and behind the opening a recess VENT_DEPTH deep: one closed solid (its front
 * face meets the recess at the opening's rim). */
static void vent_wall(geo *g)
{
    const float xs[4] = {-2.0f, VENT_X0, VENT_X0 + 11.0f * VENT_CELL, 2.0f};
    const float ys[4] = {0.0f, VENT_Y0, VENT_Y0 + 7.0f * VENT_CELL, 2.0f};
    const float pz[3] = {0.0f, 0.0f, 1.0f}, mz[3] = {0.0f, 0.0f, -1.0f};
    const float px[3] = {1.0f, 0.0f, 0.0f}, mx[3] = {-1.0f, 0.0f, 0.0f};
    const float py[3] = {0.0f, 1.0f, 0.0f}, my[3] = {0.0f, -1.0f, 0.0f};
    /* The front: 3 x 3 quads round the opening, which is the middle one. */
    for (int j = 0; j < 3; ++j)
        for (int i = 0; i < 3; ++i) {
            if (i == 1 && j == 1) continue;
            const float o[3] = {xs[i], ys[j], 0.0f};
            const float u[3] = {xs[i + 1] - xs[i], 0.0f, 0.0f}, v[3] = {0.0f, ys[j + 1] - ys[j], 0.0f};
            geo_grid(g, o, u, v, 1, 1, pz);
        }
    /* The recess: four sides facing into it and its back. */
    const float w = xs[2] - xs[1], h = ys[2] - ys[1];
    const float ux[3] = {w, 0.0f, 0.0f}, uy[3] = {0.0f, h, 0.0f}, uz[3] = {0.0f, 0.0f, -VENT_DEPTH};
    const float lo[3] = {xs[1], ys[1], 0.0f}, right[3] = {xs[2], ys[1], 0.0f}, top[3] = {xs[1], ys[2], 0.0f};
    const float back[3] = {xs[1], ys[1], -VENT_DEPTH};
    geo_grid(g, lo, uy, uz, 1, 1, px);
    geo_grid(g, right, uy, uz, 1, 1, mx);
    geo_grid(g, lo, ux, uz, 1, 1, py);
    geo_grid(g, top, ux, uz, 1, 1, my);
    geo_grid(g, back, ux, uy, 1, 1, pz);
    /* The rest of the box: back, top, ends and bottom. */
    const float b_lo[3] = {-2.0f, 0.0f, -0.6f}, b_top[3] = {-2.0f, 2.0f, -0.6f}, b_end[3] = {2.0f, 0.0f, -0.6f};
    const float long_x[3] = {4.0f, 0.0f, 0.0f}, tall[3] = {0.0f, 2.0f, 0.0f}, deep[3] = {0.0f, 0.0f, 0.6f};
    geo_grid(g, b_lo, long_x, tall, 1, 1, mz);
    geo_grid(g, b_top, long_x, deep, 1, 1, py);
    geo_grid(g, b_lo, tall, deep, 1, 1, mx);
    geo_grid(g, b_end, tall, deep, 1, 1, px);
    geo_grid(g, b_lo, long_x, deep, 1, 1, my);
}

/* A vent grille set flush into a wall, in a mesh of its own (a metal part in a plaster wall, as
 * models give them): a single sheet with 15 square 8 cm holes, its outline on the rim of the
 * wall's opening, and behind it a recess 0.8 R deep. The sheet touches the wall in its own plane
 * along its whole outline: the first rule for sheets (scene/sheets.c) read anything touching a
 * candidate in its plane as a solid standing on it, so the vent's thickness was unknown and vbao
 * made it a slab of its constant 0.75 R, which reached almost to the recess's back. */
static bool build_vent(ob_scene *s)
{
    int white = ob_scene_add_material(s, "white", 0.8f, 0.8f, 0.8f);
    int grey = ob_scene_add_material(s, "grey", 0.5f, 0.5f, 0.5f);
    if (white < 0 || grey < 0) return false;
    geo g = {0};
    geo_floor(&g);
    if (!geo_emit(&g, s, white)) return false;
    vent_wall(&g);
    if (!geo_emit(&g, s, white)) return false;
    const float o[3] = {VENT_X0, VENT_Y0, 0.0f}, u[3] = {VENT_CELL, 0.0f, 0.0f}, v[3] = {0.0f, VENT_CELL, 0.0f};
    const float pz[3] = {0.0f, 0.0f, 1.0f};
    drilled_face(&g, o, u, v, 11, 7, pz);
    if (!finish_floor_scene(s, &g, grey)) return false;
    /* From the front, a little above and to the right: the recess's back through every hole. */
    ob_camera front = make_camera("front", 0.7f, 1.6f, 2.4f, 0.0f, 0.55f, -0.2f, 45.0f);
    /* From the left and low: the recess's far side through the holes, at a slant. */
    ob_camera side = make_camera("side", -1.5f, 1.0f, 1.5f, 0.0f, 0.55f, -0.2f, 45.0f);
    return ob_scene_add_camera(s, &front) && ob_scene_add_camera(s, &side);
}

/* ---- bleed ----------------------------------------------------------------------------------- */

/* A red wall x = 0 (2 m high, 4 m long) standing on a white floor x in [0, 4]; one directional
 * light from the floor's side lights both, so the wall sends red light onto the floor next to
 * it and the floor sends white light onto the wall. */
static bool build_bleed(ob_scene *s)
{
    int white = ob_scene_add_material(s, "white", 0.8f, 0.8f, 0.8f);
    int red = ob_scene_add_material(s, "red", 0.8f, 0.05f, 0.05f);
    if (white < 0 || red < 0) return false;
    const float o[3] = {0.0f, 0.0f, -2.0f};
    const float ux[3] = {4.0f, 0.0f, 0.0f}, uy[3] = {0.0f, 2.0f, 0.0f}, uz[3] = {0.0f, 0.0f, 4.0f};
    const float nx[3] = {1.0f, 0.0f, 0.0f}, ny[3] = {0.0f, 1.0f, 0.0f};
    geo g = {0};
    geo_grid(&g, o, ux, uz, 8, 8, ny); /* floor y = 0, 0.5 m cells */
    if (!geo_emit(&g, s, white)) return false;
    geo_grid(&g, o, uy, uz, 4, 8, nx); /* wall x = 0 */
    if (!geo_emit(&g, s, red)) return false;

    s->ao_radius = 0.5f;
    /* n.l: 0.6 on the wall, 0.75 on the floor; from +x, so the wall casts no shadow on it. */
    set_light(s, 0.6f, 0.75f, 0.28f);
    ob_scene_finish(s);
    /* Looking along the wall and down at the floor beside it. */
    ob_camera side = make_camera("side", 1.6f, 1.4f, 2.2f, 0.4f, 0.0f, 0.0f, 55.0f);
    return ob_scene_add_camera(s, &side);
}

/* ---- entry ----------------------------------------------------------------------------------- */

ob_scene *ob_scene_builtin(const char *name)
{
    if (!name) {
        ob_set_error(OB_ERR_INVALID_ARGUMENT, "built-in scene name is NULL");
        return NULL;
    }
    bool (*build)(ob_scene *) = NULL;
    if (strcmp(name, "cornell") == 0) build = build_cornell;
    if (strcmp(name, "corner") == 0) build = build_corner;
    if (strcmp(name, "sphere-on-plane") == 0) build = build_sphere_on_plane;
    if (strcmp(name, "slab") == 0) build = build_slab;
    if (strcmp(name, "bleed") == 0) build = build_bleed;
    if (strcmp(name, "grille") == 0) build = build_grille;
    if (strcmp(name, "vent") == 0) build = build_vent;
    if (!build) {
        ob_set_error(OB_ERR_UNKNOWN_SCENE, "unknown built-in scene '%s'", name);
        return NULL;
    }
    ob_scene *s = ob_scene_alloc(name);
    if (!s) return NULL;
    if (!build(s)) {
        /* The builders fail only for lack of memory. */
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "built-in scene '%s': out of memory", name);
        ob_destroy_scene(s);
        return NULL;
    }
    return s;
}
