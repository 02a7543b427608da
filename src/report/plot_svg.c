/* SPDX-License-Identifier: MIT */
#include <math.h>

#include "np_plot.h"

enum { W = 720, H = 480, ML = 80, MR = 24, MT = 40, MB = 64, NP_TICKS_MAX = 24 };

typedef struct frame {
    double x0, x1, y0, y1;
    int ylog;
} frame;

static double fy(const frame *fr, double y)
{
    double a = fr->ylog ? log10(y) : y, lo = fr->ylog ? log10(fr->y0) : fr->y0,
           hi = fr->ylog ? log10(fr->y1) : fr->y1;
    return MT + (H - MT - MB) * (1.0 - (a - lo) / (hi - lo));
}

static double fx(const frame *fr, double x) { return ML + (W - ML - MR) * (x - fr->x0) / (fr->x1 - fr->x0); }

/* Text content with XML's special characters escaped. */
static void put_text(FILE *f, const char *t)
{
    for (; t && *t; t++) {
        switch (*t) {
        case '<': fputs("&lt;", f); break;
        case '>': fputs("&gt;", f); break;
        case '&': fputs("&amp;", f); break;
        default: fputc(*t, f); break;
        }
    }
}

/* A "nice" tick step covering span in about n steps. */
static double nice_step(double span, int n)
{
    double raw = span / n, p = pow(10.0, floor(log10(raw))), m = raw / p;
    return (m < 1.5 ? 1.0 : m < 3.5 ? 2.0 : m < 7.5 ? 5.0 : 10.0) * p;
}

static void fit(const np_plot *p, const np_plot_series *s, size_t ns, frame *fr)
{
    fr->x0 = p->xmin;
    fr->x1 = p->xmax;
    fr->y0 = p->ymin;
    fr->y1 = p->ymax;
    fr->ylog = p->ylog;
    if (fr->x0 < fr->x1 && fr->y0 < fr->y1)
        return;
    double x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
    for (size_t k = 0; k < ns; k++)
        for (size_t i = 0; i < s[k].n; i++) {
            x0 = fmin(x0, s[k].x[i]);
            x1 = fmax(x1, s[k].x[i]);
            y0 = fmin(y0, s[k].y[i]);
            y1 = fmax(y1, s[k].y[i]);
        }
    if (!isnan(p->vline)) { /* keep the reference line in view */
        x0 = fmin(x0, p->vline);
        x1 = fmax(x1, p->vline);
    }
    if (!(fr->x0 < fr->x1)) {
        double pad = (x1 - x0) * 0.05 + 1e-9;
        fr->x0 = x0 - pad;
        fr->x1 = x1 + pad;
    }
    if (!(fr->y0 < fr->y1)) {
        if (fr->ylog) {
            fr->y0 = pow(10.0, floor(log10(y0)));
            fr->y1 = pow(10.0, ceil(log10(y1)));
        } else {
            double pad = (y1 - y0) * 0.05 + 1e-9;
            fr->y0 = y0 - pad;
            fr->y1 = y1 + pad;
        }
    }
}

