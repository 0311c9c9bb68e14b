/* plan_march.c — method "march": the Psi_ms LUT (buffer a) and the per-pixel march
 * (atmo/plan_march.h). The LUT is small (10 planes of 64 x 32, three passes) and cheap, so it
 * is rebuilt per frame rather than cached. */
#include <stdio.h>
#include <string.h>
#include "atmo/plan_march.h"

int atmo_plan_ms_lut(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    static const char *const fragments[] = {"kernels/sky_single.h", "kernels/ms_lut.h",
                                            "kernels/ms_lut.cl"};
    int rc = atmo_plan_add_fragments(p, fragments, 3, e);
    if (rc)
        return rc;
    /* sky_single.h's integrator compiles the multiple-scattering terms in */
    size_t used = strlen(p->defines);
    snprintf(p->defines + used, sizeof p->defines - used, "%s-DATMO_MS_LUT", used ? " " : "");
    p->gpu.lut_dims[0][0] = ATMO_MS_LUT_WIDTH;
    p->gpu.lut_dims[0][1] = ATMO_MS_LUT_HEIGHT;
    p->gpu.method_int[0] = ATMO_MS_DIRECTIONS_MU;
    p->gpu.method_int[1] = ATMO_MS_DIRECTIONS_PHI;
    p->gpu.method_int[2] = ATMO_MS_STEPS;
    p->gpu.method_float[0] = ATMO_MS_HIGHER_ANISOTROPY;
    p->lut_bytes[1] = 10 * sizeof(float4) * ATMO_MS_LUT_WIDTH * ATMO_MS_LUT_HEIGHT;
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
    static const char *const fragments[] = {"kernels/method_march.h"};
    int rc = atmo_plan_ms_lut(s, p, e);
    return rc ? rc : atmo_plan_add_fragments(p, fragments, 1, e);
}
