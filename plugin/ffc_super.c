/* ffc_super.c: the numeric supernodal Cholesky factorization P A P' = L L'
 * on CHOLMOD's supernodal analysis, by sets of whole subtrees of its
 * supernodal tree and then the supernodes above them (the ranks of one
 * machine each factorize a set, and exchange the values). */
#include <stdlib.h>
#include <string.h>

#include "ffc_internal.h"
#include "ffc_super.h"

void dsyrk_(const char *uplo, const char *trans, const int *n, const int *k, const double *alpha, const double *a,
            const int *lda, const double *beta, double *c, const int *ldc);
void dgemm_(const char *ta, const char *tb, const int *m, const int *n, const int *k, const double *alpha,
            const double *a, const int *lda, const double *b, const int *ldb, const double *beta, double *c,
            const int *ldc);
void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info);
void dtrsm_(const char *side, const char *uplo, const char *ta, const char *diag, const int *m, const int *n,
            const double *alpha, const double *a, const int *lda, double *b, const int *ldb);

struct ffc__super {
    long n, ns;          /* L's order, its supernodes */
    int *ap, *ai;        /* [n+1], [nnz] P A P' (lower triangle) by columns */
    double *ax;          /* [nnz] its values */
    int *sn;             /* [n] the supernode of each column of L */
    int *map;            /* [n] a row's place in the supernode being computed */
    int *head, *next;    /* [ns] each supernode's list of the supernodes that update it next */
    int *lpos;           /* [ns] the place in a supernode's rows of the first row it updates next */
    signed char *part;   /* [ns] the set of each supernode: 0..parts-1, -1 above the subtrees */
    double *wt;          /* [ns] the flops of computing each supernode: its own and the updates it receives */
    double *share;       /* [parts + 1] the estimated flops of each set, as shares (the last: -1's) */
    int parts;           /* the sets of subtrees (count) */
    double *c;           /* [ccap] one update block */
    long ccap;           /* the largest update block (entries) */
};

void ffc__super_free(ffc__super *w)
{
    if (!w) return;
    free(w->ap); free(w->ai); free(w->ax); free(w->sn); free(w->map);
    free(w->head); free(w->next); free(w->lpos); free(w->part); free(w->wt); free(w->share); free(w->c);
    free(w);
}

/* the flops of supernode s's own factorization (DPOTRF, DTRSM) */
static double own_flops(const cholmod_factor *L, long s)
{
    const int *super = L->super, *pi = L->pi;
    const double nc = super[s + 1] - super[s], nb = (pi[s + 1] - pi[s]) - nc;
    return nc * nc * nc / 3.0 + nc * nc * nb;
}

/* the candidates by weight, largest first (ties: the lower index first);
 * insertion: nearly in order from one split to the next */
static void by_weight(long nc, int cand[], const double sub[])
{
    for (long i = 1; i < nc; i++)
        for (long j = i; j > 0 && (sub[cand[j]] > sub[cand[j - 1]] ||
                                   (sub[cand[j]] == sub[cand[j - 1]] && cand[j] < cand[j - 1])); j--) {
            const int t = cand[j]; cand[j] = cand[j - 1]; cand[j - 1] = t;
        }
}

/* the candidates (in order) dealt to the least loaded part each; the
 * largest load.  With part non-NULL: each candidate's part there. */
static double deal(long nc, const int cand[], const double sub[], int parts, double load[], signed char *part)
{
    for (int p = 0; p < parts; p++) load[p] = 0.0;
    for (long i = 0; i < nc; i++) {
        int q = 0;
        for (int p = 1; p < parts; p++) if (load[p] < load[q]) q = p;
        load[q] += sub[cand[i]];
        if (part) part[cand[i]] = (signed char)q;
    }
    double mx = 0.0;
    for (int p = 0; p < parts; p++) if (load[p] > mx) mx = load[p];
    return mx;
}

/* the largest candidate cand[0] split: above the sets, its children candidates */
static long split_first(long nc, int cand[], const int kid[], const int kids[], signed char top[])
{
    const int r = cand[0];
    top[r] = 1;
    cand[0] = cand[--nc];
    for (int e = kid[r]; e < kid[r + 1]; e++) cand[nc++] = kids[e];
    return nc;
}

