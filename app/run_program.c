/* Programs run with an argument vector, never through a shell (run_program.h). */
#include "run_program.h"

#include <cjson/cJSON.h>

#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "obscura/eval.h" /* ob_data_dir */

extern char **environ;

/* Appends what was read to o, up to its limit; the rest only marks it truncated. */
static void keep(cli_spawn_output *o, const char *buf, size_t n)
{
    if (!o->data && o->limit > 0) {
        o->data = malloc(o->limit + 1);
        if (o->data) o->data[0] = '\0';
    }
    size_t room = o->data ? o->limit - o->len : 0;
    size_t take = n < room ? n : room;
    if (take > 0) {
        memcpy(o->data + o->len, buf, take);
        o->len += take;
        o->data[o->len] = '\0';
    }
    if (take < n) o->truncated = true;
}

/* One stream of the child: a pipe whose write end becomes fd `target` in the child, or /dev/null. */
static int route(posix_spawn_file_actions_t *fa, int target, const cli_spawn_output *o, int pipe_fds[2])
{
    pipe_fds[0] = pipe_fds[1] = -1;
    if (!o) return posix_spawn_file_actions_addopen(fa, target, "/dev/null", O_WRONLY, 0);
    /* O_CLOEXEC: the child keeps only the end dup2 gives it, so EOF comes when it exits. */
    if (pipe2(pipe_fds, O_CLOEXEC) != 0) return errno;
    return posix_spawn_file_actions_adddup2(fa, pipe_fds[1], target);
}

static void close_fd(int *fd)
{
    if (*fd >= 0) close(*fd);
    *fd = -1;
}

int cli_spawn(const char *const argv[], int stdin_fd, cli_spawn_output *out, cli_spawn_output *err, int *status)
{
    *status = -1;
    int out_pipe[2] = {-1, -1}, err_pipe[2] = {-1, -1};
    posix_spawn_file_actions_t fa;
    int e = posix_spawn_file_actions_init(&fa);
    if (e != 0) return e;
    if (stdin_fd >= 0) e = posix_spawn_file_actions_adddup2(&fa, stdin_fd, 0);
    else e = posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    if (e == 0) e = route(&fa, 1, out, out_pipe);
    if (e == 0) e = route(&fa, 2, err, err_pipe);
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 34))
    /* The CLI's other descriptors (the EGL device, files being written) are none of the
     * program's business. */
    if (e == 0) e = posix_spawn_file_actions_addclosefrom_np(&fa, 3);
#endif
    pid_t pid = -1;
    /* posix_spawnp looks argv[0] up on PATH and execs it directly: the arguments reach the program
     * byte for byte. glibc reports a failed exec (ENOENT: not installed) as its return value. */
    if (e == 0) e = posix_spawnp(&pid, argv[0], &fa, NULL, (char *const *)argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    close_fd(&out_pipe[1]);
    close_fd(&err_pipe[1]);
    if (e != 0) {
        close_fd(&out_pipe[0]);
        close_fd(&err_pipe[0]);
        return e;
    }
    /* Both pipes read together until both are closed: a program that fills one while we wait on
     * the other would otherwise block for ever. */
    struct pollfd fds[2] = {{.fd = out_pipe[0], .events = POLLIN}, {.fd = err_pipe[0], .events = POLLIN}};
    cli_spawn_output *dest[2] = {out, err};
    while (fds[0].fd >= 0 || fds[1].fd >= 0) {
        if (poll(fds, 2, -1) < 0) {
            if (errno == EINTR) continue;
            break;
        }
        for (int k = 0; k < 2; ++k) {
            if (fds[k].fd < 0 || !(fds[k].revents & (POLLIN | POLLHUP | POLLERR))) continue;
            char buf[4096];
            ssize_t n = read(fds[k].fd, buf, sizeof buf);
            if (n > 0) keep(dest[k], buf, (size_t)n);
            else if (n == 0 || errno != EINTR) {
                close(fds[k].fd);
                fds[k].fd = -1; /* poll skips negative descriptors */
            }
        }
    }
    close_fd(&fds[0].fd);
    close_fd(&fds[1].fd);
    int st = 0;
    while (waitpid(pid, &st, 0) < 0)
        if (errno != EINTR) return errno;
    *status = WIFEXITED(st) ? WEXITSTATUS(st) : WIFSIGNALED(st) ? 128 + WTERMSIG(st) : -1;
    return 0;
}

void cli_spawn_output_free(cli_spawn_output *o)
{
    free(o->data);
    o->data = NULL;
    o->len = 0;
    o->truncated = false;
}

void cli_spawn_last_line(const cli_spawn_output *o, char *buf, size_t n)
{
    if (n == 0) return;
    buf[0] = '\0';
    if (!o || !o->data) return;
    const char *text = o->data;
    size_t end = o->len;
    /* gnuplot's error ends with "line N: what", after the command echoed and a '^' under the
     * spot; git's with "fatal: what". */
    while (end > 0 && (unsigned char)text[end - 1] <= ' ') --end; /* trailing blanks and newlines */
    size_t start = end;
    while (start > 0 && text[start - 1] != '\n') --start;
    while (start < end && (unsigned char)text[start] <= ' ') ++start;
    size_t k = 0;
    for (size_t i = start; i < end && k + 1 < n; ++i) {
        unsigned char ch = (unsigned char)text[i];
        buf[k++] = ch < ' ' || ch == 0x7f ? ' ' : (char)ch;
    }
    buf[k] = '\0';
}

void cli_git_commit(char *out, size_t n)
{
    snprintf(out, n, "unknown");
    const char *dir = ob_data_dir();
    if (!dir) return;
    /* git gets the directory as one argument, with no shell (run_program.h): any name works, quotes
     * included, and none runs a command. No git, no repository: "unknown". */
    const char *argv[] = {"git", "-C", dir, "rev-parse", "--short", "HEAD", NULL};
    cli_spawn_output line = {.limit = 127};
    int status = -1;
    if (cli_spawn(argv, -1, &line, NULL, &status) == 0 && status == 0 && line.data && !line.truncated) {
        line.data[strcspn(line.data, "\r\n")] = '\0';
        if (line.data[0]) snprintf(out, n, "%s", line.data);
    }
    cli_spawn_output_free(&line);
}

void cli_json_commit_and_command(cJSON *root, int argc, char **argv)
{
    char commit[64];
    cli_git_commit(commit, sizeof commit);
    cJSON_AddStringToObject(root, "commit", commit);
    cJSON *cmd = cJSON_AddArrayToObject(root, "command_line");
    for (int i = 0; i < argc; ++i) cJSON_AddItemToArray(cmd, cJSON_CreateString(argv[i]));
}
