/* bintree_mesh.c - the CPU mirror of shaders/bintree.vert.glsl (see
 * bintree_mesh.h). Each step below names the shader line it mirrors. */
#include "bintree_mesh.h"

#include <math.h>
#include <string.h>

#include "view_scale.h"

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
    const double split = morph ? FT_BT_SPLIT_FRACTION * tau : tau;
    u->k_px = cam->px_per_rad_k;
    u->split_px = split;
    u->band_px = (tau - split > 1e-6) ? tau - split : 1e-6;
    u->morph = (morph && isfinite(tau)) ? 1 : 0;
    for (int i = 0; i < 3; ++i) {
        u->axis[i] = cam->forward[i];
    }
    u->corner_cos = ft_view_corner_cos(cam);
}

/* ft_height: the coordinate clamped into the real grid, then one sample. */
static double height_at(const ft_bintree *bt, double gx, double gy)
{
    const double wx = (double)bt->width - 1.0, hy = (double)bt->height - 1.0;
    gx = (gx < 0.0) ? 0.0 : ((gx > wx) ? wx : gx);
    gy = (gy < 0.0) ? 0.0 : ((gy > hy) ? hy : gy);
    return (double)bt->heights_m[(size_t)gy * bt->width + (size_t)gx];
}

/* ft_earth_curve: lowered by k r^2, r the horizontal distance from the eye. */
static void earth_curve(const ft_bt_mesh_uniforms *u, const double p[3], double out[3])
{
    out[0] = p[0];
    out[1] = p[1];
    out[2] = p[2] - u->drop_per_m2 * (p[0] * p[0] + p[1] * p[1]);
}

/* u_origin_rel_eye_m + vec3(g * u_cell_m, h), curved */
static void position(const ft_bt_mesh_uniforms *u, const double g[2], double h, double out[3])
{
    const double p[3] = {u->origin_rel_eye_m[0] + g[0] * u->cell_m[0],
                         u->origin_rel_eye_m[1] + g[1] * u->cell_m[1],
                         u->origin_rel_eye_m[2] + h};
    earth_curve(u, p, out);
}

void ft_bt_mesh_vertex_of(const ft_bintree *bt, const ft_bt_mesh_uniforms *u,
                          const ft_bt_tile *tile, double a, double b, ft_bt_mesh_vertex *out)
{
    const double size[2] = {(double)bt->width, (double)bt->height};
    double g_raw[2], g[2];
    for (int i = 0; i < 2; ++i) {
        /* exact: a, b are multiples of 2^-k, the legs multiples of 2^k */
        g_raw[i] = (double)tile->apex[i] + a * (double)(tile->left[i] - tile->apex[i]) +
                   b * (double)(tile->right[i] - tile->apex[i]);
        g[i] = (g_raw[i] < size[i] - 1.0) ? g_raw[i] : size[i] - 1.0; /* padding collapses */
    }
    double h = height_at(bt, g[0], g[1]);

    /* central differences, one-sided at the grid edge */
    double lo[2], hi[2];
    for (int i = 0; i < 2; ++i) {
        lo[i] = (g[i] - 1.0 > 0.0) ? g[i] - 1.0 : 0.0;
        hi[i] = (g[i] + 1.0 < size[i] - 1.0) ? g[i] + 1.0 : size[i] - 1.0;
    }
    const double dhx = (height_at(bt, hi[0], g[1]) - height_at(bt, lo[0], g[1])) /
                       ((hi[0] - lo[0]) * u->cell_m[0]);
    const double dhy = (height_at(bt, g[0], hi[1]) - height_at(bt, g[0], lo[1])) /
                       ((hi[1] - lo[1]) * u->cell_m[1]);
    const double nlen = sqrt(dhx * dhx + dhy * dhy + 1.0);
    out->normal[0] = -dhx / nlen;
    out->normal[1] = -dhy / nlen;
    out->normal[2] = 1.0 / nlen;

    double w = 1.0;
    int32_t e0[2], e1[2], c[2];
    /* ft_morph_error(g_raw): the rule is ft_bt_vertex_morph's (bintree.h) */
    if (u->morph && ft_bt_vertex_morph(bt, (int32_t)g_raw[0], (int32_t)g_raw[1], e0, e1, c)) {
        const size_t li = (size_t)((uint32_t)c[1] >> bt->k) * bt->lattice_side +
                          ((uint32_t)c[0] >> bt->k);
        const size_t lattice = (size_t)bt->lattice_side * bt->lattice_side;
        if (li < lattice) { /* always: c is a diamond centre of the padded domain */
            const double err_m = (double)bt->err_m[li];
            double p_true[3];
            position(u, g, h, p_true);
            double dist = sqrt(p_true[0] * p_true[0] + p_true[1] * p_true[1] +
                               p_true[2] * p_true[2]);
            dist = (dist > 1e-3) ? dist : 1e-3;
            double cc = (p_true[0] * u->axis[0] + p_true[1] * u->axis[1] +
                         p_true[2] * u->axis[2]) / dist;
            cc = (cc > u->corner_cos) ? cc : u->corner_cos;
            const double rho = u->k_px * err_m / (dist * cc * cc);
            w = (rho - u->split_px) / u->band_px;
            w = (w < 0.0) ? 0.0 : ((w > 1.0) ? 1.0 : w);
            const double mid = 0.5 * (height_at(bt, e0[0], e0[1]) + height_at(bt, e1[0], e1[1]));
            h = mid * (1.0 - w) + h * w; /* mix(mid, h, w) */
        }
    }
    out->morph_w = w;
    out->height_m = h;
    position(u, g, h, out->pos_rel_eye_m);
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
