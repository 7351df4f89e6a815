/* ffc_cdirection.c: the condensed Newton's direction on the contact dofs:
 * a dense LU of I + G_aa Kc on the tangent's support (or GMRES
 * preconditioned by the last one), or, for a tangent of low-rank terms,
 * the Woodbury form; products with G shared over the ranks. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ffc_bulk_state.h"
#include "ffc_internal.h"

enum { PDENSE_MIN = 200 }; /* on several ranks, a dense LU of this order and more is shared over them
                              (ScaLAPACK); a smaller one is factorized on every rank */

double ffc__dotn(long m, const double x[], const double y[])
{
    double v = 0.0;
    for (long k = 0; k < m; k++) v += x[k] * y[k];
    return v;
}

enum { KRYLOV = 20 };       /* GMRES: basis vectors per cycle */

/* Solves (I + Gaa M) t = t (a x a, both dense column-major) by GMRES,
 * right-preconditioned with the kept LU of an earlier system on the same
 * support, to a true residual of 1e-14 of the right-hand side (the LU's
 * own accuracy: a looser one costs Newton iterations on a penalty-stiff
 * system).  Returns the iterations, or -1 when it does not get there in
 * two cycles (t is then unchanged: the caller factorizes afresh). */
/* y[n] += v x[n] (distinct arrays; GCC's -O2 cost model leaves the loop
 * scalar, the "cheap" one vectorizes it: element by element, the same
 * results) */
#if defined(__GNUC__) && !defined(__clang__)
__attribute__((optimize("tree-loop-vectorize", "vect-cost-model=cheap")))
#endif
static void axpy(long n, double v, const double *restrict x, double *restrict y)
{
    for (long r = 0; r < n; r++) y[r] += v * x[r];
}

/* w[a] overwritten by the kept LU's solution (shared over the ranks when
 * it is pd's); nonzero on failure */
static int kept_solve(ffc__bulk *b, long a, double w[])
{
    if (b->kdist) return ffc__pdense_solve(b->pd, a, w);
    const int ai = (int)a, one = 1;
    int info = 0;
    dgetrs_("N", &ai, &one, b->klu, &ai, b->kpiv, w, &ai, &info);
    return info;
}

static int gmres_kept(ffc__bulk *b, long a, const double M[], const double Gaa[], double t[])
{
    const long k1 = KRYLOV + 1, need = a * (k1 + 4) + k1 * KRYLOV + 3 * k1;
    if (need > b->gcap) {
        double *g = realloc(b->gv, (size_t)need * sizeof(double));
        if (!g) return -1;
        b->gv = g;
        b->gcap = need;
    }
    double *V = b->gv, *x = V + a * k1, *w = x + a, *z = w + a, *rb = z + a, *H = rb + a, *cs = H + k1 * KRYLOV,
           *sn = cs + k1, *g = sn + k1;
    const int ai = (int)a, one = 1;
    const double d1 = 1.0, d0 = 0.0;
    int iters = 0;
    double bn = 0.0;
    for (long r = 0; r < a; r++) { rb[r] = t[r]; x[r] = 0.0; bn += t[r] * t[r]; }
    bn = sqrt(bn);
    if (bn == 0.0) return 0;
    /* w = A v = v + Gaa (M v) */
#define AMUL(v_, out_)                                                                                             \
    do {                                                                                                           \
        dgemv_("N", &ai, &ai, &d1, M, &ai, (v_), &one, &d0, z, &one);                                              \
        memcpy((out_), (v_), (size_t)a * sizeof(double));                                                          \
        dgemv_("N", &ai, &ai, &d1, Gaa, &ai, z, &one, &d1, (out_), &one);                                          \
    } while (0)
    for (int cycle = 0; cycle < 2; cycle++) {
        /* r = b - A x into V[:, 0] */
        AMUL(x, w);
        double beta = 0.0;
        for (long r = 0; r < a; r++) { V[r] = rb[r] - w[r]; beta += V[r] * V[r]; }
        beta = sqrt(beta);
        if (beta <= 1e-14 * bn) {
            memcpy(t, x, (size_t)a * sizeof(double));
            return iters;
        }
        for (long r = 0; r < a; r++) V[r] /= beta;
        for (long i = 0; i < k1; i++) g[i] = 0.0;
        g[0] = beta;
        long j = 0;
        for (; j < KRYLOV; j++) {
            /* w = A P^-1 V[:, j] */
            memcpy(w, V + j * a, (size_t)a * sizeof(double));
            if (kept_solve(b, a, w)) return -1;
            double *vj1 = V + (j + 1) * a;
            AMUL(w, vj1);
            iters++;
            double *h = H + j * k1;
            for (long i = 0; i <= j; i++) { /* modified Gram-Schmidt */
                h[i] = ffc__dotn(a, vj1, V + i * a);
                for (long r = 0; r < a; r++) vj1[r] -= h[i] * V[i * a + r];
            }
            h[j + 1] = sqrt(ffc__dotn(a, vj1, vj1));
            if (h[j + 1] > 0.0)
                for (long r = 0; r < a; r++) vj1[r] /= h[j + 1];
            if (ffc__gmres_rotate(j, h, cs, sn, g)) return -1;
            if (fabs(g[j + 1]) <= 1e-15 * bn) { j++; break; }
        }
        /* y = H^-1 g (upper triangular j x j), x += P^-1 V y */
        for (long i = j - 1; i >= 0; i--) {
            double v = g[i];
            for (long c = i + 1; c < j; c++) v -= H[c * k1 + i] * g[c];
            g[i] = v / H[i * k1 + i];
        }
        for (long r = 0; r < a; r++) w[r] = 0.0;
        for (long i = 0; i < j; i++)
            for (long r = 0; r < a; r++) w[r] += g[i] * V[i * a + r];
        if (kept_solve(b, a, w)) return -1;
        for (long r = 0; r < a; r++) x[r] += w[r];
    }
    /* the true residual after the last cycle */
    AMUL(x, w);
    double rn = 0.0;
    for (long r = 0; r < a; r++) rn += (rb[r] - w[r]) * (rb[r] - w[r]);
#undef AMUL
    if (!(sqrt(rn) <= 1e-14 * bn)) return -1;
    memcpy(t, x, (size_t)a * sizeof(double));
    return iters;
}

