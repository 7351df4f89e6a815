/* ffc_link.c: augmented-Lagrangian normal contact: residual and consistent
 * tangent of one link, assembly over all links, Uzawa update and per-point
 * output. */
#include "ffc.h"
#include "ffc_internal.h"

#include <math.h>
#include <string.h>

/* Formulation (frictionless; gap g = n . (x_s - x_m) >= 0 open).
 * A link is a slave point x_s = sum_a N1_a(xs) x_a with area da = w J_s,
 * and its foot xi on the master facet: tau_a(xi) . (x_s - x_m(xi)) = 0.
 * Pressure t_N = <lambda - eps g>.  The virtual work of the contact
 * traction, da t_N dg, gives the internal-force residual
 *     R = -da t_N G,      G = dg/du = [N1_a n ; -N2_b(xi) n],
 * (the traction t_N n pushes the slave out along the master normal).
 * Its derivative, with dt_N = -eps H(t_N) G . du:
 *     K = da eps G G^T  -  da t_N D  -  t_N G (d da/du)^T,
 * where D = dG/du:
 *     slave rows  a,c:  N1_a dn_c/du
 *     master rows b,c: -N2_b dn_c/du - n_c N2_b,alpha dxi_alpha/du
 * with dn/du and dxi/du from ffc_project_deriv (they carry the variation
 * of the master normal and the sliding of the foot), and
 *     d da / d x_a = w J N1_a,alpha tau^alpha     (slave nodes only)
 * when the area element follows the deformation (finite_def); with small
 * strain the reference area is used and this term vanishes. */
int ffc_link_normal(const ffc_effects *effects, int ns, const double Xs[][3],
                    const double Xs0[][3], const double xs[2], double w,
                    int nm, const double Xm[][3], double lambda, double eps,
                    ffc_link_state *st, double R[FFC_MAXDOF],
                    double K[FFC_MAXDOF][FFC_MAXDOF])
{
    if (!effects || !Xs || !Xs0 || !xs || !Xm || !st || !R) return FFC_ERR_NULL;
    if ((ns != 3 && ns != 6) || (nm != 3 && nm != 6)) return FFC_ERR_NODES;
    if (!(eps > 0) || isinf(eps) || !isfinite(lambda) || !(w > 0)) return FFC_ERR_VALUE;
    const int nd = 3 * (ns + nm);
    for (int k = 0; k < nd; k++) R[k] = 0.0;
    if (K)
        for (int k = 0; k < nd; k++) memset(K[k], 0, (size_t)nd * sizeof K[k][0]);

    double N1[FFC_MAXNODES], dN1[FFC_MAXNODES][2];
    int s = ffc_shape(ns, xs, N1, dN1);
    if (s) return s;
    double p[3] = {0, 0, 0};
    for (int a = 0; a < ns; a++)
        for (int i = 0; i < 3; i++) p[i] += N1[a] * Xs[a][i];
    ffc_point sp;
    s = ffc_facet_point(ns, effects->finite_def ? Xs : Xs0, xs, &sp);
    if (s) return s;
    ffc_proj pr;
    s = ffc__project_free(nm, Xm, p, &pr);
    if (s) return s;

    const double trial = lambda - eps * pr.gap;
    for (int i = 0; i < 3; i++) { st->x[i] = p[i]; st->n[i] = pr.n[i]; }
    st->xi[0] = pr.xi[0];
    st->xi[1] = pr.xi[1];
    st->gap = pr.gap;
    st->da = w * sp.j;
    st->active = trial > 0.0;
    st->tn = st->active ? trial : 0.0;
    if (!st->active) return FFC_OK;

    double dxi[2][FFC_MAXDOF], G[FFC_MAXDOF], dn[3][FFC_MAXDOF];
    s = ffc_project_deriv(ns, N1, nm, Xm, &pr, dxi, G, dn);
    if (s) return s;
    const double da = st->da, tn = st->tn;
    for (int k = 0; k < nd; k++) R[k] = -da * tn * G[k];
    if (!K) return FFC_OK;

    double N2[FFC_MAXNODES], dN2[FFC_MAXNODES][2];
    ffc_shape(nm, pr.xi, N2, dN2);
    /* d da / du on slave dofs (finite deformation only) */
    double dda[FFC_MAXDOF] = {0};
    if (effects->finite_def) {
        double tc[2][3];
        for (int i = 0; i < 3; i++) {
            tc[0][i] = sp.minv[0][0] * sp.tau[0][i] + sp.minv[0][1] * sp.tau[1][i];
            tc[1][i] = sp.minv[1][0] * sp.tau[0][i] + sp.minv[1][1] * sp.tau[1][i];
        }
        for (int a = 0; a < ns; a++)
            for (int i = 0; i < 3; i++)
                dda[3 * a + i] = w * sp.j * (dN1[a][0] * tc[0][i] + dN1[a][1] * tc[1][i]);
    }
    for (int k = 0; k < nd; k++) {
        const int slave = k < 3 * ns, c = k % 3;
        const int node = slave ? k / 3 : (k - 3 * ns) / 3;
        for (int l = 0; l < nd; l++) {
            double D = slave ? N1[node] * dn[c][l]
                             : -N2[node] * dn[c][l] -
                                   pr.n[c] * (dN2[node][0] * dxi[0][l] + dN2[node][1] * dxi[1][l]);
            K[k][l] = da * (eps * G[k] * G[l] - tn * D) - tn * G[k] * dda[l];
        }
    }
    return FFC_OK;
}

