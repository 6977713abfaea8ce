/* Model import through Assimp's C API: every format Assimp reads becomes one ob_mesh per
 * material, in world space, Y-up, with unit normals and counter-clockwise front faces.
 *
 * The node tree is walked here instead of using aiProcess_PreTransformVertices, because glTF
 * cameras hang off nodes and need the same world transforms as the meshes; walking once for
 * both keeps cameras and geometry consistent by construction. */
#include "eval/import.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include <assimp/cfileio.h>
#include <assimp/cimport.h>
#include <assimp/importerdesc.h>
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <stb/stb_image.h>

#include "base/error.h"
#include "eval/model_io.h"

#define OB_PI_F 3.14159265358979f

/* Crease angle for aiProcess_GenSmoothNormals. Assimp's default (175 degrees) smooths across
 * the corners of walls and bends their normals, which darkens flat walls under AO (docs/architecture.md:
 * FZK-Haus mean ray-traced AO 0.78 instead of 0.90). Not 45 exactly: FZK-Haus joins its walls
 * with 45-degree mitre faces, and Assimp's test (cos >= cos limit) blends a 45-degree pair, which
 * tilts the inner face of every outer wall by up to 22.5 degrees across its whole width. 40
 * keeps those mitres hard and still smooths cylinders of 10 or more segments. */
#define OB_CREASE_ANGLE_DEG 40.0f

#define OB_PATH_MAX 4096

/* Per ob material: where the merged mesh is filled from. */
typedef struct mat_slot {
    uint64_t vertices;  /* pass 1: totals */
    uint64_t indices;
    bool uvs;
    ob_mesh *mesh;      /* pass 2: destination and fill cursors */
    uint32_t vfill, ifill;
} mat_slot;

typedef struct importer {
    const char *path;
    ob_model_fs *fs;    /* every external file goes through it (model_io.c) */
    uint64_t max_memory;
    bool max_memory_default; /* the caller gave none: the message says so */
    char dir[OB_PATH_MAX];
    const struct aiScene *ai;
    ob_scene *s;
    uint64_t reserved;  /* what the caller's run takes besides the scene (ob_scene_desc) */
    const char *reserved_what;
    int *mat_map;       /* assimp material index -> ob material index, -1 = not yet made */
    int *mat_source;    /* assimp material index -> im->sources index, -1 = none, -2 = not planned */
    struct tex_source *sources; /* at most one per assimp material */
    int source_count;
    mat_slot *slots;    /* by ob material index (at most ai->mNumMaterials of them) */
    int pass;           /* 1 = count, 2 = fill */
} importer;

/* ---- small matrix helpers (aiMatrix4x4 is row-major, translation in a4 b4 c4) ---------------- */

static struct aiMatrix4x4 mat_identity(void)
{
    struct aiMatrix4x4 m;
    aiIdentityMatrix4(&m);
    return m;
}

/* a * b */
static struct aiMatrix4x4 mat_mul(const struct aiMatrix4x4 *a, const struct aiMatrix4x4 *b)
{
    struct aiMatrix4x4 r = *a;
    aiMultiplyMatrix4(&r, b);
    return r;
}

static void xform_point(const struct aiMatrix4x4 *m, const struct aiVector3D *p, float out[3])
{
    out[0] = m->a1 * p->x + m->a2 * p->y + m->a3 * p->z + m->a4;
    out[1] = m->b1 * p->x + m->b2 * p->y + m->b3 * p->z + m->b4;
    out[2] = m->c1 * p->x + m->c2 * p->y + m->c3 * p->z + m->c4;
}

static void xform_dir(const struct aiMatrix4x4 *m, const struct aiVector3D *d, float out[3])
{
    out[0] = m->a1 * d->x + m->a2 * d->y + m->a3 * d->z;
    out[1] = m->b1 * d->x + m->b2 * d->y + m->b3 * d->z;
    out[2] = m->c1 * d->x + m->c2 * d->y + m->c3 * d->z;
}

/* Cofactor matrix of the upper 3x3 and its determinant: normals transform by the inverse
 * transpose, which is cofactor / det; the scale does not matter once normalised, the sign
 * does (a mirroring node flips normals). */
static float normal_matrix(const struct aiMatrix4x4 *m, float n[9])
{
    float a = m->a1, b = m->a2, c = m->a3;
    float d = m->b1, e = m->b2, f = m->b3;
    float g = m->c1, h = m->c2, i = m->c3;
    n[0] = e * i - f * h;
    n[1] = f * g - d * i;
    n[2] = d * h - e * g;
    n[3] = c * h - b * i;
    n[4] = a * i - c * g;
    n[5] = b * g - a * h;
    n[6] = b * f - c * e;
    n[7] = c * d - a * f;
    n[8] = a * e - b * d;
    return a * n[0] + b * n[1] + c * n[2];
}

static bool normalize3(float v[3])
{
    float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (!(len > 1e-20f) || !isfinite(len)) return false;
    v[0] /= len;
    v[1] /= len;
    v[2] /= len;
    return true;
}

/* Copy a (possibly long) Assimp string into a fixed field, cutting it to fit: names are labels,
 * a cut one is still useful. */
static void copy_name(char *dst, size_t n, const char *src)
{
    size_t len = 0;
    while (len + 1 < n && src[len]) ++len;
    memcpy(dst, src, len);
    dst[len] = '\0';
}

/* ---- materials and textures ------------------------------------------------------------------ */

/* One image the materials name. Every one is found and sized from its header before any is
 * decoded, so that the whole of them can be held against --max-memory (plan_textures), and each is
 * decoded once however many materials name it (a PNG of a few hundred kB can decode to 1 GiB:
 * four materials naming it were four decodes). */
typedef struct tex_source {
    int embedded;          /* index into ai->mTextures, or -1: a file */
    char *path;            /* the file as opened through the confinement (malloc'd) */
    char reference[96];    /* as the model names it: for messages and ob_material.texture_name */
    dev_t dev;             /* the file's identity: two spellings of one file are one source */
    ino_t ino;
    int width, height;     /* from the header */
    bool wide;             /* 16 bits per channel: the decoder holds more beside its result */
    int materials;         /* how many materials name it */
    bool tried;            /* decoded (or failed to) already */
    unsigned char *pixels; /* RGBA8, owned by the material `owner` once one takes it */
    int owner;             /* the ob material that owns pixels, -1 before */
} tex_source;