/* Products with G, H and G U on the ranks of a replicated bulk (rsize >
 * 1): each rank computes a contiguous share of the rows (of the columns
 * for G U) and one all-gather gives every rank all of them.  These
 * products are bound by memory bandwidth, which the ranks of one machine
 * share: computed whole on every rank, two ranks took each one about
 * twice as long as one process; shared, G and H are streamed once in all.
 * Every value is that of the rank that computed it: the same bits on
 * every rank.  Below SHARE_MIN entries every rank computes the product
 * whole (the all-gather's latency would cost more). */
enum { SHARE_MIN = 1 << 15 };

/* y = alpha A x + beta y, A n x k (column-major, leading dimension lda) */
int ffc__bulk_gemv(ffc__bulk *b, long n, long k, double alpha, const double *A, long lda, const double x[],
                   double beta, double y[])
{
    const int one = 1, ki = (int)k, ldai = (int)lda;
    if (n <= 0 || k <= 0) return FFC_OK;   /* (the callers' cases: y as it was) */
    if (b->rk.size < 2 || n * k < SHARE_MIN) {
        const int ni = (int)n;
        dgemv_("N", &ni, &ki, &alpha, A, &ldai, x, &one, &beta, y, &one);
        return FFC_OK;
    }
    long lo, hi;
    ffc__ranks_share(&b->rk, n, 1, &lo, &hi);
    const int ni = (int)(hi - lo);
    if (ni > 0) dgemv_("N", &ni, &ki, &alpha, A + lo, &ldai, x, &one, &beta, y + lo, &one);
    return ffc__mpi_allgather(b->rk.comm, y, b->rk.count);
}

/* The Newton direction dy of (I + G Kc') dy = -G rho, Kc' = Kc_CC - S from
 * the triplets (b->ti, tj, tv)[nt], reduced to Kc's support a: with
 * q = G rho, t + G_aa M t = -q_a (dense LU, b->A), dy = -q - G_Ca M t;
 * and the change of the reaction z = G^-1 (y - d0_C) it makes, by the
 * Newton equation G^-1 dy = -rho - Kc' dy: dz = -rho - E_a M dy_a.
 * ap[m], ad[m], q[m], t[m], s[m] work; *na the support's size. */