/* ------------------------------------------------------- over all links */
static int check_pair(const ffc_pair *P)
{
    if (!P || !P->Fs || !P->Fm || !P->X || !P->u) return FFC_ERR_NULL;
    if ((P->ns != 3 && P->ns != 6) || (P->nm != 3 && P->nm != 6)) return FFC_ERR_NODES;
    if (P->nfs <= 0 || P->nfm <= 0) return FFC_ERR_EMPTY;
    if (P->nv <= 0) return FFC_ERR_SIZE;
    return FFC_OK;
}

static void gather(int nn, const long *F, long f, const double X[], const double u[],
                   double P[][3], double P0[][3], long dof[])
{
    for (int a = 0; a < nn; a++) {
        long v = F[f * nn + a];
        for (int i = 0; i < 3; i++) {
            P0[a][i] = X[3 * v + i];
            P[a][i] = X[3 * v + i] + u[3 * v + i];
            dof[3 * a + i] = 3 * v + i;
        }
    }
}

/* Evaluates link k: state, residual (and tangent when K != NULL), and the
 * global dofs of its unknowns; *nd their count. */
static int eval_link(const ffc_effects *fx, const ffc_pair *P, const double qw[], int nq,
                     const ffc_link *lk, double lambda, double eps, ffc_link_state *st,
                     double R[FFC_MAXDOF], double K[FFC_MAXDOF][FFC_MAXDOF],
                     long dof[FFC_MAXDOF], int *nd)
{
    if (lk->sf < 0 || lk->sf >= P->nfs || lk->q < 0 || lk->q >= nq || lk->mf >= P->nfm)
        return FFC_ERR_INDEX;
    double Xs[FFC_MAXNODES][3], Xs0[FFC_MAXNODES][3], Xm[FFC_MAXNODES][3], Xm0[FFC_MAXNODES][3];
    for (int a = 0; a < P->ns; a++)
        if (P->Fs[lk->sf * P->ns + a] < 0 || P->Fs[lk->sf * P->ns + a] >= P->nv) return FFC_ERR_INDEX;
    for (int a = 0; a < P->nm; a++)
        if (P->Fm[lk->mf * P->nm + a] < 0 || P->Fm[lk->mf * P->nm + a] >= P->nv) return FFC_ERR_INDEX;
    gather(P->ns, P->Fs, lk->sf, P->X, P->u, Xs, Xs0, dof);
    gather(P->nm, P->Fm, lk->mf, P->X, P->u, Xm, Xm0, dof + 3 * P->ns);
    *nd = 3 * (P->ns + P->nm);
    return ffc_link_normal(fx, P->ns, (const double(*)[3])Xs, (const double(*)[3])Xs0, lk->xs,
                           qw[lk->q], P->nm, (const double(*)[3])Xm, lambda, eps, st, R, K);
}

static void stats_init(ffc_stats *s)
{
    memset(s, 0, sizeof *s);
}

static void stats_add(ffc_stats *s, const ffc_link_state *st)
{
    s->linked++;
    if (-st->gap > s->max_pen) s->max_pen = -st->gap;
    if (!st->active) return;
    s->active++;
    if (st->tn > s->max_tn) s->max_tn = st->tn;
    for (int i = 0; i < 3; i++) s->force[i] += st->tn * st->da * st->n[i];
}

