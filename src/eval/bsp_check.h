/* Quake 3 maps from untrusted hands (issue 19): the checks a .pk3 (a zip holding maps/NAME.bsp)
 * or a bare .bsp must pass before Assimp's Q3BSP importer reads it. That importer trusts the
 * zip's declared sizes (it allocates each entry's uncompressed size before inflating it) and the
 * BSP's lump table and faces (it sizes arrays from them and copies from the offsets they give),
 * so a few corrupt bytes end in std::bad_alloc or reads outside the file. */
#ifndef OB_BSP_CHECK_H
#define OB_BSP_CHECK_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

/* The Quake 3 map format Assimp 5.2 reads (Q3BSPFileData.h): "IBSP", version 46, 17 lumps. */
#define OB_BSP_VERSION 46
#define OB_BSP_LUMPS 17

/* Check the open file f (size bytes; `model` names it in messages) as Assimp will read it: a zip
 * archive when it has a zip end record (whatever its extension: Assimp opens every .pk3 and .bsp
 * as one), else a bare BSP. For a zip: the central directory and every entry's local header and
 * data lie inside the file, no entry claims more than max_memory uncompressed nor more than its
 * compressed bytes can inflate to, and every .bsp entry inflates to exactly its declared size
 * and passes the BSP checks. For a BSP: magic and version, every lump inside the file and a
 * whole number of the elements Assimp divides it into, every face's mesh-vertex range, vertex
 * indices and texture inside their lumps, texture names terminated.
 * False with OB_ERR_MODEL set: one line naming the model, the zip entry and the lump or face.
 * On success *estimate is the memory the import is expected to peak at (bytes). */
bool ob_q3_check(const char *model, FILE *f, uint64_t size, uint64_t max_memory, uint64_t *estimate);

/* The BSP checks alone, on bytes already in memory: `where` names them in messages
 * ("MODEL: ENTRY" or the model). The import's memory (the map, its lightmaps and the triangles
 * its faces make) is compared with max_memory here, before the faces' corners are read. */
bool ob_bsp_check(const char *where, const unsigned char *data, uint64_t size, uint64_t max_memory, uint64_t *estimate);

#endif
