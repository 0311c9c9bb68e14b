/* ms_lut.h — the multiple-scattering transfer LUT Psi_ms(h, mu_s) and the view-ray march that
 * uses it (methods "march" and "fast").
 *
 * Idea (Hillaire 2020, "A Scalable and Production Ready Sky and Atmosphere Rendering Technique",
 * EGSR, sec. 5.5): light that has scattered at least once arrives at a point x from every
 * direction with a radiance that changes slowly with x; treat it as if it were the same from
 * all directions and as if every later order were scattered isotropically. Then the radiance
 * scattered at x by orders >= 2 is sigma_s(x) Psi_ms(x), and Psi depends only on the altitude h
 * of x and the sun cosine mu_s there. With p_u = 1/(4 pi) and the sphere of directions w:
 *
 *   L_1'(x, w) = int_0^d T(x, y) sum_k sigma_k(y) p_k(w . s) E T_sun(y) dt
 *              + T(x, g) (rho / pi) E T_sun(g) max(mu_s(g), 0)          if the ray hits ground g
 *   L_2(x)     = int_4pi L_1'(x, w) p_u dw       (first-order light arriving at x, averaged)
 *   f_ms(x)    = int_4pi p_u int_0^d T(x, y) sigma_s(y) dt dw
 *                (the fraction of isotropic light scattered at x that scatters once more
 *                 before it leaves the atmosphere: Hillaire's eq. 7)
 *   Psi_ms(x)  = L_2 (1 + f_ms + f_ms^2 + ...) = L_2 / (1 - f_ms)                 (eq. 9-10)
 *
 * with sum_k over Rayleigh and Mie, p_k their phase functions and s the sun direction.
 * Where Hillaire uses the isotropic p_u for the first scattering too, L_1' here uses the true
 * phase functions: it costs nothing (the sun direction is known for each w) and removes the part
 * of his error that comes from spreading the strongly forward Mie scattering (and the
 * 1 + cos^2 shape of Rayleigh's) evenly over the sphere. What stays approximate is the angular
 * shape of orders >= 2 at x.
 *
 * Quadrature: w on n_mu bands in cos(zenith) times n_phi azimuths over [0, pi] (the light field is
 * symmetric about the vertical plane through the sun); half the bands lie above the horizon cosine
 * mu_h = -sqrt(r^2 - R^2) / r and half below, so no band straddles the step between sky and
 * ground, each half crowding toward the horizon as the square of its index (the bands follow the
 * local vertical, not the sun: a grid in the sun's frame would cut that step diagonally). Each
 * direction is walked by the integrator's quadrature (quadrature_walk.h, ms_segment_at): n_steps
 * segments growing as (i/n)^2 from x, the coefficients at t = d ((i + 1/2) / n)^2 in segment i
 * (QUADRATURE_GRID_MIDDLE), the segment integrated exactly for constant coefficients
 * (media.h's medium_piece_weight),
 *     G += T w J,  w = (1 - e^{-sigma_t dt}) / sigma_t,  T *= e^{-sigma_t dt}
 * for a source J (W m^-3 sr^-1 nm^-1) at that point; the densities, T and w of a segment serve
 * every azimuth of its band, which differ only in the sun's angle. LUT: x_mu = (1 + sign(mu_s)
 * sqrt|mu_s|) / 2 along the width, x_h = h / (top - bottom) along the height, texel centres at
 * x = 0 and 1 (atmosphere_texcoord_from_unit); xyz = Psi (W m^-2 sr^-1 nm^-1, with the solar
 * irradiance E folded in), w = f_ms of the middle channel.
 *
 * March (march_trace): the medium integrator (kernels/media/medium.h: the segments, the
 * per-sample offset, the sun-disc and ground terms of method single), with, at each sample,
 *     J = [sigma_R p_R(nu) + sigma_M p_M(nu)] E T_sun V + J_ms
 * where V is the sun's visibility from the visibility sources (kernels/media/visibility.h) and
 * J_ms = (sigma_R + sigma_M) Psi_ms(h, mu_s) for isotropic light, plus the anisotropic terms
 * below (ms_lut_source). With Psi = 0 the sum is the single-scattering sum term for term. The
 * ground seen by the view ray is lit by the sun and by the sky (E_sky, below).
 *
 * Rayleigh anisotropy of the second order. For the Rayleigh phase p_R = 3/(16 pi)(1 + (v.w)^2)
 * the second order toward v is exact from three moments of L_1': int L_1'(w) p_R(v.w) dw =
 * L_2 + v^T D v with m = (3/4) <L_1' w w^T> (the sphere average <.>) and D = m - (L_2/4) I,
 * traceless and 0 for isotropic light. By the symmetry about the sun's vertical plane D has
 * three free components in the frame (up, sun-ward horizontal, across): D_uu, D_ss, D_us
 * (D_pp = -D_uu - D_ss), stored per channel.
 * Mie anisotropy. The same moments are the light field's spherical harmonics up to l = 2: with
 * the first moment b = <L w> (b_u, b_s; b_p = 0 by the symmetry), L = a_0 + 3 b.w + 10 w^T D w +
 * (l >= 3), a_0 = <L> = Psi. A phase function p convolves the l-th harmonic by its Legendre
 * coefficient g_l = 2 pi int p(x) P_l(x) dx (Funk-Hecke): Rayleigh's g_1 = 0, g_2 = 1/10 give the
 * D term above exactly; the aerosols' (Cornette-Shanks g = 0.8: g_1 = 0.844, g_2 = 0.710,
 * computed by the plan into s->ms.g1, g2) give, truncated at l = 2,
 *     J_ms = sigma_R (Psi + v^T D v) + sigma_M (Psi + 3 g_1 b.v + 10 g_2 v^T D v)
 * with v the direction the camera looks along (light arriving from v scatters forward into it);
 * each part is kept >= 0. The truncation keeps the sky/ground and sun/anti-sun asymmetries and
 * the horizon band of the light field but not the aureole, narrower than l = 2 resolves: red
 * order 2 is ~20 % low toward a low sun.
 * Gathered higher orders (ms_lut_gather; kernels ms_lut_order3, ms_lut_second). Hillaire's series
 * f L_2 + f^2 L_2 + ... takes the higher orders at x from x's own L_2, which fails where they come
 * from elsewhere (into the Earth's shadow at twilight), leaves out the ground lit by the sky, and
 * makes orders >= 4 too low even in daylight (f at x underestimates what the brighter air above
 * and along the horizon sends back). So orders are gathered where they are scattered: a gathering
 * pass computes, along the same directions and segments, the radiance G(w) arriving at x from a
 * source J_src of the form of J_ms (anisotropy included: light sent along the horizon and forward
 * by the aerosols counts it), plus T (rho / pi) E where w meets the ground; <G> is the next
 * order's source per unit sigma_s and the moments of G give its anisotropy A = (D, b) the same way
 * as L_1''s. Pass 2 gathers order 3 exactly from order 2 (L_2, A_2, the ground lit by the
 * first-order sky E_1 = 4 pi <L_1' max(mu, 0)>): S_3, A_3, E_2. Pass 3 gathers orders >= 3 from
 * the series over the gathered order 3, Psi_src = L_2 + S_3 / (1 - f), A_src = A_2 + A_3 (1 + k f
 * / (1 - f)) (k = ms.higher_anisotropy: orders >= 4 shaped like order 3), E = E_1 + E_2 / (1 - f):
 * Psi = L_2 + <G>, A = A_2 + A_G. Orders >= 4 keep part of the local series' error (measured:
 * 5-10 % low in blue, ~0.5 % of the sky at the horizon). Planes of the LUT (each width x height;
 * ms_lut.cl): 0 Psi (xyz), f of channel y (w); 1-5 D_uu, D_ss, D_us, b_u, b_s; 12 E_sky (the
 * ground's sky irradiance, all orders); 6-11 and 13 scratch of the passes.
 * Accuracy against the Monte Carlo reference (tests/data/reference_sky.csv, ground camera,
 * views 0..85 deg): worst -1.3 % for sun zenith 0..80 deg (blue) and -1.2 % with the sun at the
 * horizon (red); 4x the directions and 3x the segments change these by < 0.3 %. What is left:
 * the aureole in the aerosols' part of orders >= 2 and the local series in orders >= 4 (both
 * above). Measured choices, step by step: docs/notes/ms_lut.md. */
