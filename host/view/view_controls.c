/* view_controls.c — the viewer's keys and mouse as changes of the scene.
 *
 * Camera (scene.h's thesis convention): forward = (-cos p sin y, sin p, cos p cos y) and
 * right = (cos y, 0, sin y) for pitch p and yaw y (atmo_camera_basis); up, for movement, is the
 * radial direction (position - centre) / |position - centre| with the planet centre at
 * (0, -R, 0), so Q/E climb and descend over any point of the planet. A move of dt seconds is
 *     position += v(h) dt (f forward + r right + u up) / |f forward + r right + u up|,
 * with the speed v(h) = 0.5 s^-1 max(h, 10 m) of the altitude h at its start: 5 m/s walking on
 * the ground, 1000 km/s at 2000 km, so every altitude is crossed in a few seconds of holding a
 * key (x10 with Shift, x0.1 with Control). The camera stays at least 0.5 m above the ground
 * (a move below it is put back on that sphere along the radius). A mouse drag turns the camera
 * by 0.15 degrees per pixel at a 45-degree field of view (scaled with the field of view, so the
 * scene follows the cursor when zoomed): dragging right turns right (yaw decreases, since the
 * forward vector turns toward +right as y decreases), dragging up looks up; pitch stays within
 * [-90, 90] degrees, the range of camera.pitch_deg. A scroll notch zooms by 10%.
 *
 * Sun: the arrow keys change sun.zenith_deg (Up raises the sun: zenith - step) and
 * sun.azimuth_deg (Right: azimuth + step, toward +X = the right of a camera with yaw 0) by 1
 * degree, 10 with Shift; the zenith stays within [0, 180]. Angles that wrap (yaw, azimuth) are
 * kept in [-180, 180).
 *
 * Views: 1-9 load thesis-1 ... thesis-9 over the defaults with the user's --set options
 * reapplied but for camera.* and sun.* (so a size, method or sample count stays), and the
 * current post.* settings; 0 goes back to the start scene.
 *
 * Display: = and - (or keypad + and -) change post.exposure by a third of a stop (2^(1/3));
 * T cycles post.tonemap forward (Shift+T backward). Neither restarts the accumulation: the
 * shader applies them to the same linear image. N toggles the denoised display (view.c): the
 * frame on screen, not the accumulation, goes through the denoiser while it has few samples. */
#include <GLFW/glfw3.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include "atmo/plan.h"
#include "atmo/view.h"
#include "view_controls.h"
#include "view_mode.h"

#define PI 3.14159265358979323846
#define MIN_CLEARANCE_M 0.5
#define LOOK_DEG_PER_PIXEL 0.15
#define EXPOSURE_STEP 1.2599210498948732 /* 2^(1/3): a third of a stop */

const char atmo_view_keys[] =
    "  mouse drag       look around            scroll   zoom (field of view)\n"
    "  W A S D          move forward/left/back/right\n"
    "  Q E              move down/up           Shift x10, Ctrl x0.1 (speed grows with altitude)\n"
    "  arrow Up/Down    raise/lower the sun    arrow Left/Right  turn the sun (Shift: 10 deg)\n"
    "  1 ... 9          thesis view 1 ... 9    0  the start scene\n"
    "  Tab              fast preview / progressive quality\n"
    "  = -              exposure up/down (1/3 stop)\n"
    "  T                next tone mapper (Shift+T: previous)\n"
    "  N                denoised display while samples are few (on/off)\n"
    "  H or F1          help and status overlay\n"
    "  P                save the image and its scene file\n"
    "  Esc              quit\n";

static double wrap_deg(double a)
{
    a = fmod(a + 180.0, 360.0);
    return (a < 0.0 ? a + 360.0 : a) - 180.0;
}

static double clamp_d(double x, double lo, double hi) { return x < lo ? lo : x > hi ? hi : x; }

static double planet_distance(const atmo_scene *s, double radial[3])
{
    const double *p = s->camera.position_m;
    double d[3] = {p[0], p[1] + s->atmosphere.bottom_radius_m, p[2]};
    double r = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int i = 0; i < 3; i++)
        radial[i] = r > 0.0 ? d[i] / r : (i == 1);
    return r;
}

double view_altitude_m(const atmo_scene *s)
{
    double up[3];
    return planet_distance(s, up) - s->atmosphere.bottom_radius_m;
}

double view_speed_m_per_s(const atmo_scene *s, int mods)
{
    double h = view_altitude_m(s);
    double v = 0.5 * (h > 10.0 ? h : 10.0);
    if (mods & VIEW_MOD_SHIFT)
        v *= 10.0;
    if (mods & VIEW_MOD_CONTROL)
        v *= 0.1;
    return v;
}

