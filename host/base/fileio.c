/* fileio.c — write to a temporary name, fsync, then rename (see fileio.h).
 *
 * Durability (POSIX): fsync of the file before the rename makes its contents reach the disk
 * before its name can; fsync of the directory after the rename makes the new name itself
 * durable. A power loss then leaves either the old file or the complete new one. Temporary
 * files "<name>.tmp.<pid>" of writers that were killed are removed by the next writer of the
 * same name: a pid for which kill(pid, 0) fails with ESRCH is not a running process.
 *
 * Streams ("-", FIFOs, character devices) get their temporary file in $TMPDIR, named after the
 * stream's device and inode ("atmo-stream-<dev>-<ino>.tmp.<pid>"), and the commit copies it
 * into the stream. What a path names is looked at twice, by the temporary name and by the
 * commit; both take the same decision unless the path is changed in between. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "atmo/fileio.h"

/* The directory part of path ("." when there is none) into dir, and the name's offset. */
static size_t split_dir(const char *path, char *dir, size_t size)
{
    const char *slash = strrchr(path, '/');
    if (!slash) {
        snprintf(dir, size, ".");
        return 0;
    }
    size_t n = (size_t)(slash - path);
    snprintf(dir, size, "%.*s", (int)(n ? n : 1), path);
    return n + 1;
}

static const char *file_kind(mode_t m)
{
    return S_ISDIR(m) ? "a directory" : S_ISBLK(m) ? "a block device"
         : S_ISSOCK(m) ? "a socket" : S_ISFIFO(m) ? "a FIFO" : S_ISCHR(m) ? "a character device"
         : S_ISLNK(m) ? "a symbolic link" : "not a regular file";
}

int atmo_output_target(const char *option, const char *path, char *target, int *stream,
                       atmo_err *e)
{
    const char *opt = option ? option : "", *sp = option ? " " : "";
    struct stat st, to;
    *stream = 0;
    snprintf(target, ATMO_TMP_PATH_MAX, "%s", path);
    if (strcmp(path, "-") == 0) {
        *stream = 1;
        return ATMO_OK;
    }
    if (lstat(path, &st) != 0) /* a new file; its directory and name are the writer's to check */
        return ATMO_OK;
    if (S_ISLNK(st.st_mode)) {
        char real[PATH_MAX];
        if (stat(path, &to) != 0 || !realpath(path, real))
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "%s%s'%s' is a symbolic link that leads nowhere (%s); remove it or "
                             "give another name", opt, sp, path, strerror(errno));
        if (S_ISREG(to.st_mode))
            snprintf(target, ATMO_TMP_PATH_MAX, "%s", real);
        st = to;
    }
    if (S_ISREG(st.st_mode))
        return ATMO_OK;
    if (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode)) {
        *stream = 1;
        return ATMO_OK;
    }
    if (S_ISDIR(st.st_mode))
        return atmo_fail(e, ATMO_ERR_USAGE, "%s%s'%s' is a directory; give a file name", opt, sp,
                         path);
    return atmo_fail(e, ATMO_ERR_USAGE,
                     "%s%s'%s' is %s, not a regular file, FIFO or character device; atmo writes "
                     "nothing there (give a file name)", opt, sp, path, file_kind(st.st_mode));
}

int atmo_open_regular_fd(const char *path, const char **why)
{
    struct stat st;
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        if (why)
            *why = strerror(errno);
        return -1;
    }
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) ||
        fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) & ~O_NONBLOCK) != 0) {
        int regular = S_ISREG(st.st_mode);
        if (why)
            *why = regular ? strerror(errno)
                 : S_ISFIFO(st.st_mode) ? "not a regular file (a FIFO)"
                 : S_ISCHR(st.st_mode) ? "not a regular file (a character device)"
                 : S_ISDIR(st.st_mode) ? "not a regular file (a directory)"
                 : "not a regular file";
        close(fd);
        errno = regular ? errno : EINVAL;
        return -1;
    }
    return fd;
}

FILE *atmo_open_regular(const char *path, const char **why)
{
    int fd = atmo_open_regular_fd(path, why);
    FILE *f = fd < 0 ? NULL : fdopen(fd, "rb");
    if (fd >= 0 && !f) {
        if (why)
            *why = strerror(errno);
        close(fd);
    }
    return f;
}

/* The temporary file of a stream: in $TMPDIR, named after the stream's device and inode. */
static void stream_tmp_path(const char *target, char *tmp, size_t size)
{
    struct stat st = {0};
    const char *dir = getenv("TMPDIR");
    if (strcmp(target, "-") == 0 ? fstat(STDOUT_FILENO, &st) : stat(target, &st))
        memset(&st, 0, sizeof st);
    snprintf(tmp, size, "%s/atmo-stream-%lx-%lx", dir && *dir ? dir : "/tmp",
             (unsigned long)st.st_dev, (unsigned long)st.st_ino);
}

