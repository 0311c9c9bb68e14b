/* lut_precompute.cl — method "lut": the precompute passes that fill the scattering LUTs with all
 * orders of scattering (Bruneton 2017, "Multiple scattering"; parametrisation in
 * lut_scattering.h, buffers and knobs in method_lut.h).
 *
 * Order 1 (lut_single), each texel (r, mu, mu_s, nu) integrated along its ray to the ground or
 * the top:
 *     S_R = E int_0^d T(0,t) beta_R e^{-h/H_R} T_sun(t) dt,  S_M likewise with beta_M,s, H_M,
 * phase functions left out (applied at lookup with the exact nu, so the forward Mie peak is never
 * interpolated). The ray is cut into `steps` equal segments (quadrature_walk.h's
 * quadrature_begin_equal, walked LUT_CHUNK pieces at a time); each takes the mean of each
 * exponential density over the segment (exact where the altitude is linear along it,
 * lut_mean_density) and the sun's transmittance at its midpoint, and is integrated exactly for
 * constant coefficients,
 *     L += T_acc S (1 - e^{-sigma_t dt}) / sigma_t,  T_acc *= e^{-sigma_t dt},
 * so long grazing segments neither overshoot nor lose energy (Bruneton's trapezoidal rule with
 * LUT transmittance ratios overshoots forward Mie by ~6 %, atmosphere.md).
 * Then for each order n = 2..N, with k = n - 1:
 *   lut_grid:       L_k(r, omega_i) on the sphere grid at every (r, mu_s) texel: the order-k
 *                   sky radiance (k = 1: S_R p_R(nu_i) + S_M p_M(nu_i) from the single tables
 *                   with exact phases; k > 1: the delta table), plus for ground-hitting
 *                   directions the ground reflecting the irradiance of order k - 1,
 *                   T(r -> ground) (rho / pi) E_{k-1}(mu_s at the ground point), with
 *                   E_0 = E T_sun max(mu_s, 0) the direct sun;
 *   lut_irradiance: E_k(r, mu_s) = int_{mu_i > 0} L_k mu_i d omega_i (delta irradiance, also
 *                   summed into the total indirect irradiance);
 *   lut_density:    J_n(r, mu, mu_s, nu) = int_{4 pi} [beta_R e^{-h/H_R} p_R(omega.omega_i)
 *                   + beta_M,s e^{-h/H_M} p_M(omega.omega_i)] L_k(omega_i) d omega_i
 *                   (radiance per metre), from the grid, each grid direction with its mirror,
 *                   also summed into the density table of orders >= 2 (aerial perspective);
 *   lut_multiple:   L_n = int_0^d T(0,t) J_n(r_t, mu_t, mu_s_t, nu) dt with the same exponential
 *                   segments (J interpolated in the 4-D density table), written to the delta
 *                   table and summed into the multiple-scattering table.
 * The grid reuses one set of radiance lookups for all (mu, nu) texels of an (r, mu_s) pair;
 * that is what makes many orders affordable on a CPU. */

/* (1 - e^{-sigma dt}) / sigma from e = e^{-sigma dt} (computed once for the transmittance too);
 * a Taylor series where 1 - e would cancel (its error there, x^3 / 24, is below float epsilon). */
float3 lut_weights(float3 sigma, float dt, float3 e)
{
    float3 x = sigma * dt;
    float3 series = dt * (1.0f - x * (0.5f - x / 6.0f));
    return select((1.0f - e) / sigma, series, isless(x, (float3)(1e-2f)));
}

/* Mean of e^{-h/H} over a segment of length dt whose altitude is h at its middle and changes at
 * the rate dh (the cosine mu_t of the ray there): with h linear along the segment the mean is
 * e^{-h/H} sinh(y) / y, y = dh dt / (2 H). The bare midpoint value would be low by y^2 / 6: 2.6 %
 * for the Mie layer (H = 1.2 km) on a 64-segment zenith ray from the ground. The same mean in
 * terms of the ends h -+ a (a = |dh| dt / 2) is H (e^{-(h - a)/H} - e^{-(h + a)/H}) / (2a),
 * written so for long segments (|y| > 20): those of a thick atmosphere (segments of hundreds
 * of km over H = 1.2 km) reach |y| > 89, where sinh overflows float while e^{-h/H} underflows
 * (0 x Inf = NaN), and the straight line through the midpoint can dip below the ground, which
 * a segment above it never does: its lower end is taken at altitude >= 0. */