#ifndef ATMO_MS_LUT_H
#define ATMO_MS_LUT_H
#ifndef __OPENCL_VERSION__
#include "common/compat.h"
#include "atmosphere/atmosphere.h"
#include "common/geometry.h"
#include "common/phase.h"
#include "atmosphere/ms_lut_source.h"
#include "media/media.h"
#include "media/medium.h"
#include "media/quadrature_walk.h"
#include "atmo/gpu_types.h"
#endif

/* Band k of n_mu direction bands for the sphere integrals at a point whose horizon cosine is
 * mu_h: half the bands above mu_h, half below, so no band straddles the step between sky and
 * ground, crowding toward the horizon as v^2 where the sky is brightest and changes fastest:
 * mu = mu_h +- span v^2. Returns mu; *u = span v is the band's weight (its share of the sphere
 * is span 2 v dv). */
ATMO_FN float ms_band(int k, int n_mu, float mu_h, float *u)
{
    int n_half = n_mu / 2, up = k >= n_half;
    float span = up ? 1.0f - mu_h : mu_h + 1.0f;
    float v = ((float)(up ? k - n_half : k) + 0.5f) / (float)n_half;
    *u = span * v;
    return atmo_clamp_cos(up ? mu_h + span * v * v : mu_h - span * v * v);
}

