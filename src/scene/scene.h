/* Internal scene representation: what the importers produce and the G-buffer pass uploads. */
#ifndef OB_SCENE_INTERNAL_H
#define OB_SCENE_INTERNAL_H

#include "base/error.h"
#include "obscura/scene.h"

/* One draw: triangles that share a material. Arrays are malloc'd and owned by the mesh. */
typedef struct ob_mesh {
    float *positions;   /* xyz per vertex, world units, already in the scene's Y-up frame */
    float *normals;     /* xyz per vertex, unit length */
    float *uvs;         /* uv per vertex, or NULL */
    uint32_t *indices;  /* 3 per triangle, counter-clockwise seen from the front */
    uint32_t vertex_count;
    uint32_t index_count;
    int material;       /* index into ob_scene.materials */
} ob_mesh;

typedef struct ob_material {
    char name[64];
    float diffuse[3];        /* linear RGB */
    unsigned char *texture;  /* RGBA8, top row first, or NULL */
    int tex_width, tex_height;
    /* The pixels belong to an earlier material with the same pointer: materials naming one image
     * share one decode (import.c) and one GL texture (gbuffer.c); only the owner frees them. */
    bool texture_shared;
    char texture_name[96];   /* the image as the model names it ("wall.png", "*0"), for messages */
} ob_material;

#define OB_MAX_CAMERAS 32

/* A named camera path (sidecar "paths", scene/path.c). */
typedef struct ob_camera_path {
    char name[64];
    int key_count;                 /* 2..OB_MAX_PATH_KEYS */
    float time[OB_MAX_PATH_KEYS];  /* strictly increasing */
    float eye[OB_MAX_PATH_KEYS][3], target[OB_MAX_PATH_KEYS][3];
    float fov[OB_MAX_PATH_KEYS];   /* degrees */
} ob_camera_path;

struct ob_scene {
    char name[128];
    ob_mesh *meshes;
    int mesh_count;
    ob_material *materials;
    int material_count;
    ob_camera cameras[OB_MAX_CAMERAS]; /* [0] = "default", framing the bounds */
    int camera_count;
    ob_camera_path paths[OB_MAX_PATHS];
    int path_count;
    ob_light lights[OB_MAX_LIGHTS]; /* [0] = the key light */
    int light_count;
    float ao_radius;       /* suggested, world units */
    float bounds_min[3];
    float bounds_max[3];
};

/* Allocation helpers shared by the importers (scene.c). */
OB_EVAL_SHARED ob_scene *ob_scene_alloc(const char *name);
OB_EVAL_SHARED ob_mesh *ob_scene_add_mesh(ob_scene *s, uint32_t vertex_count, uint32_t index_count, bool uvs);
OB_EVAL_SHARED int ob_scene_add_material(ob_scene *s, const char *name, float r, float g, float b);
/* Add a camera preset after "default", replacing a preset of the same name ("default" itself
 * included). Returns false (and sets no error) when all OB_MAX_CAMERAS slots are in use. */
OB_EVAL_SHARED bool ob_scene_add_camera(ob_scene *s, const ob_camera *cam);
/* v scaled to unit length without overflow (src/core/lights.c); false for a zero or non-finite v. */
OB_EVAL_SHARED bool ob_normalize_direction(float v[3]);
/* After the meshes are in: bounds, default camera, default light and radius if unset. */
OB_EVAL_SHARED void ob_scene_finish(ob_scene *s);

/* Builders: return NULL with the error set (ob_peek_error) on failure. */
OB_EVAL_SHARED ob_scene *ob_scene_builtin(const char *name); /* NULL + OB_ERR_UNKNOWN_SCENE if not built in */
/* After ob_scene_finish: false (OB_ERR_MODEL naming source) when the bounds are not finite or
 * outside the range float depth and lighting handle (scene.c says why). */
OB_EVAL_SHARED bool ob_scene_check_bounds(const ob_scene *s, const char *source);

/* The connected parts of mesh m (scene/parts.c): labels[v] (vertex_count floats) gets vertex v's
 * part, numbered from `first` and folded into 1..OB_PART_LABELS, plus OB_PART_SHEET on a sheet's.
 * Returns the number of parts, or -1 (out of memory, error set). */
#define OB_PART_LABELS 2047u
/* Added to the label of a sheet's vertices: a part with holes in it, whose open edges form two
 * loops or more (a drilled plate, a grille), has no thickness (scene/parts.c). */
#define OB_PART_SHEET 4096u
/* A hole of a sheet candidate (a loop of its open edges other than its outline): its bounds in
 * the mesh's coordinates and its part's label (with OB_PART_SHEET). */
typedef struct ob_hole {
    float label;
    float lo[3], hi[3];
} ob_hole;
typedef struct ob_holes {
    ob_hole *items;
    size_t count, cap;
} ob_holes;
/* holes (may be NULL): the candidates' holes are appended (free items when done). */
int64_t ob_mesh_part_labels(const ob_mesh *m, uint32_t first, float *labels, ob_holes *holes);
/* The plane of triangle t (its first index): unit normal and offset, plane[0..2] . x = plane[3].
 * False for a triangle with no area or an index out of range. */
bool ob_triangle_plane(const ob_mesh *m, uint32_t t, double plane[4]);
/* Over the whole scene (scene/sheets.c): a part ob_mesh_part_labels marked a sheet stays one only
 * when no vertex of another part lies on its plane within one of its holes; the others lose
 * OB_PART_SHEET. labels[m] and holes[m] are mesh m's labels and holes. Returns the sheets left,
 * or -1 (out of memory, error set). */
int ob_scene_settle_sheets(const ob_scene *s, float *const *labels, const ob_holes *holes);

/* The default framing camera for bounds, looking from the front-above-right. */
ob_camera ob_camera_frame_bounds(const float bmin[3], const float bmax[3], float fov_y_deg);
/* Near/far planes that enclose the bounds from the camera's eye. */
void ob_camera_fit_planes(ob_camera *cam, const float bmin[3], const float bmax[3]);
/* lookAt and the OpenGL perspective (lens shift in P20, P21) of a camera whose defaults and planes
 * are filled in: what ob_render_frame and ob_camera_matrices draw with. Column-major. */
void ob_camera_view_proj(const ob_camera *cam, int width, int height, float view[16], float proj[16]);

#endif