/* Bytes a source takes for the run: the decoded RGBA8 (kept by the scene), its GL_SRGB8_ALPHA8
 * copy with the mip chain (gbuffer.c; a software rasteriser keeps it in host memory too), and the
 * decoder's working memory beside its result while it runs (stb_image: the inflated rows and,
 * for 16-bit images, the 16-bit image before it is narrowed). */
static uint64_t source_bytes(const tex_source *t) { return (uint64_t)t->width * (uint64_t)t->height * 4u * 7u / 3u; }
static uint64_t source_work(const tex_source *t)
{
    return (uint64_t)t->width * (uint64_t)t->height * (t->wide ? 12u : 4u);
}

/* RGBA8 top-row-first from an Assimp embedded texture (compressed or raw BGRA texels). */
static unsigned char *load_embedded(const struct aiTexture *t, int *w, int *h)
{
    if (!t || !t->pcData) return NULL;
    if (t->mHeight == 0) {
        int comp = 0;
        if (t->mWidth > (unsigned)INT32_MAX) return NULL;
        return stbi_load_from_memory((const stbi_uc *)t->pcData, (int)t->mWidth, w, h, &comp, 4);
    }
    if (t->mWidth > 65536u || t->mHeight > 65536u) return NULL;
    size_t n = (size_t)t->mWidth * t->mHeight;
    unsigned char *px = malloc(n * 4u);
    if (!px) return NULL;
    for (size_t k = 0; k < n; ++k) {
        px[4 * k + 0] = t->pcData[k].r;
        px[4 * k + 1] = t->pcData[k].g;
        px[4 * k + 2] = t->pcData[k].b;
        px[4 * k + 3] = t->pcData[k].a;
    }
    *w = (int)t->mWidth;
    *h = (int)t->mHeight;
    return px;
}

/* An embedded texture's size without decoding it: the header of a compressed one, the counts of
 * a raw one. False when stb_image cannot read it (it would not decode either). */
static bool embedded_size(const struct aiTexture *t, int *w, int *h, bool *wide)
{
    int comp = 0;
    *wide = false;
    if (!t || !t->pcData) return false;
    if (t->mHeight == 0) {
        if (t->mWidth > (unsigned)INT32_MAX) return false;
        const stbi_uc *data = (const stbi_uc *)t->pcData;
        if (!stbi_info_from_memory(data, (int)t->mWidth, w, h, &comp)) return false;
        *wide = stbi_is_16_bit_from_memory(data, (int)t->mWidth) != 0;
        return true;
    }
    if (t->mWidth > 65536u || t->mHeight > 65536u) return false;
    *w = (int)t->mWidth;
    *h = (int)t->mHeight;
    return true;
}

/* The diffuse texture an Assimp material names, as text; false when it names none. */
static bool texture_reference(const struct aiMaterial *mat, char *name, size_t n)
{
    struct aiString tex = {0};
    enum aiReturn got = aiGetMaterialTexture(mat, aiTextureType_DIFFUSE, 0, &tex, NULL, NULL,
                                             NULL, NULL, NULL, NULL);
    /* glTF's base colour lands in DIFFUSE in Assimp 5.2, other PBR importers may use only
     * BASE_COLOR. */
    if (got != aiReturn_SUCCESS) {
        got = aiGetMaterialTexture(mat, aiTextureType_BASE_COLOR, 0, &tex, NULL, NULL, NULL, NULL,
                                   NULL, NULL);
    }
    if (got != aiReturn_SUCCESS || tex.length == 0) return false;
    snprintf(name, n, "%s", tex.data);
    return true;
}

/* The source a material's reference resolves to, added to im->sources when new: an embedded
 * texture ("*N", or (FBX, glb) one carrying the same file name), else a file through the
 * confinement, the first candidate stb_image can read (as the decoder tried them before). -1 when
 * it resolves to nothing stb_image can read (the material keeps its colour, as before), or when
 * the confinement refused a file (fs->refused says why: the import fails). */
static int find_source(importer *im, const char *reference)
{
    char name[OB_PATH_MAX] = "";
    snprintf(name, sizeof name, "%s", reference);
    tex_source t = {.embedded = -1, .owner = -1};
    int embedded = -1;
    if (name[0] == '*') {
        char *end = NULL;
        long idx = strtol(name + 1, &end, 10);
        if (!end || *end != '\0' || idx < 0 || (unsigned long)idx >= im->ai->mNumTextures) return -1;
        embedded = (int)idx;
    } else {
        for (unsigned k = 0; k < im->ai->mNumTextures && embedded < 0; ++k) {
            const struct aiTexture *e = im->ai->mTextures[k];
            if (e && e->mFilename.length && strcmp(e->mFilename.data, name) == 0) embedded = (int)k;
        }
    }
    if (embedded >= 0) {
        for (int k = 0; k < im->source_count; ++k)
            if (im->sources[k].embedded == embedded) return k;
        const struct aiTexture *e = im->ai->mTextures[embedded];
        if (embedded_size(e, &t.width, &t.height, &t.wide)) {
            t.embedded = embedded;
            /* glb images carry no file name: say which image it is. */
            if (name[0] != '*') copy_name(t.reference, sizeof t.reference, name);
            else if (e && e->mFilename.length) copy_name(t.reference, sizeof t.reference, e->mFilename.data);
            else snprintf(t.reference, sizeof t.reference, "embedded image %d", embedded);
        } else if (name[0] == '*') {
            return -1;
        }
    }
    if (t.embedded < 0) {
        /* External file, with Windows separators made portable. Exporters often store an absolute
         * path from the author's machine: the file name beside the model is tried first for those,
         * and the absolute path (refused unless --allow-external-files, when it exists) only
         * after. */
        for (char *c = name; *c; ++c) {
            if (*c == '\\') *c = '/';
        }
        const char *base = strrchr(name, '/');
        char full[OB_PATH_MAX * 2] = "";
        const char *tries[2] = {name, NULL};
        if (name[0] == '/') {
            tries[0] = base + 1;
            tries[1] = name;
        } else if (base) {
            tries[1] = base + 1;
        }
        bool found = false;
        struct stat st = {0};
        for (int k = 0; k < 2 && tries[k] && !found && !im->fs->refused[0]; ++k) {
            if (tries[k][0] == '/') snprintf(full, sizeof full, "%s", tries[k]);
            else snprintf(full, sizeof full, "%s/%s", im->dir, tries[k]);
            FILE *f = ob_model_fs_open(im->fs, full, tries[k]);
            if (!f) continue;
            int comp = 0;
            found = fstat(fileno(f), &st) == 0 && stbi_info_from_file(f, &t.width, &t.height, &comp);
            t.wide = found && stbi_is_16_bit_from_file(f) != 0;
            fclose(f);
            if (found) copy_name(t.reference, sizeof t.reference, tries[k]);
        }
        if (!found) return -1;
        t.dev = st.st_dev;
        t.ino = st.st_ino;
        for (int k = 0; k < im->source_count; ++k)
            if (im->sources[k].embedded < 0 && im->sources[k].dev == t.dev && im->sources[k].ino == t.ino) return k;
        size_t len = strlen(full) + 1;
        t.path = malloc(len);
        if (!t.path) return -1;
        memcpy(t.path, full, len);
    }
    if (t.width <= 0 || t.height <= 0) {
        free(t.path);
        return -1;
    }
    im->sources[im->source_count] = t;
    return im->source_count++;
}

