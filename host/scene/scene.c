/* scene.c — the scene parameter registry and the checks on every value a user can set.
 *
 * atmo_params[] has one row per field of atmo_scene (scene.h): its dotted key (the struct path),
 * type, unit, valid range, default and a one-line meaning. Everything that reads or writes a
 * scene goes through it: the defaults, --set, presets, JSON scene files (scene_json.c), and
 * `atmo params`. Units are those of the key's name: _deg degrees, _m metres, _nm nanometres,
 * _per_m 1/m; the Rayleigh coefficient c gives beta_R(lambda) = c * lambda[um]^-4 in 1/m.
 *
 * Values are rejected, with one line naming the key, the value, the valid range and the unit:
 * unknown keys (with the closest key by Levenshtein edit distance), text that is not entirely a
 * number (strtod must consume it all), NaN and Inf, values outside [min, max] (inclusive, every
 * component of a vec3), non-integers for int keys, and enum names not in the list.
 * String keys (file paths) take any text shorter than ATMO_PARAM_STRING_MAX bytes without control
 * characters; "" means none. Vec2 keys are two numbers "x,z".
 * atmo_scene_validate adds the checks between parameters: top radius above the bottom radius,
 * ozone bottom <= peak <= top with bottom < top, and the camera not below the ground. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "atmo/scene.h"
#include "atmo/suggest.h"

/* offsetof(atmo_scene, f), failing to compile when the field's size is not that of the row's
 * type (a row declared INT on a double field would otherwise write 4 bytes into 8). */
#define SCENE_FIELD(f, type)                                                                       \
    (offsetof(atmo_scene, f) +                                                                     \
     0 * sizeof(char[sizeof(((atmo_scene *)0)->f) == sizeof(type) ? 1 : -1]))
#define ROW_INT(k, f, unit, lo, hi, d, help) \
    {k, ATMO_PARAM_INT, SCENE_FIELD(f, int), unit, lo, hi, {d, 0, 0}, NULL, help}
#define ROW_FLOAT(k, f, unit, lo, hi, d, help) \
    {k, ATMO_PARAM_FLOAT, SCENE_FIELD(f, double), unit, lo, hi, {d, 0, 0}, NULL, help}
#define ROW_VEC3(k, f, unit, lo, hi, x, y, z, help) \
    {k, ATMO_PARAM_VEC3, SCENE_FIELD(f, double[3]), unit, lo, hi, {x, y, z}, NULL, help}
#define ROW_ENUM(k, f, names, d, help)                                                       \
    {k, ATMO_PARAM_ENUM, SCENE_FIELD(f, int), "", 0, sizeof names / sizeof names[0] - 2, \
     {d, 0, 0}, names, help}
#define ROW_BOOL(k, f, d, help) \
    {k, ATMO_PARAM_BOOL, SCENE_FIELD(f, int), "", 0, 1, {d, 0, 0}, NULL, help}
#define ROW_VEC2(k, f, unit, lo, hi, x, z, help) \
    {k, ATMO_PARAM_VEC2, SCENE_FIELD(f, double[2]), unit, lo, hi, {x, z, 0}, NULL, help}
/* a string's default is always "" (a scene starts with no file named) */
#define ROW_STRING(k, f, help) \
    {k, ATMO_PARAM_STRING, SCENE_FIELD(f, char[ATMO_PARAM_STRING_MAX]), "", 0, 0, {0, 0, 0}, \
     NULL, help}

/* Enum names in the order of the ATMO_* constants of scene.h and atmosphere.h. */
static const char *const camera_kinds[] = {"perspective", "panorama", "fisheye", NULL};
static const char *const camera_terrain_modes[] = {"off", "below", "at", NULL};
static const char *const phase_names[] = {"cornette-shanks", "henyey-greenstein", NULL};
static const char *const method_names[] = {"single", "march", "fast", "lut", "reference", "auto",
                                           NULL};
static const char *const quantity_names[] = {"radiance", "luminance", NULL};
static const char *const tonemap_names[] = {"none",           "exposure", "reinhard",
                                            "reinhard-white", "aces",     "unreal3",
                                            "uchimura",       "lottes",   NULL};
static const char *const transfer_names[] = {"srgb", "gamma22", NULL};
static const char *const denoise_names[] = {"auto", "off", "fast", "balanced", "high", NULL};
_Static_assert(ATMO_OUTPUT_DENOISE_HIGH == 4, "enum name tables follow the order of the constants");
/* the size-distribution presets of mie_dsd_preset (host/mie_dsd.c), in its order */
static const char *const cloud_dsd_names[] = {"cumulus", "stratus", "fog", "corona",
                                              "thesis-disperse", "thesis-uniform", NULL};
static const char *const cloud_phase_names[] = {"mie", "hg", "jendersie-deon", NULL};
/* ATMO_DEM_NODATA_* of dem.h, in order */
static const char *const dem_nodata_names[] = {"neighbours", "sea-level", NULL};
static const char *const clouds_look_names[] = {"physical", "thesis", NULL};
static const char *const render_modes[] = {"preview", "path", NULL};
static const char *const path_skies[] = {"atmosphere", "uniform", NULL};
static const char *const path_clouds_names[] = {"march", "volume", NULL};
static const char *const path_air_names[] = {"method", "medium", NULL};
static const char *const sampler_names[] = {"sobol", "random", NULL};
_Static_assert(ATMO_RENDER_PATH == 1 && ATMO_PATH_SKY_UNIFORM == 1 && ATMO_SAMPLER_RANDOM == 1 &&
                   ATMO_PATH_CLOUDS_VOLUME == 1 && ATMO_PATH_AIR_MEDIUM == 1,
               "enum name tables follow the order of the constants");
static const char *const terrain_format_names[] = {"float", "derivatives", "half", NULL};
static const char *const terrain_shadow_names[] = {"none", "exact", "estimate", NULL};
static const char *const terrain_sun_names[] = {"map", "exact", NULL};
_Static_assert(ATMO_CAMERA_PANORAMA == 1 && ATMO_CAMERA_FISHEYE == 2 && ATMO_PHASE_HENYEY_GREENSTEIN == 1 &&
                   ATMO_QUANTITY_LUMINANCE == 1 && ATMO_TONEMAP_LOTTES == 7 &&
                   ATMO_TRANSFER_GAMMA22 == 1,
               "enum name tables follow the order of the constants");

