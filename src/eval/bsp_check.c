/* Quake 3 maps (.pk3 / .bsp) checked before Assimp 5.2's Q3BSP importer reads them (issue 19).
 *
 * What that importer trusts, read in Assimp 5.2.5's code/Common/ZipArchiveIOSystem.cpp and
 * code/AssetLib/Q3BSP/Q3BSPFileParser.cpp, Q3BSPFileImporter.cpp:
 * - every zip entry it opens (the map, and the textures the map names) gets a buffer of the
 *   entry's declared uncompressed size before a byte is inflated; and when the entry's data is
 *   longer than declared or fails its CRC, minizip's close reports an error that Assimp meets with
 *   an ai_assert, which Debian's build keeps: the process aborts;
 * - the lump table: each lump's length (a signed int) divided by an element size sizes a vector
 *   (a negative one wraps to ~2^64: std::bad_alloc), and the lump's offset is copied from with no
 *   bound; the mesh-vertex lump is copied whole into length/4 ints (a length that is no multiple
 *   of 4 writes past them);
 * - the faces: a face's mesh-vertex range indexes the mesh-vertex array unchecked, face counts
 *   (signed) are summed into allocation sizes, a face's texture indexes the texture array
 *   unchecked, and texture names are read as C strings.
 * So each of those is checked here, on the zip's own bytes and on the inflated map. Messages name
 * the model, the entry and the lump or face; a zip entry's name is made printable ASCII first. */
#include "eval/bsp_check.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/types.h>

#include <zlib.h>

#include "base/error.h"
#include "eval/model_io.h"

/* ---- the BSP --------------------------------------------------------------------------------- */

enum { LUMP_TEXTURES = 1, LUMP_VERTICES = 10, LUMP_MESH_VERTICES = 11, LUMP_FACES = 13, LUMP_LIGHTMAPS = 14 };

static const char *const lump_name[OB_BSP_LUMPS] = {
    "entities", "textures", "planes",   "nodes",         "leafs",    "leaf faces", "leaf brushes", "models",  "brushes",
    "brush sides", "vertices", "mesh vertices", "effects", "faces", "lightmaps", "light volumes", "visibility"};

/* The bytes of one element of the lumps Assimp divides into elements (Q3BSPFileData.h:
 * sQ3BSPTexture, sQ3BSPVertex, int, sQ3BSPFace, sQ3BSPLightmap); 0 for the lumps it reads as
 * bytes or not at all. Assimp rounds a partial last element down, except for the mesh vertices
 * (copied whole, see above); a partial element in any of them means the lump table is corrupt. */
static const uint32_t lump_element[OB_BSP_LUMPS] = {
    [LUMP_TEXTURES] = 72, [LUMP_VERTICES] = 44, [LUMP_MESH_VERTICES] = 4, [LUMP_FACES] = 104,
    [LUMP_LIGHTMAPS] = 128 * 128 * 3};

#define BSP_TEXTURE_NAME 64 /* sQ3BSPTexture.strName */
#define BSP_LIGHTMAP_TEXTURE (128u * 128u * 4u) /* the aiTexture Assimp makes of each lightmap */

static uint32_t le16(const unsigned char *p) { return (uint32_t)p[0] | (uint32_t)p[1] << 8; }

static uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static int32_t s32(const unsigned char *p) { return (int32_t)le32(p); }

