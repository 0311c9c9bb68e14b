/* gpu_enums.h — the choices that host and kernels both name, in one header both compilers read.
 *
 * Scene parameters store these values, the plan copies them into the GPU structs, and the
 * kernels compare against the same names, so no choice is a bare number on either side. */
#ifndef ATMO_GPU_ENUMS_H
#define ATMO_GPU_ENUMS_H

/* camera.kind: a pinhole, an equirectangular panorama of the full sphere, or an equal-area
 * fisheye (kernels/common/camera.h) */
enum { ATMO_CAMERA_PERSPECTIVE = 0, ATMO_CAMERA_PANORAMA = 1, ATMO_CAMERA_FISHEYE = 2 };

/* atmosphere.mie_phase: the aerosol phase function */
enum { ATMO_PHASE_CORNETTE_SHANKS = 0, ATMO_PHASE_HENYEY_GREENSTEIN = 1 };

/* cloud.phase: the droplets' phase function (the Mie table, Henyey-Greenstein with the table's
 * g, or Jendersie and d'Eon's fit for the effective diameter) */
enum { ATMO_CLOUD_PHASE_MIE = 0, ATMO_CLOUD_PHASE_HG, ATMO_CLOUD_PHASE_JENDERSIE_DEON };

/* The fBm cloud layer's look (kernels/clouds/cloud_layer.h): multiple scattering by octaves and
 * sky ambient from the atmosphere, or the thesis' constant ambient, powder and soft clamp. */
enum { ATMO_CLOUDS_LOOK_PHYSICAL = 0, ATMO_CLOUDS_LOOK_THESIS = 1 };

/* The denoiser's guide pass (kernels/render/guides.cl): its pattern of GRID x GRID rays per
 * pixel under each mode's pixel filter (the path tracer's Gaussian, the preview's box), and the
 * side of the blocks of that pattern whose rays share one march through the fBm cloud layer
 * (docs/guide/denoise.md) */
enum {
    ATMO_GUIDES_PATH_GRID = 8,
    ATMO_GUIDES_PREVIEW_GRID = 4,
    ATMO_GUIDES_BLOCK = 2,                                     /* in both modes */
    ATMO_GUIDES_BLOCK_RAYS = ATMO_GUIDES_BLOCK * ATMO_GUIDES_BLOCK
};

/* post.tonemap and post.transfer: the display pipeline's operator and curve
 * (kernels/post/tonemap.h) */
enum {
    ATMO_TONEMAP_NONE = 0,
    ATMO_TONEMAP_EXPOSURE,
    ATMO_TONEMAP_REINHARD,
    ATMO_TONEMAP_REINHARD_WHITE,
    ATMO_TONEMAP_ACES,
    ATMO_TONEMAP_UNREAL3,
    ATMO_TONEMAP_UCHIMURA,
    ATMO_TONEMAP_LOTTES,
};
enum { ATMO_TRANSFER_SRGB = 0, ATMO_TRANSFER_GAMMA22 = 1 };

/* terrain.heightmap_format: the heightmap pass's texels (kernels/terrain/heightmap.cl): the
 * height alone (normals from its differences), the height and its two derivatives, or the
 * height alone as a half float (kernels/terrain/terrain_half.h) */
enum { ATMO_TERRAIN_FORMAT_FLOAT = 0, ATMO_TERRAIN_FORMAT_DERIVATIVES = 1,
       ATMO_TERRAIN_FORMAT_HALF = 2 };

/* terrain.shadow: the terrain's shadow on the sun (kernels/terrain/terrain.h): none, exact
 * (shadow rays to points of the sun disc), or Quilez's penumbra estimate from one ray */
enum { ATMO_TERRAIN_SHADOW_NONE = 0, ATMO_TERRAIN_SHADOW_EXACT, ATMO_TERRAIN_SHADOW_ESTIMATE };

/* terrain.sun_visibility: how the points of view rays ask the terrain for the sun
 * (kernels/terrain/terrain_sun.h): the baked sun-height map, or the exact march */
