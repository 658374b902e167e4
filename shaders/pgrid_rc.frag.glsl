/* pgrid_rc.frag.glsl - method 'pgrid': ray casting of the pixels whose
 * (3 x 3 dilated) error code reaches u_rc_thr (src/lod/pgrid.h 4), GLES 3 only.
 * Drawn per screen tile (shaders/pgrid_rc.vert.glsl): only the tiles that
 * hold such a pixel reach this shader.
 *
 * The ray through the pixel centre is cast against the bilinear height
 * field in grid coordinates (x, y in cells from sample (0, 0), z metres),
 * the same surface src/measure/reference.c intersects: a max-mip traversal of the
 * max pyramid (levels >= 1 from the ray caster's max atlas, level 0 = the
 * cell's 4 samples) skips every texel box the ray passes above; at level 0
 * the ray's height minus the bilinear patch along it is a quadratic in t,
 * solved in closed form for its first root in the cell. Output: colour
 * (shade.glsl, as terrain.frag.glsl) or the position (xyz rel. eye, w 1)
 * and gl_FragDepth of the hit; a miss writes the sky (u_rc_sky, depth 1).
 * Pixels under the threshold are discarded, so the mesh stays there.
 * Bounded loop (FT_RC_STEPS visits).
 * The loop is written for a SIMD rasteriser (llvmpipe) that runs every
 * branch of a loop body under a lane mask whether or not a lane takes it:
 * each visit makes the same 5 fetches (the cell's 4 samples, which are the
 * level-0 texel and the cell solve's input, and one atlas texel), and the
 * rare bisection of a root lost to round-off runs once, after the loop.
 * Over the clipmap cache (FT_RC_CLIP, pgrid.heights = clipmap): the ray is
 * cast in level-0 samples from the eye, and the max-mip is the cache's own
 * levels: a node is a cell of cache level L, its max the hi of the cell's
 * range of the finest data (lod/clip_levels.h FT_CLIP_BOUNDS_RANGES), its
 * children the level L - 1 cells under it. A node the finer level does not
 * hold is a leaf: the ray meets that level's bilinear surface there, which
 * departs from the finest data by at most the level's deviation; the frame
 * reports that error from the CPU's block bounds (src/lod/pgrid.h 7). Where
 * a level holds nothing the walk goes up (the coarsest level holds what is
 * drawn).
 * Earth curvature (src/terrain/terrain.h): the terrain r metres from the eye is
 * drawn k r^2 lower; the ray is bent up by the same amount instead,
 * z(t) = o.z + d.z t + bend t^2 with bend = k |dw.xy|^2, as
 * src/measure/reference.c does: the cell solve stays a quadratic and the ray's z
 * over a texel is convex (its minimum at an end or at -d.z / (2 bend)). */
#ifdef GL_FRAGMENT_PRECISION_HIGH
precision highp float;
#else
precision mediump float;
#endif

#if FT_ES3
out vec4 o_color;

#define FT_RC_STEPS 4096
#define FT_LEVELS 16

