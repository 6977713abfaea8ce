/* Default framing camera and near/far planes derived from scene bounds. */
#include "scene/scene.h"

#include <math.h>
#include <stdio.h>

#define OB_PI_F 3.14159265358979f

/* Used when a caller passes no field of view: a natural-looking lens, not a wide angle. */
#define OB_DEFAULT_FOV_DEG 60.0f

static void bounds_centre_radius(const float bmin[3], const float bmax[3], float c[3], float *r)
{
    float d2 = 0.0f;
    for (int i = 0; i < 3; ++i) {
        float e = bmax[i] - bmin[i];
        c[i] = 0.5f * (bmin[i] + bmax[i]);
        d2 += e * e;
    }
    *r = 0.5f * sqrtf(d2);
}

ob_camera ob_camera_frame_bounds(const float bmin[3], const float bmax[3], float fov_y_deg)
{
    ob_camera cam = {0};
    float c[3] = {0.0f, 0.0f, 0.0f};
    float r = 0.0f;
    bounds_centre_radius(bmin, bmax, c, &r);
    /* Empty or single-point bounds still need a camera that looks at something. */
    if (!(r > 0.0f) || !isfinite(r)) r = 1.0f;
    float fov = fov_y_deg > 0.0f && fov_y_deg < 179.0f ? fov_y_deg : OB_DEFAULT_FOV_DEG;

    /* Front (+Z), a little above and to the right: shows the top and two sides of a model
     * authored facing +Z, so silhouettes and contact creases are both visible. */
    const float dir_raw[3] = {0.6f, 0.45f, 1.0f};
    float len = sqrtf(dir_raw[0] * dir_raw[0] + dir_raw[1] * dir_raw[1] + dir_raw[2] * dir_raw[2]);

    /* The bounding sphere fits the vertical field of view with a 10% margin; the horizontal one
     * is at least as wide for the landscape images the renderer makes. */
    float half = 0.5f * fov * OB_PI_F / 180.0f;
    float dist = 1.1f * r / sinf(half);

    for (int i = 0; i < 3; ++i) {
        cam.target[i] = c[i];
        cam.eye[i] = c[i] + dir_raw[i] / len * dist;
    }
    cam.up[0] = 0.0f;
    cam.up[1] = 1.0f;
    cam.up[2] = 0.0f;
    cam.fov_y_deg = fov;
    /* near/far stay zero ("derived"): the viewer may move this camera, and planes fitted here
     * would go stale. The renderer fits them with ob_camera_fit_planes. */
    snprintf(cam.name, sizeof cam.name, "%s", "default");
    return cam;
}

void ob_camera_fit_planes(ob_camera *cam, const float bmin[3], const float bmax[3])
{
    if (!cam) return;
    float c[3] = {0.0f, 0.0f, 0.0f};
    float r = 0.0f;
    bounds_centre_radius(bmin, bmax, c, &r);
    if (!(r > 0.0f) || !isfinite(r)) r = 1.0f;

    /* Distance from the eye to the nearest point of the box (0 inside) and to its farthest
     * corner. */
    float near2 = 0.0f;
    float far2 = 0.0f;
    for (int i = 0; i < 3; ++i) {
        float e = cam->eye[i];
        float dn = e < bmin[i] ? bmin[i] - e : (e > bmax[i] ? e - bmax[i] : 0.0f);
        float df = fmaxf(fabsf(e - bmin[i]), fabsf(e - bmax[i]));
        near2 += dn * dn;
        far2 += df * df;
    }
    float far_z = 1.1f * sqrtf(far2);
    /* A camera inside the bounds (an interior preset) has nearest distance 0: the near plane
     * then falls back to a small fraction of the scene size, which keeps it positive. */
    float near_z = fmaxf(0.9f * sqrtf(near2), fmaxf(far_z / 10000.0f, 1e-3f * r));
    if (!isfinite(far_z) || !(far_z > near_z)) far_z = 2.0f * near_z + r;
    cam->near_z = near_z;
    cam->far_z = far_z;
}