enum { ATMO_TERRAIN_SUN_BY_MAP = 0, ATMO_TERRAIN_SUN_BY_MARCH = 1 };

/* terrain.shafts: the light-shaft shortcuts of the thesis (presets.md), each a bit; 0: every
 * sample of the medium integrator asks the terrain's shadow */
enum {
    ATMO_TERRAIN_SHAFT_BELOW_HORIZON = 1, /* (1) sun below the sample's horizon: shadowed */
    ATMO_TERRAIN_SHAFT_FAR = 2,           /* (6) sample beyond the shadow far plane: lit */
    ATMO_TERRAIN_SHAFT_SURFACE = 4,       /* (2) within 400 m of a shadowed surface hit: shadowed */
    ATMO_TERRAIN_SHAFT_SPARSE = 8,        /* (3) looking away from the sun: every 6th sample */
    ATMO_TERRAIN_SHAFT_START = 16,        /* (4) march from 0.6 of the distance to the surface */
    ATMO_TERRAIN_SHAFT_REST = 32,         /* (5) shadowed beyond half the path: the rest too */
    ATMO_TERRAIN_SHAFT_ALL = 63,
    ATMO_TERRAIN_SHAFT_DEFAULT = 8        /* terrain.shafts default: the one that pays (bench) */
};
/* (A sample above the highest terrain whose sun ray rises is lit without a shortcut: the
 * tracer's shell test, kernels/terrain/terrain.h, returns at once. The shortcuts:
 * kernels/terrain/terrain_shafts.h.) */

/* atmosphere.method, in the order of the scene registry's names */
enum {
    ATMO_METHOD_SINGLE = 0, /* single scattering only, ray marched */
    ATMO_METHOD_MARCH,      /* ray-marched single scattering + a multiple-scattering term */
    ATMO_METHOD_FAST,       /* per-frame LUTs (Hillaire 2020 style) */
    ATMO_METHOD_LUT,        /* precomputed 4-D scattering LUTs (Bruneton 2017 style) */
    ATMO_METHOD_REFERENCE,  /* Monte Carlo volumetric path tracer, all orders: the oracle */
    ATMO_METHOD_AUTO,       /* the scene's value only: the plan picks one of the above
                               (atmo_plan_auto_method) */
};

/* render.mode: the preview (sky_render: primary rays, surfaces lit by the sun and the sky's
 * irradiance) or the path tracer (path_render, kernels/render/path.h) */
enum { ATMO_RENDER_PREVIEW = 0, ATMO_RENDER_PATH = 1 };

/* objects[].type (gpu_path.h) */
enum { ATMO_OBJECT_SPHERE = 0, ATMO_OBJECT_BOX = 1 };

/* path.sky: the light a path sees where it leaves the scene: the atmosphere's (the scene's
 * method), or a uniform test sky of radiance path.uniform_sky with no air, its sun unattenuated
 * (kernels/render/path.h) */
enum { ATMO_PATH_SKY_ATMOSPHERE = 0, ATMO_PATH_SKY_UNIFORM = 1 };
/* path.clouds: the method marches the cloud layer along each segment, or the path scatters in
 * it (kernels/render/volume_stage.h) */
enum { ATMO_PATH_CLOUDS_MARCH = 0, ATMO_PATH_CLOUDS_VOLUME = 1 };
/* path.air: the method gives each segment's air light (sky_trace), or the air is a volume
 * medium of the path tracer, whose paths scatter in it (kernels/render/volume_stage.h) */
enum { ATMO_PATH_AIR_METHOD = 0, ATMO_PATH_AIR_MEDIUM = 1 };

/* path.sampler: the primary samples (pixel position): Owen-scrambled Sobol, or the counter
 * hash of rng.h (independent random numbers, for comparison) */
enum { ATMO_SAMPLER_SOBOL = 0, ATMO_SAMPLER_RANDOM = 1 };

#endif
