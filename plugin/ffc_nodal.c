/* ffc_nodal.c: the nodal (mortar-type) multiplier law: weighted nodal gaps,
 * pressures and return maps (its assembly: ffc_nodal_assemble.c). */
#include "ffc.h"
#include "ffc_internal.h"
#include "ffc_link_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Formulation (nodal multipliers).  For slave node a, over the linked
 * points q of its facets:
 *     G_a = sum_q N_a(q) da_q g_q,   W_a = sum_q N_a(q) da_q,
 *     g~_a = G_a / W_a (weighted gap),   t_a = <lambda_a - eps g~_a>.
 * The pressure at a point is t_q = sum_a N_a(q) t_a and the virtual work
 * sum_q t_q da_q dg_q gives the residual
 *     R = -sum_q t_q da_q G_q.
 * Its derivative:
 *     K = -sum_q t_q (da_q D_q + G_q dda_q^T)               (geometric)
 *       + sum_a (eps H(t_a) / W_a) B_a C_a^T                 (material)
 * with H(t_a) = 1 when lambda_a - eps g~_a >= 0 (touching counts, to round-off: >= -eps 1e-12 sqrt(W_a)).
 *     B_a = sum_q N_a(q) da_q G_q,
 *     C_a = sum_q N_a(q) (da_q G_q + (g_q - g~_a) dda_q)   (= dG_a - g~_a dW_a).
 * The Uzawa update lambda_a <- t_a has the fixed point g~_a = 0 where
 * t_a > 0 and g~_a >= 0, lambda_a = 0 elsewhere: one constraint per slave
 * node, the weighted-gap conditions of mortar methods.
 *
 * Friction, the same way: per node the weighted slip and normal
 *     r~_a = sum_q N_a da_q r_q / W_a,   m_a = sum_q N_a da_q n_q,  n~_a = m_a / |m_a|,
 * the return map at the node T_a = T(n~_a, lambda_T,a, r~_a, t_a), and the
 * point traction T_q = sum_a N_a(q) T_a.  Residual R_f = sum_q da_q S_q^T T_q.
 * Derivative: the link terms at fixed T_q (ffc__link_friction_geo) plus
 *     sum_a Bf_a dT_a,   Bf_a = sum_q N_a da_q S_q^T  (nd x 3),
 *     dT_a = dT/dr dr~_a + dT/dn dn~_a - dT/dt_N (eps H(t_a) / W_a) C_a^T,
 *     dr~_a = [sum_q N_a (da_q Q_q + (r_q - r~_a) dda_q^T)] / W_a,
 *     dn~_a = (I - n~ n~^T) / |m_a| sum_q N_a (da_q dn_q + n_q dda_q^T).
 * A direction e_k of node a held at zero in its contact plane (law->fixed
 * > 0, |n~_k| < 0.9) is dropped: r~ and m replaced by Q r~ and Q m, Q = I - e_k e_k^T
 * (constant), so dr~ and dm become Q dr~ and Q dm, and n~ = Q m / |Q m|;
 * the trial uses Q lambda_T (so the update keeps lambda_T,k = 0).
 * On a symmetry plane normal to e_k this is the mirror half's share (its
 * slip and normal have the opposite k components).
 * The Uzawa update lambda_T,a <- T_a drives the weighted slip of sticking
 * nodes to zero: one tangential constraint (a 2-vector) per node, as many
 * as there are tangential unknowns (pointwise multipliers would impose
 * more and drift).
 * With law->tdual the friction sums take the dual basis of a full linear
 * facet, Phi_a = 4 N_a - 1 (int Phi_a N_b dA = delta_ab int N_a dA), in
 * place of N_a: r~_a = sum_q Phi_a da_q r_q / W_a, m_a = sum_q Phi_a da_q n_q,
 * T_q = sum_a Phi_a T_a, Bf_a = sum_q Phi_a da_q S_q^T and
 *     dr~_a = [sum_q (Phi_a (da_q Q_q + r_q dda_q^T) - N_a r~_a dda_q^T)] / W_a
 * (W_a still sum_q N_a da_q).  With N_a, a sticking node's weighted slip
 * averages in its sliding neighbours' and the rim of a stick zone slides
 * (Cattaneo-Mindlin: stick radii 10-15% small at h_c 0.025); with Phi_a
 * the weighted slip is the node's own to the facet rule's order. */

/* the friction sums in the dual basis: asked for, on linear facets, and
 * without a dual basis or segments of the whole law (mortar) */
static int tdual_on(const ffc_pair *P, const ffc_law *law)
{
    return law->tdual && law->nodal && !law->dual && law->nedge == 0 && P->ns == 3;
}

void ffc__nodal_free(nodal_t *w)
{
    free(w->L);
    free(w->Gn);
    free(w->Wn);
    free(w->tn);
    free(w->on);
    free(w->F);
    free(w->T);
}