/* Sums over the quadrature's directions w (weights u) of a radiance L(w) and its moments in the
 * local frame (up component mu, sun-ward horizontal w_s): <L>, the second moments of the
 * Rayleigh D, the first moments b_u, b_s, and the upward flux <L max(mu, 0)>. */
typedef struct ms_moments {
    vec3 sum, m_uu, m_ss, m_us, b_u, b_s, e_up;
    float weights;
} ms_moments;

ATMO_FN void ms_moments_add(ms_moments *m, vec3 L, float u, float mu, float w_s)
{
    if (mu > 0.0f)
        m->e_up = v3_add(m->e_up, v3_scale(L, u * mu));
    m->m_uu = v3_add(m->m_uu, v3_scale(L, u * mu * mu));
    m->m_ss = v3_add(m->m_ss, v3_scale(L, u * w_s * w_s));
    m->m_us = v3_add(m->m_us, v3_scale(L, u * mu * w_s));
    m->b_u = v3_add(m->b_u, v3_scale(L, u * mu));
    m->b_s = v3_add(m->b_s, v3_scale(L, u * w_s));
    m->sum = v3_add(m->sum, v3_scale(L, u));
    m->weights += u;
}

/* <L> (normalised by the sum of the weights, 2 up to rounding); dev[0..4] = D_uu, D_ss, D_us,
 * b_u, b_s with m = (3/4) <L w w^T>, D = m - (<L> / 4) I (traceless, 0 for an isotropic L). */
ATMO_FN vec3 ms_moments_finish(const ms_moments *m, float4 *dev)
{
    vec3 mean = v3_scale(m->sum, 1.0f / m->weights);
    dev[0] = ms_float4(v3_sub(v3_scale(m->m_uu, 0.75f / m->weights), v3_scale(mean, 0.25f)),
                         0.0f);
    dev[1] = ms_float4(v3_sub(v3_scale(m->m_ss, 0.75f / m->weights), v3_scale(mean, 0.25f)),
                         0.0f);
    dev[2] = ms_float4(v3_scale(m->m_us, 0.75f / m->weights), 0.0f);
    dev[3] = ms_float4(v3_scale(m->b_u, 1.0f / m->weights), 0.0f);
    dev[4] = ms_float4(v3_scale(m->b_s, 1.0f / m->weights), 0.0f);
    return mean;
}

/* The air on one segment of a quadrature direction, at the point of the segment where its
 * coefficients are taken. */
typedef struct ms_segment {
    float t, r_t, h;    /* the point's distance from x, radius and altitude (m) */
    float rho_r, rho_m; /* the Rayleigh and aerosol densities there (relative to the ground) */
    vec3 Tw;            /* T(x, segment start) w (m): a source constant over the segment sends
                           Tw times itself to x */
} ms_segment;

/* The air on the quadrature walk's current piece along the direction from radius r along mu
 * (quadrature_walk.h, sampled at the middle of each grid segment in the grid's parameter:
 * QUADRATURE_GRID_MIDDLE), integrated exactly for constant coefficients (medium_piece_weight,
 * which moves *T = T(x, piece start) past it). Measured on the sky, that point leaves a third
 * of the quadrature error that the segment's middle in t leaves (docs/notes/ms_lut.md). */