const atmo_param atmo_params[] = {
    ROW_INT("image.width", image.width, "px", 1, 16384, 640, "image width in pixels"),
    ROW_INT("image.height", image.height, "px", 1, 16384, 360, "image height in pixels"),
    ROW_INT("image.samples", image.samples, "", 1, 1e6, 16,
            "samples per pixel (more: less noise, longer render)"),
    ROW_INT("image.seed", image.seed, "", 0, 2147483647, 0,
            "random-number seed; the same seed and scene give the same image"),
    ROW_ENUM("camera.kind", camera.kind, camera_kinds, ATMO_CAMERA_PERSPECTIVE,
             "perspective pinhole, a 360-degree equirectangular panorama (environment map, "
             "Blender's layout), or an equal-area fisheye of vertical field camera.fov_deg"),
    ROW_VEC3("camera.position_m", camera.position_m, "m", -1e9, 1e9, 0, 1.7, 0,
             "camera position in metres: Y up, origin at sea level, planet centre (0,-R,0)"),
    ROW_FLOAT("camera.pitch_deg", camera.pitch_deg, "deg", -90, 90, 0,
              "camera pitch in degrees above the horizontal (ignored by panoramas)"),
    ROW_FLOAT(
        "camera.yaw_deg", camera.yaw_deg, "deg", -3600, 3600, 0,
        "camera yaw in degrees: 0 looks along +Z, forward = (-cos p sin y, sin p, cos p cos y)"),
    ROW_FLOAT("camera.fov_deg", camera.fov_deg, "deg", 1, 179, 45,
              "vertical field of view of the perspective camera in degrees"),
    ROW_ENUM("camera.on_terrain", camera.on_terrain, camera_terrain_modes,
             ATMO_CAMERA_TERRAIN_OFF,
             "camera.position_m's y: above sea level (off), above the terrain's surface under "
             "the camera (below) or at camera.terrain_at_m (at: an object's anchor)"),
    ROW_VEC2("camera.terrain_at_m", camera.terrain_at_m, "m", -1e8, 1e8, 0, 0,
             "world X, Z of the terrain point camera.on_terrain=at measures the camera's y from"),
    ROW_FLOAT("sun.zenith_deg", sun.zenith_deg, "deg", 0, 180, 0,
              "sun zenith angle in degrees from world +Y (90 = on the horizon)"),
    ROW_FLOAT(
        "sun.azimuth_deg", sun.azimuth_deg, "deg", -3600, 3600, 0,
        "sun azimuth in degrees: direction (sin z sin a, cos z, sin z cos a); a = -yaw faces it"),
    ROW_FLOAT("sun.angular_radius_deg", sun.angular_radius_deg, "deg", 0.01, 10, 0.26786,
              "angular radius of the sun disc in degrees"),
    ROW_FLOAT("sun.irradiance_scale", sun.irradiance_scale, "", 0, 1e6, 1,
              "factor on the solar spectrum (1 = ASTM G-173 extraterrestrial)"),
    ROW_FLOAT("atmosphere.bottom_radius_m", atmosphere.bottom_radius_m, "m", 1e3, 1e8, 6360e3,
              "planet (sea-level) radius in metres"),
    ROW_FLOAT("atmosphere.top_radius_m", atmosphere.top_radius_m, "m", 1e3, 1e8, 6420e3,
              "radius of the top of the atmosphere in metres"),
    ROW_FLOAT("atmosphere.rayleigh_coefficient", atmosphere.rayleigh_coefficient, "1/m um^4", 0, 1,
              1.24062e-6, "Rayleigh scattering at sea level: beta_R = c * lambda[um]^-4 in 1/m"),
    ROW_FLOAT("atmosphere.rayleigh_scale_height_m", atmosphere.rayleigh_scale_height_m, "m", 1, 1e6,
              8000, "Rayleigh (air) density scale height in metres"),
    ROW_FLOAT("atmosphere.mie_extinction_per_m", atmosphere.mie_extinction_per_m, "1/m", 0, 1,
              4.44e-6, "aerosol extinction coefficient at sea level in 1/m, every wavelength"),
    ROW_FLOAT("atmosphere.mie_albedo", atmosphere.mie_albedo, "", 0, 1, 0.9,
              "aerosol single-scattering albedo (scattering / extinction)"),
    ROW_FLOAT("atmosphere.mie_scale_height_m", atmosphere.mie_scale_height_m, "m", 1, 1e6, 1200,
              "aerosol density scale height in metres"),
    ROW_FLOAT("atmosphere.mie_g", atmosphere.mie_g, "", -0.999, 0.999, 0.8,
              "aerosol phase asymmetry parameter g (0 = isotropic, > 0 forward)"),
    ROW_ENUM("atmosphere.mie_phase", atmosphere.mie_phase, phase_names, ATMO_PHASE_CORNETTE_SHANKS,
             "aerosol phase function"),
    ROW_ENUM("atmosphere.method", atmosphere.method, method_names, ATMO_METHOD_AUTO,
             "how light transport in the atmosphere is computed (see README: Methods); auto: "
             "march where the scene has clouds or the observer, else fast"),
    ROW_BOOL("cloud.enabled", cloud.enabled, 0,
             "a homogeneous cloud/fog shell (methods single, march and reference; "
             "kernels/cloud_shell/cloud_shell.h)"),
    ROW_FLOAT("cloud.bottom_m", cloud.bottom_m, "m", 0, 1e5, 1000,
              "altitude of the cloud shell's base above sea level"),
    ROW_FLOAT("cloud.top_m", cloud.top_m, "m", 0, 1e5, 2000,
              "altitude of the cloud shell's top above sea level (above cloud.bottom_m)"),
    ROW_ENUM("cloud.dsd", cloud.dsd, cloud_dsd_names, 0,
             "droplet size distribution (presets of atmo mie --dsd)"),
    ROW_FLOAT("cloud.lwc_g_m3", cloud.lwc_g_m3, "g/m^3", 1e-6, 10, 0.3,
              "liquid water content; extinction = sigma_ext/LWC of the distribution x this"),
    ROW_ENUM("cloud.phase", cloud.phase, cloud_phase_names, 0,
             "cloud phase function: Mie table, Henyey-Greenstein with the table's g, or "
             "Jendersie-d'Eon for the distribution's effective diameter"),
    ROW_FLOAT("cloud.hg_g", cloud.hg_g, "", -0.99, 0.99, 0,
              "asymmetry g of cloud.phase=hg at every wavelength (0: the Mie table's g)"),
    ROW_BOOL("cloud.sun_disc", cloud.sun_disc, 1,
             "convolve the Mie table with the sun's disc (smooths ripples a point sun shows)"),
    ROW_FLOAT("cloud.sun_guiding", cloud.sun_guiding, "", 0, 0.9, 0.1,
              "method reference: probability that a scattering in the shell draws its new "
              "direction from the phase lobe around the sun (unbiased; lowers the noise of "
              "forward-peaked phases)"),
    ROW_BOOL("clouds.enabled", clouds.enabled, 0,
             "the fBm cloud layer: coverage x shaped 3-D fBm between two altitudes (methods "
             "single, march and reference; kernels/clouds/cloud_layer.h)"),
    ROW_FLOAT("clouds.bottom_m", clouds.bottom_m, "m", 0, 1e5, 1000,
              "altitude of the cloud layer's bottom above sea level"),
    ROW_FLOAT("clouds.top_m", clouds.top_m, "m", 0, 1e5, 8000,
              "altitude of the cloud layer's top above sea level (above clouds.bottom_m)"),
    ROW_FLOAT("clouds.fade_m", clouds.fade_m, "m", 1, 1e5, 2000,
              "the coverage fades in over this height above the bottom and out below the top"),
    ROW_FLOAT("clouds.coverage", clouds.coverage, "", 0, 1, 0.25,
              "mean of the coverage field (0: clear, 1: overcast)"),
    ROW_FLOAT("clouds.density", clouds.density, "", 0, 1e6, 5,
              "density scale: extinction = density x (coverage - fBm)^sharpness x "
              "clouds.extinction_per_m"),
    ROW_FLOAT("clouds.sharpness", clouds.sharpness, "", 0.1, 10, 1.05,
              "exponent on (coverage - fBm): above 1 softer edges, below 1 harder"),
    ROW_VEC3("clouds.frequency_per_m", clouds.frequency_per_m, "1/m", 1e-8, 1, 8e-5, 16e-5, 8e-5,
             "base frequency of the shape fBm along world x, y, z"),
    ROW_FLOAT("clouds.coverage_scale_m", clouds.coverage_scale_m, "m", 1e3, 1e8, 5e5,
              "size of the coverage field's largest features (its 4 octaves halve it)"),
    ROW_INT("clouds.octaves", clouds.octaves, "", 1, 12, 6, "octaves of the shape fBm"),
    ROW_FLOAT("clouds.warp_m", clouds.warp_m, "m", 0, 1e5, 3000,
              "domain-warp amplitude: the fBm is sampled at points displaced this much"),
    ROW_INT("clouds.seed", clouds.seed, "", 0, 2147483647, 0, "the cloud noise's seed"),
    ROW_FLOAT("clouds.wind_m_s", clouds.wind_m_s, "m/s", 0, 1000, 10,
              "wind speed: the clouds move by wind x clouds.time_s"),
    ROW_FLOAT("clouds.wind_azimuth_deg", clouds.wind_azimuth_deg, "deg", -3600, 3600, 90,
              "azimuth the wind blows toward: direction (sin a, 0, cos a), as sun.azimuth_deg"),
    ROW_FLOAT("clouds.time_s", clouds.time_s, "s", -1e9, 1e9, 0,
              "time in seconds (atmo render --time): the clouds move with the wind"),
    ROW_FLOAT("clouds.extinction_per_m", clouds.extinction_per_m, "1/m", 0, 10, 10.354e-3,
              "extinction at unit density (thesis: 10.354e-3); 0: from clouds.dsd and "
              "clouds.lwc_g_m3"),
    ROW_FLOAT("clouds.albedo", clouds.albedo, "", 0, 1, 0.9512,
              "single-scattering albedo with clouds.extinction_per_m > 0 (thesis: 0.9512)"),
    ROW_STRING("clouds.dsd", clouds.dsd,
               "droplet size distribution of the phase table (and with clouds.extinction_per_m=0 "
               "of the extinction and albedo), as atmo mie --dsd: a preset (cumulus, stratus, "
               "fog, corona, thesis-disperse, thesis-uniform) or mono:R, gamma:REFF,VEFF, "
               "lognormal:RG,SIGMA_G, modgamma:ALPHA,B,GAMMA (um; optional ,max=R); "
               "\"\" = cumulus"),
    ROW_FLOAT("clouds.lwc_g_m3", clouds.lwc_g_m3, "g/m^3", 1e-6, 10, 0.2,
              "liquid water content at unit density, with clouds.extinction_per_m=0"),
    ROW_ENUM("clouds.phase", clouds.phase, cloud_phase_names, 0,
             "cloud phase function: Mie table, Henyey-Greenstein with the table's g, or "
             "Jendersie-d'Eon for the distribution's effective diameter"),
    ROW_FLOAT("clouds.sun_guiding", clouds.sun_guiding, "", 0, 0.9, 0.1,
              "method reference and path.clouds=volume: probability that a scattering in the "
              "layer draws its new direction from the phase lobe around the sun (unbiased; "
              "lowers the noise of forward-peaked phases)"),
    ROW_INT("clouds.steps", clouds.steps, "", 1, 100000, 256,
            "the cloud marcher's most steps along a view ray"),
    ROW_FLOAT("clouds.step_m", clouds.step_m, "m", 1, 1e5, 150,
              "the marcher's step in cloud near the camera (it grows with distance, 4x in clear "
              "air)"),
    ROW_INT("clouds.light_steps", clouds.light_steps, "", 1, 1000, 4,
            "steps of the light march toward the sun (4: within the reference's noise of 8 and "
            "16 with the fitted octaves, atmo bench clouds)"),
    ROW_FLOAT("clouds.light_distance_m", clouds.light_distance_m, "m", 1, 1e6, 8000,
              "length of the light march toward the sun from the samples inside clouds (one "
              "in clear air or on a surface spreads its steps over the whole chord through the "
              "layer, a surface in at least 32)"),
    ROW_BOOL("clouds.shadow_map", clouds.shadow_map, 0,
             "the sun shadow map: the density toward the sun precomputed per view on a grid "
             "around the camera (methods single and march; the reference keeps ratio "
             "tracking), instead of the light march at each sample"),
    ROW_INT("clouds.shadow_map_size", clouds.shadow_map_size, "", 2, 16384, 256,
            "the shadow map's nodes per horizontal axis over the marcher's far plane "
            "(2 x clouds.max_distance_m, at most 0.2 ground radii)"),
    ROW_INT("clouds.shadow_map_levels", clouds.shadow_map_levels, "", 2, 1024, 32,
            "the shadow map's nodes between clouds.bottom_m and clouds.top_m"),
    ROW_INT("clouds.shadow_map_steps", clouds.shadow_map_steps, "", 1, 1024, 48,
            "steps of each shadow-map node's integral over the whole chord toward the sun"),
    ROW_FLOAT("clouds.max_distance_m", clouds.max_distance_m, "m", 1, 1e8, 150000,
              "the marcher's far plane: clouds beyond it are not seen"),
    ROW_FLOAT("clouds.lod", clouds.lod, "", 0, 16, 1,
              "level of detail: octaves of the cloud noise finer than this many pixels' footprint "
              "at their distance are replaced by their mean and spread (0: every octave, "
              "point-sampled; kernels/clouds/cloud_layer.h)"),
    ROW_INT("clouds.ms_octaves", clouds.ms_octaves, "", 1, 16, 6,
            "multiple-scattering octaves of the marcher (1: single scattering and the diffuse "
            "orders only; 6 fitted to the reference by atmo bench clouds --fit)"),
    ROW_FLOAT("clouds.ms_a", clouds.ms_a, "", 0, 1, 0.05,
              "per octave: factor on the optical depth toward the sun (fitted: 0.05)"),
    ROW_FLOAT("clouds.ms_b", clouds.ms_b, "", 0, 1, 0.39,
              "per octave: factor on the contribution (fitted: 0.39)"),
    ROW_FLOAT("clouds.ms_c", clouds.ms_c, "", 0, 1, 0.5,
              "per octave: factor on the phase function's anisotropy (fitted: 0.5)"),
    ROW_FLOAT("clouds.ms_d", clouds.ms_d, "", 0, 100, 2.8,
              "weight of the diffuse orders beyond the octaves: isotropic light times this and "
              "the similarity albedo of a semi-infinite cloud, decaying into it at the diffusion "
              "exponent (kernels/clouds/cloud_march.h; 0: none; fitted: 2.8)"),
    ROW_ENUM("clouds.look", clouds.look, clouds_look_names, ATMO_CLOUDS_LOOK_PHYSICAL,
             "physical (octaves, sky ambient) or thesis (constant ambient, powder, soft clamp)"),
    ROW_BOOL("observer.enabled", observer.enabled, 0,
             "an observer sphere that casts a shadow on the cloud (Brocken spectre)"),
    ROW_FLOAT("observer.distance_m", observer.distance_m, "m", 0, 1e4, 5,
              "observer's centre: horizontal distance ahead of the camera toward the antisolar "
              "point (it stays in the vertical plane through the sun)"),
    ROW_FLOAT("observer.height_m", observer.height_m, "m", -1e4, 1e4, -1,
              "observer's centre: height relative to the camera"),
    ROW_FLOAT("observer.radius_m", observer.radius_m, "m", 0.01, 1e3, 1,
              "observer sphere's radius"),
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
    ROW_INT("lut.orders", atmosphere.lut_orders, "", 1, 15, 7,
            "lut method: scattering orders precomputed (1 = single scattering only)"),
    ROW_INT("lut.r_size", atmosphere.lut_r_size, "", 2, 1024, 32,
            "lut method: texels of the scattering LUT along the altitude"),
    ROW_INT("lut.mu_size", atmosphere.lut_mu_size, "", 4, 4096, 128,
            "lut method: texels along the view zenith (even: half ground rays, half sky rays)"),
    ROW_INT("lut.mu_s_size", atmosphere.lut_mu_s_size, "", 2, 1024, 32,
            "lut method: texels along the sun zenith (0 to 120 degrees)"),
    ROW_INT("lut.nu_size", atmosphere.lut_nu_size, "", 2, 256, 8,
            "lut method: texels along the view-sun angle"),
    ROW_INT("lut.steps", atmosphere.lut_steps, "", 4, 4096, 64,
            "lut method: integration steps along the ray of each texel"),
    ROW_INT("lut.sphere_samples", atmosphere.lut_sphere_samples, "", 4, 256, 32,
            "lut method: zenith rings of the direction grid for multiple scattering"),
    ROW_INT("reference.min_order", atmosphere.reference_min_order, "", 1, 1000, 1,
            "reference method: count scattering orders from this one (1 = single scattering)"),
    ROW_INT("reference.max_order", atmosphere.reference_max_order, "", 0, 1000, 0,
            "reference method: count scattering orders up to this one (0 = all orders)"),
    ROW_FLOAT("atmosphere.ozone_column_du", atmosphere.ozone_column_du, "DU", 0, 1000, 300,
              "total ozone column in Dobson units (0 = no ozone absorption)"),
    ROW_FLOAT("atmosphere.ozone_bottom_m", atmosphere.ozone_bottom_m, "m", 0, 1e6, 10000,
              "altitude in metres where the ozone tent profile starts"),
    ROW_FLOAT("atmosphere.ozone_peak_m", atmosphere.ozone_peak_m, "m", 0, 1e6, 25000,
              "altitude in metres of the ozone density peak"),
    ROW_FLOAT("atmosphere.ozone_top_m", atmosphere.ozone_top_m, "m", 0, 1e6, 40000,
              "altitude in metres where the ozone tent profile ends"),
    ROW_FLOAT("atmosphere.ground_albedo", atmosphere.ground_albedo, "", 0, 1, 0.1,
              "Lambertian albedo of the ground"),
    ROW_VEC3("render.wavelengths_nm", render.wavelengths_nm, "nm", 360, 830, 680, 550, 440,
             "the three render wavelengths in nm (R, G, B channels)"),
    ROW_INT("render.spectral_bands", render.spectral_bands, "", 0, 470, 0,
            "0: render at the three wavelengths; N >= 15: spectral mode, N bands over 360-830 nm "
            "combined through the CIE 1931 CMFs into luminance-based linear sRGB (cd/m^2)"),
    ROW_ENUM("render.quantity", render.quantity, quantity_names, ATMO_QUANTITY_RADIANCE,
             "what HDR outputs hold: spectral radiance (W/m^2/sr/nm) or luminance (cd/m^2)"),
    ROW_INT("render.view_steps", render.view_steps, "", 1, 4096, 32,
            "ray-march steps along each view ray"),
    ROW_INT("render.transmittance_width", render.transmittance_width, "", 4, 4096, 256,
            "transmittance LUT size along the view-zenith cosine"),
    ROW_INT("render.transmittance_height", render.transmittance_height, "", 4, 4096, 256,
            "transmittance LUT size along the altitude"),
    ROW_FLOAT("post.exposure", post.exposure, "", 0, 1e9, 10,
              "exposure factor on the (white-balanced) radiance before tone mapping"),
    ROW_ENUM("post.tonemap", post.tonemap, tonemap_names, ATMO_TONEMAP_EXPOSURE,
             "tone-mapping operator for PNG output"),
    ROW_FLOAT("post.white_point", post.white_point, "", 1e-6, 1e9, 4,
              "white point of the reinhard-white operator (exposed units)"),
    ROW_BOOL("post.white_balance", post.white_balance, 1,
             "divide by the sun's colour so sunlight is white"),
    ROW_ENUM("post.transfer", post.transfer, transfer_names, ATMO_TRANSFER_SRGB,
             "PNG encoding curve: sRGB or a pure 2.2 gamma"),
    ROW_ENUM("output.denoise", output.denoise, denoise_names, ATMO_OUTPUT_DENOISE_AUTO,
             "Intel Open Image Denoise on the final linear image, before tone mapping: auto "
             "(PNG outputs, quality high, where the library is installed; not the preview of the "
             "air alone), "
             "off, fast, balanced or high (every output; EXR keeps the noisy image and the "
             "guides as layers)"),
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
    ROW_BOOL("post.flare", post.flare, 0,
             "lens flare from the sun's light in the image (perspective camera only; every "
             "output)"),
    ROW_FLOAT("post.flare_strength", post.flare_strength, "", 0, 1e3, 1,
              "lens flare brightness relative to the default lens"),
    ROW_ENUM("render.mode", path.mode, render_modes, ATMO_RENDER_PREVIEW,
             "preview: primary rays with the method (objects lit by sun and sky irradiance); "
             "path: the progressive path tracer with bounces (kernels/render/path.h)"),
    ROW_INT("path.bounces", path.bounces, "", 0, 64, 5,
            "path mode: reflections off surfaces per path (N_b; 0: the camera ray's light "
            "alone, 1: direct light, each more one order of indirect light)"),
    ROW_INT("path.secondary", path.secondary, "", 1, 64, 1,
            "path mode: secondary rays per primary hit (N_s)"),
    ROW_INT("path.rr_bounce", path.rr_bounce, "", 0, 64, 4,
            "path mode: Russian roulette from this event on (reflections and cloud "
            "scatterings so far)"),
    ROW_BOOL("path.sun_nee", path.sun_nee, 1,
             "path mode: next-event estimation to the sun disc (soft shadows)"),
    ROW_BOOL("path.sky_nee", path.sky_nee, 1,
             "path mode: sample the sky at each hit, combined with BSDF sampling by MIS (off "
             "with path.air = medium, whose sky is the air's scattering)"),
    ROW_ENUM("path.sky", path.sky, path_skies, ATMO_PATH_SKY_ATMOSPHERE,
             "path mode: the atmosphere (the method), or a uniform test sky with no air and an "
             "unattenuated sun"),
    ROW_VEC3("path.uniform_sky", path.uniform_sky, "W/m^2/sr/nm", 0, 1e6, 1, 1, 1,
             "path mode: radiance of the uniform test sky (path.sky = uniform)"),
    ROW_BOOL("path.ground", path.ground, 1,
             "path mode: the planet's ground sphere is a surface (off: only objects; "
             "the terrain replaces it)"),
    ROW_ENUM("path.sampler", path.sampler, sampler_names, ATMO_SAMPLER_SOBOL,
             "path mode: primary samples from Owen-scrambled Sobol or independent random"),
    ROW_FLOAT("path.filter_radius_px", path.filter_radius_px, "px", 0.5, 4, 1.5,
              "path mode: pixel filter (truncated Gaussian) radius in pixels"),
    ROW_FLOAT("path.filter_sigma_px", path.filter_sigma_px, "px", 0.1, 2, 0.5,
              "path mode: pixel filter standard deviation in pixels"),
    ROW_FLOAT("path.aperture_m", path.aperture_m, "m", 0, 10, 0,
              "path mode: thin-lens aperture radius in metres (0: pinhole, no depth of field)"),
    ROW_FLOAT("path.focus_m", path.focus_m, "m", 0.01, 1e7, 10,
              "path mode: distance of the plane in focus in metres (path.aperture_m > 0)"),
    ROW_BOOL("path.passes", path.passes, 0,
             "path mode: render passes as EXR layers (Env, Emit, Volume, Sun, Sky, Clouds, "
             "Depth, Normal, DiffCol, samples and standard error)"),
    ROW_ENUM("path.clouds", path.clouds, path_clouds_names, ATMO_PATH_CLOUDS_MARCH,
             "path mode with clouds.enabled: march (the method marches the layer along each "
             "segment, octave multiple scattering) or volume (paths scatter in the layer: delta "
             "tracking, ratio-tracked sun, phase sampling)"),
    ROW_INT("path.volume_bounces", path.volume_bounces, "", 1, 4096, 256,
            "path mode, path.clouds = volume or path.air = medium: most scattering events in "
            "the clouds and the air per path (Russian roulette ends most paths long before)"),
    ROW_ENUM("path.air", path.air, path_air_names, ATMO_PATH_AIR_METHOD,
             "path mode: method (the atmosphere method gives each segment's air light) or "
             "medium (the air is a volume medium of the paths: Rayleigh, aerosols and ozone "
             "delta-tracked, scatterings lit by the sun, no sky term; an unbiased reference)"),
    ROW_INT("path.air_collisions", path.air_collisions, "", 0, 256, 0,
            "path mode, path.air = medium: least tentative collisions of a free flight through "
            "the air (its majorant at least this over the flight's length), each estimating "
            "the sun's single scattering with a shadow query; 8-16 halve the noise of views up "
            "through thin air at equal time to a given noise, 0 (the walk's own points) is "
            "cheapest with clouds or terrain (docs/guide/path.md)"),
    ROW_BOOL("output.blender", output.blender, 0,
             "outputs for Blender (--blender): luminance-based linear Rec.709 RGB in cd/m^2 "
             "with the EXR chromaticities, the exposure scaled to luminance, panoramas in "
             "Blender's world orientation (docs/guide/blender.md)"),
    {NULL, ATMO_PARAM_INT, 0, NULL, 0, 0, {0, 0, 0}, NULL, NULL},
};