/* The sets: whole subtrees, dealt to the parts largest first, each to the
 * least loaded part.  Starting from the roots, the subtree of largest
 * weight is split again and again (its root goes above the sets, its
 * children become subtrees: down a chain of single children and on past
 * the branches), and the split of the least estimate max(load) + f above
 * is kept, f = (1 + 1 / parts) / 2: the supernodes above are made with
 * the BLAS threads of the parts, which gain on their largest blocks but
 * not in the updates' additions (measured: CHOLMOD's factorization with
 * 2 threads took 0.7-0.9 of its time with one).  Where the best split
 * does not beat f times the whole, there is none.  A supernode's weight
 * is the flops of making it (w->wt).  The same on every rank (the same
 * L, the same order of ties). */
static int split(ffc__super *w, const cholmod_factor *L, int parts)
{
    const long ns = w->ns;
    const int *super = L->super, *pi = L->pi, *ls = L->s;
    const double f = (1.0 + 1.0 / parts) / 2.0;
    int *par = malloc((size_t)ns * sizeof(int)), *cand = malloc((size_t)ns * sizeof(int));
    int *kid = malloc((size_t)(ns + 1) * sizeof(int)), *kids = malloc((size_t)ns * sizeof(int));
    double *sub = calloc((size_t)ns, sizeof(double)), *load = malloc((size_t)parts * sizeof(double));
    signed char *top = calloc((size_t)ns, 1);
    int st = par && cand && kid && kids && sub && load && top ? FFC_OK : FFC_ERR_MEMORY;
    for (long s = 0; s < ns && !st; s++) {
        const int nc = super[s + 1] - super[s], nr = pi[s + 1] - pi[s];
        par[s] = nr > nc ? w->sn[ls[pi[s] + nc]] : -1;
        if (par[s] >= 0 && par[s] <= s) st = FFC_ERR_UNAVAILABLE;   /* (not in the order of the tree) */
    }
    double total = 0.0, above = 0.0, best = 1e300;
    long nc = 0, bestk = 0;
    if (!st) {   /* subtree weights; children by parent (counted into kid, placed with cand as the fill) */
        for (long s = 0; s <= ns; s++) kid[s] = 0;
        for (long s = 0; s < ns; s++) sub[s] = w->wt[s];
        for (long s = 0; s < ns; s++) {
            total += w->wt[s];
            if (par[s] >= 0) { sub[par[s]] += sub[s]; kid[par[s] + 1]++; }
        }
        for (long s = 0; s < ns; s++) kid[s + 1] += kid[s];
        for (long s = 0; s < ns; s++) cand[s] = kid[s];
        for (long s = 0; s < ns; s++)
            if (par[s] >= 0) kids[cand[par[s]]++] = (int)s;
        for (long s = 0; s < ns; s++)
            if (par[s] < 0) cand[nc++] = (int)s;
        for (long k = 0; k <= 64 * parts + 256 && nc > 0; k++) {
            by_weight(nc, cand, sub);
            const double est = deal(nc, cand, sub, parts, load, NULL) + f * above;
            if (est < best * (1.0 - 1e-9)) { best = est; bestk = k; }
            above += w->wt[cand[0]];
            nc = split_first(nc, cand, kid, kids, top);
        }
        if (parts > 1 && best >= f * total) st = FFC_ERR_UNAVAILABLE;
    }
    if (!st) {   /* again up to the best split; each subtree in its root's part */
        for (long s = 0; s < ns; s++) { top[s] = 0; w->part[s] = -1; }
        nc = 0;
        for (long s = 0; s < ns; s++)
            if (par[s] < 0) cand[nc++] = (int)s;
        for (long k = 0; k < bestk; k++) {
            by_weight(nc, cand, sub);
            nc = split_first(nc, cand, kid, kids, top);
        }
        by_weight(nc, cand, sub);
        deal(nc, cand, sub, parts, load, w->part);
        for (long s = ns - 1; s >= 0; s--)   /* (parents before children) */
            if (!top[s] && w->part[s] < 0 && par[s] >= 0) w->part[s] = w->part[par[s]];
        for (int p = 0; p <= parts; p++) w->share[p] = 0.0;
        for (long s = 0; s < ns && total > 0.0; s++) w->share[w->part[s] < 0 ? parts : w->part[s]] += w->wt[s] / total;
    }
    free(par); free(cand); free(kid); free(kids); free(sub); free(load); free(top);
    return st;
}

