/* output_paths.h — every file a command will write, checked before any work (output_paths.c). */
#ifndef ATMO_OUTPUT_PATHS_H
#define ATMO_OUTPUT_PATHS_H
#include "atmo/status.h"

#define OUTPUT_PATHS_MAX 16

typedef struct output_paths {
    int count;
    const char *path[OUTPUT_PATHS_MAX];   /* as given, one per file */
    const char *option[OUTPUT_PATHS_MAX]; /* the option that named it, e.g. "--output" */
    char *file[OUTPUT_PATHS_MAX];         /* realpath of its directory + "/" + its name */
} output_paths;

/* Check that `path` can be written (ATMO_ERR_USAGE with one line naming it otherwise) and add
 * it. A path naming the same file as one added before under the same option is one output and
 * is not added again (returns ATMO_OK); under another option it is an error. */
int output_paths_add(output_paths *o, const char *option, const char *path, atmo_err *e);
/* ATMO_ERR_USAGE naming both when an output added so far is the existing file `input` (the
 * same device and inode: any spelling, symbolic or hard link); `what` says which input it is,
 * e.g. "--scene". A NULL or absent input is no conflict. */
int output_paths_check_input(const output_paths *o, const char *what, const char *input,
                             atmo_err *e);
void output_paths_free(output_paths *o);

#endif
