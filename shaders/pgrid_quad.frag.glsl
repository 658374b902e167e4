/* pgrid_quad.frag.glsl - the quad-bound pass of method 'pgrid' (src/lod/pgrid.h
 * 6; src/lod/pgrid.c ft_pgrid_quad_bound is the same rule in double): one
 * fragment per grid quad (i, j), corners (i..i+1, j..j+1) read from the vertex
 * pass; writes e_Q + the curvature chord + the float margin (metres) into R:
 * the exact max of |L - H| for a quad inside a window of 4 x 4 cells, else
 * the residual rule. With FT_PGM_CLIP (pgrid.heights = clipmap) the same
 * exact rule runs on the cache's level where the quad fits the window,
 * plus that level's deviation from the finest data (src/lod/pgrid.h 6).
 * GLES 3 only; the GLES 2 variant exists so every shader validates in both
 * languages. */
precision highp float;

#if FT_ES3
out vec4 o_bound;
#define FT_FRAG_OUT o_bound
#else
#define FT_FRAG_OUT gl_FragColor
#endif

uniform highp sampler2D u_pgrid_vtx;  /* vertex pass: (pc.xy rel. eye, h, level) */
uniform float u_earth_drop_per_m2;

#ifdef FT_PGM_CLIP
#define FT_PGM_GRID_NO_IO 1
#if !FT_ES3
#define texture2DLod(s, uv, lod) texture2D(s, uv)
#endif
#include "pgm_grid.glsl"
#include "pgrid_rows.glsl" /* pgm_grid.glsl names its row placement */
#include "pgrid_cache_range.glsl"
#else
#define FT_RES_LEVELS 16

uniform highp sampler2D u_heights;
uniform highp sampler2D u_pgrid_res;  /* residual atlas, levels >= 1 */
uniform vec2 u_grid_size;             /* samples */
uniform vec2 u_cell_m;
uniform vec3 u_origin_rel_eye_m;
uniform vec2 u_pack;                  /* heights: packed (min, range); range 0 = float */
uniform vec4 u_pgrid_res_level[FT_RES_LEVELS]; /* atlas origin xy, size zw */
uniform float u_pgrid_res_levels;
#include "decode.glsl"
#endif

/* The float margin (m) every bound gets: this pass evaluates the surface and
 * the planes through heights in float32 (measured against the CPU rule in
 * double: <= 0.006 m at 2000 m). */
#define FT_PGRID_MARGIN_M(h_m) (0.005 + 4e-6 * (h_m))

#if FT_ES3
vec4 ft_vtx(vec2 ij) { return texelFetch(u_pgrid_vtx, ivec2(ij), 0); }
#else
vec4 ft_vtx(vec2 ij) { return vec4(0.0); }
#endif
#ifdef FT_PGM_CLIP
/* sample ij of the cache's level `level` (from the level's base) */
float ft_h(float level, vec2 ij) { return ft_pcm_texel(level, ij); }
#elif FT_ES3
/* sample ij of the window (one level) */
float ft_h(float level, vec2 ij) { return ft_decode(texelFetch(u_heights, ivec2(ij), 0), u_pack); }
float ft_res(vec2 a) { return texelFetch(u_pgrid_res, ivec2(a), 0).r; }
#else
float ft_h(float level, vec2 ij) { return 0.0; }
float ft_res(vec2 a) { return 0.0; }
#endif

/* src/lod/pgrid.h: FT_PGRID_EXACT_CELLS */
#define FT_EXACT_CELLS 4
#define FT_EXACT_SAMPLES 5

/* |f| at a quadratic piece's ends (values fa, fb at ta, tb; f'' = 2 gam)
 * and at its stationary point */
float ft_piece_max(float ta, float tb, float fa, float fb, float gam)
{
    float m = max(abs(fa), abs(fb));
    float w = tb - ta;
    if (w > 0.0 && gam != 0.0) {
        float sl = (fb - fa) / w;
        float ts = 0.5 * (ta + tb) - sl / (2.0 * gam);
        if (ts > ta && ts < tb) {
            m = max(m, abs(fa + (ts - ta) * sl + gam * (ts - ta) * (ts - tb)));
        }
    }
    return m;
}

/* the exact max of |H - L| along edge p -> r (drawn heights hp, hr) inside
 * the window's cell (cx, cy) with corner samples h00 h10 h01 h11 */
