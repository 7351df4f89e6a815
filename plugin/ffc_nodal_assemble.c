/* ffc_nodal_assemble.c: the nodal law's residual and tangent (see the Formulation comments in ffc_nodal.c). */
#include "ffc.h"
#include "ffc_internal.h"
#include "ffc_link_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

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
 * none with a material tangent (ffc__law_material).  Each point is evaluated into E[b];
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
        if (!s) s = ffc__link_geometry(fx, P->ns, CP3(ln.Xs), CP3(ln.Xs0), tmp.xs, 1.0, P->nm, CP3(ln.Xm), NULL, NULL, &st, &g, NULL);
        if (s) { *bad = b; return s; }
        nedge_t *e = &E[b];
        e->g = st.gap;
        e->da = st.da;
        e->nd = ln.nd;
        memcpy(e->dof, ln.dof, sizeof ln.dof);
        for (int i = 0; i < 3; i++) e->n[i] = st.n[i];
        nlink_t nl;
        memset(&nl, 0, sizeof nl);
        ffc__nodal_shape(law, P->ns, tmp.sf, tmp.xs, nl.N);
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
            ffc__link_slip_deriv(&g, CP3(ln.Dm), ffc__motion_coef(fx, law), ffc__law_material(law), sw, Q);
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

/* The state of one assembly (ffc__assemble_nodal): the pair, its links and
 * law, the nodal law evaluated over them, the triplets written, and the
 * segments' and the dual basis' motion, each listed per slave node */
typedef struct {
    const ffc_effects *fx;
    const ffc_pair *P;
    const ffc_link *links;
    const ffc_law *law;
    nodal_t w;                  /* the nodal law over the pair (ffc__nodal_prepare) */
    int material_only, ranked, fric;
    int want_k;                 /* the tangent asked for (Ti, Tj, Tv) */
    long cap, *Ti, *Tj;         /* the tangent's triplets, [cap] */
    double *Tv;
    long nt;                    /* triplets written (may exceed cap) */
    int ok;                     /* 0 once a triplet did not fit */
    long nterm;                 /* ranked: the terms written */
    long ne;                    /* segment points evaluated (law->edge; 0: none) */
    nedge_t *EB;                /* [ne] their values */
    long *es, *el;              /* [nv + 1], [3 ne]: slave node v's points el[es[v] .. es[v + 1]) */
    long ndf;                   /* partly covered facets whose dual basis moves */
    ndual_t *DF;                /* [ndf] their motion */
    long *ds, *dl;              /* [nv + 1], [3 ndf]: slave node v's facets dl[ds[v] .. ds[v + 1]) */
} nasm_t;

static void nasm_free(nasm_t *S)
{
    free(S->EB);
    free(S->es);
    free(S->el);
    free(S->DF);
    free(S->ds);
    free(S->dl);
    ffc__nodal_free(&S->w);
}

/* residual, statistics and geometric stiffness, link by link */
static int link_terms(nasm_t *S, const double qw[], int nq, double R[], ffc_stats *stats, long *bad)
{
    const ffc_pair *P = S->P;
    const nodal_t *w = &S->w;
    double D[FFC_MAXDOF][FFC_MAXDOF];
    for (long e = 0; e < w->n; e++) {
        const nlink_t *E = &w->L[e];
        const ffc_link *lk = &S->links[E->k];
        const double t = ffc__nodal_point_pressure(P, lk, E, w->tn);
        double Tq[3] = {0, 0, 0};
        int fs = FFC_FRIC_OPEN;
        if (S->fric) ffc__nodal_point_traction(P, lk, E, w->T, Tq, &fs);
        const int has_t = S->fric && (Tq[0] != 0.0 || Tq[1] != 0.0 || Tq[2] != 0.0);
        if (t == 0.0 && !has_t) continue; /* dual multipliers: t < 0 between pressed nodes counts too */
        ffc__nodal_point_stats(stats, t, E, Tq);
        for (int a = 0; a < E->nd; a++) R[E->dof[a]] -= t * E->da * E->G[a];
        if (has_t)
            for (int a = 0; a < E->nd; a++) R[E->dof[a]] += E->da * w->F[e].sw[a] * Tq[a % 3];
        if (!S->want_k || S->material_only) continue;
        lnodes_t ln;
        int s = ffc__gather_link(S->fx, P, nq, lk, &ln);
        ffc_link_state sg;
        lgeo_t g;
        if (!s)
            s = ffc__link_geometry(S->fx, P->ns, CP3(ln.Xs), CP3(ln.Xs0), lk->xs, ffc__link_weight(lk, qw), P->nm, CP3(ln.Xm),
                                   lk->xm, P->obst, &sg, &g, D);
        if (s) { *bad = E->k; return s; }
        for (int a = 0; a < E->nd; a++)
            for (int b = 0; b < E->nd; b++) D[a][b] = -t * (E->da * D[a][b] + E->G[a] * E->dda[b]);
        if (has_t) ffc__link_friction_geo(&g, E->da, w->F[e].sw, Tq, D);
        for (int a = 0; a < E->nd; a++)
            for (int b = 0; b < E->nd; b++)
                if (D[a][b] != 0.0) S->ok &= emit(&S->nt, S->cap, S->Ti, S->Tj, S->Tv, E->dof[a], E->dof[b], D[a][b]);
    }
    return FFC_OK;
}

