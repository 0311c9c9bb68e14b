/* terrain_params.c — the scene parameters of the procedural terrain (terrain.*) and a DEM as the
 * terrain (terrain.heightmap_*): rows of the scene's parameter registry (atmo/scene_params.h),
 * registered from this folder. */
#include "atmo/scene_params.h"

static const char *const terrain_format_names[] = {"float", "derivatives", "half", NULL};
static const char *const terrain_shadow_names[] = {"none", "exact", "estimate", NULL};
static const char *const terrain_sun_names[] = {"map", "exact", NULL};
/* ATMO_DEM_NODATA_* of dem.h, in order */
static const char *const dem_nodata_names[] = {"neighbours", "sea-level", NULL};

static const atmo_param rows[] = {
    ROW_BOOL("terrain.enabled", terrain.enabled, 0,
             "procedural terrain on the planet (kernels/terrain/; methods single, march, fast, lut)"),
    ROW_FLOAT("terrain.max_height_m", terrain.max_height_m, "m", 0, 2e4, 4000,
              "terrain heights lie between 0 and this above sea level"),
    ROW_FLOAT("terrain.sea_level_m", terrain.sea_level_m, "m", 0, 2e4, 0,
              "water covers the terrain up to this altitude"),
    ROW_FLOAT("terrain.frequency_per_m", terrain.frequency_per_m, "1/m", 1e-7, 1e-2, 3e-5,
              "first octave of the height fBm (thesis: 3e-5, its heightmap's 33 km period: gentle "
              "hills; the thesis presets set 1e-4, steep mountains)"),
    ROW_FLOAT("terrain.coverage_frequency_per_m", terrain.coverage_frequency_per_m, "1/m", 1e-9,
              1e-3, 2e-7, "first octave of the land/sea field (thesis: 2e-7)"),
    ROW_FLOAT("terrain.land_fraction", terrain.land_fraction, "", 0, 1, 0.6,
              "land/sea threshold: 1 all land, 0 all sea (the land's share rises steeply "
              "between 0.3 and 0.45)"),
    ROW_FLOAT("terrain.warp", terrain.warp, "", 0, 4, 1.25,
              "domain warp of the height fBm, in its first octave's cells: bends the value "
              "noise's square lattice so snow lines and valleys from orbit are not axis-aligned "
              "(0: none; the sphere tracer's slope bound grows by a factor 1 + 5.3 warp; the "
              "thesis presets set 0)"),
    ROW_INT("terrain.octaves", terrain.octaves, "", 1, 16, 9, "octaves of the height fBm"),
    ROW_INT("terrain.coverage_octaves", terrain.coverage_octaves, "", 1, 12, 6,
            "octaves of the land/sea field"),
    ROW_INT("terrain.seed", terrain.seed, "", 0, 2147483647, 0, "seed of the terrain's noise"),
    ROW_INT("terrain.heightmap_size", terrain.heightmap_size, "", 0, 16384, 0,
            "heightmap texels per side (0: evaluate the fBm directly, no memory)"),
    ROW_ENUM("terrain.heightmap_format", terrain.heightmap_format, terrain_format_names,
             ATMO_TERRAIN_FORMAT_FLOAT,
             "heightmap texels: float height, height and derivatives (3 floats), or half-float "
             "height (2 bytes, rounded to 2^-11 of it)"),
    ROW_FLOAT("terrain.heightmap_extent_m", terrain.heightmap_extent_m, "m", 1, 1e7, 65536,
              "side of the square the heightmap covers, centred on the origin"),
    ROW_INT("terrain.steps", terrain.steps, "", 1, 4096, 600,
            "sphere-tracing steps per ray (then a bounded fallback march)"),
    ROW_FLOAT("terrain.optimism", terrain.optimism, "", 0.1, 10, 3,
              "sphere-tracing step relaxation (1: within the slope bound; more: faster, "
              "back-steps on overshoot)"),
    ROW_ENUM("terrain.shadow", terrain.shadow, terrain_shadow_names, ATMO_TERRAIN_SHADOW_EXACT,
             "terrain shadows on the surface: none, exact (rays to the sun disc) or estimate "
             "(Quilez penumbra)"),
    ROW_INT("terrain.shadow_rays", terrain.shadow_rays, "", 1, 256, 4,
            "exact shadows: rays toward points of the sun disc"),
    ROW_INT("terrain.shadow_steps", terrain.shadow_steps, "", 1, 4096, 96,
            "steps of one shadow ray"),
    ROW_FLOAT("terrain.shadow_far_m", terrain.shadow_far_m, "m", 1, 1e7, 40000,
              "shadow rays and light shafts look this far toward the sun"),
    ROW_INT("terrain.shafts", terrain.shafts, "", 0, 63, ATMO_TERRAIN_SHAFT_DEFAULT,
            "light-shaft shortcuts, a bit set: 1 sun below the sample's horizon = shadowed, "
            "2 samples beyond terrain.shadow_far_m = lit, 4 within 400 m of a shadowed "
            "surface = shadowed, 8 every 6th sample away from the sun, 16 shadow march from "
            "0.6 of the way to the surface, 32 shadowed beyond half the path = rest shadowed"),
    ROW_BOOL("terrain.air_shadows", terrain.air_shadows, 1,
             "terrain shadows in the air (light shafts) and on the clouds and the preview's "
             "objects: false leaves the terrain out of the sun's occluders at those points; "
             "the terrain's own surface keeps its shadows"),
    ROW_ENUM("terrain.sun_visibility", terrain.sun_visibility, terrain_sun_names,
             ATMO_TERRAIN_SUN_BY_MAP,
             "how points of view rays (aerial perspective, light shafts) ask the terrain for "
             "the sun: map (a sun-height map baked per camera and sun, a bilinear lookup) or "
             "exact (a march toward the sun per point); the path tracer always marches"),
    ROW_INT("terrain.sun_map_size", terrain.sun_map_size, "", 2, 4096, 1024,
            "texels per side of the sun-height map"),
    ROW_FLOAT("terrain.sun_map_extent_m", terrain.sun_map_extent_m, "m", 100, 1e6, 80000,
              "side of the sun-height map's square, centred under the camera (outside it "
              "points march)"),
    /* a digital elevation model as the terrain (atmo/dem.h; `atmo dem info FILE`) */
    ROW_STRING("terrain.heightmap_file", dem.file,
               "DEM file: GeoTIFF (with GDAL), 16-bit PNG or one-channel EXR; \"\" = none"),
    ROW_FLOAT("terrain.heightmap_file_extent_m", dem.extent_m, "m", 0, 1e7, 0,
              "east-west size of a PNG/EXR heightmap (north-south by its aspect); GeoTIFF: 0, "
              "from the file"),
    ROW_VEC2("terrain.heightmap_center_m", dem.center_m, "m", -1e8, 1e8, 0, 0,
             "world X, Z of the heightmap's centre (+X east, +Z north; row 0 is north)"),
    ROW_FLOAT("terrain.heightmap_scale_m", dem.scale_m, "m", 0, 1e5, 1000,
              "PNG heightmap: metres between value 0 and the largest value (65535 or 255)"),
    ROW_FLOAT("terrain.heightmap_offset_m", dem.offset_m, "m", -1e5, 1e5, 0,
              "PNG heightmap: height of value 0 above sea level"),
    ROW_BOOL("terrain.heightmap_detail", dem.detail, 0,
             "the procedural fBm adds detail below the heightmap's cell size (the tracer takes "
             "twice terrain.steps over it)"),
    ROW_ENUM("terrain.heightmap_nodata", dem.nodata, dem_nodata_names, 0,
             "heightmap samples without data: filled from their neighbours, or sea level (0 m)"),
};
ATMO_PARAM_SET(terrain, rows);
