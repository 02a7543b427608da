/* SPDX-License-Identifier: MIT */
/* The Gerstner wave unit: bit-exact model, pipe, datapath declaration (np_wave.h). */
#include "np_wave.h"

#include <math.h>
#include <string.h>

NP_STATIC_ASSERT((-1 >> 1) == -1, "arithmetic right shift");

/*
 * The quarter-wave ROM at its finest resolution (L = 10): R[a] =
 * round(2^17 sin(2 pi a / 4096)), a = 0 .. 1024, generated with np_math
 * (np_ref_wave_rom_word); wave.rom regenerates every entry and compares.
 */
static const uint32_t rom10[1025] = {
    0, 201, 402, 603, 804, 1005, 1206, 1407, 1608, 1809, 2011, 2212,
    2413, 2614, 2815, 3016, 3217, 3418, 3619, 3820, 4021, 4222, 4423, 4623,
    4824, 5025, 5226, 5427, 5628, 5829, 6030, 6231, 6431, 6632, 6833, 7034,
    7235, 7435, 7636, 7837, 8037, 8238, 8439, 8639, 8840, 9041, 9241, 9442,
    9642, 9843, 10043, 10244, 10444, 10645, 10845, 11045, 11246, 11446, 11646, 11846,
    12047, 12247, 12447, 12647, 12847, 13047, 13247, 13447, 13647, 13847, 14047, 14247,
    14447, 14647, 14847, 15046, 15246, 15446, 15645, 15845, 16045, 16244, 16444, 16643,
    16843, 17042, 17241, 17441, 17640, 17839, 18038, 18237, 18436, 18635, 18834, 19033,
    19232, 19431, 19630, 19829, 20027, 20226, 20425, 20623, 20822, 21020, 21219, 21417,
    21615, 21814, 22012, 22210, 22408, 22606, 22804, 23002, 23200, 23398, 23596, 23794,
    23991, 24189, 24387, 24584, 24782, 24979, 25176, 25374, 25571, 25768, 25965, 26162,
    26359, 26556, 26753, 26950, 27147, 27343, 27540, 27736, 27933, 28129, 28326, 28522,
    28718, 28914, 29110, 29306, 29502, 29698, 29894, 30090, 30285, 30481, 30676, 30872,
    31067, 31262, 31458, 31653, 31848, 32043, 32238, 32433, 32627, 32822, 33017, 33211,
    33406, 33600, 33794, 33989, 34183, 34377, 34571, 34765, 34959, 35152, 35346, 35540,
    35733, 35926, 36120, 36313, 36506, 36699, 36892, 37085, 37278, 37471, 37663, 37856,
    38048, 38241, 38433, 38625, 38817, 39009, 39201, 39393, 39585, 39776, 39968, 40159,
    40350, 40542, 40733, 40924, 41115, 41306, 41497, 41687, 41878, 42068, 42259, 42449,
    42639, 42829, 43019, 43209, 43399, 43588, 43778, 43967, 44157, 44346, 44535, 44724,
    44913, 45102, 45291, 45479, 45668, 45856, 46045, 46233, 46421, 46609, 46797, 46985,
    47172, 47360, 47547, 47734, 47922, 48109, 48296, 48483, 48669, 48856, 49042, 49229,
    49415, 49601, 49787, 49973, 50159, 50345, 50530, 50716, 50901, 51086, 51271, 51456,
    51641, 51826, 52011, 52195, 52380, 52564, 52748, 52932, 53116, 53300, 53483, 53667,
    53850, 54033, 54216, 54399, 54582, 54765, 54948, 55130, 55312, 55495, 55677, 55859,
    56041, 56222, 56404, 56585, 56766, 56948, 57129, 57310, 57490, 57671, 57851, 58032,
    58212, 58392, 58572, 58752, 58931, 59111, 59290, 59470, 59649, 59828, 60007, 60185,
    60364, 60542, 60720, 60899, 61076, 61254, 61432, 61610, 61787, 61964, 62141, 62318,
    62495, 62672, 62848, 63025, 63201, 63377, 63553, 63729, 63904, 64080, 64255, 64430,
    64605, 64780, 64955, 65129, 65304, 65478, 65652, 65826, 66000, 66173, 66347, 66520,
    66693, 66866, 67039, 67212, 67384, 67557, 67729, 67901, 68073, 68245, 68416, 68588,
    68759, 68930, 69101, 69272, 69442, 69613, 69783, 69953, 70123, 70293, 70463, 70632,
    70801, 70970, 71139, 71308, 71477, 71645, 71814, 71982, 72150, 72317, 72485, 72652,
    72820, 72987, 73154, 73320, 73487, 73653, 73820, 73986, 74152, 74317, 74483, 74648,
    74813, 74978, 75143, 75308, 75472, 75637, 75801, 75965, 76128, 76292, 76455, 76619,
    76782, 76945, 77107, 77270, 77432, 77594, 77756, 77918, 78079, 78241, 78402, 78563,
    78724, 78885, 79045, 79205, 79366, 79525, 79685, 79845, 80004, 80163, 80322, 80481,
    80640, 80798, 80956, 81114, 81272, 81430, 81587, 81745, 81902, 82058, 82215, 82372,
    82528, 82684, 82840, 82996, 83151, 83307, 83462, 83617, 83771, 83926, 84080, 84234,
    84388, 84542, 84696, 84849, 85002, 85155, 85308, 85460, 85613, 85765, 85917, 86069,
    86220, 86371, 86523, 86673, 86824, 86975, 87125, 87275, 87425, 87575, 87724, 87873,
    88023, 88171, 88320, 88469, 88617, 88765, 88913, 89060, 89208, 89355, 89502, 89649,
    89795, 89942, 90088, 90234, 90379, 90525, 90670, 90815, 90960, 91105, 91249, 91394,
    91538, 91681, 91825, 91968, 92111, 92254, 92397, 92540, 92682, 92824, 92966, 93107,
    93249, 93390, 93531, 93672, 93812, 93953, 94093, 94233, 94372, 94512, 94651, 94790,
    94929, 95067, 95205, 95343, 95481, 95619, 95756, 95894, 96030, 96167, 96304, 96440,
    96576, 96712, 96847, 96983, 97118, 97253, 97388, 97522, 97656, 97790, 97924, 98058,
    98191, 98324, 98457, 98589, 98722, 98854, 98986, 99117, 99249, 99380, 99511, 99642,
    99772, 99903, 100033, 100162, 100292, 100421, 100550, 100679, 100808, 100936, 101064, 101192,
    101320, 101447, 101575, 101702, 101828, 101955, 102081, 102207, 102333, 102458, 102584, 102709,
    102833, 102958, 103082, 103206, 103330, 103454, 103577, 103700, 103823, 103946, 104068, 104190,
    104312, 104434, 104555, 104676, 104797, 104918, 105038, 105158, 105278, 105398, 105517, 105636,
    105755, 105874, 105992, 106110, 106228, 106346, 106463, 106580, 106697, 106814, 106930, 107047,
    107162, 107278, 107394, 107509, 107624, 107738, 107853, 107967, 108081, 108194, 108308, 108421,
    108534, 108646, 108758, 108871, 108982, 109094, 109205, 109316, 109427, 109538, 109648, 109758,
    109868, 109977, 110087, 110196, 110304, 110413, 110521, 110629, 110737, 110844, 110951, 111058,
    111165, 111271, 111377, 111483, 111589, 111694, 111799, 111904, 112009, 112113, 112217, 112321,
    112424, 112527, 112630, 112733, 112836, 112938, 113040, 113141, 113243, 113344, 113445, 113545,
    113645, 113746, 113845, 113945, 114044, 114143, 114242, 114340, 114438, 114536, 114634, 114731,
    114828, 114925, 115022, 115118, 115214, 115310, 115405, 115500, 115595, 115690, 115784, 115878,
    115972, 116066, 116159, 116252, 116345, 116437, 116529, 116621, 116713, 116804, 116895, 116986,
    117077, 117167, 117257, 117347, 117436, 117525, 117614, 117703, 117791, 117879, 117967, 118054,
    118142, 118229, 118315, 118402, 118488, 118574, 118659, 118744, 118829, 118914, 118998, 119083,
    119166, 119250, 119333, 119416, 119499, 119582, 119664, 119746, 119827, 119909, 119990, 120070,
    120151, 120231, 120311, 120391, 120470, 120549, 120628, 120706, 120785, 120863, 120940, 121018,
    121095, 121172, 121248, 121324, 121400, 121476, 121551, 121626, 121701, 121776, 121850, 121924,
    121997, 122071, 122144, 122217, 122289, 122361, 122433, 122505, 122576, 122647, 122718, 122789,
    122859, 122929, 122998, 123068, 123137, 123206, 123274, 123342, 123410, 123478, 123545, 123612,
    123679, 123745, 123811, 123877, 123943, 124008, 124073, 124138, 124202, 124266, 124330, 124393,
    124457, 124519, 124582, 124644, 124706, 124768, 124830, 124891, 124952, 125012, 125073, 125133,
    125192, 125252, 125311, 125370, 125428, 125486, 125544, 125602, 125659, 125716, 125773, 125829,
    125886, 125941, 125997, 126052, 126107, 126162, 126216, 126270, 126324, 126378, 126431, 126484,
    126536, 126588, 126640, 126692, 126744, 126795, 126845, 126896, 126946, 126996, 127046, 127095,
    127144, 127193, 127241, 127289, 127337, 127384, 127432, 127479, 127525, 127571, 127617, 127663,
    127709, 127754, 127799, 127843, 127887, 127931, 127975, 128018, 128061, 128104, 128146, 128188,
    128230, 128272, 128313, 128354, 128394, 128434, 128474, 128514, 128553, 128593, 128631, 128670,
    128708, 128746, 128783, 128821, 128858, 128894, 128931, 128967, 129002, 129038, 129073, 129108,
    129142, 129177, 129210, 129244, 129277, 129310, 129343, 129375, 129408, 129439, 129471, 129502,
    129533, 129563, 129594, 129624, 129653, 129683, 129712, 129740, 129769, 129797, 129825, 129852,
    129880, 129906, 129933, 129959, 129985, 130011, 130036, 130062, 130086, 130111, 130135, 130159,
    130182, 130206, 130228, 130251, 130273, 130295, 130317, 130338, 130360, 130380, 130401, 130421,
    130441, 130460, 130480, 130499, 130517, 130536, 130554, 130571, 130589, 130606, 130623, 130639,
    130655, 130671, 130687, 130702, 130717, 130731, 130746, 130760, 130774, 130787, 130800, 130813,
    130825, 130838, 130849, 130861, 130872, 130883, 130894, 130904, 130914, 130924, 130933, 130942,
    130951, 130960, 130968, 130976, 130983, 130990, 130997, 131004, 131010, 131016, 131022, 131027,
    131033, 131037, 131042, 131046, 131050, 131053, 131057, 131060, 131062, 131064, 131066, 131068,
    131070, 131071, 131071, 131072, 131072
};