/* "1.50 GiB", "20.0 MiB", "12 KiB": for the messages. */
static const char *human(uint64_t bytes, char *buf, size_t n)
{
    if (bytes >= (1ull << 30)) snprintf(buf, n, "%.2f GiB", (double)bytes / (double)(1ull << 30));
    else if (bytes >= (1ull << 20)) snprintf(buf, n, "%.1f MiB", (double)bytes / (double)(1ull << 20));
    else snprintf(buf, n, "%llu KiB", (unsigned long long)((bytes + 1023u) / 1024u));
    return buf;
}

static uint32_t triangle_count(const struct aiMesh *mesh);

/* Every texture the used materials name, found and sized before any is decoded; then the
 * textures, the geometry (what check_raw_scene estimated) and what the caller reserved against
 * max_memory. False with OB_ERR_MODEL naming the largest items when over, or when the
 * confinement refused a texture (the caller reports fs->refused). */
static bool plan_textures(importer *im, uint64_t geometry)
{
    const struct aiScene *ai = im->ai;
    for (unsigned m = 0; m < ai->mNumMeshes; ++m) {
        const struct aiMesh *mesh = ai->mMeshes[m];
        if (!mesh || triangle_count(mesh) == 0) continue;
        unsigned k = mesh->mMaterialIndex < ai->mNumMaterials ? mesh->mMaterialIndex : 0u;
        if (im->mat_source[k] != -2) continue; /* planned */
        char reference[OB_PATH_MAX] = "";
        int source = -1;
        if (texture_reference(ai->mMaterials[k], reference, sizeof reference)) source = find_source(im, reference);
        if (im->fs->refused[0]) return false;
        im->mat_source[k] = source;
        if (source >= 0) ++im->sources[source].materials;
    }
    uint64_t textures = 0, work = 0;
    for (int k = 0; k < im->source_count; ++k) {
        textures += source_bytes(&im->sources[k]);
        if (source_work(&im->sources[k]) > work) work = source_work(&im->sources[k]);
    }
    textures += work;
    uint64_t need = geometry + textures + im->reserved;
    if (need <= im->max_memory) return true;

    /* The items, largest first; the textures by the three largest images. */
    char list[2048] = "", a[32] = "", b[32] = "";
    int order[3] = {-1, -1, -1};
    for (int k = 0; k < im->source_count; ++k) {
        for (int slot = 0; slot < 3; ++slot) {
            if (order[slot] < 0 || source_bytes(&im->sources[k]) > source_bytes(&im->sources[order[slot]])) {
                for (int j = 2; j > slot; --j) order[j] = order[j - 1];
                order[slot] = k;
                break;
            }
        }
    }
    char tex[512] = "";
    for (int slot = 0; slot < 3 && order[slot] >= 0; ++slot) {
        const tex_source *t = &im->sources[order[slot]];
        size_t len = strlen(tex);
        snprintf(tex + len, sizeof tex - len, "%s%s %dx%d", slot ? ", " : "", t->reference, t->width, t->height);
        len = strlen(tex);
        if (t->materials > 1) snprintf(tex + len, sizeof tex - len, " x%d materials", t->materials);
    }
    if (im->source_count > 3) {
        size_t len = strlen(tex);
        snprintf(tex + len, sizeof tex - len, ", %d more", im->source_count - 3);
    }
    typedef struct item {
        uint64_t bytes;
        char text[600];
    } item;
    item items[3] = {{0, ""}, {0, ""}, {0, ""}};
    snprintf(items[0].text, sizeof items[0].text, "textures %s (each decoded once: %s)", human(textures, a, sizeof a), tex);
    items[0].bytes = textures;
    snprintf(items[1].text, sizeof items[1].text, "geometry %s", human(geometry, a, sizeof a));
    items[1].bytes = geometry;
    if (im->reserved_what && im->reserved_what[0]) snprintf(items[2].text, sizeof items[2].text, "%s", im->reserved_what);
    else snprintf(items[2].text, sizeof items[2].text, "the rest of the run %s", human(im->reserved, a, sizeof a));
    items[2].bytes = im->reserved;
    for (int i = 0; i < 3; ++i) {
        int best = i;
        for (int j = i + 1; j < 3; ++j)
            if (items[j].bytes > items[best].bytes) best = j;
        if (best != i) {
            item keep = items[i];
            items[i] = items[best];
            items[best] = keep;
        }
        if (items[i].bytes == 0 && i > 0) break;
        size_t len = strlen(list);
        snprintf(list + len, sizeof list - len, "%s%s", i ? ", " : "", items[i].text);
    }
    ob_set_error(OB_ERR_MODEL, "%s: this run needs about %s, more than --max-memory %s%s: %s", im->path,
                 human(need, a, sizeof a), human(im->max_memory, b, sizeof b),
                 im->max_memory_default ? " (the default)" : "", list);
    return false;
}

/* The diffuse texture of an Assimp material, decoded once per source: a later material naming
 * the same image shares the pixels (out->texture_shared). A texture that cannot be found or
 * decoded is not fatal: the material keeps its colour. */
