/* denoise.c — Intel Open Image Denoise 2.x through its C API, opened with dlopen (atmo/denoise.h).
 *
 * The library ships without headers in the PyPI wheel, so the few entry points used here are
 * declared below from OIDN's API documentation (include/OpenImageDenoise/oidn.h of OIDN 2.x):
 *   OIDNDevice oidnNewDevice(OIDNDeviceType)            OIDN_DEVICE_TYPE_CPU = 1
 *   void oidnSetDeviceInt(OIDNDevice, const char *, int), int oidnGetDeviceInt(..., const char *)
 *   void oidnCommitDevice(OIDNDevice), void oidnReleaseDevice(OIDNDevice)
 *   OIDNError oidnGetDeviceError(OIDNDevice, const char **message)   OIDN_ERROR_NONE = 0
 *   OIDNFilter oidnNewFilter(OIDNDevice, const char *type)
 *   void oidnSetSharedFilterImage(OIDNFilter, const char *name, void *ptr, OIDNFormat,
 *                                 size_t width, size_t height, size_t byteOffset,
 *                                 size_t pixelByteStride, size_t rowByteStride)
 *                                                       OIDN_FORMAT_FLOAT3 = 3
 *   void oidnSetFilterBool(OIDNFilter, const char *, bool), oidnSetFilterInt(..., int)
 *   void oidnCommitFilter(OIDNFilter), oidnExecuteFilter(OIDNFilter), oidnReleaseFilter(OIDNFilter)
 * with the filter qualities OIDN_QUALITY_FAST = 4, BALANCED = 5, HIGH = 6, and the device's
 * "version" parameter = major * 10000 + minor * 100 + patch. The handles are opaque pointers and
 * the enums are C ints, so void * and int stand for them.
 *
 * A device is created per atmo_denoise_run (and one at load time for the version check): its
 * cost is small beside the filter's, and no OIDN state outlives a call. */
#include <dlfcn.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "atmo/denoise.h"

#define OIDN_LIBRARY_NAME "libOpenImageDenoise.so.2"
#define OIDN_DEVICE_TYPE_CPU 1
#define OIDN_ERROR_NONE 0
#define OIDN_FORMAT_FLOAT3 3
#define OIDN_MIN_VERSION 20000

typedef struct oidn_api {
    void *(*new_device)(int type);
    void (*set_device_int)(void *device, const char *name, int value);
    int (*get_device_int)(void *device, const char *name);
    void (*commit_device)(void *device);
    void (*release_device)(void *device);
    int (*get_device_error)(void *device, const char **message);
    void *(*new_filter)(void *device, const char *type);
    void (*set_shared_filter_image)(void *filter, const char *name, void *ptr, int format,
                                    size_t width, size_t height, size_t byte_offset,
                                    size_t pixel_stride, size_t row_stride);
    void (*set_filter_bool)(void *filter, const char *name, bool value);
    void (*set_filter_int)(void *filter, const char *name, int value);
    void (*commit_filter)(void *filter);
    void (*execute_filter)(void *filter);
    void (*release_filter)(void *filter);
} oidn_api;

/* The process's one load: its result, the library and its entry points. */
static struct {
    int tried, status;
    atmo_err err;
    void *handle;
    oidn_api api;
    int version;
    char path[4096];
} lib;

const char *atmo_denoise_quality_name(int quality)
{
    return quality == ATMO_DENOISE_FAST       ? "fast"
           : quality == ATMO_DENOISE_BALANCED ? "balanced"
                                              : "high";
}

int atmo_denoise_version(void)
{
    return lib.status == ATMO_OK && lib.tried ? lib.version : 0;
}

const char *atmo_denoise_library_path(void)
{
    return lib.status == ATMO_OK && lib.tried ? lib.path : "";
}

/* dlopen `path` (a file, or a folder that holds the library); 1 when it opened. */
static int open_at(const char *path)
{
    struct stat st;
    char file[sizeof lib.path];
    if (stat(path, &st) == 0 && S_ISDIR(st.st_mode))
        snprintf(file, sizeof file, "%s/%s", path, OIDN_LIBRARY_NAME);
    else
        snprintf(file, sizeof file, "%s", path);
    lib.handle = dlopen(file, RTLD_NOW | RTLD_LOCAL);
    if (lib.handle)
        snprintf(lib.path, sizeof lib.path, "%s", file);
    return lib.handle != NULL;
}

/* Try the three places in order (denoise.h); ATMO_ERR_USAGE with the places when none has it. */
static int open_library(atmo_err *e)
{
    const char *env = getenv("ATMO_OIDN_LIBRARY");
    if (env && *env) {
        if (open_at(env))
            return ATMO_OK;
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "ATMO_OIDN_LIBRARY='%s': cannot load Intel Open Image Denoise (%s); point "
                         "it at pyoidn's pyoidn/oidn/lib/" OIDN_LIBRARY_NAME " or unset it",
                         env, dlerror());
    }
#ifdef ATMO_OIDN_RECORDED_PATH
    if (open_at(ATMO_OIDN_RECORDED_PATH))
        return ATMO_OK;
#endif
    if (open_at(OIDN_LIBRARY_NAME))
        return ATMO_OK;
    return atmo_fail(e, ATMO_ERR_USAGE,
                     "Intel Open Image Denoise 2.x (" OIDN_LIBRARY_NAME ") is not installed: run "
                     "./setup.sh build, or pip install pyoidn and set ATMO_OIDN_LIBRARY to its "
                     "pyoidn/oidn/lib folder");
}