uint32_t np_wave_rom(unsigned a) { return a <= 1024u ? rom10[a] : 0u; }

static inline int32_t wave_sin(uint32_t th, unsigned rom_log2)
{
    /* Written without branches on the phase (the quadrant is data): the same arithmetic as the prose above. */
    const unsigned L = rom_log2, sh = 30u - L;
    const uint32_t q = th >> 30, x0 = th & UINT32_C(0x3fffffff);
    const uint32_t mirror = (uint32_t)0 - (q & 1u); /* all ones in quadrants 1 and 3 */
    const uint32_t x = (((UINT32_C(1) << 30) - x0) & mirror) | (x0 & ~mirror); /* the mirror, exact: (0, 2^30] */
    const uint32_t a = x >> sh;                                   /* 0 .. 2^L; 2^L only for x = 2^30 (f = 0) */
    const uint32_t a1 = a + (uint32_t)(a < (UINT32_C(1) << L));   /* R[2^L] = 2^17 is its own successor */
    const uint32_t f = (x >> (sh - NP_WAVE_IFRAC)) & (uint32_t)NP_MASK(NP_WAVE_IFRAC);
    const int64_t r0 = rom10[a << (10u - L)], r1 = rom10[a1 << (10u - L)];
    const int32_t v = (int32_t)(r0 + np_shr_round_half_up((r1 - r0) * (int64_t)f, NP_WAVE_IFRAC));
    const int32_t neg = -(int32_t)(q >> 1); /* all ones in quadrants 2 and 3 */
    return (v ^ neg) - neg;
}

int32_t np_wave_sin(uint32_t th, unsigned rom_log2) { return wave_sin(th, rom_log2); }

double np_wave_sin_bound(unsigned rom_log2)
{
    const double two_pi = 6.283185307179586;
    double h = two_pi * np_pow2i(-(int)rom_log2 - 2);
    double drop = two_pi * (np_pow2i(30 - (int)rom_log2 - NP_WAVE_IFRAC) - 1.0) * np_pow2i(-32);
    return np_pow2i(-17) + h * h / 8.0 + drop;
}

np_wave_cfg np_wave_cfg_default(void)
{
    np_wave_cfg c = { 2u, 1u, 1u, NP_WAVE_ROM_DEF, 0u, 0u, NP_WAVE_SINCOS_ROM, NP_WAVE_RESET_DEF };
    return c;
}

const char *np_wave_cfg_check(const np_wave_cfg *c)
{
    if (c->trains < 1 || c->trains > NP_WAVE_MAX_TRAINS)
        return "trains out of range 1..4";
    if (c->irr > 1 || c->cap > 1)
        return "irr and cap are 0 or 1";
    if (c->normals > 1 || c->fold > 1)
        return "normals and fold are 0 or 1";
    if (c->sincos > NP_WAVE_SINCOS_RECURRENCE)
        return "sincos is rom or recurrence";
    if (c->reset < 1 || c->reset > NP_WAVE_RESET_MAX)
        return "reset out of range 1..65536";
    if (c->sincos == NP_WAVE_SINCOS_ROM && c->reset != NP_WAVE_RESET_DEF)
        return "reset is the recurrence's re-set-up interval: it needs sincos=recurrence";
    if (c->sincos == NP_WAVE_SINCOS_RECURRENCE && c->reset < c->trains)
        return "reset below trains: the lanes re-set up in turn, one a transaction (reset >= trains)";
    if (c->rom_log2 < NP_WAVE_ROM_MIN || c->rom_log2 > NP_WAVE_ROM_MAX)
        return "rom_log2 out of range 6..10";
    return NULL;
}

int64_t np_wave_range_lsb(const np_wave_regs *r, int with_b)
{
    /* (gcap / 2^14) sum (amp + airr), rounded up, plus b. */
    int64_t sum = 0;
    for (unsigned k = 0; k < r->n && k < NP_WAVE_MAX_TRAINS; k++)
        sum += (int64_t)r->tr[k].amp + r->tr[k].airr;
    int64_t m = (sum * r->gcap + (INT64_C(1) << NP_WAVE_GAIN_FRAC) - 1) >> NP_WAVE_GAIN_FRAC;
    return m + (with_b ? (int64_t)r->b : 0);
}

const char *np_wave_regs_check(const np_wave_cfg *c, const np_wave_regs *r)
{
    if (r->n < 1 || r->n > c->trains)
        return "more trains than the unit's lanes (or none)";
    for (unsigned k = 0; k < r->n; k++) {
        const np_wave_train *t = &r->tr[k];
        if (t->amp > 0x7fffu || t->airr > 0x7fffu)
            return "an amplitude over u15";
        if (t->airr > t->amp)
            return "irregular height a > A (eq. (8) requires a <= A)";
        if ((int64_t)t->cx * t->cx + (int64_t)t->cz * t->cz > (INT64_C(1) << (2 * NP_WAVE_DIR_FRAC)))
            return "direction (cx, cz) longer than 1";
    }
    if (r->mlog2 > NP_WAVE_MLOG2_MAX)
        return "smoothing margin over 2^6";
    if (r->gcap > 0x7fffu || r->b > 0x7fffu)
        return "gcap or b over u15";
    if (np_wave_range_lsb(r, 1) > 0x7fff)
        return "output range: (gcap/2^14) sum (A + a) + b exceeds 32 m (s16 Q5.10)";
    if (c->sincos == NP_WAVE_SINCOS_RECURRENCE) {
        np_wave_unit u = { *c, *r };
        if (np_wave_error_bound_lsb(&u) >= 1.0)
            return "sincos=recurrence: the error bound against the reference reaches 1 LSB (a shorter reset, or "
                   "smaller amplitudes)";
    }
    if (np_wave_has_jac(c)) {
        int64_t jb[NP_WAVE_NJ];
        np_wave_jac_range_lsb(r, jb);
        for (unsigned q = 0; q < NP_WAVE_NJ; q++)
            if (jb[q] > (INT64_C(1) << (NP_WAVE_JAC_BITS - 1)) - 1)
                return "Jacobian range: (gcap/2^14) sum (A + a) |c km| or |km| reaches 8 (s18 Q3.14)";
        np_wave_unit u = { *c, *r };
        np_wave_jac_bound b = np_wave_jac_error_bound(&u);
        double w = 0.0; /* the outputs' bound (the terms are internal: their own bounds need not be under an LSB) */
        for (unsigned q = 0; q < 3; q++)
            w = fmax(w, b.nb[q] * np_pow2i(NP_WAVE_N_FRAC));
        if (w >= 1.0)
            return "normal: the error bound against the reference reaches 1 LSB of s20 Q9.10: "
                   "the waves are too steep for the normal's formats";
    }
    return NULL;
}

