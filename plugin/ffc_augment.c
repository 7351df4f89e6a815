/* ffc_augment.c: the Uzawa update of the normal and tangential multipliers,
 * pointwise or nodal. */
#include "ffc.h"
#include "ffc_internal.h"
#include "ffc_link_internal.h"

#include <math.h>
#include <string.h>

int ffc_augment(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
                long nl, const ffc_link links[], double lambda[], double lam_t[],
                const ffc_law *law, ffc_stats *stats, long *bad)
{
    return ffc__augment(effects, pair, qdeg, nl, links, lambda, lam_t, law, stats, NULL, bad);
}

int ffc__augment(const ffc_effects *effects, const ffc_pair *pair, int qdeg, long nl, const ffc_link links[],
                 double lambda[], double lam_t[], const ffc_law *law, ffc_stats *stats, signed char state[],
                 long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    double qw[16];
    int nq;
    int s = ffc__common_checks(effects, pair, qdeg, nl, links, law, lambda, lam_t, qw, &nq, bad);
    if (s) return s;
    const int fric = ffc__friction_on(effects, law);
    ffc_stats loc;
    if (!stats) stats = &loc;
    ffc__stats_init(stats);
    if (law->nodal) {
        /* friction with the pressures of the current multipliers */
        nodal_t w;
        s = ffc__nodal_prepare(effects, pair, qw, nq, nl, links, lambda, fric ? lam_t : NULL, law, &w, stats, bad);
        if (s) return s;
        for (long e = 0; e < w.n; e++) {
            const double t = ffc__nodal_point_pressure(pair, &links[w.L[e].k], &w.L[e], w.tn);
            if (t == 0.0) continue;
            double Tq[3] = {0, 0, 0};
            int fs;
            if (fric) ffc__nodal_point_traction(pair, &links[w.L[e].k], &w.L[e], w.T, Tq, &fs);
            ffc__nodal_point_stats(stats, t, &w.L[e], Tq);
        }
        /* the pair's slave nodes only: another pair may keep its multipliers
           in the same array (a node visited twice changes nothing the second time) */
        for (long a = 0; a < pair->nfs * pair->ns; a++) {
            const long v = pair->Fs[a];
            double d = fabs(w.tn[v] - lambda[v]);
            if (d > stats->max_dlam) stats->max_dlam = d;
            lambda[v] = w.tn[v];
            if (state) state[v] = (signed char)(fric ? w.T[v].f.state : FFC_FRIC_OPEN);
            if (!fric) continue;
            for (int i = 0; i < 3; i++) {
                d = fabs(w.T[v].f.t[i] - lam_t[3 * v + i]);
                if (d > stats->max_dlam_t) stats->max_dlam_t = d;
                lam_t[3 * v + i] = w.T[v].f.t[i];
            }
        }
        ffc__nodal_free(&w);
        return FFC_OK;
    }
    double Rl[FFC_MAXDOF];
    long dof[FFC_MAXDOF];
    for (long k = 0; k < nl; k++) {
        const ffc_link *lk = &links[k];
        ffc_link_state st;
        memset(&st, 0, sizeof st);
        if (lk->mf >= 0) {
            int nd;
            s = ffc__eval_link(effects, pair, qw, nq, lk, lambda[k], fric ? lam_t + 3 * k : NULL, law, &st, Rl, NULL,
                               dof, &nd);
            if (s) { *bad = k; return s; }
            ffc__stats_add(stats, &st, fric);
        }
        double d = fabs(st.tn - lambda[k]);
        if (d > stats->max_dlam) stats->max_dlam = d;
        lambda[k] = st.tn;
        if (state) state[k] = (signed char)(fric && lk->mf >= 0 ? st.fstate : FFC_FRIC_OPEN);
        if (fric)
            for (int i = 0; i < 3; i++) {
                d = fabs(st.t[i] - lam_t[3 * k + i]);
                if (d > stats->max_dlam_t) stats->max_dlam_t = d;
                lam_t[3 * k + i] = st.t[i];
            }
    }
    stats->max_pen_node = stats->max_pen;
    return FFC_OK;
}
