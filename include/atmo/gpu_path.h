/* gpu_path.h — the path tracer's parameters and the scene's objects, shared byte for byte with
 * OpenCL C (checked by host/plan/plan.c and tests/test_gpu_layout.c).
 *
 * atmo_gpu_path is the scene's `path` member: zero unless the scene renders in path mode
 * (render.mode = path) or has objects. atmo_gpu_object is one element of the named buffer
 * `objects` (a host table the plan builds from the scene's object list): positions are
 * camera-relative metres in the world's axes, computed on the host in double, so no
 * planet-scale coordinate reaches a kernel. Radiance is spectral radiance at the three render
 * wavelengths (x, y, z), W m^-2 sr^-1 nm^-1; albedo is the Lambertian reflectance (BRDF albedo/pi). */
#ifndef ATMO_GPU_PATH_H
#define ATMO_GPU_PATH_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#endif

/* The path tracer's render passes (kernels/render/path.h, path.cl): six light passes, then
 * the primary hit's normal and depth, then its albedo, one float4 plane each. */
#define ATMO_PATH_LIGHT_PASSES 6
#define ATMO_PATH_PASS_PLANES (ATMO_PATH_LIGHT_PASSES + 2)

/* The sky's radiance table of the sky sampling (kernels/render/light_sky.h's LIGHT_SKY_W x
 * LIGHT_SKY_H), in the buffer sky_env with one more float4 per row for the CDF of the rows. */
#define ATMO_PATH_SKY_COLUMNS 32
#define ATMO_PATH_SKY_ROWS 16
#define ATMO_PATH_SKY_TEXELS (ATMO_PATH_SKY_COLUMNS * ATMO_PATH_SKY_ROWS)

typedef struct atmo_gpu_object {
    float4 a;        /* sphere: centre (xyz), radius (w); box: minimum corner (xyz) */
    float4 b;        /* box: maximum corner (xyz); sphere: unused */
    float4 albedo;   /* xyz: Lambertian albedo per wavelength, 0..1 */
    float4 emission; /* xyz: emitted radiance per wavelength */
    int kind;        /* ATMO_OBJECT_* (gpu_enums.h) */
    int pad0, pad1, pad2;
} atmo_gpu_object;

typedef struct atmo_gpu_path {
    float4 uniform_sky;  /* xyz: the test sky's radiance (sky = ATMO_PATH_SKY_UNIFORM) */
    int object_count;    /* elements of the buffer `objects` */
    int bounces;         /* N_b: reflections off surfaces per path (0: the camera ray alone) */
    int secondary;       /* N_s: secondary rays per primary hit */
    int rr_bounce;       /* Russian roulette from this event on (reflections + scatterings) */
    int sun_nee;         /* 1: next-event estimation to the sun disc */
    int sky_nee;         /* 1: sky sampling combined with BSDF sampling by MIS */
    int sky;             /* ATMO_PATH_SKY_* */
    int ground;          /* 1: the planet's ground sphere is a surface of render/surfaces.h
                            (path mode: the scene's path.ground; the preview: 1) */
    int sampler;         /* ATMO_SAMPLER_*: the primary samples' sequence */
    float filter_radius; /* pixel filter: truncation radius, px */
    float filter_sigma;  /* pixel filter: Gaussian standard deviation, px */
    float aperture_m;    /* thin lens: aperture radius (0: pinhole) */
    float focus_m;       /* thin lens: distance of the plane in focus */
    int volume_bounces;  /* path.clouds = volume: most scattering events in the clouds */
    int air_collisions;  /* path.air = medium: least tentative collisions per flight */
    int pad2;
} atmo_gpu_path;

#endif