/* The register products e of train t: cx kmx, cx kmz, cz kmx, cz kmz (s31 Q4.26, exact). */
static inline void lane_e(const np_wave_train *t, int64_t e[4])
{
    e[0] = (int64_t)t->cx * t->kmx;
    e[1] = (int64_t)t->cx * t->kmz;
    e[2] = (int64_t)t->cz * t->kmx;
    e[3] = (int64_t)t->cz * t->kmz;
}

void np_wave_jac_range_lsb(const np_wave_regs *r, int64_t jb[NP_WAVE_NJ])
{
    /*
     * In LSB of Q3.14: (gcap/2^14) sum (amp + airr)/2^10 |e|/2^26 2^14 =
     * gcap sum (amp + airr) |e| / 2^36 (and gcap sum (amp + airr) |km| / 2^22
     * for yx, yz), rounded up, plus 1 LSB for the roundings (the final 1/2 and
     * the lanes' n Gm 2^-30, i.e. n Gm 2^-16 LSB): |ap| <= amp + airr, |yq| <=
     * |ap| + 2^-18, |c|, |s| <= 1.
     */
    np_u128 acc[NP_WAVE_NJ] = { 0 };
    for (unsigned k = 0; k < r->n && k < NP_WAVE_MAX_TRAINS; k++) {
        const np_wave_train *t = &r->tr[k];
        int64_t e[4], a = (int64_t)t->amp + t->airr;
        lane_e(t, e);
        for (unsigned q = 0; q < 4; q++)
            acc[q] += (np_u128)(uint64_t)(a * (e[q] < 0 ? -e[q] : e[q]));
        acc[4] += (np_u128)(uint64_t)(a * (t->kmx < 0 ? -t->kmx : t->kmx));
        acc[5] += (np_u128)(uint64_t)(a * (t->kmz < 0 ? -t->kmz : t->kmz));
    }
    for (unsigned q = 0; q < NP_WAVE_NJ; q++) {
        unsigned sh = q < 4 ? 36u : 22u;
        np_u128 v = acc[q] * r->gcap;
        jb[q] = (int64_t)((v + (((np_u128)1 << sh) - 1u)) >> sh) + 1;
    }
}

/* --- the datapath's pieces, shared by the stages and np_wave_eval --- */

static inline uint32_t lane_phase(const np_wave_train *t, const np_wave_in *in)
{
    return (uint32_t)t->kx * in->i + (uint32_t)t->kz * in->j + t->phi + in->ph - t->om * in->t;
}

static inline unsigned smoothing(const np_wave_regs *r, uint16_t v)
{
    unsigned d = 0, m = 1u << r->mlog2;
    if (v < r->width) {
        unsigned a = v, b = (unsigned)r->width - 1u - v;
        d = a < b ? a : b;
    }
    return d < m ? d : m;
}

static inline int32_t lane_amp(const np_wave_train *t, unsigned irr, int32_t w)
{
    int64_t ap = (int64_t)t->amp << (NP_WAVE_SIN_FRAC - NP_WAVE_AMP_FRAC);
    if (irr)
        ap -= np_shr_round_half_up((int64_t)t->airr * w, NP_WAVE_AMP_FRAC);
    return (int32_t)ap;
}

static inline uint32_t gain_of(const np_wave_regs *r, unsigned sm, uint16_t g)
{
    return (uint32_t)sm * (g < r->gcap ? g : r->gcap);
}

static inline np_wave_out out_of(const np_wave_regs *r, int64_t ys, int64_t xs, int64_t zs, int64_t bc, uint32_t gm)
{
    unsigned ml = r->mlog2;
    np_wave_out o;
    int64_t yv = ys * (int64_t)gm + bc * ((int64_t)1 << (NP_WAVE_GAIN_FRAC + ml));
    o.y = (int16_t)np_sat_s(np_shr_round_half_up(yv, 31u + ml), NP_WAVE_OUT_BITS);
    o.dx = (int16_t)np_sat_s(np_shr_round_half_up(xs * (int64_t)gm, 35u + ml), NP_WAVE_OUT_BITS);
    o.dz = (int16_t)np_sat_s(np_shr_round_half_up(zs * (int64_t)gm, 35u + ml), NP_WAVE_OUT_BITS);
    return o;
}

/*
 * sincos=recurrence: lane k re-sets up from the ROM when (i + k) mod N = 0
 * (N = reset; the lanes in turn, so one set-up a transaction) and otherwise
 * rotates its (c, s), s32 Q1.30, by the step (dc, ds) once per step along i
 * (np_wave_recur_step: c' = round((c dc - s ds) / 2^30), s' = round((s dc +
 * c ds) / 2^30)). A transaction's value is that of a lane which walked the row
 * from its last set-up, m = (i + k) mod N steps back, with this transaction's
 * j, t and ph: the set-up phase is th - kx m (exact, mod 2^32), the set-up
 * values the ROM's cos and sin times 2^13, and the outputs c, s = round(Q1.30
 * / 2^13) clamped to [-2^17, 2^17] (s19 Q1.17). So every transaction is
 * self-contained (vectors, verify), and a stream that walks rows along i with
 * constant j, t and ph gets exactly what the stateful lane holds.
 */
static inline void lane_rec(const np_wave_unit *u, unsigned k, const np_wave_in *in, uint32_t th, int32_t *c,
                            int32_t *s)
{
    const np_wave_train *t = &u->r.tr[k];
    const unsigned L = u->c.rom_log2;
    const uint32_t m = ((uint32_t)in->i + k) % u->c.reset;
    const uint32_t th0 = th - (uint32_t)t->kx * m;
    const int64_t up = INT64_C(1) << 13, one = INT64_C(1) << NP_WAVE_SIN_FRAC;
    np_wave_recur q;
    np_wave_recur_setup(&q, (int64_t)wave_sin(th0 + (UINT32_C(1) << 30), L) * up, (int64_t)wave_sin(th0, L) * up, t->dc,
                        t->ds);
    for (uint32_t n = 0; n < m; n++)
        np_wave_recur_step(&q);
    int64_t cv = np_shr_round_half_up(q.c, 13), sv = np_shr_round_half_up(q.s, 13);
    *c = (int32_t)(cv > one ? one : cv < -one ? -one : cv);
    *s = (int32_t)(sv > one ? one : sv < -one ? -one : sv);
}

/* A lane's cos and sin: the ROM's (np_wave_sin), or the recurrence's (lane_rec). */
static inline void lane_cs(const np_wave_unit *u, unsigned k, const np_wave_in *in, uint32_t th, int32_t *c, int32_t *s)
{
    if (u->c.sincos == NP_WAVE_SINCOS_RECURRENCE) {
        lane_rec(u, k, in, th, c, s);
        return;
    }
    *c = wave_sin(th + (UINT32_C(1) << 30), u->c.rom_log2);
    *s = wave_sin(th, u->c.rom_log2);
}

void np_wave_lane_sincos(const np_wave_unit *u, unsigned k, const np_wave_in *in, int32_t *c, int32_t *s)
{
    lane_cs(u, k, in, lane_phase(&u->r.tr[k], in), c, s);
}

double np_wave_recur_bound(unsigned rom_log2, uint64_t m)
{
    /*
     * The set-up's error sqrt(2) e_s (a vector of two ROM values); each step
     * adds at most 2^-30.5 (the two roundings) + 2^-30 |v| (the step's
     * quantisation, |dc - cos|, |ds - sin| <= 2^-31) < 2^-29 while |v| < 1.29,
     * and rotates the error without growing it; the output's rounding 2^-18.
     */
    return 1.4142135623730951 * np_wave_sin_bound(rom_log2) + (double)m * np_pow2i(-29) + np_pow2i(-18);
}

double np_wave_lane_bound(const np_wave_cfg *c)
{
    return c->sincos == NP_WAVE_SINCOS_RECURRENCE ? np_wave_recur_bound(c->rom_log2, c->reset - 1u)
                                                  : np_wave_sin_bound(c->rom_log2);
}

/*
 * A lane's Jacobian products (normals or fold): yq = round(ap c / 2^17) s24
 * Q6.17 (the product ap c that yc rounds, rounded a second way), lj[0..3] =
 * round(yq e / 2^14) s40 Q10.29, lj[4], lj[5] = sa kmx, sa kmz s39 Q9.29 exact.
 */
static inline void lane_jac(const np_wave_train *t, int64_t ap, int64_t c, int64_t sa, int64_t lj[NP_WAVE_NJ],
                            int64_t *yq)
{
    int64_t e[4];
    lane_e(t, e);
    int64_t q = np_shr_round_half_up(ap * c, NP_WAVE_SIN_FRAC);
    for (unsigned m = 0; m < 4; m++)
        lj[m] = np_shr_round_half_up(q * e[m], 14);
    lj[4] = sa * t->kmx;
    lj[5] = sa * t->kmz;
    *yq = q;
}

