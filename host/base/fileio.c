/* fileio.c — write to a temporary name, fsync, then rename (see fileio.h).
 *
 * Durability (POSIX): fsync of the file before the rename makes its contents reach the disk
 * before its name can; fsync of the directory after the rename makes the new name itself
 * durable. A power loss then leaves either the old file or the complete new one. Temporary
 * files "<name>.tmp.<pid>" of writers that were killed are removed by the next writer of the
 * same name: a pid for which kill(pid, 0) fails with ESRCH is not a running process. */
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
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
    atmo_remove_stale_tmp(path);
    snprintf(tmp, ATMO_TMP_PATH_MAX, "%s.tmp.%ld", path, (long)getpid());
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

int atmo_atomic_commit(FILE *f, const char *tmp, const char *path, atmo_err *e)
{
    int failed = 0;
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
    if (rename(tmp, path) != 0) {
        int err = errno;
        remove(tmp);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "cannot rename '%s' to '%s': %s", tmp, path,
                         strerror(err));
    }
    char dir[ATMO_TMP_PATH_MAX];
    split_dir(path, dir, sizeof dir);
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
