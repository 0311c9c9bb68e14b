/* cmd_devices.c — `atmo devices`: list OpenCL platforms and devices. */
#include <stdio.h>
#include <string.h>
#include "atmo/cl_runtime.h"
#include "commands.h"

int cmd_devices(int argc, char **argv)
{
    int json = 0;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--json") == 0)
            json = 1;
        else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            printf("usage: atmo devices [--json]\n\n"
                   "Lists every OpenCL platform and device with its index, type, compute units,\n"
                   "global memory, fp64 support and driver version. Choose one for a render with\n"
                   "--device N|SUBSTRING or the ATMO_DEVICE variable; the default is the first\n"
                   "GPU, else the first CPU device.\n");
            return ATMO_OK;
        } else {
            fprintf(stderr, "atmo devices: unknown option '%s' (options: --json, --help)\n",
                    argv[i]);
            return ATMO_ERR_USAGE;
        }
    }
    atmo_err e;
    int rc = atmo_cl_list_devices(json, &e);
    if (rc)
        fprintf(stderr, "atmo devices: %s\n", e.msg);
    return rc;
}
