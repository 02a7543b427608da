/* SPDX-License-Identifier: MIT */
/* np_bench_units.h - `noisepipe bench`'s table of every registered unit (src/bench/bench_units.c; the command, cmd_bench.c, parses the options). */
#ifndef NP_BENCH_UNITS_H
#define NP_BENCH_UNITS_H

/*
 * Print the table: stb_perlin_noise3 on 65,536 points, then every unit (only
 * the unit called only, when not NULL) per input, through np_unit_eval_n, its
 * sweep kernel, its float reference and its cycle model, about secs of wall
 * time per figure, in its default configuration or, with only, in spec
 * ("key=value,..."; NULL: the default). NP_EXIT_OK, or NP_EXIT_USAGE with a
 * message (unknown unit, bad configuration).
 */
int np_bench_units(double secs, const char *only, const char *spec);

#endif /* NP_BENCH_UNITS_H */
