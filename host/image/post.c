/* post.c — the display pipeline on the host, for PNG output.
 *
 * Per channel c of a linear pixel (see kernels/post/tonemap.h for the operators and curves):
 *     x_c = in_c / wb_c (if white balance is on) * exposure
 *     y_c = clamp(tonemap(x_c), 0, 1)
 *     out_c = transfer(y_c)                      (sRGB or gamma 2.2)
 * and the PNG stores floor(255 out_c + 1/2). The white balance divides by the sun's colour (mean 1),
 * so that sunlight reflected by a white surface comes out neutral. */
#include "atmo/image.h"
#include "post/tonemap.h"

void atmo_post_pixel(const atmo_post *post, const float in[3], float out_display[3])
{
    for (int c = 0; c < 3; c++) {
        float x = in[c];
        if (post->white_balance)
            x /= post->white_balance_rgb[c];
        x *= post->exposure;
        float y = tonemap_apply(post->tonemap, x, post->white_point);
        out_display[c] = transfer_encode(post->transfer, y);
    }
}

void atmo_post_to_rgb8(const atmo_post *post, const atmo_image *img, unsigned char *out)
{
    size_t n = (size_t)img->width * (size_t)img->height;
    for (size_t i = 0; i < n; i++) {
        float d[3];
        atmo_post_pixel(post, img->rgb + 3 * i, d);
        for (int c = 0; c < 3; c++)
            out[3 * i + (size_t)c] = (unsigned char)(255.0f * clamp(d[c], 0.0f, 1.0f) + 0.5f);
    }
}