float ft_edge_in_cell(vec2 p, vec2 r, float hp, float hr, vec2 c0, float h00, float h10,
                      float h01, float h11)
{
    vec2 dl = r - p;
    float ta = 0.0, tb = 1.0;
    if (dl.x != 0.0) {
        float t0 = (c0.x - p.x) / dl.x, t1 = (c0.x + 1.0 - p.x) / dl.x;
        ta = max(ta, min(t0, t1));
        tb = min(tb, max(t0, t1));
    } else if (p.x < c0.x || p.x > c0.x + 1.0) {
        return 0.0;
    }
    if (dl.y != 0.0) {
        float t0 = (c0.y - p.y) / dl.y, t1 = (c0.y + 1.0 - p.y) / dl.y;
        ta = max(ta, min(t0, t1));
        tb = min(tb, max(t0, t1));
    } else if (p.y < c0.y || p.y > c0.y + 1.0) {
        return 0.0;
    }
    if (ta > tb) {
        return 0.0;
    }
    float d = h00 - h10 - h01 + h11;
    vec2 ua = p + ta * dl - c0, ub = p + tb * dl - c0;
    float fa = h00 + (h10 - h00) * ua.x + (h01 - h00) * ua.y + d * ua.x * ua.y - (hp + ta * (hr - hp));
    float fb = h00 + (h10 - h00) * ub.x + (h01 - h00) * ub.y + d * ub.x * ub.y - (hp + tb * (hr - hp));
    return ft_piece_max(ta, tb, fa, fb, d * dl.x * dl.y);
}

/* |H - L| at sample x (height hs) if it lies in triangle a b c, else 0 */
float ft_sample_in_tri(vec2 x, float hs, vec2 a, vec2 b, vec2 c, float ha, float hb, float hc)
{
    float det = (b.y - c.y) * (a.x - c.x) + (c.x - b.x) * (a.y - c.y);
    if (abs(det) < 1e-12) {
        return 0.0;
    }
    float w0 = ((b.y - c.y) * (x.x - c.x) + (c.x - b.x) * (x.y - c.y)) / det;
    float w1 = ((c.y - a.y) * (x.x - c.x) + (a.x - c.x) * (x.y - c.y)) / det;
    float w2 = 1.0 - w0 - w1;
    if (w0 < 0.0 || w1 < 0.0 || w2 < 0.0) {
        return 0.0;
    }
    return abs(hs - (w0 * ha + w1 * hb + w2 * hc));
}

/* The exact max of |H - L| over quad g0 g1 g2 g3 (drawn heights z) whose box
 * [bmin, bmax] lies in the window of FT_EXACT_CELLS^2 cells from sample o
 * (hi_g: the level's last sample), and (y) the largest deviation of the
 * finest data from H over the cells it touches (over the cache; 0 on the
 * window, whose H is the finest data). Loops bounded by the box, not the
 * window: a SIMD core runs a loop until its last lane is done, so a small
 * quad (most are 1-2 cells wide) stays cheap; the cells and samples
 * skipped add nothing. */
vec2 ft_quad_exact(float level, vec2 g0, vec2 g1, vec2 g2, vec2 g3, vec4 z, vec2 o, vec2 bmin,
                   vec2 bmax, vec2 hi_g)
{
    float n = float(FT_EXACT_CELLS);
    float dev = 0.0;
    vec2 cell_lo = max(ceil(bmin) - 1.0, o);
    vec2 cell_hi = min(min(floor(bmax), o + n - 1.0), hi_g - 1.0);
    float ex = 0.0;
    for (int y = 0; y < FT_EXACT_CELLS; ++y) {
        float cy = cell_lo.y + float(y);
        if (cy > cell_hi.y) break;
        for (int x = 0; x < FT_EXACT_CELLS; ++x) {
            float cx = cell_lo.x + float(x);
            if (cx > cell_hi.x) break;
            vec2 cc = vec2(cx, cy);
            float h00 = ft_h(level, cc), h10 = ft_h(level, cc + vec2(1.0, 0.0));
            float h01 = ft_h(level, cc + vec2(0.0, 1.0)), h11 = ft_h(level, cc + 1.0);
            /* the 5 edges of triangles 0-1-3 and 0-3-2 (the grid's order) */
            ex = max(ex, ft_edge_in_cell(g0, g1, z.x, z.y, cc, h00, h10, h01, h11));
            ex = max(ex, ft_edge_in_cell(g1, g3, z.y, z.w, cc, h00, h10, h01, h11));
            ex = max(ex, ft_edge_in_cell(g3, g2, z.w, z.z, cc, h00, h10, h01, h11));
            ex = max(ex, ft_edge_in_cell(g2, g0, z.z, z.x, cc, h00, h10, h01, h11));
            ex = max(ex, ft_edge_in_cell(g0, g3, z.x, z.w, cc, h00, h10, h01, h11));
#ifdef FT_PGM_CLIP
            /* the cell's range of the finest data is its corners' widened
             * by their deviation from H (lod/clip_levels.h): at least it */
            vec2 r = ft_range_texel(int(level), cc);
            dev = max(dev, max(r.y - max(max(h00, h10), max(h01, h11)),
                               min(min(h00, h10), min(h01, h11)) - r.x));
#endif
        }
    }
    vec2 smp_lo = max(ceil(bmin), o);
    vec2 smp_hi = min(min(floor(bmax), o + n), hi_g);
    for (int y = 0; y < FT_EXACT_SAMPLES; ++y) {
        float sy = smp_lo.y + float(y);
        if (sy > smp_hi.y) break;
        for (int x = 0; x < FT_EXACT_SAMPLES; ++x) {
            float sx = smp_lo.x + float(x);
            if (sx > smp_hi.x) break;
            vec2 sp = vec2(sx, sy);
            float h = ft_h(level, sp);
            ex = max(ex, ft_sample_in_tri(sp, h, g0, g1, g3, z.x, z.y, z.w));
            ex = max(ex, ft_sample_in_tri(sp, h, g0, g3, g2, z.x, z.w, z.z));
        }
    }
    return vec2(ex, dev);
}