static void load_texture(importer *im, unsigned ai_index, ob_material *out)
{
    int source = im->mat_source[ai_index];
    if (source < 0) return;
    tex_source *t = &im->sources[source];
    copy_name(out->texture_name, sizeof out->texture_name, t->reference);
    if (t->tried) {
        if (t->pixels && t->owner >= 0) {
            out->texture = t->pixels;
            out->tex_width = t->width;
            out->tex_height = t->height;
            out->texture_shared = true;
        }
        return;
    }
    t->tried = true;
    int w = 0, h = 0, comp = 0;
    unsigned char *px = NULL;
    if (t->embedded >= 0) {
        px = load_embedded(im->ai->mTextures[t->embedded], &w, &h);
    } else {
        FILE *f = ob_model_fs_open(im->fs, t->path, t->reference);
        /* The size planned is the size decoded: a file changed since is not decoded. */
        if (f && stbi_info_from_file(f, &w, &h, &comp) && w == t->width && h == t->height)
            px = stbi_load_from_file(f, &w, &h, &comp, 4);
        if (f) fclose(f);
    }
    if (px && w == t->width && h == t->height) {
        t->pixels = px;
        out->texture = px;
        out->tex_width = w;
        out->tex_height = h;
    } else {
        free(px);
    }
}

/* The ob material for an Assimp material index, made on first use so materials no triangle
 * uses (OBJ's unused "blue", Assimp's DefaultMaterial) do not appear. */
static int map_material(importer *im, unsigned ai_index)
{
    if (ai_index >= im->ai->mNumMaterials) ai_index = 0;
    if (im->mat_map[ai_index] >= 0) return im->mat_map[ai_index];
    const struct aiMaterial *mat = im->ai->mMaterials[ai_index];
    struct aiString name = {0};
    char label[64] = "";
    if (aiGetMaterialString(mat, AI_MATKEY_NAME, &name) == aiReturn_SUCCESS && name.length) {
        copy_name(label, sizeof label, name.data);
    } else {
        snprintf(label, sizeof label, "material%u", ai_index);
    }
    /* 0.8 grey when the file gives no colour: bright enough to show AO, not pure white. */
    struct aiColor4D c = {0.8f, 0.8f, 0.8f, 1.0f};
    if (aiGetMaterialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &c) != aiReturn_SUCCESS) {
        c.r = c.g = c.b = 0.8f;
    }
    ob_material probe = {0};
    load_texture(im, ai_index, &probe);
    /* IFC gives every building element its own copy of a material ("Kiefer" 40 times on
     * FZK-Haus): copies with the same name and colour and no texture share one mesh, which
     * turns hundreds of draws into a dozen. */
    if (!probe.texture) {
        for (int k = 0; k < im->s->material_count; ++k) {
            const ob_material *m = &im->s->materials[k];
            if (!m->texture && strcmp(m->name, label) == 0 && m->diffuse[0] == c.r &&
                m->diffuse[1] == c.g && m->diffuse[2] == c.b) {
                im->mat_map[ai_index] = k;
                return k;
            }
        }
    }
    int idx = ob_scene_add_material(im->s, label, c.r, c.g, c.b);
    if (idx < 0) {
        if (probe.texture && !probe.texture_shared) {
            /* Nobody took the pixels: a later material must not share freed ones. */
            im->sources[im->mat_source[ai_index]].pixels = NULL;
            free(probe.texture);
        }
        return -1;
    }
    ob_material *m = &im->s->materials[idx];
    m->texture = probe.texture;
    m->tex_width = probe.tex_width;
    m->tex_height = probe.tex_height;
    m->texture_shared = probe.texture_shared;
    memcpy(m->texture_name, probe.texture_name, sizeof m->texture_name);
    if (probe.texture && !probe.texture_shared) im->sources[im->mat_source[ai_index]].owner = idx;
    im->mat_map[ai_index] = idx;
    return idx;
}

/* ---- geometry -------------------------------------------------------------------------------- */

static uint32_t triangle_count(const struct aiMesh *mesh)
{
    if (!(mesh->mPrimitiveTypes & aiPrimitiveType_TRIANGLE) || !mesh->mVertices) return 0;
    uint32_t n = 0;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
        if (mesh->mFaces[f].mNumIndices == 3) ++n;
    }
    return n;
}

/* Area-weighted vertex normals for a mesh that came through without any. */
static void fallback_normals(const struct aiMesh *mesh, float *nrm)
{
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
        const struct aiFace *face = &mesh->mFaces[f];
        if (face->mNumIndices != 3) continue;
        const struct aiVector3D *a = &mesh->mVertices[face->mIndices[0]];
        const struct aiVector3D *b = &mesh->mVertices[face->mIndices[1]];
        const struct aiVector3D *c = &mesh->mVertices[face->mIndices[2]];
        float e1[3] = {b->x - a->x, b->y - a->y, b->z - a->z};
        float e2[3] = {c->x - a->x, c->y - a->y, c->z - a->z};
        float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                      e1[0] * e2[1] - e1[1] * e2[0]};
        for (int k = 0; k < 3; ++k) {
            for (int i = 0; i < 3; ++i) nrm[3u * face->mIndices[k] + (unsigned)i] += n[i];
        }
    }
}

static bool add_mesh(importer *im, const struct aiMesh *mesh, const struct aiMatrix4x4 *world)
{
    uint32_t tris = triangle_count(mesh);
    if (tris == 0) return true;
    int mat = map_material(im, mesh->mMaterialIndex);
    if (mat < 0) return false;
    mat_slot *slot = &im->slots[mat];

    if (im->pass == 1) {
        slot->vertices += mesh->mNumVertices;
        slot->indices += 3u * (uint64_t)tris;
        if (mesh->mTextureCoords[0]) slot->uvs = true;
        return true;
    }

    ob_mesh *out = slot->mesh;
    uint32_t base = slot->vfill;
    float nm[9] = {0.0f};
    float det = normal_matrix(world, nm);
    float sign = det < 0.0f ? -1.0f : 1.0f;
    float *fallback = NULL;
    if (!mesh->mNormals) {
        fallback = calloc((size_t)mesh->mNumVertices * 3u, sizeof(float));
        if (!fallback) {
            ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: out of memory computing normals", im->path);
            return false;
        }
        fallback_normals(mesh, fallback);
    }
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
        float *p = &out->positions[3u * (base + v)];
        float *n = &out->normals[3u * (base + v)];
        xform_point(world, &mesh->mVertices[v], p);
        float ln[3] = {0.0f, 0.0f, 0.0f};
        if (mesh->mNormals) {
            ln[0] = mesh->mNormals[v].x;
            ln[1] = mesh->mNormals[v].y;
            ln[2] = mesh->mNormals[v].z;
        } else {
            ln[0] = fallback[3u * v];
            ln[1] = fallback[3u * v + 1u];
            ln[2] = fallback[3u * v + 2u];
        }
        for (int i = 0; i < 3; ++i) {
            n[i] = sign * (nm[3 * i] * ln[0] + nm[3 * i + 1] * ln[1] + nm[3 * i + 2] * ln[2]);
        }
        /* Vertices of degenerate faces get no usable normal from Assimp; any unit vector is
         * harmless there because their triangles cover no pixels. */
        if (!normalize3(n)) {
            n[0] = 0.0f;
            n[1] = 1.0f;
            n[2] = 0.0f;
        }
        if (out->uvs && mesh->mTextureCoords[0]) {
            out->uvs[2u * (base + v)] = mesh->mTextureCoords[0][v].x;
            out->uvs[2u * (base + v) + 1u] = mesh->mTextureCoords[0][v].y;
        }
    }
    free(fallback);
    /* A mirroring transform turns counter-clockwise faces clockwise: swap two corners back. */
    bool flip = det < 0.0f;
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
        const struct aiFace *face = &mesh->mFaces[f];
        if (face->mNumIndices != 3) continue;
        uint32_t *dst = &out->indices[slot->ifill];
        dst[0] = base + face->mIndices[0];
        dst[1] = base + face->mIndices[flip ? 2 : 1];
        dst[2] = base + face->mIndices[flip ? 1 : 2];
        slot->ifill += 3u;
    }
    slot->vfill += mesh->mNumVertices;
    return true;
}

