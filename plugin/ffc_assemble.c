/* ffc_assemble.c: contact over all links of a pair: the checks every call
 * shares, gathering a link's nodes, statistics, and the assembly of the
 * residual and tangent (pointwise law here, nodal law in ffc_nodal.c). */
#include "ffc.h"
#include "ffc_internal.h"
#include "ffc_link_internal.h"

#include <math.h>
#include <string.h>

static int check_pair(const ffc_pair *P)
{
    if (!P || !P->Fs || (!P->Fm && !P->obst) || !P->X || !P->u) return FFC_ERR_NULL;
    if ((P->ns != 3 && P->ns != 6) || (P->obst ? P->nm != 0 : P->nm != 3 && P->nm != 6)) return FFC_ERR_NODES;
    if (P->nfs <= 0 || (!P->obst && P->nfm <= 0)) return FFC_ERR_EMPTY;
    if (P->obst) {
        int s = ffc_obstacle_check(P->obst);
        if (s) return s;
    }
    if (P->nv <= 0) return FFC_ERR_SIZE;
    return FFC_OK;
}

/* nodes of facet f: current P, reference P0, dofs, and the friction
 * motion D: u - u_prev (quasi-static, mo = u_prev), the velocity (dynamic,
 * mo = v) or zero (mo = NULL) */
static void gather(int nn, const long *F, long f, const double X[], const double u[], const double mo[],
                   int velocity, double P[][3], double P0[][3], double D[][3], long dof[])
{
    for (int a = 0; a < nn; a++) {
        long v = F[f * nn + a];
        for (int i = 0; i < 3; i++) {
            P0[a][i] = X[3 * v + i];
            P[a][i] = X[3 * v + i] + u[3 * v + i];
            D[a][i] = !mo ? 0.0 : velocity ? mo[3 * v + i] : u[3 * v + i] - mo[3 * v + i];
            dof[3 * a + i] = 3 * v + i;
        }
    }
}

int ffc__gather_link(const ffc_effects *fx, const ffc_pair *P, int nq, const ffc_link *lk, lnodes_t *n)
{
    if (lk->sf < 0 || lk->sf >= P->nfs || (nq > 0 ? lk->q < 0 || lk->q >= nq : lk->q != -1) ||
        lk->mf >= (P->obst ? 1 : P->nfm))
        return FFC_ERR_INDEX;
    for (int a = 0; a < P->ns; a++)
        if (P->Fs[lk->sf * P->ns + a] < 0 || P->Fs[lk->sf * P->ns + a] >= P->nv) return FFC_ERR_INDEX;
    for (int a = 0; a < P->nm; a++)
        if (P->Fm[lk->mf * P->nm + a] < 0 || P->Fm[lk->mf * P->nm + a] >= P->nv) return FFC_ERR_INDEX;
    const double *mo = fx->dynamic ? P->v : P->u_prev;
    gather(P->ns, P->Fs, lk->sf, P->X, P->u, mo, fx->dynamic, n->Xs, n->Xs0, n->Ds, n->dof);
    gather(P->nm, P->Fm, lk->mf, P->X, P->u, mo, fx->dynamic, n->Xm, n->Xm0, n->Dm, n->dof + 3 * P->ns);
    n->nd = 3 * (P->ns + P->nm);
    return FFC_OK;
}

/* Evaluates link k (pointwise law): state, residual (and tangent when
 * K != NULL), and the global dofs of its unknowns; *nd their count. */
int ffc__eval_link(const ffc_effects *fx, const ffc_pair *P, const double qw[], int nq,
                   const ffc_link *lk, double lambda, const double lam_t[3], const ffc_law *law,
                   ffc_link_state *st, double R[FFC_MAXDOF], double K[FFC_MAXDOF][FFC_MAXDOF],
                   long dof[FFC_MAXDOF], int *nd)
{
    lnodes_t n;
    int s = ffc__gather_link(fx, P, nq, lk, &n);
    if (s) return s;
    memcpy(dof, n.dof, sizeof n.dof);
    *nd = n.nd;
    return ffc__link_contact(fx, P->ns, CP3(n.Xs), CP3(n.Xs0), CP3(n.Ds), lk->xs, ffc__link_weight(lk, qw), P->nm,
                             CP3(n.Xm), CP3(n.Dm), P->obst, lambda, lam_t, law, st, R, K);
}

