/* scene_blender.c — output.blender: the scene rewritten so that its outputs are what Blender
 * reads as they are (docs/guide/blender.md).
 *
 * Colour. Blender takes a float EXR's R, G, B as its scene-linear space, linear Rec.709 (sRGB
 * primaries, D65 white), unless the file names another one. In radiance mode atmo's channels are
 * spectral radiance at three wavelengths, not primaries; render.quantity=luminance gives linear
 * Rec.709 in cd/m^2 (Bruneton 2016, §14.3; atmo/colour.h), and the spectral mode
 * (render.spectral_bands > 0) gives it from N bands already. The writers then state the
 * primaries (the EXR's standard chromaticities attribute; atmo/image.h).
 *
 * Exposure. post.exposure multiplies the values before the tone map, and luminance values are
 * about 10^5 times the radiance values of the same sky (the luminance factors k_c of
 * atmo/colour.h are 6.5e4 to 1.2e5 lm nm/W), so the exposure is scaled by
 * ATMO_LUMINANCE_EXPOSURE_SCALE = 1e-5 when the quantity changes: the factor Bruneton's own demo
 * applies to its exposure in luminance mode (precomputed_atmospheric_scattering, demo.cc). A PNG
 * of the same render then keeps its brightness, and the exposure is what Blender's World
 * strength must be to show the EXR as atmo shows it (outputs.c).
 *
 * Orientation. Cycles' equirectangular mapping (intern/cycles/kernel/camera/projection.h,
 * direction_to_equirectangular) puts Blender's +X at the image centre, +Y at a quarter of the
 * width, -Y at three quarters and +Z on the top row; with Blender's axes = (X, Z, Y) of atmo's
 * world, that is atmo's panorama with camera.yaw_deg = -90 (kernels/common/camera.h), whatever
 * yaw the scene had. The sun's azimuth a (from atmo +Z toward +X) is then measured from
 * Blender's +Y toward +X, and the sun's column is u = 1/4 + a/360 deg of the width. Other
 * cameras keep their orientation. */
#include <stdio.h>
#include <string.h>
#include "atmo/scene.h"

/* Append "key old -> new" to the changes text. */
static void note(char *changes, int size, const char *key, const char *old, const char *now)
{
    if (!changes || size <= 0)
        return;
    size_t used = strlen(changes);
    if (used + 1 >= (size_t)size)
        return;
    snprintf(changes + used, (size_t)size - used, "%s%s %s -> %s", used ? ", " : "", key, old,
             now);
}

int atmo_scene_for_blender(atmo_scene *s, char *changes, int size)
{
    int n = 0;
    char old[32], now[32];
    if (changes && size > 0)
        changes[0] = '\0';
    if (!s->output.blender)
        return 0;
    if (s->render.spectral_bands == 0 && s->render.quantity == ATMO_QUANTITY_RADIANCE) {
        s->render.quantity = ATMO_QUANTITY_LUMINANCE;
        note(changes, size, "render.quantity", "radiance", "luminance");
        snprintf(old, sizeof old, "%g", s->post.exposure);
        s->post.exposure *= ATMO_LUMINANCE_EXPOSURE_SCALE;
        snprintf(now, sizeof now, "%g", s->post.exposure);
        note(changes, size, "post.exposure", old, now);
        n += 2;
    }
    if (s->camera.kind == ATMO_CAMERA_PANORAMA &&
        s->camera.yaw_deg != ATMO_BLENDER_PANORAMA_YAW_DEG) {
        snprintf(old, sizeof old, "%g", s->camera.yaw_deg);
        s->camera.yaw_deg = ATMO_BLENDER_PANORAMA_YAW_DEG;
        snprintf(now, sizeof now, "%g", s->camera.yaw_deg);
        note(changes, size, "camera.yaw_deg", old, now);
        n++;
    }
    return n;
}
