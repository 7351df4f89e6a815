/* ffc_self_guard.c: the pass-through check of self pairs: slave points that crossed an opposite facet of their own surface in one step. */
#include <math.h>
#include <stdlib.h>

#include "ffc.h"
#include "ffc_internal.h"
#include "ffc_scene_state.h"

/* the nodes of facet f of F[nf*nn] at positions x (plus u when u != NULL) */
static void facet_at(int nn, const long F[], long f, const double X[], const double u[], double P[][3])
{
    for (int a = 0; a < nn; a++)
        for (int i = 0; i < 3; i++) {
            const long v = F[f * nn + a];
            P[a][i] = X[3 * v + i] + (u ? u[3 * v + i] : 0.0);
        }
}

/* One self pair at s->x (positions at u): the points behind an opposite
 * facet by more than the capture distance that were on its open side at
 * the commit (u_prev), counted into *n. */
static int pair_passed(const ffc_scene *s, const scene_pair *p, long *n)
{
    const int nper = s->nper;
    /* the step's largest motion of the surface's nodes: a point that
     * crossed a facet lies at most twice that behind it */
    double mmax = 0.0;
    for (long k = 0; k < p->nfs * nper; k++) {
        const long v = p->Fs[k];
        double d2 = 0.0;
        for (int i = 0; i < 3; i++) d2 += (s->x[3 * v + i] - s->X[3 * v + i] - s->u_prev[3 * v + i]) *
                                           (s->x[3 * v + i] - s->X[3 * v + i] - s->u_prev[3 * v + i]);
        mmax = fmax(mmax, sqrt(d2));
    }
    ffc_search_opts o = p->o.search;
    o.capture_abs += 2.0 * mmax;
    const int nq = ffc_quad_size(p->o.qdeg);
    if (nq < 0) return nq;
    ffc_link *L = malloc((size_t)(p->nfs * nq) * sizeof *L);
    if (!L) return FFC_ERR_MEMORY;
    ffc_tree *t = NULL;
    int st = ffc_tree_build(nper, p->nfm, p->Fm, s->nv, s->x, &t);
    if (!st) st = ffc_search(t, nper, p->nfs, p->Fs, s->nv, s->x, p->o.qdeg, &o, p->nfs * nq, L);
    for (long k = 0; st >= 0 && k < p->nfs * nq; k++) {
        const ffc_link *lk = &L[k];
        if (lk->mf < 0) continue;
        double Pm[FFC_MAXNODES][3], Ps[FFC_MAXNODES][3];
        facet_at(nper, p->Fm, lk->mf, s->x, NULL, Pm);
        const double cap = fmax(p->o.search.capture_abs, p->o.search.capture_rel * sqrt(ffc__facet_size2((const double(*)[3])(Pm))));
        if (lk->gap >= -cap) continue;   /* within reach of the search: the contact sees it */
        /* at the commit: the point and the same facet */
        facet_at(nper, p->Fs, lk->sf, s->X, s->u_prev, Ps);
        facet_at(nper, p->Fm, lk->mf, s->X, s->u_prev, Pm);
        double N[FFC_MAXNODES], x0[3] = {0, 0, 0};
        ffc_shape(nper, lk->xs, N, NULL);
        for (int a = 0; a < nper; a++)
            for (int i = 0; i < 3; i++) x0[i] += N[a] * Ps[a][i];
        ffc_proj pr;
        if (ffc__project_free_from(nper, (const double(*)[3])(Pm), x0, NULL, &pr)) continue;   /* (a facet degenerate then: no verdict) */
        if (pr.gap > 0.0) (*n)++;
    }
    ffc_tree_free(t);
    free(L);
    return st < 0 ? st : FFC_OK;
}

int ffc_scene_self_passed(ffc_scene *s, const double u[], long *n, long *bad)
{
    long dummy;
    if (!bad) bad = &dummy;
    *bad = -1;
    if (!s || !u || !n) return FFC_ERR_NULL;
    *n = 0;
    int st = ffc__scene_positions(s, u, bad);
    if (st) return st;
    for (int k = 0; k < s->np; k++) {
        if (!s->p[k].o.search.self) continue;
        st = pair_passed(s, &s->p[k], n);
        if (st) { *bad = k; return st; }
    }
    return FFC_OK;
}