bool ob_bsp_check(const char *where, const unsigned char *d, uint64_t n, uint64_t max_memory, uint64_t *estimate)
{
    const uint64_t header = 8u + 8u * OB_BSP_LUMPS;
    if (n < header) {
        ob_set_error(OB_ERR_MODEL, "%s: %llu bytes, too short for a Quake 3 BSP header (%llu bytes)", where,
                     (unsigned long long)n, (unsigned long long)header);
        return false;
    }
    if (memcmp(d, "IBSP", 4) != 0) {
        char magic[5] = "";
        for (int k = 0; k < 4; ++k) magic[k] = d[k] >= 0x20 && d[k] < 0x7f ? (char)d[k] : '?';
        ob_set_error(OB_ERR_MODEL, "%s: not a Quake 3 BSP: it begins '%s', not 'IBSP'", where, magic);
        return false;
    }
    int32_t version = s32(d + 4);
    if (version != OB_BSP_VERSION) {
        /* The lump layout Assimp assumes is version 46's. */
        ob_set_error(OB_ERR_MODEL, "%s: BSP version %d; only Quake 3's version %d can be read", where, (int)version,
                     OB_BSP_VERSION);
        return false;
    }
    uint64_t off[OB_BSP_LUMPS] = {0}, len[OB_BSP_LUMPS] = {0};
    for (int k = 0; k < OB_BSP_LUMPS; ++k) {
        int32_t o = s32(d + 8 + 8 * k), l = s32(d + 12 + 8 * k);
        if (o < 0 || l < 0) {
            ob_set_error(OB_ERR_MODEL, "%s: lump %d (%s) has a negative offset or length (%d, %d)", where, k, lump_name[k],
                         (int)o, (int)l);
            return false;
        }
        off[k] = (uint64_t)o;
        len[k] = (uint64_t)l;
        if (off[k] + len[k] > n) {
            ob_set_error(OB_ERR_MODEL, "%s: lump %d (%s) spans bytes %llu to %llu, past the end of the BSP (%llu bytes)",
                         where, k, lump_name[k], (unsigned long long)off[k], (unsigned long long)(off[k] + len[k]),
                         (unsigned long long)n);
            return false;
        }
        if (lump_element[k] && len[k] % lump_element[k] != 0) {
            ob_set_error(OB_ERR_MODEL, "%s: lump %d (%s) is %llu bytes, not a whole number of %u-byte elements", where, k,
                         lump_name[k], (unsigned long long)len[k], lump_element[k]);
            return false;
        }
    }
    const uint64_t vertices = len[LUMP_VERTICES] / lump_element[LUMP_VERTICES];
    const uint64_t mesh_vertices = len[LUMP_MESH_VERTICES] / lump_element[LUMP_MESH_VERTICES];
    const uint64_t faces = len[LUMP_FACES] / lump_element[LUMP_FACES];
    const uint64_t textures = len[LUMP_TEXTURES] / lump_element[LUMP_TEXTURES];
    const uint64_t lightmaps = len[LUMP_LIGHTMAPS] / lump_element[LUMP_LIGHTMAPS];

    for (uint64_t t = 0; t < textures; ++t) {
        const unsigned char *name = d + off[LUMP_TEXTURES] + t * lump_element[LUMP_TEXTURES];
        if (!memchr(name, '\0', BSP_TEXTURE_NAME)) {
            ob_set_error(OB_ERR_MODEL, "%s: texture %llu's name is not terminated within its %d bytes", where,
                         (unsigned long long)t, BSP_TEXTURE_NAME);
            return false;
        }
    }

    /* First the ranges and the corners Assimp will make (every face with mesh vertices whose type
     * is a polygon or a triangle mesh), so that the memory is known before the corners are read. */
    uint64_t corners = 0;
    for (uint64_t i = 0; i < faces; ++i) {
        const unsigned char *f = d + off[LUMP_FACES] + i * lump_element[LUMP_FACES];
        int32_t texture = s32(f), type = s32(f + 8), first = s32(f + 20), count = s32(f + 24);
        if (texture < -1 || (texture >= 0 && (uint64_t)texture >= textures)) {
            ob_set_error(OB_ERR_MODEL, "%s: face %llu names texture %d; the textures lump holds %llu", where,
                         (unsigned long long)i, (int)texture, (unsigned long long)textures);
            return false;
        }
        if (count < 0) {
            ob_set_error(OB_ERR_MODEL, "%s: face %llu has a negative mesh-vertex count (%d)", where, (unsigned long long)i,
                         (int)count);
            return false;
        }
        if (count > 0 && (first < 0 || (uint64_t)first + (uint64_t)count > mesh_vertices)) {
            ob_set_error(OB_ERR_MODEL, "%s: face %llu's mesh vertices %d to %lld lie outside the mesh-vertex lump (%llu)",
                         where, (unsigned long long)i, (int)first, (long long)first + count,
                         (unsigned long long)mesh_vertices);
            return false;
        }
        if (count > 0 && (type == 1 || type == 3)) corners += (uint64_t)count;
    }
    /* The map twice (the zip's buffer and the parser's copy) and the parser's per-element objects
     * (about as large again), the lightmaps as RGBA textures, and the triangles as any import's. */
    uint64_t est = 3u * n + lightmaps * BSP_LIGHTMAP_TEXTURE + ob_model_estimate_peak(corners, corners);
    if (est > max_memory) {
        ob_set_error(OB_ERR_MODEL, "%s: its %llu faces with %llu corners would take about %.2f GiB to import, more than the limit of %.2f GiB (--max-memory)",
                     where, (unsigned long long)faces, (unsigned long long)corners, (double)est / (double)(1ull << 30),
                     (double)max_memory / (double)(1ull << 30));
        return false;
    }
    /* Each corner names vertex (face's first vertex + mesh vertex): Assimp adds the two as ints
     * (an overflow is undefined) and skips a corner outside the vertices, which leaves the rest of
     * the face's triangles shifted: a wrong mesh, not a refusal, without this. */
    for (uint64_t i = 0; i < faces; ++i) {
        const unsigned char *f = d + off[LUMP_FACES] + i * lump_element[LUMP_FACES];
        int32_t type = s32(f + 8), base = s32(f + 12), first = s32(f + 20), count = s32(f + 24);
        if (count <= 0 || (type != 1 && type != 3)) continue;
        for (int32_t c = 0; c < count; ++c) {
            int64_t v = (int64_t)base + s32(d + off[LUMP_MESH_VERTICES] + 4u * ((uint64_t)first + (uint64_t)c));
            if (v < 0 || (uint64_t)v >= vertices) {
                ob_set_error(OB_ERR_MODEL, "%s: face %llu corner %d names vertex %lld; the vertices lump holds %llu", where,
                             (unsigned long long)i, (int)c, (long long)v, (unsigned long long)vertices);
                return false;
            }
        }
    }
    *estimate = est;
    return true;
}