#ifndef FT_PGM_CLIP
void main()
{
    vec2 q = floor(gl_FragCoord.xy);
    vec4 c0 = ft_vtx(q), c1 = ft_vtx(q + vec2(1.0, 0.0));
    vec4 c2 = ft_vtx(q + vec2(0.0, 1.0)), c3 = ft_vtx(q + vec2(1.0, 1.0));
    vec2 lo = u_origin_rel_eye_m.xy;
    vec2 inv_cell = 1.0 / u_cell_m;
    vec2 hi_g = u_grid_size - 1.0;
    /* the vertices were clamped into the grid in metres; the clamp again in
     * grid units keeps a rounding off the edge from leaving the grid */
    vec2 g0 = clamp((c0.xy - lo) * inv_cell, vec2(0.0), hi_g);
    vec2 g1 = clamp((c1.xy - lo) * inv_cell, vec2(0.0), hi_g);
    vec2 g2 = clamp((c2.xy - lo) * inv_cell, vec2(0.0), hi_g);
    vec2 g3 = clamp((c3.xy - lo) * inv_cell, vec2(0.0), hi_g);
    vec2 bmin = min(min(g0, g1), min(g2, g3)), bmax = max(max(g0, g1), max(g2, g3));
    /* the chord: the mesh interpolates the curvature drop linearly, over a
     * span of length L the chord lies up to k L^2 / 4 under the surface */
    vec2 ext = max(max(c0.xy, c1.xy), max(c2.xy, c3.xy)) - min(min(c0.xy, c1.xy), min(c2.xy, c3.xy));
    /* (with the margin: every bound written carries both) */
    float chord_m = 0.25 * u_earth_drop_per_m2 * dot(ext, ext) +
                    FT_PGRID_MARGIN_M(max(max(abs(c0.z), abs(c1.z)), max(abs(c2.z), abs(c3.z))));

    /* exact when the quad's box fits FT_EXACT_CELLS^2 cells (src/lod/pgrid.h) */
    float n = float(FT_EXACT_CELLS);
    vec2 o = max(vec2(0.0), min(floor(bmin), hi_g - n));
    if (all(greaterThanEqual(bmin, o)) && all(lessThanEqual(bmax, o + n))) {
        vec2 ed = ft_quad_exact(0.0, g0, g1, g2, g3, vec4(c0.z, c1.z, c2.z, c3.z), o, bmin,
                                bmax, hi_g);
        FT_FRAG_OUT = vec4(ed.x + chord_m, 0.0, 0.0, 1.0);
        return;
    }

    vec2 a = clamp(bmin, vec2(0.0), hi_g);
    vec2 b = clamp(bmax, vec2(0.0), hi_g);
    float side = max(max(b.x - a.x, b.y - a.y), 1.0);
    float level = max(0.0, ceil(log2(side)));
    if (level > 0.0 && exp2(level - 1.0) >= side) {
        level -= 1.0; /* log2 rounding */
    }
    if (exp2(level) < side) {
        level += 1.0;
    }
    level = min(level, u_pgrid_res_levels - 1.0);
    float scale = exp2(level);
    vec2 nodes = floor((hi_g - 1.0) / scale) + 1.0; /* nodes at this level */
    vec2 n0 = min(floor(a / scale), nodes - 1.0);
    vec2 n1 = min(min(floor(b / scale), nodes - 1.0), n0 + 1.0);
    float e = 0.0;
    for (int y = 0; y < 2; ++y) {
        for (int x = 0; x < 2; ++x) {
            vec2 n = min(n0 + vec2(float(x), float(y)), n1);
            vec2 p0 = n * scale;
            vec2 p1 = min(p0 + scale, hi_g);
            float h00 = ft_h(level, p0), h10 = ft_h(level, vec2(p1.x, p0.y));
            float h01 = ft_h(level, vec2(p0.x, p1.y)), h11 = ft_h(level, p1);
            float m = 0.25 * (h00 + h10 + h01 + h11);
            float bx = 0.5 * (h10 + h11 - h00 - h01);
            float by = 0.5 * (h01 + h11 - h00 - h10);
            float r = level < 0.5 ? 0.25 * abs(h00 - h10 - h01 + h11)
                                  : ft_res(u_pgrid_res_level[int(level)].xy + n);
            vec2 inv = 1.0 / (p1 - p0);
            vec2 u0 = (g0 - p0) * inv - 0.5, u1 = (g1 - p0) * inv - 0.5;
            vec2 u2 = (g2 - p0) * inv - 0.5, u3 = (g3 - p0) * inv - 0.5;
            float off = max(max(abs(m + bx * u0.x + by * u0.y - c0.z),
                                abs(m + bx * u1.x + by * u1.y - c1.z)),
                            max(abs(m + bx * u2.x + by * u2.y - c2.z),
                                abs(m + bx * u3.x + by * u3.y - c3.z)));
            e = max(e, r + off);
        }
    }
    FT_FRAG_OUT = vec4(e + chord_m, 0.0, 0.0, 1.0);
}
#else
/* Over the cache: the finest level L whose resident samples hold the cells
 * of a window of FT_EXACT_CELLS^2 level-L cells the quad's box lies in. There
 * |L - T| <= |L - H_L| + |H_L - T|: the exact max of the first, plus the
 * largest deviation of the finest data T from H_L over the cells the quad
 * touches (src/lod/pgrid.h 6). A quad no level holds so (wider than 4 cells
 * of the coarsest level, or past what is resident) takes the relief rule
 * from the cache's ranges over its box: every point of the quad and of T
 * there lies between their ends. */