int atmo_param_components(const atmo_param *p)
{
    return p->type == ATMO_PARAM_VEC3 ? 3
           : p->type == ATMO_PARAM_VEC2 ? 2
           : p->type == ATMO_PARAM_STRING ? 0
                                         : 1;
}

/* The types stored as doubles. */
static int is_real(const atmo_param *p)
{
    return p->type == ATMO_PARAM_FLOAT || p->type == ATMO_PARAM_VEC3 ||
           p->type == ATMO_PARAM_VEC2;
}

const atmo_param *atmo_param_find(const char *key)
{
    for (const atmo_param *p = atmo_params; p->key; p++)
        if (strcmp(p->key, key) == 0)
            return p;
    return NULL;
}

static int *int_field(atmo_scene *s, const atmo_param *p)
{
    return (int *)((char *)s + p->offset);
}

static double *double_field(atmo_scene *s, const atmo_param *p)
{
    return (double *)((char *)s + p->offset);
}

void atmo_param_get(const atmo_scene *s, const atmo_param *p, double v[3])
{
    const char *base = (const char *)s + p->offset;
    v[0] = v[1] = v[2] = 0;
    if (is_real(p))
        memcpy(v, base, (size_t)atmo_param_components(p) * sizeof(double));
    else if (p->type != ATMO_PARAM_STRING)
        v[0] = *(const int *)base;
}

