/* view_controls.h — keys and mouse to changes of the viewer's scene (view_controls.c). */
#ifndef ATMO_VIEW_CONTROLS_H
#define ATMO_VIEW_CONTROLS_H
#include "atmo/scene.h"
#include "atmo/status.h"

typedef struct view_state {
    atmo_scene scene;        /* the user's scene: current camera, sun and post */
    atmo_scene start;        /* the scene the viewer started with (key 0) */
    const char *const *sets; /* the user's --set assignments, reapplied over thesis views */
    int set_count;
    int mode;                /* VIEW_MODE_* */
    int help;                /* the overlay is shown */
    int denoise;             /* N: the display shows the frame denoised while it has few
                                samples (view_denoise.c) */
} view_state;

/* What a control changed (bit flags). */
enum {
    VIEW_CHANGE_RENDER = 1,  /* camera, sun, mode or scene: restart the accumulation */
    VIEW_CHANGE_DISPLAY = 2, /* exposure, tone mapper, overlay: redraw only */
    VIEW_CHANGE_SAVE = 4,    /* P */
    VIEW_CHANGE_QUIT = 8     /* Esc */
};

/* Modifier bits of a key press or a held movement (GLFW's values). */
#define VIEW_MOD_SHIFT 1
#define VIEW_MOD_CONTROL 2

/* The speed of WASD/QE movement at the camera's altitude: 0.5 per second times the altitude
 * above the ground (at least 10 m), times 10 with Shift, 0.1 with Control. */
double view_speed_m_per_s(const atmo_scene *s, int mods);
/* Altitude of the camera above the ground sphere, in metres. */
double view_altitude_m(const atmo_scene *s);

/* A key press (GLFW key code and modifier bits): VIEW_CHANGE_* flags. Thesis views that cannot
 * be loaded leave the scene as it was and set e (the caller shows the message). */
int view_controls_key(view_state *v, int key, int mods, atmo_err *e);
/* Movement for dt seconds with the movement keys held: forward (W +1, S -1), right (D +1,
 * A -1), up (E +1, Q -1). VIEW_CHANGE_RENDER when the camera moved. */
int view_controls_move(view_state *v, int forward, int right, int up, int mods, double dt);
/* A mouse drag of (dx, dy) window pixels turns the camera; a scroll of dy notches zooms. */
int view_controls_look(view_state *v, double dx, double dy);
int view_controls_zoom(view_state *v, double notches);


#endif
