/* Regular files only, opened without blocking (file.h). */
#include "io/file.h"

#include <errno.h>
#include <fcntl.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/error.h"

const char *ob_file_kind(mode_t m)
{
    if (S_ISDIR(m)) return "a directory";
    if (S_ISFIFO(m)) return "a FIFO";
    if (S_ISCHR(m)) return "a character device";
    if (S_ISBLK(m)) return "a block device";
    if (S_ISSOCK(m)) return "a socket";
    return "not a regular file";
}

FILE *ob_fopen_regular(const char *path, const char *what)
{
    if (!path || !*path) {
        ob_set_error(OB_ERR_IO, "cannot read %s '': expected a file name", what);
        return NULL;
    }
    /* open() of a FIFO with no writer waits for one forever; O_NONBLOCK returns at once and fstat
     * then says what it is. */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        ob_set_error(OB_ERR_IO, "cannot read %s %s: %s", what, path, errno == ENOENT ? "no such file" : strerror(errno));
        return NULL;
    }
    struct stat st = {0};
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ob_set_error(OB_ERR_IO, "cannot read %s %s: it is %s, not a regular file", what, path, ob_file_kind(st.st_mode));
        close(fd);
        return NULL;
    }
    int flags = fcntl(fd, F_GETFL);
    if (flags >= 0) (void)fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        ob_set_error(OB_ERR_IO, "cannot read %s %s: %s", what, path, strerror(errno));
        close(fd);
    }
    return f;
}