/* The terms: j = round(js G / 2^(29 + mlog2)), s18 Q3.14 (a 128-bit product: no overflow if the check is bypassed). */
static inline void jac_terms(const np_wave_regs *r, const int64_t js[NP_WAVE_NJ], uint32_t gm, np_wave_jac *j)
{
    const unsigned sh = 29u + r->mlog2;
    const int64_t hi = (INT64_C(1) << (NP_WAVE_JAC_BITS - 1)) - 1;
    for (unsigned m = 0; m < NP_WAVE_NJ; m++) {
        np_s128 v = ((np_s128)js[m] * gm + ((np_s128)1 << (sh - 1u))) >> sh;
        j->j[m] = (int32_t)(v > hi ? hi : v < -hi - 1 ? -hi - 1 : (int64_t)v);
    }
}

/* Stage N: the normal dP/dz0 x dP/dx0 from the terms (exact in Q8.28, then s20 Q9.10) and the fold flag Ny <= 0. */
static inline void jac_normal(np_wave_jac *j)
{
    const int64_t a = (INT64_C(1) << NP_WAVE_JAC_FRAC) + j->j[NP_WAVE_JXX];
    const int64_t d = (INT64_C(1) << NP_WAVE_JAC_FRAC) + j->j[NP_WAVE_JZZ];
    const int64_t xz = j->j[NP_WAVE_JXZ], zx = j->j[NP_WAVE_JZX], yx = j->j[NP_WAVE_YX], yz = j->j[NP_WAVE_YZ];
    const unsigned sh = 2u * NP_WAVE_JAC_FRAC - NP_WAVE_N_FRAC;
    j->ny28 = a * d - xz * zx;
    j->nx = (int32_t)np_sat_s(np_shr_round_half_up(yz * zx - d * yx, sh), NP_WAVE_N_BITS);
    j->ny = (int32_t)np_sat_s(np_shr_round_half_up(j->ny28, sh), NP_WAVE_N_BITS);
    j->nz = (int32_t)np_sat_s(np_shr_round_half_up(xz * yx - yz * a, sh), NP_WAVE_N_BITS);
    j->fold = j->ny28 <= 0;
}

/* --- stages --- */

static const np_wave_unit *U(const void *cfg) { return cfg; }

static void stage_p(const void *cfg, void *sv)
{
    const np_wave_unit *u = U(cfg);
    np_wave_sig *s = sv;
    const np_wave_in *in = &s->in;
    for (unsigned k = 0; k < u->c.trains; k++)
        s->th[k] = k < u->r.n ? lane_phase(&u->r.tr[k], in) : 0u;
    s->p1 = u->r.pu * in->u + u->r.pt * in->t;
    s->p2 = u->r.pv * in->v;
    s->pc = (uint32_t)in->r * u->r.omc * in->t;
    s->sm = smoothing(&u->r, in->v);
}

static void stage_s(const void *cfg, void *sv)
{
    const np_wave_unit *u = U(cfg);
    np_wave_sig *s = sv;
    unsigned L = u->c.rom_log2;
    for (unsigned k = 0; k < u->c.trains; k++)
        lane_cs(u, k, &s->in, s->th[k], &s->c[k], &s->s[k]);
    s->s1 = u->c.irr ? np_wave_sin(s->p1, L) : 0;
    s->s2 = u->c.irr ? np_wave_sin(s->p2, L) : 0;
    s->sc = u->c.cap ? np_wave_sin(s->pc, L) : 0;
}

static void stage_a(const void *cfg, void *sv)
{
    const np_wave_unit *u = U(cfg);
    np_wave_sig *s = sv;
    s->w = (int32_t)np_shr_round_half_up((int64_t)s->s1 * s->s2, NP_WAVE_SIN_FRAC);
    for (unsigned k = 0; k < u->c.trains; k++)
        s->ap[k] = k < u->r.n ? lane_amp(&u->r.tr[k], u->c.irr, s->w) : 0;
    s->gm = gain_of(&u->r, s->sm, s->in.g);
}

static void stage_m(const void *cfg, void *sv)
{
    const np_wave_unit *u = U(cfg);
    np_wave_sig *s = sv;
    for (unsigned k = 0; k < u->c.trains; k++) {
        s->yc[k] = np_shr_round_half_up((int64_t)s->ap[k] * s->c[k], 7);
        s->sa[k] = np_shr_round_half_up((int64_t)s->ap[k] * s->s[k], NP_WAVE_SIN_FRAC);
        s->xp[k] = s->sa[k] * u->r.tr[k].cx;
        s->zp[k] = s->sa[k] * u->r.tr[k].cz;
        if (np_wave_has_jac(&u->c))
            lane_jac(&u->r.tr[k], s->ap[k], s->c[k], s->sa[k], s->lj[k], &s->yq[k]);
    }
    s->bc = u->c.cap ? (int64_t)u->r.b * s->sc : 0;
}

static void stage_t(const void *cfg, void *sv)
{
    const np_wave_unit *u = U(cfg);
    np_wave_sig *s = sv;
    int64_t y = 0, x = 0, z = 0;
    for (unsigned k = 0; k < u->c.trains; k++) {
        y += s->yc[k];
        x -= s->xp[k];
        z -= s->zp[k];
    }
    s->ys = y;
    s->xs = x;
    s->zs = z;
    if (np_wave_has_jac(&u->c))
        for (unsigned m = 0; m < NP_WAVE_NJ; m++) {
            int64_t v = 0;
            for (unsigned k = 0; k < u->c.trains; k++)
                v -= s->lj[k][m];
            s->js[m] = v;
        }
}

static void stage_g(const void *cfg, void *sv)
{
    const np_wave_unit *u = U(cfg);
    np_wave_sig *s = sv;
    s->out = out_of(&u->r, s->ys, s->xs, s->zs, s->bc, s->gm);
    if (np_wave_has_jac(&u->c))
        jac_terms(&u->r, s->js, s->gm, &s->jac);
}

static void stage_n(const void *cfg, void *sv)
{
    (void)cfg;
    jac_normal(&((np_wave_sig *)sv)->jac);
}

static const np_stage_desc stages[] = {
    { "P", stage_p }, { "S", stage_s }, { "A", stage_a }, { "M", stage_m },
    { "T", stage_t }, { "G", stage_g }, { "N", stage_n },
};
enum { N_STAGES = 6, N_STAGES_JAC = sizeof stages / sizeof stages[0] };

const np_stage_desc *np_wave_stage_table(void) { return stages; }
unsigned np_wave_stage_count(void) { return N_STAGES; }
unsigned np_wave_stage_count_of(const np_wave_cfg *c) { return np_wave_has_jac(c) ? N_STAGES_JAC : N_STAGES; }

int np_wave_pipe_init(np_pipe *p, const np_wave_unit *u)
{
    return np_pipe_init(p, stages, np_wave_stage_count_of(&u->c), sizeof(np_wave_sig), u);
}

/* Eq. (8)'s w = round(sin(p1) sin(p2) / 2^17), s19 Q1.17. */
static inline int32_t irr_w(const np_wave_regs *r, const np_wave_in *in, unsigned L)
{
    return (int32_t)np_shr_round_half_up((int64_t)wave_sin(r->pu * in->u + r->pt * in->t, L) *
                                             wave_sin(r->pv * in->v, L),
                                         NP_WAVE_SIN_FRAC);
}

/*
 * The stages' arithmetic in a row on locals (the pieces above, so it cannot
 * differ from the pipe: conformance.wave.cycle_vs_bitexact checks it too);
 * lanes beyond the register set's n contribute 0, as in the pipe.
 */
static inline void eval_gen(const np_wave_unit *u, const np_wave_in *in, np_wave_out *out, unsigned irr, unsigned cap,
                            unsigned n, unsigned rec)
{
    const np_wave_regs *r = &u->r;
    const unsigned L = u->c.rom_log2;
    const int32_t w = irr ? irr_w(r, in, L) : 0;
    int64_t ys = 0, xs = 0, zs = 0;
    for (unsigned k = 0; k < n; k++) {
        const np_wave_train *t = &r->tr[k];
        uint32_t th = lane_phase(t, in);
        int64_t ap = lane_amp(t, irr, w);
        int32_t cv, sv;
        if (rec) {
            lane_rec(u, k, in, th, &cv, &sv);
        } else {
            sv = wave_sin(th, L);
            cv = wave_sin(th + (UINT32_C(1) << 30), L);
        }
        int64_t sa = np_shr_round_half_up(ap * sv, NP_WAVE_SIN_FRAC);
        ys += np_shr_round_half_up(ap * cv, 7);
        xs -= sa * t->cx;
        zs -= sa * t->cz;
    }
    int64_t bc = cap ? (int64_t)r->b * wave_sin((uint32_t)in->r * r->omc * in->t, L) : 0;
    *out = out_of(r, ys, xs, zs, bc, gain_of(r, smoothing(r, in->v), in->g));
}

static inline unsigned lanes_of(const np_wave_unit *u) { return u->r.n < u->c.trains ? u->r.n : u->c.trains; }

