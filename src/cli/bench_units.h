/* SPDX-License-Identifier: MIT */
/* bench_units.h - internal: `noisepipe bench`'s table of every registered unit (bench_units.c). */
#ifndef BENCH_UNITS_H
#define BENCH_UNITS_H

/*
 * Print the table: stb_perlin_noise3 on 65,536 points, then every unit (only
 * the unit called only, when not NULL) per input, through np_unit_eval_n, its
 * sweep kernel, its float reference and its cycle model, about secs of wall
 * time per figure, in its default configuration or, with only, in spec
 * ("key=value,..."; NULL: the default). NP_EXIT_OK, or NP_EXIT_USAGE with a
 * message (unknown unit, bad configuration).
 */
int np_bench_units(double secs, const char *only, const char *spec);

#endif /* BENCH_UNITS_H */