const char *atmo_param_text(const atmo_scene *s, const atmo_param *p)
{
    return p->type == ATMO_PARAM_STRING ? (const char *)s + p->offset : NULL;
}

int atmo_param_store_text(atmo_scene *s, const atmo_param *p, const char *text, const char *where,
                          atmo_err *e)
{
    if (p->type != ATMO_PARAM_STRING)
        return atmo_fail(e, ATMO_ERR_USAGE, "%s (from %s) takes a number, not text", p->key,
                         where);
    size_t n = strlen(text);
    if (n >= ATMO_PARAM_STRING_MAX)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "%s = '%.40s...' (from %s) is %zu bytes long; the limit is %d (use a "
                         "shorter path)",
                         p->key, text, where, n, ATMO_PARAM_STRING_MAX - 1);
    for (size_t i = 0; i < n; i++)
        if ((unsigned char)text[i] < 0x20 || text[i] == 0x7f)
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "%s (from %s) holds a control character at byte %zu; write the "
                             "text without one",
                             p->key, where, i);
    char *field = (char *)s + p->offset;
    memset(field, 0, ATMO_PARAM_STRING_MAX); /* the rest zero, so scenes compare with memcmp */
    memcpy(field, text, n);
    return ATMO_OK;
}

void atmo_scene_defaults(atmo_scene *s)
{
    memset(s, 0, sizeof *s); /* padding too, so scenes compare with memcmp */
    for (const atmo_param *p = atmo_params; p->key; p++) {
        if (is_real(p))
            memcpy(double_field(s, p), p->def, (size_t)atmo_param_components(p) * sizeof(double));
        else if (p->type != ATMO_PARAM_STRING) /* strings: "" from the memset */
            *int_field(s, p) = (int)p->def[0];
    }
}

