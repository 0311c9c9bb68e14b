/* path_params.c — the scene parameters of the path tracer (path.*; the scene's render.mode
 * switches it on): rows of the scene's parameter registry (atmo/scene_params.h), registered
 * from this folder. */
#include "atmo/scene_params.h"

static const char *const path_skies[] = {"atmosphere", "uniform", NULL};
static const char *const path_clouds_names[] = {"march", "volume", NULL};
static const char *const path_air_names[] = {"method", "medium", NULL};
static const char *const sampler_names[] = {"sobol", "random", NULL};
_Static_assert(ATMO_PATH_SKY_UNIFORM == 1 && ATMO_SAMPLER_RANDOM == 1 &&
                   ATMO_PATH_CLOUDS_VOLUME == 1 && ATMO_PATH_AIR_MEDIUM == 1,
               "enum name tables follow the order of the constants");

static const atmo_param rows[] = {
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
};
ATMO_PARAM_SET(path, rows);