/* ---- the zip --------------------------------------------------------------------------------- */

#define ZIP_END 22u               /* end of central directory record, without its comment */
#define ZIP_END_SEARCH 65535u     /* minizip looks this far back from the end for that record */
#define ZIP_CENTRAL 46u           /* central directory file header, fixed part */
#define ZIP_LOCAL 30u             /* local file header, fixed part */
/* Deflate turns one compressed byte into at most 1032 bytes (zlib's FAQ: 258-byte matches of one
 * bit each); the slack covers the stream's own header and final block. */
#define DEFLATE_MAX_RATIO 1032u
#define DEFLATE_SLACK 1024u

typedef struct zip_read {
    const char *model;
    FILE *f;
    uint64_t size;
} zip_read;

static bool read_at(const zip_read *z, uint64_t at, void *buf, size_t n)
{
    return at <= z->size && n <= z->size - at && fseeko(z->f, (off_t)at, SEEK_SET) == 0 && fread(buf, 1, n, z->f) == n;
}

/* The entry's name as printable ASCII (anything else becomes '?'), cut at 200 bytes: it goes
 * into a one-line message and from there into JSON and HTML. */
static void printable(const unsigned char *name, size_t n, char *out, size_t out_n)
{
    size_t k = 0;
    for (; k < n && k + 1 < out_n && k < 200; ++k) out[k] = name[k] >= 0x20 && name[k] < 0x7f ? (char)name[k] : '?';
    out[k] = '\0';
}

static const char *human(uint64_t bytes, char *buf, size_t n)
{
    if (bytes >= (1ull << 30)) snprintf(buf, n, "%.2f GiB", (double)bytes / (double)(1ull << 30));
    else snprintf(buf, n, "%.1f MiB", (double)bytes / (double)(1ull << 20));
    return buf;
}

/* What Assimp extracts: the map and the textures it names (Q3BSPFileImporter: .jpg .png .tga). */
static bool assimp_opens(const char *name)
{
    const char *dot = strrchr(name, '.');
    if (!dot) return false;
    return !strcasecmp(dot, ".bsp") || !strcasecmp(dot, ".jpg") || !strcasecmp(dot, ".png") || !strcasecmp(dot, ".tga");
}

/* Inflate (or copy, for a stored entry) the entry's csize bytes at `at`, checking that they
 * give exactly usize bytes with the CRC the directory declares. keep: return the bytes (the
 * caller frees them); else they are only checked and *out stays NULL. */
