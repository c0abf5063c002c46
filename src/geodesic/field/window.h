/* window.h - window geometry of the exact field engine: the windows of one list trimmed against
 * each other (window.c). */
#ifndef TG_GEODESIC_FIELD_WINDOW_H
#define TG_GEODESIC_FIELD_WINDOW_H

#include "geodesic/field/engine.h"

/* Trims the windows of one list against each other (ids[0..n), sorted here by b0; keys: scratch
 * for n entries; len: the edge's length): touching windows of one source image are merged; where
 * one window is shorter than another by the relative margin over a part of their common interval
 * that touches an end of the other, that part is cut from the other (each window against the next
 * few by start: window.c's TRIM_NEXT); windows left empty get b1 <= b0. Each window's d0 and d1
 * are its distances at b0 and b1 (as the engine stores them) or NAN (unknown); an end trimming
 * moves gets NAN. Returns the number of pairs compared. */
uint64_t tg__windows_trim(tg__window* pool, uint32_t* ids, tg__win_key* keys, size_t n, double len, bool lines);

#endif
