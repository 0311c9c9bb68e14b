/* cl_runtime.c — platform and device enumeration, device choice, context and queue
 * (atmo/cl_runtime.h).
 *
 * Before the first OpenCL call, POCL_CACHE_DIR is pointed at "<atmo cache dir>/pocl" unless the
 * user set it: PoCL then keeps its compiled programs and the work-group functions it compiles
 * at a kernel's first launch next to atmo's kernel binaries and LUTs, where `atmo cache` shows
 * them, instead of in ~/.cache/pocl. A program whose atmo binary is gone (atmo cache clear, a
 * new atmo build with the same kernels) is then found in PoCL's cache rather than compiled.
 *
 * POCL_WORK_GROUP_SPECIALIZATION is 0 unless the user set it. PoCL's build compiles one generic
 * work-group function per kernel (any local size), and by default a kernel's first launch then
 * compiles it again, specialised to the local size, for a zero global offset, and once more
 * for a nonzero one (the precompute's slices): three LLVM code generations per kernel, the
 * last two in the first run's precompute and render. Without the specialisation every launch
 * uses the generic function: no compile after the build, the same image bit for bit, and no
 * measurable loss in speed (the time goes into the kernels' arithmetic, not the work-item
 * loop); docs/notes/speed_io.md has the measurements. */
#include <cjson/cJSON.h>
#include <ctype.h>
#include <errno.h>
#include <ftw.h>
#include <sys/stat.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/cl_runtime.h"

const char *atmo_cl_error_string(cl_int err)
{
    switch (err) {
#define E(x) case x: return #x;
        E(CL_SUCCESS) E(CL_DEVICE_NOT_FOUND) E(CL_DEVICE_NOT_AVAILABLE)
        E(CL_COMPILER_NOT_AVAILABLE) E(CL_MEM_OBJECT_ALLOCATION_FAILURE) E(CL_OUT_OF_RESOURCES)
        E(CL_OUT_OF_HOST_MEMORY) E(CL_PROFILING_INFO_NOT_AVAILABLE) E(CL_MEM_COPY_OVERLAP)
        E(CL_IMAGE_FORMAT_MISMATCH) E(CL_IMAGE_FORMAT_NOT_SUPPORTED) E(CL_BUILD_PROGRAM_FAILURE)
        E(CL_MAP_FAILURE) E(CL_MISALIGNED_SUB_BUFFER_OFFSET)
        E(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST) E(CL_COMPILE_PROGRAM_FAILURE)
        E(CL_LINKER_NOT_AVAILABLE) E(CL_LINK_PROGRAM_FAILURE) E(CL_DEVICE_PARTITION_FAILED)
        E(CL_KERNEL_ARG_INFO_NOT_AVAILABLE) E(CL_INVALID_VALUE) E(CL_INVALID_DEVICE_TYPE)
        E(CL_INVALID_PLATFORM) E(CL_INVALID_DEVICE) E(CL_INVALID_CONTEXT)
        E(CL_INVALID_QUEUE_PROPERTIES) E(CL_INVALID_COMMAND_QUEUE) E(CL_INVALID_HOST_PTR)
        E(CL_INVALID_MEM_OBJECT) E(CL_INVALID_IMAGE_FORMAT_DESCRIPTOR) E(CL_INVALID_IMAGE_SIZE)
        E(CL_INVALID_SAMPLER) E(CL_INVALID_BINARY) E(CL_INVALID_BUILD_OPTIONS)
        E(CL_INVALID_PROGRAM) E(CL_INVALID_PROGRAM_EXECUTABLE) E(CL_INVALID_KERNEL_NAME)
        E(CL_INVALID_KERNEL_DEFINITION) E(CL_INVALID_KERNEL) E(CL_INVALID_ARG_INDEX)
        E(CL_INVALID_ARG_VALUE) E(CL_INVALID_ARG_SIZE) E(CL_INVALID_KERNEL_ARGS)
        E(CL_INVALID_WORK_DIMENSION) E(CL_INVALID_WORK_GROUP_SIZE) E(CL_INVALID_WORK_ITEM_SIZE)
        E(CL_INVALID_GLOBAL_OFFSET) E(CL_INVALID_EVENT_WAIT_LIST) E(CL_INVALID_EVENT)
        E(CL_INVALID_OPERATION) E(CL_INVALID_GL_OBJECT) E(CL_INVALID_BUFFER_SIZE)
        E(CL_INVALID_MIP_LEVEL) E(CL_INVALID_GLOBAL_WORK_SIZE) E(CL_INVALID_PROPERTY)
        E(CL_INVALID_IMAGE_DESCRIPTOR) E(CL_INVALID_COMPILER_OPTIONS) E(CL_INVALID_LINKER_OPTIONS)
        E(CL_INVALID_DEVICE_PARTITION_COUNT)
#undef E
    case -1001: return "CL_PLATFORM_NOT_FOUND_KHR (no OpenCL platform is installed: install pocl-opencl-icd)";
    default: return "unknown OpenCL error";
    }
}

