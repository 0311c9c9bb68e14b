/* gpu_cloud.h — the homogeneous cloud shell and the observer sphere
 * (kernels/cloud_shell/cloud_shell.h), at the three render wavelengths (x, y, z; w unused). Zero
 * unless the scene has a cloud or an observer. Shared byte for byte with OpenCL C (checked by
 * plan.c and tests/test_gpu_layout.c). */
#ifndef ATMO_GPU_CLOUD_H
#define ATMO_GPU_CLOUD_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#endif

typedef struct atmo_gpu_cloud {
    float4 extinction;   /* sigma_ext, 1/m */
    float4 albedo;       /* single-scattering albedo */
    float4 g;            /* asymmetry g of the Mie table */
    float4 observer;     /* xyz: centre, camera-relative in the world axes (m); w: radius (0: none) */
    float base_m;        /* altitude of the shell's base, m */
    float top_m;         /* altitude of its top, m */
    float diameter_um;   /* effective droplet diameter for Jendersie-d'Eon's fit (5..50 um) */
    int phase;           /* ATMO_CLOUD_PHASE_* (gpu_enums.h) */
    int table_size;      /* rows of the buffer cloud_phase_table (theta ascending) */
    int steps;           /* steps in optical depth per cloud segment of a view ray */
    float sun_guiding;   /* the reference's probability of the phase lobe around the sun */
    int pad1;
} atmo_gpu_cloud;

#endif
