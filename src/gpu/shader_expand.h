/* #include expansion of the GLSL sources, shared by the build-time embedder (tools/embed_shaders.c)
 * and the development shader directory (program.c, ob_set_shader_directory), so a shader compiled
 * from the source tree carries exactly the text and #line numbers of its embedded copy.
 * Plain C, no GL: the embedder links it without the library. */
#ifndef OB_SHADER_EXPAND_H
#define OB_SHADER_EXPAND_H

#include <stddef.h>

/* Lines are numbered FILE_ID * OB_SHADER_LINE_STRIDE + LINE, FILE_ID the 1-based position in the
 * file list, so any driver's "LINE" names both the file and the line (program.c decodes it). */
#define OB_SHADER_LINE_STRIDE 10000

/* `name` read from dir/name with every #include "FILE" replaced by FILE's text (each file at most
 * once per shader; includes nest at most 16 deep), and `#line` markers re-syncing the numbering
 * after each include and after the top-level #version line. Every file, `name` included, must be
 * one of files[0..file_count) (it gives the id). Returns a malloc'd string (free it), or NULL with
 * a one-line "shaders/FILE[:LINE]: error: ..." message in err (never exits or prints). */
char *ob_shader_expand(const char *dir, const char *const *files, int file_count, const char *name, char *err,
                       size_t err_len);

#endif