static bool walk(importer *im, const struct aiNode *node, const struct aiMatrix4x4 *parent)
{
    struct aiMatrix4x4 world = mat_mul(parent, &node->mTransformation);
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
        unsigned mi = node->mMeshes[k];
        if (mi < im->ai->mNumMeshes && !add_mesh(im, im->ai->mMeshes[mi], &world)) return false;
    }
    for (unsigned k = 0; k < node->mNumChildren; ++k) {
        if (!walk(im, node->mChildren[k], &world)) return false;
    }
    return true;
}

/* World transform of the node called name (depth first), or false when there is none. */
static bool find_node(const struct aiNode *node, const char *name,
                      const struct aiMatrix4x4 *parent, struct aiMatrix4x4 *out)
{
    struct aiMatrix4x4 world = mat_mul(parent, &node->mTransformation);
    if (strcmp(node->mName.data, name) == 0) {
        *out = world;
        return true;
    }
    for (unsigned k = 0; k < node->mNumChildren; ++k) {
        if (find_node(node->mChildren[k], name, &world, out)) return true;
    }
    return false;
}

static const struct aiNode *find_node_ptr(const struct aiNode *node, const char *name)
{
    if (strcmp(node->mName.data, name) == 0) return node;
    for (unsigned k = 0; k < node->mNumChildren; ++k) {
        const struct aiNode *found = find_node_ptr(node->mChildren[k], name);
        if (found) return found;
    }
    return NULL;
}

/* Cameras stored in the file (glTF, FBX, Collada) become presets after "default". */
static void add_cameras(importer *im, const struct aiMatrix4x4 *up_fix)
{
    ob_scene *s = im->s;
    for (unsigned k = 0; k < im->ai->mNumCameras; ++k) {
        const struct aiCamera *c = im->ai->mCameras[k];
        /* ob_camera is perspective only. */
        if (c->mOrthographicWidth > 0.0f || !(c->mHorizontalFOV > 0.0f)) continue;
        struct aiMatrix4x4 world = *up_fix;
        if (!find_node(im->ai->mRootNode, c->mName.data, up_fix, &world)) world = *up_fix;

        /* Assimp 5.2's glTF2 importer copies the node's translation into mPosition although the
         * node transform already holds it, which would place the camera twice as far out. A
         * local position equal to the node's own translation is taken as that copy. */
        struct aiVector3D local = c->mPosition;
        const struct aiNode *node = find_node_ptr(im->ai->mRootNode, c->mName.data);
        if (node && local.x == node->mTransformation.a4 && local.y == node->mTransformation.b4 &&
            local.z == node->mTransformation.c4) {
            local.x = local.y = local.z = 0.0f;
        }

        ob_camera cam = {0};
        float dir[3] = {0.0f, 0.0f, 0.0f};
        xform_point(&world, &local, cam.eye);
        xform_dir(&world, &c->mLookAt, dir);
        xform_dir(&world, &c->mUp, cam.up);
        if (!normalize3(dir)) continue;
        if (!normalize3(cam.up)) {
            cam.up[0] = 0.0f;
            cam.up[1] = 1.0f;
            cam.up[2] = 0.0f;
        }
        /* mLookAt is a direction; put the target about as far away as the scene's centre, so an
         * orbiting viewer turns around something sensible. */
        float dist = 0.0f;
        for (int i = 0; i < 3; ++i) {
            float d = 0.5f * (s->bounds_min[i] + s->bounds_max[i]) - cam.eye[i];
            dist += d * d;
        }
        dist = sqrtf(dist);
        if (!(dist > 1e-3f * s->ao_radius) || !isfinite(dist)) dist = 1.0f;
        for (int i = 0; i < 3; ++i) cam.target[i] = cam.eye[i] + dir[i] * dist;

        /* Assimp stores the horizontal fov; aspect 0 means unknown, taken as square. */
        float aspect = c->mAspect > 0.0f ? c->mAspect : 1.0f;
        float vfov = 2.0f * atanf(tanf(0.5f * c->mHorizontalFOV) / aspect) * 180.0f / OB_PI_F;
        cam.fov_y_deg = vfov > 1.0f && vfov < 179.0f ? vfov : 60.0f;

        if (c->mName.length) {
            copy_name(cam.name, sizeof cam.name, c->mName.data);
        } else {
            snprintf(cam.name, sizeof cam.name, "camera%u", k);
        }
        /* "default" is the framing camera's name; keep a file camera of that name apart. */
        if (strcmp(cam.name, "default") == 0) snprintf(cam.name, sizeof cam.name, "camera%u", k);
        if (!ob_scene_add_camera(s, &cam)) break;
    }
}

/* Lights stored in the file (glTF KHR_lights_punctual, FBX, Collada) replace the default light.
 * glTF intensities are photometric (lux, candela); they are taken as they are, so a file lit for
 * a physical camera wants --exposure or the automatic HDR key. */
