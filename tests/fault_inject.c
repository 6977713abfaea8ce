/* An LD_PRELOAD shim for tests/test_transaction.sh: it counts the calls that put a file in place
 * (rename, renameat, renameat2, link, linkat) and makes one of them fail, or sends a signal or
 * changes a file just before it, so that the test can stop a command at every step of writing and
 * committing its outputs. The production code has no hook for this: the dynamic linker puts these
 * functions in front of libc's.
 *
 *   OB_FAULT_RENAME_FAIL=N          the Nth counted call fails with EIO and does nothing
 *   OB_FAULT_RENAME_SIGNAL=N:SIG    SIG (INT, TERM, HUP or a number) is raised in the calling
 *                                   thread just before the Nth counted call, which then runs
 *   OB_FAULT_RENAME_KILL=N:SIG      SIG is sent to the process (kill, not raise: any thread that
 *                                   does not block it may take it) just before the Nth counted call
 *   OB_FAULT_RENAME_DIR=N:PATH      PATH is removed and made a directory just before the Nth
 *                                   counted call (an output turned into a directory mid-run)
 *   OB_FAULT_RENAME_FILE=N:PATH     PATH is written ("mine\n") just before the Nth counted call (a
 *                                   file of the user's that comes into a report mid-run)
 * Each action is a system call of its own: no shell ever runs, whatever the test passes.
 *   OB_FAULT_SKIP=PAT[:PAT...]      a call whose new name matches one of the patterns (fnmatch, '*'
 *                                   matches '/') is passed on without being counted
 *   OB_FAULT_LOG=FILE               one line per counted call, "N CALL OLD NEW", appended
 *   OB_FAULT_NO_LINK=1              every link and linkat fails with EPERM, uncounted, as on a file
 *                                   system without hard links (FAT) */
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <fnmatch.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

static int calls = 0;

static long env_number(const char *name, const char **rest)
{
    const char *v = getenv(name);
    *rest = NULL;
    if (!v || !*v) return 0;
    char *end = NULL;
    long n = strtol(v, &end, 10);
    if (end && *end == ':') *rest = end + 1;
    return n;
}

static int signal_of(const char *text)
{
    static const struct { const char *name; int sig; } names[] = {{"INT", SIGINT}, {"TERM", SIGTERM}, {"HUP", SIGHUP}};
    if (!text) return 0;
    for (size_t i = 0; i < sizeof names / sizeof names[0]; ++i)
        if (!strcmp(text, names[i].name)) return names[i].sig;
    return atoi(text);
}

static bool skipped(const char *to)
{
    const char *list = getenv("OB_FAULT_SKIP");
    if (!list || !to) return false;
    char pat[1024] = "";
    for (const char *p = list; *p;) {
        size_t n = strcspn(p, ":");
        if (n < sizeof pat) {
            memcpy(pat, p, n);
            pat[n] = '\0';
            if (n && fnmatch(pat, to, 0) == 0) return true;
        }
        p += n;
        if (*p == ':') ++p;
    }
    return false;
}

static void log_call(int n, const char *call, const char *from, const char *to)
{
    const char *path = getenv("OB_FAULT_LOG");
    if (!path || !*path) return;
    int fd = open(path, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) return;
    char line[8400] = "";
    int len = snprintf(line, sizeof line, "%d %s %s %s\n", n, call, from ? from : "?", to ? to : "?");
    if (len > 0) (void)!write(fd, line, (size_t)len < sizeof line ? (size_t)len : sizeof line - 1);
    close(fd);
}

/* Before a call: counts it and acts. false: fail it with EIO. */
static bool before(const char *call, const char *from, const char *to)
{
    if (skipped(to)) return true;
    int n = __atomic_add_fetch(&calls, 1, __ATOMIC_SEQ_CST);
    log_call(n, call, from, to);
    const char *rest = NULL;
    if (env_number("OB_FAULT_RENAME_KILL", &rest) == n) {
        int sig = signal_of(rest);
        if (sig > 0) kill(getpid(), sig);
    }
    if (env_number("OB_FAULT_RENAME_DIR", &rest) == n && rest) {
        (void)unlink(rest);
        (void)mkdir(rest, 0777);
    }
    if (env_number("OB_FAULT_RENAME_FILE", &rest) == n && rest) {
        int fd = open(rest, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
        if (fd >= 0) {
            (void)!write(fd, "mine\n", 5);
            close(fd);
        }
    }
    if (env_number("OB_FAULT_RENAME_SIGNAL", &rest) == n) {
        int sig = signal_of(rest);
        if (sig > 0) raise(sig);
    }
    if (env_number("OB_FAULT_RENAME_FAIL", &rest) == n) {
        errno = EIO;
        return false;
    }
    return true;
}

typedef int (*rename_fn)(const char *, const char *);
typedef int (*renameat_fn)(int, const char *, int, const char *);
typedef int (*renameat2_fn)(int, const char *, int, const char *, unsigned);
typedef int (*linkat_fn)(int, const char *, int, const char *, int);

/* libc's own function of that name. */
static void *next(const char *name)
{
    void *f = dlsym(RTLD_NEXT, name);
    if (!f) errno = ENOSYS;
    return f;
}

int rename(const char *from, const char *to)
{
    static rename_fn real = NULL;
    if (!real && !(*(void **)&real = next("rename"))) return -1;
    return before("rename", from, to) ? real(from, to) : -1;
}

int renameat(int fd1, const char *from, int fd2, const char *to)
{
    static renameat_fn real = NULL;
    if (!real && !(*(void **)&real = next("renameat"))) return -1;
    return before("renameat", from, to) ? real(fd1, from, fd2, to) : -1;
}

int renameat2(int fd1, const char *from, int fd2, const char *to, unsigned flags)
{
    static renameat2_fn real = NULL;
    if (!real && !(*(void **)&real = next("renameat2"))) return -1;
    return before(flags & RENAME_EXCHANGE ? "exchange" : "renameat2", from, to) ? real(fd1, from, fd2, to, flags) : -1;
}

static bool no_link(void)
{
    const char *v = getenv("OB_FAULT_NO_LINK");
    if (!v || strcmp(v, "1")) return false;
    errno = EPERM;
    return true;
}

int link(const char *from, const char *to)
{
    static rename_fn real = NULL;
    if (no_link() || (!real && !(*(void **)&real = next("link")))) return -1;
    return before("link", from, to) ? real(from, to) : -1;
}

int linkat(int fd1, const char *from, int fd2, const char *to, int flags)
{
    static linkat_fn real = NULL;
    if (no_link() || (!real && !(*(void **)&real = next("linkat")))) return -1;
    return before("linkat", from, to) ? real(fd1, from, fd2, to, flags) : -1;
}
