/* gpu_terrain.h — the procedural terrain (kernels/terrain/) as the kernels see it. Zero unless
 * the scene has terrain.enabled. Shared byte for byte with OpenCL C (checked by plan.c and
 * tests/test_gpu_layout.c).
 *
 * `field` is the height field itself, the only part the heightmap pass reads (its cache key);
 * with a host-supplied height grid (a digital elevation model in metres, atmo_plan_terrain_base)
 * the heightmap pass resamples the grid and adds base_detail times the fBm, and lookups inside
 * the heightmap add the fBm's octaves below the grid's cells (detail_*; terrain_detail.h); the
 * rest is the
 * camera's placement over it (follows the view) and the tracing, shading and
 * shadow settings. Heights are in metres above the ground sphere (sea level), a function of
 * the planar coordinates (u, v) of a point's foot on the sphere (kernels/terrain/terrain.h). */
#ifndef ATMO_GPU_TERRAIN_H
#define ATMO_GPU_TERRAIN_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#endif

typedef struct atmo_gpu_terrain_field {
    float max_height_m;             /* H: heights lie in [0, H] */
    float frequency_per_m;          /* the fBm's first octave */
    float coverage_frequency_per_m; /* the land/sea field's first octave */
    float land_fraction;            /* land/sea threshold: 1 all land, 0 all sea */
    int octaves;                    /* of the height fBm (9) */
    int coverage_octaves;           /* of the land/sea field (6) */
    uint seed;                      /* of the integer hash */
    int heightmap_size;             /* texels per side; 0: direct evaluation, no heightmap */
    int heightmap_format;           /* ATMO_TERRAIN_FORMAT_* (gpu_enums.h) */
    float heightmap_extent_m;       /* side of the square it covers, centred on the origin */
    int base_nx, base_nz;           /* a host-supplied height grid (buffer terrain_base, row-major
                                       in z), 0 x 0: none */
    float4 base_rect;               /* its first sample's planar (u, v) and its spacing, m:
                                       x0, z0, dx, dz */
    float base_detail;              /* the fBm's share added over the grid (0: the grid alone) */
    int detail_octave0;             /* first fBm octave of the detail below a DEM's cells */
    int detail_octaves;             /* its octaves, 0: none (terrain_detail.h) */
    float detail_amplitude_m;       /* the first detail octave's amplitude, m */
    float warp;                     /* the fBm's domain warp, first-octave cells (noise.h);
                                       0: none */
    int pad0, pad1, pad2;
} atmo_gpu_terrain_field;

typedef struct atmo_gpu_terrain {
    atmo_gpu_terrain_field field;
    float4 camera;        /* xyz: the camera's world position (m); w: its altitude above the
                             ground sphere (m), computed in double */
    float sea_level_m;    /* water where the height is at or below it */
    float slope_bound;    /* bound on |grad h| used to size the sphere-tracing steps */
    float optimism;       /* step relaxation factor (1: steps within the bound) */
    float tolerance;      /* hit tolerance per metre of distance (a pixel's footprint) */
    int steps;            /* sphere-tracing steps before the fallback march */
    int shadow;           /* ATMO_TERRAIN_SHADOW_* */
    int shadow_rays;      /* exact shadows: rays toward points of the sun disc */
    int shadow_steps;     /* steps of one shadow ray */
    float shadow_far_m;   /* shadow rays and shafts look this far toward the sun */
    int shafts;           /* bit set of ATMO_TERRAIN_SHAFT_* shortcuts */
    float pixel_angle;    /* radians per pixel: the distance filter of shading detail */
    int sun_map_size;     /* the sun-height map's texels per side (terrain_sun.h); 0: no map,
                             every sun query marches */
    float sun_map_extent_m; /* side of the map's square on the camera's tangent plane, m */
    int sun_map_lead;     /* texels the bake marches beyond the map's sunward edge */
    float sun_map_soft_m; /* width of the query's soft edge around the stored height, m */
    int pad3;
    float4 sun_map_axis;  /* xyz: the sun's horizontal direction at the camera (the map's
                             rows); w: tan of the sun's elevation there */
    float stretch_slope;  /* under the domain warp: the bound on |grad h| per unit of the warp's
                             stretch ||J|| over the direct fBm (the tracer's local bound);
                             0 without a warp */
    float slope_growth_per_m; /* how fast that local bound can grow per metre along a ray */
    int pad4, pad5;
} atmo_gpu_terrain;

#endif