void ffc__stats_init(ffc_stats *s)
{
    memset(s, 0, sizeof *s);
}

/* a point pressed by t > 0 over the area da, normal n */
void ffc__stats_pressure(ffc_stats *s, double t, double da, const double n[3])
{
    s->active++;
    if (t > s->max_tn) s->max_tn = t;
    for (int i = 0; i < 3; i++) s->force[i] += t * da * n[i];
}

/* |r - (r . n) n|: the tangential part of r for a unit n */
double ffc__tangential_norm(const double r[3], const double n[3])
{
    const double rn = ffc__dot(r, n), rt[3] = {r[0] - rn * n[0], r[1] - rn * n[1], r[2] - rn * n[2]};
    return sqrt(ffc__dot(rt, rt));
}

/* an active point (pointwise law): pressure t, and its friction state */
static void stats_active(ffc_stats *s, double t, const ffc_link_state *st, int fric)
{
    ffc__stats_pressure(s, t, st->da, st->n);
    if (!fric) return;
    s->stick += st->fstate == FFC_FRIC_STICK;
    s->slip += st->fstate == FFC_FRIC_SLIP;
    const double tt = sqrt(ffc__dot(st->t, st->t));
    if (tt > s->max_tt) s->max_tt = tt;
    for (int i = 0; i < 3; i++) s->force_t[i] -= st->t[i] * st->da;
    s->dissipation += st->da * ffc__dot(st->t, st->slip);
    const double rt = ffc__tangential_norm(st->slip, st->n);
    if (rt > s->max_slip) s->max_slip = rt;
}

void ffc__stats_add(ffc_stats *s, const ffc_link_state *st, int fric)
{
    s->linked++;
    if (-st->gap > s->max_pen) s->max_pen = -st->gap;
    if (st->active) stats_active(s, st->tn, st, fric);
}

/* The checks every call over all links shares: pair, law, quadrature rule
 * (its weights into qw, point count *nq), link count, slave node indices,
 * finite multipliers (lambda[nv] and lam_t[3 nv] nodal, lambda[nl] and
 * lam_t[3 nl] per link, lam_t with friction only; *bad = the index of a
 * non-finite one) and, with friction,
 * finite previous displacements. */
