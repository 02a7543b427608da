/* SPDX-License-Identifier: MIT */
/*
 * np_tradeoff.h - `noisepipe report tradeoff --scene S`: the seed's
 * comparison (forward differences against per-pixel evaluation) in hardware
 * terms. For fdiff and texel, both within their proved bound (<= 1 LSB)
 * on the scene: gates, cycles per frame (the cycle-accurate models on the
 * scene's spans) and gates x cycles, for every set-up engine size P, as the
 * image grows (256, 512, 1024, 2048 square) and as the octave count grows
 * (1, 2, 4, 8 at 256 square). Writes DIR/tradeoff-NAME.{md,svg} (or the
 * table to standard output without -o). docs/tradeoff.md is its output for
 * the seed scenes.
 */
#ifndef NP_TRADEOFF_H
#define NP_TRADEOFF_H

/* Exit status: 0, or 2 (bad scene, or a unit refuses it), with the message on stderr. */
int np_report_tradeoff(const char *dir, const char *scene_path);

#endif /* NP_TRADEOFF_H */
