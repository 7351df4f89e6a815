/* ffc_link.c: augmented-Lagrangian normal contact: residual and consistent
 * tangent of one link, assembly over all links, Uzawa update and per-point
 * output. */
#include "ffc.h"
#include "ffc_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Geometry of one link: slave point, foot, gap g, point area da and
 *   G[nd]      = dg/du = [N1_a n ; -N2_b(xi) n]
 *   dda[nd]    = d da / du (slave dofs; zero with small strain)
 *   D[nd][nd]  = dG/du (when D != NULL):
 *     slave rows  a,c:  N1_a dn_c/du
 *     master rows b,c: -N2_b dn_c/du - n_c N2_b,alpha dxi_alpha/du
 * with dn/du and dxi/du from ffc_project_deriv (the variation of the
 * master normal and the sliding of the foot), and
 *     d da / d x_a = w J N1_a,alpha tau^alpha
 * when the area element follows the deformation (finite_def). */
static int link_geometry(const ffc_effects *fx, int ns, const double Xs[][3], const double Xs0[][3],
                         const double xs[2], double w, int nm, const double Xm[][3],
                         ffc_link_state *st, double G[FFC_MAXDOF], double dda[FFC_MAXDOF],
                         double D[FFC_MAXDOF][FFC_MAXDOF])
{
    const int nd = 3 * (ns + nm);
    double N1[FFC_MAXNODES], dN1[FFC_MAXNODES][2];
    int s = ffc_shape(ns, xs, N1, dN1);
    if (s) return s;
    double p[3] = {0, 0, 0};
    for (int a = 0; a < ns; a++)
        for (int i = 0; i < 3; i++) p[i] += N1[a] * Xs[a][i];
    ffc_point sp;
    s = ffc_facet_point(ns, fx->finite_def ? Xs : Xs0, xs, &sp);
    if (s) return s;
    ffc_proj pr;
    s = ffc__project_free(nm, Xm, p, &pr);
    if (s) return s;
    for (int i = 0; i < 3; i++) { st->x[i] = p[i]; st->n[i] = pr.n[i]; }
    st->xi[0] = pr.xi[0];
    st->xi[1] = pr.xi[1];
    st->gap = pr.gap;
    st->da = w * sp.j;
    double dxi[2][FFC_MAXDOF], dn[3][FFC_MAXDOF];
    s = ffc_project_deriv(ns, N1, nm, Xm, &pr, dxi, G, dn);
    if (s) return s;
    for (int k = 0; k < nd; k++) dda[k] = 0.0;
    if (fx->finite_def) {
        double tc[2][3];
        for (int i = 0; i < 3; i++) {
            tc[0][i] = sp.minv[0][0] * sp.tau[0][i] + sp.minv[0][1] * sp.tau[1][i];
            tc[1][i] = sp.minv[1][0] * sp.tau[0][i] + sp.minv[1][1] * sp.tau[1][i];
        }
        for (int a = 0; a < ns; a++)
            for (int i = 0; i < 3; i++)
                dda[3 * a + i] = w * sp.j * (dN1[a][0] * tc[0][i] + dN1[a][1] * tc[1][i]);
    }
    if (!D) return FFC_OK;
    double N2[FFC_MAXNODES], dN2[FFC_MAXNODES][2];
    ffc_shape(nm, pr.xi, N2, dN2);
    for (int k = 0; k < nd; k++) {
        const int slave = k < 3 * ns, c = k % 3;
        const int node = slave ? k / 3 : (k - 3 * ns) / 3;
        for (int l = 0; l < nd; l++)
            D[k][l] = slave ? N1[node] * dn[c][l]
                            : -N2[node] * dn[c][l] -
                                  pr.n[c] * (dN2[node][0] * dxi[0][l] + dN2[node][1] * dxi[1][l]);
    }
    return FFC_OK;
}

