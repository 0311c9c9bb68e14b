/* plan_march.c — the Psi_ms LUT of methods "march" and "fast" (atmo/plan_march.h): its knobs
 * (atmo_gpu_ms_lut), its buffer ms_lut (14 planes of 64 x 32) and its three passes. */
#include <math.h>
#include "atmo/plan_march.h"
#include "common/phase.h"

/* Legendre coefficients g_l = 2 pi int_{-1}^{1} p_M(x) P_l(x) dx, l = 1, 2, of the aerosol phase
 * function (ms_lut.h's Mie anisotropy: p_M convolves the l-th harmonic of the light field by
 * g_l), in double by the midpoint rule in the scattering angle, dx = sin(theta) d theta, on
 * 20000 intervals: the forward peak (width ~ 1 - g rad) spans hundreds of them. */
static void mie_legendre(const atmo_gpu_atmosphere *a, float *g1, float *g2)
{
    const int n = 20000;
    double s1 = 0.0, s2 = 0.0;
    for (int i = 0; i < n; i++) {
        double theta = M_PI * (i + 0.5) / n, x = cos(theta);
        double p = a->mie_phase == ATMO_PHASE_HENYEY_GREENSTEIN
                       ? phase_henyey_greenstein((float)x, a->mie_g)
                       : phase_cornette_shanks((float)x, a->mie_g);
        double w = 2.0 * M_PI * p * sin(theta) * M_PI / n;
        s1 += w * x;
        s2 += w * 0.5 * (3.0 * x * x - 1.0);
    }
    *g1 = (float)s1;
    *g2 = (float)s2;
}

_Static_assert(ATMO_MS_DIRECTIONS_PHI <= ATMO_MS_MAX_DIRECTIONS_PHI,
               "the Psi_ms passes keep at most ATMO_MS_MAX_DIRECTIONS_PHI azimuths");

int atmo_plan_ms_lut(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    (void)s;
    atmo_gpu_ms_lut *ms = &p->gpu.ms;
    ms->width = ATMO_MS_LUT_WIDTH;
    ms->height = ATMO_MS_LUT_HEIGHT;
    ms->directions_mu = ATMO_MS_DIRECTIONS_MU;
    ms->directions_phi = ATMO_MS_DIRECTIONS_PHI;
    ms->steps = ATMO_MS_STEPS;
    ms->higher_anisotropy = ATMO_MS_HIGHER_ANISOTROPY;
    mie_legendre(&p->gpu.atmosphere, &ms->g1, &ms->g2);
    int rc = atmo_plan_add_buffer(p, "ms_lut", "float4",
                                  ATMO_MS_LUT_PLANES * sizeof(float4) * ATMO_MS_LUT_WIDTH *
                                      ATMO_MS_LUT_HEIGHT,
                                  0, NULL, e);
    if (!rc)
        rc = atmo_plan_add_pass(p, "ms_lut", ATMO_MS_LUT_WIDTH, ATMO_MS_LUT_HEIGHT, 1, 0, e);
    if (!rc)
        rc = atmo_plan_add_pass(p, "ms_lut_order3", ATMO_MS_LUT_WIDTH, ATMO_MS_LUT_HEIGHT, 1, 0,
                                e);
    return rc ? rc
              : atmo_plan_add_pass(p, "ms_lut_second", ATMO_MS_LUT_WIDTH, ATMO_MS_LUT_HEIGHT, 1,
                                   0, e);
}