const char *atmo_preset_closest(const char *name)
{
    atmo_suggest near;
    atmo_suggest_begin(&near, name);
    for (const atmo_preset *p = atmo_presets; p->name; p++)
        atmo_suggest_offer(&near, p->name);
    return atmo_suggest_result(&near);
}

const char *atmo_param_closest(const char *key)
{
    atmo_suggest near;
    atmo_suggest_begin(&near, key);
    for (const atmo_param *p = atmo_params; p->key; p++)
        atmo_suggest_offer(&near, p->key);
    return atmo_suggest_result(&near);
}

static int unknown_key(const char *key, const char *where, atmo_err *e)
{
    const char *near = atmo_param_closest(key);
    if (!near)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "unknown parameter '%s' (from %s); atmo params lists them all", key, where);
    return atmo_fail(
        e, ATMO_ERR_USAGE,
        "unknown parameter '%s' (from %s); did you mean '%s'? (atmo params lists them all)", key,
        where, near);
}

/* "0 .. 180 deg" */
static void range_text(const atmo_param *p, char *buf, size_t n)
{
    snprintf(buf, n, "%.15g .. %.15g%s%s%s", p->min, p->max,
             atmo_param_components(p) > 1 ? " (each)" : "", p->unit[0] ? " " : "", p->unit);
}

