/* atmosphere_params.c — the scene parameters of the air (atmosphere.*: the planet, Rayleigh,
 * aerosols, ozone, the ground, the method) and the methods' knobs (lut.*, reference.*): rows of
 * the scene's parameter registry (atmo/scene_params.h), registered from this folder. */
#include "atmo/scene_params.h"

static const char *const phase_names[] = {"cornette-shanks", "henyey-greenstein", NULL};
static const char *const method_names[] = {"single", "march", "fast", "lut", "reference", "auto",
                                           NULL};
_Static_assert(ATMO_PHASE_HENYEY_GREENSTEIN == 1 && ATMO_METHOD_REFERENCE == 4 &&
                   ATMO_METHOD_AUTO == 5,
               "enum name tables follow the order of the constants");

static const atmo_param rows[] = {
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
};
ATMO_PARAM_SET(atmosphere, rows);
