/* The obscura CLI: shared helpers for the subcommands (cli.c) and the subcommands' entry points.
 * The options every rendering command shares are in cli_options.h. */
#ifndef OB_CLI_H
#define OB_CLI_H

#include <stdbool.h>
#include <stdio.h>

#include "obscura/eval.h"

/* Exit codes: documented in README.md and `obscura --help`. */
enum {
    EXIT_OK = 0,
    EXIT_RUNTIME = 1, /* GL or shader failure, out of memory */
    EXIT_USAGE = 2,   /* bad argument: unknown scene/method/parameter/camera, value out of range, bad size */
    EXIT_INPUT = 3,   /* missing, unreadable or corrupt model or sidecar */
    EXIT_OUTPUT = 4,  /* an output file could not be written */
    EXIT_NO_GPU = 5,  /* no OpenGL 4.5 context could be made */
};

/* Print "obscura: MESSAGE" (one line) and return the exit code for the library's last error.
 * ob_get_error clears the code it returns, so call this only while the failing call's error is
 * still pending (nothing has read it since). */
int cli_fail_from_library(void);
/* The same, the line prefixed with where the value came from ("--set ssao.radius=abc"), for a
 * library message that cannot know which option or file it was given by. */
int cli_fail_from_library_in(const char *where);
/* The library's last message with an explicit exit code (e.g. EXIT_OUTPUT for a failed write). */
int cli_fail_library_as(int code);
/* Print "obscura: MESSAGE" and return code. */
int cli_fail(int code, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* The message of the last cli_fail (any of the above) as it was printed, without "obscura: ": one
 * line, control bytes escaped, cut to about 1000 bytes; "" before any. */
const char *cli_last_failure(void);
/* "unknown option 'ARG'; did you mean '--NEAR'? (see obscura COMMAND --help)", exit EXIT_USAGE: the
 * options to suggest are the ones the command's own --help text names (usage writes it), so the
 * suggestion never names one the command does not take. */
struct cli_common;
int cli_unknown_option(const char *command, const char *arg, void (*usage)(FILE *, const struct cli_common *),
                       const struct cli_common *c);

bool cli_parse_size(const char *text, int *w, int *h);
/* A file-system-safe name (a view's directory): letters, digits, '-' and '_' kept, any other byte
 * '_', cut to n - 1 bytes. */
void cli_safe_name(char *out, size_t n, const char *in);
bool cli_parse_vec3(const char *text, float out[3]);
bool cli_parse_float(const char *text, float *out);
/* The GL context for a command; with verbose, one stderr line naming GL_RENDERER, GL_VERSION and
 * the EGL device. NULL (the library's error set) when none can be made. */
ob_context *cli_make_context(ob_gpu_kind gpu, bool verbose);
/* Before any context (cli_make_context calls it; the viewer before its window): when the
 * directory Mesa's shader cache would use is read-only, not writable or under 64 MiB from full,
 * set MESA_SHADER_CACHE_DISABLE (Mesa maps that cache and dies of SIGBUS on a full disk), with
 * one warning line naming the directory. */
void cli_guard_shader_cache(void);
/* auto, hw or sw. */
bool cli_parse_gpu(const char *text, ob_gpu_kind *out);
/* The option values several commands share; false (and *out untouched) for anything else. */
bool cli_parse_on_off(const char *text, bool *out);            /* on, off */
bool cli_parse_up(const char *text, ob_up_axis *out);          /* y, z */
bool cli_parse_ao_scale(const char *text, float *out);         /* 1, 0.5, 0.25 */
bool cli_parse_shadow(const char *text, ob_shadow_method *out); /* none, hard, pcf, vsm */
/* The median of n values (sorted in place, so v[0] and v[n-1] are then the min and max); NAN
 * for n = 0. */
double cli_median(double *v, int n);
/* A number as results.json and bench --json write it: 6 significant digits ("%.6g"). cJSON writes
 * every double with 15 to 17 (an RMSE of 0.077481550454739076, a GPU time of 2.0711430000000001),
 * digits no measurement here has. A whole number (a count, a size, N) is kept as it is, and NaN
 * and infinities pass through (cJSON writes them as null). */
double cli_json_round(double v);
/* cJSON_AddNumberToObject with the value rounded by cli_json_round: what those two files add a
 * number with. */
struct cJSON;
struct cJSON *cli_json_add_number(struct cJSON *object, const char *name, double v);
/* The log-average luminance (SSDO thesis eq. 2.1) of the frame just rendered, over its composed
 * radiance before exposure (OB_IMAGE_HDR_F32), as the luminance pass measures it: the L_avg in the
 * tone map's scale exposure x key / L_avg. rgb is scratch for px x 3 floats. NAN if the radiance
 * cannot be read back. */
double cli_frame_log_average(ob_renderer *r, float *rgb, size_t px);
/* One exposure for several frames of one camera (compare's rows, sheet's rows): the tone map scales
 * each frame by exposure x key / L_avg of its own radiance, so a frame that AO darkens is brightened
 * back and the frames would differ by less than the AO (issue 20). The anchor is the view without
 * AO: a `none` frame with `like`'s lights, ambient, shadows and HDR settings. cli_exposure_apply
 * renders the frame just rendered with settings s once more at the anchor's key and at exposure
 * e_0 L_m / L_0, which gives its radiance the anchor's scale e_0 key_0 / L_0 (render.c's
 * print_exposure, scripts/noao_frame.sh). With HDR off there is no adaptation and nothing to do. */
typedef struct cli_exposure {
    bool active;
    double log_average; /* L_0 */
    float key;          /* key_0: like's key, or the automatic key of L_0 */
    float exposure;     /* e_0 */
    float *scratch;     /* px x 3 floats */
    size_t px;
} cli_exposure;
/* EXIT_OK or the failure's exit code (one line printed). */
int cli_exposure_begin(cli_exposure *e, ob_renderer *r, const ob_camera *cam, const ob_settings *like, size_t px);
int cli_exposure_apply(cli_exposure *e, ob_renderer *r, const ob_camera *cam, const ob_settings *s);
void cli_exposure_free(cli_exposure *e);
/* The whole of a file the user named (a settings file, a camera list...), at most limit bytes,
 * malloc'd and NUL-terminated, or NULL with why (n bytes) saying what was found: "no such file",
 * "a FIFO, not a regular file", "larger than N bytes", errno's text. The file is opened without
 * blocking and checked to be a regular file before a byte is read, so a FIFO or a device in its
 * place never hangs the command. *size (when not NULL) gets the bytes read. */
char *cli_read_regular(const char *path, size_t limit, size_t *size, char *why, size_t n);
/* path opened for reading the same way (never blocking, a regular file only: *st its fstat), the
 * descriptor then blocking for ordinary reads; -1 with why as above. */
struct stat;
int cli_open_regular(const char *path, struct stat *st, char *why, size_t n);
/* The pixel size a Radiance .hdr image (an environment map) declares in its header, read without
 * decoding it; false when the file is not one, is not a regular file or cannot be read. For an
 * estimate of the memory its decode will take. */
bool cli_hdr_dimensions(const char *path, long long *width, long long *height);
/* What a stat mode is, for messages: "a directory", "a FIFO", "a character device"... */
const char *cli_file_kind(unsigned mode);
/* Fail early when an output's directory cannot take a new file. */
bool cli_output_writable(const char *path);
/* Whether the frame r holds (w x h) covers any pixel: EXIT_OK, else "nothing visible from this
 * camera (scene:camera)" and code (EXIT_USAGE for a camera of the options, EXIT_INPUT for one of a
 * scene or sidecar). allow_empty (--allow-empty) skips the check. A silent empty image is a wrong
 * result: a camera that looks away, or coordinates float depth cannot hold. */
int cli_check_visible(ob_renderer *r, int w, int h, const char *scene, const char *camera, bool allow_empty, int code);

int cmd_render(int argc, char **argv);
int cmd_list(int argc, char **argv);
int cmd_sheet(int argc, char **argv);
int cmd_compare(int argc, char **argv);
int cmd_bench(int argc, char **argv);
int cmd_view(int argc, char **argv);
int cmd_tune(int argc, char **argv);
int cmd_dataset(int argc, char **argv);
int cmd_merge(int argc, char **argv);

#endif
