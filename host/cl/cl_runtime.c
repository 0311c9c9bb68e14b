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

void atmo_cl_query_caps(cl_device_id d, atmo_cl_caps *caps)
{
    cl_bool available = CL_FALSE, compiler = CL_FALSE;
    memset(caps, 0, sizeof *caps);
    clGetDeviceInfo(d, CL_DEVICE_AVAILABLE, sizeof available, &available, NULL);
    clGetDeviceInfo(d, CL_DEVICE_COMPILER_AVAILABLE, sizeof compiler, &compiler, NULL);
    caps->available = available == CL_TRUE;
    caps->compiler = compiler == CL_TRUE;
    if (clGetDeviceInfo(d, CL_DEVICE_OPENCL_C_VERSION, sizeof caps->c_version, caps->c_version,
                        NULL) != CL_SUCCESS)
        caps->c_version[0] = '\0';
    clGetDeviceInfo(d, CL_DEVICE_SINGLE_FP_CONFIG, sizeof caps->single_fp, &caps->single_fp,
                    NULL);
    clGetDeviceInfo(d, CL_DEVICE_MAX_WORK_GROUP_SIZE, sizeof caps->max_work_group,
                    &caps->max_work_group, NULL);
    clGetDeviceInfo(d, CL_DEVICE_MAX_WORK_ITEM_SIZES, sizeof caps->max_work_item,
                    caps->max_work_item, NULL);
}

int atmo_cl_caps_usable(const atmo_cl_caps *caps, char *why, size_t size)
{
    int major = 0, minor = 0;
    const size_t *item = caps->max_work_item;
    why[0] = '\0';
    if (!caps->available)
        snprintf(why, size, "not available (CL_DEVICE_AVAILABLE is false)");
    else if (!caps->compiler)
        snprintf(why, size, "no OpenCL C compiler (the kernels are built from source)");
    else if (sscanf(caps->c_version, "OpenCL C %d.%d", &major, &minor) != 2 ||
             major * 100 + minor < 102)
        snprintf(why, size, "'%s': the kernels need OpenCL C 1.2",
                 caps->c_version[0] ? caps->c_version : "no OpenCL C version");
    else if ((caps->single_fp & (CL_FP_INF_NAN | CL_FP_ROUND_TO_NEAREST)) !=
             (CL_FP_INF_NAN | CL_FP_ROUND_TO_NEAREST))
        snprintf(why, size, "float without %s (the kernels test for NaN and need IEEE rounding)",
                 caps->single_fp & CL_FP_INF_NAN ? "round-to-nearest" : "Inf and NaN");
    else if (caps->max_work_group < ATMO_CL_WORK_GROUP_ITEMS ||
             item[0] < ATMO_CL_WORK_ITEM_MIN_X || item[1] < ATMO_CL_WORK_ITEM_MIN_Y ||
             item[2] < ATMO_CL_WORK_ITEM_MIN_Z)
        snprintf(why, size, "work groups of %zu items (%zu x %zu x %zu) are below the %d x %d x "
                 "%d (%d items) the kernels launch",
                 caps->max_work_group, item[0], item[1], item[2], ATMO_CL_WORK_ITEM_MIN_X,
                 ATMO_CL_WORK_ITEM_MIN_Y, ATMO_CL_WORK_ITEM_MIN_Z, ATMO_CL_WORK_GROUP_ITEMS);
    return why[0] == '\0';
}