static void names_text(const atmo_param *p, char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = '\0';
    for (const char *const *name = p->names; *name && used < n; name++)
        used += (size_t)snprintf(buf + used, n - used, "%s%s", name == p->names ? "" : ", ", *name);
}

int atmo_param_store(atmo_scene *s, const atmo_param *p, const double v[3], const char *shown,
                     const char *where, atmo_err *e)
{
    char range[128];
    int n = atmo_param_components(p);
    if (p->type == ATMO_PARAM_STRING)
        return atmo_fail(e, ATMO_ERR_USAGE, "%s = %s (from %s) must be text, not a number",
                         p->key, shown, where);
    for (int i = 0; i < n; i++) {
        if (!isfinite(v[i]))
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "%s = %s (from %s) is not a finite number; give a value in %s", p->key,
                             shown, where, (range_text(p, range, sizeof range), range));
        if (p->type == ATMO_PARAM_ENUM) {
            char names[256];
            names_text(p, names, sizeof names);
            const char *near = atmo_suggest_among(shown, p->names);
            if (v[i] != floor(v[i]) || v[i] < p->min || v[i] > p->max)
                return atmo_fail(e, ATMO_ERR_USAGE,
                                 "%s = %s (from %s) is not a valid name; %s%s%suse one of: %s",
                                 p->key, shown, where, near ? "did you mean '" : "",
                                 near ? near : "", near ? "'? " : "", names);
            continue;
        }
        if (v[i] < p->min || v[i] > p->max) {
            range_text(p, range, sizeof range);
            if (p->type == ATMO_PARAM_BOOL)
                return atmo_fail(e, ATMO_ERR_USAGE,
                                 "%s = %s (from %s) is not a boolean; use true or false", p->key,
                                 shown, where);
            return atmo_fail(e, ATMO_ERR_USAGE, "%s = %s (from %s) is out of range; valid: %s",
                             p->key, shown, where, range);
        }
        if ((p->type == ATMO_PARAM_INT || p->type == ATMO_PARAM_BOOL) && v[i] != floor(v[i])) {
            range_text(p, range, sizeof range);
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "%s = %s (from %s) must be a whole number; valid: integers in %s",
                             p->key, shown, where, range);
        }
    }
    if (is_real(p))
        memcpy(double_field(s, p), v, (size_t)n * sizeof(double));
    else
        *int_field(s, p) = (int)v[0];
    return ATMO_OK;
}

