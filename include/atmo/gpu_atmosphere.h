/* gpu_atmosphere.h — the atmosphere as the kernels read it (the float form of atmosphere.h's
 * model at the three render wavelengths: x, y, z; w unused), and the size of its transmittance
 * LUT (kernels/atmosphere/atmosphere.h). Shared byte for byte with OpenCL C (plan.c checks the
 * layout with _Static_assert, tests/test_gpu_layout.c against the device compiler). */
#ifndef ATMO_GPU_ATMOSPHERE_H
#define ATMO_GPU_ATMOSPHERE_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#endif

typedef struct atmo_gpu_atmosphere {
    float4 rayleigh_scattering; /* 1/m at sea level */
    float4 mie_scattering;      /* 1/m at sea level */
    float4 mie_extinction;      /* 1/m at sea level */
    float4 ozone_absorption;    /* 1/m at the peak of the tent */
    float4 solar_irradiance;    /* W m^-2 nm^-1 at the top of the atmosphere */
    float4 ground_albedo;
    float bottom_radius;        /* m */
    float top_radius;           /* m */
    float rayleigh_scale_height; /* m */
    float mie_scale_height;     /* m */
    float mie_g;
    int mie_phase;              /* ATMO_PHASE_* (gpu_enums.h) */
    float ozone_bottom, ozone_peak, ozone_top; /* altitudes of the tent, m */
    float sun_angular_radius;   /* rad */
    float pad0, pad1;
} atmo_gpu_atmosphere;

#endif
