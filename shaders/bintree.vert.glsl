/* bintree.vert.glsl - one triangular tile of the bintree, drawn from the one
 * template every tile shares (the unit right triangle bisected 2k times).
 *
 * a_uv.xy are the template vertex's leg coordinates (a, b), multiples of 2^-k:
 *   grid = apex + a * (left - apex) + b * (right - apex)
 * an exact integer grid coordinate for every tile the selection emits, so
 * every tile that holds a grid vertex computes the same coordinate. The CPU
 * sends two corners a tile, u_bt_tiles[slot] = (apex, left) with slot =
 * a_uv.z, a batch of tiles a draw (src/lod/method_bintree.c); every tile is a
 * right isosceles triangle with the roots' counter-clockwise turn, so
 * right - apex is left - apex turned a quarter counter-clockwise (exact).
 *
 * Geomorphing is a function of the grid vertex alone (src/lod/bintree.c,
 * ft_bt_diamond_q and ft_bt_morph_weight, is the same rule on the CPU): the
 * vertex is the midpoint of a coarse edge e0-e1 and enters the mesh when one
 * diamond c splits; its height slides from (h(e0) + h(e1)) / 2 to h(g) with
 * weight clamp(2 Q / W + 1, 0, 1), Q = K (err + chord) gain / tau - d over
 * c's box (bintree.h: d the distance from the eye to the box, gain the
 * pixels a vertical metre covers bounded over its corners, view_scale.h),
 * W = morph_width x c's square side. A parent's Q is at least its child's
 * + W, so the endpoints of a moving vertex are at their own heights: the
 * coarse height is the drawn edge's midpoint and a split never pops. Every tile that draws the vertex
 * computes the same position from the same inputs: no cracks, even
 * mid-morph.
 *
 * Sub-sample levels (bintree.subsample_levels S > 0): tile coordinates are
 * in fine units (2^-S of a cell). A vertex on a sample reads it; a vertex
 * between samples takes the bilinear height of its cell (the cell is the
 * floor of its coordinate, clamped into the grid; the same arithmetic as
 * ft_bt_height_fine on the CPU, exact for integer heights). Its morph
 * endpoints lie in the same cell, its normal is the cell's gradient there,
 * and the error of the diamond that inserts it is the closed form of
 * src/lod/bintree.c (sub_q x the largest twist over the diamond's closure, from
 * <= 4 texels of the twist atlas).
 *
 * GLES 3: a vertex on a sample does two fetches, its texel of the vertex
 * table (src/lod/bintree.h, ft_bt_sample_texel: height, the morph's coarse
 * height, -1 when it never morphs, a 12+12-bit hemi-octahedral normal) and
 * its diamond's texel (error and height range), and no search; the lowest
 * set bit of a coordinate is integer arithmetic. GLES 2 (and GLES 3 with
 * bintree.vertex_table = 0) reads the samples, the diamond texel and the
 * normal's four neighbours.
 *
 * Padding: coordinates are clamped into the real grid; clamped vertices do
 * not morph. All arithmetic on grid coordinates is on integers below 2^24
 * (exact in highp float; divisions are by powers of two). */

precision highp float;

/* Compile-time variants (src/lod/method.c, ft_method_vertex_defines): the code a
 * scene does not use is not in its shader. A branch costs its time on a SIMD
 * rasteriser even when no vertex takes it, so this is also speed. */
#ifndef FT_BT_SUB
#define FT_BT_SUB 1 /* bintree.subsample_levels > 0 */
#endif
#ifndef FT_BT_VTX
#define FT_BT_VTX 0 /* bintree.vertex_table (GLES 3) */
#endif
#ifndef FT_BT_BATCH
#define FT_BT_BATCH 64 /* tiles a draw */
#endif

#include "curvature.glsl"

uniform sampler2D u_heights;
uniform vec2 u_grid_size;
uniform vec2 u_cell_m;
uniform vec3 u_origin_rel_eye_m;
uniform mat4 u_view_proj;
uniform vec2 u_pack;

uniform highp sampler2D u_bt_dia; /* per lattice diamond: (saturated error, box z0, z1) (m) */
uniform highp sampler2D u_bt_zb;  /* S > 0: (min, max) height of aligned blocks of cells */
uniform vec4 u_bt_gap;        /* (morph_width, metres per fine unit, block side in cells, 0) */
uniform vec3 u_bt_lattice;    /* (2^k, lattice side, N 2^S: the domain in fine units) */
uniform vec4 u_bt_morph;      /* (K px, tau px, 0, on) */
uniform vec3 u_bt_axis;       /* view axis (world, unit) */
uniform vec2 u_bt_gain_cap;   /* largest A and B over the image (core/view_scale.h) */
uniform vec4 u_bt_sub;        /* (2^S, 2^(k+S): table lattice step in fine units,
                                 twist levels, 1 if S > 0) */
