/* units.h - the constants and unit conversions, each defined once.
 * Names say the direction: FT_RAD_PER_DEG converts degrees to radians. */
#ifndef FT_UNITS_H
#define FT_UNITS_H

#define FT_PI 3.14159265358979323846
#define FT_RAD_PER_DEG (FT_PI / 180.0)
#define FT_DEG_PER_RAD (180.0 / FT_PI)
#define FT_M_PER_FT 0.3048 /* the international foot, exact */

#endif
