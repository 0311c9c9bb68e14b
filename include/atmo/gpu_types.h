/* gpu_types.h — the structs the host hands to the kernels, byte for byte.
 *
 * Fixed-size fields only (float, int, uint, float4; no float3, size_t, bool or pointers) so the
 * layout is the same in C11 and OpenCL C; host/plan.c checks sizes and offsets with
 * _Static_assert. Everything is in SI units at the render wavelengths (x, y, z = the three
 * wavelengths; w unused unless a comment says otherwise). Positions are camera-relative: the
 * kernels never see world coordinates of planet scale, only the camera's distance r from the
 * planet centre and unit directions. */
#ifndef ATMO_GPU_TYPES_H
#define ATMO_GPU_TYPES_H
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
    int mie_phase;              /* ATMO_PHASE_* */
    float ozone_bottom, ozone_peak, ozone_top; /* altitudes of the tent, m */
    float sun_angular_radius;   /* rad */
    float pad0, pad1;
} atmo_gpu_atmosphere;

enum { ATMO_GPU_CAMERA_PERSPECTIVE = 0, ATMO_GPU_CAMERA_PANORAMA = 1 };

typedef struct atmo_gpu_camera {
    float4 right, up, forward; /* world-space unit basis (xyz) */
    float4 local_up;           /* xyz: unit vector from the planet centre to the camera; w: r (m) */
    int kind;                  /* ATMO_GPU_CAMERA_* */
    int width, height;         /* image size in pixels */
    float tan_half_fov;        /* perspective: tan(vertical fov / 2) */
} atmo_gpu_camera;

typedef struct atmo_gpu_scene {
    atmo_gpu_atmosphere atmosphere;
    atmo_gpu_camera camera;
    float4 sun_direction;  /* xyz: unit vector towards the sun; w: cos(sun angular radius) */
    float4 sky_factor;     /* multiplies scattered and ground radiance (1, or k_sky for luminance) */
    float4 sun_factor;     /* multiplies the sun disc (1, or k_sun for luminance) */
    int view_steps;        /* ray-march segments along a view ray */
    int transmittance_width, transmittance_height; /* LUT size: mu (x), r (y) */
    uint seed;
    int lut_dims[3][4];    /* sizes of the method's LUTs a, b, c (the method says which axes) */
    int method_int[4];     /* integer knobs of the method (its fragment documents them) */
    float method_float[4]; /* float knobs of the method */
    /* cloud shell and observer (kernels/media/cloud_shell.h): zero unless the plan defines ATMO_CLOUD */
    float4 cloud_extinction; /* xyz: sigma_ext (1/m); w: altitude of the shell's base (m) */
    float4 cloud_albedo;     /* xyz: single-scattering albedo; w: altitude of its top (m) */
    float4 cloud_g;          /* xyz: asymmetry g of the table; w: Jendersie-d'Eon diameter (um) */
    float4 observer;         /* xyz: centre, camera-relative in the world axes (m); w: radius */
    int cloud_phase;         /* ATMO_CLOUD_PHASE_* of scene.h */
    int cloud_table_offset;  /* float4 index of the phase table's first row in LUT buffer 0 */
    int cloud_table_size;    /* rows of the phase table (theta ascending) */
    int cloud_steps;         /* steps in optical depth per cloud segment of a view ray */
} atmo_gpu_scene;

#endif