uniform sampler2D u_err;          /* the error buffer (G = code) */
uniform float u_rc_thr;           /* code threshold (0..255) */
#ifdef FT_RC_CLIP
/* the cache (shaders/pgm_grid.glsl names: the same values pgm's grid gets) */
uniform highp sampler2D u_pgm_atlas;   /* heights, level L at block (L mod cols, L / cols) */
uniform vec2 u_pgm_atlas_pack;
uniform vec4 u_pgm_level[FT_LEVELS];   /* (base mod side, eye - base 2^L in level-0 samples) */
uniform vec4 u_pcm_box[FT_LEVELS];     /* resident samples from base, inclusive */
uniform vec4 u_pcm_clamp;              /* what is drawn, m from the eye */
uniform vec4 u_pcm_misc;               /* (side, transition samples, levels, atlas columns) */
uniform highp sampler2D u_pgrid_range; /* per cell (lo, hi) of the finest data */
#else
uniform sampler2D u_heights;
uniform vec2 u_pack;
uniform vec2 u_grid_size;
uniform sampler2D u_rc_max;       /* max pyramid levels >= 1 (src/lod/pgrid.h 4) */
uniform vec4 u_rc_max_level[FT_LEVELS]; /* origin xy, size zw per level (level 0: size) */
#endif
uniform float u_rc_levels;
uniform vec3 u_rc_eye_g;          /* eye in ray coordinates (x, y samples, z m) */
uniform vec2 u_cell_m;
uniform vec3 u_rc_fwd, u_rc_right, u_rc_up; /* camera frame (world) */
uniform vec3 u_rc_tan;            /* (tan half fov x, tan half fov y, 0) */
uniform vec2 u_rc_size;           /* viewport px */
uniform mat4 u_view_proj;
uniform float u_rc_mode;          /* 0 colour, 1 position */
uniform vec4 u_rc_sky;
uniform float u_earth_drop_per_m2; /* k: 1 / (2 R) or 0 */

#include "decode.glsl"
#include "shade_relative.glsl"
#include "shade_grid.glsl"
#include "shade_haze.glsl"
#include "shade.glsl"

#ifndef FT_RC_CLIP
float hs(vec2 ij)
{
    ivec2 q = ivec2(clamp(ij, vec2(0.0), u_grid_size - 1.0));
    return ft_decode(texelFetch(u_heights, q, 0), u_pack);
}

/* bilinear height at grid point g (clamped into the grid) */
float ft_surface_at(vec2 g)
{
    vec2 gc = clamp(g, vec2(0.0), u_grid_size - 1.0);
    vec2 ij = min(floor(gc), max(u_grid_size - 2.0, vec2(0.0)));
    vec2 f = gc - ij;
    float h00 = hs(ij), h10 = hs(ij + vec2(1.0, 0.0));
    float h01 = hs(ij + vec2(0.0, 1.0)), h11 = hs(ij + 1.0);
    return mix(mix(h00, h10, f.x), mix(h01, h11, f.x), f.y);
}

/* max of level L >= 1 texel (i, j), from the atlas (L clamped to >= 1: the
 * caller takes level 0 from the cell's samples) */
float atlas_max(float level, vec2 ij)
{
    vec4 lv = u_rc_max_level[int(max(level, 1.0))];
    vec2 o = lv.xy + clamp(ij, vec2(0.0), lv.zw - 1.0);
    return ft_decode(texelFetch(u_rc_max, ivec2(o), 0), u_pack); /* the same format */
}

/* The node (texel of pyramid level `level`) that holds ray point p, entered
 * along d: its texel c, its box [lo, hi] in ray coordinates; the grid holds
 * every node (p is clamped into it). */
bool ft_node(float level, vec2 p, vec2 d, out vec2 c, out vec2 lo, out vec2 hi)
{
    vec2 gmax = u_grid_size - 1.0;
    float sc = exp2(level);
    vec2 g = clamp(p, vec2(0.0), gmax);
    c = floor(g / sc);
    if (d.x < 0.0 && g.x == c.x * sc && c.x > 0.0) c.x -= 1.0;
    if (d.y < 0.0 && g.y == c.y * sc && c.y > 0.0) c.y -= 1.0;
    vec2 cellmax = vec2(floor((gmax.x - 1.0) / sc), floor((gmax.y - 1.0) / sc));
    c = clamp(c, vec2(0.0), max(cellmax, vec2(0.0)));
    lo = c * sc;
    hi = min((c + 1.0) * sc, gmax);
    return true;
}

/* The same fetches on every visit: the samples of level-0 cell c (the leaf
 * texel; at higher levels a cell of the texel, unused) and the atlas texel;
 * .xyzw = h00, h10, h01, h11, and the node's max. */
