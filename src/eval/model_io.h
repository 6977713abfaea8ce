/* Opening untrusted models (issue 19): one I/O layer through which the model and every file it
 * refers to are opened, and the checks that run on a model before Assimp allocates anything. */
#ifndef OB_MODEL_IO_H
#define OB_MODEL_IO_H

#include <stdbool.h>
#include <stdint.h>
#include <sys/types.h>
#include <stdio.h>

#include <assimp/cfileio.h>

#define OB_MODEL_PATH_MAX 4096

/* The confinement of one model import. The model's directory tree is the directory holding the
 * model's real path (symlinks resolved): a reference that resolves outside it, or to anything but
 * a regular file, is refused unless allow_external. */
typedef struct ob_model_fs {
    struct aiFileIO io;          /* handed to aiImportFileExWithProperties; UserData = this */
    const char *model;           /* the path as the user gave it: named in every message */
    char root[OB_MODEL_PATH_MAX];/* realpath of the model's directory */
    bool allow_external;
    /* The first refusal, "REFERENCE: why"; empty when nothing was refused. A refusal is fatal to
     * the import even where Assimp would go on without the file (OBJ without its MTL). */
    char refused[3 * OB_MODEL_PATH_MAX + 256];
} ob_model_fs;

/* False (error set: OB_ERR_IO naming the model) when the model's directory cannot be resolved. */
bool ob_model_fs_init(ob_model_fs *fs, const char *model, bool allow_external);

/* Open `path` (as the importer built it: relative to the working directory) for reading through
 * the confinement. NULL when it does not exist (quietly: importers probe for optional files) or
 * when it is refused (fs->refused then says why). `reference` is what the model wrote, for the
 * message (NULL = path). An absolute reference is refused when the file exists. */
FILE *ob_model_fs_open(ob_model_fs *fs, const char *path, const char *reference);

/* Checks on the model's own bytes before Assimp reads it: element counts declared in the file
 * (PLY header, glTF accessors and buffers, OBJ statements) against the bytes that are there, and
 * the memory the import would need against max_memory. False with OB_ERR_MODEL set (naming the
 * model and what is wrong) when the model fails one. */
bool ob_model_precheck(ob_model_fs *fs, uint64_t max_memory);

/* Bytes an import holding these raw Assimp element counts is expected to peak at (the raw scene,
 * post-processing's copies and the ob_scene built from it): checked after Assimp has read the
 * file and before post-processing multiplies it. */
uint64_t ob_model_estimate_peak(uint64_t vertices, uint64_t face_indices);

#endif
