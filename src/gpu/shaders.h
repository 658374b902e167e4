/* shaders.h - GLSL ES sources embedded at build time (tools/embed_shaders.cmake).
 * A program's source = prelude_es2.glsl or prelude_es3.glsl + body. */
#ifndef FT_SHADERS_H
#define FT_SHADERS_H

typedef struct ft_shader_source {
    const char *name; /* file name under shaders/, e.g. "terrain.vert.glsl" */
    const char *text;
} ft_shader_source;

extern const ft_shader_source ft_shader_sources[];
extern const unsigned ft_shader_source_count;

/* NULL if no such embedded file. */
const char *ft_shader_find(const char *name);

#endif