int ffc__bulk_direction(ffc__bulk *b, long nt, const double rho[], double dy[], double dz[], long ap[], long ad[],
                        double q[], double t[], double s[], long *na, long *bad)
{
    const long m = b->m, ld = b->ld;
    for (long k = 0; k < m; k++) b->pos[b->dof[k]] = k;
    int st = FFC_OK;
    /* support: dofs with a tangent entry or a shift */
    long a = 0;
    for (long k = 0; k < m; k++) ap[k] = -1;
    for (long e = 0; e < nt && !st; e++) {
        const long i = b->ti[e], j = b->tj[e];
        if (b->tv[e] == 0.0 || b->big[i] || b->big[j]) continue;
        if (!isfinite(b->tv[e])) { *bad = i; st = FFC_ERR_NONFINITE; break; }
        if (b->pos[i] < 0 || b->pos[j] < 0) { *bad = b->pos[i] < 0 ? i : j; st = FFC_ERR_INDEX; break; }
        const long pi = b->pos[i], pj = b->pos[j];
        if (ap[pi] < 0) { ap[pi] = a; ad[a++] = pi; }
        if (ap[pj] < 0) { ap[pj] = a; ad[a++] = pj; }
    }
    for (long k = 0; k < m && !st; k++)
        if (b->sh[b->dof[k]] != 0.0 && ap[k] < 0) { ap[k] = a; ad[a++] = k; }
    *na = a;
    const int one = 1, ai = (int)a;
    const double d1 = 1.0, d0 = 0.0;
    if (!st && a * a > b->wcap) { /* the dense work of the support, grown as needed */
        double *Mw = realloc(b->Mw, (size_t)(a * a) * sizeof(double));
        if (Mw) b->Mw = Mw;
        double *Gw = Mw ? realloc(b->Gw, (size_t)(a * a) * sizeof(double)) : NULL;
        if (Gw) { b->Gw = Gw; b->wcap = a * a; }
        else st = FFC_ERR_MEMORY;
    }
    double *M = b->Mw, *Gaa = b->Gw;
    st = ffc__bulk_agree(b, st);   /* (a rank's failure is every rank's before the shared product) */
    if (!st) st = ffc__bulk_gemv(b, m, m, 1.0, b->G, ld, rho, 0.0, q); /* q = G rho */
    if (!st && a > 0) {
        /* M = Kc' on the support (dense, a x a), G_aa */
        for (long k = 0; k < a * a; k++) M[k] = 0.0;
        for (long e = 0; e < nt; e++) {
            const long i = b->ti[e], j = b->tj[e];
            if (b->tv[e] == 0.0 || b->big[i] || b->big[j]) continue;
            M[ap[b->pos[i]] + ap[b->pos[j]] * a] += b->tv[e];
        }
        for (long k = 0; k < m; k++)
            if (b->sh[b->dof[k]] != 0.0) M[ap[k] + ap[k] * a] -= b->sh[b->dof[k]];
        for (long c = 0; c < a; c++) {
            const double *g = b->G + ad[c] * ld;
            for (long r = 0; r < a; r++) Gaa[r + c * a] = g[ad[r]];
        }
        for (long r = 0; r < a; r++) t[r] = -q[ad[r]];
        /* on the support of the kept LU: GMRES preconditioned by it (a few
         * a^2 products instead of an a^3 LU; the support stays the same
         * over most iterations of a step) */
        int reuse = b->ka == a;
        for (long r = 0; r < a && reuse; r++) reuse = b->kdof[r] == b->dof[ad[r]];
        const int git = reuse ? gmres_kept(b, a, M, Gaa, t) : -1;
        if (git > 10) b->ka = 0; /* (slow to converge: a fresh LU next time) */
        if (git >= 0) b->info.kept++;
        /* else A = I + G_aa M, column by column over M's nonzeros (a few
         * dozen per column: a^2 x that, against 2 a^3 for a dense product) */
        /* (several ranks and a large support: each rank builds the columns
         * it holds and the LU is shared, ffc__pdense) */
        const int dist = git < 0 && b->pd && a >= PDENSE_MIN;
        double *A = git < 0 && !dist ? ffc__bulk_dense_a(b) : b->A;
        if (git < 0 && !dist && !A) st = FFC_ERR_MEMORY;
        double *Al = dist ? ffc__pdense_reserve(b->pd, a) : NULL;
        if (dist && !Al) st = FFC_ERR_MEMORY;
        for (long j = 0; j < a && git < 0 && !st; j++) {
            long jl = 0;
            if (dist && (jl = ffc__pdense_local(b->pd, j)) < 0) continue;
            double *aj = dist ? Al + jl * a : A + j * a;
            for (long r = 0; r < a; r++) aj[r] = 0.0;
            aj[j] = 1.0;
            const double *mj = M + j * a;
            for (long i = 0; i < a; i++)
                if (mj[i] != 0.0) axpy(a, mj[i], Gaa + i * a, aj);
        }
        if (git < 0 && !st) {
            if (dist) {
                st = ffc__pdense_factor(b->pd, a);
                if (!st) st = ffc__pdense_solve(b->pd, a, t);
            } else
                st = ffc__lu_solve(a, A, b->piv, t);
            if (!st && a > b->kcap) { /* keep the LU */
                long *kd = realloc(b->kdof, (size_t)a * sizeof(long));
                if (kd) b->kdof = kd;
                int *kp = kd ? realloc(b->kpiv, (size_t)a * sizeof(int)) : NULL;
                if (kp) b->kpiv = kp;
                double *kl = kp ? realloc(b->klu, (size_t)(a * a) * sizeof(double)) : NULL;
                if (kl) { b->klu = kl; b->kcap = a; }
            }
            b->ka = 0;
            if (!st && a <= b->kcap) {
                if (!dist) {
                    memcpy(b->klu, A, (size_t)(a * a) * sizeof(double));
                    memcpy(b->kpiv, b->piv, (size_t)a * sizeof(int));
                }
                for (long r = 0; r < a; r++) b->kdof[r] = b->dof[ad[r]];
                b->ka = a;
                b->kdist = dist;
            }
        }
        if (!st) dgemv_("N", &ai, &ai, &d1, M, &ai, t, &one, &d0, s, &one); /* s = M t */
    }
    if (!st) {
        for (long k = 0; k < m; k++) dy[k] = -q[k];
        for (long r = 0; r < a; r++) {
            const double *g = b->G + ad[r] * ld; /* G symmetric: column ad[r] = row ad[r] */
            const double sr = s[r];
            for (long k = 0; k < m; k++) dy[k] -= g[k] * sr;
        }
        for (long k = 0; k < m; k++) dz[k] = -rho[k];
        if (a > 0) {
            for (long r = 0; r < a; r++) t[r] = dy[ad[r]];
            dgemv_("N", &ai, &ai, &d1, M, &ai, t, &one, &d0, s, &one);
            for (long r = 0; r < a; r++) dz[ad[r]] -= s[r];
        }
    }
    for (long k = 0; k < m; k++) b->pos[b->dof[k]] = -1;
    return st;
}

