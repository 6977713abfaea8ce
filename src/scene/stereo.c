/* The two eyes of a headset (Belonogov 2018 §5.2: the HTC Vive, 1080x1200 per eye, in "Mirror" and
 * "SinglePass" modes).
 *
 * Parallel-axis asymmetric-frustum stereo (P. Bourke, "Calculating stereo pairs", 1999; the
 * "off-axis" model): both eyes look along the centre camera's forward vector, moved by -+ipd/2
 * along its right vector. Toed-in eyes (each turned toward the target) would make vertical
 * parallax away from the centre, which a viewer cannot fuse; parallel eyes with symmetric frusta
 * would put the zero-parallax plane at infinity. Instead each eye's frustum window is moved so
 * that both windows coincide on the convergence plane at distance D: in the left eye that plane's
 * centre lies ipd/2 to the right, i.e. at tan = ipd / (2 D), which is
 *     shift = (ipd / 2) / (D tan(fov_x / 2))
 * of the window's half-width (ob_camera.shift, P20). A point X on the plane then lands at
 * ndc = (X + ipd/2) / (D tan) - shift = X / (D tan) in the left eye and the same in the right.
 *
 * A headset's frustum is fixed by its optics instead: each eye's lens sits in front of its own
 * display half, and the runtime hands out the four tangents of its window (OpenVR
 * IVRSystem::GetProjectionRaw). The preset stores them as fov and shift. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "base/error.h"
#include "obscura/scene.h"

/* HTC Vive (the seed's headset): 1080x1200 pixels per eye (Belonogov 2018 §5.2), 64 mm ipd (the
 * population mean the seed's setup assumes). The per-eye frustum is OpenVR's GetProjectionRaw of a
 * Vive, left eye, as tangents of the half-angles (gamedev.net, "Projection matrix model of the HTC
 * Vive", 2016): left 1.39811385, right 1.24539280, up 1.45936251, down 1.47835493 (OpenVR calls
 * up "bottom": its tangents are y-down). So
 *     fov_y    = 2 atan((1.45936 + 1.47835) / 2)                   = 111.506 deg
 *     shift[0] = (right - left) / (right + left) = -0.15272 / 2.64351 = -0.057772  (P20: looks out)
 *     shift[1] = (up - down) / (up + down)       = -0.01899 / 2.93772 = -0.006465  (P21: a bit down)
 * matching that thread's GetProjectionMatrix (P20 -0.0577721, P21 -0.0064650). Width over height
 * of the window, 2.64351 / 2.93772 = 0.89985, is the panel's 1080/1200 = 0.9 to 0.02 %, so the
 * pixel aspect alone gives the horizontal extent (105.7 deg). The right eye mirrors the left. */
static const ob_headset headsets[] = {
    {.name = "vive",
     .description = "HTC Vive: 1080x1200 per eye, 111.5 deg vertical fov, frusta canted outward (OpenVR)",
     .width = 1080,
     .height = 1200,
     .ipd = 0.064f,
     .fov_y_deg = 111.50588f,
     .shift = {-0.0577721f, -0.0064650f}},
};

enum { HEADSET_COUNT = (int)(sizeof headsets / sizeof headsets[0]) };

int ob_headset_count(void) { return HEADSET_COUNT; }

const ob_headset *ob_headset_at(int index) { return index >= 0 && index < HEADSET_COUNT ? &headsets[index] : NULL; }

ob_error ob_find_headset(const char *name, ob_headset *out)
{
    if (!name || !out) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_find_headset: NULL argument");
    for (int i = 0; i < HEADSET_COUNT; ++i)
        if (!strcmp(name, headsets[i].name)) {
            *out = headsets[i];
            return OB_OK;
        }
    return ob_set_error(OB_ERR_INVALID_ARGUMENT, "unknown headset '%s' (known: vive)", name);
}

static bool finite_nonneg(float v) { return isfinite(v) && v >= 0.0f; }

ob_error ob_stereo_cameras(const ob_camera *centre, const ob_stereo_desc *desc, ob_camera eyes_out[2])
{
    if (!centre || !eyes_out) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_stereo_cameras: NULL argument");
    const ob_stereo_desc d = desc ? *desc : (ob_stereo_desc){0};
    ob_headset hs = {0};
    const bool has_headset = d.headset && d.headset[0];
    if (has_headset && ob_find_headset(d.headset, &hs) != OB_OK) return ob_peek_error(NULL);
    if (!finite_nonneg(d.ipd) || !finite_nonneg(d.convergence) || !finite_nonneg(d.aspect))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_stereo_cameras: ipd %g, convergence %g or aspect %g is "
                            "negative or not finite", (double)d.ipd, (double)d.convergence, (double)d.aspect);
    const float ipd = d.ipd > 0.0f ? d.ipd : has_headset ? hs.ipd : 0.064f;
    const float aspect = d.aspect > 0.0f ? d.aspect : has_headset ? (float)hs.width / (float)hs.height : 1.0f;

    float f[3] = {centre->target[0] - centre->eye[0], centre->target[1] - centre->eye[1],
                  centre->target[2] - centre->eye[2]};
    const float dist = sqrtf(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    if (!(dist > 0.0f) || !isfinite(dist))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_stereo_cameras: eye and target coincide or are not finite");
    float up[3] = {centre->up[0], centre->up[1], centre->up[2]};
    if (up[0] == 0.0f && up[1] == 0.0f && up[2] == 0.0f) up[1] = 1.0f;
    /* right = forward x up, as glm_lookat builds the view's +X. */
    float rt[3] = {f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0]};
    const float len = sqrtf(rt[0] * rt[0] + rt[1] * rt[1] + rt[2] * rt[2]);
    if (!(len > 1e-6f * dist))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_stereo_cameras: the view direction is parallel to up");

    const float fov = has_headset ? hs.fov_y_deg : centre->fov_y_deg > 0.0f ? centre->fov_y_deg : 60.0f;
    if (!(fov < 179.0f))
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_stereo_cameras: fov %g is not in (0, 179)", (double)fov);
    const float convergence = d.convergence > 0.0f ? d.convergence : dist;
    const float tan_x = aspect * tanf(0.5f * fov * 3.14159265358979f / 180.0f);
    /* Bourke's window shift (the file's header): the left eye's window moves right. */
    const float parallel_shift = 0.5f * ipd / (convergence * tan_x);
    for (int e = 0; e < 2; ++e) {
        const float side = e == 0 ? -1.0f : 1.0f;
        ob_camera *c = &eyes_out[e];
        *c = *centre;
        const float s = side * 0.5f * ipd / len;
        for (int k = 0; k < 3; ++k) {
            c->eye[k] += s * rt[k];
            c->target[k] += s * rt[k];
        }
        c->fov_y_deg = fov;
        if (has_headset) {
            c->shift[0] += side < 0.0f ? hs.shift[0] : -hs.shift[0];
            c->shift[1] += hs.shift[1];
        } else {
            c->shift[0] -= side * parallel_shift;
        }
        char name[sizeof c->name];
        snprintf(name, sizeof name, "%.40s-%s", centre->name[0] ? centre->name : "camera", e == 0 ? "left" : "right");
        memcpy(c->name, name, sizeof c->name);
    }
    return OB_OK;
}
