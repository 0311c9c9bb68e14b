/* gpu_types.h — the scene struct the host hands to the kernels, byte for byte.
 *
 * Fixed-size fields only (float, int, uint, float4; no float3, size_t, bool or pointers) so the
 * layout is the same in C11 and OpenCL C; host/plan/plan.c checks sizes and offsets with
 * _Static_assert and tests/test_gpu_layout.c against the device compiler. Everything is in SI
 * units at the render wavelengths (x, y, z = the three wavelengths; w unused unless a comment
 * says otherwise). Positions are camera-relative: the kernels never see world coordinates of
 * planet scale, only the camera's distance r from the planet centre and unit directions.
 *
 * Each feature of the plan's registry (host/plan/features.c) has its own typed struct in its own
 * header; the scene holds one of each, zero for the features the scene does not contain. In the
 * kernels those headers are fragments placed before this one. */
#ifndef ATMO_GPU_TYPES_H
#define ATMO_GPU_TYPES_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmo/gpu_enums.h"
#include "atmo/gpu_atmosphere.h"
#include "atmo/gpu_cloud.h"
#include "atmo/gpu_clouds.h"
#include "atmo/gpu_lut.h"
#include "atmo/gpu_ms_lut.h"
#include "atmo/gpu_path.h"
#include "atmo/gpu_reference.h"
#include "atmo/gpu_sky_view.h"
#include "atmo/gpu_terrain.h"
#endif

typedef struct atmo_gpu_camera {
    float4 right, up, forward; /* world-space unit basis (xyz) */
    float4 local_up;           /* xyz: unit vector from the planet centre to the camera; w: r (m) */
    int kind;                  /* ATMO_CAMERA_* (gpu_enums.h) */
    int width, height;         /* image size in pixels */
    float tan_half_fov;        /* perspective: tan(vertical fov / 2); fisheye: sin(fov / 4) */
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
    atmo_gpu_ms_lut ms;           /* methods march and fast */
    atmo_gpu_sky_view sky_view;   /* method fast */
    atmo_gpu_lut lut;             /* method lut */
    atmo_gpu_reference reference; /* method reference */
    atmo_gpu_cloud cloud;         /* the cloud shell and the observer */
    atmo_gpu_clouds clouds;       /* the fBm cloud layer */
    atmo_gpu_path path;           /* the path tracer and the objects (render.mode = path) */
    atmo_gpu_terrain terrain;     /* the procedural terrain */
} atmo_gpu_scene;

#endif
