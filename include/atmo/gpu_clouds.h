/* gpu_clouds.h — the fBm cloud layer (kernels/clouds/cloud_layer.h, cloud_noise.h) as the kernels
 * see it: optics per unit density at the three render wavelengths (x, y, z; w unused), the
 * noise's placement and shape, the layer's altitudes and the marcher's knobs. Zero unless the
 * scene has clouds.enabled. Shared byte for byte with OpenCL C (checked by plan.c and
 * tests/test_gpu_layout.c). */
#ifndef ATMO_GPU_CLOUDS_H
#define ATMO_GPU_CLOUDS_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#endif

typedef struct atmo_gpu_clouds {
    float4 extinction;     /* sigma_t per unit density, 1/m */
    float4 albedo;         /* single-scattering albedo */
    float4 g;              /* asymmetry g of the phase table (the octaves' Henyey-Greenstein) */
    float4 origin;         /* xyz: the camera's world position minus the wind's displacement
                              (m), so noise point = camera-relative point + origin; w unused */
    float4 frequency;      /* xyz: the shape fBm's base frequency per axis (1/m); w: the coverage
                              field's base frequency (1/m) */
    float bottom_m, top_m; /* the layer's altitudes above sea level */
    float fade_m;          /* fade-in above the bottom and fade-out below the top (m) */
    float coverage;        /* mean of the coverage field, 0..1 */
    float density;         /* density scale (sigma_t = density x extinction at full density) */
    float sharpness;       /* exponent on (coverage - fBm) */
    float warp_m;          /* domain-warp amplitude (m) */
    float step_m;          /* the marcher's step in cloud near the camera (m) */
    float light_distance_m; /* length of the light march toward the sun (m) */
    float max_distance_m;  /* the marcher's far plane (m) */
    float ms_a, ms_b;      /* multiple-scattering octaves: extinction and contribution factors */
    float ms_c;            /* ... and the phase anisotropy factor */
    float majorant;        /* bound on the density anywhere (for delta and ratio tracking) */
    int phase;             /* ATMO_CLOUD_PHASE_* (gpu_enums.h) */
    int table_size;        /* rows of the buffer clouds_phase_table (theta ascending) */
    int octaves;           /* octaves of the shape fBm */
    int steps;             /* most steps of the marcher along a view ray */
    int light_steps;       /* steps of the light march */
    int ms_octaves;        /* multiple-scattering octaves (1: single scattering only) */
    int look;              /* ATMO_CLOUDS_LOOK_* */
    uint seed;             /* the noise's seed */
    float diameter_um;     /* effective droplet diameter for Jendersie-d'Eon's fit (5..50 um) */
    float sun_guiding;     /* the Monte Carlo walks' probability of the phase lobe around the sun */
    int shadow_map_size;   /* the sun shadow map's nodes per horizontal axis (cloud_shadow_map.h;
                              0 without clouds.shadow_map) */
    int shadow_map_levels; /* its nodes between the layer's bottom and top */
    int shadow_map_steps;  /* steps of its nodes' integrals toward the sun */
    float footprint;       /* the noise's level of detail: a pixel's footprint per metre of
                              distance from the camera (rad, times clouds.lod; 0: every octave) */
    float ms_d;            /* weight of the diffuse orders beyond the multiple-scattering
                              octaves (cloud_march.h) */
} atmo_gpu_clouds;

#endif
