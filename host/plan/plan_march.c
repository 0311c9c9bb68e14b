/* plan_march.c — method "march": the Psi_ms LUT (buffer a) and the per-pixel march
 * (atmo/plan_march.h). The LUT is small (14 planes of 64 x 32, three passes) and cheap, so it
 * is rebuilt per frame rather than cached. */
#include <math.h>
#include <stdio.h>
#include <string.h>
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

int atmo_plan_ms_lut(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    static const char *const fragments[] = {"kernels/atmosphere/ms_lut.h",
                                            "kernels/atmosphere/ms_lut.cl"};
    int rc = atmo_plan_add_fragments(p, fragments, 2, e);
    if (rc)
        return rc;
    /* the medium integrator (kernels/media/medium.h) compiles the Psi_ms source in */
    size_t used = strlen(p->defines);
    snprintf(p->defines + used, sizeof p->defines - used, "%s-DATMO_MS_LUT", used ? " " : "");
    p->gpu.lut_dims[0][0] = ATMO_MS_LUT_WIDTH;
    p->gpu.lut_dims[0][1] = ATMO_MS_LUT_HEIGHT;
    p->gpu.method_int[0] = ATMO_MS_DIRECTIONS_MU;
    p->gpu.method_int[1] = ATMO_MS_DIRECTIONS_PHI;
    p->gpu.method_int[2] = ATMO_MS_STEPS;
    p->gpu.method_float[0] = ATMO_MS_HIGHER_ANISOTROPY;
    mie_legendre(&p->gpu.atmosphere, &p->gpu.method_float[1], &p->gpu.method_float[2]);
    p->lut_bytes[1] = ATMO_MS_LUT_PLANES * sizeof(float4) * ATMO_MS_LUT_WIDTH * ATMO_MS_LUT_HEIGHT;
    rc = atmo_plan_add_pass(p, "ms_lut", ATMO_MS_LUT_WIDTH, ATMO_MS_LUT_HEIGHT, 1, 0, e);
    if (!rc)
        rc = atmo_plan_add_pass(p, "ms_lut_order3", ATMO_MS_LUT_WIDTH, ATMO_MS_LUT_HEIGHT, 1, 0,
                                e);
    return rc ? rc
              : atmo_plan_add_pass(p, "ms_lut_second", ATMO_MS_LUT_WIDTH, ATMO_MS_LUT_HEIGHT, 1,
                                   0, e);
}

int atmo_plan_march(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    static const char *const fragments[] = {"kernels/atmosphere/method_march.h"};
    int rc = atmo_plan_ms_lut(s, p, e);
    return rc ? rc : atmo_plan_add_fragments(p, fragments, 1, e);
}