ATMO_FN void ms_segment_at(ATMO_GLOBAL const atmo_gpu_atmosphere *a, float r, float mu,
                           const quadrature_walk *q, vec3 *T, ms_segment *g)
{
    g->t = q->t;
    g->r_t = geometry_radius_at(r, mu, g->t);
    g->h = geometry_altitude_at(r, mu, g->t, a->bottom_radius);
    g->rho_r = expf(-g->h / a->rayleigh_scale_height);
    g->rho_m = expf(-g->h / a->mie_scale_height);
    g->Tw = medium_piece_weight(atmosphere_extinction_at(a, g->h, g->rho_r, g->rho_m), q->dt, T);
}

/* First pass at one texel at radius r and sun cosine mu_s: returns L_2 (xyz) and f_ms of
 * channel y (w); dev[0..4] = the anisotropy of order 2 (xyz per channel; see the file's
 * comment): D_uu, D_ss, D_us, b_u, b_s; dev[5] = 1 - f_ms (xyz per channel); dev[6] = E_1, the
 * first-order sky irradiance of a horizontal surface at x, 4 pi <L_1' max(mu, 0)>.
 * 1 - f_ms is summed as what leaves instead of subtracted: along each direction the segments'
 * weights telescope, sum_i T_i w_i sigma_t,i = 1 - T_end, so the light that does not scatter
 * again is T_end + sum_i T_i w_i sigma_abs,i (absorbed by the aerosols and ozone, or reaching
 * the top or the ground). In an optically thick air (tau ~ 1e5 at rayleigh_coefficient 1)
 * f_ms is 1 - 1e-8 and rounds to 1 in float, where the series 1 / (1 - f_ms) would divide by
 * zero; the sum keeps the 1e-8. */