/* the segments' motion (law->edge): its geometric part, and each point
 * evaluated for the nodal part (node_segments); per slave node, its points */
static int segments_setup(nasm_t *S, long *bad)
{
    const ffc_pair *P = S->P;
    const ffc_law *law = S->law;
    const long ne = S->ne;
    S->EB = malloc((size_t)ne * sizeof *S->EB);
    S->es = calloc((size_t)P->nv + 1, sizeof *S->es);
    S->el = malloc((size_t)(3 * ne) * sizeof *S->el);
    if (!S->EB || !S->es || !S->el) return FFC_ERR_MEMORY;
    int s = segment_motion(S->fx, P, law, &S->w, S->fric, S->EB, S->cap, S->Ti, S->Tj, S->Tv, &S->nt, &S->ok, bad);
    if (s) return s;
    for (long b = 0; b < ne; b++)
        for (int a = 0; a < 3; a++) S->es[P->Fs[law->edge[b].sf * P->ns + a] + 1]++;
    for (long v = 0; v < P->nv; v++) S->es[v + 1] += S->es[v];
    long *fill = calloc((size_t)P->nv, sizeof *fill);
    if (!fill) return FFC_ERR_MEMORY;
    for (long b = 0; b < ne; b++)
        for (int a = 0; a < 3; a++) {
            const long v = P->Fs[law->edge[b].sf * P->ns + a];
            S->el[S->es[v] + fill[v]++] = b;
        }
    free(fill);
    return FFC_OK;
}

/* the dual basis of partly covered facets moves with their segments
 * (dual_motion); per slave node, its facets */
static int duals_setup(nasm_t *S)
{
    const ffc_pair *P = S->P;
    const ffc_link *links = S->links;
    const nodal_t *w = &S->w;
    long cnt = 0;
    for (long e0 = 0; e0 < w->n;) {
        const long f = links[w->L[e0].k].sf;
        double c = 0.0;
        while (e0 < w->n && links[w->L[e0].k].sf == f) c += links[w->L[e0++].k].w;
        cnt += c < 0.5 * (1.0 - 1e-12);
    }
    if (cnt == 0) return FFC_OK;
    S->DF = malloc((size_t)cnt * sizeof *S->DF);
    S->ds = calloc((size_t)P->nv + 1, sizeof *S->ds);
    S->dl = malloc((size_t)(3 * cnt) * sizeof *S->dl);
    if (!S->DF || !S->ds || !S->dl) return FFC_ERR_MEMORY;
    const long ndf = dual_motion(P, links, S->law, w, S->fric, S->DF, cnt, S->Ti, S->Tj, S->Tv, S->cap, &S->nt, &S->ok);
    if (ndf < 0) return (int)ndf;
    S->ndf = ndf;
    for (long i = 0; i < ndf; i++)
        for (int a = 0; a < 3; a++) S->ds[P->Fs[P->ns * S->DF[i].f + a] + 1]++;
    for (long v = 0; v < P->nv; v++) S->ds[v + 1] += S->ds[v];
    long *fill = calloc((size_t)P->nv, sizeof *fill);
    if (!fill) return FFC_ERR_MEMORY;
    for (long i = 0; i < ndf; i++)
        for (int a = 0; a < 3; a++) {
            const long v = P->Fs[P->ns * S->DF[i].f + a];
            S->dl[S->ds[v] + fill[v]++] = i;
        }
    free(fill);
    return FFC_OK;
}

