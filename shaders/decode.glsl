/* decode.glsl - a height from a texel (src/gpu/gpu_texture.h): float textures
 * hold metres in R; packed RGBA8 textures hold 24-bit fixed point over
 * [pack.x, pack.x + pack.y] (pack.y = 0 means float). Included by every
 * shader that reads heights or height bounds. */
float ft_decode(vec4 t, vec2 pack)
{
    if (pack.y > 0.0) {
        float q = dot(floor(t.rgb * 255.0 + 0.5), vec3(65536.0, 256.0, 1.0));
        return pack.x + pack.y * (q / 16777215.0);
    }
    return t.r;
}
