/* bintree_mesh.c - the CPU mirror of shaders/bintree.vert.glsl (see
 * bintree_mesh.h). Each step below names the shader line it mirrors. */
#include "lod/bintree_mesh.h"

#include <math.h>
#include <string.h>

#include "core/view_scale.h"

void ft_bt_mesh_uniforms_for(const ft_terrain *t, const ft_camera *cam, double tau_target_px,
                             int morph, ft_bt_mesh_uniforms *u)
{
    memset(u, 0, sizeof *u);
    /* renderer.c draw_pass: the subtraction in double */
    u->origin_rel_eye_m[0] = t->origin_world_x_m - cam->eye_m[0];
    u->origin_rel_eye_m[1] = t->origin_world_y_m - cam->eye_m[1];
    u->origin_rel_eye_m[2] = 0.0 - cam->eye_m[2];
    u->cell_m[0] = t->cell_x_m;
    u->cell_m[1] = t->cell_y_m;
    u->drop_per_m2 = t->curv_drop_per_m2;
    /* method_bintree.c ft_bintree_method_draw */
    const double tau = tau_target_px;
    u->k_px = cam->px_per_rad_k;
    u->tau_px = tau;
    u->morph = (morph && isfinite(tau)) ? 1 : 0;
    ft_bt_view_from_camera(cam, t, 0, morph, &u->view);
}

/* ft_height: the coordinate (grid units) clamped into the real grid, then
 * one sample. */
static double height_at(const ft_bintree *bt, double gx, double gy)
{
    const double wx = (double)bt->width - 1.0, hy = (double)bt->height - 1.0;
    gx = (gx < 0.0) ? 0.0 : ((gx > wx) ? wx : gx);
    gy = (gy < 0.0) ? 0.0 : ((gy > hy) ? hy : gy);
    return (double)bt->heights_m[(size_t)gy * bt->width + (size_t)gx];
}

static double clampd(double v, double lo, double hi)
{
    return fmin(fmax(v, lo), hi); /* GLSL clamp */
}

/* ft_bilinear: the surface of the cell with corner heights h (h00, h10,
 * h01, h11) and corner cf (fine units) at fine point g; f = 2^S. */
static double bilinear(const double h[4], const double cf[2], const double g[2], double f)
{
    const double uu = (g[0] - cf[0]) / f, vv = (g[1] - cf[1]) / f;
    return h[0] + (h[1] - h[0]) * uu + (h[2] - h[0]) * vv + ((h[0] + h[3]) - (h[1] + h[2])) * uu * vv;
}

/* ft_twist_texel: atlas texel p (atlas coordinates). */
static double twist_texel(const ft_bintree *bt, double px, double py)
{
    return (double)bt->twist_atlas[(size_t)py * bt->twist.atlas_w + (size_t)px];
}

/* ft_sub_error: the closed-form error of a diamond below the samples, split
 * vertex c, square side sd (fine units); even_level when c is a square's
 * centre. The same <= 4 texels of the twist atlas as the shader (the
 * closure spans at most 2 blocks a side at the level it picks). */