/* One pass over the supernodes in the tree's order (children first):
 * those of set `part` computed, the other subtrees' (when part >= 0)
 * only followed in the lists of updates, the rest left.  Formulation
 * (left-looking): supernode s holds columns k1..k2-1 of L and rows
 * ls[pi[s]..] (the first k2 - k1 of them its columns); its block is A's
 * columns k1..k2-1 on those rows less, for each supernode d below it
 * with rows in k1..k2-1, L_d(rows of d from k1 on, :) L_d(rows of d in
 * k1..k2-1, :)^T (DSYRK on the rows within, DGEMM below), added in by
 * the rows' places in s; then L_s = chol(diagonal block) and the rows
 * below L_s^-T from the right (DPOTRF, DTRSM).  d is then listed under
 * the supernode of its next row below k2.  With Lx NULL: every supernode
 * only followed, to size the update blocks and weigh the supernodes. */
static int pass(ffc__super *w, const cholmod_factor *L, double *Lx, int part)
{
    const long ns = w->ns;
    const int *super = L->super, *pi = L->pi, *px = L->px, *ls = L->s;
    const double one = 1.0, zero = 0.0;
    if (part >= 0 || !Lx)
        for (long s = 0; s < ns; s++) w->head[s] = -1;
    for (long s = 0; s < ns; s++) {
        const int ps = w->part[s];
        const int num = Lx && (part >= 0 ? ps == part : ps < 0);
        if (Lx && !num && (part < 0 || ps < 0)) continue;
        const int k1 = super[s], k2 = super[s + 1], nscol = k2 - k1, psi = pi[s], nsrow = pi[s + 1] - psi;
        double *Ls = num ? Lx + px[s] : NULL;
        if (num) {
            for (int k = 0; k < nsrow; k++) w->map[ls[psi + k]] = k;
            memset(Ls, 0, (size_t)nsrow * (size_t)nscol * sizeof(double));
            for (int j = k1; j < k2; j++) {
                double *col = Ls + (size_t)(j - k1) * (size_t)nsrow;
                for (int p = w->ap[j]; p < w->ap[j + 1]; p++) col[w->map[w->ai[p]]] += w->ax[p];
            }
        }
        for (int d = w->head[s]; d >= 0;) {
            const int dnext = w->next[d];
            const int pdi = pi[d], ndrow = pi[d + 1] - pdi, ndcol = super[d + 1] - super[d];
            const int pdi1 = pdi + w->lpos[d];
            int pdi2 = pdi1;
            while (pdi2 < pdi + ndrow && ls[pdi2] < k2) pdi2++;
            const int n1 = pdi2 - pdi1, n2 = pdi + ndrow - pdi1, n3 = n2 - n1;
            if (!Lx) {
                if ((long)n1 * n2 > w->ccap) w->ccap = (long)n1 * n2;
                w->wt[s] += (double)ndcol * n1 * (2.0 * n2 - n1);   /* (DSYRK and DGEMM) */
            }
            if (num) {
                const double *Ld = Lx + px[d] + (pdi1 - pdi);
                double *C = w->c;
                dsyrk_("L", "N", &n1, &ndcol, &one, Ld, &ndrow, &zero, C, &n2);
                if (n3 > 0) dgemm_("N", "T", &n3, &n1, &ndcol, &one, Ld + n1, &ndrow, Ld, &ndrow, &zero, C + n1, &n2);
                for (int j = 0; j < n1; j++) {
                    double *col = Ls + (size_t)(ls[pdi1 + j] - k1) * (size_t)nsrow;
                    const double *cj = C + (size_t)j * (size_t)n2;
                    for (int i = j; i < n2; i++) col[w->map[ls[pdi1 + i]]] -= cj[i];
                }
            }
            w->lpos[d] = pdi2 - pdi;
            if (pdi2 < pdi + ndrow) {
                const int t = w->sn[ls[pdi2]];
                w->next[d] = w->head[t];
                w->head[t] = d;
            }
            d = dnext;
        }
        w->head[s] = -1;
        if (num) {
            int info = 0;
            dpotrf_("L", &nscol, Ls, &nsrow, &info);
            if (info != 0) return FFC_ERR_SINGULAR;
            const int nb = nsrow - nscol;
            if (nb > 0) dtrsm_("R", "L", "T", "N", &nb, &nscol, &one, Ls, &nsrow, Ls + nscol, &nsrow);
        }
        w->lpos[s] = nscol;
        if (nsrow > nscol) {
            const int t = w->sn[ls[psi + nscol]];
            w->next[s] = w->head[t];
            w->head[t] = (int)s;
        }
    }
    return FFC_OK;
}

