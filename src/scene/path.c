/* Camera paths (issue 17): a scene's named keyframe paths (sidecar "paths", parsed and validated in
 * sidecar.c) evaluated at a fraction of their time span, and orbits about a camera's target. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "base/suggest.h"
#include "scene/scene.h"

int ob_query_path_count(const ob_scene *scene) { return scene ? scene->path_count : 0; }

const char *ob_query_path_name(const ob_scene *scene, int index)
{
    return scene && index >= 0 && index < scene->path_count ? scene->paths[index].name : "";
}

/* Catmull-Rom with the keys' own times (a non-uniform cardinal spline): the tangent at key i is the
 * slope between its neighbours over their time gap, so a key twice as far in time is approached
 * no faster than its spacing says; keys with uneven gaps then give no overshoot a uniform
 * parametrisation would. The ends use the one-sided slope. Hermite form between keys a and b. */
static float tangent(const float *v, const float *t, int n, int i, int stride)
{
    int lo = i > 0 ? i - 1 : i, hi = i < n - 1 ? i + 1 : i;
    return (v[hi * stride] - v[lo * stride]) / (t[hi] - t[lo]);
}

static void interpolate(const float *v, const float *t, int n, int a, float s, int stride, float *out, int dims)
{
    const float h = t[a + 1] - t[a];
    const float s2 = s * s, s3 = s2 * s;
    const float h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
    for (int d = 0; d < dims; ++d) {
        const float *c = v + d;
        out[d] = h00 * c[a * stride] + h10 * h * tangent(c, t, n, a, stride) + h01 * c[(a + 1) * stride] +
                 h11 * h * tangent(c, t, n, a + 1, stride);
    }
}

ob_error ob_camera_on_path(const ob_scene *scene, const char *name, float u, ob_camera *out)
{
    if (!scene || !name || !out) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_camera_on_path: NULL argument");
    const ob_camera_path *p = NULL;
    for (int i = 0; i < scene->path_count; ++i)
        if (!strcmp(scene->paths[i].name, name)) p = &scene->paths[i];
    if (!p) {
        char names[512] = "";
        for (int i = 0; i < scene->path_count; ++i)
            snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", i ? ", " : "", scene->paths[i].name);
        const char *known[OB_MAX_PATHS] = {0};
        for (int i = 0; i < scene->path_count && i < OB_MAX_PATHS; ++i) known[i] = scene->paths[i].name;
        char hint[96];
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "unknown camera path '%s' in scene '%s'%s (%s%s)", name, scene->name,
                            ob_suggest_text(name, strlen(name), known, scene->path_count, hint, sizeof hint),
                            scene->path_count ? "paths: " : "it has no \"paths\" in its sidecar", names);
    }
    if (!(u >= 0.0f)) u = 0.0f; /* NaN too */
    if (u > 1.0f) u = 1.0f;
    const int n = p->key_count;
    const float time = p->time[0] + u * (p->time[n - 1] - p->time[0]);
    int a = 0;
    while (a < n - 2 && time > p->time[a + 1]) ++a;
    const float s = (time - p->time[a]) / (p->time[a + 1] - p->time[a]);
    memset(out, 0, sizeof *out);
    interpolate(&p->eye[0][0], p->time, n, a, s, 3, out->eye, 3);
    interpolate(&p->target[0][0], p->time, n, a, s, 3, out->target, 3);
    out->fov_y_deg = p->fov[a] + s * (p->fov[a + 1] - p->fov[a]);
    out->up[1] = 1.0f;
    snprintf(out->name, sizeof out->name, "%s", p->name);
    return OB_OK;
}

ob_camera ob_camera_orbit(const ob_camera *camera, float degrees)
{
    ob_camera c = *camera;
    const float a = degrees * 0.01745329252f, ca = cosf(a), sa = sinf(a);
    const float dx = c.eye[0] - c.target[0], dz = c.eye[2] - c.target[2];
    c.eye[0] = c.target[0] + ca * dx + sa * dz;
    c.eye[2] = c.target[2] - sa * dx + ca * dz;
    return c;
}