static double sub_error(const ft_bintree *bt, const int32_t c[2], double sd, int even_level)
{
    const double f = (double)(1u << bt->sub);
    const double size[2] = {(double)bt->width, (double)bt->height};
    const double a = sd / ((double)bt->step * f); /* its template squares' side, cells */
    const double leg = even_level ? a : 0.5 * a;
    const double r = even_level ? 1.5 * sd : sd;
    double c0[2], c1[2];
    for (int i = 0; i < 2; ++i) {
        const double lo = clampd(((double)c[i] - r) / f, 0.0, size[i] - 1.0);
        const double hi = clampd(((double)c[i] + r) / f, 0.0, size[i] - 1.0);
        c0[i] = clampd(floor(lo), 0.0, size[i] - 2.0);
        c1[i] = clampd(ceil(hi) - 1.0, c0[i], size[i] - 2.0);
    }
    const double span = fmax(c1[0] - c0[0], c1[1] - c0[1]) + 1.0;
    uint32_t m = 0;
    double bs = 1.0;
    for (int i = 0; i < 16; ++i) {
        if (bs >= span || (double)m >= (double)bt->twist.levels - 1.0) {
            break;
        }
        bs *= 2.0;
        m += 1u;
    }
    const double b0[2] = {floor(c0[0] / bs), floor(c0[1] / bs)};
    const double b1[2] = {floor(c1[0] / bs), floor(c1[1] / bs)};
    const double ox = (double)bt->twist.ox[m], oy = (double)bt->twist.oy[m];
    double d = twist_texel(bt, ox + b0[0], oy + b0[1]);
    d = fmax(d, twist_texel(bt, ox + b1[0], oy + b0[1]));
    d = fmax(d, twist_texel(bt, ox + b0[0], oy + b1[1]));
    d = fmax(d, twist_texel(bt, ox + b1[0], oy + b1[1]));
    return 0.25 * leg * leg * d;
}

/* ft_morph_error: the error (m) of the diamond that inserts vertex g_raw
 * (fine units, integers) and the coarse edge e0-e1 it bisects; negative when
 * the vertex never morphs (the rule is ft_bt_vertex_morph's, bintree.h).
 * *closed_form: the error came from sub_error, not the table. */
static double morph_error(const ft_bintree *bt, int32_t x, int32_t y, int32_t e0[2],
                          int32_t e1[2], int32_t c[2], uint32_t *level, int *closed_form)
{
    *closed_form = 0;
    if (!ft_bt_vertex_morph(bt, x, y, e0, e1, c, level)) {
        return -1.0;
    }
    const uint32_t sh = bt->k + bt->sub; /* table lattice step 2^(k+S), fine units */
    const uint32_t cx = (uint32_t)c[0], cy = (uint32_t)c[1];
    if (((cx | cy) & ((1u << sh) - 1u)) != 0u) {
        const int32_t s = (x | y) & -(x | y); /* lowest set bit */
        const int even_level = ((x / s) & 1) != 0 && ((y / s) & 1) != 0;
        *closed_form = 1;
        return sub_error(bt, c, 2.0 * (double)s * (double)bt->step, even_level);
    }
    const size_t li = (size_t)(cy >> sh) * bt->lattice_side + (cx >> sh);
    if (li >= (size_t)bt->lattice_side * bt->lattice_side) {
        return -1.0; /* never: c is a diamond centre of the padded domain */
    }
    return (double)bt->err_m[li];
}

/* ft_earth_curve: lowered by k r^2, r the horizontal distance from the eye. */
static void earth_curve(const ft_bt_mesh_uniforms *u, const double p[3], double out[3])
{
    out[0] = p[0];
    out[1] = p[1];
    out[2] = p[2] - u->drop_per_m2 * (p[0] * p[0] + p[1] * p[1]);
}

/* u_origin_rel_eye_m + vec3(gs * u_cell_m, h), curved; gs in grid units */
static void position(const ft_bt_mesh_uniforms *u, const double gs[2], double h, double out[3])
{
    const double p[3] = {u->origin_rel_eye_m[0] + gs[0] * u->cell_m[0],
                         u->origin_rel_eye_m[1] + gs[1] * u->cell_m[1],
                         u->origin_rel_eye_m[2] + h};
    earth_curve(u, p, out);
}