/* Formulation (frictionless, pointwise; gap g = n . (x_s - x_m) >= 0 open).
 * A link is a slave point x_s = sum_a N1_a(xs) x_a with area da = w J_s,
 * and its foot xi on the master facet: tau_a(xi) . (x_s - x_m(xi)) = 0.
 * Pressure t_N = <lambda - eps g>.  The virtual work of the contact
 * traction, da t_N dg, gives the internal-force residual
 *     R = -da t_N G
 * (the traction t_N n pushes the slave out along the master normal).
 * Its derivative, with dt_N = -eps H(t_N) G . du:
 *     K = da eps G G^T  -  da t_N D  -  t_N G dda^T
 * with G, D, dda from link_geometry. */
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
    double G[FFC_MAXDOF], dda[FFC_MAXDOF];
    int s = link_geometry(effects, ns, Xs, Xs0, xs, w, nm, Xm, st, G, dda, K);
    if (s) return s;
    const double trial = lambda - eps * st->gap;
    st->active = trial > 0.0;
    st->tn = st->active ? trial : 0.0;
    if (!st->active) {
        if (K)
            for (int k = 0; k < nd; k++) memset(K[k], 0, (size_t)nd * sizeof K[k][0]);
        return FFC_OK;
    }
    const double da = st->da, tn = st->tn;
    for (int k = 0; k < nd; k++) R[k] = -da * tn * G[k];
    if (!K) return FFC_OK;
    /* K holds D on entry */
    for (int k = 0; k < nd; k++)
        for (int l = 0; l < nd; l++)
            K[k][l] = da * (eps * G[k] * G[l] - tn * K[k][l]) - tn * G[k] * dda[l];
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

/* The checks every call over all links shares: pair, law, quadrature rule
 * (its weights into qw, point count *nq), link count, slave node indices,
 * and finite multipliers (lambda[nv] nodal, lambda[nl] per link; *bad =
 * the index of a non-finite one). */
static int common_checks(const ffc_effects *fx, const ffc_pair *P, int qdeg, long nl,
                         const ffc_link links[], const ffc_law *law, const double lambda[],
                         double qw[16], int *nq, long *bad)
{
    if (!fx || !links || !law || !lambda) return FFC_ERR_NULL;
    int s = check_pair(P);
    if (s) return s;
    if (!(law->eps_n > 0) || isinf(law->eps_n) || (law->nodal != 0 && law->nodal != 1) ||
        (law->material_only != 0 && law->material_only != 1))
        return FFC_ERR_VALUE;
    double qxi[16][2];
    *nq = ffc_quad(qdeg, 16, qxi, qw);
    if (*nq < 0) return *nq;
    if (nl != P->nfs * *nq) return FFC_ERR_SIZE;
    for (long k = 0; k < P->nfs * P->ns; k++)
        if (P->Fs[k] < 0 || P->Fs[k] >= P->nv) return FFC_ERR_INDEX;
    const long n = law->nodal ? P->nv : nl;
    for (long k = 0; k < n; k++)
        if (!isfinite(lambda[k])) { *bad = k; return FFC_ERR_NONFINITE; }
    return FFC_OK;
}

/* ----------------------------------------------- nodal (mortar-type) law */
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
 * with H(t_a) = 1 when lambda_a - eps g~_a >= 0 (touching counts).
 *     B_a = sum_q N_a(q) da_q G_q,
 *     C_a = sum_q N_a(q) (da_q G_q + (g_q - g~_a) dda_q)   (= dG_a - g~_a dW_a).
 * The Uzawa update lambda_a <- t_a has the fixed point g~_a = 0 where
 * t_a > 0 and g~_a >= 0, lambda_a = 0 elsewhere: one constraint per slave
 * node, the weighted-gap conditions of mortar methods. */
typedef struct {
    long k;                 /* link index */
    int nd;                 /* unknowns */
    double g, da;           /* gap, point area */
    double n[3];            /* master normal at the foot */
    double N[FFC_MAXNODES]; /* slave shape values at the point */
    long dof[FFC_MAXDOF];
    double G[FFC_MAXDOF], dda[FFC_MAXDOF];
} nlink_t;