int atmo_cl_fail(atmo_err *e, const char *call, cl_int err)
{
    return atmo_fail(e, ATMO_ERR_RUNTIME, "%s failed: %s (%d)", call, atmo_cl_error_string(err),
                     (int)err);
}

#define ATMO_MAX_DEVICES 64

/* Set when atmo_cl_prepare_environment chose POCL_CACHE_DIR. */
static int driver_cache_own = -1;
static char driver_cache_private[4200];

int atmo_cl_driver_cache_is_own(void)
{
    const char *env = getenv("POCL_CACHE_DIR");
    return driver_cache_own >= 0 ? driver_cache_own : !(env && *env);
}

int atmo_cl_driver_cache_dir(char *dir, size_t size)
{
    const char *env = getenv("POCL_CACHE_DIR");
    char base[1024], why[256];
    if (env && *env) {
        snprintf(dir, size, "%s", env);
        return 0;
    }
    if (atmo_cache_dir_find(base, sizeof base, why, sizeof why) != 0)
        return -1;
    snprintf(dir, size, "%s/pocl", base);
    return 0;
}

static int remove_entry(const char *path, const struct stat *st, int flag, struct FTW *ftw)
{
    (void)st, (void)flag, (void)ftw;
    return remove(path);
}

static void remove_private_driver_cache(void)
{
    nftw(driver_cache_private, remove_entry, 16, FTW_DEPTH | FTW_PHYS);
}

/* A private PoCL directory for a process whose cache directory is unusable. */
static void use_private_driver_cache(void)
{
    const char *tmp = getenv("TMPDIR");
    snprintf(driver_cache_private, sizeof driver_cache_private, "%s/atmo-pocl-XXXXXX",
             tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(driver_cache_private))
        return;
    setenv("POCL_CACHE_DIR", driver_cache_private, 1);
    atexit(remove_private_driver_cache);
}

void atmo_cl_prepare_environment(void)
{
    char dir[1100];
    const char *env = getenv("POCL_CACHE_DIR");
    if (driver_cache_own < 0) {
        driver_cache_own = !(env && *env);
        if (driver_cache_own && atmo_cl_driver_cache_dir(dir, sizeof dir) == 0 &&
            (mkdir(dir, 0755) == 0 || errno == EEXIST)) {
            setenv("POCL_CACHE_DIR", dir, 1);
        } else if (driver_cache_own) {
            use_private_driver_cache();
        }
    }
    setenv("POCL_WORK_GROUP_SPECIALIZATION", "0", 0);
}

typedef struct cl_device_entry {
    cl_platform_id platform;
    cl_device_id device;
} cl_device_entry;