/* The whole of text (surrounding blanks aside) as one number; 0 when it is not one. strtod's
 * "nan" and "inf" are accepted here so that the caller reports them as not finite. */
static int parse_number(const char *text, double *out)
{
    char *end;
    errno = 0;
    while (isspace((unsigned char)*text))
        text++;
    if (!*text)
        return 0;
    *out = strtod(text, &end);
    if (end == text)
        return 0;
    while (isspace((unsigned char)*end))
        end++;
    if (*end)
        return 0;
    if (errno == ERANGE && fabs(*out) > 1.0) /* overflow: report as Inf, not as garbage */
        *out = HUGE_VAL;
    return 1;
}

int atmo_parse_decimal(const char *text, double *out)
{
    const char *c = text;
    c += *c == '-';
    /* JSON's number grammar: -?(0|[1-9][0-9]*)(.[0-9]+)?([eE][+-]?[0-9]+)?, so no blanks, '+',
     * hexadecimal, "inf"/"nan" or leading zero (which C and other readers take for octal) */
    if (!isdigit((unsigned char)*c) || (c[0] == '0' && isdigit((unsigned char)c[1])))
        return 0;
    while (isdigit((unsigned char)*c))
        c++;
    if (*c == '.') {
        if (!isdigit((unsigned char)*++c))
            return 0;
        while (isdigit((unsigned char)*c))
            c++;
    }
    if (*c == 'e' || *c == 'E') {
        c++;
        c += *c == '+' || *c == '-';
        if (!isdigit((unsigned char)*c))
            return 0;
        while (isdigit((unsigned char)*c))
            c++;
    }
    if (*c)
        return 0;
    errno = 0;
    *out = strtod(text, NULL);
    if (errno == ERANGE && fabs(*out) > 1.0) /* overflow: report as Inf, not as garbage */
        *out = HUGE_VAL;
    return 1;
}

static int parse_value(const atmo_param *p, const char *value, double v[3])
{
    switch (p->type) {
    case ATMO_PARAM_INT:
        return atmo_parse_decimal(value, &v[0]);
    case ATMO_PARAM_FLOAT:
        return parse_number(value, &v[0]);
    case ATMO_PARAM_VEC2:
    case ATMO_PARAM_VEC3: {
        int want = atmo_param_components(p);
        char buf[256];
        if (strlen(value) >= sizeof buf)
            return 0;
        strcpy(buf, value);
        char *parts[4] = {buf, NULL, NULL, NULL};
        int n = 1;
        for (char *c = buf; *c; c++)
            if (*c == ',') {
                if (n == want)
                    return 0;
                *c = '\0';
                parts[n++] = c + 1;
            }
        if (n != want)
            return 0;
        for (int i = 0; i < want; i++)
            if (!parse_number(parts[i], &v[i]))
                return 0;
        return 1;
    }
    case ATMO_PARAM_ENUM:
        for (int i = 0; p->names[i]; i++)
            if (strcmp(value, p->names[i]) == 0) {
                v[0] = i;
                return 1;
            }
        v[0] = -1; /* reported by atmo_param_store with the list of names */
        return 1;
    case ATMO_PARAM_BOOL:
        if (!strcmp(value, "true") || !strcmp(value, "1") || !strcmp(value, "yes") ||
            !strcmp(value, "on"))
            v[0] = 1;
        else if (!strcmp(value, "false") || !strcmp(value, "0") || !strcmp(value, "no") ||
                 !strcmp(value, "off"))
            v[0] = 0;
        else
            v[0] = -1; /* reported as not a boolean */
        return 1;
    case ATMO_PARAM_STRING: /* stored by atmo_param_store_text */
        return 0;
    }
    return 0;
}

int atmo_scene_set(atmo_scene *s, const char *key, const char *value, const char *where,
                   atmo_err *e)
{
    if (strcmp(key, "objects") == 0)
        return atmo_scene_set_objects(s, value, where, e);
    const atmo_param *p = atmo_param_find(key);
    if (!p)
        return unknown_key(key, where, e);
    if (p->type == ATMO_PARAM_STRING)
        return atmo_param_store_text(s, p, value, where, e);
    double v[3] = {0, 0, 0};
    if (!parse_value(p, value, v)) {
        char range[128], example[96] = "";
        range_text(p, range, sizeof range);
        if (p->type == ATMO_PARAM_VEC3) /* the default is a valid example */
            snprintf(example, sizeof example, ", e.g. %.15g,%.15g,%.15g (the default)",
                     p->def[0], p->def[1], p->def[2]);
        else if (p->type == ATMO_PARAM_VEC2)
            snprintf(example, sizeof example, ", e.g. %.15g,%.15g (the default)", p->def[0],
                     p->def[1]);
        else if (p->type == ATMO_PARAM_INT)
            snprintf(example, sizeof example, ", written as decimal digits, e.g. %.15g",
                     p->def[0]);
        return atmo_fail(e, ATMO_ERR_USAGE, "%s = '%s' (from %s) is not %s; valid: %s%s", p->key,
                         value, where,
                         p->type == ATMO_PARAM_VEC3   ? "three numbers x,y,z"
                         : p->type == ATMO_PARAM_VEC2 ? "two numbers x,z"
                         : p->type == ATMO_PARAM_INT  ? "an integer"
                                                      : "a number",
                         range, example);
    }
    return atmo_param_store(s, p, v, value, where, e);
}