float lut_mean_density(float h, float dh, float dt, float H)
{
    float y = 0.5f * dh * dt / H, ay = fabs(y);
    if (ay > 20.0f) {
        float lo = fmax(h - ay * H, 0.0f), hi = h + ay * H;
        return H * (exp(-lo / H) - exp(-hi / H)) / (hi - lo);
    }
    if (ay < 0.1f) /* sinh(y) / y by its series (truncation y^6 / 5040 < 2e-10) */
        return exp(-h / H) * (1.0f + y * y / 6.0f * (1.0f + y * y / 20.0f));
    /* (e^{y - h/H} - e^{-y - h/H}) / (2 y): two exps cost less than PoCL's sinh (Sleef),
     * measured ~2.5 exps, and lose at most ~6e-8 / (2 |y|) <= 3e-7 relative to cancellation */
    return (exp(y - h / H) - exp(-y - h / H)) / (2.0f * y);
}

/* Mean extinction over such a segment (the ozone tent is linear in h: its midpoint value). */
float3 lut_mean_extinction(__global const atmo_gpu_atmosphere *a, float h, float dh, float dt)
{
    return a->rayleigh_scattering.xyz * lut_mean_density(h, dh, dt, a->rayleigh_scale_height) +
           a->mie_extinction.xyz * lut_mean_density(h, dh, dt, a->mie_scale_height) +
           a->ozone_absorption.xyz * atmosphere_ozone_tent(a, h);
}

/* This work item's texel of a 4-D table: its index and its (r, mu, mu_s, nu, ground); 0 for
 * the padding items past the table's end. */
int lut_this_texel(__global const atmo_gpu_atmosphere *a, __global const int *dims, int *idx,
                     float *r, float *mu, float *mu_s, float *nu, int *ground)
{
    int x = get_global_id(0), y = get_global_id(1), z = get_global_id(2);
    if (x >= dims[0] * dims[1] || y >= dims[2] || z >= dims[3])
        return 0;
    *idx = (z * dims[2] + y) * dims[0] * dims[1] + x;
    lut_scattering_texel(a, dims, x, y, z, r, mu, mu_s, nu, ground);
    return 1;
}

/* Segments whose media a work item keeps at once (lut_single, lut_multiple): a ray's densities,
 * extinction and weights depend on its (r, mu) only, so one work item per (r, mu) computes them
 * once per segment and reuses them for all n_nu x n_mu_s texels of that ray, which differ only
 * in the sun (its transmittance, the density J's sun cosine). */
#define LUT_CHUNK 16

/* This work item's ray of the 4-D tables: (r, mu, ground) of texels (., y = its mu, z = its r),
 * and the first index of their n_nu x n_mu_s texels; 0 for the padding items. */
int lut_this_ray(__global const atmo_gpu_atmosphere *a, __global const int *dims, int *first,
                 float *r, float *mu, int *ground)
{
    int y = get_global_id(0), z = get_global_id(1);
    if (y >= dims[2] || z >= dims[3])
        return 0;
    *r = lut_r_at(a, (float)z, dims[3]);
    *mu = lut_mu_at(a, *r, (float)y, dims[2], ground);
    *first = (z * dims[2] + y) * dims[0] * dims[1];
    return 1;
}