static inline void eval_one(const np_wave_unit *u, const np_wave_in *in, np_wave_out *out)
{
    eval_gen(u, in, out, u->c.irr, u->c.cap, lanes_of(u), u->c.sincos == NP_WAVE_SINCOS_RECURRENCE);
}

void np_wave_eval(const np_wave_unit *u, const np_wave_in *in, np_wave_out *out) { eval_one(u, in, out); }

void np_wave_eval_jac(const np_wave_unit *u, const np_wave_in *in, np_wave_out *out, np_wave_jac *jac)
{
    eval_one(u, in, out);
    memset(jac, 0, sizeof *jac);
    if (!np_wave_has_jac(&u->c))
        return;
    /* The lanes again, through the same pieces as the stages (so eval_jac and the pipe cannot differ). */
    const np_wave_regs *r = &u->r;
    const unsigned L = u->c.rom_log2, n = lanes_of(u);
    const int32_t w = u->c.irr ? irr_w(r, in, L) : 0;
    int64_t js[NP_WAVE_NJ] = { 0 };
    for (unsigned k = 0; k < n; k++) {
        const np_wave_train *t = &r->tr[k];
        uint32_t th = lane_phase(t, in);
        int64_t ap = lane_amp(t, u->c.irr, w), lj[NP_WAVE_NJ], yq;
        int32_t cv, sv;
        lane_cs(u, k, in, th, &cv, &sv);
        int64_t sa = np_shr_round_half_up(ap * sv, NP_WAVE_SIN_FRAC);
        lane_jac(t, ap, cv, sa, lj, &yq);
        for (unsigned m = 0; m < NP_WAVE_NJ; m++)
            js[m] -= lj[m];
    }
    jac_terms(r, js, gain_of(r, smoothing(r, in->v), in->g), jac);
    jac_normal(jac);
}

np_wave_jac_bound np_wave_jac_error_bound(const np_wave_unit *u)
{
    /*
     * docs/wave.md, "Normals and the fold flag". Term m's error: its final
     * rounding 2^-15 plus G times, per lane, the lane's factor f (|e_m| for
     * jxx .. jzz, |kmx| or |kmz| for yx, yz) times ap c's (or ap s's) error
     * ((A + a) e_s + ap's error + yq's or sa's rounding 2^-18), plus the
     * lane rounding 2^-30 for jxx .. jzz. Its magnitude: G sum (A + a) f.
     */
    const np_wave_regs *r = &u->r;
    const double es = np_wave_sin_bound(u->c.rom_log2), gm = (double)r->gcap * np_pow2i(-NP_WAVE_GAIN_FRAC);
    const double el = np_wave_lane_bound(&u->c); /* the lanes' cos and sin: the ROM's, or the recurrence's */
    const double q = np_pow2i(-18);
    np_wave_jac_bound b;
    memset(&b, 0, sizeof b);
    for (unsigned m = 0; m < NP_WAVE_NJ; m++)
        b.e[m] = np_pow2i(-NP_WAVE_JAC_FRAC - 1);
    for (unsigned k = 0; k < r->n; k++) {
        const np_wave_train *t = &r->tr[k];
        int64_t e[4];
        lane_e(t, e);
        const double f[NP_WAVE_NJ] = { fabs((double)e[0]) * np_pow2i(-26), fabs((double)e[1]) * np_pow2i(-26),
                                       fabs((double)e[2]) * np_pow2i(-26), fabs((double)e[3]) * np_pow2i(-26),
                                       fabs((double)t->kmx) * np_pow2i(-NP_WAVE_KM_FRAC),
                                       fabs((double)t->kmz) * np_pow2i(-NP_WAVE_KM_FRAC) };
        double a = (double)(t->amp + t->airr) * np_pow2i(-NP_WAVE_AMP_FRAC);
        double dap = u->c.irr ? (double)t->airr * np_pow2i(-NP_WAVE_AMP_FRAC) * (2.0 * es + q) + q : 0.0;
        for (unsigned m = 0; m < NP_WAVE_NJ; m++) {
            b.e[m] += gm * (f[m] * (a * el + dap + q) + (m < 4 ? np_pow2i(-30) : 0.0));
            b.m[m] += gm * a * f[m];
        }
    }
    /* |xy - x'y'| <= |x| dy + |y| dx + dx dy over each product of the normal, |x| <= m + 1 for 1 + jxx, 1 + jzz. */
    const double *E = b.e, *M = b.m;
#define PB(x, y) (M[x] * E[y] + M[y] * E[x] + E[x] * E[y])
#define PB1(x, y) ((1.0 + M[x]) * E[y] + M[y] * E[x] + E[x] * E[y])
    b.nb[0] = PB(NP_WAVE_YZ, NP_WAVE_JZX) + PB1(NP_WAVE_JZZ, NP_WAVE_YX);
    b.nb[1] = PB1(NP_WAVE_JXX, NP_WAVE_JZZ) + E[NP_WAVE_JXX] + PB(NP_WAVE_JXZ, NP_WAVE_JZX); /* (1 + M) both */
    b.nb[2] = PB(NP_WAVE_JXZ, NP_WAVE_YX) + PB1(NP_WAVE_JXX, NP_WAVE_YZ);
#undef PB
#undef PB1
    for (unsigned m = 0; m < 3; m++)
        b.nb[m] += np_pow2i(-NP_WAVE_N_FRAC - 1); /* the normal's one rounding */
    return b;
}

/* Runs of the commonest shapes with the lanes and effects as constants (the compiler specialises eval_gen). */
#define RUN_OF(IRR, CAP, N)                                                                                        \
    do {                                                                                                           \
        for (size_t k = 0; k < n; k++)                                                                             \
            eval_gen(u, &in[k], &out[k], IRR, CAP, N, 0);                                                             \
        return;                                                                                                    \
    } while (0)

void np_wave_eval_n(const np_wave_unit *u, const np_wave_in *in, np_wave_out *out, size_t n)
{
    const unsigned m = lanes_of(u);
    if (!u->c.irr && !u->c.cap && u->c.sincos == NP_WAVE_SINCOS_ROM) {
        if (m == 1)
            RUN_OF(0, 0, 1);
        if (m == 2)
            RUN_OF(0, 0, 2);
    }
    for (size_t k = 0; k < n; k++)
        eval_one(u, &in[k], &out[k]);
}
#undef RUN_OF

double np_wave_error_bound_lsb(const np_wave_unit *u)
{
    const np_wave_regs *r = &u->r;
    double es = np_wave_sin_bound(u->c.rom_log2), gm = (double)r->gcap * np_pow2i(-NP_WAVE_GAIN_FRAC);
    double el = np_wave_lane_bound(&u->c); /* the lanes' cos and sin: e_s from the ROM, or the recurrence's bound */
    double sa = 0.0, si = 0.0, q = np_pow2i(-18);
    for (unsigned k = 0; k < r->n; k++) {
        sa += (double)(r->tr[k].amp + r->tr[k].airr) * np_pow2i(-NP_WAVE_AMP_FRAC);
        if (u->c.irr)
            si += (double)r->tr[k].airr * np_pow2i(-NP_WAVE_AMP_FRAC);
    }
    double n = (double)r->n;
    double ey = gm * (sa * el + si * (2.0 * es + q) + n * (q + np_pow2i(-28))) +
                (u->c.cap ? (double)r->b * np_pow2i(-NP_WAVE_AMP_FRAC) * es : 0.0);
    double ed = gm * (sa * el + si * (2.0 * es + q) + n * 2.0 * q);
    double e = ey > ed ? ey : ed;
    return 0.5 + e * np_pow2i(NP_WAVE_AMP_FRAC);
}

/* --- datapath declaration --- */

/* Largest magnitudes of the register-dependent signals (the declared widths follow them). */
typedef struct wave_bounds {
    int64_t ap, yc, sa, xp, ys, xs, bc, gm;
} wave_bounds;

static int64_t iabs64(int64_t v) { return v < 0 ? -v : v; }

static wave_bounds bounds_of(const np_wave_unit *u)
{
    wave_bounds b;
    memset(&b, 0, sizeof b);
    const int64_t one = INT64_C(1) << NP_WAVE_SIN_FRAC;
    for (unsigned k = 0; k < u->r.n; k++) {
        const np_wave_train *t = &u->r.tr[k];
        int64_t ap = ((int64_t)t->amp + (u->c.irr ? t->airr : 0)) << (NP_WAVE_SIN_FRAC - NP_WAVE_AMP_FRAC);
        int64_t cm = iabs64(t->cx) > iabs64(t->cz) ? iabs64(t->cx) : iabs64(t->cz);
        int64_t yc = (ap * one) >> 7, xp = ap * cm;
        b.ap = ap > b.ap ? ap : b.ap;
        b.yc = yc > b.yc ? yc : b.yc;
        b.sa = ap > b.sa ? ap : b.sa;
        b.xp = xp > b.xp ? xp : b.xp;
        b.ys += yc;
        b.xs += xp;
    }
    b.bc = u->c.cap ? (int64_t)u->r.b * one : 0;
    b.gm = ((int64_t)1 << u->r.mlog2) * u->r.gcap;
    return b;
}