void ft_bt_mesh_vertex_of(const ft_bintree *bt, const ft_bt_mesh_uniforms *u,
                          const ft_bt_tile *tile, double a, double b, ft_bt_mesh_vertex *out)
{
    const double size[2] = {(double)bt->width, (double)bt->height};
    const double f = (double)(1u << bt->sub); /* fine units a cell */
    double g_raw[2], g[2], gs[2];
    for (int i = 0; i < 2; ++i) {
        /* exact: a, b are multiples of 2^-k, the legs multiples of 2^k */
        g_raw[i] = (double)tile->apex[i] + a * (double)(tile->left[i] - tile->apex[i]) +
                   b * (double)(tile->right[i] - tile->apex[i]);
        /* padding collapses onto the grid edge */
        g[i] = (g_raw[i] < (size[i] - 1.0) * f) ? g_raw[i] : (size[i] - 1.0) * f;
        gs[i] = g[i] / f; /* grid coordinates (exact: f is a power of two) */
    }
    const int on_sample = gs[0] == floor(gs[0]) && gs[1] == floor(gs[1]);
    double h;
    double cell[4] = {0.0, 0.0, 0.0, 0.0}; /* corner heights of a sub-sample vertex's cell */
    double cf[2] = {0.0, 0.0};             /* that cell's corner, fine units */
    double dhx, dhy;
    if (on_sample) {
        h = height_at(bt, gs[0], gs[1]);
        /* central differences, one-sided at the grid edge */
        double lo[2], hi[2];
        for (int i = 0; i < 2; ++i) {
            lo[i] = (gs[i] - 1.0 > 0.0) ? gs[i] - 1.0 : 0.0;
            hi[i] = (gs[i] + 1.0 < size[i] - 1.0) ? gs[i] + 1.0 : size[i] - 1.0;
        }
        dhx = (height_at(bt, hi[0], gs[1]) - height_at(bt, lo[0], gs[1])) /
              ((hi[0] - lo[0]) * u->cell_m[0]);
        dhy = (height_at(bt, gs[0], hi[1]) - height_at(bt, gs[0], lo[1])) /
              ((hi[1] - lo[1]) * u->cell_m[1]);
    } else {
        /* the cell: floor of the coordinate, clamped into the grid */
        double cc[2];
        for (int i = 0; i < 2; ++i) {
            cc[i] = clampd(floor(gs[i]), 0.0, size[i] - 2.0);
            cf[i] = cc[i] * f;
        }
        cell[0] = height_at(bt, cc[0], cc[1]);
        cell[1] = height_at(bt, cc[0] + 1.0, cc[1]);
        cell[2] = height_at(bt, cc[0], cc[1] + 1.0);
        cell[3] = height_at(bt, cc[0] + 1.0, cc[1] + 1.0);
        h = bilinear(cell, cf, g, f);
        /* the cell's bilinear gradient there */
        const double uv[2] = {gs[0] - cc[0], gs[1] - cc[1]};
        const double tw = (cell[0] + cell[3]) - (cell[1] + cell[2]);
        dhx = ((cell[1] - cell[0]) + tw * uv[1]) / u->cell_m[0];
        dhy = ((cell[2] - cell[0]) + tw * uv[0]) / u->cell_m[1];
    }
    const double nlen = sqrt(dhx * dhx + dhy * dhy + 1.0);
    out->normal[0] = -dhx / nlen;
    out->normal[1] = -dhy / nlen;
    out->normal[2] = 1.0 / nlen;
    if (on_sample && u->vertex_table) {
        ft_bt_unpack_normal(ft_bt_pack_normal(out->normal), out->normal);
    }
    out->on_sample = on_sample;
    out->err_m = -1.0;
    out->q_m = -INFINITY;
    out->w_m = 0.0;
    out->q_scale_m = 0.0;
    out->morph_span_m = 0.0;
    out->err_closed_form = 0;

    double w = 1.0;
    if (u->morph) {
        int32_t e0[2], e1[2], c[2];
        uint32_t level = 0;
        int closed_form = 0;
        const double err_m = morph_error(bt, (int32_t)g_raw[0], (int32_t)g_raw[1], e0, e1, c,
                                         &level, &closed_form);
        if (err_m >= 0.0) {
            out->err_m = err_m;
            out->err_closed_form = closed_form;
            memcpy(out->e0, e0, sizeof out->e0);
            memcpy(out->e1, e1, sizeof out->e1);
            /* ft_morph_weight: the inserting diamond's Q over its box */
            double w_m;
            out->q_m = ft_bt_diamond_q(bt, &u->view, level, c, u->tau_px, &w_m);
            w = ft_bt_morph_weight(out->q_m, w_m);
            out->w_m = w_m;
            float box[FT_BT_BOX_FLOATS];
            (void)ft_bt_diamond_error(bt, level, c, box);
            const double bx = ((double)box[1] - (double)box[0]) * u->cell_m[0];
            const double by = ((double)box[3] - (double)box[2]) * u->cell_m[1];
            const double bz = (box[5] >= box[4]) ? (double)box[5] - (double)box[4] : 0.0;
            double p_now[3];
            position(u, gs, h, p_now);
            out->q_scale_m = (isfinite(out->q_m) ? fabs(out->q_m) : 0.0) +
                             2.0 * (sqrt(p_now[0] * p_now[0] + p_now[1] * p_now[1] +
                                         p_now[2] * p_now[2]) +
                                    sqrt(bx * bx + by * by + bz * bz));
            /* a sub-sample vertex's coarse edge lies in its own cell */
            double h0, h1;
            if (on_sample) {
                h0 = height_at(bt, (double)e0[0] / f, (double)e0[1] / f);
                h1 = height_at(bt, (double)e1[0] / f, (double)e1[1] / f);
            } else {
                const double pe0[2] = {(double)e0[0], (double)e0[1]};
                const double pe1[2] = {(double)e1[0], (double)e1[1]};
                h0 = bilinear(cell, cf, pe0, f);
                h1 = bilinear(cell, cf, pe1, f);
            }
            const double mid = 0.5 * (h0 + h1);
            out->morph_span_m = fabs(h - mid);
            h = mid * (1.0 - w) + h * w; /* mix(mid, h, w) */
        }
    }
    out->morph_w = w;
    out->height_m = h;
    position(u, gs, h, out->pos_rel_eye_m);
}

