/* clouds_params.c — the scene parameters of the fBm cloud layer (clouds.*: its shape, optics,
 * marcher, shadow map, octaves): rows of the scene's parameter registry (atmo/scene_params.h),
 * registered from this folder. */
#include "atmo/scene_params.h"

static const char *const cloud_phase_names[] = {"mie", "hg", "jendersie-deon", NULL};
static const char *const clouds_look_names[] = {"physical", "thesis", NULL};

static const atmo_param rows[] = {
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
    ROW_INT("clouds.ms_octaves", clouds.ms_octaves, "", 1, 16, 2,
            "multiple-scattering octaves of the marcher (1: single scattering and the diffuse "
            "orders only; 2 fitted to the reference by atmo bench clouds --fit)"),
    ROW_FLOAT("clouds.ms_a", clouds.ms_a, "", 0, 1, 0.2,
              "per octave: factor on the optical depth toward the sun (fitted: 0.2)"),
    ROW_FLOAT("clouds.ms_b", clouds.ms_b, "", 0, 1, 0.99,
              "per octave: factor on the contribution (fitted: 0.99)"),
    ROW_FLOAT("clouds.ms_c", clouds.ms_c, "", 0, 1, 0.7,
              "per octave: factor on the phase function's anisotropy (fitted: 0.7)"),
    ROW_FLOAT("clouds.ms_d", clouds.ms_d, "", 0, 100, 6.81,
              "weight of the diffuse orders beyond the octaves: isotropic light times this and "
              "the similarity albedo of a semi-infinite cloud, decaying into it at the diffusion "
              "exponent (kernels/clouds/cloud_march.h; 0: none; fitted: 6.81)"),
    ROW_ENUM("clouds.look", clouds.look, clouds_look_names, ATMO_CLOUDS_LOOK_PHYSICAL,
             "physical (octaves, sky ambient) or thesis (constant ambient, powder, soft clamp)"),
};
ATMO_PARAM_SET(clouds, rows);