static bool extract(const zip_read *z, const char *entry, uint32_t method, uint64_t at, uint64_t csize, uint64_t usize,
                    uint32_t crc, bool keep, unsigned char **out)
{
    enum { CHUNK = 1 << 16 };
    *out = NULL;
    unsigned char *in = malloc(CHUNK), *scratch = malloc(CHUNK);
    /* Grown as bytes arrive, so that memory follows what the data holds, not what it claims. */
    uint64_t cap = keep ? (usize < (1u << 20) ? usize + 1u : (1u << 20)) : 0;
    unsigned char *buf = keep ? malloc(cap) : NULL;
    z_stream zs;
    memset(&zs, 0, sizeof zs);
    bool ok = in && scratch && (!keep || buf);
    if (!ok) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: out of memory checking zip entry '%s'", z->model, entry);
    } else if (method == 8 && inflateInit2(&zs, -MAX_WBITS) != Z_OK) {
        ok = false;
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: zlib could not start on zip entry '%s'", z->model, entry);
    }
    bool inflating = ok && method == 8;
    uint64_t read = 0, made = 0;
    uLong sum = crc32(0L, Z_NULL, 0);
    bool ended = false;
    if (ok && fseeko(z->f, (off_t)at, SEEK_SET) != 0) {
        ob_set_error(OB_ERR_MODEL, "%s: zip entry '%s' cannot be read", z->model, entry);
        ok = false;
    }
    while (ok && !ended) {
        if (zs.avail_in == 0 && read < csize) {
            size_t want = csize - read < CHUNK ? (size_t)(csize - read) : CHUNK;
            if (fread(in, 1, want, z->f) != want) {
                ob_set_error(OB_ERR_MODEL, "%s: zip entry '%s' cannot be read (truncated?)", z->model, entry);
                ok = false;
                break;
            }
            read += want;
            zs.next_in = in;
            zs.avail_in = (uInt)want;
        }
        unsigned char *dst = scratch;
        uInt room = CHUNK;
        if (keep) {
            if (made == cap) {
                /* Full at usize + 1 means more bytes than declared: the check below says so. */
                uint64_t grown = cap * 2u > usize + 1u ? usize + 1u : cap * 2u;
                unsigned char *bigger = realloc(buf, grown);
                if (!bigger) {
                    ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: out of memory inflating zip entry '%s'", z->model, entry);
                    ok = false;
                    break;
                }
                buf = bigger;
                cap = grown;
            }
            dst = buf + made;
            room = cap - made < CHUNK ? (uInt)(cap - made) : CHUNK;
        }
        uInt produced = 0;
        if (inflating) {
            zs.next_out = dst;
            zs.avail_out = room;
            int r = inflate(&zs, Z_NO_FLUSH);
            produced = room - zs.avail_out;
            if (r == Z_STREAM_END) {
                ended = true;
            } else if (r == Z_DATA_ERROR || r == Z_NEED_DICT || r == Z_MEM_ERROR ||
                       (r == Z_BUF_ERROR && zs.avail_in == 0 && read == csize)) {
                ob_set_error(OB_ERR_MODEL, "%s: zip entry '%s' has corrupt or truncated deflate data%s%s", z->model, entry,
                             zs.msg ? ": " : "", zs.msg ? zs.msg : "");
                ok = false;
                break;
            }
        } else {
            produced = zs.avail_in < room ? zs.avail_in : room;
            memcpy(dst, zs.next_in, produced);
            zs.next_in += produced;
            zs.avail_in -= produced;
            ended = zs.avail_in == 0 && read == csize;
        }
        sum = crc32(sum, dst, produced);
        made += produced;
        if (made > usize) {
            ob_set_error(OB_ERR_MODEL, "%s: zip entry '%s' inflates to more than its declared %llu bytes (corrupt)", z->model,
                         entry, (unsigned long long)usize);
            ok = false;
        }
    }
    if (ok && made != usize) {
        ob_set_error(OB_ERR_MODEL, "%s: zip entry '%s' holds %llu bytes, not its declared %llu (truncated or corrupt)",
                     z->model, entry, (unsigned long long)made, (unsigned long long)usize);
        ok = false;
    } else if (ok && sum != crc) {
        ob_set_error(OB_ERR_MODEL, "%s: zip entry '%s' fails its CRC check (corrupt)", z->model, entry);
        ok = false;
    }
    if (inflating) inflateEnd(&zs);
    free(in);
    free(scratch);
    if (ok && keep) *out = buf;
    else free(buf);
    return ok;
}

/* The offset of the end-of-central-directory record as minizip finds it (the last signature
 * within ZIP_END_SEARCH + ZIP_END bytes of the end), or -1 when there is none: not a zip. */
static int64_t find_end_record(const zip_read *z, unsigned char *tail, uint64_t *tail_at, uint64_t *tail_n)
{
    uint64_t n = z->size < ZIP_END_SEARCH + ZIP_END ? z->size : ZIP_END_SEARCH + ZIP_END;
    *tail_at = z->size - n;
    *tail_n = n;
    if (n < 4 || !read_at(z, *tail_at, tail, (size_t)n)) return -1;
    for (uint64_t k = n - 4u + 1u; k-- > 0;)
        if (tail[k] == 'P' && tail[k + 1] == 'K' && tail[k + 2] == 5 && tail[k + 3] == 6) return (int64_t)(*tail_at + k);
    return -1;
}

