/* gpu_sky_view.h — the sky-view LUT of method "fast" around the camera
 * (kernels/atmosphere/method_fast.h, fast_luts.cl). Zero when the camera is above the atmosphere
 * (no LUT is made; every ray marches). Shared byte for byte with OpenCL C. */
#ifndef ATMO_GPU_SKY_VIEW_H
#define ATMO_GPU_SKY_VIEW_H

typedef struct atmo_gpu_sky_view {
    int width;   /* columns of azimuth */
    int height;  /* rows: half toward the sky, half toward the ground */
    int steps;   /* segments per texel ray */
    int pad0;
} atmo_gpu_sky_view;

#endif
