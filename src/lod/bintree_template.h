/* bintree_template.h - the one geometry every bintree tile is drawn with.
 *
 * The unit right triangle apex (0,0), left (1,0), right (0,1) in leg
 * coordinates (a, b), refined 2k times by longest-edge bisection (each
 * triangle splits at its hypotenuse midpoint into (m, apex, left) and
 * (m, right, apex), both counter-clockwise like the parent). Its vertices
 * are exactly the points (i, j) / 2^k with i + j <= 2^k, so a tile's legs
 * are cut into 2^k equal segments and every template vertex of a tile of
 * level <= 2n - 2k lands on a grid sample. 4^k triangles,
 * (2^k + 1)(2^k + 2)/2 vertices (16-bit indices up to k = 7). */
#ifndef FT_BINTREE_TEMPLATE_H
#define FT_BINTREE_TEMPLATE_H

#include <stdint.h>

#include "core/ft_status.h"

#define FT_BT_TEMPLATE_K_MIN 1u
#define FT_BT_TEMPLATE_K_MAX 6u

uint32_t ft_bt_template_vertices(uint32_t k);
uint32_t ft_bt_template_triangles(uint32_t k);
/* int16 scratch entries the build needs (6 per triangle). */
uint32_t ft_bt_template_scratch(uint32_t k);

/* Writes the 4^k template triangles into scratch as integer corners
 * (apex, left, right; 6 int16 each) in units of 2^-k, in the order of idx. */
void ft_bt_template_corners(uint32_t k, int16_t *scratch);

/* Writes uv (2 floats per vertex: a, b) and idx (3 per triangle). The
 * caller's arrays hold exactly the counts above. O(4^k), no recursion. */
ft_status ft_bt_template_build(uint32_t k, float *uv, uint16_t *idx, int16_t *scratch,
                               ft_error *err);

#endif