static unsigned sbits(int64_t m) { return np_bits_for_range(-m, m, 1); }
static unsigned ubits(int64_t m) { return np_bits_for_range(0, m, 0); }

#define OP(st, sig, kind, cnt, a, b, out, sg, lv) np_dp_op(&d, st, sig, kind, cnt, a, b, out, sg, lv)

/*
 * Normals or fold: per lane the four register products e (a set-up could
 * share them; priced per lane), yq (the second rounding of ap c), the four
 * products yq e and, with normals, sa kmx and sa kmz; in T the terms' adder
 * trees; in G their gain products and roundings; stage N: 1 + jxx, 1 + jzz,
 * the normal's six products (ny's two with fold only) and the fold compare.
 * The widths follow the register set's bounds (as the trains' do).
 */
void np_wave_datapath_widths(const np_wave_unit *u, np_wave_dp_widths *w)
{
    const wave_bounds b = bounds_of(u);
    const unsigned nt = u->c.normals ? 6u : 4u;
    int64_t mlj = 0, mly = 0, sum[NP_WAVE_NJ] = { 0 }, jb[NP_WAVE_NJ];
    memset(w, 0, sizeof *w);
    w->ap = ubits(b.ap);
    w->yc = sbits(b.yc);
    w->sa = sbits(b.sa);
    w->xp = sbits(b.xp);
    w->ys = sbits(b.ys);
    w->xs = sbits(b.xs);
    w->gm = ubits(b.gm);
    w->bc = u->c.cap ? sbits(b.bc) : 0u;
    if (!np_wave_has_jac(&u->c))
        return;
    for (unsigned k = 0; k < u->r.n; k++) {
        const np_wave_train *t = &u->r.tr[k];
        int64_t e[4], ap = ((int64_t)t->amp + (u->c.irr ? t->airr : 0)) << (NP_WAVE_SIN_FRAC - NP_WAVE_AMP_FRAC);
        lane_e(t, e);
        for (unsigned m = 0; m < 4; m++) {
            int64_t v = ((ap + 1) * iabs64(e[m])) >> 14;
            mlj = v > mlj ? v : mlj;
            sum[m] += v;
        }
        int64_t vx = ap * iabs64(t->kmx), vz = ap * iabs64(t->kmz);
        mly = vx > mly ? vx : mly;
        mly = vz > mly ? vz : mly;
        sum[4] += vx;
        sum[5] += vz;
    }
    np_wave_jac_range_lsb(&u->r, jb);
    w->lj = sbits(mlj);
    w->ly = sbits(mly);
    for (unsigned m = 0; m < nt; m++) {
        w->js = sbits(sum[m]) > w->js ? sbits(sum[m]) : w->js;
        w->j = sbits(jb[m]) > w->j ? sbits(jb[m]) : w->j;
    }
}

static void jac_datapath(np_dp *dp, const np_wave_unit *u, unsigned n, const np_wave_dp_widths *w)
{
    np_dp d = *dp;
    const unsigned nrm = u->c.normals, nt = nrm ? 6u : 4u;
    const unsigned wsa = w->sa, wgm = w->gm, wlj = w->lj, wly = w->ly, wjs = w->js, wj = w->j;
    OP("M", NULL, NP_OP_SMUL, 4u * n, 16, 16, 0, 0, 0); /* e: cx kmx, cx kmz, cz kmx, cz kmz (s16 x s16) */
    OP("M", "yq", NP_OP_ADD, n, wsa, 0, wsa, 1, 1);    /* round(ap c / 2^17) from the product yc rounds */
    OP("M", "lj", NP_OP_SMUL, 4u * n, wsa, 31, wlj, 1, 2); /* yq e */
    if (nrm)
        OP("M", "ly", NP_OP_SMUL, 2u * n, wsa, 16, wly, 1, 1); /* sa kmx, sa kmz */
    OP("M", NULL, NP_OP_REG, 1, n * (4u * wlj + (nrm ? 2u * wly : 0u)), 0, 0, 0, 0);
    /* js[m] = -sum lj[m]: as X and Z, 0 - lj[m] of lane 0 (an incrementer), then n - 1 subtractors */
    OP("T", NULL, NP_OP_INC, nt, wjs, 0, 0, 0, 0);
    OP("T", n > 1u ? "js" : NULL, NP_OP_ADD, nt * (n - 1u), wjs, 0, n > 1u ? wjs : 0u, 1, 1);
    if (n == 1u)
        OP("T", "js", NP_OP_REG, 0, 0, 0, wjs, 1, 1);
    OP("T", NULL, NP_OP_REG, 1, nt * wjs, 0, 0, 0, 0);
    OP("G", NULL, NP_OP_MUL, nt, wjs, wgm, 0, 0, 0);
    OP("G", "jac", NP_OP_ADD, nt, wj, 0, wj, 1, 2);
    OP("G", NULL, NP_OP_REG, 1, 3u * 16u + nt * wj + 1u, 0, 0, 0, 0);
    /*
     * N: a = 2^14 + jxx, d = 2^14 + jzz (s(wj + 1)); ny = a d - jxz jzx (fold); with normals
     * nx = jzx yz - d yx and nz = jxz yx - a yz too. Every product is signed x signed: a d is
     * s(wj + 1) x s(wj + 1); nx's and nz's products by d or a are s(wj + 1) x s(wj); the others
     * (jxz jzx, jzx yz, jxz yx) s(wj) x s(wj).
     */
    OP("N", NULL, NP_OP_ADD, 2, wj + 1u, 0, 0, 0, 0);
    OP("N", NULL, NP_OP_SMUL, 1, wj + 1u, wj + 1u, 0, 0, 1);
    if (nrm)
        OP("N", NULL, NP_OP_SMUL, 2, wj + 1u, wj, 0, 0, 1);
    OP("N", NULL, NP_OP_SMUL, nrm ? 3u : 1u, wj, wj, 0, 0, 1);
    OP("N", NULL, NP_OP_ADD, nrm ? 3u : 1u, 2u * (wj + 1u), 0, 0, 0, 2); /* exact differences, Q8.28 */
    if (nrm)
        OP("N", NULL, NP_OP_ADD, 3, NP_WAVE_N_BITS, 0, 0, 0, 3); /* the roundings to s20 Q9.10 */
    if (u->c.fold)
        OP("N", NULL, NP_OP_CMP, 1, 2u * (wj + 1u), 0, 0, 0, 3); /* Ny <= 0 */
    OP("N", NULL, NP_OP_REG, 1, 3u * 16u + (nrm ? 3u * NP_WAVE_N_BITS : 0u) + u->c.fold + 1u, 0, 0, 0, 0);
    *dp = d;
}

