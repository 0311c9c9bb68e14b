/* cmd_devices.c — `atmo devices`: the OpenCL platforms and devices, why a device is skipped, and
 * which one a render would use (atmo_cl_list_devices). */
#include <stdio.h>
#include <string.h>
#include "atmo/cl_runtime.h"
#include "commands.h"

int cmd_devices(int argc, char **argv)
{
    int json = 0;
    const char *device = NULL;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--json") == 0)
            json = 1;
        else if (strcmp(argv[i], "--device") == 0 && i + 1 < argc)
            device = argv[++i];
        else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            printf("usage: atmo devices [--device N|NAME] [--json]\n\n"
                   "Lists every OpenCL platform and its devices: name, vendor, type, OpenCL and\n"
                   "OpenCL C versions, driver, compute units, global memory and largest buffer.\n"
                   "A device that cannot run atmo's kernels (not available, no compiler, OpenCL\n"
                   "C below 1.2, float without Inf/NaN, work groups under 8 x 8) is marked\n"
                   "skipped with the reason. The device a render would use is marked *: the one\n"
                   "--device N|NAME (an index, or part of \"platform (vendor) / device\") or the\n"
                   "ATMO_DEVICE variable names, else the first usable GPU, else CPU. A --device\n"
                   "that names no usable device exits 2. docs/guide/gpu.md: GPU drivers.\n");
            return ATMO_OK;
        } else {
            fprintf(stderr, "atmo devices: %s '%s' (options: --device N|NAME, --json, --help)\n",
                    strcmp(argv[i], "--device") == 0 ? "missing value for" : "unknown option",
                    argv[i]);
            return ATMO_ERR_USAGE;
        }
    }
    atmo_err e;
    int rc = atmo_cl_list_devices(device, json, &e);
    if (rc)
        fprintf(stderr, "atmo devices: %s\n", e.msg);
    return rc;
}
