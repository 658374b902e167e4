/* font5x7.h - a 5x7 bitmap font for the failure annunciation overlay.
 *
 * Glyphs: ASCII space, 0-9, A-Z and  . , : ; - + / ( ) % _ = ! ? ' " # < >
 * Lower case maps to upper case. Any other character (control characters,
 * bytes >= 0x80, the other punctuation) draws a filled 5x7 box, so an
 * unexpected character is visible rather than silently dropped.
 *
 * A glyph is 7 row bytes, row 0 at the top. In each row bit 4 (0x10) is the
 * leftmost column and bit 0 the rightmost; bits 5-7 are always zero.
 * Drawn on a 6-column advance (one blank column between glyphs). */
#ifndef FT_FONT5X7_H
#define FT_FONT5X7_H

#include <stdint.h>

#define FT_FONT5X7_COLS 5u    /* columns per glyph */
#define FT_FONT5X7_ROWS 7u    /* rows per glyph */
#define FT_FONT5X7_ADVANCE 6u /* columns from one glyph to the next */

/* Every character with its own glyph (upper case only), NUL-terminated. */
extern const char ft_font5x7_charset[];

/* The 7 row bytes for c (never NULL): its glyph, the upper-case glyph for a
 * lower-case letter, or the filled box for a character outside the set. */
const uint8_t *ft_font5x7_glyph(char c);

/* 1 if c (or its upper case) has its own glyph, 0 if it draws the box. */
int ft_font5x7_has_glyph(char c);

#endif
