/* Files embedded into the binary at build time (tools/embed.c): the OpenCL C fragments of
 * kernels/ and the spectral tables of data/. Names are paths relative to the source tree,
 * e.g. "kernels/common/rng.h" or "data/cie1931_2deg_cmf.csv". Each table ends with a NULL name. */
#ifndef ATMO_EMBEDDED_H
#define ATMO_EMBEDDED_H
#include <stddef.h>

struct atmo_embedded_file {
    const char *name;
    const char *text;
    size_t size;
};

extern const struct atmo_embedded_file atmo_kernel_sources[];
extern const struct atmo_embedded_file atmo_data_files[];

/* The embedded file with this name, or NULL. */
const struct atmo_embedded_file *atmo_embedded_find(const struct atmo_embedded_file *table,
                                                    const char *name);

#endif