/* Formulation (a touching node).  A node whose trial pressure is exactly
 * zero (the gap closed, no load yet: w->on, t_N = 0) and whose trial
 * traction T_tr = P (lambda_T + eps_T r) vanishes sits on the kink of the
 * return map, where the stick branch (T = T_tr, dT/dr = eps_T P,
 * dT/dn = -(n.v) I - n v^T with v = lambda_T + eps_T r) and the slip branch
 * (T = mu t_N e = 0, derivative 0) meet.  Both give T = 0; the stick
 * branch's derivative is taken (an element of the generalized Jacobian,
 * as in a semi-smooth Newton method), so that a body held only by
 * frictional contact (a block between two others) has a regular first
 * system; with the slip branch's it would be free to translate. */
static void touching_stick(nfn_t *T, const double lam_t[3], double eps_t)
{
    double v[3], ttr[3];
    for (int i = 0; i < 3; i++) v[i] = lam_t[i] + eps_t * T->r[i];
    const double nv = ffc__dot(T->n, v);
    for (int i = 0; i < 3; i++) ttr[i] = v[i] - T->n[i] * nv;
    if (T->f.state != FFC_FRIC_OPEN || ffc__dot(ttr, ttr) != 0.0) return;
    T->f.state = FFC_FRIC_STICK;
    for (int i = 0; i < 3; i++) {
        T->f.t[i] = 0.0;
        T->f.dt_dtn[i] = 0.0;
        for (int j = 0; j < 3; j++) {
            T->f.dt_dr[i][j] = eps_t * ((i == j) - T->n[i] * T->n[j]);
            T->f.dt_dn[i][j] = -nv * (i == j) - T->n[i] * v[j];
        }
    }
}

/* The multiplier shape values at xs of slave facet f: linear on the
 * facet's vertices (for 6-node facets too: quadratic vertex shape
 * functions integrate to zero, which would leave vertex nodes without
 * weight), in the facet's dual basis Phi_a = sum_b A_ab N_b with
 * law->dual (ffc_dual_basis); N[ns] */
void ffc__nodal_shape(const ffc_law *law, int ns, long f, const double xs[2], double N[FFC_MAXNODES])
{
    ffc_shape(3, xs, N, NULL);
    for (int a = 3; a < ns; a++) N[a] = 0.0;
    if (law->dual) {
        const double *A = law->dual + 9 * f, L[3] = {N[0], N[1], N[2]};
        for (int a = 0; a < 3; a++) N[a] = A[3 * a] * L[0] + A[3 * a + 1] * L[1] + A[3 * a + 2] * L[2];
    }
}

/* A share of the links (law->lsel): its partial node sums G_a, W_a and the
 * weighted slip's and normal's sums, 8 per node of the linked links' slave
 * facets in ascending node order, completed by law->nsum into every share's; called
 * with the share's status st on every path (the shares wait for each
 * other there).  Returns the shares' combined status. */
static int share_sums(const ffc_pair *P, long nl, const ffc_link links[], const ffc_law *law, int st, nodal_t *w)
{
    /* the nodes of the linked links' slave facets (every share's alike) */
    unsigned char *mark = st ? NULL : calloc((size_t)(P->nv > 0 ? P->nv : 1), 1);
    long *v = NULL, nn = 0;
    if (mark) {
        long nm = 0;
        for (long k = 0; k < nl; k++)
            if (links[k].mf >= 0)
                for (int a = 0; a < P->ns; a++) {
                    unsigned char *m = &mark[P->Fs[links[k].sf * P->ns + a]];
                    nm += !*m;
                    *m = 1;
                }
        v = malloc((size_t)(nm > 0 ? nm : 1) * sizeof *v);
        for (long i = 0; i < P->nv && v; i++)
            if (mark[i]) v[nn++] = i;
        free(mark);
    }
    double *buf = v ? malloc((size_t)(8 * nn > 0 ? 8 * nn : 1) * sizeof *buf) : NULL;
    if (!st && !buf) st = FFC_ERR_MEMORY;
    for (long i = 0; i < nn && buf; i++) {
        double *b = buf + 8 * i;
        b[0] = w->Gn[v[i]];
        b[1] = w->Wn[v[i]];
        for (int c = 0; c < 3; c++) {
            b[2 + c] = w->T ? w->T[v[i]].r[c] : 0.0;
            b[5 + c] = w->T ? w->T[v[i]].n[c] : 0.0;
        }
    }
    st = law->nsum(law->nsum_ctx, st, st ? 0 : 8 * nn, st ? NULL : buf);
    for (long i = 0; i < nn && !st; i++) {
        const double *b = buf + 8 * i;
        w->Gn[v[i]] = b[0];
        w->Wn[v[i]] = b[1];
        for (int c = 0; c < 3 && w->T; c++) {
            w->T[v[i]].r[c] = b[2 + c];
            w->T[v[i]].n[c] = b[5 + c];
        }
    }
    free(v);
    free(buf);
    return st;
}