/* Formulation (the ranked direction).  With the tangent in ranked form
 * (FFC_TANGENT_RANKED) Kc' = U V^T - S_C: term k's columns U_k, V_k from
 * the triplets (b->ti = dof, b->tj = 2 k or 2 k + 1, b->tv)[nt] (Dirichlet
 * rows dropped), and a shifted dof d of C one more term (-s_d e_d, e_d).
 * The Newton equation (I + G Kc') dy = -q, q = G rho, is then (Woodbury)
 *     (I_p + V^T G U) w = -V^T q,   dy = -q - (G U) w,
 * a p x p system for p terms (an active slave node gives one term without
 * friction, four with) in place of the a x a one on the tangent's support
 * (three dofs of every slave and master node it couples); and
 * dz = -rho - Kc' dy = -rho - U (V^T dy).  Building G U takes m nnz(U),
 * V^T G U p nnz(V), the LU p^3 / 1.5.  *np the terms; ranked work grown
 * in b->rv, b->ri. */
/* sum over the entries e of list l of val[e] x[idx[e]] (the ranked lists:
 * start[l] .. start[l + 1]) */
static double list_dot(const long start[], const long idx[], const double val[], long l, const double x[])
{
    double v = 0.0;
    for (long e = start[l]; e < start[l + 1]; e++) v += val[e] * x[idx[e]];
    return v;
}