void main()
{
    vec2 q = floor(gl_FragCoord.xy);
    vec4 c0 = ft_vtx(q), c1 = ft_vtx(q + vec2(1.0, 0.0));
    vec4 c2 = ft_vtx(q + vec2(0.0, 1.0)), c3 = ft_vtx(q + vec2(1.0, 1.0));
    vec4 z = vec4(c0.z, c1.z, c2.z, c3.z);
    /* level-0 samples from the eye */
    vec2 inv_cell = 1.0 / u_cell_m;
    vec2 p0 = c0.xy * inv_cell, p1 = c1.xy * inv_cell, p2 = c2.xy * inv_cell;
    vec2 p3 = c3.xy * inv_cell;
    vec2 pmin = min(min(p0, p1), min(p2, p3)), pmax = max(max(p0, p1), max(p2, p3));
    vec2 ext = max(max(c0.xy, c1.xy), max(c2.xy, c3.xy)) - min(min(c0.xy, c1.xy), min(c2.xy, c3.xy));
    float chord_m = 0.25 * u_earth_drop_per_m2 * dot(ext, ext) +
                    FT_PGRID_MARGIN_M(max(max(abs(z.x), abs(z.y)), max(abs(z.z), abs(z.w))));

    float n = float(FT_EXACT_CELLS);
    float top = u_pcm_misc.z - 1.0;
    float level = -1.0;
    for (int k = 0; k < FT_PGM_LEVELS; ++k) {
        if (float(k) > top) {
            break;
        }
        vec4 bx = u_pcm_box[k]; /* resident samples, inclusive, from the level's base */
        float s = exp2(float(k));
        vec2 ua = (pmin + u_pgm_level[k].zw) / s, ub = (pmax + u_pgm_level[k].zw) / s;
        vec2 o = floor(ua);
        if (bx.z >= bx.x && bx.w >= bx.y && all(lessThanEqual(ub, o + n)) &&
            all(greaterThanEqual(o, bx.xy)) && all(lessThanEqual(max(ceil(ub), o + 1.0), bx.zw))) {
            level = float(k);
            break;
        }
    }
    float e;
    if (level >= 0.0) {
        /* level-L samples from the level's base */
        vec2 off = u_pgm_level[int(level)].zw;
        float s = exp2(level);
        vec2 bmin = (pmin + off) / s;
        vec2 ed = ft_quad_exact(level, (p0 + off) / s, (p1 + off) / s, (p2 + off) / s,
                                (p3 + off) / s, z, floor(bmin), bmin, (pmax + off) / s,
                                u_pcm_box[int(level)].zw);
        e = ed.x + ed.y;
    } else {
        vec2 mm = ft_region_minmax_cache(pmin, pmax);
        float zlo = min(min(z.x, z.y), min(z.z, z.w)), zhi = max(max(z.x, z.y), max(z.z, z.w));
        e = max(max(mm.y - zlo, zhi - mm.x), 0.0);
    }
    /* G: the level the quad was bounded on, -1 by the relief rule (tests) */
    FT_FRAG_OUT = vec4(e + chord_m, level, 0.0, 1.0);
}
#endif