/* pass 1: geometry of every linked point, nodal sums and pressures; with
 * friction (lam_t != NULL) the slips and the nodal return maps */
int ffc__nodal_prepare(const ffc_effects *fx, const ffc_pair *P, const double qw[], int nq, long nl,
                       const ffc_link links[], const double lambda[], const double lam_t[], const ffc_law *law,
                       nodal_t *w, ffc_stats *stats, long *bad)
{
    const double eps = law->eps_n;
    const int tdual = tdual_on(P, law);
    memset(w, 0, sizeof *w);
    long n = 0;
    for (long k = 0; k < nl; k++) n += links[k].mf >= 0 && (!law->lsel || law->lsel[k]);
    w->L = malloc((size_t)(n > 0 ? n : 1) * sizeof *w->L);
    w->Gn = calloc((size_t)P->nv, sizeof *w->Gn);
    w->Wn = calloc((size_t)P->nv, sizeof *w->Wn);
    w->tn = calloc((size_t)P->nv, sizeof *w->tn);
    w->on = calloc((size_t)P->nv, 1);
    if (lam_t) {
        w->F = malloc((size_t)(n > 0 ? n : 1) * sizeof *w->F);
        w->T = calloc((size_t)P->nv, sizeof *w->T);
    }
    int st = !w->L || !w->Gn || !w->Wn || !w->tn || !w->on || (lam_t && (!w->F || !w->T)) ? FFC_ERR_MEMORY : FFC_OK;
    for (long k = 0; k < nl && !st; k++) {
        const ffc_link *lk = &links[k];
        if (lk->mf < 0 || (law->lsel && !law->lsel[k])) continue;
        nlink_t *e = &w->L[w->n];
        lnodes_t ln;
        int s = ffc__gather_link(fx, P, nq, lk, &ln);
        if (s) { *bad = k; st = s; break; }
        memcpy(e->dof, ln.dof, sizeof ln.dof);
        e->k = k;
        e->nd = ln.nd;
        ffc_link_state ls;
        lgeo_t g;
        s = ffc__link_geometry(fx, P->ns, CP3(ln.Xs), CP3(ln.Xs0), lk->xs, ffc__link_weight(lk, qw), P->nm, CP3(ln.Xm), lk->xm,
                               P->obst, &ls, &g, NULL);
        if (s) { *bad = k; st = s; break; }
        memcpy(e->G, g.G, sizeof e->G);
        memcpy(e->dda, g.dda, sizeof e->dda);
        e->g = ls.gap;
        e->da = ls.da;
        for (int i = 0; i < 3; i++) e->n[i] = ls.n[i];
        ffc__nodal_shape(law, P->ns, lk->sf, lk->xs, e->N);
        for (int a = 0; a < P->ns; a++) e->Nt[a] = tdual ? 4.0 * e->N[a] - 1.0 : e->N[a];
        if (lam_t) {
            nfl_t *fl = &w->F[w->n];
            ffc__link_slip(&g, CP3(ln.Ds), CP3(ln.Dm), fl->r);
            ffc__link_slip_deriv(&g, CP3(ln.Dm), ffc__motion_coef(fx, law), ffc__law_material(law), fl->sw, fl->Q);
            memcpy(fl->dn, g.dn, sizeof fl->dn);
        }
        for (int a = 0; a < P->ns; a++) {
            long v = P->Fs[lk->sf * P->ns + a];
            w->Gn[v] += e->N[a] * e->da * e->g;
            w->Wn[v] += e->N[a] * e->da;
            if (lam_t)
                for (int i = 0; i < 3; i++) {
                    w->T[v].r[i] += e->Nt[a] * e->da * w->F[w->n].r[i];
                    w->T[v].n[i] += e->Nt[a] * e->da * e->n[i];
                }
        }
        if (stats) {
            stats->linked++;
            if (-e->g > stats->max_pen) stats->max_pen = -e->g;
        }
        w->n++;
    }
    if (law->lsel && law->nsum) st = share_sums(P, nl, links, law, st, w);   /* (every share's sums; on every path) */
    if (st) { ffc__nodal_free(w); return st; }
    for (long v = 0; v < P->nv; v++)
        if (w->Wn[v] > 0.0) {
            double g = w->Gn[v] / w->Wn[v];
            const double trial = lambda[v] - eps * g;
            w->tn[v] = fmax(0.0, trial);
            /* touching: the gap closed to round-off (two bodies meshed on one
             * plane carry gaps of +-1e-17) counts as on the kink */
            w->on[v] = trial >= -eps * 1e-12 * sqrt(w->Wn[v]);
            if (stats && w->tn[v] > 0.0 && -g > stats->max_pen_node) stats->max_pen_node = -g;
            if (!lam_t) continue;
            nfn_t *T = &w->T[v];
            T->mnorm = sqrt(ffc__dot(T->n, T->n));
            /* directions held at zero in the contact plane (a symmetry
             * plane's): their components of the weighted slip and normal
             * dropped (law->fixed > 0; a prescribed motion, < 0, keeps them) */
            T->drop = 0;
            for (int i = 0; law->fixed && i < 3; i++)
                if (law->fixed[3 * v + i] > 0.0 && fabs(T->n[i]) < 0.9 * T->mnorm) {
                    T->drop |= 1 << i;
                    T->r[i] = T->n[i] = 0.0;
                }
            if (T->drop) T->mnorm = sqrt(ffc__dot(T->n, T->n));
            for (int i = 0; i < 3; i++) {
                T->r[i] /= w->Wn[v];
                T->n[i] = T->mnorm > 0.0 ? T->n[i] / T->mnorm : 0.0;
            }
            if (!(T->mnorm > 0.0)) continue; /* opposite normals cancel: no friction */
            double lt[3];                /* lambda_T without the dropped components */
            for (int i = 0; i < 3; i++) lt[i] = (T->drop & (1 << i)) ? 0.0 : lam_t[3 * v + i];
            int s = ffc_friction_map(T->n, lt, T->r, law->mu, law->eps_t, w->tn[v], &T->f);
            if (s) { ffc__nodal_free(w); return s; }
            if (w->on[v] && !(w->tn[v] > 0.0)) touching_stick(T, lt, law->eps_t);
            if (stats && T->f.state != FFC_FRIC_OPEN) {
                stats->stick += T->f.state == FFC_FRIC_STICK;
                stats->slip += T->f.state == FFC_FRIC_SLIP;
                const double tt = sqrt(ffc__dot(T->f.t, T->f.t));
                if (tt > stats->max_tt) stats->max_tt = tt;
                stats->dissipation += ffc__slip_scale(fx, law) * w->Wn[v] * ffc__dot(T->f.t, T->r);
                const double rt = ffc__slip_scale(fx, law) * ffc__tangential_norm(T->r, T->n);
                if (rt > stats->max_slip) stats->max_slip = rt;
            }
        }
    return FFC_OK;
}