static int common_checks(const ffc_effects *fx, const ffc_pair *P, int qdeg, long nl,
                         const ffc_link links[], double eps, double qw[16], int *nq)
{
    if (!fx || !links) return FFC_ERR_NULL;
    int s = check_pair(P);
    if (s) return s;
    if (!(eps > 0) || isinf(eps)) return FFC_ERR_VALUE;
    double qxi[16][2];
    *nq = ffc_quad(qdeg, 16, qxi, qw);
    if (*nq < 0) return *nq;
    if (nl != P->nfs * *nq) return FFC_ERR_SIZE;
    return FFC_OK;
}

int ffc_assemble(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
                 long nl, const ffc_link links[], const double lambda[],
                 double eps, double R[], long cap, long Ti[], long Tj[],
                 double Tv[], long *ntrip, ffc_stats *stats, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    double qw[16];
    int nq;
    int s = common_checks(effects, pair, qdeg, nl, links, eps, qw, &nq);
    if (s) return s;
    if (!lambda || !R || !ntrip) return FFC_ERR_NULL;
    const int want_k = Ti && Tj && Tv;
    ffc_stats loc;
    if (!stats) stats = &loc;
    stats_init(stats);
    long nt = 0;
    int over = 0;
    double Rl[FFC_MAXDOF], Kl[FFC_MAXDOF][FFC_MAXDOF];
    long dof[FFC_MAXDOF];
    for (long k = 0; k < nl; k++) {
        if (links[k].mf < 0) continue;
        if (!isfinite(lambda[k])) { *bad = k; return FFC_ERR_NONFINITE; }
        ffc_link_state st;
        int nd;
        s = eval_link(effects, pair, qw, nq, &links[k], lambda[k], eps, &st, Rl,
                      want_k ? Kl : NULL, dof, &nd);
        if (s) { *bad = k; return s; }
        stats_add(stats, &st);
        if (!st.active) continue;
        for (int a = 0; a < nd; a++) R[dof[a]] += Rl[a];
        if (!want_k) continue;
        if (nt + (long)nd * nd > cap) { over = 1; nt += (long)nd * nd; continue; }
        for (int a = 0; a < nd; a++)
            for (int b = 0; b < nd; b++) {
                Ti[nt] = dof[a];
                Tj[nt] = dof[b];
                Tv[nt++] = Kl[a][b];
            }
    }
    *ntrip = nt;
    return over ? FFC_ERR_CAPACITY : FFC_OK;
}

int ffc_augment(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
                long nl, const ffc_link links[], double lambda[], double eps,
                ffc_stats *stats, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    double qw[16];
    int nq;
    int s = common_checks(effects, pair, qdeg, nl, links, eps, qw, &nq);
    if (s) return s;
    if (!lambda) return FFC_ERR_NULL;
    ffc_stats loc;
    if (!stats) stats = &loc;
    stats_init(stats);
    double Rl[FFC_MAXDOF];
    long dof[FFC_MAXDOF];
    for (long k = 0; k < nl; k++) {
        if (!isfinite(lambda[k])) { *bad = k; return FFC_ERR_NONFINITE; }
        double lnew = 0.0;
        if (links[k].mf >= 0) {
            ffc_link_state st;
            int nd;
            s = eval_link(effects, pair, qw, nq, &links[k], lambda[k], eps, &st, Rl, NULL, dof, &nd);
            if (s) { *bad = k; return s; }
            stats_add(stats, &st);
            lnew = st.tn;
        }
        double d = fabs(lnew - lambda[k]);
        if (d > stats->max_dlam) stats->max_dlam = d;
        lambda[k] = lnew;
    }
    return FFC_OK;
}

int ffc_points(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
               long nl, const ffc_link links[], const double lambda[],
               double eps, double P[], long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    double qw[16];
    int nq;
    int s = common_checks(effects, pair, qdeg, nl, links, eps, qw, &nq);
    if (s) return s;
    if (!lambda || !P) return FFC_ERR_NULL;
    double Rl[FFC_MAXDOF];
    long dof[FFC_MAXDOF];
    for (long k = 0; k < nl; k++) {
        double *row = P + k * FFC_POINT_COLS;
        const ffc_link *lk = &links[k];
        if (lk->sf < 0 || lk->sf >= pair->nfs) { *bad = k; return FFC_ERR_INDEX; }
        ffc_link_state st;
        memset(&st, 0, sizeof st);
        if (lk->mf >= 0) {
            int nd;
            s = eval_link(effects, pair, qw, nq, lk, lambda[k], eps, &st, Rl, NULL, dof, &nd);
            if (s) { *bad = k; return s; }
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
    }
    return FFC_OK;
}
