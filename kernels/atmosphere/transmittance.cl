/* transmittance.cl — fills the transmittance LUT (atmosphere.h has its parametrisation).
 *
 * Each texel (i, j) is placed at its centre u = (i + 0.5)/W, v = (j + 0.5)/H, mapped back to
 * (r, mu), and holds the optical depth tau to the top of the atmosphere by the midpoint rule
 * with TRANSMITTANCE_STEPS segments (error ~ 1/n^2). 200 is where the LUT's worst error stops
 * being the quadrature's (tests/test_transmittance.c against the published table and the double
 * quadrature: 9.7e-4 at 100 steps, 8.8e-4 at 200, 8.4e-4 at 500), at 2.5x less cost than 500. */
#define TRANSMITTANCE_STEPS 200

__kernel void transmittance_lut(__global const atmo_gpu_scene *scene, ATMO_LUT_OUT_PARAMS,
                                int arg)
{
    int i = get_global_id(0), j = get_global_id(1);
    int w = scene->transmittance_width, h = scene->transmittance_height;
    if (i >= w || j >= h)
        return;
    float r, mu;
    atmosphere_transmittance_r_mu(&scene->atmosphere, ((float)i + 0.5f) / (float)w,
                                  ((float)j + 0.5f) / (float)h, w, h, &r, &mu);
    vec3 tau = atmosphere_optical_depth_to_top(&scene->atmosphere, r, mu, TRANSMITTANCE_STEPS);
    transmittance_lut[j * w + i] = (float4)(tau, 0.0f);
}