typedef struct {
    long n;          /* linked links */
    nlink_t *L;      /* [n] */
    double *Gn, *Wn; /* [nv] weighted gap sums and weights per node */
    double *tn;      /* [nv] nodal pressures */
    unsigned char *on; /* [nv] 1 when lambda_a - eps g~_a >= 0: the node touches
                          and its stiffness enters the tangent (a node at
                          exactly zero gap and zero multiplier included, so
                          that a body held only by contact is not singular
                          at the first iteration) */
} nodal_t;

static void nodal_free(nodal_t *w)
{
    free(w->L);
    free(w->Gn);
    free(w->Wn);
    free(w->tn);
    free(w->on);
}

/* pass 1: geometry of every linked point, nodal sums and pressures */
static int nodal_prepare(const ffc_effects *fx, const ffc_pair *P, const double qw[], int nq, long nl,
                         const ffc_link links[], const double lambda[], double eps, nodal_t *w,
                         ffc_stats *stats, long *bad)
{
    memset(w, 0, sizeof *w);
    long n = 0;
    for (long k = 0; k < nl; k++) n += links[k].mf >= 0;
    w->L = malloc((size_t)(n > 0 ? n : 1) * sizeof *w->L);
    w->Gn = calloc((size_t)P->nv, sizeof *w->Gn);
    w->Wn = calloc((size_t)P->nv, sizeof *w->Wn);
    w->tn = calloc((size_t)P->nv, sizeof *w->tn);
    w->on = calloc((size_t)P->nv, 1);
    if (!w->L || !w->Gn || !w->Wn || !w->tn || !w->on) { nodal_free(w); return FFC_ERR_MEMORY; }
    for (long k = 0; k < nl; k++) {
        const ffc_link *lk = &links[k];
        if (lk->mf < 0) continue;
        if (lk->sf < 0 || lk->sf >= P->nfs || lk->q < 0 || lk->q >= nq || lk->mf >= P->nfm) {
            *bad = k;
            nodal_free(w);
            return FFC_ERR_INDEX;
        }
        nlink_t *e = &w->L[w->n];
        double Xs[FFC_MAXNODES][3], Xs0[FFC_MAXNODES][3], Xm[FFC_MAXNODES][3], Xm0[FFC_MAXNODES][3];
        for (int a = 0; a < P->nm; a++)
            if (P->Fm[lk->mf * P->nm + a] < 0 || P->Fm[lk->mf * P->nm + a] >= P->nv) {
                *bad = k;
                nodal_free(w);
                return FFC_ERR_INDEX;
            }
        gather(P->ns, P->Fs, lk->sf, P->X, P->u, Xs, Xs0, e->dof);
        gather(P->nm, P->Fm, lk->mf, P->X, P->u, Xm, Xm0, e->dof + 3 * P->ns);
        e->k = k;
        e->nd = 3 * (P->ns + P->nm);
        ffc_link_state st;
        int s = link_geometry(fx, P->ns, (const double(*)[3])Xs, (const double(*)[3])Xs0, lk->xs, qw[lk->q],
                              P->nm, (const double(*)[3])Xm, &st, e->G, e->dda, NULL);
        if (s) { *bad = k; nodal_free(w); return s; }
        e->g = st.gap;
        e->da = st.da;
        for (int i = 0; i < 3; i++) e->n[i] = st.n[i];
        /* multipliers are linear on the facet's vertices (for 6-node facets
         * too: quadratic vertex shape functions integrate to zero, which
         * would leave vertex nodes without weight) */
        ffc_shape(3, lk->xs, e->N, NULL);
        for (int a = 3; a < P->ns; a++) e->N[a] = 0.0;
        for (int a = 0; a < P->ns; a++) {
            long v = P->Fs[lk->sf * P->ns + a];
            w->Gn[v] += e->N[a] * e->da * e->g;
            w->Wn[v] += e->N[a] * e->da;
        }
        if (stats) {
            stats->linked++;
            if (-e->g > stats->max_pen) stats->max_pen = -e->g;
        }
        w->n++;
    }
    for (long v = 0; v < P->nv; v++)
        if (w->Wn[v] > 0.0) {
            double g = w->Gn[v] / w->Wn[v];
            const double trial = lambda[v] - eps * g;
            w->tn[v] = fmax(0.0, trial);
            w->on[v] = trial >= 0.0;
            if (stats && w->tn[v] > 0.0 && -g > stats->max_pen_node) stats->max_pen_node = -g;
        }
    return FFC_OK;
}

