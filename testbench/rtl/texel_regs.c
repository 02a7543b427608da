/* SPDX-License-Identifier: MIT */
/*
 * texel_regs - the texture registers of a built-in texture (np_ut_regs: what
 * `texture=NAME` selects for the units fdiff and texel) as text for the RTL
 * bench rtl_texel_tb.v, which drives np_texel.v's register inputs with them.
 *
 *   texel_regs NAME [FILE]     (FILE: default stdout)
 *
 * First "texture NAME", then one register a line, fixed-width hex of the register's two's-complement
 * bits (formats as np_texture.h):
 *   n_oct N            (decimal)
 *   cmap_n N           (decimal) and cmap_rep 0|1
 *   k I HEX            k[I] s48 Q23.24, 12 digits (A' .. J' = 0 .. 9)
 *   m O A B HEX        octave O's m[A][B] s24 Q7.16, 6 digits
 *   o O A HEX          o[A] s48 Q15.32, 12 digits
 *   amp O HEX          a'_O s32 Q17.14, 8 digits
 *   cmap E RRGGBB      colour entry E
 * The RTL takes the default register formats only: a texture with scene-sized
 * formats (k_bits or m_bits set) is refused (exit status 2).
 */
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "np_fixed.h"
#include "np_texture.h"
#include "unit_span.h"

int main(int argc, char **argv)
{
    if (argc < 2 || argc > 3) {
        fprintf(stderr, "usage: texel_regs TEXTURE [FILE]\n");
        return 2;
    }
    unsigned tex = 0;
    const char *name;
    while ((name = np_ut_texture_name(tex)) != NULL && strcmp(name, argv[1]) != 0)
        tex++;
    if (!name) {
        fprintf(stderr, "texel_regs: no built-in texture '%s'\n", argv[1]);
        return 2;
    }
    const np_tex_regs *r = np_ut_regs(tex);
    if (r->k_bits || r->m_bits) {
        fprintf(stderr, "texel_regs: texture '%s' has scene-sized register formats; the RTL takes the defaults\n",
                argv[1]);
        return 2;
    }
    FILE *f = argc == 3 ? fopen(argv[2], "w") : stdout;
    if (!f) {
        fprintf(stderr, "texel_regs: cannot write %s\n", argv[2]);
        return 2;
    }
    fprintf(f, "# np_tex_regs of a built-in texture (np_ut_regs), default formats\ntexture %s\n", argv[1]);
    fprintf(f, "n_oct %u\ncmap_n %u\ncmap_rep %d\n", r->n_oct, r->cmap_n, r->cmap_repeat ? 1 : 0);
    for (unsigned i = 0; i < 10; i++)
        fprintf(f, "k %u %012llx\n", i, (unsigned long long)np_trunc_u((uint64_t)r->k[i], NP_TEX_K_BITS));
    for (unsigned o = 0; o < r->n_oct; o++) {
        const np_tex_octave *t = &r->oct[o];
        for (unsigned a = 0; a < 3; a++)
            for (unsigned b = 0; b < 3; b++)
                fprintf(f, "m %u %u %u %06llx\n", o, a, b,
                        (unsigned long long)np_trunc_u((uint64_t)t->m[a][b], NP_TEX_M_BITS));
        for (unsigned a = 0; a < 3; a++)
            fprintf(f, "o %u %u %012llx\n", o, a, (unsigned long long)np_trunc_u((uint64_t)t->o[a], NP_TEX_O_BITS));
        fprintf(f, "amp %u %08llx\n", o,
                (unsigned long long)np_trunc_u((uint64_t)(int64_t)t->amp, NP_TEX_AMP_BITS));
    }
    for (unsigned e = 0; e < r->cmap_n; e++)
        fprintf(f, "cmap %u %02x%02x%02x\n", e, r->cmap[e][0], r->cmap[e][1], r->cmap[e][2]);
    if (f != stdout && fclose(f) != 0) {
        fprintf(stderr, "texel_regs: cannot write %s\n", argv[2]);
        return 2;
    }
    return 0;
}
