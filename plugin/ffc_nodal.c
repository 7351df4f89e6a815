/* ffc_nodal.c: the nodal (mortar-type) multiplier law: weighted nodal gaps,
 * pressures and return maps, and the assembly of its residual and tangent. */
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
static void multiplier_shape(const ffc_law *law, int ns, long f, const double xs[2], double N[FFC_MAXNODES])
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
                               &ls, &g, NULL);
        if (s) { *bad = k; st = s; break; }
        memcpy(e->G, g.G, sizeof e->G);
        memcpy(e->dda, g.dda, sizeof e->dda);
        e->g = ls.gap;
        e->da = ls.da;
        for (int i = 0; i < 3; i++) e->n[i] = ls.n[i];
        multiplier_shape(law, P->ns, lk->sf, lk->xs, e->N);
        for (int a = 0; a < P->ns; a++) e->Nt[a] = tdual ? 4.0 * e->N[a] - 1.0 : e->N[a];
        if (lam_t) {
            nfl_t *fl = &w->F[w->n];
            ffc__link_slip(&g, CP3(ln.Ds), CP3(ln.Dm), fl->r);
            ffc__link_slip_deriv(&g, CP3(ln.Dm), ffc__motion_coef(fx, law), law->material_only, fl->sw, fl->Q);
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

/* traction at a linked point: the interpolated nodal tractions; *state the
 * "largest" state of its nodes (slip > stick > open) */
void ffc__nodal_point_traction(const ffc_pair *P, const ffc_link *lk, const nlink_t *e, const nfn_t T[],
                               double t[3], int *state)
{
    t[0] = t[1] = t[2] = 0.0;
    *state = FFC_FRIC_OPEN;
    for (int a = 0; a < P->ns; a++) {
        if (e->Nt[a] == 0.0) continue;
        const nfn_t *Ta = &T[P->Fs[lk->sf * P->ns + a]];
        for (int i = 0; i < 3; i++) t[i] += e->Nt[a] * Ta->f.t[i];
        if (Ta->f.state > *state) *state = Ta->f.state;
    }
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

static int emit(long *nt, long cap, long Ti[], long Tj[], double Tv[], long i, long j, double v)
{
    if (*nt < cap) { Ti[*nt] = i; Tj[*nt] = j; Tv[*nt] = v; }
    (*nt)++;
    return *nt <= cap;
}

/* one ranked term (FFC_TANGENT_RANKED) of a node's dofs loc[nloc]: its
 * U column c x[i s] as triplets (loc[i], 2 term, .), its V column
 * y[j s] as (loc[j], 2 term + 1, .) (s: the stride of x and y) */
static int emit_term(long *nt, long cap, long Ti[], long Tj[], double Tv[], long nloc, const long loc[], double c,
                     const double x[], const double y[], int s, long term)
{
    int ok = 1;
    for (long i = 0; i < nloc; i++)
        if (x[i * s] != 0.0) ok &= emit(nt, cap, Ti, Tj, Tv, loc[i], 2 * term, c * x[i * s]);
    for (long j = 0; j < nloc; j++)
        if (y[j * s] != 0.0) ok &= emit(nt, cap, Ti, Tj, Tv, loc[j], 2 * term + 1, y[j * s]);
    return ok;
}

/* per-node work arrays of the material stiffness */
typedef struct {
    long *start, *lst, *pos, *loc;
    double *Bv, *Cv;            /* [maxloc] */
    double *Bf, *Rt, *Nt;       /* [3 maxloc] friction: Bf_a, dr~_a, dn~_a */
} nodework_t;

static void nodework_free(nodework_t *k)
{
    free(k->start); free(k->lst); free(k->pos); free(k->loc);
    free(k->Bv); free(k->Cv); free(k->Bf); free(k->Rt); free(k->Nt);
}

static int nodework_alloc(const ffc_pair *P, const ffc_link links[], const nodal_t *w, nodework_t *k)
{
    memset(k, 0, sizeof *k);
    const long nv = P->nv;
    k->start = calloc((size_t)nv + 1, sizeof *k->start);
    if (!k->start) return FFC_ERR_MEMORY;
    for (long e = 0; e < w->n; e++)
        for (int a = 0; a < P->ns; a++) k->start[P->Fs[links[w->L[e].k].sf * P->ns + a] + 1]++;
    for (long v = 0; v < nv; v++) k->start[v + 1] += k->start[v];
    k->lst = malloc((size_t)(k->start[nv] > 0 ? k->start[nv] : 1) * sizeof *k->lst);
    k->pos = malloc((size_t)3 * nv * sizeof *k->pos);
    long *fill = calloc((size_t)nv, sizeof *fill);
    long maxloc = 1;
    for (long v = 0; v < nv; v++)
        if (FFC_MAXDOF * (k->start[v + 1] - k->start[v]) > maxloc) maxloc = FFC_MAXDOF * (k->start[v + 1] - k->start[v]);
    k->loc = malloc((size_t)maxloc * sizeof *k->loc);
    k->Bv = malloc((size_t)maxloc * sizeof *k->Bv);
    k->Cv = malloc((size_t)maxloc * sizeof *k->Cv);
    if (w->T) {
        k->Bf = malloc((size_t)3 * maxloc * sizeof *k->Bf);
        k->Rt = malloc((size_t)3 * maxloc * sizeof *k->Rt);
        k->Nt = malloc((size_t)3 * maxloc * sizeof *k->Nt);
    }
    if (!k->lst || !k->pos || !fill || !k->loc || !k->Bv || !k->Cv || (w->T && (!k->Bf || !k->Rt || !k->Nt))) {
        free(fill);
        nodework_free(k);
        return FFC_ERR_MEMORY;
    }
    for (long e = 0; e < w->n; e++)
        for (int a = 0; a < P->ns; a++) {
            long v = P->Fs[links[w->L[e].k].sf * P->ns + a];
            k->lst[k->start[v] + fill[v]++] = e;
        }
    free(fill);
    for (long i = 0; i < 3 * nv; i++) k->pos[i] = -1;
    return FFC_OK;
}

/* A moving-edge point of a segment, evaluated (see segment_motion) */
typedef struct {
    double g, da, N[3], r[3], n[3]; /* gap, area element, multiplier shape values, slip, normal */
    long dof[FFC_MAXDOF];
    int nd;
} nedge_t;

/* Formulation (segments that follow the surfaces).  Every integral of the
 * law over the slave surface is a sum over segments S(u), and moving a
 * segment's edge adds oint F (v . nu) ds (ffc_mortar_segment): law->edge
 * holds the points b of the moving edges with dv_b = omega L d(v . nu)/du.
 * So the tangent gains, with F evaluated at b (weight 1):
 *   the residual's own integral:  K += F_R(b) dv_b^T,
 *       F_R = -t_b da G (+ da S^T T_b with friction);
 *   the nodal sums, through the nodal pressure and traction:
 *       C_a += Phi_a(b) da (g_b - g~_a) dv_b            (dG_a - g~_a dW_a),
 *       dr~_a += Phi_a(b) da (r_b - r~_a) dv_b / W_a,   dm_a += Phi_a(b) da n_b dv_b.
 * The dual basis of a partly covered facet also moves with its segments;
 * that term is not included (full coverage: A is fixed).  Geometric terms:
 * none with law->material_only.  Each point is evaluated into E[b];
 * returns the status. */
static int segment_motion(const ffc_effects *fx, const ffc_pair *P, const ffc_law *law, const nodal_t *w, int fric,
                          nedge_t E[], long cap, long Ti[], long Tj[], double Tv[], long *nt, int *ok, long *bad)
{
    for (long b = 0; b < law->nedge; b++) {
        const ffc_mortar_edge *ed = &law->edge[b];
        ffc_link tmp;
        memset(&tmp, 0, sizeof tmp);
        tmp.sf = ed->sf;
        tmp.mf = ed->mf;
        tmp.q = -1;
        tmp.w = 1.0;
        tmp.xs[0] = ed->xs[0];
        tmp.xs[1] = ed->xs[1];
        lnodes_t ln;
        int s = ffc__gather_link(fx, P, 0, &tmp, &ln);
        ffc_link_state st;
        lgeo_t g;
        if (!s) s = ffc__link_geometry(fx, P->ns, CP3(ln.Xs), CP3(ln.Xs0), tmp.xs, 1.0, P->nm, CP3(ln.Xm), NULL, &st, &g, NULL);
        if (s) { *bad = b; return s; }
        nedge_t *e = &E[b];
        e->g = st.gap;
        e->da = st.da;
        e->nd = ln.nd;
        memcpy(e->dof, ln.dof, sizeof ln.dof);
        for (int i = 0; i < 3; i++) e->n[i] = st.n[i];
        nlink_t nl;
        memset(&nl, 0, sizeof nl);
        multiplier_shape(law, P->ns, tmp.sf, tmp.xs, nl.N);
        memcpy(nl.Nt, nl.N, sizeof nl.Nt); /* (segments: no tdual, see tdual_on) */
        for (int a = 0; a < 3; a++) e->N[a] = nl.N[a];
        const double t = ffc__nodal_point_pressure(P, &tmp, &nl, w->tn);
        double F[FFC_MAXDOF], Tq[3] = {0, 0, 0};
        for (int k = 0; k < ln.nd; k++) F[k] = -t * st.da * g.G[k];
        e->r[0] = e->r[1] = e->r[2] = 0.0;
        if (fric) {
            int fs;
            double sw[FFC_MAXDOF], Q[3][FFC_MAXDOF];
            ffc__link_slip(&g, CP3(ln.Ds), CP3(ln.Dm), e->r);
            ffc__link_slip_deriv(&g, CP3(ln.Dm), ffc__motion_coef(fx, law), law->material_only, sw, Q);
            ffc__nodal_point_traction(P, &tmp, &nl, w->T, Tq, &fs);
            for (int k = 0; k < ln.nd; k++) F[k] += st.da * sw[k] * Tq[k % 3];
        }
        for (int k = 0; k < ln.nd; k++) {
            if (F[k] == 0.0) continue;
            for (int l = 0; l < ln.nd; l++)
                if (ed->dv[l] != 0.0) *ok &= emit(nt, cap, Ti, Tj, Tv, ln.dof[k], ln.dof[l], F[k] * ed->dv[l]);
        }
    }
    return FFC_OK;
}

/* The motion of a partly covered facet's dual basis (dual_motion) */
typedef struct {
    long f;             /* slave facet */
    long e0, e1;        /* its linked points: w->L[e0 .. e1) */
    int nd;             /* dofs of dA */
    long dof[9 + 9 * 64]; /* the facet's nodes, then its master facets' nodes (x, y, z each) */
    double dA[9][9 + 9 * 64]; /* d A_ab / d dof */
} ndual_t;

/* Formulation (the dual basis of a partly covered facet).  With the
 * covered part's c = sum_q w_q, D_a = sum_q w_q N_a, M_ab = sum_q w_q N_a N_b
 * (integrands fixed in xi: they change through the segments' edges only,
 * dI = sum_b F(b) dv_b) and s = min(1, (2 c - 1/2) / 0.4),
 *     A = s D M^-1 + (1 - s) I,
 *     dA = ds (D M^-1 - I) + s (dD M^-1 - D M^-1 dM M^-1),  ds = 5 dc (s < 1).
 * Phi_a(q) = sum_b A_ab N_b(q) then moves by sum_b dA_ab N_b(q): in the
 * residual (t_q = sum_a Phi_a t_a, T_q = sum_a Phi_a T_a),
 *     K += sum_ab Y_ab dA_ab^T,  Y_ab = sum_q da N_b(q) (-t_a G_q + S_q^T T_a),
 * and in each nodal sum (nodal_dual_terms).  Fully covered facets have a
 * fixed A (dA = 0 up to round-off) and are skipped; so are facets whose
 * basis is standard (s = 0 or M nearly singular).  Returns the count of
 * facets written into F (at most cap), or an error. */
static long dual_motion(const ffc_pair *P, const ffc_link links[], const ffc_law *law, const nodal_t *w, int fric,
                        ndual_t F[], long cap, long Ti[], long Tj[], double Tv[], long tcap, long *nt, int *ok)
{
    long nf = 0;
    for (long e0 = 0; e0 < w->n;) {
        const long f = links[w->L[e0].k].sf;
        long e1 = e0;
        while (e1 < w->n && links[w->L[e1].k].sf == f) e1++;
        ffc__dual_moments mo;
        memset(&mo, 0, sizeof mo);
        for (long e = e0; e < e1; e++) ffc__dual_add(&mo, links[w->L[e].k].xs, links[w->L[e].k].w);
        const long first = e0;
        e0 = e1;
        double Mi[3][3];
        const double s = mo.c >= 0.5 * (1.0 - 1e-12) ? 0.0 : ffc__dual_blend(&mo, Mi);
        if (!(s > 0.0)) continue; /* fully covered (A fixed) or standard */
        if (nf >= cap) return FFC_ERR_CAPACITY;
        ndual_t *d = &F[nf];
        d->f = f;
        d->e0 = first;
        d->e1 = e1;
        d->nd = 9;
        for (int a = 0; a < 3; a++)
            for (int i = 0; i < 3; i++) d->dof[3 * a + i] = 3 * P->Fs[P->ns * f + a] + i;
        double Pm[3][3];
        for (int a = 0; a < 3; a++)
            for (int b = 0; b < 3; b++) Pm[a][b] = mo.D[a] * Mi[a][b];
        for (int ab = 0; ab < 9; ab++)
            for (int l = 0; l < 9 + 9 * 64; l++) d->dA[ab][l] = 0.0;
        int over = 0;
        for (long b = 0; b < law->nedge && !over; b++) {
            const ffc_mortar_edge *ed = &law->edge[b];
            if (ed->sf != f) continue;
            /* the edge point's dofs (a link's: the slave facet's ns nodes, then its master facet's nm)
               in d: the slave facet's vertices first, then its master facets' nodes */
            int pos[FFC_MAXDOF];
            for (int l = 0; l < 3 * (P->ns + P->nm) && !over; l++) {
                pos[l] = -1;
                if (ed->dv[l] == 0.0) continue;
                const long dof = l < 3 * P->ns ? 3 * P->Fs[P->ns * f + l / 3] + l % 3
                                               : 3 * P->Fm[P->nm * ed->mf + (l - 3 * P->ns) / 3] + l % 3;
                int p = -1;
                for (int k = 0; k < d->nd && p < 0; k++)
                    if (d->dof[k] == dof) p = k;
                if (p < 0) {
                    if (d->nd >= 9 + 9 * 64) { over = 1; break; }
                    p = d->nd++;
                    d->dof[p] = dof;
                }
                pos[l] = p;
            }
            if (over) break;
            const double L[3] = {1.0 - ed->xs[0] - ed->xs[1], ed->xs[0], ed->xs[1]};
            /* dc, dD, dM of this point, then into dA */
            double dM[3][3], dD[3];
            for (int a = 0; a < 3; a++) {
                dD[a] = L[a];
                for (int bb = 0; bb < 3; bb++) dM[a][bb] = L[a] * L[bb];
            }
            double G[3][3]; /* dA per unit dv: ds (P - I) + s (dD Mi - P dM Mi) */
            double PdM[3][3];
            for (int a = 0; a < 3; a++)
                for (int bb = 0; bb < 3; bb++) {
                    PdM[a][bb] = 0.0;
                    for (int k = 0; k < 3; k++) PdM[a][bb] += Pm[a][k] * dM[k][bb];
                }
            for (int a = 0; a < 3; a++)
                for (int bb = 0; bb < 3; bb++) {
                    double x = dD[a] * Mi[a][bb];
                    for (int k = 0; k < 3; k++) x -= PdM[a][k] * Mi[k][bb];
                    G[a][bb] = s * x + (s < 1.0 ? 5.0 * (Pm[a][bb] - (a == bb)) : 0.0);
                }
            for (int l = 0; l < 3 * (P->ns + P->nm); l++) {
                if (ed->dv[l] == 0.0) continue;
                for (int a = 0; a < 3; a++)
                    for (int bb = 0; bb < 3; bb++) d->dA[3 * a + bb][pos[l]] += G[a][bb] * ed->dv[l];
            }
        }
        if (over) continue; /* (a partly covered facet over more than 64 master facets: its basis' motion left out) */
        /* the residual's part: K += sum_ab Y_ab dA_ab^T, Y summed over the facet's points first
           (its dofs: those of dA, the facet's and its master facets' nodes) */
        static const int nyc = 9 + 9 * 64;
        double Y[9][9 + 9 * 64];
        for (int ab = 0; ab < 9; ab++)
            for (int l = 0; l < nyc; l++) Y[ab][l] = 0.0;
        for (long e = first; e < e1 && !over; e++) {
            const nlink_t *E = &w->L[e];
            const ffc_link *lk = &links[E->k];
            const double L[3] = {1.0 - lk->xs[0] - lk->xs[1], lk->xs[0], lk->xs[1]};
            for (int k = 0; k < E->nd; k++) {
                int p = -1;
                for (int l = 0; l < d->nd && p < 0; l++)
                    if (d->dof[l] == E->dof[k]) p = l;
                if (p < 0) { /* a dof of the points that no moving edge has (dA = 0 there) */
                    if (d->nd >= nyc) { over = 1; break; }
                    p = d->nd++;
                    d->dof[p] = E->dof[k];
                    for (int ab = 0; ab < 9; ab++) d->dA[ab][p] = 0.0;
                }
                for (int a = 0; a < 3; a++) {
                    const long v = P->Fs[P->ns * f + a];
                    double y = -w->tn[v] * E->G[k];
                    if (fric && w->T[v].f.state != FFC_FRIC_OPEN) y += w->F[e].sw[k] * w->T[v].f.t[k % 3];
                    for (int bb = 0; bb < 3; bb++) Y[3 * a + bb][p] += E->da * L[bb] * y;
                }
            }
        }
        if (over) continue;
        for (int ab = 0; ab < 9; ab++)
            for (int k = 0; k < d->nd; k++) {
                if (Y[ab][k] == 0.0) continue;
                for (int l = 0; l < d->nd; l++)
                    if (d->dA[ab][l] != 0.0) *ok &= emit(nt, tcap, Ti, Tj, Tv, d->dof[k], d->dof[l], Y[ab][k] * d->dA[ab][l]);
            }
        nf++;
    }
    return nf;
}

int ffc__assemble_nodal(const ffc_effects *fx, const ffc_pair *P, const double qw[], int nq, long nl,
                        const ffc_link links[], const double lambda[], const double lam_t[],
                        const ffc_law *law, double R[], long cap, long Ti[], long Tj[], double Tv[],
                        long *ntrip, ffc_stats *stats, long *bad)
{
    const double eps = law->eps_n;
    const int material_only = law->material_only != 0, ranked = law->material_only == 2,
              fric = ffc__friction_on(fx, law);
    long nterm = 0; /* ranked: the terms written */
    /* a share of the links: the residual and the ranked tangent only, whose
     * terms are sums over links (not the segments' or the dual basis' motion) */
    if (law->lsel && (law->dual || law->nedge > 0 || (Ti && Tj && Tv && !ranked))) return FFC_ERR_VALUE;
    nodal_t w;
    int s = ffc__nodal_prepare(fx, P, qw, nq, nl, links, lambda, fric ? lam_t : NULL, law, &w, stats, bad);
    if (s) return s;
    const int want_k = Ti && Tj && Tv;
    long nt = 0;
    int ok = 1;
    double D[FFC_MAXDOF][FFC_MAXDOF];
    /* residual, statistics and geometric stiffness, link by link */
    for (long e = 0; e < w.n; e++) {
        const nlink_t *E = &w.L[e];
        const ffc_link *lk = &links[E->k];
        const double t = ffc__nodal_point_pressure(P, lk, E, w.tn);
        double Tq[3] = {0, 0, 0};
        int fs = FFC_FRIC_OPEN;
        if (fric) ffc__nodal_point_traction(P, lk, E, w.T, Tq, &fs);
        const int has_t = fric && (Tq[0] != 0.0 || Tq[1] != 0.0 || Tq[2] != 0.0);
        if (t == 0.0 && !has_t) continue; /* dual multipliers: t < 0 between pressed nodes counts too */
        ffc__nodal_point_stats(stats, t, E, Tq);
        for (int a = 0; a < E->nd; a++) R[E->dof[a]] -= t * E->da * E->G[a];
        if (has_t)
            for (int a = 0; a < E->nd; a++) R[E->dof[a]] += E->da * w.F[e].sw[a] * Tq[a % 3];
        if (!want_k || material_only) continue;
        lnodes_t ln;
        s = ffc__gather_link(fx, P, nq, lk, &ln);
        ffc_link_state sg;
        lgeo_t g;
        if (!s)
            s = ffc__link_geometry(fx, P->ns, CP3(ln.Xs), CP3(ln.Xs0), lk->xs, ffc__link_weight(lk, qw), P->nm, CP3(ln.Xm),
                                   lk->xm, &sg, &g, D);
        if (s) { *bad = E->k; ffc__nodal_free(&w); return s; }
        for (int a = 0; a < E->nd; a++)
            for (int b = 0; b < E->nd; b++) D[a][b] = -t * (E->da * D[a][b] + E->G[a] * E->dda[b]);
        if (has_t) ffc__link_friction_geo(&g, E->da, w.F[e].sw, Tq, D);
        for (int a = 0; a < E->nd; a++)
            for (int b = 0; b < E->nd; b++)
                if (D[a][b] != 0.0) ok &= emit(&nt, cap, Ti, Tj, Tv, E->dof[a], E->dof[b], D[a][b]);
    }
    /* the segments' motion (law->edge): its geometric part, and each point
     * evaluated for the nodal part below; per slave node, its points */
    const long ne = want_k && !material_only ? law->nedge : 0;
    nedge_t *EB = NULL;
    long *es = NULL, *el = NULL;
    if (ne > 0) {
        EB = malloc((size_t)ne * sizeof *EB);
        es = calloc((size_t)P->nv + 1, sizeof *es);
        el = malloc((size_t)(3 * ne) * sizeof *el);
        if (!EB || !es || !el) { free(EB); free(es); free(el); ffc__nodal_free(&w); return FFC_ERR_MEMORY; }
        s = segment_motion(fx, P, law, &w, fric, EB, cap, Ti, Tj, Tv, &nt, &ok, bad);
        if (s) { free(EB); free(es); free(el); ffc__nodal_free(&w); return s; }
        for (long b = 0; b < ne; b++)
            for (int a = 0; a < 3; a++) es[P->Fs[law->edge[b].sf * P->ns + a] + 1]++;
        for (long v = 0; v < P->nv; v++) es[v + 1] += es[v];
        long *fill = calloc((size_t)P->nv, sizeof *fill);
        if (!fill) { free(EB); free(es); free(el); ffc__nodal_free(&w); return FFC_ERR_MEMORY; }
        for (long b = 0; b < ne; b++)
            for (int a = 0; a < 3; a++) {
                const long v = P->Fs[law->edge[b].sf * P->ns + a];
                el[es[v] + fill[v]++] = b;
            }
        free(fill);
    }
    /* the dual basis of partly covered facets moves with their segments */
    ndual_t *DF = NULL;
    long ndf = 0, *ds = NULL, *dl = NULL;
    if (ne > 0 && law->dual) {
        long cnt = 0;
        for (long e0 = 0; e0 < w.n;) {
            const long f = links[w.L[e0].k].sf;
            double c = 0.0;
            while (e0 < w.n && links[w.L[e0].k].sf == f) c += links[w.L[e0++].k].w;
            cnt += c < 0.5 * (1.0 - 1e-12);
        }
        if (cnt > 0) {
            DF = malloc((size_t)cnt * sizeof *DF);
            ds = calloc((size_t)P->nv + 1, sizeof *ds);
            dl = malloc((size_t)(3 * cnt) * sizeof *dl);
            if (!DF || !ds || !dl) s = FFC_ERR_MEMORY;
            else {
                ndf = dual_motion(P, links, law, &w, fric, DF, cnt, Ti, Tj, Tv, cap, &nt, &ok);
                if (ndf < 0) s = (int)ndf;
            }
            if (s) { free(DF); free(ds); free(dl); free(EB); free(es); free(el); ffc__nodal_free(&w); return s; }
            for (long i = 0; i < ndf; i++)
                for (int a = 0; a < 3; a++) ds[P->Fs[P->ns * DF[i].f + a] + 1]++;
            for (long v = 0; v < P->nv; v++) ds[v + 1] += ds[v];
            long *fill = calloc((size_t)P->nv, sizeof *fill);
            if (!fill) { free(DF); free(ds); free(dl); free(EB); free(es); free(el); ffc__nodal_free(&w); return FFC_ERR_MEMORY; }
            for (long i = 0; i < ndf; i++)
                for (int a = 0; a < 3; a++) {
                    const long v = P->Fs[P->ns * DF[i].f + a];
                    dl[ds[v] + fill[v]++] = i;
                }
            free(fill);
        }
    }
    if (want_k) {
        /* material stiffness, node by node: links of each slave node */
        nodework_t k;
        if (nodework_alloc(P, links, &w, &k)) { free(DF); free(ds); free(dl); free(EB); free(es); free(el); ffc__nodal_free(&w); return FFC_ERR_MEMORY; }
        for (long v = 0; v < P->nv; v++) {
            if (!w.on[v] || !(w.Wn[v] > 0.0)) continue;
            const double W = w.Wn[v], gt = w.Gn[v] / W, c = eps / W;
            const nfn_t *Tn = fric ? &w.T[v] : NULL;
            const int ft = Tn && Tn->f.state != FFC_FRIC_OPEN;
            long nloc = 0;
            for (long m = k.start[v]; m < k.start[v + 1]; m++) {
                const long e = k.lst[m];
                const nlink_t *E = &w.L[e];
                const ffc_link *lk = &links[E->k];
                double Na = 0.0, Nta = 0.0; /* (the normal part's, the friction sums') */
                for (int a = 0; a < P->ns; a++)
                    if (P->Fs[lk->sf * P->ns + a] == v) { Na += E->N[a]; Nta += E->Nt[a]; }
                for (int a = 0; a < E->nd; a++) {
                    long d = E->dof[a];
                    if (k.pos[d] < 0) {
                        k.pos[d] = nloc; k.loc[nloc] = d; k.Bv[nloc] = k.Cv[nloc] = 0.0;
                        if (ft)
                            for (int i = 0; i < 3; i++) k.Bf[3 * nloc + i] = k.Rt[3 * nloc + i] = k.Nt[3 * nloc + i] = 0.0;
                        nloc++;
                    }
                    const long p = k.pos[d];
                    k.Bv[p] += Na * E->da * E->G[a];
                    k.Cv[p] += Na * (E->da * E->G[a] + (E->g - gt) * E->dda[a]);
                    if (!ft) continue;
                    const nfl_t *fl = &w.F[e];
                    k.Bf[3 * p + a % 3] += Nta * E->da * fl->sw[a];
                    for (int i = 0; i < 3; i++) {
                        k.Rt[3 * p + i] += (Nta * (E->da * fl->Q[i][a] + fl->r[i] * E->dda[a]) - Na * Tn->r[i] * E->dda[a]) / W;
                        if (!material_only) k.Nt[3 * p + i] += Nta * (E->da * fl->dn[i][a] + E->n[i] * E->dda[a]);
                    }
                }
            }
            for (long m = ne > 0 ? es[v] : 0; ne > 0 && m < es[v + 1]; m++) { /* the segments' motion */
                const long b = el[m];
                const nedge_t *Eb = &EB[b];
                double Na = 0.0;
                for (int a = 0; a < 3; a++)
                    if (P->Fs[law->edge[b].sf * P->ns + a] == v) Na += Eb->N[a];
                for (int l = 0; l < Eb->nd; l++) {
                    const double dv = law->edge[b].dv[l];
                    const long p = k.pos[Eb->dof[l]];
                    if (dv == 0.0 || p < 0) continue; /* (the segment's links put every dof there) */
                    k.Cv[p] += Na * Eb->da * (Eb->g - gt) * dv;
                    if (!ft) continue;
                    for (int i = 0; i < 3; i++) {
                        k.Rt[3 * p + i] += Na * Eb->da * (Eb->r[i] - Tn->r[i]) * dv / W;
                        k.Nt[3 * p + i] += Na * Eb->da * Eb->n[i] * dv;
                    }
                }
            }
            for (long m = ndf > 0 ? ds[v] : 0; ndf > 0 && m < ds[v + 1]; m++) { /* the dual basis' motion */
                const ndual_t *d = &DF[dl[m]];
                int av = -1;
                for (int a = 0; a < 3; a++)
                    if (P->Fs[P->ns * d->f + a] == v) av = a;
                double Z[3] = {0, 0, 0}, Zr[3][3] = {{0}}, Zn[3][3] = {{0}};
                for (long e = d->e0; e < d->e1; e++) {
                    const nlink_t *E = &w.L[e];
                    const ffc_link *lk = &links[E->k];
                    const double L[3] = {1.0 - lk->xs[0] - lk->xs[1], lk->xs[0], lk->xs[1]};
                    for (int b = 0; b < 3; b++) {
                        Z[b] += L[b] * E->da * (E->g - gt);
                        if (!ft) continue;
                        for (int i = 0; i < 3; i++) {
                            Zr[b][i] += L[b] * E->da * (w.F[e].r[i] - Tn->r[i]) / W;
                            Zn[b][i] += L[b] * E->da * E->n[i];
                        }
                    }
                }
                for (int l = 0; l < d->nd; l++) {
                    const long p = k.pos[d->dof[l]];
                    if (p < 0) continue; /* (the facet's links put every dof there) */
                    for (int b = 0; b < 3; b++) {
                        const double x = d->dA[3 * av + b][l];
                        if (x == 0.0) continue;
                        k.Cv[p] += Z[b] * x;
                        if (!ft) continue;
                        for (int i = 0; i < 3; i++) {
                            k.Rt[3 * p + i] += Zr[b][i] * x;
                            k.Nt[3 * p + i] += Zn[b][i] * x;
                        }
                    }
                }
            }
            if (ranked) /* the term c B_a C_a^T */
                ok &= emit_term(&nt, cap, Ti, Tj, Tv, nloc, k.loc, c, k.Bv, k.Cv, 1, nterm++);
            else
                for (long i = 0; i < nloc; i++)
                    for (long j = 0; j < nloc; j++)
                        if (k.Bv[i] != 0.0 && k.Cv[j] != 0.0)
                            ok &= emit(&nt, cap, Ti, Tj, Tv, k.loc[i], k.loc[j], c * k.Bv[i] * k.Cv[j]);
            if (ft) {
                /* dropped directions: dr~ and dm without their components;
                 * dn~ = (I - n~ n~^T) / |m| (accumulated), then
                 * dT_a = dT/dr dr~ + dT/dn dn~ - dT/dt_N c C^T, K += Bf dT_a */
                const double *nn = Tn->n;
                for (long j = 0; j < nloc; j++) {
                    double *q = &k.Nt[3 * j];
                    for (int i = 0; i < 3; i++)
                        if (Tn->drop & (1 << i)) q[i] = k.Rt[3 * j + i] = 0.0;
                    const double d = ffc__dot(nn, q);
                    for (int i = 0; i < 3; i++) q[i] = (q[i] - nn[i] * d) / Tn->mnorm;
                }
                for (long j = 0; j < nloc; j++) {
                    double dT[3];
                    for (int i = 0; i < 3; i++) {
                        double x = -Tn->f.dt_dtn[i] * c * k.Cv[j];
                        for (int l = 0; l < 3; l++)
                            x += Tn->f.dt_dr[i][l] * k.Rt[3 * j + l] + Tn->f.dt_dn[i][l] * k.Nt[3 * j + l];
                        dT[i] = x;
                    }
                    if (ranked) { /* kept for the terms Bf_i dT_i^T below */
                        for (int i = 0; i < 3; i++) k.Rt[3 * j + i] = dT[i];
                        continue;
                    }
                    for (long i = 0; i < nloc; i++) {
                        const double x = k.Bf[3 * i] * dT[0] + k.Bf[3 * i + 1] * dT[1] + k.Bf[3 * i + 2] * dT[2];
                        if (x != 0.0) ok &= emit(&nt, cap, Ti, Tj, Tv, k.loc[i], k.loc[j], x);
                    }
                }
                for (int d = 0; ranked && d < 3; d++) /* the terms Bf_d dT_d^T */
                    ok &= emit_term(&nt, cap, Ti, Tj, Tv, nloc, k.loc, 1.0, k.Bf + d, k.Rt + d, 3, nterm++);
            }
            for (long i = 0; i < nloc; i++) k.pos[k.loc[i]] = -1;
        }
        nodework_free(&k);
    }
    free(EB);
    free(es);
    free(el);
    free(DF);
    free(ds);
    free(dl);
    *ntrip = nt;
    ffc__nodal_free(&w);
    return ok ? FFC_OK : FFC_ERR_CAPACITY;
}
