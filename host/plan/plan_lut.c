/* plan_lut.c — atmosphere method "lut" (atmo/plan_lut.h): buffer sizes, knobs and passes; the
 * layout of the buffers is in kernels/atmosphere/lut_scattering.h, the passes in kernels/atmosphere/lut_precompute.cl. */
#include <stdio.h>
#include <string.h>
#include "atmo/plan_lut.h"
#include "atmosphere/lut_scattering.h"

int atmo_plan_lut(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
    static const char *const fragments[] = {"kernels/atmosphere/lut_scattering.h",
                                            "kernels/atmosphere/method_lut.h",
                                            "kernels/atmosphere/lut_precompute.cl"};
    int rc;
    int n_nu = s->atmosphere.lut_nu_size, n_mu_s = s->atmosphere.lut_mu_s_size;
    int n_mu = s->atmosphere.lut_mu_size, n_r = s->atmosphere.lut_r_size;
    int rings = s->atmosphere.lut_sphere_samples, orders = s->atmosphere.lut_orders;
    if (n_mu % 2)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "lut.mu_size=%d must be even (half ground rays, half sky rays)", n_mu);
    if (rings % 2)
        return atmo_fail(e, ATMO_ERR_USAGE,
                         "lut.sphere_samples=%d must be even (no ring on the horizon)", rings);
    if (2 + 4 * (orders - 1) > ATMO_PLAN_MAX_PASSES - p->pass_count)
        return atmo_fail(e, ATMO_ERR_USAGE, "lut.orders=%d is too many passes; use at most %d",
                         orders, (ATMO_PLAN_MAX_PASSES - p->pass_count - 2) / 4 + 1);
    if ((rc = atmo_plan_add_fragments(p, fragments, 3, e)))
        return rc;
    size_t used = strlen(p->defines); /* the medium integrator's march takes the density of orders >= 2 */
    snprintf(p->defines + used, sizeof p->defines - used, "%s-DATMO_LUT_J", used ? " " : "");
    int *dims = p->gpu.lut_dims[0];
    dims[0] = n_nu, dims[1] = n_mu_s, dims[2] = n_mu, dims[3] = n_r;
    p->gpu.method_int[LUT_INT_STEPS] = s->atmosphere.lut_steps;
    p->gpu.method_int[LUT_INT_RINGS] = rings;
    p->gpu.method_int[LUT_INT_ORDERS] = orders;
    size_t N = (size_t)LUT_TEXELS(dims), I = (size_t)LUT_IRRADIANCE_TEXELS(dims);
    size_t G = (size_t)rings * (size_t)rings;
    p->lut_bytes[1] = sizeof(float4) * 2 * N;
    p->lut_bytes[2] = sizeof(float4) * (2 * N + I);
    p->lut_bytes[3] = sizeof(float4) * (2 * N + I * G + I + G);

    int w = n_nu * n_mu_s;
    if ((rc = atmo_plan_add_pass(p, "lut_single", w, n_mu, n_r, 1, e)))
        return rc;
    for (int n = 2; n <= orders; n++)
        if ((rc = atmo_plan_add_pass(p, "lut_grid", (int)G, n_mu_s, n_r, n - 1, e)) ||
            (rc = atmo_plan_add_pass(p, "lut_irradiance", n_mu_s, n_r, 1, n - 1, e)) ||
            (rc = atmo_plan_add_pass(p, "lut_density", w, n_mu, n_r, n, e)) ||
            (rc = atmo_plan_add_pass(p, "lut_multiple", w, n_mu, n_r, n, e)))
            return rc;
    return ATMO_OK;
}