size_t np_wave_datapath(const np_wave_unit *u, np_op *ops, size_t max)
{
    np_dp d = { ops, max, 0 };
    const unsigned n = u->c.trains, L = u->c.rom_log2, ml = u->r.mlog2;
    /*
     * sincos=recurrence: one phase datapath and one ROM cos/sin pair serve the
     * lane that re-sets up this transaction (the lanes in turn), instead of a
     * phase and two interpolated sines a lane; each lane rotates its state.
     */
    const unsigned rec = u->c.sincos == NP_WAVE_SINCOS_RECURRENCE, nl = rec ? 1u : n;
    const unsigned nfx = (u->c.irr ? 2u : 0u) + (u->c.cap ? 1u : 0u), nsin = 2u * nl + nfx;
    np_wave_dp_widths w;
    np_wave_datapath_widths(u, &w);
    const unsigned wap = w.ap, wyc = w.yc, wsa = w.sa, wxp = w.xp, wys = w.ys, wxs = w.xs, wgm = w.gm, wbc = w.bc;
    /*
     * The widths are those np_wave.v is built at (`report gates --synth`
     * passes them); each operator is the RTL's, stage by stage (docs/wave.md,
     * "Gates against synthesis"). P: per train lane th = kx i + kz j + phi +
     * ph - om t, every product modulo 2^32 (the partial products under bit
     * 32 only: mullo), four adders.
     */
    OP("P", NULL, NP_OP_MULLO, 2u * nl, 32, 16, 0, 0, 0);
    OP("P", NULL, NP_OP_MULLO, nl, 32, 32, 0, 0, 0);
    OP("P", NULL, NP_OP_ADD, 3u * nl, 32, 0, 0, 0, 1);
    OP("P", "th", NP_OP_ADD, nl, 32, 0, 32, 0, 2);
    if (rec) {
        OP("P", NULL, NP_OP_MUX, 4, 32, n, 0, 0, 0); /* kx, kz, phi, om of the lane setting up */
        OP("P", NULL, NP_OP_ADD, 1, 17, 0, 0, 0, 0); /* the set-up counter, i mod N */
        OP("P", NULL, NP_OP_CMP, n, 17, 0, 0, 0, 1); /* which lane sets up: (i + k) mod N = 0 */
    }
    if (u->c.irr) {
        OP("P", NULL, NP_OP_MULLO, 2, 32, 16, 0, 0, 0); /* pu u, pv v */
        OP("P", NULL, NP_OP_MULLO, 1, 32, 32, 0, 0, 0); /* pt t */
        OP("P", "p1", NP_OP_ADD, 1, 32, 0, 32, 0, 1);
    }
    if (u->c.cap) {
        OP("P", NULL, NP_OP_MULLO, 1, 32, 32, 0, 0, 0); /* omc t */
        OP("P", "pc", NP_OP_MULLO, 1, 32, 8, 32, 0, 1); /* r (omc t) */
    }
    /* Smoothing: V - 1 - v, v < V, v < V - 1 - v, the smaller, min with M (a constant compare). */
    OP("P", NULL, NP_OP_ADD, 1, 16, 0, 0, 0, 0);
    OP("P", NULL, NP_OP_CMP, 2, 16, 0, 0, 0, 1);
    OP("P", NULL, NP_OP_MUX, 1, 16, 2, 0, 0, 2);
    OP("P", NULL, NP_OP_CMPK, 1, 17, 0, 0, 0, 3);
    OP("P", "sm", NP_OP_MUX, 1, ml + 1u, 2, ml + 1u, 0, 4);
    OP("P", NULL, NP_OP_REG, 1, 32u * (nl + nfx) + (rec ? n : 0u) + (ml + 1u) + 15u + 1u, 0, 0, 0, 0); /* phases, sm, g, valid */
    /*
     * S: per sine the mirror 2^30 - x, the successor's address a + 1, the
     * two ROM reads, the chord D = R[a+1] - R[a] (dbits: the ROM's first
     * step, its largest), D f, its rounding, the sum and the sign. The
     * quarter sine is smooth, and its two ROMs with D synthesise to far less
     * than an arbitrary table: they are priced at rom_eff[L] bits a word, the
     * width that puts np_wave_sin.v alone (Yosys + ABC, the --synth flow) at
     * its measured size: 2,932.5 / 3,284 / 3,896.5 / 5,063.5 / 6,790 NAND2
     * at L = 6 .. 10 (the model: 2,921 / 3,309 / 3,909 / 5,099 / 7,135).
     */
    static const unsigned rom_eff[NP_WAVE_ROM_MAX + 1u] = { [6] = 13, [7] = 13, [8] = 11, [9] = 10, [10] = 8 };
    const unsigned dbits = np_bits_for_range(0, (int64_t)np_wave_rom(1u << (10u - L)) - (int64_t)np_wave_rom(0), 0);
    OP("S", NULL, NP_OP_NEG, nsin, 30, 0, 0, 0, 0);
    OP("S", NULL, NP_OP_INC, nsin, L + 1u, 0, 0, 0, 0);
    OP("S", NULL, NP_OP_ROM, 2u * nsin, L, rom_eff[L], 0, 0, 1);
    OP("S", NULL, NP_OP_ADD, nsin, dbits, 0, 0, 0, 2);
    OP("S", NULL, NP_OP_MUL, nsin, dbits, NP_WAVE_IFRAC, 0, 0, 3);
    OP("S", NULL, NP_OP_INC, nsin, 13, 0, 0, 0, 4);
    OP("S", NULL, NP_OP_ADD, nsin, 18, 0, 0, 0, 4);
    OP("S", "cs", NP_OP_NEG, nsin, 19, 0, 19, 1, 5);
    if (rec) {
        /* Per lane: (c dc - s ds, s dc + c ds) in one clock (the state's loop), rounded, the set-up mux, the state. */
        OP("S", NULL, NP_OP_SMUL, 4u * n, 31, 31, 0, 0, 0); /* signed x signed */
        OP("S", NULL, NP_OP_ADD, 2u * n, 62, 0, 0, 0, 1);
        OP("S", NULL, NP_OP_ADD, 2u * n, 31, 0, 0, 0, 2);
        OP("S", NULL, NP_OP_MUX, 2u * n, 31, 2, 0, 0, 3);
        OP("S", NULL, NP_OP_REG, 1, 2u * 31u * n, 0, 0, 0, 0);
        OP("S", NULL, NP_OP_ADD, 2u * n, 19, 0, 0, 0, 4); /* round to Q1.17 and clamp */
    }
    OP("S", NULL, NP_OP_REG, 1, 19u * (2u * n + nfx) + (ml + 1u) + 15u + 1u, 0, 0, 0, 0);
    /*
     * A: w = round(s1 s2 / 2^17), ap = amp 2^7 - round(airr w / 2^10) per
     * train (airr with its sign bit: 16 x 19), 0 for lanes k >= n (an AND a
     * bit); G = sm min(g, gcap).
     */
    if (u->c.irr) {
        OP("A", NULL, NP_OP_SMUL, 1, 19, 19, 0, 0, 0); /* s1 s2: s19 x s19 */
        OP("A", "w", NP_OP_INC, 1, 21, 0, 19, 1, 1);
        OP("A", NULL, NP_OP_MUL, n, 16, 19, 0, 0, 2);
        OP("A", NULL, NP_OP_INC, n, wap + 1u, 0, 0, 0, 3);
        OP("A", "ap", NP_OP_ADD, n, wap, 0, wap, 0, 4);
    }
    OP("A", NULL, NP_OP_MUX, n, wap, 2, 0, 0, 5);
    OP("A", NULL, NP_OP_CMP, 1, 15, 0, 0, 0, 0);
    OP("A", NULL, NP_OP_MUX, 1, 15, 2, 0, 0, 1);
    OP("A", "gm", NP_OP_MUL, 1, ml + 1u, 15, wgm, 0, 2);
    OP("A", NULL, NP_OP_REG, 1, n * (wap + 38u) + (u->c.cap ? 19u : 0u) + wgm + 1u, 0, 0, 0, 0);
    /*
     * M: a train lane's four products ap c, ap s ((ap with its sign bit) x
     * 19), sa cx, sa cz, the roundings of yc and sa; the capillary b sc (16 x 19).
     */
    OP("M", NULL, NP_OP_MUL, 2u * n, wap + 1u, 19, 0, 0, 0);
    OP("M", "yc", NP_OP_INC, n, wyc, 0, wyc, 1, 1);
    OP("M", "sa", NP_OP_INC, n, wsa, 0, wsa, 1, 1);
    OP("M", "xp", NP_OP_SMUL, 2u * n, wsa, 16, wxp, 1, 2); /* sa cx, sa cz: signed x s16 */
    if (u->c.cap)
        OP("M", "bc", NP_OP_MUL, 1, 16, 19, wbc, 1, 0);
    OP("M", NULL, NP_OP_REG, 1, n * (wyc + 2u * wxp) + wbc + wgm + 1u, 0, 0, 0, 0);
    /* T: Y = sum yc (n - 1 adders); X = -sum xp, Z likewise (0 - xp0: an incrementer, then n - 1 subtractors). */
    np_dp_add_tree(&d, "T", "ys", n, wys, 1, 0);
    if (n == 1u)
        OP("T", "ys", NP_OP_REG, 0, 0, 0, wys, 1, 0); /* wiring */
    OP("T", NULL, NP_OP_INC, 2, wxs, 0, 0, 0, 0);
    OP("T", n > 1u ? "xs" : NULL, NP_OP_ADD, 2u * (n - 1u), wxs, 0, n > 1u ? wxs : 0u, 1, 1);
    if (n == 1u)
        OP("T", "xs", NP_OP_REG, 0, 0, 0, wxs, 1, 1);
    OP("T", NULL, NP_OP_REG, 1, wys + 2u * wxs + wbc + wgm + 1u, 0, 0, 0, 0);
    /*
     * G: the gain products (G with its sign bit), the capillary term added
     * from bit 14 + mlog2 up to the last one read, the three roundings (an
     * incrementer of the 16 kept bits and the round bit each).
     */
    OP("G", NULL, NP_OP_MUL, 1, wys, wgm + 1u, 0, 0, 0);
    OP("G", NULL, NP_OP_MUL, 2, wxs, wgm + 1u, 0, 0, 0);
    if (u->c.cap)
        OP("G", NULL, NP_OP_ADD, 1, 33, 0, 0, 0, 1);
    OP("G", "out", NP_OP_INC, 3, 17, 0, 16, 1, 2);
    if (np_wave_has_jac(&u->c))
        jac_datapath(&d, u, n, &w);
    else
        OP("G", NULL, NP_OP_REG, 1, 3u * 16u + 1u, 0, 0, 0, 0);
    return d.n;
}