/* pressure at a linked point: the interpolated nodal pressure */
double ffc__nodal_point_pressure(const ffc_pair *P, const ffc_link *lk, const nlink_t *e, const double tn[])
{
    double t = 0.0;
    for (int a = 0; a < P->ns; a++) t += e->N[a] * tn[P->Fs[lk->sf * P->ns + a]];
    return t;
}

int ffc__nearest_corner(const ffc_link *lk, const int state[3])
{
    double L[FFC_MAXNODES];
    ffc_shape(3, lk->xs, L, NULL);
    int best = -1;
    for (int a = 0; a < 3; a++)
        if (state[a] != FFC_FRIC_OPEN && (best < 0 || L[a] > L[best])) best = a;
    return best;
}

/* traction at a linked point: the interpolated nodal tractions; *state the
 * state of its nearest corner that is not open (ffc__nearest_corner: the
 * points take their nodes' states over the nodes' tributary areas, so
 * that a stick zone measured on points or on nodes is the same) */
void ffc__nodal_point_traction(const ffc_pair *P, const ffc_link *lk, const nlink_t *e, const nfn_t T[],
                               double t[3], int *state)
{
    t[0] = t[1] = t[2] = 0.0;
    int corner[3];
    for (int a = 0; a < P->ns; a++) {
        const nfn_t *Ta = &T[P->Fs[lk->sf * P->ns + a]];
        if (a < 3) corner[a] = Ta->f.state;
        if (e->Nt[a] == 0.0) continue;
        for (int i = 0; i < 3; i++) t[i] += e->Nt[a] * Ta->f.t[i];
    }
    const int c = ffc__nearest_corner(lk, corner);
    *state = c < 0 ? FFC_FRIC_OPEN : corner[c];
}

/* statistics of a linked point of the nodal law: pressure t (counted as
 * active when > 0; a negative t, between pressed nodes with dual
 * multipliers, adds to the force) and friction traction Tq */
void ffc__nodal_point_stats(ffc_stats *s, double t, const nlink_t *e, const double Tq[3])
{
    if (t > 0.0) ffc__stats_pressure(s, t, e->da, e->n);
    else
        for (int i = 0; i < 3; i++) s->force[i] += t * e->da * e->n[i];
    for (int i = 0; i < 3; i++) s->force_t[i] -= Tq[i] * e->da;
}
