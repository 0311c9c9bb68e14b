/* plan_lut.c — atmosphere method "lut" (atmo/plan_lut.h): its knobs (atmo_gpu_lut), buffers and
 * passes; the layout of the buffers is in kernels/atmosphere/lut_scattering.h, the passes in
 * kernels/atmosphere/lut_precompute.cl. */
#include "atmo/plan_lut.h"
#include "atmosphere/lut_scattering.h"

int atmo_plan_lut(const atmo_scene *s, atmo_plan *p, atmo_err *e)
{
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
    int *dims = p->gpu.lut.dims;
    dims[0] = n_nu, dims[1] = n_mu_s, dims[2] = n_mu, dims[3] = n_r;
    p->gpu.lut.steps = s->atmosphere.lut_steps;
    p->gpu.lut.rings = rings;
    p->gpu.lut.orders = orders;
    size_t N = (size_t)LUT_TEXELS(dims), I = (size_t)LUT_IRRADIANCE_TEXELS(dims);
    size_t G = (size_t)rings * (size_t)rings;
    if ((rc = atmo_plan_add_buffer(p, "scattering_rayleigh", "float4", sizeof(float4) * 2 * N, 0,
                                   NULL, e)) ||
        (rc = atmo_plan_add_buffer(p, "scattering_mie", "float4", sizeof(float4) * (2 * N + I),
                                   0, NULL, e)) ||
        (rc = atmo_plan_add_buffer(p, "scattering_scratch", "float4",
                                   sizeof(float4) * (2 * N + I * G + I + G), 0, NULL, e)))
        return rc;

    int w = n_nu * n_mu_s;
    /* lut_single and lut_multiple: one work item per ray (mu, r) for all its nu x mu_s texels */
    if ((rc = atmo_plan_add_pass(p, "lut_single", n_mu, n_r, 1, 1, e)))
        return rc;
    for (int n = 2; n <= orders; n++)
        if ((rc = atmo_plan_add_pass(p, "lut_grid", (int)G, n_mu_s, n_r, n - 1, e)) ||
            (rc = atmo_plan_add_pass(p, "lut_irradiance", n_mu_s, n_r, 1, n - 1, e)) ||
            (rc = atmo_plan_add_pass(p, "lut_density", w, n_mu, n_r, n, e)) ||
            (rc = atmo_plan_add_pass(p, "lut_multiple", n_mu, n_r, 1, n, e)))
            return rc;
    return ATMO_OK;
}
