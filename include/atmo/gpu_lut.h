/* gpu_lut.h — the 4-D scattering tables of method "lut" (kernels/atmosphere/lut_scattering.h has
 * their layout, lut_precompute.cl their passes). Shared byte for byte with OpenCL C. */
#ifndef ATMO_GPU_LUT_H
#define ATMO_GPU_LUT_H

typedef struct atmo_gpu_lut {
    int dims[4];  /* texels along nu, mu_s, mu, r */
    int steps;    /* segments per texel ray */
    int rings;    /* zenith rings of the sphere grid (even) */
    int orders;   /* scattering orders (for reports; the plan lists the passes) */
    int pad0;
} atmo_gpu_lut;

#endif