static void add_lights(importer *im, const struct aiMatrix4x4 *up_fix)
{
    ob_scene *s = im->s;
    int count = 0;
    for (unsigned k = 0; k < im->ai->mNumLights && count < OB_MAX_LIGHTS; ++k) {
        const struct aiLight *l = im->ai->mLights[k];
        ob_light out = {0};
        if (l->mType == aiLightSource_DIRECTIONAL) out.type = OB_LIGHT_DIRECTIONAL;
        else if (l->mType == aiLightSource_POINT) out.type = OB_LIGHT_POINT;
        else if (l->mType == aiLightSource_SPOT) out.type = OB_LIGHT_SPOT;
        else continue; /* area and ambient lights have no place here */
        struct aiMatrix4x4 world = *up_fix;
        if (!find_node(im->ai->mRootNode, l->mName.data, up_fix, &world)) world = *up_fix;
        /* As with cameras, assimp's glTF2 importer may copy the node translation into mPosition. */
        struct aiVector3D local = l->mPosition;
        const struct aiNode *node = find_node_ptr(im->ai->mRootNode, l->mName.data);
        if (node && local.x == node->mTransformation.a4 && local.y == node->mTransformation.b4 &&
            local.z == node->mTransformation.c4) {
            local.x = local.y = local.z = 0.0f;
        }
        float dir[3] = {0.0f, 0.0f, -1.0f};
        xform_point(&world, &local, out.position);
        xform_dir(&world, &l->mDirection, dir);
        if (out.type != OB_LIGHT_POINT && !normalize3(dir)) continue;
        for (int i = 0; i < 3; ++i) {
            /* ob_light's directional vector points toward the light; assimp's along the light. */
            out.direction[i] = out.type == OB_LIGHT_DIRECTIONAL ? -dir[i] : dir[i];
        }
        float peak = fmaxf(l->mColorDiffuse.r, fmaxf(l->mColorDiffuse.g, l->mColorDiffuse.b));
        if (!(peak > 0.0f)) continue;
        out.intensity = peak;
        out.color[0] = l->mColorDiffuse.r / peak;
        out.color[1] = l->mColorDiffuse.g / peak;
        out.color[2] = l->mColorDiffuse.b / peak;
        /* Assimp documents full cone angles, but its glTF2 importer passes on glTF's half-angles
         * (innerConeAngle, outerConeAngle) unchanged; checked with a glTF in test_scene.c. */
        const char *ext = strrchr(im->path, '.');
        bool half_angles = ext && (!strcasecmp(ext, ".gltf") || !strcasecmp(ext, ".glb"));
        float to_half = half_angles ? 1.0f : 0.5f;
        out.spot_inner_deg = to_half * l->mAngleInnerCone * 180.0f / OB_PI_F;
        out.spot_outer_deg = to_half * l->mAngleOuterCone * 180.0f / OB_PI_F;
        if (!(out.spot_outer_deg > 0.0f && out.spot_outer_deg < 90.0f)) out.spot_outer_deg = 45.0f;
        if (!(out.spot_inner_deg >= 0.0f && out.spot_inner_deg <= out.spot_outer_deg)) out.spot_inner_deg = out.spot_outer_deg;
        s->lights[count++] = out;
    }
    if (count > 0) s->light_count = count;
}

/* ---- Quake 3 maps ---------------------------------------------------------------------------- */

/* Assimp reads Quake 3 maps (Q3BSP) only from a .pk3 archive, and only the first map in it. */
static bool is_q3bsp(const char *path)
{
    const char *ext = strrchr(path, '.');
    return ext && strcasecmp(ext, ".pk3") == 0;
}

/* Assimp 5.2.5's Q3BSP importer writes every triangle's three vertices in order (mNumVertices is
 * 3 * mNumFaces) but leaves the faces' indices mostly unwritten, which ValidateDataStructure
 * rejects ("mIndices[0] is out of range") and every other step would read as garbage. Quake
 * also winds front faces clockwise. Rewrite each face as 3f, 3f+2, 3f+1: sequential and
 * counter-clockwise. Runs before any post-processing, on the importer's own scene. */
static bool repair_q3bsp(struct aiScene *ai, const char *path)
{
    for (unsigned m = 0; m < ai->mNumMeshes; ++m) {
        struct aiMesh *mesh = ai->mMeshes[m];
        if (!mesh || mesh->mNumFaces == 0) continue;
        if ((uint64_t)mesh->mNumVertices != 3u * (uint64_t)mesh->mNumFaces) {
            /* Not the layout the fix assumes (a later Assimp may have changed it): refuse
             * rather than draw triangles between unrelated vertices. */
            ob_set_error(OB_ERR_MODEL, "%s: Q3BSP mesh %u has %u vertices for %u faces", path, m,
                         mesh->mNumVertices, mesh->mNumFaces);
            return false;
        }
        for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
            struct aiFace *face = &mesh->mFaces[f];
            if (face->mNumIndices != 3 || !face->mIndices) {
                ob_set_error(OB_ERR_MODEL, "%s: Q3BSP mesh %u face %u is not a triangle", path,
                             m, f);
                return false;
            }
            face->mIndices[0] = 3u * f;
            face->mIndices[1] = 3u * f + 2u;
            face->mIndices[2] = 3u * f + 1u;
        }
    }
    return true;
}

/* ---- entry ----------------------------------------------------------------------------------- */

static ob_scene *import_scene(importer *im, ob_up_axis up)
{
    const struct aiScene *ai = im->ai;
    /* Z-up to Y-up: (x, y, z) -> (x, z, -y), a rotation (det +1), so winding is kept. */
    struct aiMatrix4x4 up_fix = mat_identity();
    if (up == OB_UP_Z) {
        up_fix.b2 = 0.0f;
        up_fix.b3 = 1.0f;
        up_fix.c2 = -1.0f;
        up_fix.c3 = 0.0f;
    }

    if (!ai->mRootNode) {
        ob_set_error(OB_ERR_MODEL, "%s: the file has no scene graph", im->path);
        return NULL;
    }
    im->pass = 1;
    if (!walk(im, ai->mRootNode, &up_fix)) return NULL;

    uint64_t total = 0;
    for (int m = 0; m < im->s->material_count; ++m) total += im->slots[m].indices;
    if (total == 0) {
        ob_set_error(OB_ERR_MODEL, "%s: no triangles in the file", im->path);
        return NULL;
    }
    for (int m = 0; m < im->s->material_count; ++m) {
        mat_slot *slot = &im->slots[m];
        if (slot->indices == 0) continue;
        if (slot->vertices > UINT32_MAX || slot->indices > UINT32_MAX) {
            ob_set_error(OB_ERR_MODEL, "%s: material '%s' has more than 2^32 vertices", im->path,
                         im->s->materials[m].name);
            return NULL;
        }
        slot->mesh = ob_scene_add_mesh(im->s, (uint32_t)slot->vertices, (uint32_t)slot->indices,
                                       slot->uvs);
        if (!slot->mesh) return NULL;
        slot->mesh->material = m;
    }
    /* ob_scene_add_mesh may have moved the mesh array: look the meshes up again. */
    int next = 0;
    for (int m = 0; m < im->s->material_count; ++m) {
        if (im->slots[m].indices != 0) im->slots[m].mesh = &im->s->meshes[next++];
    }
    im->pass = 2;
    if (!walk(im, ai->mRootNode, &up_fix)) return NULL;

    ob_scene_finish(im->s);
    add_cameras(im, &up_fix);
    add_lights(im, &up_fix);
    return im->s;
}

