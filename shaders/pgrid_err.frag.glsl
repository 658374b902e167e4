/* pgrid_err.frag.glsl - the error buffer of method 'pgrid' (src/lod/pgrid.h 3),
 * drawn on its own: the position pass of a view the picture did not see,
 * GLES 2, and (FT_PGRID_ERR_LOCATION 1) the envelopes drawn into the picture's
 * framebuffer, whose error buffer is its second colour attachment. */
#ifdef GL_FRAGMENT_PRECISION_HIGH
precision highp float;
#else
precision mediump float;
#endif

#ifndef FT_PGRID_FLAT_DELTA
#define FT_PGRID_FLAT_DELTA 0
#endif
#ifndef FT_PGRID_ERR_LOCATION
#define FT_PGRID_ERR_LOCATION 0
#endif
#if FT_ES3
layout(location = FT_PGRID_ERR_LOCATION) out vec4 o_err;
#define FT_ERR_OUT o_err
#else
#define FT_ERR_OUT gl_FragColor
#endif

#include "pgrid_err_code.glsl"

FT_IN_FS vec3 v_pos_rel_eye_m;
FT_IN_FS vec3 v_normal;
FT_IN_FS float v_height_m;
FT_IN_FS float v_col_t;
#if FT_PGRID_FLAT_DELTA && FT_ES3
/* the tight bound's (src/lod/pgrid.h 6): a mesh pixel's its quad's, an
 * envelope pixel's the vertices' delta, interpolated */
flat in float v_delta_m;
in float v_env_delta_m;
uniform float u_pgrid_envelope;
#define FT_PIXEL_DELTA_M (u_pgrid_envelope != 0.0 ? v_env_delta_m : v_delta_m)
#else
FT_IN_FS float v_delta_m;
#define FT_PIXEL_DELTA_M v_delta_m
#endif

void main()
{
    FT_ERR_OUT = ft_pgrid_err_texel(v_pos_rel_eye_m, FT_PIXEL_DELTA_M, v_col_t);
}