/* Each entry point by name; ATMO_ERR_RUNTIME naming the first one missing. */
static int bind_api(atmo_err *e)
{
    static const char *const names[] = {
        "oidnNewDevice",    "oidnSetDeviceInt",   "oidnGetDeviceInt",
        "oidnCommitDevice", "oidnReleaseDevice",  "oidnGetDeviceError",
        "oidnNewFilter",    "oidnSetSharedFilterImage", "oidnSetFilterBool",
        "oidnSetFilterInt", "oidnCommitFilter",   "oidnExecuteFilter",
        "oidnReleaseFilter"};
    void *slots[sizeof names / sizeof names[0]];
    _Static_assert(sizeof slots == sizeof(oidn_api), "one slot per entry point");
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        slots[i] = dlsym(lib.handle, names[i]);
        if (!slots[i])
            return atmo_fail(e, ATMO_ERR_RUNTIME, "%s: no entry point %s (an OIDN 2.x library is "
                             "needed)", lib.path, names[i]);
    }
    /* POSIX guarantees that a function's address round-trips through void * (dlsym) */
    memcpy(&lib.api, slots, sizeof slots);
    return ATMO_OK;
}

/* OIDN's pending error after `call`, as ATMO_ERR_RUNTIME naming the call; ATMO_OK when none. */
static int device_error(void *device, const char *call, atmo_err *e)
{
    const char *message = NULL;
    int code = lib.api.get_device_error(device, &message);
    if (code == OIDN_ERROR_NONE)
        return ATMO_OK;
    return atmo_fail(e, ATMO_ERR_RUNTIME, "Open Image Denoise: %s failed (error %d): %s", call,
                     code, message && *message ? message : "no message");
}

/* The processors online, as the EXR writer counts them (image_exr.c). */
static int thread_count(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? (int)n : 1;
}

/* A committed CPU device with thread_count() threads, into *device. */
static int new_device(void **device, atmo_err *e)
{
    *device = lib.api.new_device(OIDN_DEVICE_TYPE_CPU);
    if (!*device)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "Open Image Denoise: oidnNewDevice(CPU) returned "
                         "no device (is the CPU supported?)");
    lib.api.set_device_int(*device, "numThreads", thread_count());
    lib.api.commit_device(*device);
    return device_error(*device, "oidnCommitDevice", e);
}

static int load_once(atmo_err *e)
{
    void *device = NULL;
    int rc = open_library(e);
    if (!rc)
        rc = bind_api(e);
    if (!rc)
        rc = new_device(&device, e);
    if (!rc) {
        lib.version = lib.api.get_device_int(device, "version");
        rc = device_error(device, "oidnGetDeviceInt(\"version\")", e);
    }
    if (!rc && lib.version < OIDN_MIN_VERSION)
        rc = atmo_fail(e, ATMO_ERR_RUNTIME, "%s is Open Image Denoise %d.%d.%d; atmo needs 2.0 "
                       "or later (pip install -U pyoidn)", lib.path, lib.version / 10000,
                       lib.version / 100 % 100, lib.version % 100);
    if (device)
        lib.api.release_device(device);
    if (rc && lib.handle) {
        dlclose(lib.handle);
        lib.handle = NULL;
    }
    return rc;
}

int atmo_denoise_load(atmo_err *e)
{
    if (!lib.tried) {
        lib.tried = 1;
        lib.status = load_once(&lib.err);
    }
    if (lib.status && e)
        *e = lib.err;
    return lib.status;
}

/* Share one FLOAT3 image of the input's size with the filter. */
static void share_image(void *filter, const char *name, const float *data, int width, int height)
{
    lib.api.set_shared_filter_image(filter, name, (void *)data, OIDN_FORMAT_FLOAT3,
                                    (size_t)width, (size_t)height, 0, 0, 0);
}

int atmo_denoise_run(const atmo_denoise_input *in, float *out, atmo_err *e)
{
    static const int oidn_quality[] = {4, 5, 6}; /* OIDN_QUALITY_FAST, BALANCED, HIGH */
    void *device = NULL, *filter = NULL;
    int rc = atmo_denoise_load(e);
    if (rc)
        return rc;
    if (in->width < 1 || in->height < 1 || !in->color || (in->normal && !in->albedo) ||
        in->quality < ATMO_DENOISE_FAST || in->quality > ATMO_DENOISE_HIGH)
        return atmo_fail(e, ATMO_ERR_USAGE, "atmo_denoise_run: bad input (%dx%d, quality %d)",
                         in->width, in->height, in->quality);
    if ((rc = new_device(&device, e)))
        goto cleanup;
    filter = lib.api.new_filter(device, "RT");
    if ((rc = device_error(device, "oidnNewFilter(\"RT\")", e)))
        goto cleanup;
    share_image(filter, "color", in->color, in->width, in->height);
    if (in->albedo)
        share_image(filter, "albedo", in->albedo, in->width, in->height);
    if (in->normal)
        share_image(filter, "normal", in->normal, in->width, in->height);
    share_image(filter, "output", out, in->width, in->height);
    if ((rc = device_error(device, "oidnSetSharedFilterImage", e)))
        goto cleanup;
    lib.api.set_filter_bool(filter, "hdr", true);
    lib.api.set_filter_bool(filter, "cleanAux", in->albedo && in->clean_aux);
    lib.api.set_filter_int(filter, "quality", oidn_quality[in->quality]);
    if ((rc = device_error(device, "oidnSetFilterBool/oidnSetFilterInt", e)))
        goto cleanup;
    lib.api.commit_filter(filter);
    if ((rc = device_error(device, "oidnCommitFilter", e)))
        goto cleanup;
    lib.api.execute_filter(filter);
    rc = device_error(device, "oidnExecuteFilter", e);
cleanup:
    if (filter)
        lib.api.release_filter(filter);
    if (device)
        lib.api.release_device(device);
    return rc;
}
