/* overwrite.c — refuse to replace an existing output without --force (overwrite.h).
 *
 * Outputs are written to a temporary file and renamed over the target, so a render never
 * leaves a half-written file; that same rename would silently replace a finished image of an
 * earlier run. The commands therefore check each output before any work: a regular file
 * there (followed through symbolic links) is refused with exit status 2 unless --force is
 * given. Devices and FIFOs are written through, not replaced, and are allowed. */
#include <sys/stat.h>
#include "overwrite.h"

int overwrite_check(const char *option, const char *path, int force, atmo_err *e)
{
    struct stat st;
    if (force || stat(path, &st) != 0 || !S_ISREG(st.st_mode))
        return ATMO_OK;
    return atmo_fail(e, ATMO_ERR_USAGE,
                     "%s '%s' exists; add --force to overwrite it, or choose another name", option,
                     path);
}
