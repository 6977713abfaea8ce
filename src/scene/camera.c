/* Default framing camera and near/far planes derived from scene bounds. */
#include "scene/scene.h"

#include <cglm/cglm.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"

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

static bool coordinates_ok(const float *v, int n)
{
    for (int i = 0; i < n; ++i)
        if (!isfinite(v[i]) || fabsf(v[i]) > OB_MAX_COORDINATE) return false;
    return true;
}

ob_error ob_check_camera(const ob_camera *cam)
{
    if (!cam) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_check_camera: NULL camera");
    if (!coordinates_ok(cam->eye, 3))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "eye (%g, %g, %g) is not finite or beyond +-%g",
                            (double)cam->eye[0], (double)cam->eye[1], (double)cam->eye[2], (double)OB_MAX_COORDINATE);
    if (!coordinates_ok(cam->target, 3))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "target (%g, %g, %g) is not finite or beyond +-%g",
                            (double)cam->target[0], (double)cam->target[1], (double)cam->target[2],
                            (double)OB_MAX_COORDINATE);
    if (!coordinates_ok(cam->up, 3) || !isfinite(cam->shift[0]) || !isfinite(cam->shift[1]))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "up or lens shift is not finite");
    /* Within +-1e18 every difference and its squares stay finite in float. */
    float f[3] = {cam->target[0] - cam->eye[0], cam->target[1] - cam->eye[1], cam->target[2] - cam->eye[2]};
    float fl = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    if (!(fl > 0.0f)) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "eye and target are the same point");
    float u[3] = {cam->up[0], cam->up[1], cam->up[2]};
    if (u[0] == 0.0f && u[1] == 0.0f && u[2] == 0.0f) u[1] = 1.0f; /* zero = world up */
    /* Scaled by the largest component first: a huge up vector's squares would overflow. */
    float m = fmaxf(fabsf(u[0]), fmaxf(fabsf(u[1]), fabsf(u[2])));
    for (int i = 0; i < 3; ++i) u[i] /= m;
    float ul = sqrtf(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    float c[3] = {f[1] * u[2] - f[2] * u[1], f[2] * u[0] - f[0] * u[2], f[0] * u[1] - f[1] * u[0]};
    /* sin(angle) below 1e-4 (0.006 degrees): lookAt's side vector is then mostly rounding. */
    if (!(sqrtf(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) >= 1e-4f * fl * ul))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "up (%g, %g, %g) is parallel to the view direction: the camera's "
                            "roll is undefined (move the eye sideways or give another up)",
                            (double)u[0] * (double)m, (double)u[1] * (double)m, (double)u[2] * (double)m);
    if (cam->fov_y_deg != 0.0f && !(cam->fov_y_deg >= OB_MIN_FOV_DEG && cam->fov_y_deg < 179.0f))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "fov %g degrees is outside [%g, 179)", (double)cam->fov_y_deg,
                            (double)OB_MIN_FOV_DEG);
    if ((cam->near_z != 0.0f || cam->far_z != 0.0f) &&
        !(cam->near_z > 0.0f && cam->far_z > cam->near_z && isfinite(cam->far_z)))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "near %g and far %g planes: expected both 0 (fitted) or 0 < near < far",
                            (double)cam->near_z, (double)cam->far_z);
    return OB_OK;
}

void ob_camera_view_proj(const ob_camera *cam, int width, int height, float view[16], float proj[16])
{
    /* Through aligned cglm matrices: its SIMD paths assume them. */
    vec3 eye = {cam->eye[0], cam->eye[1], cam->eye[2]}, target = {cam->target[0], cam->target[1], cam->target[2]};
    vec3 up = {cam->up[0], cam->up[1], cam->up[2]};
    mat4 v, p;
    glm_lookat(eye, target, up, v);
    glm_perspective(glm_rad(cam->fov_y_deg), (float)width / (float)height, cam->near_z, cam->far_z, p);
    p[2][0] = cam->shift[0]; /* off-axis frustum (ob_camera.shift): P20, P21 */
    p[2][1] = cam->shift[1];
    memcpy(view, v, sizeof v);
    memcpy(proj, p, sizeof p);
}

ob_error ob_camera_matrices(ob_camera *cam, const float bounds_min[3], const float bounds_max[3], int width, int height,
                            float view[16], float proj[16])
{
    if (!cam || !view || !proj || width < 1 || height < 1)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_camera_matrices: %s",
                            !cam ? "NULL camera" : (!view || !proj) ? "NULL matrix" : "size below 1x1");
    if (ob_check_camera(cam) != OB_OK) return ob_peek_error(NULL);
    /* ob_render_frame's defaults (frame.c). */
    if (cam->fov_y_deg <= 0.0f) cam->fov_y_deg = 60.0f;
    if (cam->up[0] == 0.0f && cam->up[1] == 0.0f && cam->up[2] == 0.0f) cam->up[1] = 1.0f;
    if (cam->near_z <= 0.0f || cam->far_z <= cam->near_z) {
        if (!bounds_min || !bounds_max)
            return ob_set_error(OB_ERR_INVALID_ARGUMENT,
                                "ob_camera_matrices: the camera's near and far planes are 0 and no bounds to fit them to");
        ob_camera_fit_planes(cam, bounds_min, bounds_max);
    }
    ob_camera_view_proj(cam, width, height, view, proj);
    return OB_OK;
}
