/* ffc_points.c: per-link output: slave point, gap, pressure, area, master
 * facet, friction traction, state and dissipation density. */
#include "ffc.h"
#include "ffc_internal.h"
#include "ffc_link_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

int ffc_points(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
               long nl, const ffc_link links[], const double lambda[],
               const double lam_t[], const ffc_law *law, double P[], long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    double qw[16];
    int nq;
    int s = ffc__common_checks(effects, pair, qdeg, nl, links, law, lambda, lam_t, qw, &nq, bad);
    if (s) return s;
    if (!P) return FFC_ERR_NULL;
    const int fric = ffc__friction_on(effects, law);
    double Rl[FFC_MAXDOF];
    long dof[FFC_MAXDOF];
    nodal_t w;
    memset(&w, 0, sizeof w);
    if (law->nodal &&
        (s = ffc__nodal_prepare(effects, pair, qw, nq, nl, links, lambda, fric ? lam_t : NULL, law, &w, NULL, bad)))
        return s;
    long e = 0;
    for (long k = 0; k < nl; k++) {
        double *row = P + k * FFC_POINT_COLS;
        const ffc_link *lk = &links[k];
        if (lk->sf < 0 || lk->sf >= pair->nfs) { *bad = k; ffc__nodal_free(&w); return FFC_ERR_INDEX; }
        ffc_link_state st;
        memset(&st, 0, sizeof st);
        if (lk->mf >= 0) {
            int nd;
            if (law->nodal) { /* geometry, then the interpolated nodal pressure and traction */
                ffc_law l0 = *law;
                l0.mu = 0.0;
                s = ffc__eval_link(effects, pair, qw, nq, lk, 0.0, NULL, &l0, &st, Rl, NULL, dof, &nd);
                if (!s) {
                    const nlink_t *E = &w.L[e];
                    st.tn = ffc__nodal_point_pressure(pair, lk, E, w.tn);
                    st.active = st.tn > 0.0;
                    if (fric) {
                        ffc__nodal_point_traction(pair, lk, E, w.T, st.t, &st.fstate);
                        for (int i = 0; i < 3; i++) st.slip[i] = ffc__slip_scale(effects, law) * w.F[e].r[i];
                    }
                    e++;
                }
            } else {
                s = ffc__eval_link(effects, pair, qw, nq, lk, lambda[k], fric ? lam_t + 3 * k : NULL, law, &st, Rl,
                                   NULL, dof, &nd);
            }
            if (s) { *bad = k; ffc__nodal_free(&w); return s; }
        } else {
            /* no partner: the slave point alone */
            double N[FFC_MAXNODES];
            ffc_shape(pair->ns, lk->xs, N, NULL);
            for (int a = 0; a < pair->ns; a++) {
                long v = pair->Fs[lk->sf * pair->ns + a];
                for (int i = 0; i < 3; i++) st.x[i] += N[a] * (pair->X[3 * v + i] + pair->u[3 * v + i]);
            }
            st.gap = NAN;
        }
        row[FFC_PT_X] = st.x[0]; row[FFC_PT_Y] = st.x[1]; row[FFC_PT_Z] = st.x[2];
        row[FFC_PT_GAP] = st.gap; row[FFC_PT_P] = st.tn; row[FFC_PT_ACTIVE] = st.active;
        row[FFC_PT_AREA] = st.da; row[FFC_PT_FACET] = (double)lk->mf;
        row[FFC_PT_TX] = -st.t[0]; row[FFC_PT_TY] = -st.t[1]; row[FFC_PT_TZ] = -st.t[2];
        row[FFC_PT_STATE] = st.fstate; row[FFC_PT_DISS] = ffc__dot(st.t, st.slip);
    }
    ffc__nodal_free(&w);
    return FFC_OK;
}

int ffc_points_nodes(const ffc_effects *effects, const ffc_pair *pair, int qdeg, long nl, const ffc_link links[],
                     const double lambda[], const double lam_t[], const ffc_law *law, long cap, double P[], long *n,
                     long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!n) return FFC_ERR_NULL;
    *n = 0;
    double qw[16];
    int nq;
    int s = ffc__common_checks(effects, pair, qdeg, nl, links, law, lambda, lam_t, qw, &nq, bad);
    if (s) return s;
    if (!law->nodal) return FFC_ERR_VALUE;
    if (cap > 0 && !P) return FFC_ERR_NULL;
    long *mf = malloc((size_t)pair->nv * sizeof *mf);
    if (!mf) return FFC_ERR_MEMORY;
    for (long v = 0; v < pair->nv; v++) mf[v] = -2; /* not a slave node */
    for (long k = 0; k < pair->nfs * pair->ns; k++) /* (the multipliers' nodes: the facets' vertices) */
        if (k % pair->ns < 3) mf[pair->Fs[k]] = -1;
    for (long k = nl - 1; k >= 0; k--) /* each node's first link's master facet */
        if (links[k].mf >= 0)
            for (int a = 0; a < 3; a++) mf[pair->Fs[links[k].sf * pair->ns + a]] = links[k].mf;
    long need = 0;
    for (long v = 0; v < pair->nv; v++) need += mf[v] >= -1;
    *n = need;
    if (cap < need) { free(mf); return FFC_ERR_CAPACITY; }
    const int fric = ffc__friction_on(effects, law);
    nodal_t w;
    if ((s = ffc__nodal_prepare(effects, pair, qw, nq, nl, links, lambda, fric ? lam_t : NULL, law, &w, NULL, bad))) {
        free(mf);
        return s;
    }
    long r = 0;
    for (long v = 0; v < pair->nv; v++) {
        if (mf[v] < -1) continue;
        double *row = P + r++ * FFC_POINT_COLS;
        const double W = w.Wn[v];
        for (int i = 0; i < 3; i++) row[FFC_PT_X + i] = pair->X[3 * v + i] + pair->u[3 * v + i];
        row[FFC_PT_GAP] = W > 0.0 ? w.Gn[v] / W : NAN;
        row[FFC_PT_P] = w.tn[v];
        row[FFC_PT_ACTIVE] = w.tn[v] > 0.0;
        row[FFC_PT_AREA] = W;
        row[FFC_PT_FACET] = (double)mf[v];
        for (int i = FFC_PT_TX; i < FFC_POINT_COLS; i++) row[i] = 0.0;
        if (fric && W > 0.0) {
            const nfn_t *T = &w.T[v];
            for (int i = 0; i < 3; i++) row[FFC_PT_TX + i] = -T->f.t[i];
            row[FFC_PT_STATE] = T->f.state;
            row[FFC_PT_DISS] = ffc__slip_scale(effects, law) * ffc__dot(T->f.t, T->r);
        }
    }
    ffc__nodal_free(&w);
    free(mf);
    return FFC_OK;
}
