/* gpu_ms_lut.h — the knobs of the multiple-scattering transfer LUT Psi_ms
 * (kernels/atmosphere/ms_lut.h, ms_lut.cl), shared by methods "march" and "fast". Shared byte for
 * byte with OpenCL C (checked by plan.c and tests/test_gpu_layout.c). */
#ifndef ATMO_GPU_MS_LUT_H
#define ATMO_GPU_MS_LUT_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#endif

/* Most azimuths a pass takes (the kernels keep per-azimuth sums in private arrays). */
#define ATMO_MS_MAX_DIRECTIONS_PHI 16

typedef struct atmo_gpu_ms_lut {
    int width, height;         /* texels: mu_s (x) by altitude (y) */
    int directions_mu;         /* cosine bands of the sphere quadrature */
    int directions_phi;        /* azimuths over [0, pi] (half of them in the gathering passes) */
    int steps;                 /* segments per direction */
    float higher_anisotropy;   /* share of the order-3 anisotropy given to orders >= 4 */
    float g1, g2;              /* Legendre coefficients of the aerosol phase function */
} atmo_gpu_ms_lut;

#endif
