/* Running another program (gnuplot for compare's chart, git for bench's commit) without a shell:
 * an argument vector through posix_spawnp, so no path or name the user gave is ever parsed as a
 * command line (issue 44: a report called "rep'$(touch X)'x" once ran touch). Paths go to the
 * program as whole argv elements or not at all; data goes on stdin.
 *
 *   const char *argv[] = {"git", "-C", dir, "rev-parse", "--short", "HEAD", NULL};
 *   cli_spawn_output out = {.limit = 128};
 *   int status = 0;
 *   int e = cli_spawn(argv, -1, &out, NULL, &status);  e: 0, or an errno value (ENOENT: not on PATH)
 *   ...out.data (out.len bytes, NUL-terminated) when e == 0 && status == 0...
 *   cli_spawn_output_free(&out);
 */
#ifndef OB_CLI_RUN_PROGRAM_H
#define OB_CLI_RUN_PROGRAM_H

#include <stdbool.h>
#include <stddef.h>

/* What a program wrote on one stream: at most `limit` bytes are kept (the rest is read and
 * dropped, so the program never blocks on a full pipe), NUL-terminated. */
typedef struct cli_spawn_output {
    char *data;     /* malloc'd; NULL until something was read */
    size_t len;
    size_t limit;   /* set by the caller; 0 keeps nothing */
    bool truncated; /* the program wrote more than limit */
} cli_spawn_output;

/* Runs argv[0] (looked up on PATH) with argv, and waits for it. stdin_fd: the program's stdin
 * (the caller keeps and closes it), or -1 for /dev/null. out, err: its stdout and stderr through
 * pipes, or NULL for /dev/null. Returns 0 once the program ran and ended, *status then being its
 * exit status (128 + the signal that killed it); or an errno value and nothing ran: ENOENT when
 * the program is not installed, EACCES when it is not executable, ENOMEM, EMFILE... */
int cli_spawn(const char *const argv[], int stdin_fd, cli_spawn_output *out, cli_spawn_output *err, int *status);
void cli_spawn_output_free(cli_spawn_output *o);
/* The last non-blank line of what a program wrote (its error, usually), trimmed, into buf
 * ("" when none). Control bytes become spaces: the line goes into one of our stderr lines. */
void cli_spawn_last_line(const cli_spawn_output *o, char *buf, size_t n);

/* The source tree's commit (`git rev-parse --short HEAD` in the data directory, run without a
 * shell), or "unknown" without git or a repository: what results.json and bench --json record. */
void cli_git_commit(char *out, size_t n);

/* "commit" (cli_git_commit) and "command_line" (argv as given, every option that shaped the run)
 * into a JSON object: what compare's results.json, bench --json and dataset's manifest record. */
struct cJSON;
void cli_json_commit_and_command(struct cJSON *root, int argc, char **argv);

#endif
