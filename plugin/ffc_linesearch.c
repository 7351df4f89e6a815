/* ffc_linesearch.c: the Newton loops' line search (regula falsi on
 * g(a) = r(u + a d) . d, then a guard against growth of |r|), by reverse
 * communication (see ffc/newton.h). */
#include <math.h>

#include "ffc.h"

int ffc_ls_start(ffc_linesearch *s, int max_ls, double ls_tol, double a0, double g0, double rn, int secant,
                 int guard)
{
    if (!s) return FFC_ERR_NULL;
    if (max_ls < 0 || !(ls_tol > 0 && ls_tol < 1) || !(a0 > 0 && a0 <= 1)) return FFC_ERR_VALUE;
    *s = (ffc_linesearch){0};
    s->max_ls = max_ls;
    s->ls_tol = ls_tol;
    s->g0 = g0;
    s->rn = rn;
    s->a = a0;
    s->at = -1.0;
    s->alo = 0.0;
    s->glo = g0;
    s->ahi = a0;
    s->ghi = 0.0;
    s->guard = guard && max_ls > 0;
    s->phase = secant && max_ls > 0 ? 1 : s->guard ? 2 : 0;
    return FFC_OK;
}

/* phase 2 from where phase 1 left the step, or the end */
static void to_guard(ffc_linesearch *s)
{
    s->phase = s->guard ? 2 : 0;
    s->it = 0;
}

int ffc_ls_next(ffc_linesearch *s, double *a)
{
    if (!s || !a) return FFC_ERR_NULL;
    if (s->phase == 1 && s->it >= s->max_ls) to_guard(s);
    while (s->phase == 2) {
        if (s->it >= s->max_ls) { s->phase = 0; break; }
        if (s->a != s->at) break;
        /* the point last evaluated: its |r| is at hand */
        if (s->rt <= 10 * s->rn) { s->phase = 0; break; }
        s->a *= 0.5;
        s->cuts++;
        s->it++;
    }
    *a = s->a;
    s->waiting = s->phase != 0;
    return s->phase != 0;
}

int ffc_ls_report(ffc_linesearch *s, double g, double rnorm, int full_taken)
{
    if (!s) return FFC_ERR_NULL;
    if (!s->waiting) return FFC_ERR_VALUE;
    s->waiting = 0;
    s->at = s->a;
    s->rt = rnorm;
    s->it++;
    if (s->phase == 2) {
        if (rnorm <= 10 * s->rn) { s->phase = 0; return FFC_OK; }
        s->a *= 0.5;
        s->cuts++;
        return FFC_OK;
    }
    const double a = s->a;
    if (fabs(g) <= s->ls_tol * fabs(s->g0) || (g < 0 && a == s->ahi) || (a == 1.0 && full_taken)) {
        to_guard(s);
        return FFC_OK;
    }
    if (g < 0) {
        s->alo = a; s->glo = g;
        if (s->side == -1) s->ghi *= 0.5;
        s->side = -1;
    } else {
        s->ahi = a; s->ghi = g;
        if (s->side == 1) s->glo *= 0.5;
        s->side = 1;
    }
    const double an = s->alo - s->glo * (s->ahi - s->alo) / (s->ghi - s->glo);
    s->a = fmax(s->alo + 0.05 * (s->ahi - s->alo), fmin(an, s->ahi - 0.05 * (s->ahi - s->alo)));
    s->cuts++;
    return FFC_OK;
}

int ffc_ls_reject(ffc_linesearch *s)
{
    if (!s) return FFC_ERR_NULL;
    if (!s->waiting) return FFC_ERR_VALUE;
    s->waiting = 0;
    s->it++;
    s->cuts++;
    if (s->phase == 2) s->a *= 0.5;
    else {
        s->ahi = s->a;
        s->a = 0.5 * (s->alo + s->a);
    }
    return FFC_OK;
}