/* pressure at a linked point: the interpolated nodal pressure */
static double nodal_point_pressure(const ffc_pair *P, const ffc_link *lk, const nlink_t *e, const double tn[])
{
    double t = 0.0;
    for (int a = 0; a < P->ns; a++) t += e->N[a] * tn[P->Fs[lk->sf * P->ns + a]];
    return t;
}

static int emit(long *nt, long cap, long Ti[], long Tj[], double Tv[], long i, long j, double v)
{
    if (*nt < cap) { Ti[*nt] = i; Tj[*nt] = j; Tv[*nt] = v; }
    (*nt)++;
    return *nt <= cap;
}

static int assemble_nodal(const ffc_effects *fx, const ffc_pair *P, const double qw[], int nq, long nl,
                          const ffc_link links[], const double lambda[], double eps, int material_only,
                          double R[], long cap, long Ti[], long Tj[], double Tv[], long *ntrip,
                          ffc_stats *stats, long *bad)
{
    nodal_t w;
    int s = nodal_prepare(fx, P, qw, nq, nl, links, lambda, eps, &w, stats, bad);
    if (s) return s;
    const int want_k = Ti && Tj && Tv;
    long nt = 0;
    int ok = 1;
    double D[FFC_MAXDOF][FFC_MAXDOF], G2[FFC_MAXDOF], dda2[FFC_MAXDOF];
    /* residual, statistics and geometric stiffness, link by link */
    for (long e = 0; e < w.n; e++) {
        const nlink_t *E = &w.L[e];
        const ffc_link *lk = &links[E->k];
        const double t = nodal_point_pressure(P, lk, E, w.tn);
        if (!(t > 0.0)) continue;
        stats->active++;
        if (t > stats->max_tn) stats->max_tn = t;
        for (int a = 0; a < E->nd; a++) R[E->dof[a]] -= t * E->da * E->G[a];
        for (int i = 0; i < 3; i++) stats->force[i] += t * E->da * E->n[i];
        if (!want_k || material_only) continue;
        double Xs[FFC_MAXNODES][3], Xs0[FFC_MAXNODES][3], Xm[FFC_MAXNODES][3], Xm0[FFC_MAXNODES][3];
        long dof[FFC_MAXDOF];
        gather(P->ns, P->Fs, lk->sf, P->X, P->u, Xs, Xs0, dof);
        gather(P->nm, P->Fm, lk->mf, P->X, P->u, Xm, Xm0, dof + 3 * P->ns);
        ffc_link_state st;
        s = link_geometry(fx, P->ns, (const double(*)[3])Xs, (const double(*)[3])Xs0, lk->xs, qw[lk->q], P->nm,
                          (const double(*)[3])Xm, &st, G2, dda2, D);
        if (s) { *bad = E->k; nodal_free(&w); return s; }
        for (int a = 0; a < E->nd; a++)
            for (int b = 0; b < E->nd; b++)
                ok &= emit(&nt, cap, Ti, Tj, Tv, E->dof[a], E->dof[b],
                           -t * (E->da * D[a][b] + E->G[a] * E->dda[b]));
    }
    if (want_k) {
        /* material stiffness, node by node: links of each slave node */
        const long nv = P->nv;
        long *start = calloc((size_t)nv + 1, sizeof *start), *lst = NULL, *pos = NULL;
        double *Bv = NULL, *Cv = NULL;
        long *loc = NULL;
        if (!start) { nodal_free(&w); return FFC_ERR_MEMORY; }
        for (long e = 0; e < w.n; e++)
            for (int a = 0; a < P->ns; a++) start[P->Fs[links[w.L[e].k].sf * P->ns + a] + 1]++;
        for (long v = 0; v < nv; v++) start[v + 1] += start[v];
        lst = malloc((size_t)(start[nv] > 0 ? start[nv] : 1) * sizeof *lst);
        pos = malloc((size_t)3 * nv * sizeof *pos);
        long maxloc = 0;
        if (lst && pos) {
            long *fill = calloc((size_t)nv, sizeof *fill);
            if (fill) {
                for (long e = 0; e < w.n; e++)
                    for (int a = 0; a < P->ns; a++) {
                        long v = P->Fs[links[w.L[e].k].sf * P->ns + a];
                        lst[start[v] + fill[v]++] = e;
                    }
                free(fill);
            } else {
                free(lst);
                lst = NULL;
            }
            for (long v = 0; v < nv; v++)
                if (FFC_MAXDOF * (start[v + 1] - start[v]) > maxloc) maxloc = FFC_MAXDOF * (start[v + 1] - start[v]);
            Bv = malloc((size_t)(maxloc > 0 ? maxloc : 1) * sizeof *Bv);
            Cv = malloc((size_t)(maxloc > 0 ? maxloc : 1) * sizeof *Cv);
            loc = malloc((size_t)(maxloc > 0 ? maxloc : 1) * sizeof *loc);
        }
        if (!lst || !pos || !Bv || !Cv || !loc) {
            free(start); free(lst); free(pos); free(Bv); free(Cv); free(loc);
            nodal_free(&w);
            return FFC_ERR_MEMORY;
        }
        for (long i = 0; i < 3 * nv; i++) pos[i] = -1;
        for (long v = 0; v < nv; v++) {
            if (!w.on[v] || !(w.Wn[v] > 0.0)) continue;
            const double gt = w.Gn[v] / w.Wn[v], c = eps / w.Wn[v];
            long nloc = 0;
            for (long m = start[v]; m < start[v + 1]; m++) {
                const nlink_t *E = &w.L[lst[m]];
                const ffc_link *lk = &links[E->k];
                double Na = 0.0;
                for (int a = 0; a < P->ns; a++)
                    if (P->Fs[lk->sf * P->ns + a] == v) Na += E->N[a];
                for (int a = 0; a < E->nd; a++) {
                    long d = E->dof[a];
                    if (pos[d] < 0) { pos[d] = nloc; loc[nloc] = d; Bv[nloc] = Cv[nloc] = 0.0; nloc++; }
                    Bv[pos[d]] += Na * E->da * E->G[a];
                    Cv[pos[d]] += Na * (E->da * E->G[a] + (E->g - gt) * E->dda[a]);
                }
            }
            for (long i = 0; i < nloc; i++)
                for (long j = 0; j < nloc; j++)
                    if (Bv[i] != 0.0 && Cv[j] != 0.0) ok &= emit(&nt, cap, Ti, Tj, Tv, loc[i], loc[j], c * Bv[i] * Cv[j]);
            for (long i = 0; i < nloc; i++) pos[loc[i]] = -1;
        }
        free(start); free(lst); free(pos); free(Bv); free(Cv); free(loc);
    }
    *ntrip = nt;
    nodal_free(&w);
    return ok ? FFC_OK : FFC_ERR_CAPACITY;
}