int atmo_remove_stale_tmp(const char *path)
{
    char dir[ATMO_TMP_PATH_MAX], prefix[ATMO_TMP_PATH_MAX], stale[ATMO_TMP_PATH_MAX];
    size_t name_at = split_dir(path, dir, sizeof dir);
    int n = snprintf(prefix, sizeof prefix, "%s.tmp.", path + name_at), removed = 0;
    DIR *d = opendir(dir);
    if (!d || n <= 0 || (size_t)n >= sizeof prefix) {
        if (d)
            closedir(d);
        return 0;
    }
    for (struct dirent *ent; (ent = readdir(d));) {
        if (strncmp(ent->d_name, prefix, (size_t)n) != 0)
            continue;
        char *end;
        errno = 0;
        long pid = strtol(ent->d_name + n, &end, 10);
        if (errno || end == ent->d_name + n || *end || pid <= 0 || pid == (long)getpid())
            continue;
        if (kill((pid_t)pid, 0) == -1 && errno == ESRCH) {
            snprintf(stale, sizeof stale, "%.*s%s", (int)name_at, path, ent->d_name);
            removed += remove(stale) == 0;
        }
    }
    closedir(d);
    return removed;
}

void atmo_tmp_path(const char *path, char *tmp)
{
    char target[ATMO_TMP_PATH_MAX], base[ATMO_TMP_PATH_MAX - 32];
    int stream = 0;
    if (atmo_output_target(NULL, path, target, &stream, NULL) != ATMO_OK)
        snprintf(target, sizeof target, "%s", path);
    if (stream)
        stream_tmp_path(target, base, sizeof base);
    else
        snprintf(base, sizeof base, "%.*s", (int)(sizeof base - 1), target);
    atmo_remove_stale_tmp(base);
    snprintf(tmp, ATMO_TMP_PATH_MAX, "%.*s.tmp.%ld", (int)(sizeof base - 1), base,
             (long)getpid());
}

FILE *atmo_atomic_open(const char *path, char *tmp, atmo_err *e)
{
    atmo_tmp_path(path, tmp);
    FILE *f = fopen(tmp, "wb");
    if (!f)
        atmo_fail(e, ATMO_ERR_RUNTIME, "cannot write '%s': %s (check the directory exists and is writable)",
                  path, strerror(errno));
    return f;
}

/* fsync a path opened read-only (a file written through a library, or a directory). A
 * directory that cannot be opened for reading (write and search permission only) or a file
 * system that cannot sync one (EINVAL) leaves the name's durability to the file system, which
 * is not a failure of the write: allow_unopened says so for directories. */
static int sync_path(const char *path, int allow_unopened)
{
    int fd = open(path, O_RDONLY);
    if (fd < 0)
        return allow_unopened ? 0 : -1;
    int rc = fsync(fd) != 0 && errno != EINVAL ? -1 : 0;
    close(fd);
    return rc;
}

/* Copy the file tmp into the stream target ("-": standard output); errno on failure. */
static int copy_to_stream(const char *tmp, const char *target)
{
    int in = open(tmp, O_RDONLY | O_CLOEXEC), out = -1, rc = -1;
    char buf[65536];
    if (in < 0)
        return -1;
    if (strcmp(target, "-") == 0) {
        fflush(stdout);
        out = STDOUT_FILENO;
    } else if ((out = open(target, O_WRONLY | O_CLOEXEC)) < 0) {
        goto cleanup;
    }
    for (;;) {
        ssize_t n = read(in, buf, sizeof buf);
        if (n < 0 && errno == EINTR)
            continue;
        if (n <= 0) {
            rc = n == 0 ? 0 : -1;
            break;
        }
        for (ssize_t done = 0; done < n;) {
            ssize_t w = write(out, buf + done, (size_t)(n - done));
            if (w < 0 && errno != EINTR)
                goto cleanup;
            done += w > 0 ? w : 0;
        }
    }
cleanup:;
    int err = errno;
    if (out > STDOUT_FILENO)
        rc |= close(out);
    close(in);
    errno = rc ? err : 0;
    return rc;
}

int atmo_atomic_commit(FILE *f, const char *tmp, const char *path, atmo_err *e)
{
    char target[ATMO_TMP_PATH_MAX];
    int failed = 0, stream = 0;
    if (f) {
        failed = ferror(f);
        failed |= fflush(f) != 0;
        failed |= fsync(fileno(f)) != 0;
        failed |= fclose(f) != 0;
    } else {
        failed = sync_path(tmp, 0) != 0;
    }
    if (failed) {
        int err = errno;
        remove(tmp);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "writing '%s' failed: %s", path, strerror(err));
    }
    if (atmo_output_target(NULL, path, target, &stream, e) != ATMO_OK) {
        remove(tmp);
        return ATMO_ERR_RUNTIME;
    }
    if (stream) {
        int rc = copy_to_stream(tmp, target), err = errno;
        remove(tmp);
        return rc ? atmo_fail(e, ATMO_ERR_RUNTIME, "writing '%s' failed: %s", path, strerror(err))
                  : ATMO_OK;
    }
    if (rename(tmp, target) != 0) {
        int err = errno;
        remove(tmp);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "cannot rename '%s' to '%s': %s", tmp, path,
                         strerror(err));
    }
    char dir[ATMO_TMP_PATH_MAX];
    split_dir(target, dir, sizeof dir);
    if (sync_path(dir, 1) != 0)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "cannot sync directory '%s' after writing '%s': %s",
                         dir, path, strerror(errno));
    return ATMO_OK;
}

void atmo_atomic_abort(FILE *f, const char *tmp)
{
    if (f)
        fclose(f);
    remove(tmp);
}

int atmo_write_text_file(const char *path, const char *text, atmo_err *e)
{
    char tmp[ATMO_TMP_PATH_MAX];
    FILE *f = atmo_atomic_open(path, tmp, e);
    if (!f)
        return ATMO_ERR_RUNTIME;
    fputs(text, f);
    return atmo_atomic_commit(f, tmp, path, e);
}