/* Assimp's message (raw) with what failed: the importer (format) and the file. */
static void fail_assimp(const char *path, const ob_model_fs *fs, const char *raw)
{
    if (fs->refused[0]) {
        ob_set_error(OB_ERR_MODEL, "%s: refers to %s", path, fs->refused);
        return;
    }
    const char *ext = strrchr(path, '.');
    const struct aiImporterDesc *desc = ext && !strchr(ext, '/') ? aiGetImporterDesc(ext + 1) : NULL;
    char who[160] = "";
    if (desc && desc->mName) snprintf(who, sizeof who, "Assimp's %s", desc->mName);
    else snprintf(who, sizeof who, "Assimp");
    if (raw && strstr(raw, "bad_alloc")) {
        ob_set_error(OB_ERR_MODEL, "%s: %s ran out of memory reading it (corrupt counts?)", path, who);
    } else {
        ob_set_error(OB_ERR_MODEL, "%s: %s could not import it: %s", path, who, raw && raw[0] ? raw : "no reason given");
    }
}

/* A raw scene (no post-processing): finite positions (Assimp's FindInvalidData drops a mesh with
 * a NaN and then reports "No meshes remaining"), and the memory post-processing and our copy
 * take, from the counts Assimp actually read (model_io.c cannot see into pk3 archives). */
static bool check_raw_scene(const struct aiScene *ai, const char *path, uint64_t max_memory, bool check_faces,
                            uint64_t *geometry)
{
    uint64_t vertices = 0, indices = 0;
    for (unsigned m = 0; m < ai->mNumMeshes; ++m) {
        const struct aiMesh *mesh = ai->mMeshes[m];
        if (!mesh) continue;
        vertices += mesh->mNumVertices;
        for (unsigned f = 0; mesh->mFaces && f < mesh->mNumFaces; ++f) indices += mesh->mFaces[f].mNumIndices;
        /* Debian's Assimp keeps its assertions: a face with no corner (a PLY whose face lines
         * are cut short, found by tests/fuzz/fuzz_model.c) aborts the process in
         * TriangulateProcess before ValidateDataStructure can refuse it. */
        if (check_faces && ((mesh->mNumFaces && !mesh->mFaces) || (mesh->mNumVertices && !mesh->mVertices))) {
            ob_set_error(OB_ERR_MODEL, "%s: mesh %u has no face or vertex array (corrupt file)", path, m);
            return false;
        }
        for (unsigned f = 0; check_faces && f < mesh->mNumFaces; ++f) {
            const struct aiFace *face = &mesh->mFaces[f];
            if (face->mNumIndices == 0 || !face->mIndices) {
                ob_set_error(OB_ERR_MODEL, "%s: mesh %u face %u has no vertices (corrupt or cut-short file)", path, m, f);
                return false;
            }
            for (unsigned k = 0; k < face->mNumIndices; ++k) {
                if (face->mIndices[k] >= mesh->mNumVertices) {
                    ob_set_error(OB_ERR_MODEL, "%s: mesh %u face %u names vertex %u of %u (corrupt file)", path, m, f,
                                 face->mIndices[k], mesh->mNumVertices);
                    return false;
                }
            }
        }
        for (unsigned v = 0; mesh->mVertices && v < mesh->mNumVertices; ++v) {
            const struct aiVector3D *p = &mesh->mVertices[v];
            if (!isfinite(p->x) || !isfinite(p->y) || !isfinite(p->z)) {
                ob_set_error(OB_ERR_MODEL, "%s: mesh %u ('%s') vertex %u has a non-finite coordinate (%g, %g, %g)", path,
                             m, mesh->mName.data, v, (double)p->x, (double)p->y, (double)p->z);
                return false;
            }
        }
    }
    uint64_t need = ob_model_estimate_peak(vertices, indices);
    *geometry = need;
    if (need > max_memory) {
        ob_set_error(OB_ERR_MODEL, "%s: its %llu vertices would take about %.2f GiB to import, more than the limit of %.2f GiB (--max-memory)",
                     path, (unsigned long long)vertices, (double)need / (double)(1ull << 30),
                     (double)max_memory / (double)(1ull << 30));
        return false;
    }
    return true;
}

ob_scene *ob_scene_import(const char *path, ob_up_axis up, bool allow_external_files, uint64_t max_memory)
{
    return ob_scene_import_within(path, up, allow_external_files, max_memory, 0, NULL);
}

