/* plan_march.h — plan of the multiple-scattering transfer LUT that methods "march" and "fast"
 * share (kernels/atmosphere/ms_lut.h). */
#ifndef ATMO_PLAN_MARCH_H
#define ATMO_PLAN_MARCH_H
#include "atmo/plan.h"

/* Psi_ms LUT size (mu_s x altitude) and its quadrature (atmo_gpu_ms_lut, ms_lut.cl). */
#define ATMO_MS_LUT_WIDTH 64
#define ATMO_MS_LUT_HEIGHT 32
#define ATMO_MS_DIRECTIONS_MU 16
#define ATMO_MS_DIRECTIONS_PHI 8
#define ATMO_MS_STEPS 20
/* planes of w x h texels in the buffer ms_lut (ms_lut.cl) */
#define ATMO_MS_LUT_PLANES 14
/* share of the order-3 anisotropy given to orders >= 4 (ms_lut.h) */
#define ATMO_MS_HIGHER_ANISOTROPY 1.0f

/* The Psi_ms LUT (feature "ms_lut" of host/features/): gpu.ms, the buffer ms_lut and its passes. */
int atmo_plan_ms_lut(const atmo_scene *s, atmo_plan *p, atmo_err *e);

#endif
