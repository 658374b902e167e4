/* terrain.frag.glsl - colour: height ramp times Lambert light. Mirrors
 * src/shade.c; the ramp and light come in as uniforms from the same C
 * constants, so the CPU reference and the GPU share one definition. */
#ifdef GL_FRAGMENT_PRECISION_HIGH
precision highp float;
#else
precision mediump float;
#endif

#if FT_ES3
out vec4 o_color;
#define FT_FRAG_COLOR o_color
#else
#define FT_FRAG_COLOR gl_FragColor
#endif

#define FT_RAMP_STOPS 6
uniform float u_ramp_height_m[FT_RAMP_STOPS];
uniform vec3 u_ramp_rgb[FT_RAMP_STOPS];
uniform vec3 u_sun_dir;      /* unit */
uniform vec2 u_light;        /* (ambient, diffuse) */

FT_IN_FS vec3 v_pos_rel_eye_m;
FT_IN_FS vec3 v_normal;
FT_IN_FS float v_height_m;

void main()
{
    vec3 rgb = u_ramp_rgb[FT_RAMP_STOPS - 1];
    for (int i = 0; i < FT_RAMP_STOPS - 1; ++i) {
        /* first segment whose upper stop is at or above the height */
        if (v_height_m <= u_ramp_height_m[i + 1] || i == FT_RAMP_STOPS - 2) {
            float t = clamp((v_height_m - u_ramp_height_m[i]) /
                            (u_ramp_height_m[i + 1] - u_ramp_height_m[i]), 0.0, 1.0);
            rgb = mix(u_ramp_rgb[i], u_ramp_rgb[i + 1], t);
            break;
        }
    }
    float light = u_light.x + u_light.y * max(0.0, dot(normalize(v_normal), u_sun_dir));
    FT_FRAG_COLOR = vec4(clamp(rgb * light, 0.0, 1.0), 1.0);
}
