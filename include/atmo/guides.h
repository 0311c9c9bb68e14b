/* guides.h — the denoiser's guides of a session's image (host/render/guides.c over
 * kernels/render/guide_render): albedo, normal and depth of the first surface the camera's rays
 * meet, averaged over a fixed pattern of rays per pixel that follows the mode's pixel filter,
 * so they carry no Monte Carlo noise and OIDN may take them as clean (cleanAux). Conventions
 * (OIDN's, docs/guide/denoise.md): a ray that meets no surface counts as albedo 1, normal 0 and
 * depth ATMO_GUIDES_NO_HIT_DEPTH_M; volumes are transparent to the guides. */
#ifndef ATMO_GUIDES_H
#define ATMO_GUIDES_H
#include "atmo/scene.h"
#include "atmo/session.h"
#include "atmo/status.h"

#define ATMO_GUIDES_NO_HIT_DEPTH_M 1e10

/* The guides of s's current view: albedo and normal W x H x 3, depth W x H and disc W x H (the
 * share of the pixel's guide rays that see the sun's disc unobstructed; either may be NULL),
 * row 0 = top. ATMO_ERR_RUNTIME names the failing OpenCL call. cancel (may be NULL) stops the
 * pass after the launch in flight: ATMO_INTERRUPTED_EMPTY, the outputs unspecified. */
int atmo_session_guides(atmo_session *s, float *albedo, float *normal, float *depth,
                        float *disc, const atmo_cancel *cancel, atmo_err *e);

/* The floats per pixel of a guide block: albedo 3, normal 3, depth 1, disc 1, as planes. */
#define ATMO_GUIDES_FLOATS 8

/* Whether the guides stand for the image of `scene`: not with a thin lens (its blur is not in
 * the pinhole's guides) or in the spectral mode (whose albedo would be of other wavelengths). */
int atmo_guides_apply(const atmo_scene *scene);

#endif