/* A slave node of the material stiffness (material_terms) */
typedef struct {
    long v;                     /* the node */
    double W, gt, c;            /* W_a, g~_a, eps / W_a */
    const nfn_t *Tn;            /* its return map (NULL without friction) */
    int ft;                     /* its friction terms: Tn, not open */
    long nloc;                  /* its dofs: k->loc[nloc], their places k->pos */
} nnode_t;

/* node n's links: B_a, C_a and with friction Bf_a, dr~_a, dn~_a summed
 * over its linked points, its dofs gathered in k->loc */
static void node_links(const nasm_t *S, nodework_t *k, nnode_t *n)
{
    const ffc_pair *P = S->P;
    const nodal_t *w = &S->w;
    const long v = n->v;
    const double W = n->W, gt = n->gt;
    const nfn_t *Tn = n->Tn;
    const int ft = n->ft;
    for (long m = k->start[v]; m < k->start[v + 1]; m++) {
        const long e = k->lst[m];
        const nlink_t *E = &w->L[e];
        const ffc_link *lk = &S->links[E->k];
        double Na = 0.0, Nta = 0.0; /* (the normal part's, the friction sums') */
        for (int a = 0; a < P->ns; a++)
            if (P->Fs[lk->sf * P->ns + a] == v) { Na += E->N[a]; Nta += E->Nt[a]; }
        for (int a = 0; a < E->nd; a++) {
            long d = E->dof[a];
            if (k->pos[d] < 0) {
                const long nloc = n->nloc;
                k->pos[d] = nloc; k->loc[nloc] = d; k->Bv[nloc] = k->Cv[nloc] = 0.0;
                if (ft)
                    for (int i = 0; i < 3; i++) k->Bf[3 * nloc + i] = k->Rt[3 * nloc + i] = k->Nt[3 * nloc + i] = 0.0;
                n->nloc++;
            }
            const long p = k->pos[d];
            k->Bv[p] += Na * E->da * E->G[a];
            k->Cv[p] += Na * (E->da * E->G[a] + (E->g - gt) * E->dda[a]);
            if (!ft) continue;
            const nfl_t *fl = &w->F[e];
            k->Bf[3 * p + a % 3] += Nta * E->da * fl->sw[a];
            for (int i = 0; i < 3; i++) {
                k->Rt[3 * p + i] += (Nta * (E->da * fl->Q[i][a] + fl->r[i] * E->dda[a]) - Na * Tn->r[i] * E->dda[a]) / W;
                if (!S->material_only) k->Nt[3 * p + i] += Nta * (E->da * fl->dn[i][a] + E->n[i] * E->dda[a]);
            }
        }
    }
}

/* node n's share of the segments' motion (segment_motion) in C_a, dr~_a, dn~_a */
static void node_segments(const nasm_t *S, nodework_t *k, const nnode_t *n)
{
    const ffc_pair *P = S->P;
    const ffc_law *law = S->law;
    const long v = n->v;
    for (long m = S->es[v]; m < S->es[v + 1]; m++) {
        const long b = S->el[m];
        const nedge_t *Eb = &S->EB[b];
        double Na = 0.0;
        for (int a = 0; a < 3; a++)
            if (P->Fs[law->edge[b].sf * P->ns + a] == v) Na += Eb->N[a];
        for (int l = 0; l < Eb->nd; l++) {
            const double dv = law->edge[b].dv[l];
            const long p = k->pos[Eb->dof[l]];
            if (dv == 0.0 || p < 0) continue; /* (the segment's links put every dof there) */
            k->Cv[p] += Na * Eb->da * (Eb->g - n->gt) * dv;
            if (!n->ft) continue;
            for (int i = 0; i < 3; i++) {
                k->Rt[3 * p + i] += Na * Eb->da * (Eb->r[i] - n->Tn->r[i]) * dv / n->W;
                k->Nt[3 * p + i] += Na * Eb->da * Eb->n[i] * dv;
            }
        }
    }
}