size_t ft_bt_mesh_build(const ft_bintree *bt, uint32_t tiles, const ft_bt_mesh_uniforms *u,
                        const float *tmpl_uv, uint32_t tmpl_verts, float *out, size_t out_floats)
{
    const size_t verts = (size_t)tiles * tmpl_verts;
    if (tiles > bt->tiles_max || verts > out_floats / FT_BT_MESH_FLOATS) {
        return 0u;
    }
    for (uint32_t i = 0; i < tiles; ++i) {
        const ft_bt_tile *tile = &bt->tiles[i];
        for (uint32_t v = 0; v < tmpl_verts; ++v) {
            ft_bt_mesh_vertex m;
            ft_bt_mesh_vertex_of(bt, u, tile, (double)tmpl_uv[2u * v], (double)tmpl_uv[2u * v + 1u],
                                 &m);
            float *o = out + ((size_t)i * tmpl_verts + v) * FT_BT_MESH_FLOATS;
            o[0] = (float)m.pos_rel_eye_m[0];
            o[1] = (float)m.pos_rel_eye_m[1];
            o[2] = (float)m.pos_rel_eye_m[2];
            o[3] = (float)m.normal[0];
            o[4] = (float)m.normal[1];
            o[5] = (float)m.normal[2];
            o[6] = (float)m.height_m;
        }
    }
    return verts;
}

size_t ft_bt_mesh_indices(uint32_t tiles, const uint16_t *tmpl_idx, uint32_t tmpl_indices,
                          uint32_t tmpl_verts, uint32_t *out, size_t out_count)
{
    const size_t n = (size_t)tiles * tmpl_indices;
    if (n > out_count || (uint64_t)tiles * tmpl_verts > (uint64_t)UINT32_MAX + 1u) {
        return 0u;
    }
    for (uint32_t i = 0; i < tiles; ++i) {
        const uint32_t base = i * tmpl_verts;
        uint32_t *o = out + (size_t)i * tmpl_indices;
        for (uint32_t j = 0; j < tmpl_indices; ++j) {
            o[j] = base + tmpl_idx[j];
        }
    }
    return n;
}

