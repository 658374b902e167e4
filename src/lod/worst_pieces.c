/* worst_pieces.c - see worst_pieces.h. */
#include "lod/worst_pieces.h"

#include <string.h>

void ft_worst_pieces_init(ft_worst_pieces *w, uint32_t cap)
{
    memset(w, 0, sizeof *w);
    w->cap = (cap == 0u) ? 1u : (cap > FT_WORST_PIECES_MAX ? FT_WORST_PIECES_MAX : cap);
}

static void to_rest(ft_worst_pieces *w, uint32_t level, double px)
{
    if (px > w->rest_px) {
        w->rest_px = px;
        w->rest_level = level;
    }
}

void ft_worst_pieces_note(ft_worst_pieces *w, uint32_t level, const ft_clip_box *box, double px)
{
    if (w->n == w->cap) {
        const ft_worst_piece *last = &w->piece[w->cap - 1u];
        if (!(px > last->px)) {
            to_rest(w, level, px);
            return;
        }
        to_rest(w, last->level, last->px); /* it leaves the kept ones */
        --w->n;
    }
    uint32_t i = w->n++;
    while (i > 0u && w->piece[i - 1u].px < px) { /* at most cap steps */
        w->piece[i] = w->piece[i - 1u];
        --i;
    }
    const ft_worst_piece p = {px, level, *box};
    w->piece[i] = p;
}