vec4 ft_node_heights(float level, vec2 c, out float zmax)
{
    vec2 c0 = min(c, max(u_grid_size - 2.0, vec2(0.0)));
    vec4 h = vec4(hs(c0), hs(c0 + vec2(1.0, 0.0)), hs(c0 + vec2(0.0, 1.0)), hs(c0 + 1.0));
    float zatlas = atlas_max(level, c);
    zmax = (level < 0.5) ? max(max(h.x, h.y), max(h.z, h.w)) : zatlas;
    return h;
}

/* Below a node the ray meets: its children, down to the samples. */
bool ft_descend(float level, vec2 p)
{
    return level > 0.5;
}

/* The ray in the leaf level's cell units (level 0: the grid's own). */
void ft_leaf_ray(float level, vec3 o, vec3 d, out vec3 ok, out vec3 dk)
{
    ok = o;
    dk = d;
}
#else
/* The atlas texel of level `level`'s sample a (from its base): heights and
 * cell ranges share the layout. */
ivec2 ft_cache_texel(float level, vec2 a)
{
    vec4 lv = u_pgm_level[int(level)];
    float side = u_pcm_misc.x;
    vec2 block = vec2(mod(level, u_pcm_misc.w), floor(level / u_pcm_misc.w));
    return ivec2(block * side + mod(lv.xy + a, side));
}

float ft_texel(float level, vec2 a)
{
    return ft_decode(texelFetch(u_pgm_atlas, ft_cache_texel(level, a), 0), u_pgm_atlas_pack);
}

float ft_range_hi(float level, vec2 a)
{
    return texelFetch(u_pgrid_range, ft_cache_texel(level, a), 0).y;
}

/* Level `level`'s units (its samples from its base) of ray point p. */
vec2 ft_level_xy(float level, vec2 p)
{
    return (p + u_pgm_level[int(level)].zw) / exp2(level);
}

/* 1 when level `level` holds cells around ray point p: p is inside its
 * resident samples' box, which spans at least one cell. */
bool ft_level_holds(float level, vec2 p)
{
    vec4 b = u_pcm_box[int(level)];
    vec2 u = ft_level_xy(level, p);
    return b.z > b.x && b.w > b.y && all(greaterThanEqual(u, b.xy)) && all(lessThanEqual(u, b.zw));
}

/* The node (cell of cache level `level`) that holds ray point p, entered
 * along d: its cell c (level samples from base), its box [lo, hi] in ray
 * coordinates; false when the level does not hold p. */
bool ft_node(float level, vec2 p, vec2 d, out vec2 c, out vec2 lo, out vec2 hi)
{
    vec4 b = u_pcm_box[int(level)];
    float sc = exp2(level);
    vec2 u = ft_level_xy(level, p);
    c = floor(u);
    if (d.x < 0.0 && u.x == c.x) c.x -= 1.0;
    if (d.y < 0.0 && u.y == c.y) c.y -= 1.0;
    c = clamp(c, b.xy, max(b.zw - 1.0, b.xy));
    lo = c * sc - u_pgm_level[int(level)].zw;
    hi = lo + sc;
    return ft_level_holds(level, p);
}

/* The cell's 4 samples and its max: the hi of its range of the finest data */
vec4 ft_node_heights(float level, vec2 c, out float zmax)
{
    vec4 h = vec4(ft_texel(level, c), ft_texel(level, c + vec2(1.0, 0.0)),
                  ft_texel(level, c + vec2(0.0, 1.0)), ft_texel(level, c + 1.0));
    zmax = ft_range_hi(level, c);
    return h;
}

/* Below a node the ray meets: the finer level's cells, where it holds them. */
bool ft_descend(float level, vec2 p)
{
    return level > 0.5 && ft_level_holds(level - 1.0, p);
}

