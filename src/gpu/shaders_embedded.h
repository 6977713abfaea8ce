/* The table tools/embed_shaders.c generates at build time. */
#ifndef OB_SHADERS_EMBEDDED_H
#define OB_SHADERS_EMBEDDED_H

typedef struct ob_embedded_shader {
    const char *name;   /* file name under shaders/ */
    const char *source; /* includes expanded, with #line FILE_ID markers */
} ob_embedded_shader;

/* #line source-string numbers are 1-based indices into this list. */
extern const char *const ob_shader_file_names[];
extern const int ob_shader_file_count;
extern const ob_embedded_shader ob_embedded_shaders[];
extern const int ob_embedded_shader_count;

#endif