uniform sampler2D u_bt_twist; /* twist atlas (S > 0) */
uniform vec4 u_bt_twist_pack; /* (pack like u_pack, atlas width, height) */
uniform vec2 u_bt_twist_off[9]; /* atlas origin of each twist level */
#if FT_ES3 && FT_BT_VTX
uniform highp sampler2D u_bt_vtx; /* the one-fetch vertex table (src/lod/bintree.h) */
#endif

FT_IN_VS vec3 a_uv; /* (a, b, slot) */
uniform vec4 u_bt_tiles[FT_BT_BATCH]; /* per slot: apex.xy, left.xy (fine units) */

FT_OUT_VS vec3 v_pos_rel_eye_m;
FT_OUT_VS vec3 v_normal;
FT_OUT_VS float v_height_m;
FT_OUT_VS float v_morph; /* 1 = at its own height (captured by the crack tests) */

#include "decode.glsl"

/* A sample (grid coordinates, clamped into the grid). */
float ft_height(vec2 g)
{
    vec2 gc = clamp(g, vec2(0.0), u_grid_size - 1.0);
#if FT_ES3
    vec4 t = texelFetch(u_heights, ivec2(gc), 0);
#else
    vec4 t = texture2DLod(u_heights, (gc + 0.5) / u_grid_size, 0.0);
#endif
    return ft_decode(t, u_pack);
}

/* The bilinear surface of a cell (corner heights h = (h00, h10, h01, h11))
 * at fine point g; cf = the cell's corner in fine units, f = 2^S. */
float ft_bilinear(vec4 h, vec2 cf, vec2 g)
{
    vec2 uv = (g - cf) / u_bt_sub.x;
    return h.x + (h.y - h.x) * uv.x + (h.z - h.x) * uv.y + ((h.x + h.w) - (h.y + h.z)) * uv.x * uv.y;
}

#if FT_BT_SUB
float ft_twist_texel(vec2 p)
{
#if FT_ES3
    vec4 t = texelFetch(u_bt_twist, ivec2(p), 0);
#else
    vec4 t = texture2DLod(u_bt_twist, (p + 0.5) / u_bt_twist_pack.zw, 0.0);
#endif
    return ft_decode(t, u_bt_twist_pack.xy);
}

vec2 ft_zblock(vec2 b)
{
#if FT_ES3
    return texelFetch(u_bt_zb, ivec2(b), 0).xy;
#else
    vec2 n = ceil((u_grid_size - 1.0) / u_bt_gap.z);
    return texture2DLod(u_bt_zb, (b + 0.5) / n, 0.0).xy;
#endif
}

/* Closed form below the samples (src/lod/bintree.c, ft_bt_sub_error):
 * split vertex c, square side sd (fine units), even level when c is a
 * square's centre: (error, raw height range of its closure). */
vec3 ft_sub_diamond(vec2 c, float sd, bool even_level)
{
    float f = u_bt_sub.x;
    float a = sd / (u_bt_lattice.x * f); /* its template squares' side, cells */
    float leg = even_level ? a : 0.5 * a;
    float r = even_level ? 1.5 * sd : sd;
    vec2 lo = clamp((c - r) / f, vec2(0.0), u_grid_size - 1.0);
    vec2 hi = clamp((c + r) / f, vec2(0.0), u_grid_size - 1.0);
    vec2 c0 = clamp(floor(lo), vec2(0.0), u_grid_size - 2.0);
    vec2 c1 = clamp(ceil(hi) - 1.0, c0, u_grid_size - 2.0);
    float span = max(c1.x - c0.x, c1.y - c0.y) + 1.0;
    float m = 0.0;
    float bs = 1.0;
    for (int i = 0; i < 16; ++i) {
        if (bs >= span || m >= u_bt_sub.z - 1.0) {
            break;
        }
        bs *= 2.0;
        m += 1.0;
    }
    /* the closure spans at most 2 blocks a side at this level */
    vec2 b0 = floor(c0 / bs), b1 = floor(c1 / bs);
    vec2 off = u_bt_twist_off[int(m)];
    float d = ft_twist_texel(off + b0);
    d = max(d, ft_twist_texel(off + vec2(b1.x, b0.y)));
    d = max(d, ft_twist_texel(off + vec2(b0.x, b1.y)));
    d = max(d, ft_twist_texel(off + b1));
    /* its height range: the <= 2 x 2 height blocks under the same cells */
    vec2 z0 = floor(c0 / u_bt_gap.z), z1 = floor(c1 / u_bt_gap.z);
    vec2 za = ft_zblock(z0), zb = ft_zblock(vec2(z1.x, z0.y));
    vec2 zc = ft_zblock(vec2(z0.x, z1.y)), zd = ft_zblock(z1);
    float zlo = min(min(za.x, zb.x), min(zc.x, zd.x));
    float zhi = max(max(za.y, zb.y), max(zc.y, zd.y));
    return vec3(0.25 * leg * leg * d, zlo, zhi);
}
#endif