/* All devices of all platforms, in platform order. */
static int cl_enumerate(cl_device_entry *out, int *count, atmo_err *e)
{
    cl_platform_id platforms[16];
    cl_uint np = 0;
    static int repaired;
    atmo_cl_prepare_environment();
    if (driver_cache_own == 1 && !driver_cache_private[0] && !repaired++)
        atmo_cl_driver_cache_repair(getenv("POCL_CACHE_DIR"), stderr);
    cl_int err = clGetPlatformIDs(16, platforms, &np);
    if (err == -1001 || (err == CL_SUCCESS && np == 0))
        return atmo_fail(e, ATMO_ERR_RUNTIME,
                         "no OpenCL platform found (install pocl-opencl-icd for the CPU, or your "
                         "GPU's OpenCL driver)");
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clGetPlatformIDs", err);
    *count = 0;
    for (cl_uint p = 0; p < np && *count < ATMO_MAX_DEVICES; p++) {
        cl_device_id devices[ATMO_MAX_DEVICES];
        cl_uint nd = 0;
        err = clGetDeviceIDs(platforms[p], CL_DEVICE_TYPE_ALL, ATMO_MAX_DEVICES, devices, &nd);
        if (err == CL_DEVICE_NOT_FOUND)
            continue;
        if (err != CL_SUCCESS)
            return atmo_cl_fail(e, "clGetDeviceIDs", err);
        for (cl_uint d = 0; d < nd && *count < ATMO_MAX_DEVICES; d++) {
            out[*count].platform = platforms[p];
            out[*count].device = devices[d];
            (*count)++;
        }
    }
    if (*count == 0)
        return atmo_fail(e, ATMO_ERR_RUNTIME, "OpenCL platforms exist but offer no device");
    return ATMO_OK;
}

static void cl_string(cl_device_id d, cl_device_info what, char *buf, size_t size)
{
    buf[0] = 0;
    if (clGetDeviceInfo(d, what, size, buf, NULL) != CL_SUCCESS)
        snprintf(buf, size, "?");
}

static void cl_describe(atmo_cl *cl, cl_platform_id p, cl_device_id d)
{
    cl->platform = p;
    cl->device = d;
    if (clGetPlatformInfo(p, CL_PLATFORM_NAME, sizeof cl->platform_name, cl->platform_name,
                          NULL) != CL_SUCCESS)
        snprintf(cl->platform_name, sizeof cl->platform_name, "?");
    cl_string(d, CL_DEVICE_NAME, cl->device_name, sizeof cl->device_name);
    cl_string(d, CL_DEVICE_VENDOR, cl->device_vendor, sizeof cl->device_vendor);
    cl_string(d, CL_DRIVER_VERSION, cl->driver_version, sizeof cl->driver_version);
    cl_string(d, CL_DEVICE_VERSION, cl->device_version, sizeof cl->device_version);
    cl->type = 0;
    cl->compute_units = 0;
    cl->global_memory = 0;
    clGetDeviceInfo(d, CL_DEVICE_TYPE, sizeof cl->type, &cl->type, NULL);
    clGetDeviceInfo(d, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof cl->compute_units,
                    &cl->compute_units, NULL);
    clGetDeviceInfo(d, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof cl->global_memory, &cl->global_memory,
                    NULL);
    cl_device_fp_config fp64 = 0;
    clGetDeviceInfo(d, CL_DEVICE_DOUBLE_FP_CONFIG, sizeof fp64, &fp64, NULL);
    cl->has_fp64 = fp64 != 0;
}

static const char *cl_type_name(cl_device_type t)
{
    if (t & CL_DEVICE_TYPE_GPU)
        return "GPU";
    if (t & CL_DEVICE_TYPE_CPU)
        return "CPU";
    if (t & CL_DEVICE_TYPE_ACCELERATOR)
        return "accelerator";
    return "other";
}

int atmo_cl_list_devices(int json, atmo_err *e)
{
    cl_device_entry list[ATMO_MAX_DEVICES];
    int n = 0;
    int rc = cl_enumerate(list, &n, e);
    if (rc)
        return rc;
    cJSON *root = json ? cJSON_CreateObject() : NULL;
    cJSON *array = json ? cJSON_AddArrayToObject(root, "devices") : NULL;
    for (int i = 0; i < n; i++) {
        atmo_cl c;
        cl_describe(&c, list[i].platform, list[i].device);
        if (json) {
            cJSON *d = cJSON_CreateObject();
            cJSON_AddNumberToObject(d, "index", i);
            cJSON_AddStringToObject(d, "platform", c.platform_name);
            cJSON_AddStringToObject(d, "name", c.device_name);
            cJSON_AddStringToObject(d, "type", cl_type_name(c.type));
            cJSON_AddNumberToObject(d, "compute_units", c.compute_units);
            cJSON_AddNumberToObject(d, "global_memory_bytes", (double)c.global_memory);
            cJSON_AddBoolToObject(d, "fp64", c.has_fp64);
            cJSON_AddStringToObject(d, "driver_version", c.driver_version);
            cJSON_AddStringToObject(d, "device_version", c.device_version);
            cJSON_AddItemToArray(array, d);
        } else
            printf("%d: %s / %s\n   type %s, %u compute units, %.1f GiB global memory, fp64 %s, "
                   "driver %s, %s\n",
                   i, c.platform_name, c.device_name, cl_type_name(c.type), c.compute_units,
                   (double)c.global_memory / (1024.0 * 1024.0 * 1024.0),
                   c.has_fp64 ? "yes" : "no", c.driver_version, c.device_version);
    }
    if (json) {
        char *text = cJSON_Print(root);
        if (text)
            printf("%s\n", text);
        free(text);
        cJSON_Delete(root);
    }
    return ATMO_OK;
}

