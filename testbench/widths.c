/* SPDX-License-Identifier: MIT */
/* Declared datapath widths against traced ranges (np_widths.h). */
#include "np_widths.h"

#include <inttypes.h>
#include <string.h>

#include "np_test.h"

size_t np_widths_traces(const np_op *ops, size_t n_ops, np_trace *t)
{
    size_t n = 0;
    for (size_t i = 0; i < n_ops; i++)
        if (ops[i].signal && ops[i].out) {
            memset(&t[n], 0, sizeof t[n]);
            t[n++].signal = ops[i].signal;
        }
    return n;
}

unsigned np_widths_judge(const np_op *ops, size_t n_ops, const np_trace *t, unsigned margin, const char *what,
                         int print)
{
    unsigned bad = 0;
    if (print)
        printf("  %-8s %9s %-36s %5s\n", "signal", "declared", "traced range", "needs");
    for (size_t i = 0, ti = 0; i < n_ops; i++) {
        const np_op *op = &ops[i];
        if (!(op->signal && op->out))
            continue;
        const np_trace *tr = &t[ti++];
        unsigned need = np_trace_need(tr, op->out_signed);
        bad += !(tr->samples > 0 && need <= op->out && op->out <= need + margin);
        char range[64];
        if (tr->wide && tr->lo == 0 && tr->hi == 0) /* traced by width only (np_trace_add_wide) */
            snprintf(range, sizeof range, "%u bits (two's complement)%s", tr->wide, tr->wide_neg ? ", < 0 seen" : "");
        else
            snprintf(range, sizeof range, "[%" PRId64 ", %" PRId64 "]", tr->lo, tr->hi);
        NP_CHECK(tr->samples > 0, "%s: signal %s never traced", what, tr->signal);
        NP_CHECK(need <= op->out, "%s: %s declared %u bits, needs %u (%s)", what, tr->signal, op->out, need, range);
        NP_CHECK(op->out <= need + margin, "%s: %s declared %u bits, needs only %u", what, tr->signal, op->out, need);
        if (print)
            printf("  %-8s %8u%s %-36s %5u\n", tr->signal, op->out, op->out_signed ? "s" : "u", range, need);
    }
    return bad;
}