ob_scene *ob_scene_import_within(const char *path, ob_up_axis up, bool allow_external_files, uint64_t max_memory,
                                 uint64_t reserved, const char *reserved_what)
{
    if (!path) {
        ob_set_error(OB_ERR_INVALID_ARGUMENT, "model path is NULL");
        return NULL;
    }
    /* Heap, not stack: it holds two paths. */
    ob_model_fs *fs = malloc(sizeof *fs);
    if (!fs) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
        return NULL;
    }
    const bool max_memory_default = max_memory == 0;
    if (max_memory == 0) max_memory = ob_default_max_memory();
    if (!ob_model_fs_init(fs, path, allow_external_files) || !ob_model_precheck(fs, max_memory)) {
        free(fs);
        return NULL;
    }

    struct aiPropertyStore *props = aiCreatePropertyStore();
    aiSetImportPropertyFloat(props, AI_CONFIG_PP_GSN_MAX_SMOOTHING_ANGLE, OB_CREASE_ANGLE_DEG);
    /* Points and lines cover no area for a G-buffer: SortByPType drops them. */
    aiSetImportPropertyInteger(props, AI_CONFIG_PP_SBP_REMOVE,
                               aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    unsigned flags = aiProcess_Triangulate | aiProcess_GenSmoothNormals |
                     aiProcess_JoinIdenticalVertices | aiProcess_SortByPType |
                     aiProcess_ValidateDataStructure | aiProcess_FindInvalidData;
    /* Through the confinement (fs). Assimp's C API catches the C++ exceptions of the import
     * and its steps (std::bad_alloc included) and reports them as a NULL scene with a message.
     * The raw scene is checked through a raw import of its own, not by aiApplyPostProcessing on
     * it: Assimp 5.2.5 frees the scene twice when a step fails there. */
    const struct aiScene *ai = NULL;
    uint64_t geometry = 0; /* check_raw_scene's estimate, for the texture plan */
    if (is_q3bsp(path)) {
        /* Read raw, repair the indices and winding, then post-process the repaired scene (the
         * importer keeps the properties above for aiApplyPostProcessing). Validation stays off:
         * Assimp 5.2.5 still rejects the repaired map (the double free above), and repair_q3bsp
         * has checked the indices itself. The file's vertex normals are replaced: q3map2 smooths
         * them across wall corners, which leaves a third of the flat faces with bent normals;
         * regenerated with the crease angle flat walls come out flat. */
        ai = aiImportFileExWithProperties(path, 0, &fs->io, props);
        if (ai && (fs->refused[0] || !check_raw_scene(ai, path, max_memory, false, &geometry) ||
                   !repair_q3bsp((struct aiScene *)ai, path))) {
            if (fs->refused[0]) ob_set_error(OB_ERR_MODEL, "%s: refers to %s", path, fs->refused);
            aiReleaseImport(ai);
            aiReleasePropertyStore(props);
            free(fs);
            return NULL;
        }
        if (ai) {
            unsigned q3_flags = (flags & ~(unsigned)aiProcess_ValidateDataStructure) |
                                aiProcess_ForceGenNormals;
            /* On failure Assimp has already released the scene. */
            ai = aiApplyPostProcessing(ai, q3_flags);
        }
    } else {
        /* First raw, to check what post-processing would otherwise trust (the NaNs that
         * FindInvalidData turns into "No meshes remaining", faces that abort Triangulate, the
         * memory its copies take), then released before the real import so that the two never
         * coexist: peak memory stays that of one import, the time is about one import more. */
        /* Validation on: without it Assimp's own scene preprocessing dereferences a face that
         * has no index array (an OFF face naming vertex 5 of 3, found by fuzz_model). */
        const struct aiScene *raw = aiImportFileExWithProperties(path, aiProcess_ValidateDataStructure, &fs->io, props);
        if (!raw || fs->refused[0] || !check_raw_scene(raw, path, max_memory, true, &geometry)) {
            if (!raw || fs->refused[0]) fail_assimp(path, fs, aiGetErrorString());
            if (raw) aiReleaseImport(raw);
            aiReleasePropertyStore(props);
            free(fs);
            return NULL;
        }
        aiReleaseImport(raw);
        ai = aiImportFileExWithProperties(path, flags, &fs->io, props);
    }
    if (!ai && !fs->refused[0]) {
        fail_assimp(path, fs, aiGetErrorString());
        aiReleasePropertyStore(props);
        free(fs);
        return NULL;
    }
    aiReleasePropertyStore(props);
    if (!ai || fs->refused[0]) {
        /* Refused: even where Assimp went on without the file (an OBJ without its MTL), the
         * user would not know the model was cut. */
        ob_set_error(OB_ERR_MODEL, "%s: refers to %s", path, fs->refused);
        if (ai) aiReleaseImport(ai);
        free(fs);
        return NULL;
    }
    if (ai->mFlags & AI_SCENE_FLAGS_INCOMPLETE) {
        ob_set_error(OB_ERR_MODEL, "%s: incomplete scene (no meshes?)", path);
        aiReleaseImport(ai);
        free(fs);
        return NULL;
    }

    /* The scene's name: the file name without directory and extension. */
    const char *slash = strrchr(path, '/');
    char name[128] = "";
    snprintf(name, sizeof name, "%s", slash ? slash + 1 : path);
    char *dot = strrchr(name, '.');
    if (dot && dot != name) *dot = '\0';

    importer im = {0};
    im.path = path;
    im.fs = fs;
    im.max_memory = max_memory;
    im.max_memory_default = max_memory_default;
    im.reserved = reserved;
    im.reserved_what = reserved_what;
    im.ai = ai;
    if (slash) {
        size_t len = (size_t)(slash - path);
        if (len >= sizeof im.dir) len = sizeof im.dir - 1;
        memcpy(im.dir, path, len);
        im.dir[len] = '\0';
        if (len == 0) snprintf(im.dir, sizeof im.dir, "/");
    } else {
        snprintf(im.dir, sizeof im.dir, ".");
    }
    unsigned nmat = ai->mNumMaterials ? ai->mNumMaterials : 1u;
    im.mat_map = malloc(nmat * sizeof *im.mat_map);
    im.mat_source = malloc(nmat * sizeof *im.mat_source);
    im.sources = calloc(nmat, sizeof *im.sources);
    im.slots = calloc(nmat, sizeof *im.slots);
    im.s = ob_scene_alloc(name);
    ob_scene *result = NULL;
    if (!im.mat_map || !im.mat_source || !im.sources || !im.slots || !im.s) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    } else if (ai->mNumMaterials == 0) {
        /* Assimp always makes a default material; without one there is nothing to map to. */
        ob_set_error(OB_ERR_MODEL, "%s: the file has no materials", path);
    } else {
        for (unsigned k = 0; k < nmat; ++k) {
            im.mat_map[k] = -1;
            im.mat_source[k] = -2;
        }
        /* Every texture sized and the whole run held against the limit before one is decoded. */
        if (plan_textures(&im, geometry)) result = import_scene(&im, up);
    }
    if (fs->refused[0]) { /* a texture's reference, refused while the textures were planned */
        ob_set_error(OB_ERR_MODEL, "%s: refers to %s", path, fs->refused);
        result = NULL;
    }
    if (result && !ob_scene_check_bounds(result, path)) result = NULL;
    if (!result) ob_destroy_scene(im.s);
    free(fs);
    for (int k = 0; im.sources && k < im.source_count; ++k) {
        free(im.sources[k].path);
        if (im.sources[k].owner < 0) free(im.sources[k].pixels); /* decoded, taken by no material */
    }
    free(im.sources);
    free(im.mat_source);
    free(im.mat_map);
    free(im.slots);
    aiReleaseImport(ai);
    return result;
}
