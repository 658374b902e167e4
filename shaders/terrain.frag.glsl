/* terrain.frag.glsl - the terrain colour (shade.glsl) of the height and
 * normal the method drew. */
#ifdef GL_FRAGMENT_PRECISION_HIGH
precision highp float;
#else
precision mediump float;
#endif

#include "frag_out.glsl"

/* pgrid's picture pass also writes its error buffer (a second colour
 * attachment, GLES 3): one draw of the grid instead of two */
#ifndef FT_PGRID_ERR_OUT
#define FT_PGRID_ERR_OUT 0
#endif
#ifndef FT_PGRID_FLAT_DELTA
#define FT_PGRID_FLAT_DELTA 0
#endif
#if FT_PGRID_ERR_OUT && FT_ES3
#include "pgrid_err_code.glsl"
layout(location = 1) out vec4 o_pgrid_err;
FT_IN_FS float v_col_t; /* the grid column's t (the column warp) */
#if FT_PGRID_FLAT_DELTA
flat in float v_delta_m; /* the tight bound's: one a quad (src/lod/pgrid.h 6) */
#else
FT_IN_FS float v_delta_m;
#endif
#endif

#include "shade_relative.glsl"
#include "shade_grid.glsl"
#include "shade_haze.glsl"
#include "shade.glsl"

FT_IN_FS vec3 v_pos_rel_eye_m;
FT_IN_FS vec3 v_normal;
FT_IN_FS float v_height_m;

void main()
{
    FT_FRAG_COLOR = ft_colour(v_height_m, v_normal, v_pos_rel_eye_m);
#if FT_PGRID_ERR_OUT && FT_ES3
    o_pgrid_err = ft_pgrid_err_texel(v_pos_rel_eye_m, v_delta_m, v_col_t);
#endif
}