__kernel void lut_single(__global const atmo_gpu_scene *s, ATMO_LUT_OUT_PARAMS, int arg)
{
    __global const atmo_gpu_atmosphere *a = &s->atmosphere;
    __global const int *dims = s->lut.dims;
    int n_nu = dims[0], n_mu_s = dims[1], first, ground;
    float r, mu;
    if (!lut_this_ray(a, dims, &first, &r, &mu, &ground))
        return;
    int N = LUT_TEXELS(dims), texels = n_nu * n_mu_s;
    int n = s->lut.steps;
    quadrature_walk q = quadrature_begin_equal(atmosphere_ray_length(a, r, mu, ground), n);
    float dt = q.step;
    float3 E = a->solar_irradiance.xyz;
    float3 beta_r = E * a->rayleigh_scattering.xyz, beta_m = E * a->mie_scattering.xyz;
    float3 T = (float3)(1.0f);
    float ts[LUT_CHUNK], rs[LUT_CHUNK];
    float3 lit_r[LUT_CHUNK], lit_m[LUT_CHUNK];
    for (int c0 = 0;; c0 += LUT_CHUNK) {
        int m = 0;
        for (; m < LUT_CHUNK && quadrature_next(&q) != QUADRATURE_END; m++) {
            float t = q.t;
            float r_t = geometry_radius_at(r, mu, t);
            float h = geometry_altitude_at(r, mu, t, a->bottom_radius);
            float mu_t = atmo_clamp_cos((r * mu + t) / r_t);
            float rayleigh = lut_mean_density(h, mu_t, dt, a->rayleigh_scale_height);
            float mie = lut_mean_density(h, mu_t, dt, a->mie_scale_height);
            float3 sigma_t = a->rayleigh_scattering.xyz * rayleigh + a->mie_extinction.xyz * mie +
                             a->ozone_absorption.xyz * atmosphere_ozone_tent(a, h);
            float3 e = exp(-sigma_t * dt);
            float3 tw = T * lut_weights(sigma_t, dt, e);
            ts[m] = t;
            rs[m] = r_t;
            lit_r[m] = tw * rayleigh * beta_r;
            lit_m[m] = tw * mie * beta_m;
            T *= e;
        }
        if (m == 0) /* the walk has ended */
            break;
        for (int x = 0; x < texels; x++) {
            float mu_s = lut_mu_s_at(a, (float)(x % n_mu_s), n_mu_s);
            float nu = lut_nu_at((float)(x / n_mu_s), n_nu, mu, mu_s);
            float3 S_r = (float3)(0.0f), S_m = (float3)(0.0f);
            for (int i = 0; i < m; i++) {
                float mu_s_t = atmo_clamp_cos((r * mu_s + ts[i] * nu) / rs[i]);
                float3 sun = atmosphere_sun_transmittance(a, transmittance_lut,
                                                          s->transmittance_width,
                                                          s->transmittance_height, rs[i], mu_s_t);
                S_r += lit_r[i] * sun;
                S_m += lit_m[i] * sun;
            }
            int idx = first + x;
            if (c0 > 0) {
                S_r += scattering_rayleigh[idx].xyz;
                S_m += scattering_mie[idx].xyz;
            }
            scattering_rayleigh[idx] = (float4)(S_r, 0.0f);
            scattering_mie[idx] = (float4)(S_m, 0.0f);
        }
    }
    for (int x = 0; x < texels; x++) { /* orders >= 2 add to these */
        scattering_rayleigh[N + first + x] = (float4)(0.0f);
        scattering_mie[LUT_DENSITY_SUM(dims) + first + x] = (float4)(0.0f);
    }
    /* once per r: clear the total indirect irradiance of its (r, mu_s) cells */
    if (get_global_id(0) == 0)
        for (int x = 0; x < n_mu_s; x++)
            scattering_mie[N + get_global_id(1) * n_mu_s + x] = (float4)(0.0f);
}

__kernel void lut_grid(__global const atmo_gpu_scene *s, ATMO_LUT_OUT_PARAMS, int k)
{
    __global const atmo_gpu_atmosphere *a = &s->atmosphere;
    __global const int *dims = s->lut.dims;
    int rings = s->lut.rings, G = rings * rings;
    int g = get_global_id(0), i_mu_s = get_global_id(1), i_r = get_global_id(2);
    if (g >= G || i_mu_s >= dims[1] || i_r >= dims[3])
        return;
    int N = LUT_TEXELS(dims);
    float r = lut_r_at(a, (float)i_r, dims[3]), mu_s = lut_mu_s_at(a, (float)i_mu_s, dims[1]);
    float domega;
    float3 dir = lut_grid_direction(g, rings, &domega);
    float mu = dir.z, nu = atmo_clamp_cos(dot(dir, lut_grid_sun(mu_s)));
    int ground = geometry_ray_hits_ground(r, mu, a->bottom_radius);
    float3 L;
    if (k == 1)
        L = lut_scattering_lookup(a, scattering_rayleigh, dims, r, mu, mu_s, nu, ground) * phase_rayleigh(nu) +
            lut_scattering_lookup(a, scattering_mie, dims, r, mu, mu_s, nu, ground) *
                media_mie_phase(a, nu);
    else
        L = lut_scattering_lookup(a, scattering_scratch, dims, r, mu, mu_s, nu, ground);
    if (ground) {
        float d = geometry_distance_to_bottom(r, mu, a->bottom_radius);
        float mu_s_g = atmo_clamp_cos((r * mu_s + d * nu) / a->bottom_radius);
        float3 E;
        if (k == 1)
            E = a->solar_irradiance.xyz * fmax(mu_s_g, 0.0f) *
                atmosphere_sun_transmittance(a, transmittance_lut, s->transmittance_width,
                                             s->transmittance_height, a->bottom_radius, mu_s_g);
        else
            E = lut_irradiance_lookup(a, scattering_scratch + LUT_DELTA_IRRADIANCE(dims, G), dims,
                                      a->bottom_radius, mu_s_g);
        L += lut_transmittance_to_ground(s, transmittance_lut, r, mu, d) *
             a->ground_albedo.xyz * E / ATMO_PI;
    }
    scattering_scratch[2 * N + (i_r * dims[1] + i_mu_s) * G + g] = (float4)(L, 0.0f);
    if (i_mu_s == 0 && i_r == 0)
        scattering_scratch[LUT_DIRECTIONS(dims, G) + g] = (float4)(dir, domega);
}

