/* Opening a file that a user or a file named, for reading: never blocking, never anything but a
 * regular file. */
#ifndef OB_IO_FILE_H
#define OB_IO_FILE_H

#include <stdio.h>
#include <sys/types.h>

#include "obscura/scene.h"

/* path opened for reading ("rb"), or NULL with the library's error set (OB_ERR_IO, "cannot read
 * WHAT PATH: why", why naming what was found: no such file, a FIFO, a directory...). The file is
 * opened with O_NONBLOCK and checked with fstat to be a regular file before any byte is read, so
 * a FIFO with no writer, a device or a directory in its place fails at once instead of hanging or
 * reading forever; the descriptor is then made blocking again for ordinary reads. */
FILE *ob_fopen_regular(const char *path, const char *what);

/* What a path that is not a regular file is, for messages: "a directory", "a FIFO", "a character
 * device", "a block device", "a socket", else "not a regular file". */
const char *ob_file_kind(mode_t m);

#endif