static void tr(np_trace *t, size_t n, const char *name, int64_t v)
{
    for (size_t i = 0; i < n; i++)
        if (t[i].signal && strcmp(t[i].signal, name) == 0)
            np_trace_add(&t[i], v);
}

void np_wave_trace(const np_wave_unit *u, unsigned k, const np_wave_sig *s, np_trace *t, size_t n)
{
    unsigned m = u->c.trains;
    switch (k) {
    case 0:
        for (unsigned q = 0; q < m; q++)
            tr(t, n, "th", s->th[q]);
        tr(t, n, "p1", s->p1);
        tr(t, n, "pc", s->pc);
        tr(t, n, "sm", s->sm);
        break;
    case 1:
        for (unsigned q = 0; q < m; q++) {
            tr(t, n, "cs", s->c[q]);
            tr(t, n, "cs", s->s[q]);
        }
        if (u->c.irr) {
            tr(t, n, "cs", s->s1);
            tr(t, n, "cs", s->s2);
        }
        if (u->c.cap)
            tr(t, n, "cs", s->sc);
        break;
    case 2:
        tr(t, n, "w", s->w);
        for (unsigned q = 0; q < m; q++)
            tr(t, n, "ap", s->ap[q]);
        tr(t, n, "gm", s->gm);
        break;
    case 3:
        for (unsigned q = 0; q < m; q++) {
            tr(t, n, "yc", s->yc[q]);
            tr(t, n, "sa", s->sa[q]);
            tr(t, n, "xp", s->xp[q]);
            tr(t, n, "xp", s->zp[q]);
        }
        tr(t, n, "bc", s->bc);
        if (np_wave_has_jac(&u->c))
            for (unsigned q = 0; q < m; q++) {
                tr(t, n, "yq", s->yq[q]);
                for (unsigned e = 0; e < 4; e++)
                    tr(t, n, "lj", s->lj[q][e]);
                tr(t, n, "ly", s->lj[q][4]);
                tr(t, n, "ly", s->lj[q][5]);
            }
        break;
    case 4:
        tr(t, n, "ys", s->ys);
        tr(t, n, "xs", s->xs);
        tr(t, n, "xs", s->zs);
        if (np_wave_has_jac(&u->c))
            for (unsigned q = 0; q < (u->c.normals ? 6u : 4u); q++)
                tr(t, n, "js", s->js[q]);
        break;
    case 5:
        tr(t, n, "out", s->out.y);
        tr(t, n, "out", s->out.dx);
        tr(t, n, "out", s->out.dz);
        if (np_wave_has_jac(&u->c))
            for (unsigned q = 0; q < (u->c.normals ? 6u : 4u); q++)
                tr(t, n, "jac", s->jac.j[q]);
        break;
    default:
        break;
    }
}

/* --- the test register set --- */

static uint64_t splitmix(uint64_t *x)
{
    uint64_t z = (*x += UINT64_C(0x9e3779b97f4a7c15));
    z = (z ^ (z >> 30)) * UINT64_C(0xbf58476d1ce4e5b9);
    z = (z ^ (z >> 27)) * UINT64_C(0x94d049bb133111eb);
    return z ^ (z >> 31);
}

/* A direction of length <= 1 in Q1.14 from an angle drawn as a point on the square's border, normalised by a table-free step. */
static void direction(uint64_t *x, int16_t *cx, int16_t *cz)
{
    /* Rejection: a random point in the unit disc's inscribed annulus [0.75, 1], kept as drawn. */
    for (;;) {
        int64_t a = (int64_t)(splitmix(x) >> 49) - 16384, b = (int64_t)(splitmix(x) >> 49) - 16384;
        int64_t r2 = a * a + b * b;
        if (r2 <= (INT64_C(1) << 28) && r2 >= (INT64_C(9) << 24)) {
            *cx = (int16_t)a;
            *cz = (int16_t)b;
            return;
        }
    }
}

static void regs_test(uint64_t seed, unsigned n, np_wave_regs *r, int jac)
{
    uint64_t x = seed * UINT64_C(0x2545f4914f6cdd1d) + 17u;
    memset(r, 0, sizeof *r);
    if (n < 1)
        n = 1;
    if (n > NP_WAVE_MAX_TRAINS)
        n = NP_WAVE_MAX_TRAINS;
    r->n = n;
    r->gcap = NP_WAVE_GCAP_DEF;
    r->mlog2 = NP_WAVE_MLOG2_DEF;
    r->width = (uint16_t)(0x8000u + (splitmix(&x) >> 49));
    r->pu = (uint32_t)splitmix(&x);
    r->pv = (uint32_t)splitmix(&x);
    r->pt = (uint32_t)splitmix(&x);
    r->omc = (uint32_t)splitmix(&x);
    r->b = (uint16_t)(256u + (splitmix(&x) >> 55)); /* 0.25 .. 0.75 m */
    /* Weights, then amplitudes scaled so that (gcap/2^14) sum (amp + airr) + b lies in [1/2, 1] of 2^15 - 1. */
    uint64_t wsum = 0, wt[NP_WAVE_MAX_TRAINS], fill = 16384u + (splitmix(&x) >> 50); /* /32768 of the range */
    for (unsigned k = 0; k < n; k++) {
        wt[k] = 1024u + (splitmix(&x) >> 54);
        wsum += wt[k];
    }
    int64_t room = (((int64_t)0x7fff - r->b) * (int64_t)fill) >> 15; /* output LSB for the trains */
    int64_t sum_lsb = (room << NP_WAVE_GAIN_FRAC) / r->gcap;        /* sum (amp + airr) */
    for (unsigned k = 0; k < n; k++) {
        np_wave_train *t = &r->tr[k];
        int64_t share = sum_lsb * (int64_t)wt[k] / (int64_t)wsum; /* amp + airr; airr <= 3/16 of it (3 amp / 13) */
        int64_t airr = (int64_t)(splitmix(&x) >> 62) * share / 16;  /* 0 .. 3/16 of the share */
        t->amp = (uint16_t)(share - airr);
        t->airr = (uint16_t)airr;
        t->kx = (int32_t)(uint32_t)splitmix(&x);
        t->kz = (int32_t)(uint32_t)splitmix(&x);
        t->phi = (uint32_t)splitmix(&x);
        t->om = (uint32_t)splitmix(&x);
        direction(&x, &t->cx, &t->cz);
    }
    /* Train 0 points along x, c = (1, 0), so that sa cx reaches its bound. */
    r->tr[0].cx = (int16_t)(1 << NP_WAVE_DIR_FRAC);
    r->tr[0].cz = 0;
    if (!jac)
        return;
    /*
     * normals or fold: kmx, kmz drawn after everything above (so the other
     * registers are the same set's). Train 0 (c = (1, 0)) is steep along x:
     * kmx = st 2^24 / (gcap (amp + airr)), st = 5734 + (D() >> 53) in Q.12
     * (1.4 .. 1.9 at the gain cap, 1.08 .. 1.46 at gain 1), kmz = 0, so the
     * surface folds where its cos is near 1 and not elsewhere; the other
     * trains k >= 1 draw kmx, kmz uniform in [-K, K] (D() mod (2K + 1) - K each),
     * K = 2^10 2^24 / (gcap sum_{k>=1} (amp + airr)) (0.25 at the cap).
     */
    int64_t st = 5734 + (int64_t)(splitmix(&x) >> 53), so = 0;
    r->tr[0].kmx = (int16_t)((st << 24) / ((int64_t)r->gcap * ((int64_t)r->tr[0].amp + r->tr[0].airr)));
    r->tr[0].kmz = 0;
    for (unsigned k = 1; k < n; k++)
        so += (int64_t)r->tr[k].amp + r->tr[k].airr;
    int64_t K = so ? (INT64_C(1) << 34) / ((int64_t)r->gcap * so) : 0;
    for (unsigned k = 1; k < n; k++) {
        r->tr[k].kmx = (int16_t)((int64_t)(splitmix(&x) % (uint64_t)(2 * K + 1)) - K);
        r->tr[k].kmz = (int16_t)((int64_t)(splitmix(&x) % (uint64_t)(2 * K + 1)) - K);
    }
}

void np_wave_regs_test(uint64_t seed, unsigned n, np_wave_regs *r) { regs_test(seed, n, r, 0); }
void np_wave_regs_test_jac(uint64_t seed, unsigned n, np_wave_regs *r) { regs_test(seed, n, r, 1); }

/* --- sincos=recurrence --- */

void np_wave_recur_setup(np_wave_recur *q, int64_t c0, int64_t s0, int64_t dc, int64_t ds)
{
    q->c = c0;
    q->s = s0;
    q->dc = dc;
    q->ds = ds;
}

void np_wave_recur_step(np_wave_recur *q)
{
    int64_t c = np_shr_round_half_up(q->c * q->dc - q->s * q->ds, 30);
    int64_t s = np_shr_round_half_up(q->s * q->dc + q->c * q->ds, 30);
    q->c = c;
    q->s = s;
}