/* The ray in the leaf level's units (a cell is 1 x 1, z stays metres). */
void ft_leaf_ray(float level, vec3 o, vec3 d, out vec3 ok, out vec3 dk)
{
    float sc = exp2(level);
    ok = vec3((o.xy + u_pgm_level[int(level)].zw) / sc, o.z);
    dk = vec3(d.xy / sc, d.z);
}

/* The surface at ray point p: the finest level that holds it, bilinear. */
float ft_surface_at(vec2 p)
{
    float top = u_rc_levels - 1.0;
    for (int k = 0; k < FT_LEVELS; ++k) {
        float level = float(k);
        vec2 c, lo, hi;
        if (ft_node(level, p, vec2(0.0), c, lo, hi) || level >= top) {
            float zmax;
            vec4 h = ft_node_heights(level, c, zmax);
            vec2 f = clamp(ft_level_xy(level, p) - c, 0.0, 1.0);
            return mix(mix(h.x, h.y, f.x), mix(h.z, h.w, f.x), f.y);
        }
    }
    return 0.0;
}
#endif

/* first t in [ta, tb] where o + t d meets cell (i, j)'s bilinear patch
 * (h = its samples h00, h10, h01, h11). Solved in the segment's own frame
 * (origin: the ray at ta, s = t - ta), so the patch is never extrapolated
 * out to the eye: the coefficients stay of the order of the cell's heights
 * and float keeps millimetres. Returns 1 with th set for a root; 2 for a
 * sign change the closed form lost to round-off, with f(s) = (q.x s + q.y) s
 * + q.z over [0, q.w] for the caller to bisect (after its loop); else 0. */
int solve_cell(vec2 ij, vec4 h, vec3 o, vec3 d, float bend, float ta, float tb, bool entry_hit,
               out float th, out vec4 q)
{
    /* local u = u0 + s d.x, v likewise; H = h00 + a u + b v + c u v */
    float a = h.y - h.x, b = h.z - h.x, c = h.x - h.y - h.z + h.w;
    vec3 pa = o + ta * d;
    pa.z += bend * ta * ta;
    float u0 = pa.x - ij.x, v0 = pa.y - ij.y;
    float len = tb - ta;
    /* f(s) = pa.z + s d.z - H(u0 + s dx, v0 + s dy) = A s^2 + B s + C */
    float A = bend - c * d.x * d.y;
    float B = (d.z + 2.0 * bend * ta) - a * d.x - b * d.y - c * (u0 * d.y + v0 * d.x);
    float C = pa.z - (h.x + a * u0 + b * v0 + c * u0 * v0);
    float fa = C;
    float fb = (A * len + B) * len + C;
    float best = 1e30;
    q = vec4(A, B, C, len);
    th = ta;
    if (entry_hit && fa <= 0.0) {
        /* already under the (continuous) surface where the ray enters the
         * cell: the crossing was at the entry, within the round-off of the
         * previous cell's solve. Without this the ray would run on under
         * the ground (a hole, or a hit on a later, farther surface). Not
         * for a ray that starts under the surface (an eye under the
         * terrain): that one looks for its crossing from below, as the
         * reference does. */
        return 1;
    }
    if (abs(A) * len < 1e-6 * max(abs(B), 1e-30)) {
        if (B != 0.0) {
            float s = -C / B;
            if (s >= 0.0 && s <= len) best = s;
        }
    } else {
        float disc = B * B - 4.0 * A * C;
        if (disc >= 0.0) {
            float sq = sqrt(disc);
            float qq = -0.5 * (B + (B >= 0.0 ? sq : -sq));
            float s1 = qq / A;
            float s2 = (qq != 0.0) ? C / qq : s1;
            if (s1 >= 0.0 && s1 <= len) best = min(best, s1);
            if (s2 >= 0.0 && s2 <= len) best = min(best, s2);
        }
    }
    if (best < 1e29) {
        th = ta + best;
        return 1;
    }
    return (fa * fb <= 0.0) ? 2 : 0;
}

