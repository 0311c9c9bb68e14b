/* fileio.c — write to a temporary name, then rename (see fileio.h). */
#include <errno.h>
#include <string.h>
#include <unistd.h>
#include "atmo/fileio.h"

void atmo_tmp_path(const char *path, char *tmp)
{
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

int atmo_atomic_commit(FILE *f, const char *tmp, const char *path, atmo_err *e)
{
    int failed = 0;
    if (f) {
        failed = ferror(f);
        failed |= fclose(f) != 0;
    }
    if (failed) {
        remove(tmp);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "writing '%s' failed: %s", path, strerror(errno));
    }
    if (rename(tmp, path) != 0) {
        int err = errno;
        remove(tmp);
        return atmo_fail(e, ATMO_ERR_RUNTIME, "cannot rename '%s' to '%s': %s", tmp, path,
                         strerror(err));
    }
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