/* The inserting diamond of vertex g (fine units): the coarse edge e0-e1 it
 * bisects, the diamond's split vertex c and square side sd (fine units),
 * even when c is a square's centre. False when g never morphs. */
bool ft_insertion(vec2 g, out vec2 e0, out vec2 e1, out vec2 c, out float sd, out bool even_level)
{
    e0 = g;
    e1 = g;
    c = g;
    sd = 0.0;
    even_level = false;
    /* s: the lowest power of two that does not divide both coordinates */
#if FT_ES3
    int gi = int(g.x) | int(g.y);
    float s = float(gi & -gi);
#else
    float s = 0.0;
    float p = 1.0;
    for (int i = 0; i < 20; ++i) {
        if (mod(g.x, 2.0 * p) != 0.0 || mod(g.y, 2.0 * p) != 0.0) {
            s = p;
            break;
        }
        p *= 2.0;
    }
#endif
    sd = 2.0 * s * u_bt_lattice.x; /* square side of the inserting diamond */
    if (s == 0.0 || sd > u_bt_lattice.z) {
        return false;
    }
    bool odd_x = mod(g.x, 2.0 * s) != 0.0;
    bool odd_y = mod(g.y, 2.0 * s) != 0.0;
    even_level = odd_x && odd_y;
    vec2 base = floor(g / sd) * sd;
    if (even_level) {
        vec2 q = (g - s) / (2.0 * s);
        float dy = (mod(q.x + q.y, 2.0) == 0.0) ? s : -s;
        e0 = g - vec2(s, dy);
        e1 = g + vec2(s, dy);
        c = base + 0.5 * sd;
    } else {
        vec2 d = odd_x ? vec2(s, 0.0) : vec2(0.0, s);
        e0 = g - d;
        e1 = g + d;
        vec2 r = g - base;
        if (r.y <= r.x && r.y <= sd - r.x) {
            c = base + vec2(0.5 * sd, 0.0);
        } else if (r.y >= r.x && r.y >= sd - r.x) {
            c = base + vec2(0.5 * sd, sd);
        } else if (r.x <= r.y && r.x <= sd - r.y) {
            c = base + vec2(0.0, 0.5 * sd);
        } else {
            c = base + vec2(sd, 0.5 * sd);
        }
    }
    vec2 top = max(g, max(e0, e1));
    if (top.x > (u_grid_size.x - 1.0) * u_bt_sub.x || top.y > (u_grid_size.y - 1.0) * u_bt_sub.x) {
        e0 = g;
        e1 = g;
        return false;
    }
    return true;
}

/* The lattice diamond at split vertex c (fine units): (error, box z0, z1). */
vec3 ft_lattice_diamond(vec2 c)
{
    vec2 lc = c / u_bt_sub.y;
#if FT_ES3
    return texelFetch(u_bt_dia, ivec2(lc), 0).xyz;
#else
    return texture2DLod(u_bt_dia, (lc + 0.5) / u_bt_lattice.y, 0.0).xyz;
#endif
}

/* (error, box z0, z1) of the diamond at c: the lattice texel, or below the
 * samples the closed form with its z range widened by the box margin. */
vec3 ft_diamond(vec2 c, float sd, bool even_level)
{
#if FT_BT_SUB
    vec2 lc = c / u_bt_sub.y;
    if (lc != floor(lc)) {
        vec3 d = ft_sub_diamond(c, sd, even_level);
        float mz = (even_level ? 3.0 : 2.0) * u_bt_gap.x * sd * u_bt_gap.y;
        return vec3(d.x, d.y - mz, d.z + mz);
    }
#endif
    return ft_lattice_diamond(c);
}