__kernel void lut_irradiance(__global const atmo_gpu_scene *s, ATMO_LUT_OUT_PARAMS, int k)
{
    __global const int *dims = s->lut.dims;
    int rings = s->lut.rings, G = rings * rings;
    int i_mu_s = get_global_id(0), i_r = get_global_id(1);
    if (i_mu_s >= dims[1] || i_r >= dims[3])
        return;
    int N = LUT_TEXELS(dims), cell = i_r * dims[1] + i_mu_s;
    __global const float4 *grid = scattering_scratch + 2 * N + cell * G;
    float3 E = (float3)(0.0f);
    __global const float4 *dirs = scattering_scratch + LUT_DIRECTIONS(dims, G);
    for (int g = 0; g < G / 2; g++) /* the upper hemisphere: the first rings/2 rings */
        E += grid[g].xyz * (2.0f * dirs[g].z * dirs[g].w); /* 2: the mirror half */
    scattering_scratch[LUT_DELTA_IRRADIANCE(dims, G) + cell] = (float4)(E, 0.0f);
    scattering_mie[N + cell] += (float4)(E, 0.0f);
}

__kernel void lut_density(__global const atmo_gpu_scene *s, ATMO_LUT_OUT_PARAMS, int n)
{
    __global const atmo_gpu_atmosphere *a = &s->atmosphere;
    __global const int *dims = s->lut.dims;
    int rings = s->lut.rings, G = rings * rings;
    int x = get_global_id(0), z = get_global_id(2), n_mu_s = dims[1], idx, ground;
    float r, mu, mu_s, nu;
    if (!lut_this_texel(a, dims, &idx, &r, &mu, &mu_s, &nu, &ground))
        return;
    int N = LUT_TEXELS(dims);
    /* the view direction in the grid's frame (sun in the x-z plane) */
    float sin_v = atmo_safe_sqrt(1.0f - mu * mu), sin_s = atmo_safe_sqrt(1.0f - mu_s * mu_s);
    float vx = sin_s > 1e-6f ? clamp((nu - mu * mu_s) / sin_s, -sin_v, sin_v) : sin_v;
    float vy = atmo_safe_sqrt(sin_v * sin_v - vx * vx);
    float h = fmax(r - a->bottom_radius, 0.0f);
    float3 beta_r = a->rayleigh_scattering.xyz * exp(-h / a->rayleigh_scale_height);
    float3 beta_m = a->mie_scattering.xyz * exp(-h / a->mie_scale_height);
    __global const float4 *grid = scattering_scratch + 2 * N + (z * n_mu_s + x % n_mu_s) * G;
    float3 J = (float3)(0.0f);
    __global const float4 *dirs = scattering_scratch + LUT_DIRECTIONS(dims, G);
    for (int g = 0; g < G; g++) {
        float4 dir = dirs[g];
        float c1 = vx * dir.x + vy * dir.y + mu * dir.z;
        float c2 = vx * dir.x - vy * dir.y + mu * dir.z; /* the mirror direction */
        float p_r = phase_rayleigh(c1) + phase_rayleigh(c2);
        float p_m = media_mie_phase(a, c1) + media_mie_phase(a, c2);
        J += grid[g].xyz * ((beta_r * p_r + beta_m * p_m) * dir.w);
    }
    scattering_scratch[N + idx] = (float4)(J, 0.0f);
    scattering_mie[LUT_DENSITY_SUM(dims) + idx] += (float4)(J, 0.0f);
}

