/* worst_pieces.h - the largest of a frame's per-piece error bounds.
 *
 * A method that bounds a frame's error block by block over the clipmap
 * cache (terrain/clip_cache.h: ft_clip_blocks_visit) keeps the pieces with
 * the largest bounds, largest first, to bound them again cell by cell, and
 * the largest bound of the others, which stands as it is. Fixed capacity,
 * no memory; noting a piece takes at most `cap` steps. */
#ifndef FT_WORST_PIECES_H
#define FT_WORST_PIECES_H

#include <stdint.h>

#include "terrain/clip_cache.h"

#define FT_WORST_PIECES_MAX 64u

typedef struct ft_worst_piece {
    double px;
    uint32_t level;
    ft_clip_box box; /* level-l samples: the cells' south-west corners */
} ft_worst_piece;

typedef struct ft_worst_pieces {
    ft_worst_piece piece[FT_WORST_PIECES_MAX]; /* the largest, descending */
    uint32_t cap, n;
    double rest_px;      /* the largest bound of a piece not kept (0: none) */
    uint32_t rest_level; /* its level */
} ft_worst_pieces;

/* Empty, keeping at most cap (1 .. FT_WORST_PIECES_MAX) pieces. */
void ft_worst_pieces_init(ft_worst_pieces *w, uint32_t cap);

/* Notes a piece's bound: kept if among the cap largest so far (the piece
 * it pushes out goes to the rest), else into the rest. An unknown bound
 * is +INF, never NaN. */
void ft_worst_pieces_note(ft_worst_pieces *w, uint32_t level, const ft_clip_box *box, double px);

#endif