int view_controls_move(view_state *v, int forward, int right, int up, int mods, double dt)
{
    if ((forward == 0 && right == 0 && up == 0) || dt <= 0.0)
        return 0;
    atmo_scene *s = &v->scene;
    double f[3], r[3], u_cam[3], radial[3], d[3];
    atmo_camera_basis(s->camera.pitch_deg, s->camera.yaw_deg, f, r, u_cam);
    planet_distance(s, radial);
    double len = 0.0;
    for (int i = 0; i < 3; i++) {
        d[i] = forward * f[i] + right * r[i] + up * radial[i];
        len += d[i] * d[i];
    }
    len = sqrt(len);
    if (len == 0.0)
        return 0;
    double step = view_speed_m_per_s(s, mods) * dt / len;
    for (int i = 0; i < 3; i++)
        s->camera.position_m[i] = clamp_d(s->camera.position_m[i] + step * d[i], -1e9, 1e9);
    double R = s->atmosphere.bottom_radius_m;
    double dist = planet_distance(s, radial);
    if (dist < R + MIN_CLEARANCE_M) {
        double c[3] = {0.0, -R, 0.0};
        for (int i = 0; i < 3; i++)
            s->camera.position_m[i] = c[i] + (R + MIN_CLEARANCE_M) * radial[i];
    }
    return VIEW_CHANGE_RENDER;
}

int view_controls_look(view_state *v, double dx, double dy)
{
    if (dx == 0.0 && dy == 0.0)
        return 0;
    double k = LOOK_DEG_PER_PIXEL * v->scene.camera.fov_deg / 45.0;
    v->scene.camera.yaw_deg = wrap_deg(v->scene.camera.yaw_deg - k * dx);
    v->scene.camera.pitch_deg = clamp_d(v->scene.camera.pitch_deg - k * dy, -90.0, 90.0);
    return VIEW_CHANGE_RENDER;
}

int view_controls_zoom(view_state *v, double notches)
{
    if (notches == 0.0)
        return 0;
    v->scene.camera.fov_deg = clamp_d(v->scene.camera.fov_deg * pow(0.9, notches), 1.0, 179.0);
    return VIEW_CHANGE_RENDER;
}

/* Thesis view n over the defaults, then the user's --set list but for its camera.* and sun.*
 * keys (the view is the thesis'), keeping the display settings; its camera placed in world
 * metres (atmo_plan_place_camera), as the controls move it. */
static int thesis_view(view_state *v, int n, atmo_err *e)
{
    char name[16];
    snprintf(name, sizeof name, "thesis-%d", n);
    atmo_scene s;
    atmo_scene_defaults(&s);
    int rc = atmo_scene_apply_preset(&s, name, e);
    for (int i = 0; i < v->set_count && !rc; i++)
        if (strncmp(v->sets[i], "camera.", 7) != 0 && strncmp(v->sets[i], "sun.", 4) != 0)
            rc = atmo_scene_assign(&s, v->sets[i], "--set", e);
    s.post = v->scene.post;
    if (rc || (rc = atmo_scene_validate(&s, e)) || atmo_plan_place_camera(&s, &v->scene, e))
        return 0;
    return VIEW_CHANGE_RENDER;
}

int view_controls_key(view_state *v, int key, int mods, atmo_err *e)
{
    atmo_scene *s = &v->scene;
    double sun_step = (mods & VIEW_MOD_SHIFT) ? 10.0 : 1.0;
    int tonemaps = ATMO_TONEMAP_LOTTES + 1;
    switch (key) {
    case GLFW_KEY_UP:
    case GLFW_KEY_DOWN:
        s->sun.zenith_deg =
            clamp_d(s->sun.zenith_deg + (key == GLFW_KEY_UP ? -sun_step : sun_step), 0.0, 180.0);
        return VIEW_CHANGE_RENDER;
    case GLFW_KEY_LEFT:
    case GLFW_KEY_RIGHT:
        s->sun.azimuth_deg =
            wrap_deg(s->sun.azimuth_deg + (key == GLFW_KEY_RIGHT ? sun_step : -sun_step));
        return VIEW_CHANGE_RENDER;
    case GLFW_KEY_TAB:
        v->mode = v->mode == VIEW_MODE_PREVIEW ? VIEW_MODE_QUALITY : VIEW_MODE_PREVIEW;
        return VIEW_CHANGE_RENDER;
    case GLFW_KEY_0:
        v->scene = v->start;
        return VIEW_CHANGE_RENDER;
    case GLFW_KEY_EQUAL:
    case GLFW_KEY_KP_ADD:
        s->post.exposure = clamp_d(s->post.exposure * EXPOSURE_STEP, 1e-6, 1e9);
        return VIEW_CHANGE_DISPLAY;
    case GLFW_KEY_MINUS:
    case GLFW_KEY_KP_SUBTRACT:
        s->post.exposure = clamp_d(s->post.exposure / EXPOSURE_STEP, 1e-6, 1e9);
        return VIEW_CHANGE_DISPLAY;
    case GLFW_KEY_T:
        s->post.tonemap = (s->post.tonemap + ((mods & VIEW_MOD_SHIFT) ? tonemaps - 1 : 1)) %
                          tonemaps;
        return VIEW_CHANGE_DISPLAY;
    case GLFW_KEY_N:
        v->denoise = !v->denoise;
        return VIEW_CHANGE_DISPLAY;
    case GLFW_KEY_H:
    case GLFW_KEY_F1:
        v->help = !v->help;
        return VIEW_CHANGE_DISPLAY;
    case GLFW_KEY_P:
        return VIEW_CHANGE_SAVE;
    case GLFW_KEY_ESCAPE:
        return VIEW_CHANGE_QUIT;
    default:
        if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9)
            return thesis_view(v, key - GLFW_KEY_0, e);
        return 0;
    }
}