__kernel void lut_multiple(__global const atmo_gpu_scene *s, ATMO_LUT_OUT_PARAMS, int order)
{
    __global const atmo_gpu_atmosphere *a = &s->atmosphere;
    __global const int *dims = s->lut.dims;
    int n_nu = dims[0], n_mu_s = dims[1], first, ground;
    float r, mu;
    if (!lut_this_ray(a, dims, &first, &r, &mu, &ground))
        return;
    int N = LUT_TEXELS(dims), texels = n_nu * n_mu_s;
    int n = s->lut.steps;
    quadrature_walk q = quadrature_begin_equal(atmosphere_ray_length(a, r, mu, ground), n);
    float dt = q.step;
    __global const float4 *J = scattering_scratch + N;
    float3 T = (float3)(1.0f);
    int n_mu = dims[2], n_r = dims[3], slab = n_nu * n_mu_s;
    float ts[LUT_CHUNK], inv_r[LUT_CHUNK];
    float3 tw[LUT_CHUNK];
    /* the four (r, mu) corners of each segment's quadrilinear lookup in J (lut_scattering_fetch
     * with its sums regrouped): their first index and weight */
    int rows[LUT_CHUNK][4];
    float w_rm[LUT_CHUNK][4];
    for (int c0 = 0;; c0 += LUT_CHUNK) {
        int m = 0;
        for (; m < LUT_CHUNK && quadrature_next(&q) != QUADRATURE_END; m++) {
            float t = q.t;
            float r_t = geometry_radius_at(r, mu, t);
            float h = geometry_altitude_at(r, mu, t, a->bottom_radius);
            float mu_t = atmo_clamp_cos((r * mu + t) / r_t);
            float3 sigma_t = lut_mean_extinction(a, h, mu_t, dt);
            float3 e = exp(-sigma_t * dt);
            ts[m] = t;
            inv_r[m] = 1.0f / r_t;
            float f_mu, f_r;
            int upper = !ground; /* the ray stays on its side of the horizon */
            int i_mu = lut_cell(lut_mu_position(a, r_t, mu_t, ground, n_mu),
                                upper ? n_mu / 2 : 0, upper ? n_mu - 1 : n_mu / 2 - 1, &f_mu);
            int i_r = lut_cell(lut_r_position(a, r_t, n_r), 0, n_r - 1, &f_r);
            for (int c = 0; c < 4; c++) {
                int b_mu = c & 1, b_r = c >> 1;
                rows[m][c] = ((i_r + b_r) * n_mu + i_mu + b_mu) * slab;
                w_rm[m][c] = (b_mu ? f_mu : 1.0f - f_mu) * (b_r ? f_r : 1.0f - f_r);
            }
            tw[m] = T * lut_weights(sigma_t, dt, e);
            T *= e;
        }
        if (m == 0) /* the walk has ended */
            break;
        for (int x = 0; x < texels; x++) {
            float mu_s = lut_mu_s_at(a, (float)(x % n_mu_s), n_mu_s);
            float nu = lut_nu_at((float)(x / n_mu_s), n_nu, mu, mu_s);
            float f_nu, f_mu_s;
            int o_nu = lut_cell(lut_nu_position(nu, n_nu), 0, n_nu - 1, &f_nu) * n_mu_s;
            float3 L = (float3)(0.0f);
            for (int i = 0; i < m; i++) {
                float mu_s_t = atmo_clamp_cos((r * mu_s + ts[i] * nu) * inv_r[i]);
                int i_mu_s = lut_cell(lut_mu_s_position(a, mu_s_t, n_mu_s), 0, n_mu_s - 1,
                                      &f_mu_s);
                float3 j = (float3)(0.0f);
                for (int c = 0; c < 4; c++) {
                    __global const float4 *q = J + rows[i][c] + o_nu + i_mu_s;
                    float3 near = mix(q[0].xyz, q[1].xyz, f_mu_s);
                    float3 far = mix(q[n_mu_s].xyz, q[n_mu_s + 1].xyz, f_mu_s);
                    j += w_rm[i][c] * mix(near, far, f_nu);
                }
                L += tw[i] * j;
            }
            int idx = first + x;
            if (c0 > 0)
                L += scattering_scratch[idx].xyz;
            scattering_scratch[idx] = (float4)(L, 0.0f);
        }
    }
    for (int x = 0; x < texels; x++)
        scattering_rayleigh[N + first + x] += scattering_scratch[first + x];
}
