/* ffc_points.c: per-link output: slave point, gap, pressure, area, master
 * facet, friction traction, state and dissipation density. */
#include "ffc.h"
#include "ffc_internal.h"
#include "ffc_link_internal.h"

#include <math.h>
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
        row[0] = st.x[0]; row[1] = st.x[1]; row[2] = st.x[2];
        row[3] = st.gap; row[4] = st.tn; row[5] = st.active;
        row[6] = st.da; row[7] = (double)lk->mf;
        row[8] = -st.t[0]; row[9] = -st.t[1]; row[10] = -st.t[2];
        row[11] = st.fstate; row[12] = ffc__dot(st.t, st.slip);
    }
    ffc__nodal_free(&w);
    return FFC_OK;
}
