/* view_shader.h — the viewer's GLSL sources (view_shader.c). */
#ifndef ATMO_VIEW_SHADER_H
#define ATMO_VIEW_SHADER_H

/* Prefixes that make the sources below GLSL 3.30 core or GLSL 1.20 (OpenGL 2.1). */
extern const char view_glsl_core[];
extern const char view_glsl_legacy[];

/* The image: a quad over the viewport rectangle, the linear texture tone mapped per pixel. */
extern const char view_glsl_image_vertex[];
extern const char view_glsl_image_fragment[];
/* The overlay: solid-coloured triangles in window pixels. */
extern const char view_glsl_text_vertex[];
extern const char view_glsl_text_fragment[];

#endif