static int cl_usable(cl_device_id d, char *why, size_t size)
{
    atmo_cl_caps caps;
    atmo_cl_query_caps(d, &caps);
    return atmo_cl_caps_usable(&caps, why, size);
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

/* "platform (platform vendor) / device", the text a name selector is matched against (the
 * vendor lets "pocl" find "Portable Computing Language (The pocl project)"). */
static void cl_full_name(const cl_device_entry *entry, char *buf, size_t size)
{
    atmo_cl c;
    char vendor[256];
    cl_describe(&c, entry->platform, entry->device);
    if (clGetPlatformInfo(entry->platform, CL_PLATFORM_VENDOR, sizeof vendor, vendor, NULL) !=
        CL_SUCCESS)
        snprintf(vendor, sizeof vendor, "?");
    snprintf(buf, size, "%s (%s) / %s", c.platform_name, vendor, c.device_name);
}

/* A usage error for a selector that names no device, listing in one line the devices there
 * are. */
static int cl_no_match(const cl_device_entry *list, int n, const char *what, atmo_err *e)
{
    char names[900] = "";
    size_t used = 0;
    for (int i = 0; i < n && used + 1 < sizeof names; i++) {
        char full[780];
        cl_full_name(&list[i], full, sizeof full);
        used += (size_t)snprintf(names + used, sizeof names - used, "%s%d '%s'", i ? ", " : "",
                                 i, full);
    }
    return atmo_fail(e, ATMO_ERR_USAGE, "%s; give an index or part of a name: %s", what, names);
}

/* The device the selector names: by index, else the first usable device whose name contains
 * it; one that cannot run the kernels is refused with the reason. */
static int cl_choose_named(const cl_device_entry *list, int n, const char *selector, int *index,
                           atmo_err *e)
{
    char why[256], full[780], what[300];
    char *end;
    long k = strtol(selector, &end, 10);
    int first_match = -1;
    if (*end == 0) {
        snprintf(what, sizeof what, "OpenCL device %ld does not exist", k);
        if (k < 0 || k >= n)
            return cl_no_match(list, n, what, e);
        first_match = (int)k;
    } else {
        for (int i = 0; i < n; i++) {
            cl_full_name(&list[i], full, sizeof full);
            if (!cl_contains_nocase(full, selector))
                continue;
            if (first_match < 0)
                first_match = i;
            if (cl_usable(list[i].device, why, sizeof why)) {
                *index = i;
                return ATMO_OK;
            }
        }
        snprintf(what, sizeof what, "no OpenCL device matches '%s'", selector);
        if (first_match < 0)
            return cl_no_match(list, n, what, e);
    }
    if (!cl_usable(list[first_match].device, why, sizeof why)) {
        cl_full_name(&list[first_match], full, sizeof full);
        return atmo_fail(e, ATMO_ERR_USAGE, "device %d '%s' cannot run atmo: %s (see 'atmo "
                         "devices')", first_match, full, why);
    }
    *index = first_match;
    return ATMO_OK;
}

/* Index of the device the selector names, or the default: the first usable GPU, else CPU,
 * else device of any kind. */
static int cl_choose(const cl_device_entry *list, int n, const char *selector, int *index,
                     atmo_err *e)
{
    if (selector && *selector)
        return cl_choose_named(list, n, selector, index, e);
    cl_device_type prefer[] = {CL_DEVICE_TYPE_GPU, CL_DEVICE_TYPE_CPU, CL_DEVICE_TYPE_ALL};
    char why[256];
    for (int p = 0; p < 3; p++)
        for (int i = 0; i < n; i++) {
            cl_device_type t = 0;
            clGetDeviceInfo(list[i].device, CL_DEVICE_TYPE, sizeof t, &t, NULL);
            if ((t & prefer[p]) && cl_usable(list[i].device, why, sizeof why)) {
                *index = i;
                return ATMO_OK;
            }
        }
    return atmo_fail(e, ATMO_ERR_RUNTIME,
                     "no OpenCL device can run atmo's kernels ('atmo devices' says why each is "
                     "skipped)");
}

/* One platform's name, vendor and version for the listing. */
static void cl_platform_text(cl_platform_id p, cl_platform_info what, char *buf, size_t size)
{
    if (clGetPlatformInfo(p, what, size, buf, NULL) != CL_SUCCESS)
        snprintf(buf, size, "?");
}

/* One device of the listing, as text or as a JSON object added to `array`. */
static void cl_list_device(const cl_device_entry *entry, int index, int chosen, cJSON *array)
{
    atmo_cl c;
    atmo_cl_caps caps;
    char why[256];
    cl_ulong max_alloc = 0;
    cl_describe(&c, entry->platform, entry->device);
    atmo_cl_query_caps(entry->device, &caps);
    int usable = atmo_cl_caps_usable(&caps, why, sizeof why);
    clGetDeviceInfo(entry->device, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof max_alloc, &max_alloc,
                    NULL);
    const double gib = 1024.0 * 1024.0 * 1024.0;
    if (!array) {
        printf("  %s %d: %s [%s]%s%s\n", index == chosen ? "*" : " ", index, c.device_name,
               cl_type_name(c.type), usable ? "" : " skipped: ", usable ? "" : why);
        printf("       vendor %s; %s; %s; driver %s\n", c.device_vendor, c.device_version,
               caps.c_version[0] ? caps.c_version : "no OpenCL C", c.driver_version);
        printf("       %u compute units, %.1f GiB global memory (largest buffer %.1f GiB), "
               "fp64 %s\n",
               c.compute_units, (double)c.global_memory / gib, (double)max_alloc / gib,
               c.has_fp64 ? "yes" : "no");
        return;
    }
    cJSON *d = cJSON_CreateObject();
    cJSON_AddNumberToObject(d, "index", index);
    cJSON_AddStringToObject(d, "platform", c.platform_name);
    cJSON_AddStringToObject(d, "name", c.device_name);
    cJSON_AddStringToObject(d, "vendor", c.device_vendor);
    cJSON_AddStringToObject(d, "type", cl_type_name(c.type));
    cJSON_AddNumberToObject(d, "compute_units", c.compute_units);
    cJSON_AddNumberToObject(d, "global_memory_bytes", (double)c.global_memory);
    cJSON_AddNumberToObject(d, "max_alloc_bytes", (double)max_alloc);
    cJSON_AddBoolToObject(d, "fp64", c.has_fp64);
    cJSON_AddStringToObject(d, "driver_version", c.driver_version);
    cJSON_AddStringToObject(d, "device_version", c.device_version);
    cJSON_AddStringToObject(d, "opencl_c_version", caps.c_version);
    cJSON_AddBoolToObject(d, "usable", usable);
    if (usable)
        cJSON_AddNullToObject(d, "skipped");
    else
        cJSON_AddStringToObject(d, "skipped", why);
    cJSON_AddBoolToObject(d, "selected", index == chosen);
    cJSON_AddItemToArray(array, d);
}

/* The platforms in clGetPlatformIDs' order, each with its devices (their indices follow
 * cl_enumerate's order, which is the same). */
static void cl_list_platforms(const cl_device_entry *list, int n, int chosen, cJSON *root)
{
    cl_platform_id platforms[16];
    cl_uint np = 0;
    if (clGetPlatformIDs(16, platforms, &np) != CL_SUCCESS)
        np = 0;
    cJSON *jplatforms = root ? cJSON_AddArrayToObject(root, "platforms") : NULL;
    cJSON *jdevices = root ? cJSON_AddArrayToObject(root, "devices") : NULL;
    for (cl_uint p = 0; p < np; p++) {
        char name[256], vendor[256], version[256];
        cl_platform_text(platforms[p], CL_PLATFORM_NAME, name, sizeof name);
        cl_platform_text(platforms[p], CL_PLATFORM_VENDOR, vendor, sizeof vendor);
        cl_platform_text(platforms[p], CL_PLATFORM_VERSION, version, sizeof version);
        int count = 0;
        for (int i = 0; i < n; i++)
            count += list[i].platform == platforms[p];
        if (root) {
            cJSON *jp = cJSON_CreateObject();
            cJSON_AddStringToObject(jp, "name", name);
            cJSON_AddStringToObject(jp, "vendor", vendor);
            cJSON_AddStringToObject(jp, "version", version);
            cJSON_AddNumberToObject(jp, "devices", count);
            cJSON_AddItemToArray(jplatforms, jp);
        } else
            printf("platform %u: %s (%s), %s%s\n", p, name, vendor, version,
                   count ? "" : ": no devices");
        for (int i = 0; i < n; i++)
            if (list[i].platform == platforms[p])
                cl_list_device(&list[i], i, chosen, jdevices);
    }
}

int atmo_cl_list_devices(const char *selector, int json, atmo_err *e)
{
    cl_device_entry list[ATMO_MAX_DEVICES];
    int n = 0, chosen = -1;
    atmo_err none;
    int rc = cl_enumerate(list, &n, e);
    if (rc)
        return rc;
    const char *from = "--device";
    if (!selector || !*selector) {
        selector = getenv("ATMO_DEVICE");
        from = "ATMO_DEVICE";
    }
    int named = selector && *selector;
    if (named && (rc = cl_choose(list, n, selector, &chosen, e)))
        return rc;
    if (!named && cl_choose(list, n, NULL, &chosen, &none))
        chosen = -1;
    cJSON *root = json ? cJSON_CreateObject() : NULL;
    cl_list_platforms(list, n, chosen, root);
    const char *how = named ? from : "default: the first usable GPU, else CPU";
    if (json) {
        if (chosen >= 0)
            cJSON_AddNumberToObject(root, "selected", chosen);
        else
            cJSON_AddNullToObject(root, "selected");
        cJSON_AddStringToObject(root, "selected_by", how);
        char *text = cJSON_Print(root);
        if (text)
            printf("%s\n", text);
        free(text);
        cJSON_Delete(root);
    } else if (chosen >= 0)
        printf("a render uses device %d (* above; %s%s%s)\n", chosen, how, named ? " " : "",
               named ? selector : "");
    else
        printf("a render has no device: none can run atmo's kernels (see 'skipped' above)\n");
    return ATMO_OK;
}

/* The devices into list[] and the index of the one the selector (NULL or "": ATMO_DEVICE, else
 * the default) names, by the rule of cl_choose. */
static int cl_find(const char *selector, cl_device_entry *list, int *index, atmo_err *e)
{
    if (!selector || !*selector)
        selector = getenv("ATMO_DEVICE");
    int n = 0, rc;
    if ((rc = cl_enumerate(list, &n, e)))
        return rc;
    return cl_choose(list, n, selector, index, e);
}

int atmo_cl_check_selector(const char *selector, atmo_err *e)
{
    cl_device_entry list[ATMO_MAX_DEVICES];
    int index = 0;
    return cl_find(selector, list, &index, e);
}

int atmo_cl_open(atmo_cl *cl, const char *selector, atmo_err *e)
{
    memset(cl, 0, sizeof *cl);
    cl_device_entry list[ATMO_MAX_DEVICES];
    int index = 0, rc;
    cl_int err;
    if ((rc = cl_find(selector, list, &index, e)))
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
