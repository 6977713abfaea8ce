/* Lights from text (the CLI's --light). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "obscura/obscura.h"

static bool parse_floats(const char *v, float *out, int n)
{
    const char *p = v;
    for (int i = 0; i < n; ++i) {
        char *end = NULL;
        double d = strtod(p, &end);
        if (end == p || !isfinite(d)) return false;
        out[i] = (float)d;
        if (i < n - 1) {
            if (*end != ',') return false;
            p = end + 1;
        } else if (*end != '\0') {
            return false;
        }
    }
    return true;
}

ob_error ob_parse_light(const char *text, ob_light *out)
{
    if (!text || !out) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "ob_parse_light: NULL argument");
    char buf[512];
    if (snprintf(buf, sizeof buf, "%s", text) >= (int)sizeof buf)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%.40s...' is too long", text);
    ob_light l = {.color = {1.0f, 1.0f, 1.0f}, .intensity = 1.0f, .spot_inner_deg = 20.0f, .spot_outer_deg = 30.0f};
    bool has_dir = false, has_pos = false;
    char *save = NULL;
    char *tok = strtok_r(buf, " ", &save);
    if (!tok) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%s': expected directional, point or spot", text);
    if (!strcmp(tok, "directional") || !strcmp(tok, "dir")) l.type = OB_LIGHT_DIRECTIONAL;
    else if (!strcmp(tok, "point")) l.type = OB_LIGHT_POINT;
    else if (!strcmp(tok, "spot")) l.type = OB_LIGHT_SPOT;
    else return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%s': unknown type '%s' (directional, point, spot)", text, tok);
    while ((tok = strtok_r(NULL, " ", &save)) != NULL) {
        char *eq = strchr(tok, '=');
        if (!eq) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%s': expected key=value, got '%s'", text, tok);
        *eq = '\0';
        const char *k = tok, *v = eq + 1;
        bool ok = true;
        if (!strcmp(k, "dir")) ok = parse_floats(v, l.direction, 3), has_dir = true;
        else if (!strcmp(k, "pos")) ok = parse_floats(v, l.position, 3), has_pos = true;
        else if (!strcmp(k, "color")) ok = parse_floats(v, l.color, 3) && l.color[0] >= 0.0f && l.color[1] >= 0.0f && l.color[2] >= 0.0f;
        else if (!strcmp(k, "intensity")) ok = parse_floats(v, &l.intensity, 1) && l.intensity >= 0.0f;
        else if (!strcmp(k, "range")) ok = parse_floats(v, &l.range, 1) && l.range > 0.0f;
        else if (!strcmp(k, "cone")) {
            float c[2] = {0.0f, 0.0f};
            ok = parse_floats(v, c, 2) && c[0] >= 0.0f && c[0] <= c[1] && c[1] < 90.0f;
            l.spot_inner_deg = c[0];
            l.spot_outer_deg = c[1];
        } else {
            return ob_set_error(OB_ERR_INVALID_ARGUMENT,
                                "light '%s': unknown key '%s' (dir, pos, color, intensity, range, cone)", text, k);
        }
        if (!ok) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%s': bad value for %s: '%s'", text, k, v);
    }
    if (l.type != OB_LIGHT_POINT) {
        if (!has_dir) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%s': needs dir=x,y,z", text);
        float len = sqrtf(l.direction[0] * l.direction[0] + l.direction[1] * l.direction[1] + l.direction[2] * l.direction[2]);
        if (!(len > 0.0f)) return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%s': dir is zero", text);
        for (int i = 0; i < 3; ++i) l.direction[i] /= len;
    }
    if (l.type != OB_LIGHT_DIRECTIONAL && !has_pos)
        return ob_set_error(OB_ERR_INVALID_ARGUMENT, "light '%s': needs pos=x,y,z", text);
    *out = l;
    return OB_OK;
}