void np_plot_svg(FILE *f, const np_plot *p, const np_plot_series *s, size_t ns)
{
    frame fr;
    fit(p, s, ns, &fr);
    fprintf(f, "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%d\" height=\"%d\" viewBox=\"0 0 %d %d\" "
               "font-family=\"sans-serif\" font-size=\"12\">\n", W, H, W, H);
    fprintf(f, "<rect width=\"%d\" height=\"%d\" fill=\"white\"/>\n", W, H);
    fprintf(f, "<text x=\"%d\" y=\"24\" text-anchor=\"middle\" font-size=\"15\">", W / 2);
    put_text(f, p->title);
    fputs("</text>\n", f);
    /* Axes and ticks. */
    fprintf(f, "<rect x=\"%d\" y=\"%d\" width=\"%d\" height=\"%d\" fill=\"none\" stroke=\"black\"/>\n", ML, MT,
            W - ML - MR, H - MT - MB);
    /* Ticks by index with a relative tolerance: any data scale gives at most NP_TICKS_MAX ticks. */
    double xs = nice_step(fr.x1 - fr.x0, 8), x0t = ceil(fr.x0 / xs) * xs;
    for (int i = 0; i < NP_TICKS_MAX && xs > 0; i++) {
        double t = x0t + i * xs;
        if (t > fr.x1 + xs * 1e-6)
            break;
        double X = fx(&fr, t);
        fprintf(f, "<line x1=\"%.1f\" y1=\"%d\" x2=\"%.1f\" y2=\"%d\" stroke=\"#ddd\"/>"
                   "<text x=\"%.1f\" y=\"%d\" text-anchor=\"middle\">%g</text>\n",
                X, MT, X, H - MB, X, H - MB + 16, t);
    }
    if (fr.ylog) {
        double t = fr.y0;
        for (int i = 0; i < NP_TICKS_MAX && t > 0 && t <= fr.y1 * 1.0001; i++, t *= 10.0) {
            double Y = fy(&fr, t);
            fprintf(f, "<line x1=\"%d\" y1=\"%.1f\" x2=\"%d\" y2=\"%.1f\" stroke=\"#ddd\"/>"
                       "<text x=\"%d\" y=\"%.1f\" text-anchor=\"end\">%g</text>\n",
                    ML, Y, W - MR, Y, ML - 6, Y + 4, t);
        }
    } else {
        double ys = nice_step(fr.y1 - fr.y0, 6), y0t = ceil(fr.y0 / ys) * ys;
        for (int i = 0; i < NP_TICKS_MAX && ys > 0; i++) {
            double t = y0t + i * ys;
            if (t > fr.y1 + ys * 1e-6)
                break;
            double Y = fy(&fr, t);
            fprintf(f, "<line x1=\"%d\" y1=\"%.1f\" x2=\"%d\" y2=\"%.1f\" stroke=\"#ddd\"/>"
                       "<text x=\"%d\" y=\"%.1f\" text-anchor=\"end\">%g</text>\n",
                    ML, Y, W - MR, Y, ML - 6, Y + 4, t);
        }
    }
    fprintf(f, "<text x=\"%d\" y=\"%d\" text-anchor=\"middle\">", (ML + W - MR) / 2, H - 24);
    put_text(f, p->xlabel);
    fprintf(f, "</text>\n<text x=\"18\" y=\"%d\" text-anchor=\"middle\" transform=\"rotate(-90 18 %d)\">",
            (MT + H - MB) / 2, (MT + H - MB) / 2);
    put_text(f, p->ylabel);
    fputs("</text>\n", f);
    /* Reference lines. */
    if (!isnan(p->vline) && p->vline >= fr.x0 && p->vline <= fr.x1) {
        double X = fx(&fr, p->vline);
        fprintf(f, "<line x1=\"%.1f\" y1=\"%d\" x2=\"%.1f\" y2=\"%d\" stroke=\"#c00\" stroke-dasharray=\"6 4\"/>"
                   "<text x=\"%.1f\" y=\"%d\" fill=\"#c00\">",
                X, MT, X, H - MB, X + 4, MT + 14);
        put_text(f, p->vlabel);
        fputs("</text>\n", f);
    }
    if (!isnan(p->hline) && p->hline >= fr.y0 && p->hline <= fr.y1) {
        double Y = fy(&fr, p->hline);
        fprintf(f, "<line x1=\"%d\" y1=\"%.1f\" x2=\"%d\" y2=\"%.1f\" stroke=\"#c00\" stroke-dasharray=\"6 4\"/>"
                   "<text x=\"%d\" y=\"%.1f\" fill=\"#c00\" text-anchor=\"end\">",
                ML, Y, W - MR, Y, W - MR - 4, Y - 4);
        put_text(f, p->hlabel);
        fputs("</text>\n", f);
    }
    /* Series and legend. */
    for (size_t k = 0; k < ns; k++) {
        const np_plot_series *q = &s[k];
        if (q->line && q->n > 1) {
            fprintf(f, "<polyline fill=\"none\" stroke=\"%s\" stroke-width=\"1.5\" points=\"", q->color);
            for (size_t i = 0; i < q->n; i++)
                fprintf(f, "%s%.1f,%.1f", i ? " " : "", fx(&fr, q->x[i]), fy(&fr, q->y[i]));
            fprintf(f, "\"/>\n");
        }
        if (q->markers)
            for (size_t i = 0; i < q->n; i++)
                fprintf(f, "<circle cx=\"%.1f\" cy=\"%.1f\" r=\"3\" fill=\"%s\"/>\n", fx(&fr, q->x[i]),
                        fy(&fr, q->y[i]), q->color);
        double ly = MT + 16.0 + 16.0 * (double)k;
        fprintf(f, "<rect x=\"%d\" y=\"%.1f\" width=\"10\" height=\"10\" fill=\"%s\"/>"
                   "<text x=\"%d\" y=\"%.1f\">",
                W - MR - 220, ly - 9, q->color, W - MR - 205, ly);
        put_text(f, q->label);
        fputs("</text>\n", f);
    }
    fprintf(f, "</svg>\n");
}