ATMO_FN float4 ms_lut_texel(ATMO_GLOBAL const atmo_gpu_scene *s,
                            ATMO_GLOBAL const float4 *transmittance, float r, float mu_s,
                            int n_mu, int n_phi, int n_steps, float4 *dev)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    int tw = s->transmittance_width, th = s->transmittance_height;
    vec3 E = v3_from4(a->solar_irradiance);
    vec3 beta_r = v3_mul(v3_from4(a->rayleigh_scattering), E);
    vec3 beta_m = v3_mul(v3_from4(a->mie_scattering), E);
    vec3 albedo = v3_from4(a->ground_albedo);
    float sin_s = atmo_safe_sqrt(1.0f - mu_s * mu_s);
    vec3 mie_absorption = v3_sub(v3_from4(a->mie_extinction), v3_from4(a->mie_scattering));
    vec3 ozone_absorption = v3_from4(a->ozone_absorption);
    vec3 escape = v3(0.0f, 0.0f, 0.0f), zero = v3(0.0f, 0.0f, 0.0f);
    ms_moments mom = {zero, zero, zero, zero, zero, zero, zero, 0.0f};
    float mu_h = -atmo_safe_sqrt((r - a->bottom_radius) * (r + a->bottom_radius)) / r;
    n_phi = n_phi < ATMO_MS_MAX_DIRECTIONS_PHI ? n_phi : ATMO_MS_MAX_DIRECTIONS_PHI;
    float cos_phi[ATMO_MS_MAX_DIRECTIONS_PHI], nu[ATMO_MS_MAX_DIRECTIONS_PHI];
    float p_r[ATMO_MS_MAX_DIRECTIONS_PHI], p_m[ATMO_MS_MAX_DIRECTIONS_PHI];
    vec3 L1[ATMO_MS_MAX_DIRECTIONS_PHI];
    for (int l = 0; l < n_phi; l++)
        cos_phi[l] = cosf(ATMO_PI * ((float)l + 0.5f) / (float)n_phi);
    for (int k = 0; k < n_mu; k++) {
        float u, mu = ms_band(k, n_mu, mu_h, &u);
        int hits_ground = k < n_mu / 2;
        float sin_v = atmo_safe_sqrt(1.0f - mu * mu);
        float d = atmosphere_ray_length(a, r, mu, hits_ground);
        for (int l = 0; l < n_phi; l++) {
            nu[l] = atmo_clamp_cos(mu * mu_s + sin_v * sin_s * cos_phi[l]);
            p_r[l] = phase_rayleigh(nu[l]);
            p_m[l] = media_mie_phase(a, nu[l]);
            L1[l] = zero;
        }
        /* the densities, extinction and segment weights along the band's rays do not depend
         * on the azimuth: computed once per segment, the sun's transmittance per azimuth */
        vec3 T = v3(1.0f, 1.0f, 1.0f), absorbed = zero;
        quadrature_walk q = quadrature_begin(d, n_steps, QUADRATURE_GRID_MIDDLE);
        while (quadrature_next(&q) != QUADRATURE_END) {
            ms_segment g;
            ms_segment_at(a, r, mu, &q, &T, &g);
            vec3 sigma_abs = v3_add(v3_scale(mie_absorption, g.rho_m),
                                    v3_scale(ozone_absorption, atmosphere_ozone_tent(a, g.h)));
            vec3 lit_r = v3_mul(g.Tw, v3_scale(beta_r, g.rho_r));
            vec3 lit_m = v3_mul(g.Tw, v3_scale(beta_m, g.rho_m));
            float rmu_s = r * mu_s, inv_r_t = 1.0f / g.r_t;
            for (int l = 0; l < n_phi; l++) {
                float mu_s_t = atmo_clamp_cos((rmu_s + g.t * nu[l]) * inv_r_t);
                vec3 sun_t = atmosphere_sun_transmittance(a, transmittance, tw, th, g.r_t,
                                                          mu_s_t);
                vec3 scattered = v3_add(v3_scale(lit_r, p_r[l]), v3_scale(lit_m, p_m[l]));
                L1[l] = v3_add(L1[l], v3_mul(scattered, sun_t));
            }
            absorbed = v3_add(absorbed, v3_mul(g.Tw, sigma_abs));
        }
        for (int l = 0; l < n_phi; l++) {
            if (hits_ground) {
                float mu_s_g = atmo_clamp_cos((r * mu_s + d * nu[l]) / a->bottom_radius);
                vec3 sun_g = atmosphere_sun_transmittance(a, transmittance, tw, th,
                                                          a->bottom_radius, mu_s_g);
                vec3 radiance = v3_scale(v3_mul(v3_mul(albedo, E), sun_g),
                                         fmaxf(mu_s_g, 0.0f) / ATMO_PI);
                L1[l] = v3_add(L1[l], v3_mul(T, radiance));
            }
            /* w in the local frame: up component mu, sun-ward horizontal sin_v cos(phi) */
            ms_moments_add(&mom, L1[l], u, mu, sin_v * cos_phi[l]);
        }
        escape = v3_add(escape, v3_scale(v3_add(T, absorbed), u * (float)n_phi));
    }
    vec3 L2 = ms_moments_finish(&mom, dev);
    escape = v3_scale(escape, 1.0f / mom.weights);
    dev[5] = ms_float4(escape, 0.0f);
    dev[6] = ms_float4(v3_scale(mom.e_up, 4.0f * ATMO_PI / mom.weights), 0.0f);
    return ms_float4(L2, 1.0f - escape.y);
}

/* A gathering pass at one texel (x at radius r, sun cosine mu_s): the radiance arriving at x
 * from each direction w of the quadrature, G(w) = int_0^d T(x, y) J(y, w) dt + T(x, g) (rho / pi)
 * E(g) where w meets the ground g, for the source per unit scattering coefficient read from the
 * plane `psi_src` and the five anisotropy planes from `aniso_src` (ms_lut_source_planes, with
 * w as the view direction), E from the plane `sky_e`. Returns <G> (the next order's source per
 * unit sigma_s, isotropic part); dev[0..4] = its anisotropy from the moments of G, as
 * ms_lut_texel's from L_1'; dev[5] = the irradiance G gives a horizontal surface,
 * 4 pi <G max(mu, 0)>. Same quadrature as ms_lut_texel (ms_lut.cl passes half the azimuths). */