static int cl_contains_nocase(const char *hay, const char *needle)
{
    size_t n = strlen(needle);
    for (; *hay; hay++) {
        size_t i = 0;
        while (i < n && hay[i] && tolower((unsigned char)hay[i]) == tolower((unsigned char)needle[i]))
            i++;
        if (i == n)
            return 1;
    }
    return n == 0;
}

/* Index of the device the selector names (or the default), or an error. */
static int cl_choose(const cl_device_entry *list, int n, const char *selector, int *index,
                       atmo_err *e)
{
    if (selector && *selector) {
        char *end;
        long k = strtol(selector, &end, 10);
        if (*end == 0) {
            if (k < 0 || k >= n)
                return atmo_fail(e, ATMO_ERR_USAGE,
                                 "device %ld does not exist (there are %d; see 'atmo devices')", k,
                                 n);
            *index = (int)k;
            return ATMO_OK;
        }
        for (int i = 0; i < n; i++) {
            atmo_cl c;
            char both[520];
            cl_describe(&c, list[i].platform, list[i].device);
            snprintf(both, sizeof both, "%s / %s", c.platform_name, c.device_name);
            if (cl_contains_nocase(both, selector)) {
                *index = i;
                return ATMO_OK;
            }
        }
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "no OpenCL device matches '%s' (give an index or part of a name from "
                         "'atmo devices')",
                         selector);
    }
    cl_device_type prefer[] = {CL_DEVICE_TYPE_GPU, CL_DEVICE_TYPE_CPU, CL_DEVICE_TYPE_ALL};
    for (int p = 0; p < 3; p++)
        for (int i = 0; i < n; i++) {
            cl_device_type t = 0;
            clGetDeviceInfo(list[i].device, CL_DEVICE_TYPE, sizeof t, &t, NULL);
            if (t & prefer[p]) {
                *index = i;
                return ATMO_OK;
            }
        }
    *index = 0;
    return ATMO_OK;
}

int atmo_cl_open(atmo_cl *cl, const char *selector, atmo_err *e)
{
    memset(cl, 0, sizeof *cl);
    if (!selector || !*selector)
        selector = getenv("ATMO_DEVICE");
    cl_device_entry list[ATMO_MAX_DEVICES];
    int n = 0, index = 0, rc;
    cl_int err;
    if ((rc = cl_enumerate(list, &n, e)) || (rc = cl_choose(list, n, selector, &index, e)))
        return rc;
    cl_describe(cl, list[index].platform, list[index].device);
    cl->device_index = index;
    cl_context_properties props[] = {CL_CONTEXT_PLATFORM, (cl_context_properties)cl->platform, 0};
    cl->context = clCreateContext(props, 1, &cl->device, NULL, NULL, &err);
    if (err != CL_SUCCESS)
        return atmo_cl_fail(e, "clCreateContext", err);
    cl->queue = clCreateCommandQueue(cl->context, cl->device, 0, &err);
    if (err != CL_SUCCESS) {
        rc = atmo_cl_fail(e, "clCreateCommandQueue", err);
        goto fail_context;
    }
    return ATMO_OK;

fail_context:
    clReleaseContext(cl->context);
    cl->context = NULL;
    return rc;
}

void atmo_cl_close(atmo_cl *cl)
{
    if (cl->queue)
        clReleaseCommandQueue(cl->queue);
    if (cl->context)
        clReleaseContext(cl->context);
    cl->queue = NULL;
    cl->context = NULL;
}
