/* testclouds.h — the host-built cloud marcher's test scene (tests/support_clouds.c): an
 * overcast deck of the thesis' cloud numbers for the tests that run cloud_march.h on the host
 * (test_clouds_march, test_clouds_thesis). */
#ifndef ATMO_TESTCLOUDS_H
#define ATMO_TESTCLOUDS_H
#include "atmo/gpu_types.h"

/* *s zeroed, then: the atmosphere's radii and scale heights with no scattering coefficient
 * (the atmosphere off), the sun's irradiance 1 in every channel, 45 degrees above the horizon,
 * transmittance tables of 4 x 4 texels, the camera 500 m above the ground; the fBm layer of
 * the thesis' extinction, albedo and noise frequencies with HG g = 0.85, 1-3 km with 500 m
 * fades, coverage 1, density 0.4 (its majorant too), a light march over 1000 km, one octave
 * of multiple scattering (single scattering only), the physical look. */
void test_overcast_scene(atmo_gpu_scene *s);

#endif