/* ---- over the clipmap cache (shaders/bintree_clip.vert.glsl) -------------------------- */

static double btc_height(const ft_clip_cache *c, uint32_t d, int64_t a, int64_t b)
{
    const uint32_t side = c->desc.side;
    const int64_t sa = ((a % (int64_t)side) + (int64_t)side) % (int64_t)side;
    const int64_t sb = ((b % (int64_t)side) + (int64_t)side) % (int64_t)side;
    return (double)c->mirror_m[d][(size_t)sb * side + (size_t)sa];
}

size_t ft_btc_mesh_build(const ft_bt_cache *bc, const ft_clip_cache *c, uint32_t tiles,
                         double eye_i, double eye_j, double eye_z_m, double drop_per_m2,
                         const float *tmpl_uv, uint32_t tmpl_verts, float *out,
                         size_t out_floats)
{
    const size_t verts = (size_t)tiles * tmpl_verts;
    if (tiles > bc->tiles_max || verts > out_floats / FT_BT_MESH_FLOATS) {
        return 0u;
    }
    const double lo[2] = {(double)(bc->data[0] - bc->origin[0]),
                          (double)(bc->data[1] - bc->origin[1])};
    const double hi[2] = {(double)(bc->data[2] - bc->origin[0]),
                          (double)(bc->data[3] - bc->origin[1])};
    const double eye_rel[2] = {eye_i - (double)bc->origin[0], eye_j - (double)bc->origin[1]};
    for (uint32_t i = 0; i < tiles; ++i) {
        const ft_bt_tile *tile = &bc->tiles[i];
        const int64_t leg[2] = {(int64_t)tile->left[0] - tile->apex[0],
                                (int64_t)tile->left[1] - tile->apex[1]};
        const uint32_t m = ft_btc_table_of(bc, tile->level);
        const uint32_t d = (m < bc->top) ? m : bc->top;
        const int64_t sp = (int64_t)1 << d;
        for (uint32_t v = 0; v < tmpl_verts; ++v) {
            /* g = apex + a leg + b (leg turned a quarter), exact */
            const double a = (double)tmpl_uv[2u * v], b = (double)tmpl_uv[2u * v + 1u];
            const int64_t gx = tile->apex[0] + (int64_t)llround(a * (double)leg[0] - b * (double)leg[1]);
            const int64_t gy = tile->apex[1] + (int64_t)llround(a * (double)leg[1] + b * (double)leg[0]);
            const int64_t sa = (bc->origin[0] + gx) / sp, sb = (bc->origin[1] + gy) / sp;
            const double h = btc_height(c, d, sa, sb);
            const double dhx = btc_height(c, d, sa + 1, sb) - btc_height(c, d, sa - 1, sb);
            const double dhy = btc_height(c, d, sa, sb + 1) - btc_height(c, d, sa, sb - 1);
            const double span[2] = {2.0 * (double)sp * bc->cell_m[0], 2.0 * (double)sp * bc->cell_m[1]};
            double n[3] = {-dhx / span[0], -dhy / span[1], 1.0};
            const double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            const double gp[2] = {clampd((double)gx, lo[0], hi[0]), clampd((double)gy, lo[1], hi[1])};
            const double x = (gp[0] - eye_rel[0]) * bc->cell_m[0];
            const double y = (gp[1] - eye_rel[1]) * bc->cell_m[1];
            float *o = out + ((size_t)i * tmpl_verts + v) * FT_BT_MESH_FLOATS;
            o[0] = (float)x;
            o[1] = (float)y;
            o[2] = (float)(h - eye_z_m - drop_per_m2 * (x * x + y * y));
            o[3] = (float)(n[0] / nl);
            o[4] = (float)(n[1] / nl);
            o[5] = (float)(n[2] / nl);
            o[6] = (float)h;
        }
    }
    return verts;
}