int ffc__bulk_direction_ranked(ffc__bulk *b, long nt, const double rho[], double dy[], double dz[], double q[],
                               double gdz[], long *np, long *bad)
{
    const long m = b->m, ld = b->ld;
    for (long k = 0; k < m; k++) b->pos[b->dof[k]] = k;
    int st = FFC_OK;
    long p = 0, ne = 0, nsh = 0;
    for (long e = 0; e < nt; e++) {
        const long i = b->ti[e];
        if (b->tv[e] == 0.0 || b->big[i]) continue;
        if (!isfinite(b->tv[e])) { *bad = i; st = FFC_ERR_NONFINITE; break; }
        if (b->pos[i] < 0 || b->tj[e] < 0) { *bad = i; st = FFC_ERR_INDEX; break; }
        if (b->tj[e] / 2 + 1 > p) p = b->tj[e] / 2 + 1;
        ne++;
    }
    for (long k = 0; k < m; k++) nsh += b->sh[b->dof[k]] != 0.0;
    const long pt = p + nsh, nl = 2 * pt;
    *np = pt;
    /* work: the lists' starts [nl + 1], fill [nl], entries [ne + 2 nsh], pivots [pt];
     * values [ne + 2 nsh], G U [m pt], the system [pt pt], w [pt] */
    const long needi = 2 * nl + 1 + ne + 2 * nsh + pt, needv = ne + 2 * nsh + m * pt + pt * pt + 2 * pt;
    if (!st && needi > b->ricap) {
        long *ri = realloc(b->ri, (size_t)needi * sizeof(long));
        if (ri) { b->ri = ri; b->ricap = needi; }
        else st = FFC_ERR_MEMORY;
    }
    if (!st && needv > b->rcap) {
        double *rv = realloc(b->rv, (size_t)needv * sizeof(double));
        if (rv) { b->rv = rv; b->rcap = needv; }
        else st = FFC_ERR_MEMORY;
    }
    st = ffc__bulk_agree(b, st);   /* (a rank's failure is every rank's before the shared products) */
    if (st) {
        for (long k = 0; k < m; k++) b->pos[b->dof[k]] = -1;
        return st;
    }
    long *start = b->ri, *fill = start + nl + 1, *idx = fill + nl, *piv = idx + ne + 2 * nsh;
    double *val = b->rv, *GU = val + ne + 2 * nsh, *S = GU + m * pt, *wv = S + pt * pt, *vd = wv + pt;
    for (long l = 0; l <= nl; l++) start[l] = 0;
    for (long e = 0; e < nt; e++)
        if (b->tv[e] != 0.0 && !b->big[b->ti[e]]) start[b->tj[e] + 1]++;
    for (long j = p; j < pt; j++) start[2 * j + 1] = start[2 * j + 2] = 1; /* a shift term: one entry each */
    for (long l = 0; l < nl; l++) { start[l + 1] += start[l]; fill[l] = start[l]; }
    for (long e = 0; e < nt; e++) {
        if (b->tv[e] == 0.0 || b->big[b->ti[e]]) continue;
        const long at = fill[b->tj[e]]++;
        idx[at] = b->pos[b->ti[e]];
        val[at] = b->tv[e];
    }
    for (long k = 0, j = p; k < m; k++) {
        const double sh = b->sh[b->dof[k]];
        if (sh == 0.0) continue;
        idx[fill[2 * j]] = k; val[fill[2 * j]++] = -sh;
        idx[fill[2 * j + 1]] = k; val[fill[2 * j + 1]++] = 1.0;
        j++;
    }
    for (long k = 0; k < m; k++) b->pos[b->dof[k]] = -1;
    st = ffc__bulk_gemv(b, m, m, 1.0, b->G, ld, rho, 0.0, q); /* q = G rho */
    if (st) return st;
    /* G U, column by column (G symmetric: its column c is row c); shared
     * out by columns on the ranks of a replicated bulk */
    const int split = b->rk.size > 1 && pt * m >= SHARE_MIN;
    long k0 = 0, k1 = pt;
    if (split) ffc__ranks_share(&b->rk, pt, m, &k0, &k1);
    for (long k = k0; k < k1; k++) {
        double *gu = GU + k * m;
        for (long r = 0; r < m; r++) gu[r] = 0.0;
        for (long e = start[2 * k]; e < start[2 * k + 1]; e++) axpy(m, val[e], b->G + idx[e] * ld, gu);
    }
    if (split && (st = ffc__mpi_allgather(b->rk.comm, GU, b->rk.count))) return st;
    /* S = I + V^T G U, wv = -V^T q; S column by column (one column of G U
     * read for all of V's columns) */
    for (long k = 0; k < pt; k++) wv[k] = -list_dot(start, idx, val, 2 * k + 1, q);
    for (long l = 0; l < pt; l++)
        for (long k = 0; k < pt; k++) S[k + l * pt] = (k == l) + list_dot(start, idx, val, 2 * k + 1, GU + l * m);
    st = ffc__lu_solve(pt, S, piv, wv);
    if (st) return st;
    /* dy = -q - G U w;  dz = -rho - U (V^T dy) */
    for (long k = 0; k < m; k++) dy[k] = -q[k];
    st = ffc__bulk_gemv(b, m, pt, -1.0, GU, m, wv, 1.0, dy);
    if (st) return st;
    for (long k = 0; k < m; k++) dz[k] = -rho[k];
    for (long k = 0; k < pt; k++) vd[k] = list_dot(start, idx, val, 2 * k + 1, dy);
    for (long k = 0; k < pt; k++)
        for (long e = start[2 * k]; e < start[2 * k + 1]; e++) dz[idx[e]] -= val[e] * vd[k];
    /* G dz = -q - (G U) (V^T dy), from the products at hand (G U is m x p,
     * G m x m) */
    for (long k = 0; k < m; k++) gdz[k] = -q[k];
    return ffc__bulk_gemv(b, m, pt, -1.0, GU, m, vd, 1.0, gdz);
}