/* node n's share of the dual basis' motion (dual_motion) in C_a, dr~_a, dn~_a */
static void nodal_dual_terms(const nasm_t *S, nodework_t *k, const nnode_t *n)
{
    const ffc_pair *P = S->P;
    const nodal_t *w = &S->w;
    const long v = n->v;
    const double W = n->W, gt = n->gt;
    const nfn_t *Tn = n->Tn;
    const int ft = n->ft;
    for (long m = S->ds[v]; m < S->ds[v + 1]; m++) {
        const ndual_t *d = &S->DF[S->dl[m]];
        int av = -1;
        for (int a = 0; a < 3; a++)
            if (P->Fs[P->ns * d->f + a] == v) av = a;
        double Z[3] = {0, 0, 0}, Zr[3][3] = {{0}}, Zn[3][3] = {{0}};
        for (long e = d->e0; e < d->e1; e++) {
            const nlink_t *E = &w->L[e];
            const ffc_link *lk = &S->links[E->k];
            const double L[3] = {1.0 - lk->xs[0] - lk->xs[1], lk->xs[0], lk->xs[1]};
            for (int b = 0; b < 3; b++) {
                Z[b] += L[b] * E->da * (E->g - gt);
                if (!ft) continue;
                for (int i = 0; i < 3; i++) {
                    Zr[b][i] += L[b] * E->da * (w->F[e].r[i] - Tn->r[i]) / W;
                    Zn[b][i] += L[b] * E->da * E->n[i];
                }
            }
        }
        for (int l = 0; l < d->nd; l++) {
            const long p = k->pos[d->dof[l]];
            if (p < 0) continue; /* (the facet's links put every dof there) */
            for (int b = 0; b < 3; b++) {
                const double x = d->dA[3 * av + b][l];
                if (x == 0.0) continue;
                k->Cv[p] += Z[b] * x;
                if (!ft) continue;
                for (int i = 0; i < 3; i++) {
                    k->Rt[3 * p + i] += Zr[b][i] * x;
                    k->Nt[3 * p + i] += Zn[b][i] * x;
                }
            }
        }
    }
}

/* node n's friction terms: dropped directions: dr~ and dm without their
 * components; dn~ = (I - n~ n~^T) / |m| (accumulated), then
 * dT_a = dT/dr dr~ + dT/dn dn~ - dT/dt_N c C^T, K += Bf dT_a */
static void node_friction(nasm_t *S, nodework_t *k, const nnode_t *n)
{
    const nfn_t *Tn = n->Tn;
    const double c = n->c;
    const long nloc = n->nloc;
    const int ranked = S->ranked;
    const double *nn = Tn->n;
    for (long j = 0; j < nloc; j++) {
        double *q = &k->Nt[3 * j];
        for (int i = 0; i < 3; i++)
            if (Tn->drop & (1 << i)) q[i] = k->Rt[3 * j + i] = 0.0;
        const double d = ffc__dot(nn, q);
        for (int i = 0; i < 3; i++) q[i] = (q[i] - nn[i] * d) / Tn->mnorm;
    }
    for (long j = 0; j < nloc; j++) {
        double dT[3];
        for (int i = 0; i < 3; i++) {
            double x = -Tn->f.dt_dtn[i] * c * k->Cv[j];
            for (int l = 0; l < 3; l++)
                x += Tn->f.dt_dr[i][l] * k->Rt[3 * j + l] + Tn->f.dt_dn[i][l] * k->Nt[3 * j + l];
            dT[i] = x;
        }
        if (ranked) { /* kept for the terms Bf_i dT_i^T below */
            for (int i = 0; i < 3; i++) k->Rt[3 * j + i] = dT[i];
            continue;
        }
        for (long i = 0; i < nloc; i++) {
            const double x = k->Bf[3 * i] * dT[0] + k->Bf[3 * i + 1] * dT[1] + k->Bf[3 * i + 2] * dT[2];
            if (x != 0.0) S->ok &= emit(&S->nt, S->cap, S->Ti, S->Tj, S->Tv, k->loc[i], k->loc[j], x);
        }
    }
    for (int d = 0; ranked && d < 3; d++) /* the terms Bf_d dT_d^T */
        S->ok &= emit_term(&S->nt, S->cap, S->Ti, S->Tj, S->Tv, nloc, k->loc, 1.0, k->Bf + d, k->Rt + d, 3, S->nterm++);
}

