/* cl_runtime.h — the OpenCL device, its context and queue, and program builds.
 *
 * Device choice: a selector (from --device or the ATMO_DEVICE variable) that is either a number
 * (the index in `atmo devices`' list) or a case-insensitive substring of
 * "platform (platform vendor) / device";
 * with none, the first GPU, else the first CPU, else the first device of any kind. Only devices
 * that meet the kernels' requirements (atmo_cl_caps_usable) are chosen: a selector that names a
 * device that does not meet them is refused with the reason, and the default skips it.
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
#include <stdio.h>
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

/* The largest work group atmo launches: 8 x 8 render tiles (session.c), 8 x 8 x 1 and
 * 4 x 4 x 4 precompute passes (precompute.c). */
#define ATMO_CL_WORK_GROUP_ITEMS 64
#define ATMO_CL_WORK_ITEM_MIN_X 8
#define ATMO_CL_WORK_ITEM_MIN_Y 8
#define ATMO_CL_WORK_ITEM_MIN_Z 4

/* What the kernels need of a device, as clGetDeviceInfo reports it. */
typedef struct atmo_cl_caps {
    int available;                 /* CL_DEVICE_AVAILABLE */
    int compiler;                  /* CL_DEVICE_COMPILER_AVAILABLE: kernels build from source */
    char c_version[128];           /* CL_DEVICE_OPENCL_C_VERSION, "OpenCL C <major>.<minor> ..." */
    cl_device_fp_config single_fp; /* CL_DEVICE_SINGLE_FP_CONFIG */
    size_t max_work_group;         /* CL_DEVICE_MAX_WORK_GROUP_SIZE */
    size_t max_work_item[3];       /* CL_DEVICE_MAX_WORK_ITEM_SIZES */
} atmo_cl_caps;

/* The caps of a device (unreadable fields stay 0 or ""). */
void atmo_cl_query_caps(cl_device_id device, atmo_cl_caps *caps);

/* 1 if a device with these caps can run atmo's kernels; else 0 and why not, one phrase, in why:
 * not available, no compiler, OpenCL C below 1.2 (the kernels are OpenCL C 1.2), float without
 * Inf/NaN or round-to-nearest (the kernels test for NaN and rely on IEEE rounding), or work
 * groups smaller than ATMO_CL_WORK_GROUP_ITEMS (8 x 8 x 4 items). */
int atmo_cl_caps_usable(const atmo_cl_caps *caps, char *why, size_t size);

/* Print every platform and its devices (name, vendor, type, versions, compute units, memory),
 * why a device is skipped, and which one a render would use with this selector (NULL: the
 * ATMO_DEVICE variable, else the default); json: the same as one JSON object. A selector that
 * names no usable device is ATMO_ERR_USAGE, and nothing is printed. */
int atmo_cl_list_devices(const char *selector, int json, atmo_err *e);

/* The device a selector names (NULL: ATMO_DEVICE, else the default), by the rule atmo_cl_open
 * uses, without opening it: a command checks its --device before any work. A selector that
 * names no usable device is ATMO_ERR_USAGE with the devices listed. */
int atmo_cl_check_selector(const char *selector, atmo_err *e);

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

/* The cache directory: ATMO_CACHE_DIR, else $XDG_CACHE_HOME/atmo, else ~/.cache/atmo, created
 * if missing. atmo_cache_dir_find returns 0 when it is usable (atmo_cache_dir_usable), else -1
 * with the reason in why (dir still names it). atmo_cache_dir is the same for a cache that is
 * about to be used: the first time in a process that the directory is unusable it prints one
 * warning naming it and why, and the caller runs without that cache. */
int atmo_cache_dir_find(char *dir, size_t size, char *why, size_t why_size);
int atmo_cache_dir(char *dir, size_t size);
/* 1 when dir is a directory in which a file can be created, written and removed; else 0 with
 * the reason in why. */
int atmo_cache_dir_usable(const char *dir, char *why, size_t size);
/* Check every program in PoCL's cache directory pocl_dir (host/cl/cl_driver_cache.c) and
 * remove those with a file cut short, each with one line on say (when not NULL); returns how
 * many were removed. */
int atmo_cl_driver_cache_repair(const char *pocl_dir, FILE *say);
/* 1 when POCL_CACHE_DIR is atmo's own ("<cache dir>/pocl", set by atmo_cl_prepare_environment
 * or not set yet), 0 when the user set it. */
int atmo_cl_driver_cache_is_own(void);

/* PoCL's own cache (the compiled kernels and their work-group functions, which it builds at a
 * kernel's first launch): POCL_CACHE_DIR when the user set it, else "<atmo_cache_dir>/pocl",
 * which atmo_cl_open (and every device listing) puts into POCL_CACHE_DIR before the platform is
 * opened, so both caches live in one place. Returns 0 and fills dir, or -1 (no cache dir). */
int atmo_cl_driver_cache_dir(char *dir, size_t size);
/* When the cache directory is unusable, PoCL (which must write its build products somewhere)
 * gets a private temporary directory in $TMPDIR (/tmp without it), removed when atmo exits;
 * atmo's own PoCL directory is repaired (atmo_cl_driver_cache_repair) by the first listing of
 * the platforms, before PoCL reads it. */
/* PoCL reads its settings once, when the ICD loader first opens it: set POCL_CACHE_DIR and
 * POCL_WORK_GROUP_SPECIALIZATION before that, each only where the user has not (without a cache
 * directory PoCL keeps its own default). setenv is not thread-safe, so a program with threads
 * (the viewer: GLFW, Mesa and the render thread) calls this once before it starts any; the
 * first OpenCL call of atmo_cl_open calls it too, which changes nothing once it has run. */
void atmo_cl_prepare_environment(void);

#endif
