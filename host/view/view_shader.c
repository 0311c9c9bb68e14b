/* view_shader.c — the viewer's GLSL: the display pipeline of kernels/post/tonemap.h on the GPU.
 *
 * Per channel of the linear texel x (the session's mean radiance), exactly the steps of
 * atmo_post_pixel (host/image/post.c):
 *     x / white balance (when on)  ->  * exposure  ->  tone map  ->  clamp [0, 1]
 *     ->  transfer curve (sRGB or gamma 2.2)
 * with the operators and curves of tonemap.h written again in GLSL, formula for formula and
 * constant for constant (exposure 1 - exp(-x); Reinhard 2002 eq. 3 and 4; Narkowicz's ACES fit;
 * Unreal 3 linearised with gamma 2.2; Uchimura 2017 with P = 1, a = 1, m = 0.22, l = 0.4,
 * c = 1.33, b = 0; Lottes 2016 with a = 1.6, d = 0.977, midIn = 0.18, midOut = 0.267 and
 * hdrMax = the white point; sRGB per IEC 61966-2-1). The operator and transfer numbers are the
 * ATMO_TONEMAP_* and ATMO_TRANSFER_* values of gpu_enums.h (0 none ... 7 lottes; 0 sRGB,
 * 1 gamma 2.2), passed as uniforms. GLSL has no expm1: 1 - exp(-x) loses relative precision
 * for tiny x, but its absolute error (~1e-7) is far below the 1/255 step of the framebuffer.
 * The one difference to the host is float rounding in exp, pow and division (a few ulps), so
 * the 8-bit framebuffer agrees with the PNG writer's floor(255 v + 1/2) to within one step
 * (tests/test_view_screenshot.sh measures it).
 *
 * The framebuffer is plain 8-bit RGBA (no GL_FRAMEBUFFER_SRGB): the shader writes the encoded
 * value, as the PNG stores it. The sources compile as GLSL 3.30 core and as GLSL 1.20 through
 * the prefixes, which name the in/out qualifiers, the output and the texture lookup. */
#include "view_shader.h"

const char view_glsl_core[] = "#version 330 core\n"
                              "#define VERTEX_IN in\n"
                              "#define VARYING_OUT out\n"
                              "#define VARYING_IN in\n"
                              "#define TEXTURE texture\n"
                              "#define FRAGMENT_OUT frag_colour\n"
                              "#define DECLARE_OUT out vec4 frag_colour;\n";

const char view_glsl_legacy[] = "#version 120\n"
                                "#define VERTEX_IN attribute\n"
                                "#define VARYING_OUT varying\n"
                                "#define VARYING_IN varying\n"
                                "#define TEXTURE texture2D\n"
                                "#define FRAGMENT_OUT gl_FragColor\n"
                                "#define DECLARE_OUT\n";

const char view_glsl_image_vertex[] =
    "VERTEX_IN vec2 position;\n" /* NDC corner */
    "VERTEX_IN vec2 texcoord;\n"
    "VARYING_OUT vec2 uv;\n"
    "void main() { uv = texcoord; gl_Position = vec4(position, 0.0, 1.0); }\n";