int atmo_scene_assign(atmo_scene *s, const char *assignment, const char *where, atmo_err *e)
{
    const char *eq = strchr(assignment, '=');
    char key[128];
    if (!eq || eq == assignment)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "'%s' (from %s) is not key=value; write e.g. sun.zenith_deg=60",
                         assignment, where);
    size_t n = (size_t)(eq - assignment);
    if (n >= sizeof key)
        return unknown_key(assignment, where, e);
    memcpy(key, assignment, n);
    key[n] = '\0';
    return atmo_scene_set(s, key, eq + 1, where, e);
}

int atmo_scene_apply_preset(atmo_scene *s, const char *name, atmo_err *e)
{
    const atmo_preset *pr = atmo_preset_find(name);
    const char *near = pr ? NULL : atmo_preset_closest(name);
    if (near)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "unknown preset '%s' (did you mean '%s'? atmo presets lists them)", name,
                         near);
    if (!pr) {
        char names[512];
        size_t used = 0;
        names[0] = '\0';
        for (const atmo_preset *q = atmo_presets; q->name && used < sizeof names; q++)
            used += (size_t)snprintf(names + used, sizeof names - used, "%s%s",
                                     q == atmo_presets ? "" : ", ", q->name);
        return atmo_fail(e, ATMO_ERR_USAGE, "unknown preset '%s'; use one of: %s", name, names);
    }
    char where[96];
    snprintf(where, sizeof where, "preset %s", pr->name);
    for (const char *const *a = pr->settings; *a; a++) {
        int rc = atmo_scene_assign(s, *a, where, e);
        if (rc)
            return rc;
    }
    return ATMO_OK;
}

int atmo_scene_check_spectral_bands(int bands, atmo_err *e)
{
    if (bands == 0 || (bands >= ATMO_SPECTRAL_MIN_BANDS && bands <= ATMO_SPECTRAL_MAX_BANDS))
        return ATMO_OK;
    return atmo_fail(e, ATMO_ERR_USAGE,
                     "render.spectral_bands=%d: use 0 (3-wavelength mode) or %d to %d bands "
                     "over 360-830 nm",
                     bands, ATMO_SPECTRAL_MIN_BANDS, ATMO_SPECTRAL_MAX_BANDS);
}

int atmo_scene_validate(const atmo_scene *s, atmo_err *e)
{
    /* every value again, for scenes filled in by code rather than through atmo_scene_set */
    atmo_scene copy = *s;
    for (const atmo_param *p = atmo_params; p->key; p++) {
        double v[3];
        char shown[96];
        atmo_param_get(s, p, v);
        if (p->type == ATMO_PARAM_VEC3)
            snprintf(shown, sizeof shown, "%.9g,%.9g,%.9g", v[0], v[1], v[2]);
        else if (p->type == ATMO_PARAM_VEC2)
            snprintf(shown, sizeof shown, "%.9g,%.9g", v[0], v[1]);
        else
            snprintf(shown, sizeof shown, "%.9g", v[0]);
        const char *text = atmo_param_text(s, p);
        /* a string filled in by code may lack its terminator: check it within the field */
        if (text && !memchr(text, '\0', ATMO_PARAM_STRING_MAX))
            return atmo_fail(e, ATMO_ERR_USAGE, "%s is not terminated within %d bytes", p->key,
                             ATMO_PARAM_STRING_MAX);
        int rc = text ? atmo_param_store_text(&copy, p, text, "the scene", e)
                      : atmo_param_store(&copy, p, v, shown, "the scene", e);
        if (rc)
            return rc;
    }
    int rc = atmo_scene_check_spectral_bands(s->render.spectral_bands, e);
    if (rc || (rc = atmo_scene_check_objects(s, e)))
        return rc;
    double bottom = s->atmosphere.bottom_radius_m, top = s->atmosphere.top_radius_m;
    double oz_bottom = s->atmosphere.ozone_bottom_m, oz_peak = s->atmosphere.ozone_peak_m,
           oz_top = s->atmosphere.ozone_top_m;
    if (!(top > bottom))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "atmosphere.top_radius_m (%.9g m) must be greater than "
                         "atmosphere.bottom_radius_m (%.9g m); raise the top or lower the bottom",
                         top, bottom);
    if (!(oz_bottom <= oz_peak && oz_peak <= oz_top && oz_bottom < oz_top))
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "ozone layer out of order: atmosphere.ozone_bottom_m (%.9g m) <= "
                         "atmosphere.ozone_peak_m (%.9g m) <= atmosphere.ozone_top_m (%.9g m) with "
                         "bottom < top is required; reorder the three altitudes",
                         oz_bottom, oz_peak, oz_top);
    if (s->dem.detail && !s->dem.file[0])
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "terrain.heightmap_detail=true adds detail below a heightmap file's "
                         "cells; set terrain.heightmap_file or the detail to false");
    const double *c = s->camera.position_m;
    if (s->camera.on_terrain != ATMO_CAMERA_TERRAIN_OFF) {
        if (!s->terrain.enabled && !s->dem.file[0])
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "camera.on_terrain=%s measures the camera's height from the "
                             "terrain; set terrain.enabled=true or camera.on_terrain=off",
                             camera_terrain_modes[s->camera.on_terrain]);
        if (c[1] < 0.0)
            return atmo_fail(e, ATMO_ERR_USAGE,
                             "camera.position_m's y (%.9g m) is below the terrain's surface "
                             "with camera.on_terrain=%s; use y >= 0 (metres above it)",
                             c[1], camera_terrain_modes[s->camera.on_terrain]);
        return ATMO_OK; /* above the terrain, which lies at or above sea level */
    }
    double dy = c[1] + bottom;
    double r = sqrt(c[0] * c[0] + dy * dy + c[2] * c[2]);
    /* 1 m of slack: a camera placed at sea level must not fail on rounding */
    if (r < bottom - 1.0)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "camera.position_m (%.9g, %.9g, %.9g) is %.6g m below the ground of "
                         "radius atmosphere.bottom_radius_m = %.9g m around (0, -R, 0); raise the "
                         "camera's y",
                         c[0], c[1], c[2], bottom - r, bottom);
    return ATMO_OK;
}
