/* SPDX-License-Identifier: MIT */
/* np_anim4d.h - a time-varying solid texture through 4-D noise, as PNG frames (anim4d.c). */
#ifndef NP_ANIM4D_H
#define NP_ANIM4D_H

#include <stddef.h>

/* Write dir/anim4d-00.png .. (frames of 192 x 192). 0, or -1 with err. */
int np_anim4d_frames(const char *dir, unsigned frames, char *err, size_t errlen);

#endif /* NP_ANIM4D_H */
