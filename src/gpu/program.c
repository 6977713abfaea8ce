/* Programs from the embedded shaders (or, in development, from the source tree's shader files:
 * ob_set_shader_directory), with driver errors mapped back to shaders/FILE:LINE. */
#include <ctype.h>
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/error.h"
#include "gpu/gpu.h"
#include "gpu/shader_expand.h"
#include "gpu/shaders_embedded.h"

/* The development shader directory; "" = the embedded copies. Process-wide and unsynchronised:
 * ob_set_shader_directory is documented as a between-frames call on the GL thread. */
static char shader_dir[4096] = "";

ob_error ob_set_shader_directory(const char *dir)
{
    if (!dir) {
        shader_dir[0] = '\0';
        return OB_OK;
    }
    if (strlen(dir) >= sizeof shader_dir)
        return ob_set_error(OB_ERR_IO, "shader directory %.64s...: path longer than %zu bytes", dir,
                            sizeof shader_dir - 1);
    /* Opening it is the check that it exists, is a directory and can be listed; the files are
     * read when each program is made, so a broken file surfaces there as OB_ERR_SHADER. */
    DIR *d = opendir(dir);
    if (!d) return ob_set_error(OB_ERR_IO, "shader directory %s is not a readable directory", dir);
    closedir(d);
    snprintf(shader_dir, sizeof shader_dir, "%s", dir);
    return OB_OK;
}

const char *ob_shader_source(const char *name)
{
    for (int i = 0; i < ob_embedded_shader_count; ++i)
        if (strcmp(ob_embedded_shaders[i].name, name) == 0) return ob_embedded_shaders[i].source;
    return NULL;
}

static const char *file_for_id(int id, const char *fallback)
{
    if (id >= 1 && id <= ob_shader_file_count) return ob_shader_file_names[id - 1];
    return fallback;
}

/* tools/embed_shaders.c (through shader_expand.c) numbers lines as FILE_ID * stride + LINE. */
#define LINE_STRIDE OB_SHADER_LINE_STRIDE

/* Mesa writes "0:LINE(COL): error: ...", NVIDIA "0(LINE) : error C0000: ...". We keep the first
 * error line (the one a person needs), rewritten as "shaders/FILE:LINE: message". */
void ob_format_shader_log(const char *log, const char *fallback_name, char *out, size_t out_len)
{
    const char *line = log ? log : "";
    const char *chosen = NULL;
    for (const char *p = line; *p;) {
        const char *eol = strchr(p, '\n');
        size_t n = eol ? (size_t)(eol - p) : strlen(p);
        if (n > 0 && !chosen) chosen = p;
        if (n > 0 && (strstr(p, "error") && (size_t)(strstr(p, "error") - p) < n)) { chosen = p; break; }
        p = eol ? eol + 1 : p + n;
    }
    if (!chosen) {
        snprintf(out, out_len, "shaders/%s: (no driver message)", fallback_name);
        return;
    }
    size_t n = strcspn(chosen, "\n");
    int id = 0, ln = 0, col = 0, used = 0;
    const char *msg = chosen;
    if (sscanf(chosen, "%d:%d(%d)%n", &id, &ln, &col, &used) == 3 && used > 0) {
        msg = chosen + used;
    } else if (sscanf(chosen, "%d(%d)%n", &id, &ln, &used) == 2 && used > 0) {
        msg = chosen + used;
    } else {
        ln = 0;
    }
    while (*msg == ' ' || *msg == ':') ++msg;
    int msg_len = (int)(n - (size_t)(msg - chosen));
    (void)id; /* the source-string number: Mesa always prints 0 */
    if (ln > 0)
        snprintf(out, out_len, "shaders/%s:%d: %.*s", file_for_id(ln / LINE_STRIDE, fallback_name), ln % LINE_STRIDE,
                 msg_len, msg);
    else
        snprintf(out, out_len, "shaders/%s: %.*s", fallback_name, msg_len, msg);
}

/* #version stays the first line; the defines go right after it (before the #line re-sync). */
static char *with_defines(const char *src, const char *defines)
{
    const char *eol = strchr(src, '\n');
    size_t head = eol ? (size_t)(eol - src) + 1 : strlen(src);
    const char *always = "#define OB_GLSL 1\n";
    size_t dn = defines ? strlen(defines) : 0;
    size_t total = strlen(src) + strlen(always) + dn + 2;
    char *s = malloc(total);
    if (!s) return NULL;
    memcpy(s, src, head);
    size_t at = head;
    memcpy(s + at, always, strlen(always));
    at += strlen(always);
    if (dn) {
        memcpy(s + at, defines, dn);
        at += dn;
        if (defines[dn - 1] != '\n') s[at++] = '\n';
    }
    strcpy(s + at, src + head);
    return s;
}

static GLuint compile(GLenum stage, const char *name, const char *defines)
{
    const char *src = NULL;
    char *from_dir = NULL;
    if (shader_dir[0]) {
        /* The embedded file list gives the ids, so driver lines decode to the same names. */
        char err[1024] = "";
        from_dir = ob_shader_expand(shader_dir, ob_shader_file_names, ob_shader_file_count, name, err, sizeof err);
        if (!from_dir) {
            ob_set_error(OB_ERR_SHADER, "%s", err);
            return 0;
        }
        src = from_dir;
    } else {
        src = ob_shader_source(name);
        if (!src) {
            ob_set_error(OB_ERR_SHADER, "shaders/%s: not embedded in this build", name);
            return 0;
        }
    }
    char *text = with_defines(src, defines);
    free(from_dir);
    if (!text) {
        ob_set_error(OB_ERR_OUT_OF_MEMORY, "out of memory compiling shaders/%s", name);
        return 0;
    }
    GLuint sh = glCreateShader(stage);
    const GLchar *srcs[1] = {text};
    glShaderSource(sh, 1, srcs, NULL);
    glCompileShader(sh);
    free(text);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[4096] = "", line[1024] = "";
        glGetShaderInfoLog(sh, sizeof log, NULL, log);
        ob_format_shader_log(log, name, line, sizeof line);
        ob_set_error(OB_ERR_SHADER, "%s", line);
        glDeleteShader(sh);
        return 0;
    }
    return sh;
}

static GLuint link(GLuint *shaders, int n, const char *name)
{
    GLuint prog = glCreateProgram();
    for (int i = 0; i < n; ++i) glAttachShader(prog, shaders[i]);
    glLinkProgram(prog);
    for (int i = 0; i < n; ++i) glDeleteShader(shaders[i]);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096] = "", line[1024] = "";
        glGetProgramInfoLog(prog, sizeof log, NULL, log);
        ob_format_shader_log(log, name, line, sizeof line);
        ob_set_error(OB_ERR_SHADER, "link: %s", line);
        glDeleteProgram(prog);
        return 0;
    }
    return prog;
}

GLuint ob_make_compute_program(const char *name, const char *defines)
{
    GLuint cs = compile(GL_COMPUTE_SHADER, name, defines);
    if (!cs) return 0;
    return link(&cs, 1, name);
}

GLuint ob_make_raster_program(const char *vert_name, const char *frag_name, const char *defines)
{
    GLuint sh[2] = {compile(GL_VERTEX_SHADER, vert_name, defines), 0};
    if (!sh[0]) return 0;
    sh[1] = compile(GL_FRAGMENT_SHADER, frag_name, defines);
    if (!sh[1]) {
        glDeleteShader(sh[0]);
        return 0;
    }
    return link(sh, 2, frag_name);
}