/* minizip tries the Zip64 end record first: a locator ("PK\6\7", disk 0) pointing at a Zip64
 * record ("PK\6\6"). Sizes then come from extra fields this check does not read. */
static bool is_zip64(const zip_read *z, const unsigned char *tail, uint64_t tail_n)
{
    for (uint64_t k = tail_n >= 20u ? tail_n - 20u + 1u : 0; k-- > 0;) {
        const unsigned char *p = tail + k;
        if (p[0] != 'P' || p[1] != 'K' || p[2] != 6 || p[3] != 7) continue;
        if (le32(p + 4) != 0) return false;
        uint64_t at = (uint64_t)le32(p + 8) | (uint64_t)le32(p + 12) << 32;
        unsigned char sig[4] = {0};
        return read_at(z, at, sig, 4) && sig[0] == 'P' && sig[1] == 'K' && sig[2] == 6 && sig[3] == 6;
    }
    return false;
}

bool ob_q3_check(const char *model, FILE *f, uint64_t size, uint64_t max_memory, uint64_t *estimate)
{
    zip_read z = {model, f, size};
    unsigned char *tail = malloc(ZIP_END_SEARCH + ZIP_END);
    if (!tail) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: out of memory", model);
        return false;
    }
    uint64_t tail_at = 0, tail_n = 0;
    int64_t end = find_end_record(&z, tail, &tail_at, &tail_n);
    bool zip64 = end >= 0 && is_zip64(&z, tail, tail_n);
    unsigned char e[ZIP_END] = {0};
    bool have_end = end >= 0 && read_at(&z, (uint64_t)end, e, ZIP_END);
    free(tail);

    if (end < 0) {
        /* Assimp opens a .bsp as a zip too, and fails on a bare one; its lumps are still worth
         * naming when they are what is wrong. */
        const char *dot = strrchr(model, '.');
        if (!dot || strcasecmp(dot, ".bsp") != 0) {
            ob_set_error(OB_ERR_MODEL, "%s: not a .pk3 (zip) archive: it has no zip end-of-central-directory record", model);
            return false;
        }
        if (size > max_memory) {
            char a[32] = "", b[32] = "";
            ob_set_error(OB_ERR_MODEL, "%s: a %s BSP, more than the limit of %s (--max-memory)", model,
                         human(size, a, sizeof a), human(max_memory, b, sizeof b));
            return false;
        }
        unsigned char *data = malloc(size ? size : 1u);
        bool ok = data && read_at(&z, 0, data, (size_t)size);
        if (!ok) ob_set_error(data ? OB_ERR_IO : OB_ERR_OUT_OF_MEMORY, "%s: cannot read the BSP", model);
        ok = ok && ob_bsp_check(model, data, size, max_memory, estimate);
        free(data);
        if (ok)
            ob_set_error(OB_ERR_MODEL, "%s: a bare .bsp; Assimp reads Quake 3 maps only from a .pk3 (a zip holding maps/NAME.bsp)",
                         model);
        return false;
    }
    if (zip64) {
        ob_set_error(OB_ERR_MODEL, "%s: a Zip64 archive; Quake 3 maps come in plain zip archives (.pk3)", model);
        return false;
    }
    if (!have_end) {
        ob_set_error(OB_ERR_MODEL, "%s: its zip end record is cut short (truncated)", model);
        return false;
    }
    uint32_t disk = le16(e + 4), cd_disk = le16(e + 6), disk_entries = le16(e + 8), entries = le16(e + 10);
    uint64_t cd_size = le32(e + 12), cd_at = le32(e + 16);
    /* minizip refuses multi-disk archives itself; an archive with bytes before it (self-extracting)
     * is no .pk3: both are refused here so that the offsets below are the file's. */
    if (disk != 0 || cd_disk != 0 || disk_entries != entries || cd_at + cd_size != (uint64_t)end) {
        ob_set_error(OB_ERR_MODEL, "%s: zip end record declares a central directory of %llu bytes at %llu, which does not end where the record is (%lld): corrupt",
                     model, (unsigned long long)cd_size, (unsigned long long)cd_at, (long long)end);
        return false;
    }
    unsigned char *cd = malloc(cd_size ? cd_size : 1u);
    if (!cd || !read_at(&z, cd_at, cd, (size_t)cd_size)) {
        if (cd) ob_set_error(OB_ERR_MODEL, "%s: its zip central directory cannot be read", model);
        else ob_set_error(OB_ERR_OUT_OF_MEMORY, "%s: out of memory", model);
        free(cd);
        return false;
    }
    bool ok = true;
    uint64_t pos = 0, unpacked = 0, est = 0;
    char where[OB_MODEL_PATH_MAX + 512] = "", name[256] = "";
    for (uint32_t i = 0; ok && i < entries; ++i) {
        const unsigned char *h = cd + pos;
        if (pos + ZIP_CENTRAL > cd_size || le32(h) != 0x02014b50u) {
            ob_set_error(OB_ERR_MODEL, "%s: zip central directory entry %u of %u is cut short or corrupt", model, i, entries);
            ok = false;
            break;
        }
        uint32_t flags = le16(h + 8), method = le16(h + 10), crc = le32(h + 16);
        uint64_t csize = le32(h + 20), usize = le32(h + 24);
        uint64_t nlen = le16(h + 28), xlen = le16(h + 30), clen = le16(h + 32), local = le32(h + 42);
        if (pos + ZIP_CENTRAL + nlen + xlen + clen > cd_size) {
            ob_set_error(OB_ERR_MODEL, "%s: zip central directory entry %u of %u runs past the directory (corrupt)", model, i,
                         entries);
            ok = false;
            break;
        }
        printable(h + ZIP_CENTRAL, (size_t)nlen, name, sizeof name);
        pos += ZIP_CENTRAL + nlen + xlen + clen;
        /* The data must lie between its local header and the central directory. */
        unsigned char lh[ZIP_LOCAL] = {0};
        uint64_t data_at = 0;
        if (local + ZIP_LOCAL > cd_at || !read_at(&z, local, lh, ZIP_LOCAL) || le32(lh) != 0x04034b50u ||
            (data_at = local + ZIP_LOCAL + le16(lh + 26) + le16(lh + 28)) + csize > cd_at) {
            ob_set_error(OB_ERR_MODEL, "%s: zip entry '%s' (%llu bytes at %llu) does not lie inside the archive before its central directory (truncated or corrupt)",
                         model, name, (unsigned long long)csize, (unsigned long long)local);
            ok = false;
            break;
        }
        char a[32] = "", b[32] = "";
        if (usize > max_memory) {
            ob_set_error(OB_ERR_MODEL, "%s: zip entry '%s' claims %s uncompressed, more than the limit of %s (--max-memory)", model,
                         name, human(usize, a, sizeof a), human(max_memory, b, sizeof b));
            ok = false;
            break;
        }
        if ((method == 0 && !(flags & 1u) && usize != csize) ||
            (method == 8 && usize > csize * DEFLATE_MAX_RATIO + DEFLATE_SLACK)) {
            ob_set_error(OB_ERR_MODEL, "%s: zip entry '%s' claims %llu bytes uncompressed from %llu %s, more than it can hold (corrupt)",
                         model, name, (unsigned long long)usize, (unsigned long long)csize,
                         method == 0 ? "stored" : "deflated (at most 1032 to 1)");
            ok = false;
            break;
        }
        unpacked += usize;
        /* Assimp lists no empty entry, and opens only the map and its textures. */
        if (usize == 0 || !assimp_opens(name)) continue;
        if ((flags & 1u) || (method != 0 && method != 8)) {
            ob_set_error(OB_ERR_MODEL, "%s: zip entry '%s' is %s; Assimp reads stored and deflated entries only", model, name,
                         (flags & 1u) ? "encrypted" : "compressed with another method");
            ok = false;
            break;
        }
        const char *dot = strrchr(name, '.');
        bool bsp = dot && !strcasecmp(dot, ".bsp");
        unsigned char *data = NULL;
        ok = extract(&z, name, method, data_at, csize, usize, crc, bsp, &data);
        if (ok && bsp) {
            snprintf(where, sizeof where, "%s: %s", model, name);
            uint64_t map_est = 0;
            ok = ob_bsp_check(where, data, usize, max_memory, &map_est);
            est += map_est;
        }
        free(data);
    }
    free(cd);
    if (!ok) return false;
    /* Every entry Assimp may extract stays in memory (textures in the scene) besides the map. */
    *estimate = est + unpacked;
    return true;
}