/* the sign change of f(s) = (q.x s + q.y) s + q.z on [0, q.w], bisected */
float bisect(vec4 q)
{
    float lo = 0.0, hi = q.w, flo = q.z;
    if (q.z == 0.0) return 0.0;
    for (int k = 0; k < 24; ++k) {
        float mid = 0.5 * (lo + hi);
        float fm = (q.x * mid + q.y) * mid + q.z;
        if ((fm <= 0.0) == (flo <= 0.0) && fm != 0.0) {
            lo = mid;
            flo = fm;
        } else {
            hi = mid;
        }
    }
    return hi;
}

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    ivec2 lim = ivec2(u_rc_size) - 1;
    float code = 0.0;
    for (int y = -1; y <= 1; ++y) {
        for (int x = -1; x <= 1; ++x) {
            ivec2 q = clamp(px + ivec2(x, y), ivec2(0), lim);
            code = max(code, floor(texelFetch(u_err, q, 0).g * 255.0 + 0.5));
        }
    }
    if (code < u_rc_thr) {
        discard;
    }
    vec2 ndc = gl_FragCoord.xy / u_rc_size * 2.0 - 1.0;
    vec3 dw = normalize(u_rc_fwd + ndc.x * u_rc_tan.x * u_rc_right + ndc.y * u_rc_tan.y * u_rc_up);
    /* ray frame: x, y in level-0 samples (of the grid, or of the cache's
     * lattice from the eye), z metres; t stays metres along dw */
    vec3 d = vec3(dw.x / u_cell_m.x, dw.y / u_cell_m.y, dw.z);
    vec3 o = u_rc_eye_g;
    float bend = u_earth_drop_per_m2 * dot(dw.xy, dw.xy);
    /* clip to what is drawn: the grid's box, or the cache's */
#ifdef FT_RC_CLIP
    vec2 box_lo = u_pcm_clamp.xy / u_cell_m, box_hi = u_pcm_clamp.zw / u_cell_m;
#else
    vec2 box_lo = vec2(0.0), box_hi = u_grid_size - 1.0;