/* material stiffness, node by node: links of each slave node */
static int material_terms(nasm_t *S)
{
    const ffc_pair *P = S->P;
    const nodal_t *w = &S->w;
    nodework_t k;
    if (nodework_alloc(P, S->links, w, &k)) return FFC_ERR_MEMORY;
    for (long v = 0; v < P->nv; v++) {
        if (!w->on[v] || !(w->Wn[v] > 0.0)) continue;
        nnode_t n;
        n.v = v;
        n.W = w->Wn[v];
        n.gt = w->Gn[v] / n.W;
        n.c = S->law->eps_n / n.W;
        n.Tn = S->fric ? &w->T[v] : NULL;
        n.ft = n.Tn && n.Tn->f.state != FFC_FRIC_OPEN;
        n.nloc = 0;
        node_links(S, &k, &n);
        if (S->ne > 0) node_segments(S, &k, &n);
        if (S->ndf > 0) nodal_dual_terms(S, &k, &n);
        const long nloc = n.nloc;
        const double c = n.c;
        if (S->ranked) /* the term c B_a C_a^T */
            S->ok &= emit_term(&S->nt, S->cap, S->Ti, S->Tj, S->Tv, nloc, k.loc, c, k.Bv, k.Cv, 1, S->nterm++);
        else
            for (long i = 0; i < nloc; i++)
                for (long j = 0; j < nloc; j++)
                    if (k.Bv[i] != 0.0 && k.Cv[j] != 0.0)
                        S->ok &= emit(&S->nt, S->cap, S->Ti, S->Tj, S->Tv, k.loc[i], k.loc[j], c * k.Bv[i] * k.Cv[j]);
        if (n.ft) node_friction(S, &k, &n);
        for (long i = 0; i < nloc; i++) k.pos[k.loc[i]] = -1;
    }
    nodework_free(&k);
    return FFC_OK;
}

int ffc__assemble_nodal(const ffc_effects *fx, const ffc_pair *P, const double qw[], int nq, long nl,
                        const ffc_link links[], const double lambda[], const double lam_t[],
                        const ffc_law *law, double R[], long cap, long Ti[], long Tj[], double Tv[],
                        long *ntrip, ffc_stats *stats, long *bad)
{
    nasm_t S;
    memset(&S, 0, sizeof S);
    S.fx = fx;
    S.P = P;
    S.links = links;
    S.law = law;
    S.material_only = ffc__law_material(law);
    S.ranked = law->tangent == FFC_TANGENT_RANKED;
    S.fric = ffc__friction_on(fx, law);
    /* a share of the links: the residual and the ranked tangent only, whose
     * terms are sums over links (not the segments' or the dual basis' motion) */
    if (law->lsel && (law->dual || law->nedge > 0 || (Ti && Tj && Tv && !S.ranked))) return FFC_ERR_VALUE;
    int s = ffc__nodal_prepare(fx, P, qw, nq, nl, links, lambda, S.fric ? lam_t : NULL, law, &S.w, stats, bad);
    if (s) return s;
    S.want_k = Ti && Tj && Tv;
    S.cap = cap;
    S.Ti = Ti;
    S.Tj = Tj;
    S.Tv = Tv;
    S.ok = 1;
    s = link_terms(&S, qw, nq, R, stats, bad);
    S.ne = S.want_k && !S.material_only ? law->nedge : 0;
    if (!s && S.ne > 0) s = segments_setup(&S, bad);
    if (!s && S.ne > 0 && law->dual) s = duals_setup(&S);
    if (!s && S.want_k) s = material_terms(&S);
    if (s) { nasm_free(&S); return s; }
    *ntrip = S.nt;
    nasm_free(&S);
    return S.ok ? FFC_OK : FFC_ERR_CAPACITY;
}
