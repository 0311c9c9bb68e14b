/* output_paths.c — the files a command writes, checked before the work, so that a render never
 * runs to its end only to fail at its outputs, and no output overwrites another.
 *
 * A path is accepted when its directory exists, is a directory and is writable (and
 * searchable), the path is not a directory itself (nor ends in '/', '.' or '..'), and both the
 * path and its temporary sibling (atmo/fileio.h: "<path>.tmp.<pid>", which is what is created
 * first) fit the file system's limits: the name's length against pathconf(dir, _PC_NAME_MAX)
 * (NAME_MAX), the resolved directory plus the name against pathconf(dir, _PC_PATH_MAX)
 * (PATH_MAX), and the path as given against ATMO_TMP_PATH_MAX. Two paths are the same file
 * when the realpath(3) of their directories and their names agree: what rename(2) replaces is
 * the directory entry, so this is the identity that matters.
 *
 * What the path names decides how it is written (atmo/fileio.h, atmo_output_target): a
 * symbolic link to a regular file is followed, and the checks above apply to the file it
 * leads to, whose identity it takes; "-", a FIFO or a character device is written through
 * (its identity is "-" or its realpath, and it needs no directory); anything else is refused.
 *
 * An output is also never one of the command's inputs (output_paths_check_input): the input's
 * device and inode against those of each output that exists already, which sees through
 * symbolic links, hard links and any spelling of the path. */
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "atmo/fileio.h"
#include "output_paths.h"

/* Bytes that the temporary name adds to a path (".tmp.<pid>"). */
static size_t tmp_suffix_length(void)
{
    char tmp[ATMO_TMP_PATH_MAX];
    atmo_tmp_path("x", tmp);
    return strlen(tmp) - 1;
}

static long limit(const char *dir, int name, long fallback)
{
    errno = 0;
    long v = pathconf(dir, name);
    return v > 0 ? v : fallback;
}

/* The checks of the header; *file gets the file's identity (malloc'd). */
static int check_path(const char *option, const char *path, char **file, atmo_err *e)
{
    size_t len = strlen(path), suffix = tmp_suffix_length();
    const char *slash = strrchr(path, '/');
    const char *name = slash ? slash + 1 : path;
    char dir[ATMO_TMP_PATH_MAX], real[PATH_MAX], target[ATMO_TMP_PATH_MAX];
    struct stat st;
    int stream = 0, rc;
    *file = NULL;
    if (len == 0)
        return atmo_fail(e, ATMO_ERR_USAGE, "%s needs a file name, got ''", option);
    if ((rc = atmo_output_target(option, path, target, &stream, e)))
        return rc;
    if (stream) {
        *file = strdup(strcmp(target, "-") == 0 || !realpath(target, real) ? target : real);
        return *file ? ATMO_OK : atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory checking '%s'",
                                           path);
    }
    if (strcmp(target, path) != 0) { /* a symbolic link: the checks are the target's */
        path = target;
        len = strlen(path);
        slash = strrchr(path, '/');
        name = slash ? slash + 1 : path;
    }
    if (len + suffix >= ATMO_TMP_PATH_MAX)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s '%.64s...': the path is too long (%zu bytes; at most %zu)", option,
                         path, len, (size_t)ATMO_TMP_PATH_MAX - 1 - suffix);
    if (*name == 0 || strcmp(name, ".") == 0 || strcmp(name, "..") == 0)
        return atmo_fail(e, ATMO_ERR_USAGE, "%s '%s' is a directory; give a file name", option,
                         path);
    if (!slash)
        snprintf(dir, sizeof dir, ".");
    else if (slash == path)
        snprintf(dir, sizeof dir, "/");
    else
        snprintf(dir, sizeof dir, "%.*s", (int)(slash - path), path);
    if (stat(dir, &st) != 0)
        return atmo_fail(e, ATMO_ERR_USAGE, "%s '%s': directory '%s' does not exist", option,
                         path, dir);
    if (!S_ISDIR(st.st_mode))
        return atmo_fail(e, ATMO_ERR_USAGE, "%s '%s': '%s' is not a directory", option, path,
                         dir);
    if (access(dir, W_OK | X_OK) != 0)
        return atmo_fail(e, ATMO_ERR_USAGE, "%s '%s': directory '%s' is not writable (%s)",
                         option, path, dir, strerror(errno));
    long name_max = limit(dir, _PC_NAME_MAX, NAME_MAX);
    long path_max = limit(dir, _PC_PATH_MAX, PATH_MAX);
    if ((long)(strlen(name) + suffix) > name_max)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s '%.64s...': the file name is too long (%zu bytes; at most %ld with "
                         "the temporary suffix, NAME_MAX = %ld)",
                         option, path, strlen(name), name_max - (long)suffix, name_max);
    if (!realpath(dir, real))
        return atmo_fail(e, ATMO_ERR_USAGE, "%s '%s': cannot resolve directory '%s' (%s)",
                         option, path, dir, strerror(errno));
    size_t full = strlen(real) + 1 + strlen(name);
    if ((long)(full + suffix) >= path_max)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s '%.64s...': the path is too long (%zu bytes resolved; at most %ld "
                         "with the temporary suffix, PATH_MAX = %ld)",
                         option, path, full, path_max - 1 - (long)suffix, path_max);
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
        return atmo_fail(e, ATMO_ERR_USAGE, "%s '%s' is a directory; give a file name", option,
                         path);
    *file = malloc(full + 1);
    if (!*file)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "out of memory checking '%s'", path);
    snprintf(*file, full + 1, "%s/%s", strcmp(real, "/") == 0 ? "" : real, name);
    return ATMO_OK;
}

int output_paths_add(output_paths *o, const char *option, const char *path, atmo_err *e)
{
    char *file;
    int rc = check_path(option, path, &file, e);
    if (rc)
        return rc;
    for (int i = 0; i < o->count; i++) {
        if (strcmp(o->file[i], file) != 0)
            continue;
        free(file);
        if (strcmp(o->option[i], option) == 0)
            return ATMO_OK;
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s '%s' and %s '%s' are the same file; give each its own name", option,
                         path, o->option[i], o->path[i]);
    }
    if (o->count == OUTPUT_PATHS_MAX) {
        free(file);
        return atmo_fail(e, ATMO_ERR_USAGE, "more than %d output files", OUTPUT_PATHS_MAX);
    }
    o->path[o->count] = path;
    o->option[o->count] = option;
    o->file[o->count++] = file;
    return ATMO_OK;
}

int output_paths_check_input(const output_paths *o, const char *what, const char *input,
                             atmo_err *e)
{
    struct stat in, out;
    if (!input || !*input || strcmp(input, "-") == 0 || stat(input, &in) != 0)
        return ATMO_OK;
    for (int i = 0; i < o->count; i++)
        if (strcmp(o->path[i], "-") != 0 && stat(o->path[i], &out) == 0 &&
            out.st_dev == in.st_dev && out.st_ino == in.st_ino)
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "%s '%s' is the input %s '%s'; atmo never overwrites its inputs, "
                             "give the output another name",
                             o->option[i], o->path[i], what, input);
    return ATMO_OK;
}

void output_paths_free(output_paths *o)
{
    for (int i = 0; i < o->count; i++)
        free(o->file[i]);
    o->count = 0;
}