int ffc__common_checks(const ffc_effects *fx, const ffc_pair *P, int qdeg, long nl,
                       const ffc_link links[], const ffc_law *law, const double lambda[],
                       const double lam_t[], double qw[16], int *nq, long *bad)
{
    if (!fx || !links || !law || !lambda) return FFC_ERR_NULL;
    int s = check_pair(P);
    if (s) return s;
    if (!(law->eps_n > 0) || isinf(law->eps_n) || (law->nodal != 0 && law->nodal != 1) ||
        (law->tangent != 0 && law->tangent != FFC_TANGENT_CONSISTENT && law->tangent != FFC_TANGENT_MATERIAL &&
         law->tangent != FFC_TANGENT_RANKED) || (law->tangent == FFC_TANGENT_RANKED && !law->nodal))
        return FFC_ERR_VALUE;
    if (fx->friction && (!(law->mu >= 0) || isinf(law->mu))) return FFC_ERR_VALUE;
    const int fric = ffc__friction_on(fx, law);
    if (fric && (!(law->eps_t > 0) || isinf(law->eps_t))) return FFC_ERR_VALUE;
    if (fric && fx->dynamic && !ffc__dynamic_ok(law)) return FFC_ERR_VALUE;
    const double *mo = fx->dynamic ? P->v : P->u_prev;
    if (fric && (!lam_t || !mo)) return FFC_ERR_NULL;
    if (qdeg == 0) { /* segment links, each with its weight */
        if (!law->nodal || P->ns != P->nm || P->obst) return FFC_ERR_VALUE;
        if (nl < 0) return FFC_ERR_SIZE;
        *nq = 0;
        for (long k = 0; k < nl; k++)
            if (!(links[k].w >= 0) || isinf(links[k].w)) { *bad = k; return FFC_ERR_NONFINITE; }
    } else {
        double qxi[16][2];
        *nq = ffc_quad(qdeg, 16, qxi, qw);
        if (*nq < 0) return *nq;
        if (nl != P->nfs * *nq) return FFC_ERR_SIZE;
    }
    if (law->nedge) {
        if (qdeg != 0 || law->nedge < 0) return FFC_ERR_VALUE;
        if (!law->edge) return FFC_ERR_NULL;
        for (long b = 0; b < law->nedge; b++) {
            const ffc_mortar_edge *e = &law->edge[b];
            if (e->sf < 0 || e->sf >= P->nfs || e->mf < 0 || e->mf >= P->nfm) { *bad = b; return FFC_ERR_INDEX; }
            for (int l = 0; l < 3 * (P->ns + P->nm); l++)
                if (!isfinite(e->dv[l])) { *bad = b; return FFC_ERR_NONFINITE; }
            if (!isfinite(e->xs[0]) || !isfinite(e->xs[1])) { *bad = b; return FFC_ERR_NONFINITE; }
        }
    }
    if (law->lsel && !law->nodal) return FFC_ERR_VALUE;
    if (law->lsel && !law->nsum) return FFC_ERR_NULL;
    if (law->dual) {
        if (!law->nodal) return FFC_ERR_VALUE;
        for (long k = 0; k < 9 * P->nfs; k++)
            if (!isfinite(law->dual[k])) { *bad = k / 9; return FFC_ERR_NONFINITE; }
    }
    for (long k = 0; k < P->nfs * P->ns; k++)
        if (P->Fs[k] < 0 || P->Fs[k] >= P->nv) return FFC_ERR_INDEX;
    const long n = law->nodal ? P->nv : nl;
    for (long k = 0; k < n; k++)
        if (!isfinite(lambda[k])) { *bad = k; return FFC_ERR_NONFINITE; }
    if (fric) {
        for (long k = 0; k < 3 * n; k++)
            if (!isfinite(lam_t[k])) { *bad = k / 3; return FFC_ERR_NONFINITE; }
        for (long k = 0; k < 3 * P->nv; k++)
            if (!isfinite(mo[k])) return FFC_ERR_NONFINITE;
    }
    return FFC_OK;
}

int ffc_assemble(const ffc_effects *effects, const ffc_pair *pair, int qdeg,
                 long nl, const ffc_link links[], const double lambda[],
                 const double lam_t[], const ffc_law *law, double R[], long cap, long Ti[], long Tj[],
                 double Tv[], long *ntrip, ffc_stats *stats, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    double qw[16];
    int nq;
    int s = ffc__common_checks(effects, pair, qdeg, nl, links, law, lambda, lam_t, qw, &nq, bad);
    if (s) return s;
    if (!R || !ntrip) return FFC_ERR_NULL;
    const int want_k = Ti && Tj && Tv, fric = ffc__friction_on(effects, law);
    ffc_stats loc;
    if (!stats) stats = &loc;
    ffc__stats_init(stats);
    if (law->nodal)
        return ffc__assemble_nodal(effects, pair, qw, nq, nl, links, lambda, lam_t, law, R, cap, Ti, Tj, Tv, ntrip,
                                   stats, bad);
    long nt = 0;
    int over = 0;
    double Rl[FFC_MAXDOF], Kl[FFC_MAXDOF][FFC_MAXDOF];
    long dof[FFC_MAXDOF];
    for (long k = 0; k < nl; k++) {
        if (links[k].mf < 0) continue;
        ffc_link_state st;
        int nd;
        s = ffc__eval_link(effects, pair, qw, nq, &links[k], lambda[k], fric ? lam_t + 3 * k : NULL, law, &st, Rl,
                           want_k ? Kl : NULL, dof, &nd);
        if (s) { *bad = k; return s; }
        ffc__stats_add(stats, &st, fric);
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
