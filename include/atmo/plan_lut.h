/* plan_lut.h — the plan of atmosphere method "lut" (precomputed 4-D scattering LUTs with all
 * orders; kernels/atmosphere/method_lut.h). */
#ifndef ATMO_PLAN_LUT_H
#define ATMO_PLAN_LUT_H
#include "atmo/plan.h"

/* Fills gpu.lut, sizes its three buffers (scattering_rayleigh, scattering_mie,
 * scattering_scratch) from the lut.* scene keys and lists
 * its precompute passes: single scattering, then per order 2..lut.orders the sphere grid, the
 * irradiance, the scattering density and the scattering. */
int atmo_plan_lut(const atmo_scene *s, atmo_plan *p, atmo_err *e);

#endif
