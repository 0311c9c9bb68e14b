/* cloud_shell_params.c — the scene parameters of the homogeneous cloud/fog shell (cloud.*) and
 * the observer (observer.*): rows of the scene's parameter registry (atmo/scene_params.h),
 * registered from this folder. */
#include "atmo/scene_params.h"

/* the size-distribution presets of mie_dsd_preset (host/mie/mie_dsd.c), in its order */
static const char *const cloud_dsd_names[] = {"cumulus", "stratus", "fog", "corona",
                                              "thesis-disperse", "thesis-uniform", NULL};
static const char *const cloud_phase_names[] = {"mie", "hg", "jendersie-deon", NULL};

static const atmo_param rows[] = {
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
    ROW_BOOL("observer.enabled", observer.enabled, 0,
             "an observer sphere that casts a shadow on the cloud (Brocken spectre)"),
    ROW_FLOAT("observer.distance_m", observer.distance_m, "m", 0, 1e4, 5,
              "observer's centre: horizontal distance ahead of the camera toward the antisolar "
              "point (it stays in the vertical plane through the sun)"),
    ROW_FLOAT("observer.height_m", observer.height_m, "m", -1e4, 1e4, -1,
              "observer's centre: height relative to the camera"),
    ROW_FLOAT("observer.radius_m", observer.radius_m, "m", 0.01, 1e3, 1,
              "observer sphere's radius"),
};
ATMO_PARAM_SET(cloud_shell, rows);