int ffc_assemble(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
                 long nl, const ffc_link links[], const double lambda[],
                 const ffc_law *law, double R[], long cap, long Ti[], long Tj[],
                 double Tv[], long *ntrip, ffc_stats *stats, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    double qw[16];
    int nq;
    int s = common_checks(effects, pair, qdeg, nl, links, law, lambda, qw, &nq, bad);
    if (s) return s;
    if (!R || !ntrip) return FFC_ERR_NULL;
    const double eps = law->eps_n;
    const int want_k = Ti && Tj && Tv;
    ffc_stats loc;
    if (!stats) stats = &loc;
    stats_init(stats);
    if (law->nodal)
        return assemble_nodal(effects, pair, qw, nq, nl, links, lambda, eps, law->material_only, R, cap, Ti,
                              Tj, Tv, ntrip, stats, bad);
    long nt = 0;
    int over = 0;
    double Rl[FFC_MAXDOF], Kl[FFC_MAXDOF][FFC_MAXDOF];
    long dof[FFC_MAXDOF];
    for (long k = 0; k < nl; k++) {
        if (links[k].mf < 0) continue;
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
        if (law->material_only) { /* K = da eps G G^T, G = -R / (da t_N) */
            const double c = eps / (st.da * st.tn * st.tn);
            for (int a = 0; a < nd; a++)
                for (int b = 0; b < nd; b++) Kl[a][b] = c * Rl[a] * Rl[b];
        }
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
                long nl, const ffc_link links[], double lambda[],
                const ffc_law *law, ffc_stats *stats, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    double qw[16];
    int nq;
    int s = common_checks(effects, pair, qdeg, nl, links, law, lambda, qw, &nq, bad);
    if (s) return s;
    const double eps = law->eps_n;
    ffc_stats loc;
    if (!stats) stats = &loc;
    stats_init(stats);
    if (law->nodal) {
        nodal_t w;
        s = nodal_prepare(effects, pair, qw, nq, nl, links, lambda, eps, &w, stats, bad);
        if (s) return s;
        for (long e = 0; e < w.n; e++) {
            const double t = nodal_point_pressure(pair, &links[w.L[e].k], &w.L[e], w.tn);
            if (!(t > 0.0)) continue;
            stats->active++;
            if (t > stats->max_tn) stats->max_tn = t;
            for (int i = 0; i < 3; i++) stats->force[i] += t * w.L[e].da * w.L[e].n[i];
        }
        for (long v = 0; v < pair->nv; v++) {
            double d = fabs(w.tn[v] - lambda[v]);
            if (d > stats->max_dlam) stats->max_dlam = d;
            lambda[v] = w.tn[v];
        }
        nodal_free(&w);
        return FFC_OK;
    }
    double Rl[FFC_MAXDOF];
    long dof[FFC_MAXDOF];
    for (long k = 0; k < nl; k++) {
        const ffc_link *lk = &links[k];
        double lnew = 0.0;
        if (lk->mf >= 0) {
            ffc_link_state st;
            int nd;
            s = eval_link(effects, pair, qw, nq, lk, lambda[k], eps, &st, Rl, NULL, dof, &nd);
            if (s) { *bad = k; return s; }
            stats_add(stats, &st);
            lnew = st.tn;
        }
        double d = fabs(lnew - lambda[k]);
        if (d > stats->max_dlam) stats->max_dlam = d;
        lambda[k] = lnew;
    }
    stats->max_pen_node = stats->max_pen;
    return FFC_OK;
}

int ffc_points(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
               long nl, const ffc_link links[], const double lambda[],
               const ffc_law *law, double P[], long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    double qw[16];
    int nq;
    int s = common_checks(effects, pair, qdeg, nl, links, law, lambda, qw, &nq, bad);
    if (s) return s;
    if (!P) return FFC_ERR_NULL;
    const double eps = law->eps_n;
    double Rl[FFC_MAXDOF];
    long dof[FFC_MAXDOF];
    nodal_t w;
    memset(&w, 0, sizeof w);
    if (law->nodal && (s = nodal_prepare(effects, pair, qw, nq, nl, links, lambda, eps, &w, NULL, bad)))
        return s;
    long e = 0;
    for (long k = 0; k < nl; k++) {
        double *row = P + k * FFC_POINT_COLS;
        const ffc_link *lk = &links[k];
        if (lk->sf < 0 || lk->sf >= pair->nfs) { *bad = k; nodal_free(&w); return FFC_ERR_INDEX; }
        ffc_link_state st;
        memset(&st, 0, sizeof st);
        if (lk->mf >= 0) {
            int nd;
            s = eval_link(effects, pair, qw, nq, lk, law->nodal ? 0.0 : lambda[k], eps, &st, Rl, NULL, dof, &nd);
            if (s) { *bad = k; nodal_free(&w); return s; }
            if (law->nodal) { /* the interpolated nodal pressure */
                st.tn = nodal_point_pressure(pair, lk, &w.L[e++], w.tn);
                st.active = st.tn > 0.0;
            }
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
    nodal_free(&w);
    return FFC_OK;
}