#endif
    float t0 = 0.0, t1 = 1e30;
    for (int k = 0; k < 2; ++k) {
        float dk = d[k], ok = o[k];
        if (abs(dk) < 1e-30) {
            if (ok < box_lo[k] || ok > box_hi[k]) t1 = -1.0;
        } else {
            float ta = (box_lo[k] - ok) / dk, tb = (box_hi[k] - ok) / dk;
            t0 = max(t0, min(ta, tb));
            t1 = min(t1, max(ta, tb));
        }
    }
    float top = u_rc_levels - 1.0;
    bool hit = false;
    float th = 0.0;
    bool entry_hit = true; /* false: the ray starts under the surface */
    if (t0 <= t1) {
        vec3 p0 = o + t0 * d;
        entry_hit = p0.z + bend * t0 * t0 >= ft_surface_at(p0.xy);
    }
    vec4 lost = vec4(0.0); /* a root to bisect: f's coefficients and length */
    float lost_ta = 0.0;
    bool bisect_lost = false;
    /* the leaf the ray met: its level, cell and samples */
    float leaf_level = 0.0;
    vec2 leaf_c = vec2(0.0);
    vec4 leaf_h = vec4(0.0);
    if (t0 <= t1) {
        float t = t0;
        float level = top;
        for (int step = 0; step < FT_RC_STEPS; ++step) {
            if (t > t1) break;
            vec3 p = o + t * d;
            vec2 c, lo, hi;
            bool held = ft_node(level, p.xy, d.xy, c, lo, hi);
            /* exit of the node's box */
            float tx = d.x > 0.0 ? (hi.x - o.x) / d.x : (d.x < 0.0 ? (lo.x - o.x) / d.x : 1e30);
            float ty = d.y > 0.0 ? (hi.y - o.y) / d.y : (d.y < 0.0 ? (lo.y - o.y) / d.y : 1e30);
            float te = min(min(tx, ty), t1);
            te = max(te, t);
            float zmax;
            vec4 h = ft_node_heights(level, c, zmax);
            if (!held) {
                /* the cache's level holds nothing here: a coarser one does
                 * (the coarsest holds what is drawn: past it the ray left) */
                if (level >= top) break;
                level += 1.0;
                continue;
            }
            float zlo = min(p.z + bend * t * t, o.z + te * (d.z + bend * te));
            float t_low = -d.z / max(2.0 * bend, 1e-30); /* the bent ray's lowest point */
            if (bend > 0.0 && t_low > t && t_low < te) {
                zlo = min(zlo, o.z + t_low * (d.z + bend * t_low));
            }
            if (zlo > zmax) {
                /* above the whole box: skip it, and go up a level */
                t = te + max(abs(te), 1.0) * 1e-7;
                level = min(level + 1.0, top);
                continue;
            }
            if (ft_descend(level, p.xy)) {
                level -= 1.0;
                continue;
            }
            vec3 ok, dk;
            ft_leaf_ray(level, o, d, ok, dk);
            float tt;
            vec4 q;
            int r = solve_cell(c, h, ok, dk, bend, t, te, entry_hit, tt, q);
            leaf_level = level;
            leaf_c = c;
            leaf_h = h;
            if (r == 1) {
                th = tt;
                hit = true;
                break;
            }
            if (r == 2) {
                lost = q;
                lost_ta = t;
                bisect_lost = true;
                break;
            }
            t = te + max(abs(te), 1.0) * 1e-7;
        }
    }
    if (bisect_lost) {
        th = lost_ta + bisect(lost);
        hit = true;
    }
    if (!hit) {
        o_color = (u_rc_mode > 0.5) ? vec4(0.0) : u_rc_sky;
        gl_FragDepth = 1.0;
        return;
    }
    vec3 pg = o + th * d;
    vec3 rel = th * dw; /* hit - eye, world axes, metres */
    vec4 clip = u_view_proj * vec4(rel, 1.0);
    gl_FragDepth = clamp((clip.z / clip.w) * 0.5 + 0.5, 0.0, 1.0);
    if (u_rc_mode > 0.5) {
        o_color = vec4(rel, 1.0);
        return;
    }
#ifdef FT_RC_CLIP
    /* the leaf's bilinear surface and slope (per metre) at the hit */
    float sc = exp2(leaf_level);
    vec2 f = clamp(ft_level_xy(leaf_level, pg.xy) - leaf_c, 0.0, 1.0);
    float h00 = leaf_h.x, h10 = leaf_h.y, h01 = leaf_h.z, h11 = leaf_h.w;
    vec2 cell_m = sc * u_cell_m;
#else
    vec2 gmax = u_grid_size - 1.0;
    vec2 ij = clamp(floor(pg.xy), vec2(0.0), max(gmax - 1.0, vec2(0.0)));
    vec2 f = pg.xy - ij;
    float h00 = hs(ij), h10 = hs(ij + vec2(1.0, 0.0));
    float h01 = hs(ij + vec2(0.0, 1.0)), h11 = hs(ij + 1.0);
    vec2 cell_m = u_cell_m;
#endif
    float dhx = mix(h10 - h00, h11 - h01, f.y) / cell_m.x;
    float dhy = mix(h01 - h00, h11 - h10, f.x) / cell_m.y;
    float h = mix(mix(h00, h10, f.x), mix(h01, h11, f.x), f.y);
    o_color = ft_colour(h, vec3(-dhx, -dhy, 1.0), rel);
}
#else
/* GLSL ES 1.00 has no gl_FragDepth or texelFetch: pgrid never ray casts on
 * GLES 2 (the program is not built there); this variant only validates. */
void main()
{
    gl_FragColor = vec4(0.0);
}
#endif
