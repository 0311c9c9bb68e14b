/* cl_runtime.h — the OpenCL device, its context and queue, and program builds.
 *
 * Device choice: a selector (from --device or the ATMO_DEVICE variable) that is either a number
 * (the index in `atmo devices`' list) or a case-insensitive substring of "platform / device";
 * with none, the first GPU, else the first CPU, else the first device of any kind.
 *
 * Programs are assembled from the embedded fragments of kernels/ (atmo/embedded.h), each preceded
 * by a #line directive naming its file, and built with "-cl-std=CL1.2" plus the plan's -D flags.
 * Built binaries are cached in the cache directory (ATMO_CACHE_DIR, else
 * $XDG_CACHE_HOME/atmo, else ~/.cache/atmo), keyed by a hash of platform, device, driver
 * version, options and source, so a second run does not compile. A failed build prints the
 * build log.
 *
 * Every OpenCL call is checked; failures name the call and the error (ATMO_ERR_RUNTIME). */
#ifndef ATMO_CL_RUNTIME_H
#define ATMO_CL_RUNTIME_H
#include <CL/cl.h>
#include "atmo/status.h"

typedef struct atmo_cl {
    cl_platform_id platform;
    cl_device_id device;
    cl_context context;
    cl_command_queue queue;
    char platform_name[256];
    char device_name[256];
    char device_vendor[256];
    char driver_version[128];
    char device_version[128];
    cl_device_type type;
    cl_uint compute_units;
    cl_ulong global_memory;
    int has_fp64;
    int device_index; /* in the list of `atmo devices` */
} atmo_cl;

typedef struct atmo_cl_build_options {
    const char *const *fragments; /* embedded names, in order, e.g. "kernels/common/compat.h" */
    int fragment_count;
    const char *defines;          /* extra options, e.g. "-DATMO_LUMINANCE" (may be NULL) */
    const char *dump_dir;         /* --dump-kernels DIR, or NULL */
    int use_cache;                /* 0 with --no-kernel-cache */
    const char *extra_source;     /* appended after the fragments (tests' probe kernels), or NULL */
    const char *prelude;          /* generated source before the fragments (the plan's buffer
                                     lists, atmo/plan.h), or NULL */
    const char *const *texts;     /* per fragment: its generated text (the plan's composition,
                                     atmo/features.h) or NULL for an embedded file; NULL: all
                                     embedded */
} atmo_cl_build_options;

typedef struct atmo_cl_build_info {
    int cache_hit;
    double seconds;
    unsigned long long key;
} atmo_cl_build_info;

const char *atmo_cl_error_string(cl_int err);
/* Format "CALL failed: ERROR" into e and return ATMO_ERR_RUNTIME. */
int atmo_cl_fail(atmo_err *e, const char *call, cl_int err);

/* Print every platform and device (name, type, compute units, memory, fp64, driver). */
int atmo_cl_list_devices(int json, atmo_err *e);

int atmo_cl_open(atmo_cl *cl, const char *selector, atmo_err *e);
void atmo_cl_close(atmo_cl *cl);

/* Assemble, build (or load from the cache) and return a program. */
int atmo_cl_build(atmo_cl *cl, const atmo_cl_build_options *o, cl_program *program,
                  atmo_cl_build_info *info, atmo_err *e);

/* The assembled source (malloc'd), as the build sees it; prelude (may be NULL) goes first,
 * extra (may be NULL) last; fragment i is texts[i] where texts and texts[i] are not NULL
 * (generated source, named fragments[i] in #line), else the embedded file fragments[i]. */
char *atmo_cl_assemble(const char *prelude, const char *const *fragments,
                       const char *const *texts, int count, const char *extra, atmo_err *e);

/* Cache directory (created if missing); returns 0 and fills dir, or -1. */
int atmo_cache_dir(char *dir, size_t size);

/* PoCL's own cache (the compiled kernels and their work-group functions, which it builds at a
 * kernel's first launch): POCL_CACHE_DIR when the user set it, else "<atmo_cache_dir>/pocl",
 * which atmo_cl_open (and every device listing) puts into POCL_CACHE_DIR before the platform is
 * opened, so both caches live in one place. Returns 0 and fills dir, or -1 (no cache dir). */
int atmo_cl_driver_cache_dir(char *dir, size_t size);
/* PoCL reads its settings once, when the ICD loader first opens it: set POCL_CACHE_DIR and
 * POCL_WORK_GROUP_SPECIALIZATION before that, each only where the user has not (without a cache
 * directory PoCL keeps its own default). setenv is not thread-safe, so a program with threads
 * (the viewer: GLFW, Mesa and the render thread) calls this once before it starts any; the
 * first OpenCL call of atmo_cl_open calls it too, which changes nothing once it has run. */
void atmo_cl_prepare_environment(void);

#endif
