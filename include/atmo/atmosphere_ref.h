/* atmosphere_ref.h — the double-precision host reference of the atmosphere: the oracle that the
 * kernels are tested against (transmittance, single scattering, directly lit ground).
 *
 * Geometry follows Bruneton 2017: a point at radius r (m from the planet centre) and a ray of
 * direction cosine mu to the local vertical; at distance t along it
 *     r_t = sqrt(t^2 + 2 r mu t + r^2),   mu_s,t = (r mu_s + t nu) / r_t
 * with mu_s the sun's cosine at the start and nu the cosine between the ray and the sun. A ray
 * starts where it enters the atmosphere (at the camera, or at the top for a camera in space) and
 * ends at the ground if it hits it, else at the top. The sun is a point of irradiance E (the
 * model's solar irradiance); the planet's shadow is the cylinder behind it.
 *
 * Every integral uses adaptive Gauss-Kronrod (7/15) quadrature, split at the altitudes where the
 * ozone tent has kinks and, for single scattering, at the edges of the planet's shadow, refined
 * until |K15 - G7| (a pessimistic bound on the K15 error) sums to below the relative tolerance
 * in every component: 1e-11 for optical depths, 1e-9 for single scattering. */
#ifndef ATMO_ATMOSPHERE_REF_H
#define ATMO_ATMOSPHERE_REF_H
#include "atmo/atmosphere.h"

#define ATMO_REF_PI 3.14159265358979323846

/* ---- geometry (radii and distances in metres) ---- */
/* Distance from radius r along mu to where the ray leaves the sphere of radius `top` (from
 * above it: its far side; 0 when the ray never is inside). */
double atmo_ref_distance_to_top(double r, double mu, double top);
/* Distance to the sphere of radius `bottom` along mu; valid where the ray hits it. */
double atmo_ref_distance_to_bottom(double r, double mu, double bottom);
/* 1 if the ray from r along mu hits the sphere of radius `bottom` (grazing counts as a hit,
 * horizontal at the ground does not). */
int atmo_ref_ray_hits_ground(double r, double mu, double bottom);
/* r_t and mu_s,t at distance t along the ray. */
double atmo_ref_radius_at(double r, double mu, double t);
double atmo_ref_mu_s_at(double r, double mu, double mu_s, double nu, double t);

/* ---- phase functions (per steradian) ---- */
double atmo_ref_phase_rayleigh(double nu);
double atmo_ref_phase_mie(const atmo_atmosphere *a, double nu);

/* ---- transmittance ---- */
/* Column integrals along the whole ray (m): out[0] = int e^{-h/H_R} dt, out[1] = int e^{-h/H_M}
 * dt, out[2] = int tent(h) dt. Airmass = column / vertical column. */
void atmo_ref_columns(const atmo_atmosphere *a, double r, double mu, double out[3]);
/* Optical depth (Rayleigh + Mie extinction + ozone) along the whole ray, per wavelength. */
void atmo_ref_optical_depth(const atmo_atmosphere *a, double r, double mu, double out_tau[3]);
/* Optical depth from the ray's start to distance d along it (clamped to the ray's end). */
void atmo_ref_optical_depth_to(const atmo_atmosphere *a, double r, double mu, double d,
                               double out_tau[3]);
/* exp(-optical depth) along the whole ray. */
void atmo_ref_transmittance(const atmo_atmosphere *a, double r, double mu, double out_T[3]);
/* Transmittance to the sun from radius r with sun cosine mu_s: 0 when the planet hides it. */
void atmo_ref_sun_transmittance(const atmo_atmosphere *a, double r, double mu_s, double out_T[3]);
/* Direct irradiance of the point sun on a horizontal surface at radius r,
 * E · T_sun · max(mu_s, 0), W m^-2 nm^-1. */
void atmo_ref_direct_irradiance(const atmo_atmosphere *a, double r, double mu_s, double out_E[3]);

/* ---- radiance (W m^-2 sr^-1 nm^-1) ---- */
/* Single scattering of the point sun along the view ray (sun disc and ground excluded):
 *   L = int_0^d T(0, t) [sigma_R(t) p_R(nu) + sigma_M,s(t) p_M(nu)] E T_sun(t) dt,
 * returned as its Rayleigh and Mie parts (phase included); either pointer may be NULL. */
void atmo_ref_single_scattering_parts(const atmo_atmosphere *a, double r, double mu, double mu_s,
                                      double nu, double out_rayleigh[3], double out_mie[3]);
/* Their sum. */
void atmo_ref_single_scattering(const atmo_atmosphere *a, double r, double mu, double mu_s,
                                double nu, double out_L[3]);
/* The same over the segment [0, d] of the ray (d in metres from the camera, which may be above
 * the atmosphere): aerial perspective toward a black surface at d. */
void atmo_ref_single_scattering_to(const atmo_atmosphere *a, double r, double mu, double mu_s,
                                   double nu, double d, double out_L[3]);
/* A view ray that hits the ground: the Lambertian ground lit by the direct sun only,
 * T(0, d) (rho / pi) E T_sun(ground) max(mu_s,ground, 0); zero if the ray misses the ground. */
void atmo_ref_ground_radiance(const atmo_atmosphere *a, double r, double mu, double mu_s,
                              double nu, double out_L[3]);

#endif