ATMO_FN vec3 ms_lut_gather(ATMO_GLOBAL const atmo_gpu_scene *s,
                           ATMO_GLOBAL const float4 *psi_src, ATMO_GLOBAL const float4 *aniso_src,
                           ATMO_GLOBAL const float4 *sky_e,
                           int width, int height, float r, float mu_s, int n_mu, int n_phi,
                           int n_steps, float4 *dev)
{
    ATMO_GLOBAL const atmo_gpu_atmosphere *a = &s->atmosphere;
    vec3 albedo = v3_from4(a->ground_albedo);
    vec3 beta_r = v3_from4(a->rayleigh_scattering), beta_m = v3_from4(a->mie_scattering);
    float sin_s = atmo_safe_sqrt(1.0f - mu_s * mu_s);
    float mu_h = -atmo_safe_sqrt((r - a->bottom_radius) * (r + a->bottom_radius)) / r;
    vec3 zero = v3(0.0f, 0.0f, 0.0f);
    ms_moments mom = {zero, zero, zero, zero, zero, zero, zero, 0.0f};
    n_phi = n_phi < ATMO_MS_MAX_DIRECTIONS_PHI ? n_phi : ATMO_MS_MAX_DIRECTIONS_PHI;
    float cos_phi[ATMO_MS_MAX_DIRECTIONS_PHI], nu[ATMO_MS_MAX_DIRECTIONS_PHI];
    vec3 acc[ATMO_MS_MAX_DIRECTIONS_PHI];
    for (int l = 0; l < n_phi; l++)
        cos_phi[l] = cosf(ATMO_PI * ((float)l + 0.5f) / (float)n_phi);
    for (int k = 0; k < n_mu; k++) {
        float u, mu = ms_band(k, n_mu, mu_h, &u);
        int up = k >= n_mu / 2;
        float sin_v = atmo_safe_sqrt(1.0f - mu * mu);
        float d = atmosphere_ray_length(a, r, mu, !up);
        for (int l = 0; l < n_phi; l++) {
            nu[l] = atmo_clamp_cos(mu * mu_s + sin_v * sin_s * cos_phi[l]);
            acc[l] = zero;
        }
        /* as in ms_lut_texel: the segment's media once, the source per azimuth */
        vec3 T = v3(1.0f, 1.0f, 1.0f);
        quadrature_walk q = quadrature_begin(d, n_steps, QUADRATURE_GRID_MIDDLE);
        while (quadrature_next(&q) != QUADRATURE_END) {
            ms_segment g;
            ms_segment_at(a, r, mu, &q, &T, &g);
            vec3 sigma_r = v3_scale(beta_r, g.rho_r), sigma_m = v3_scale(beta_m, g.rho_m);
            float rmu_s = r * mu_s, inv_r_t = 1.0f / g.r_t, mu_t = (r * mu + g.t) * inv_r_t;
            for (int l = 0; l < n_phi; l++) {
                float mu_s_t = atmo_clamp_cos((rmu_s + g.t * nu[l]) * inv_r_t);
                vec3 j = ms_lut_source_planes(s, psi_src, aniso_src, width, height, g.r_t, mu_t,
                                              mu_s_t, nu[l], sigma_r, sigma_m);
                acc[l] = v3_add(acc[l], v3_mul(g.Tw, j));
            }
        }
        for (int l = 0; l < n_phi; l++) {
            if (!up) { /* the ground lit by the sky: (rho / pi) E */
                float mu_s_g = atmo_clamp_cos((r * mu_s + d * nu[l]) / a->bottom_radius);
                vec3 e = ms_lut_lookup(a, sky_e, width, height, a->bottom_radius, mu_s_g);
                acc[l] = v3_add(acc[l], v3_mul(T, v3_scale(v3_mul(albedo, e), 1.0f / ATMO_PI)));
            }
            ms_moments_add(&mom, acc[l], u, mu, sin_v * cos_phi[l]);
        }
    }
    vec3 sum = ms_moments_finish(&mom, dev);
    dev[5] = ms_float4(v3_scale(mom.e_up, 4.0f * ATMO_PI / mom.weights), 0.0f);
    return sum;
}

/* Single scattering plus sigma_s Psi_ms: the medium integrator with this LUT's source
 * (kernels/media/medium.h), s->view_steps segments with sample offset `jitter`, over [0, t_max]
 * of the ray (sky_method.h's sky_trace). */
ATMO_FN void march_trace(ATMO_GLOBAL const atmo_gpu_scene *s, ATMO_LUT_PARAMS,
                         const medium_ray *m, float t_max, float jitter, vec3 *sky, vec3 *sun,
                         vec3 *view_t)
{
    medium_result res;
    medium_integrate(s, ATMO_LUT_ARGS, m, 0.0f, t_max, s->view_steps, jitter, 1, &res);
    *sky = medium_radiance(s, ATMO_LUT_ARGS, &res, m->nu);
    *sun = res.sun;
    *view_t = res.view_t;
}

#endif