/* The vertical gain's factors at box corner p (relative to the eye),
 * squared, into ab2 = (max A^2, max B^2) (src/core/view_scale.c: A Z =
 * sqrt(|p_h|^2 - (p_x f_y - p_y f_x)^2), B = |p| / Z); bad: p at or behind
 * the eye. */
void ft_corner(vec3 p, inout vec2 ab2, inout bool bad)
{
    float z = dot(p, u_bt_axis);
    if (!(z > 0.0)) {
        bad = true;
    } else {
        float c = p.x * u_bt_axis.y - p.y * u_bt_axis.x;
        float z2 = z * z;
        ab2 = max(ab2, vec2(max(dot(p.xy, p.xy) - c * c, 0.0) / z2, dot(p, p) / z2));
    }
}

/* Morph weight of the vertices diamond c inserts (src/lod/bintree.c,
 * ft_bt_diamond_q): its box is the closure widened by the margin (xy) and
 * the height range d.yz, drawn on the curved earth. */
float ft_morph_weight(vec2 c, float sd, bool even_level, vec3 d)
{
    float f = u_bt_sub.x;
    float r = (even_level ? 1.5 + 3.0 * u_bt_gap.x : 1.0 + 2.0 * u_bt_gap.x) * sd;
    vec3 lo = u_origin_rel_eye_m + vec3((c - r) / f * u_cell_m, d.y);
    vec3 hi = u_origin_rel_eye_m + vec3((c + r) / f * u_cell_m, d.z);
    vec2 near_xy = max(max(lo.xy, -hi.xy), vec2(0.0));
    vec2 far_xy = max(abs(lo.xy), abs(hi.xy));
    lo.z -= u_earth_drop_per_m2 * dot(far_xy, far_xy);
    hi.z -= u_earth_drop_per_m2 * dot(near_xy, near_xy);
    float dist = length(max(max(lo, -hi), vec3(0.0)));
    vec2 ext = hi.xy - lo.xy;
    float e = d.x + 0.25 * u_earth_drop_per_m2 * dot(ext, ext);
    if (!(e > 0.0)) {
        return 0.0;
    }
    if (!(dist > 0.0)) {
        return 1.0;
    }
    vec2 ab2 = vec2(0.0, 1.0);
    bool bad = false;
    ft_corner(lo, ab2, bad);
    ft_corner(vec3(hi.x, lo.y, lo.z), ab2, bad);
    ft_corner(vec3(lo.x, hi.y, lo.z), ab2, bad);
    ft_corner(vec3(hi.x, hi.y, lo.z), ab2, bad);
    ft_corner(vec3(lo.x, lo.y, hi.z), ab2, bad);
    ft_corner(vec3(hi.x, lo.y, hi.z), ab2, bad);
    ft_corner(vec3(lo.x, hi.y, hi.z), ab2, bad);
    ft_corner(hi, ab2, bad);
    vec2 ab = bad ? u_bt_gain_cap : min(sqrt(ab2), u_bt_gain_cap);
    float gain = ab.x * ab.y;
    float q = u_bt_morph.x * e * gain / u_bt_morph.y - dist;
    float w_m = u_bt_gap.x * sd * u_bt_gap.y;
    return clamp(2.0 * q / w_m + 1.0, 0.0, 1.0);
}

/* The outputs of a vertex at grid point gs with drawn height h, morph w. */
void ft_emit(vec2 gs, float h, float w)
{
    v_morph = w;
    v_height_m = h;
    v_pos_rel_eye_m = ft_earth_curve(u_origin_rel_eye_m + vec3(gs * u_cell_m, h));
    gl_Position = u_view_proj * vec4(v_pos_rel_eye_m, 1.0);
}

#if FT_ES3 && FT_BT_VTX
/* A vertex on a sample, two fetches: height, coarse height, normal, then its
 * inserting diamond. moved: the padding clamp moved it (no morph). */
