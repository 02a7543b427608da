/* SPDX-License-Identifier: MIT */
/* Wind, dispersion and register quantisation of the wave unit (np_wave_host.h). */
#include <math.h>
#include <stdlib.h>

#include "np_math.h"
#include "np_wave_host.h"

static const double TWO_PI = 6.283185307179586;

double np_wave_height(double wind) { return NP_WAVE_ALPHA * wind * wind / NP_WAVE_G; }

double np_wave_amp_of_wind(double wind) { return np_wave_height(wind) / 2.0; }

double np_wave_omega(double k, double depth)
{
    if (!(depth > 0.0) || !(k > 0.0))
        return 0.0;
    if (depth >= 1e9)
        return sqrt(NP_WAVE_G * k);
    return sqrt(NP_WAVE_G * k * np_tanh(k * depth));
}

double np_wave_k_of_omega(double omega, double depth)
{
    if (!(omega > 0.0) || !(depth > 0.0))
        return 0.0;
    /* g k tanh(k D) rises with k; k lies between the deep-water value and the shallow-water omega / sqrt(g D). */
    double lo = omega * omega / NP_WAVE_G, hi = lo;
    double sh = omega / sqrt(NP_WAVE_G * depth);
    if (sh > hi)
        hi = sh;
    hi *= 2.0;
    for (int it = 0; it < 2000; it++) {
        double mid = lo + (hi - lo) / 2.0;
        if (mid <= lo || mid >= hi)
            break;
        if (NP_WAVE_G * mid * np_tanh(mid * depth) < omega * omega)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* x in turns (any real) to u32 Q0.32 modulo one turn, rounded to nearest. */
static uint32_t turns_u32(double x)
{
    double f = x - floor(x);
    double v = floor(f * 4294967296.0 + 0.5);
    return v >= 4294967296.0 ? 0u : (uint32_t)v;
}

static uint16_t q510(double m)
{
    double v = floor(m * 1024.0 + 0.5);
    return v < 0.0 ? 0u : v > 32767.0 ? 32767u : (uint16_t)v;
}

/* rad/m as s16 Q3.12, saturated (np_wave_regs_check refuses a Jacobian out of range). */
static int16_t q312(double k)
{
    double v = floor(k * 4096.0 + 0.5);
    return v < -32768.0 ? INT16_MIN : v > 32767.0 ? INT16_MAX : (int16_t)v;
}

void np_wave_steps(np_wave_regs *r)
{
    for (unsigned k = 0; k < r->n && k < NP_WAVE_MAX_TRAINS; k++) {
        double s, c;
        np_sincos_turns(ldexp((double)r->tr[k].kx, -32), &s, &c);
        r->tr[k].dc = (int32_t)floor(c * 1073741824.0 + 0.5);
        r->tr[k].ds = (int32_t)floor(s * 1073741824.0 + 0.5);
    }
}

unsigned np_wave_quantise(const np_wave_phys *p, np_wave_regs *r, unsigned *dropped)
{
    unsigned n = 0, drop = 0;
    for (unsigned k = 0; k < p->n && k < NP_WAVE_MAX_TRAINS; k++) {
        const np_wave_phys_train *t = &p->tr[k];
        double kk = sqrt(t->kx * t->kx + t->kz * t->kz);
        double Kx = t->kx * p->spacing / TWO_PI, Kz = t->kz * p->spacing / TWO_PI;
        if (!(kk > 0.0) || kk * p->spacing / TWO_PI >= 0.5) { /* lambda <= 2 spacings */
            drop++;
            continue;
        }
        np_wave_train *q = &r->tr[n++];
        q->kx = (int32_t)floor(Kx * 4294967296.0 + 0.5);
        q->kz = (int32_t)floor(Kz * 4294967296.0 + 0.5);
        q->phi = turns_u32(t->phi / TWO_PI);
        q->om = turns_u32(t->omega * p->dt / TWO_PI);
        q->amp = q510(t->amp);
        q->airr = q510(t->airr);
        q->kmx = q312(t->kx); /* read by the unit only with normals or fold */
        q->kmz = q312(t->kz);
        q->cx = (int16_t)floor(t->kx / kk * 16384.0 + 0.5);
        q->cz = (int16_t)floor(t->kz / kk * 16384.0 + 0.5);
        /* Rounding may make |c| exceed 1 by an LSB: shorten the longer component. */
        while ((int32_t)q->cx * q->cx + (int32_t)q->cz * q->cz > (1 << 28)) {
            if (abs(q->cx) >= abs(q->cz))
                q->cx = (int16_t)(q->cx - (q->cx > 0 ? 1 : -1));
            else
                q->cz = (int16_t)(q->cz - (q->cz > 0 ? 1 : -1));
        }
    }
    r->n = n;
    np_wave_steps(r); /* read by the unit only with sincos=recurrence */
    if (dropped)
        *dropped = drop;
    return n;
}