ffc__super *ffc__super_create(const cholmod_factor *L, const cholmod_sparse *A, int parts, int *status)
{
    *status = FFC_ERR_UNAVAILABLE;
    if (!L || !A || !L->is_super || L->xtype != CHOLMOD_REAL || A->xtype != CHOLMOD_REAL || !A->packed ||
        A->stype >= 0 || A->nrow != L->n || A->ncol != L->n || parts < 1 || parts > 127 || L->itype != CHOLMOD_INT ||
        A->itype != CHOLMOD_INT)
        return NULL;
    const long n = (long)L->n, ns = (long)L->nsuper;
    const int *super = L->super, *pi = L->pi, *ls = L->s, *perm = L->Perm;
    for (long s = 0; s < ns; s++) {   /* each supernode's rows ascending, its columns first */
        const int nc = super[s + 1] - super[s], nr = pi[s + 1] - pi[s];
        if (nr < nc) return NULL;
        for (int k = 0; k < nr; k++)
            if ((k < nc && ls[pi[s] + k] != super[s] + k) || (k > 0 && ls[pi[s] + k] <= ls[pi[s] + k - 1]))
                return NULL;
    }
    *status = FFC_ERR_MEMORY;
    ffc__super *w = calloc(1, sizeof *w);
    if (!w) return NULL;
    const int *Ap = A->p, *Ai = A->i;
    const double *Ax = A->x;
    const long nnz = Ap[n];
    w->n = n;
    w->ns = ns;
    w->parts = parts;
    w->ap = malloc((size_t)(n + 1) * sizeof(int));
    w->ai = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof(int));
    w->ax = malloc((size_t)(nnz > 0 ? nnz : 1) * sizeof(double));
    w->sn = malloc((size_t)n * sizeof(int));
    w->map = malloc((size_t)n * sizeof(int));
    w->head = malloc((size_t)ns * sizeof(int));
    w->next = malloc((size_t)ns * sizeof(int));
    w->lpos = malloc((size_t)ns * sizeof(int));
    w->part = malloc((size_t)ns);
    w->wt = malloc((size_t)ns * sizeof(double));
    w->share = malloc((size_t)(parts + 1) * sizeof(double));
    int *ipm = malloc((size_t)n * sizeof(int));
    if (!w->ap || !w->ai || !w->ax || !w->sn || !w->map || !w->head || !w->next || !w->lpos || !w->part ||
        !w->wt || !w->share || !ipm) {
        free(ipm);
        ffc__super_free(w);
        return NULL;
    }
    /* P A P' by columns, its lower triangle: A's (i, j) at (ipm[i], ipm[j]) */
    for (long k = 0; k < n; k++) ipm[perm[k]] = (int)k;
    for (long k = 0; k <= n; k++) w->ap[k] = 0;
    for (long j = 0; j < n; j++)
        for (int p = Ap[j]; p < Ap[j + 1]; p++) {
            const int a = ipm[Ai[p]], b = ipm[j];
            w->ap[(a < b ? a : b) + 1]++;
        }
    for (long k = 0; k < n; k++) w->ap[k + 1] += w->ap[k];
    memcpy(w->map, w->ap, (size_t)n * sizeof(int));   /* (the fill positions) */
    for (long j = 0; j < n; j++)
        for (int p = Ap[j]; p < Ap[j + 1]; p++) {
            const int a = ipm[Ai[p]], b = ipm[j], c = a < b ? a : b;
            const int q = w->map[c]++;
            w->ai[q] = a < b ? b : a;
            w->ax[q] = Ax[p];
        }
    free(ipm);
    for (long s = 0; s < ns; s++)
        for (int c = super[s]; c < super[s + 1]; c++) w->sn[c] = (int)s;
    for (long s = 0; s < ns; s++) { w->wt[s] = own_flops(L, s); w->part[s] = -1; }
    pass(w, L, NULL, 0);   /* (the largest update block, the updates' flops) */
    int st = split(w, L, parts);
    if (!st) {
        w->c = malloc((size_t)(w->ccap > 0 ? w->ccap : 1) * sizeof(double));
        if (!w->c) st = FFC_ERR_MEMORY;
    }
    if (st) {
        *status = st;
        ffc__super_free(w);
        return NULL;
    }
    *status = FFC_OK;
    return w;
}

int ffc__super_numeric(ffc__super *w, const cholmod_factor *L, double Lx[], int part)
{
    if (!w || !L || !Lx || part < -1 || part >= w->parts) return FFC_ERR_SIZE;
    return pass(w, L, Lx, part);
}

const signed char *ffc__super_parts(const ffc__super *w) { return w ? w->part : NULL; }

double ffc__super_share(const ffc__super *w, int part)
{
    if (!w || part < -1 || part >= w->parts) return 0.0;
    return w->share[part < 0 ? w->parts : part];
}
