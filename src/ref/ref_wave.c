/* SPDX-License-Identifier: MIT */
/*
 * The float references of the wave unit (np_wave.h): one in double from the
 * unit's own registers (the bit-exact model's contract: within
 * np_wave_error_bound_lsb), one from the unquantised physical parameters
 * (np_wave_phys), so that the registers' quantisation is reported on its own.
 * sin and cos in turns from np_math (never libm's).
 */
#include <math.h>

#include "np_math.h"
#include "np_wave_ref.h"

double np_ref_wave_rom_word(unsigned a)
{
    return floor(np_sin_turns((double)a / 4096.0) * 131072.0 + 0.5);
}

/* The phase u32 in turns, exactly. */
static const double NP_TWO_PI = 6.283185307179586; /* 2 pi rounded to double */

static double turns(uint32_t th) { return ldexp((double)th, -32); }

/* The gain G = min(d, M)/M min(g, gcap) in double, and eq. (8)'s w = sin(p1) sin(p2) (0 without irr). */
static double ref_gain(const np_wave_unit *u, const np_wave_in *in, double *w)
{
    const np_wave_regs *r = &u->r;
    *w = 0.0;
    if (u->c.irr)
        *w = np_sin_turns(turns(r->pu * in->u + r->pt * in->t)) * np_sin_turns(turns(r->pv * in->v));
    unsigned d = 0, m = 1u << r->mlog2;
    if (in->v < r->width) {
        unsigned a = in->v, b = (unsigned)r->width - 1u - in->v;
        d = a < b ? a : b;
    }
    double g = (double)(in->g < r->gcap ? in->g : r->gcap) / 16384.0;
    return (double)(d < m ? d : m) / (double)m * g;
}

/* A train's exact phase, its sin and cos in double, and its amplitude ap = A - a w. */
static double ref_lane(const np_wave_unit *u, const np_wave_train *t, const np_wave_in *in, double w, double *s,
                       double *c)
{
    uint32_t th = (uint32_t)t->kx * in->i + (uint32_t)t->kz * in->j + t->phi + in->ph - t->om * in->t;
    np_sincos_turns(turns(th), s, c);
    return (double)t->amp / 1024.0 - (u->c.irr ? (double)t->airr / 1024.0 * w : 0.0);
}

void np_ref_wave(const np_wave_unit *u, const np_wave_in *in, double out[3])
{
    const np_wave_regs *r = &u->r;
    double w, gain = ref_gain(u, in, &w);
    double y = 0.0, x = 0.0, z = 0.0;
    for (unsigned k = 0; k < r->n; k++) {
        const np_wave_train *t = &r->tr[k];
        double s, c, ap = ref_lane(u, t, in, w, &s, &c);
        y += ap * c;
        x -= ap * s * ((double)t->cx / 16384.0);
        z -= ap * s * ((double)t->cz / 16384.0);
    }
    out[0] = gain * y;
    if (u->c.cap)
        out[0] += (double)r->b / 1024.0 * np_sin_turns(turns((uint32_t)in->r * r->omc * in->t));
    out[1] = gain * x;
    out[2] = gain * z;
}

void np_ref_wave_jac(const np_wave_unit *u, const np_wave_in *in, double j[6], double n[3])
{
    /* The same G, ap and phases as np_ref_wave; the terms of np_wave.h in double, then the normal. */
    const np_wave_regs *r = &u->r;
    double w, gain = ref_gain(u, in, &w);
    for (unsigned q = 0; q < 6; q++)
        j[q] = 0.0;
    for (unsigned k = 0; k < r->n; k++) {
        const np_wave_train *t = &r->tr[k];
        double s, c, ap = ref_lane(u, t, in, w, &s, &c);
        double cx = (double)t->cx / 16384.0, cz = (double)t->cz / 16384.0;
        double kx = (double)t->kmx / 4096.0, kz = (double)t->kmz / 4096.0;
        j[0] -= ap * c * cx * kx;
        j[1] -= ap * c * cx * kz;
        j[2] -= ap * c * cz * kx;
        j[3] -= ap * c * cz * kz;
        j[4] -= ap * s * kx;
        j[5] -= ap * s * kz;
    }
    for (unsigned q = 0; q < 6; q++)
        j[q] *= gain;
    double a = 1.0 + j[0], dd = 1.0 + j[3];
    n[0] = j[5] * j[2] - dd * j[4];
    n[1] = a * dd - j[1] * j[2];
    n[2] = j[1] * j[4] - j[5] * a;
}

void np_ref_wave_phys(const np_wave_phys *p, double i, double j, double frame, double ph_turns, double out[3])
{
    double y = 0.0, x = 0.0, z = 0.0, tsec = frame * p->dt;
    for (unsigned k = 0; k < p->n; k++) {
        const np_wave_phys_train *t = &p->tr[k];
        double kk = sqrt(t->kx * t->kx + t->kz * t->kz);
        /* Phase in turns: (k . p0 + phi - omega t) / 2 pi. */
        double tau = (t->kx * i * p->spacing + t->kz * j * p->spacing + t->phi - t->omega * tsec) / NP_TWO_PI +
                     ph_turns;
        double s, c;
        np_sincos_turns(tau, &s, &c);
        y += t->amp * c;
        x -= t->kx / kk * t->amp * s;
        z -= t->kz / kk * t->amp * s;
    }
    out[0] = y;
    out[1] = x;
    out[2] = z;
}