const char view_glsl_image_fragment[] =
    "VARYING_IN vec2 uv;\n"
    "DECLARE_OUT\n"
    "uniform sampler2D image;\n"
    "uniform float exposure;\n"
    "uniform int tonemap;\n"
    "uniform float white_point;\n"
    "uniform int white_balance;\n"
    "uniform vec3 white_balance_rgb;\n"
    "uniform int transfer;\n"
    "float tm_smoothstep(float e0, float e1, float x) {\n"
    "    float t = clamp((x - e0) / (e1 - e0), 0.0, 1.0);\n"
    "    return t * t * (3.0 - 2.0 * t);\n"
    "}\n"
    "float tm_uchimura(float x) {\n"
    "    const float p = 1.0, a = 1.0, m = 0.22, l = 0.4, c = 1.33, b = 0.0;\n"
    "    float l0 = (p - m) * l / a;\n"
    "    float s0 = m + l0;\n"
    "    float s1 = m + a * l0;\n"
    "    float rate = a * p / (p - s1);\n"
    "    float w0 = 1.0 - tm_smoothstep(0.0, m, x);\n"
    "    float w2 = x >= s0 ? 1.0 : 0.0;\n"
    "    float w1 = 1.0 - w0 - w2;\n"
    "    float toe = m * pow(x / m, c) + b;\n"
    "    float linear_part = m + a * (x - m);\n"
    "    float shoulder = p - (p - s1) * exp(-rate * (x - s0));\n"
    "    return toe * w0 + linear_part * w1 + shoulder * w2;\n"
    "}\n"
    "float tm_lottes(float x, float hdr_max) {\n"
    "    const float a = 1.6, d = 0.977, mid_in = 0.18, mid_out = 0.267;\n"
    "    float mid_a = pow(mid_in, a), mid_ad = pow(mid_in, a * d);\n"
    "    float max_a = pow(hdr_max, a), max_ad = pow(hdr_max, a * d);\n"
    "    float denom = (max_ad - mid_ad) * mid_out;\n"
    "    float bb = (max_a * mid_out - mid_a) / denom;\n"
    "    float cc = (max_ad * mid_a - max_a * mid_ad * mid_out) / denom;\n"
    "    return pow(x, a) / (pow(x, a * d) * bb + cc);\n"
    "}\n"
    "float tm_apply(int op, float x, float w) {\n"
    "    float y;\n"
    "    x = max(x, 0.0);\n"
    "    if (op == 1) y = 1.0 - exp(-x);\n"
    "    else if (op == 2) y = x / (1.0 + x);\n"
    "    else if (op == 3) y = x * (1.0 + x / (w * w)) / (1.0 + x);\n"
    "    else if (op == 4) y = x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);\n"
    "    else if (op == 5) y = pow(min(1.019 * x / (x + 0.155), 1.0), 2.2);\n"
    "    else if (op == 6) y = tm_uchimura(x);\n"
    "    else if (op == 7) y = tm_lottes(x, w);\n"
    "    else y = x;\n"
    "    return y > 0.0 ? min(y, 1.0) : 0.0;\n"
    "}\n"
    "float tm_encode(int curve, float v) {\n"
    "    if (curve == 1) return pow(v, 1.0 / 2.2);\n"
    "    return v <= 0.0031308 ? 12.92 * v : 1.055 * pow(v, 1.0 / 2.4) - 0.055;\n"
    "}\n"
    "void main() {\n"
    "    vec3 x = TEXTURE(image, uv).rgb;\n"
    "    if (white_balance != 0) x = x / white_balance_rgb;\n"
    "    x = x * exposure;\n"
    "    vec3 d = vec3(tm_encode(transfer, tm_apply(tonemap, x.r, white_point)),\n"
    "                  tm_encode(transfer, tm_apply(tonemap, x.g, white_point)),\n"
    "                  tm_encode(transfer, tm_apply(tonemap, x.b, white_point)));\n"
    "    FRAGMENT_OUT = vec4(d, 1.0);\n"
    "}\n";

const char view_glsl_text_vertex[] =
    "VERTEX_IN vec2 position;\n" /* window pixels, y down */
    "VERTEX_IN vec4 colour;\n"
    "VARYING_OUT vec4 tint;\n"
    "uniform vec2 viewport;\n"
    "void main() {\n"
    "    tint = colour;\n"
    "    gl_Position = vec4(2.0 * position.x / viewport.x - 1.0,\n"
    "                       1.0 - 2.0 * position.y / viewport.y, 0.0, 1.0);\n"
    "}\n";

const char view_glsl_text_fragment[] = "VARYING_IN vec4 tint;\n"
                                       "DECLARE_OUT\n"
                                       "void main() { FRAGMENT_OUT = tint; }\n";
