/* A command's output files, written all or nothing (issue 19, issue 44).
 *
 *   cli_outputs set = {0};
 *   int out = -1;
 *   code = cli_outputs_add(&set, "--out", path, CLI_FMT_IMAGE, &out);  while parsing: before any work
 *   ...render...
 *   code = cli_outputs_write_rgb8(&set, out, w, h, 4, rgba);          into PATH.tmp-XXXXXX/ beside PATH
 *   code = code == EXIT_OK ? cli_outputs_commit(&set) : (cli_outputs_abort(&set), code);
 *
 * Every output is checked when it is added (a name, an extension the format follows, not an
 * existing directory, FIFO or device, a directory that really takes a new file), so a bad one
 * fails before anything is rendered. Each is written into a directory of its own beside its
 * target, PATH.tmp-XXXXXX (a rename never crosses a file system), which holds everything
 * temporary of that output. cli_outputs_commit is one transaction over the whole set: the
 * existing files are hard-linked into those directories, the new ones renamed over them, and if
 * any step fails every step is undone, so that either every output is replaced or none is. A
 * directory output (compare's report) is built in PATH.tmp-XXXXXX and exchanged with PATH as a
 * whole; it replaces an existing directory only when that one is empty or holds nothing but what
 * its manifest (.obscura-report, written at the commit) lists. SIGINT, SIGTERM and SIGHUP (unless
 * ignored) remove the temporary directories of the sets in use before the process dies of the
 * signal; one that comes during a commit waits until the commit has undone its steps. */
#ifndef OB_CLI_OUTPUTS_H
#define OB_CLI_OUTPUTS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* What an output may be; an image output's format follows its extension. */
enum {
    CLI_FMT_PNG = 1u << 0,  /* .png: 8-bit */
    CLI_FMT_JPG = 1u << 1,  /* .jpg, .jpeg: 8-bit, baseline, no alpha */
    CLI_FMT_PFM = 1u << 2,  /* .pfm: 32-bit floats */
    CLI_FMT_TEXT = 1u << 3, /* JSON, CSV, HTML: any name; the text is made valid UTF-8 */
    CLI_FMT_DIR = 1u << 4,  /* a directory the command fills (compare's report) */
    CLI_FMT_IMAGE = CLI_FMT_PNG | CLI_FMT_JPG | CLI_FMT_PFM,
};

typedef struct cli_output {
    char *option;   /* "--out": names the output in every message */
    char *path;     /* where it goes (a directory without its trailing '/') */
    char *tmp;      /* its temporary directory (PATH.tmp-XXXXXX), once made; NULL before */
    unsigned format; /* one CLI_FMT_* */
    bool ready;     /* written whole (a directory output: made), so the commit puts it in place */
} cli_output;

typedef struct cli_outputs {
    cli_output *items;
    int count, cap;
} cli_outputs;

/* Checks path as option's output and adds it (*index, for the writers). 0, or the exit code of
 * the one line printed: EXIT_USAGE for an empty name, an extension of none of the formats (the
 * message lists them) or a path already added; EXIT_OUTPUT for a path that exists and is not a
 * regular file (a directory for CLI_FMT_DIR: one that is empty or holds only what its manifest
 * lists), or whose directory cannot take a new file. */
int cli_outputs_add(cli_outputs *s, const char *option, const char *path, unsigned formats, int *index);
/* The format the extension gives (one CLI_FMT_*), or 0. */
unsigned cli_format_of(const char *path);

/* Top-row-first 8-bit pixels (channels 1, 3 or 4) in the output's format: PNG and JPEG as they
 * are (JPEG drops alpha), PFM as the same values / 255 (alpha dropped, rows bottom first). */
int cli_outputs_write_rgb8(cli_outputs *s, int index, int w, int h, int channels, const uint8_t *px);
/* Bottom-row-first floats (channels 1 or 3) in the output's format: PFM exactly, PNG and JPEG
 * clamped to 0..1 and quantised (rows top first). */
int cli_outputs_write_f32(cli_outputs *s, int index, int w, int h, int channels, const float *px);
/* Text, with invalid UTF-8 replaced (cli_utf8_valid). */
int cli_outputs_write_text(cli_outputs *s, int index, const char *text);
/* A directory output: the temporary directory to fill (made on the first call), or NULL with
 * the one line printed. */
const char *cli_outputs_dir(cli_outputs *s, int index);

/* Every written output put in its place, or (a failure, or SIGINT/SIGTERM/SIGHUP meanwhile, which
 * then ends the process) none; the set is emptied. 0 or EXIT_OUTPUT. */
int cli_outputs_commit(cli_outputs *s);
/* Every temporary directory removed, nothing renamed; the set is emptied. */
void cli_outputs_abort(cli_outputs *s);
/* Commit when code is EXIT_OK, else abort; the resulting exit code. */
int cli_outputs_finish(cli_outputs *s, int code);

/* text as valid UTF-8, malloc'd: each byte that does not start or continue a well-formed sequence
 * (RFC 3629: no overlong forms, no surrogates, nothing past U+10FFFF) becomes U+FFFD. NULL only
 * when out of memory. Every JSON and HTML writer of the CLI passes names through this: model and
 * sidecar names are bytes from a file, and a browser or JSON parser may reject the whole document
 * for one bad byte. */
char *cli_utf8_valid(const char *text);

#endif