void ft_sample_vertex(vec2 gs, bool moved)
{
    vec4 vt = texelFetch(u_bt_vtx, ivec2(gs), 0);
    float h = vt.x;
    float qu = floor(vt.w / 4096.0); /* hemi-octahedral (u, v), 12 bits each */
    vec2 uv = vec2(qu, vt.w - qu * 4096.0) / 4095.0 * 2.0 - 1.0;
    vec2 nxy = 0.5 * vec2(uv.x + uv.y, uv.x - uv.y);
    v_normal = normalize(vec3(nxy, 1.0 - abs(nxy.x) - abs(nxy.y)));
    float w = 1.0;
    if (u_bt_morph.w > 0.5 && vt.z >= 0.0 && !moved) {
        vec2 e0, e1, c;
        float sd;
        bool even_level;
        if (ft_insertion(gs * u_bt_sub.x, e0, e1, c, sd, even_level)) {
            w = ft_morph_weight(c, sd, even_level, ft_lattice_diamond(c));
            h = mix(vt.y, h, w);
        }
    }
    ft_emit(gs, h, w);
}
#endif

/* Any vertex, from the samples, the error table and (S > 0) the twist atlas. */
void ft_general_vertex(vec2 g_raw, vec2 g, vec2 gs, bool on_sample)
{
    float f = u_bt_sub.x;
    float h;
    vec4 cell = vec4(0.0); /* corner heights of a sub-sample vertex's cell */
    vec2 cf = vec2(0.0);   /* that cell's corner, fine units */
#if FT_BT_SUB
    if (on_sample) {
#endif
        h = ft_height(gs);
        vec2 lo = max(gs - 1.0, vec2(0.0));
        vec2 hi = min(gs + 1.0, u_grid_size - 1.0);
        float dhx = (ft_height(vec2(hi.x, gs.y)) - ft_height(vec2(lo.x, gs.y))) / ((hi.x - lo.x) * u_cell_m.x);
        float dhy = (ft_height(vec2(gs.x, hi.y)) - ft_height(vec2(gs.x, lo.y))) / ((hi.y - lo.y) * u_cell_m.y);
        v_normal = normalize(vec3(-dhx, -dhy, 1.0));
#if FT_BT_SUB
    } else {
        vec2 c = clamp(floor(gs), vec2(0.0), u_grid_size - 2.0);
        cell = vec4(ft_height(c), ft_height(c + vec2(1.0, 0.0)), ft_height(c + vec2(0.0, 1.0)),
                    ft_height(c + vec2(1.0, 1.0)));
        cf = c * f;
        h = ft_bilinear(cell, cf, g);
        vec2 uv = gs - c;
        float tw = (cell.x + cell.w) - (cell.y + cell.z);
        float dhx = ((cell.y - cell.x) + tw * uv.y) / u_cell_m.x;
        float dhy = ((cell.z - cell.x) + tw * uv.x) / u_cell_m.y;
        v_normal = normalize(vec3(-dhx, -dhy, 1.0));
    }
#endif

    float w = 1.0;
    if (u_bt_morph.w > 0.5) {
        vec2 e0, e1, c;
        float sd;
        bool even_level;
        if (ft_insertion(g_raw, e0, e1, c, sd, even_level)) {
            w = ft_morph_weight(c, sd, even_level, ft_diamond(c, sd, even_level));
#if FT_BT_SUB
            /* a sub-sample vertex's coarse edge lies in its own cell */
            float h0 = on_sample ? ft_height(e0 / f) : ft_bilinear(cell, cf, e0);
            float h1 = on_sample ? ft_height(e1 / f) : ft_bilinear(cell, cf, e1);
#else
            float h0 = ft_height(e0 / f);
            float h1 = ft_height(e1 / f);
#endif
            h = mix(0.5 * (h0 + h1), h, w);
        }
    }
    ft_emit(gs, h, w);
}

void main()
{
    vec4 tile = u_bt_tiles[int(a_uv.z)];
    vec2 apex = tile.xy;
    vec2 leg = tile.zw - apex;
    vec2 g_raw = apex + a_uv.x * leg + a_uv.y * vec2(-leg.y, leg.x);
    float f = u_bt_sub.x;
    vec2 g = min(g_raw, (u_grid_size - 1.0) * f); /* padding collapses onto the grid edge */
    vec2 gs = g / f;                              /* grid coordinates */
#if FT_ES3 && FT_BT_VTX && FT_BT_SUB
    if (gs == floor(gs)) {
        ft_sample_vertex(gs, g_raw != g);
    } else {
        ft_general_vertex(g_raw, g, gs, false);
    }
#elif FT_ES3 && FT_BT_VTX
    ft_sample_vertex(gs, g_raw != g); /* without sub-sample levels every vertex is on a sample */
#else
    ft_general_vertex(g_raw, g, gs, gs == floor(gs));
#endif
}
