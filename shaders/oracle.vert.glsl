/* oracle.vert.glsl - the bench's oracle (tools/bench_oracle.h): a static,
 * pre-transformed mesh. Positions relative to the eye, normals and drawn
 * heights were computed on the CPU (src/lod/bintree_mesh.h, the mirror of
 * bintree.vert.glsl); this shader only passes them to the varyings
 * terrain.frag.glsl reads and projects the position. */
precision highp float;

uniform mat4 u_view_proj;

FT_IN_VS vec3 a_pos_rel_eye_m;
FT_IN_VS vec3 a_normal;
FT_IN_VS float a_height_m;

FT_OUT_VS vec3 v_pos_rel_eye_m;
FT_OUT_VS vec3 v_normal;
FT_OUT_VS float v_height_m;

void main()
{
    v_pos_rel_eye_m = a_pos_rel_eye_m;
    v_normal = a_normal;
    v_height_m = a_height_m;
    gl_Position = u_view_proj * vec4(a_pos_rel_eye_m, 1.0);
}
